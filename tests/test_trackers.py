"""Tracker registry and the OpenCV peers' adapters (colour order, box type, lost handling).

Thresholds were set from measurements (see each test), a margin below what was measured,
so that a driving bug (BGR/RGB swapped, 0-based/1-based, lost boxes used as (0,0,0,0))
fails them.
"""

from __future__ import annotations

import math

import cv2
import numpy as np
import pytest

from smtmvt.evaluation.trackers import (
    EvalTracker,
    UnknownTrackerError,
    available_trackers,
    covering_rect,
    make_tracker,
    register_tracker,
    to_bgr8,
    unregister_tracker,
)

OPENCV_PEERS = [
    "opencv-boosting",
    "opencv-csrt",
    "opencv-kcf",
    "opencv-medianflow",
    "opencv-mil",
    "opencv-mosse",
    "opencv-tld",
]


def mean_iou(a, b) -> float:
    """Mean IoU of two (n, 4) x,y,w,h box arrays (continuous extents)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    iw = np.clip(np.minimum(a[:, 0] + a[:, 2], b[:, 0] + b[:, 2]) - np.maximum(a[:, 0], b[:, 0]), 0, None)
    ih = np.clip(np.minimum(a[:, 1] + a[:, 3], b[:, 1] + b[:, 3]) - np.maximum(a[:, 1], b[:, 1]), 0, None)
    inter = iw * ih
    return float(np.mean(inter / (a[:, 2] * a[:, 3] + b[:, 2] * b[:, 3] - inter)))


def moving_square(n=25, size=(120, 160), start=(30, 40), step=(2.0, 1.0), side=(28, 24), seed=0):
    """RGB frames of a textured reddish square moving over a blurred-noise background,
    and its 0-based boxes."""
    rng = np.random.default_rng(seed)
    h, w = size
    bg = cv2.GaussianBlur(rng.integers(0, 256, (h, w, 3)).astype(np.uint8), (0, 0), 3)
    bg = cv2.normalize(bg, None, 40, 160, cv2.NORM_MINMAX)
    tw, th = side
    tex = rng.integers(0, 256, (th // 4 + 1, tw // 4 + 1, 3)).astype(np.uint8)
    tex = cv2.resize(tex, (tw, th), interpolation=cv2.INTER_NEAREST)
    tex[..., 0] = np.maximum(tex[..., 0], 150)
    frames, boxes = [], []
    for i in range(n):
        x, y = int(round(start[0] + step[0] * i)), int(round(start[1] + step[1] * i))
        f = bg.copy()
        f[y : y + th, x : x + tw] = tex
        frames.append(f)
        boxes.append((x, y, tw, th))
    return frames, np.array(boxes, float)


def track(tracker, frames, first_box):
    tracker.init(frames[0], tuple(first_box))
    out = [tuple(first_box)]
    for f in frames[1:]:
        out.append(tracker.update(f))
    return out


# ----------------------------------------------------------------------------- registry


def test_builtin_names_registered():
    names = available_trackers()
    assert "smtmvt" in names
    for peer in OPENCV_PEERS:
        assert peer in names


def test_unknown_name_lists_available():
    with pytest.raises(UnknownTrackerError) as info:
        make_tracker("opencv-nope")
    msg = str(info.value)
    assert "opencv-nope" in msg
    for name in ["smtmvt", "opencv-csrt", "opencv-kcf", "opencv-mil"]:
        assert name in msg
    assert isinstance(info.value, ValueError)  # the CLI reports ValueErrors as one line


def test_register_make_unregister():
    class Fixed:
        def __init__(self, offset=0.0):
            self.offset = offset

        def init(self, frame, box):
            self.box = tuple(box)

        def update(self, frame):
            return tuple(v + self.offset for v in self.box)

    register_tracker("test-fixed", Fixed)
    try:
        with pytest.raises(ValueError, match="already registered"):
            register_tracker("test-fixed", Fixed)
        t = make_tracker("test-fixed", offset=1.0, seed=5)  # seed dropped: Fixed takes none
        assert isinstance(t, EvalTracker)
        t.init(np.zeros((4, 4), np.uint8), (1, 2, 3, 4))
        assert t.update(None) == (2.0, 3.0, 4.0, 5.0)
        assert "test-fixed" in available_trackers()
    finally:
        unregister_tracker("test-fixed")
    assert "test-fixed" not in available_trackers()


@pytest.mark.parametrize("bad", ["", "a/b", "../x", "with space", ".hidden"])
def test_register_rejects_names_unusable_as_folders(bad):
    with pytest.raises(ValueError, match="invalid tracker name"):
        register_tracker(bad, lambda: None)


def test_opencv_options_checked():
    t = make_tracker("opencv-kcf", detect_thresh=0.2)
    assert math.isclose(t._params.detect_thresh, 0.2, rel_tol=1e-6)
    with pytest.raises(ValueError, match="unknown option 'nope'"):
        make_tracker("opencv-kcf", nope=1)
    with pytest.raises(ValueError, match="takes no options"):
        make_tracker("opencv-mosse", psr=3)


# ----------------------------------------------------------------------------- frames and boxes


def test_to_bgr8_color_order_gray_and_uint16():
    rgb = np.zeros((2, 3, 3), np.uint8)
    rgb[..., 0], rgb[..., 1], rgb[..., 2] = 10, 20, 30
    bgr = to_bgr8(rgb)
    assert bgr.dtype == np.uint8 and bgr.flags.c_contiguous
    assert bgr[0, 0].tolist() == [30, 20, 10]

    gray = np.arange(6, dtype=np.uint8).reshape(2, 3)
    g3 = to_bgr8(gray)
    assert g3.shape == (2, 3, 3) and (g3 == gray[..., None]).all()

    g16 = np.array([[0, 257, 65535]], np.uint16)
    assert to_bgr8(g16)[0, :, 0].tolist() == [0, 1, 255]
    with pytest.raises(TypeError):
        to_bgr8(np.zeros((2, 2), np.float32))


def test_covering_rect_covers_the_box():
    assert covering_rect((10, 20, 30, 40)) == (10, 20, 30, 40)  # integers unchanged
    assert covering_rect((10.5, 20.2, 30.0, 39.9)) == (10, 20, 31, 41)
    assert covering_rect((-0.0000001, 0, 5, 5)) == (0, 0, 5, 5)  # float noise is not a pixel


class SpyCV:
    """Stands in for a cv2 tracker: records what it is given, returns scripted updates."""

    def __init__(self, updates):
        self.updates = list(updates)
        self.init_args = None
        self.update_images = []

    def init(self, image, box):
        self.init_args = (image.copy(), box)

    def update(self, image):
        self.update_images.append(image.copy())
        return self.updates.pop(0)


def _spy_frames():
    f = np.zeros((40, 50, 3), np.uint8)
    f[..., 0], f[..., 1], f[..., 2] = 200, 100, 7  # R, G, B all different
    return f


def test_current_api_gets_bgr_and_integer_rect(monkeypatch):
    spy = SpyCV([(True, (11, 12, 8, 9)), (False, (0, 0, 0, 0)), (True, (13, 12, 8, 9))])
    monkeypatch.setattr(cv2, "TrackerKCF_create", lambda *a: spy)
    t = make_tracker("opencv-kcf")
    frame = _spy_frames()
    t.init(frame, (10.4, 11.6, 7.2, 8.1))
    image, rect = spy.init_args
    assert image[0, 0].tolist() == [7, 100, 200]  # BGR
    assert rect == (10, 11, 8, 9) and all(type(v) is int for v in rect)
    assert t.update(frame) == (11.0, 12.0, 8.0, 9.0)
    assert spy.update_images[0][0, 0].tolist() == [7, 100, 200]
    # lost: OpenCV's (0, 0, 0, 0) must not be reported; the previous box is kept
    assert t.update(frame) == (11.0, 12.0, 8.0, 9.0)
    assert t.lost and t.lost_frames == 1
    assert t.update(frame) == (13.0, 12.0, 8.0, 9.0)
    assert not t.lost


def test_legacy_api_gets_bgr_and_float_rect(monkeypatch):
    spy = SpyCV([(True, (10.5, 11.25, 7.0, 8.0)), (True, (float("nan"), 0.0, 7.0, 8.0))])
    monkeypatch.setattr(cv2.legacy, "TrackerMOSSE_create", lambda *a: spy)
    t = make_tracker("opencv-mosse")
    gray = np.full((40, 50), 77, np.uint8)
    t.init(gray, (10.4, 11.6, 7.2, 8.1))
    image, rect = spy.init_args
    assert image.shape == (40, 50, 3) and (image == 77).all()  # gray -> 3-channel BGR
    assert rect == pytest.approx((10.4, 11.6, 7.2, 8.1)) and all(type(v) is float for v in rect)
    assert t.update(gray) == (10.5, 11.25, 7.0, 8.0)
    assert t.update(gray) == (10.5, 11.25, 7.0, 8.0)  # a NaN box counts as lost
    assert t.lost_frames == 1


def test_initial_box_clipped_to_image(monkeypatch):
    spy = SpyCV([])
    monkeypatch.setattr(cv2, "TrackerCSRT_create", lambda *a: spy)
    t = make_tracker("opencv-csrt")
    t.init(_spy_frames(), (-3.0, 30.0, 10.0, 20.0))  # leaves the 50x40 image left and bottom
    assert spy.init_args[1] == (0, 30, 7, 10)


def test_tld_small_target_is_upscaled(monkeypatch):
    spy = SpyCV([(True, (40.0, 40.0, 20.02, 40.04))])
    monkeypatch.setattr(cv2.legacy, "TrackerTLD_create", lambda *a: spy)
    t = make_tracker("opencv-tld")
    t.init(_spy_frames(), (10.0, 10.0, 10.0, 20.0))  # smaller side 10 < 20: factor ~2
    image, rect = spy.init_args
    s = 20.0 / 10.0 * 1.001
    assert image.shape[:2] == (round(40 * s), round(50 * s))
    assert min(rect[2], rect[3]) >= 20.0
    assert t.update(_spy_frames()) == pytest.approx((40 / s, 40 / s, 20.02 / s, 40.04 / s))


# ----------------------------------------------------------------------------- real peers, synthetic


# Mean IoU measured on the default 25-frame sequence (28x24 square, texture seed 0):
# CSRT 0.93, KCF 0.81, MedianFlow 0.995, Boosting 1.0, TLD 0.63-0.99 (random, 12 runs).
# MIL (random): 0.40-0.69 there, 0.62-0.90 over 12 runs on a 40x36 square (seed 3), used here.
# MOSSE loses the 28x24 square (0.19: OpenCV's MOSSE has no context padding and its
# peak-to-sidelobe test over the target-sized window fails); 1.0 on a 32x32 one (seed 2).
SYNTH_CASES = {
    "opencv-csrt": (0.85, {}),
    "opencv-kcf": (0.7, {}),
    "opencv-medianflow": (0.9, {}),
    "opencv-boosting": (0.9, {}),
    "opencv-tld": (0.5, {}),
    "opencv-mil": (0.45, {"side": (40, 36), "seed": 3}),
    "opencv-mosse": (0.8, {"side": (32, 32), "seed": 2}),
}


@pytest.mark.parametrize("name", sorted(SYNTH_CASES))
def test_peer_tracks_moving_square(name):
    threshold, kwargs = SYNTH_CASES[name]
    frames, gt = moving_square(**kwargs)
    out = track(make_tracker(name, seed=1), frames, gt[0])
    assert all(len(b) == 4 and all(isinstance(v, float) and math.isfinite(v) for v in b) for b in out)
    assert mean_iou(out, gt) > threshold


def test_deterministic_peers_repeat_exactly():
    frames, gt = moving_square(n=12)
    for name in ["opencv-csrt", "opencv-kcf", "opencv-medianflow", "opencv-boosting"]:
        a = track(make_tracker(name, seed=3), frames, gt[0])
        b = track(make_tracker(name, seed=3), frames, gt[0])
        assert a == b, name


def test_smtmvt_adapter_tracks_and_repeats_with_a_seed():
    frames, gt = moving_square(n=6)
    runs = [track(make_tracker("smtmvt", seed=11, n_particles=40), frames, gt[0]) for _ in range(2)]
    assert runs[0] == runs[1]
    assert all(len(b) == 4 and all(isinstance(v, float) and math.isfinite(v) for v in b) for b in runs[0])
    assert mean_iou(runs[0], gt) > 0.8  # measured 0.93 (40 particles, 6 frames)


# ----------------------------------------------------------------------------- real data


def _real(otb_dir, name, n):
    from smtmvt.data import open_otb_sequence

    seq = open_otb_sequence(otb_dir / name)
    return [seq[i] for i in range(n)], np.asarray(seq.groundtruth[:n])


# Measured on CarDark frames 1-100 (mean IoU, continuous extents): KCF 0.912, CSRT 0.893,
# MIL 0.64-0.83 (random), MOSSE 0.897, Boosting 0.871, MedianFlow 0.758.
REAL_THRESHOLDS = {
    "opencv-kcf": 0.8,
    "opencv-csrt": 0.8,
    "opencv-mil": 0.5,
    "opencv-mosse": 0.8,
    "opencv-boosting": 0.75,
    "opencv-medianflow": 0.65,
}


@pytest.fixture(scope="module")
def cardark(otb_dir):
    return _real(otb_dir, "CarDark", 100)


@pytest.mark.slow
@pytest.mark.parametrize("name", list(REAL_THRESHOLDS))
def test_peer_on_cardark(name, cardark):
    frames, gt = cardark
    out = track(make_tracker(name, seed=0), frames, gt[0])
    assert mean_iou(out, gt) > REAL_THRESHOLDS[name]


_TLD_ON_CROSSING = """
import sys
from pathlib import Path
import numpy as np
from smtmvt.data import open_otb_sequence
from smtmvt.evaluation.trackers import make_tracker
seq = open_otb_sequence(Path(sys.argv[1]) / "Crossing")
frames, gt = [seq[i] for i in range(60)], np.asarray(seq.groundtruth[:60])
tracker = make_tracker("opencv-tld", seed=0)
tracker.init(frames[0], tuple(gt[0]))
boxes = [gt[0]] + [tracker.update(f) for f in frames[1:]]
print(repr([[float(v) for v in box] for box in boxes]))
"""


@pytest.mark.slow
def test_tld_small_target_fix_on_crossing(otb_dir):
    """Crossing's pedestrian is 17 px wide: OpenCV's TLD alone scores 0.03 (boxes drift by its
    internal 20/17 factor); with the adapter's upscaling 0.39-0.43 was measured. Run in a fresh
    process, as the runner runs TLD: its random state, which the seed does not reach, depends on
    what ran before it in a process (0.23 after other tests in one pytest worker)."""
    import ast
    import subprocess
    import sys

    done = subprocess.run(
        [sys.executable, "-c", _TLD_ON_CROSSING, str(otb_dir)], capture_output=True, text=True, check=True
    )
    out = ast.literal_eval(done.stdout.strip().splitlines()[-1])
    _, gt = _real(otb_dir, "Crossing", 60)
    assert mean_iou(out, gt) > 0.25


# ----------------------------------------------------------------------------- registry metadata (issues 6 and 8)


def test_smtmvt_paper_is_the_paper_configuration():
    from smtmvt import TrackerConfig

    assert {"smtmvt", "smtmvt-paper"} <= set(available_trackers())
    paper = make_tracker("smtmvt-paper", seed=3)
    assert paper.config == TrackerConfig.paper(seed=3)
    assert make_tracker("smtmvt-paper", seed=3, n_particles=50).config == TrackerConfig.paper(seed=3, n_particles=50)
    assert make_tracker("smtmvt", seed=3).config == TrackerConfig(seed=3)


def test_determinism_and_fresh_process_are_declared():
    from smtmvt.evaluation.trackers import tracker_spec

    for name in ("opencv-csrt", "opencv-kcf", "opencv-mosse", "opencv-medianflow", "opencv-boosting"):
        assert tracker_spec(name).deterministic and not tracker_spec(name).fresh_process, name
    assert tracker_spec("opencv-mil").fresh_process and not tracker_spec("opencv-mil").deterministic
    assert tracker_spec("opencv-tld").fresh_process and tracker_spec("opencv-tld").deterministic
    for name in ("smtmvt", "smtmvt-paper", "smtmvt-l1t"):
        assert not tracker_spec(name).deterministic, name

    class Declared:
        deterministic = True

        def init(self, frame, box): ...

        def update(self, frame): ...

    register_tracker("test-declared", Declared)
    try:
        assert tracker_spec("test-declared").deterministic  # the factory's own attribute
    finally:
        unregister_tracker("test-declared")


def test_comparison_models_are_registered_in_the_papers_setting():
    from smtmvt import TrackerConfig

    lad = make_tracker("smtmvt-mtmvt-lad", seed=2)
    assert lad.config == TrackerConfig.paper(seed=2, model="mtmvt-lad")
    assert make_tracker("smtmvt-mtmvt-ls", seed=2).config.model == "mtmvt-ls"
    ivt = make_tracker("smtmvt-ivt", seed=4, forgetting=0.95)
    assert ivt.config.seed == 4 and ivt.config.forgetting == 0.95 and ivt.config.n_particles == 600
    assert ivt.config.affine_std == (4.0, 4.0, 0.01, 0.0, 0.005, 0.0)
