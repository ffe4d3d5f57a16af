"""Planes computed on the window the candidates read (config.crop_planes)."""

import cv2
import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.demo import make_demo_sequence
from smtmvt.features import tan_triggs
from smtmvt.features.tan_triggs import difference_of_gaussians, tan_triggs_scales
from smtmvt.geometry import box_to_affine
from smtmvt.motion import propagate
from smtmvt.preprocess import plane_window, prepare_crop, prepare_frame, to_unit_range
from smtmvt.warp import remap_patches, sampling_grid


@pytest.fixture(scope="module")
def frame():
    rng = np.random.default_rng(0)
    f = cv2.GaussianBlur(rng.integers(0, 256, (180, 240, 3)).astype(np.float32), (0, 0), 2.0)
    return np.clip(f, 0, 255).astype(np.uint8)


def _states(n=60, box=(100.0, 60.0, 40.0, 30.0), seed=1):
    start = np.repeat(box_to_affine(np.array(box))[None], n, axis=0)
    return propagate(start, [0.03, 0.01, 0.01, 0.03, 5.0, 5.0], np.random.default_rng(seed))


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16, np.float32])
def test_to_unit_range_of_a_crop_is_the_crop_of_the_whole(frame, dtype):
    f = frame.astype(dtype) * (257 if dtype == np.uint16 else 1)
    if dtype == np.float32:
        f = f / 255.0 * 0.8  # a float frame already in [0, 1]: scaled as a whole, not per crop
    whole = to_unit_range(f)
    np.testing.assert_array_equal(to_unit_range(f, crop=(30, 20, 90, 70)), whole[20:70, 30:90])
    with pytest.raises(ValueError, match="crop"):
        to_unit_range(f, crop=(30, 20, 300, 70))


def test_tan_triggs_statistics_over_a_region(frame):
    gray = cv2.cvtColor(frame, cv2.COLOR_RGB2GRAY)
    whole = (slice(0, gray.shape[0]), slice(0, gray.shape[1]))
    np.testing.assert_array_equal(tan_triggs(gray, region=whole), tan_triggs(gray))
    # a region brighter in contrast than the frame is scaled down relative to the whole frame's normalization
    g = gray.astype(np.float64)
    g[40:100, 60:160] = 128 + 2.0 * (g[40:100, 60:160] - 128)
    g = np.clip(g, 0, 255).astype(np.uint8)
    region = (slice(40, 100), slice(60, 160))
    inside = (slice(50, 90), slice(70, 150))
    ratio = np.abs(tan_triggs(g, region=region)[inside]).mean() / np.abs(tan_triggs(g)[inside]).mean()
    assert ratio < 0.9


def test_tan_triggs_divisors_are_the_robust_means_and_can_be_given(frame):
    gray = cv2.cvtColor(frame, cv2.COLOR_RGB2GRAY)
    out, (s1, s2) = tan_triggs_scales(gray)
    d = difference_of_gaussians((gray / 255.0) ** 0.2, 1.0, 2.0)
    assert s1 == pytest.approx(np.mean(np.abs(d) ** 0.1) ** 10, rel=1e-9)
    assert s2 == pytest.approx(np.mean(np.minimum(np.abs(d / s1), 10.0) ** 0.1) ** 10, rel=1e-9)
    np.testing.assert_array_equal(out, tan_triggs(gray))
    np.testing.assert_array_equal(tan_triggs(gray, scales=(s1, s2)), out)
    # given divisors replace the measured ones: twice the divisors, half the equalized values (before tanh)
    half = tan_triggs(gray, scales=(2 * s1, s2))
    np.testing.assert_allclose(np.arctanh(half / 10), np.arctanh(np.clip(out / 10, -0.999, 0.999)) / 2, atol=2e-3)


def test_a_crop_normalized_with_the_whole_frames_divisors_holds_the_whole_frames_plane(frame):
    states = _states()
    window = plane_window(
        (states[:, 4].min() - 30, states[:, 5].min() - 30, states[:, 4].max() + 30, states[:, 5].max() + 30),
        frame.shape[:2],
        3,
    )
    whole = prepare_frame(frame, "f", 3)
    assert min(whole.contrast) > 0
    crop = prepare_crop(frame, "f", 3, window, (1.0, 1.0), frame.shape[:2], contrast=whole.contrast)
    assert crop.contrast == whole.contrast
    x0, y0, x1, y1 = window
    ox, oy = (int(v) for v in crop.origin)
    local = (slice(y0 - oy, y1 - oy), slice(x0 - ox, x1 - ox))
    np.testing.assert_allclose(crop.normalized[local], whole.normalized[y0:y1, x0:x1], atol=2e-5)
    # the crop alone normalizes differently (its own window's statistics)
    own = prepare_crop(frame, "f", 3, window, (1.0, 1.0), frame.shape[:2])
    assert np.abs(own.normalized[local] - whole.normalized[y0:y1, x0:x1]).max() > 1e-2


@pytest.mark.parametrize("stats", [None, (20, 10, 200, 150)])
def test_crop_at_scale_one_holds_the_whole_planes_inside_the_window(frame, stats):
    states = _states()
    window = plane_window(
        (states[:, 4].min() - 30, states[:, 5].min() - 30, states[:, 4].max() + 30, states[:, 5].max() + 30),
        frame.shape[:2],
        3,
    )
    crop = prepare_crop(frame, "f", 3, window, (1.0, 1.0), frame.shape[:2], stats)
    whole = prepare_frame(frame, "f", 3)
    x0, y0, x1, y1 = window
    ox, oy = crop.origin
    assert float(ox).is_integer() and float(oy).is_integer() and crop.plane_shape == frame.shape[:2]
    local = (slice(y0 - int(oy), y1 - int(oy)), slice(x0 - int(ox), x1 - int(ox)))
    np.testing.assert_array_equal(crop.gray[local], whole.gray[y0:y1, x0:x1])
    np.testing.assert_array_equal(crop.color[local], whole.color[y0:y1, x0:x1])
    # Tan-Triggs: the frame's band-pass there, normalized by the statistics of the window
    # (or of the region given), which the crop then also holds
    sx0, sy0, sx1, sy1 = window if stats is None else stats
    assert ox <= sx0 and oy <= sy0 and sx1 <= ox + crop.shape[1] and sy1 <= oy + crop.shape[0]
    expected = tan_triggs(whole.gray, region=(slice(sy0, sy1), slice(sx0, sx1)))[y0:y1, x0:x1]
    np.testing.assert_allclose(crop.normalized[local], expected, atol=2e-5)


@pytest.mark.parametrize("scale", [1.6, 0.55])
def test_crop_of_a_resized_plane_samples_like_the_whole_resized_plane(frame, scale):
    """At plane scale s the crop is resized by exactly s: sampled at the same plane points
    (shifted by its origin) it gives the whole resized plane's values, up to resampling
    on grids offset by the origin's fraction (measured on this blurred noise, color in
    [0, 1] varying by 0.03 on average: at 1.6 mean 0.0002 / max 0.002, at 0.55 area
    averaging 0.002 / 0.012)."""
    states = _states()
    shape = (int(round(frame.shape[0] * scale)), int(round(frame.shape[1] * scale)))
    X, Y = sampling_grid(states, (16, 16), scale)
    window = plane_window((X.min(), Y.min(), X.max(), Y.max()), shape, 2)
    crop = prepare_crop(frame, "f", 3, window, (scale, scale), shape)
    interp = cv2.INTER_LINEAR if scale > 1 else cv2.INTER_AREA
    whole = cv2.resize(to_unit_range(frame), None, fx=scale, fy=scale, interpolation=interp)
    ours = remap_patches(crop.color, *sampling_grid(states, (16, 16), scale, crop.origin))
    theirs = remap_patches(whole, X, Y)
    tol = 0.01 if scale > 1 else 0.05
    assert np.abs(ours - theirs).max() < tol
    assert np.abs(ours - theirs).mean() < tol / 10


@pytest.mark.parametrize("crop", [False, True])
@pytest.mark.parametrize(
    "bad,match",
    [
        (np.full((120, 160, 3), np.nan, np.float32), "NaN"),
        (np.zeros(50, np.uint8), "shape"),
        (np.zeros((60, 80), np.int32), "dtype"),
    ],
)
def test_a_frame_that_cannot_be_read_leaves_the_tracker_unchanged(crop, bad, match):
    demo = make_demo_sequence(n_frames=8)
    config = TrackerConfig(n_particles=60, seed=2, crop_planes=crop)
    a, b = Tracker(config), Tracker(config)
    for t in (a, b):
        t.init(demo.frames[0], demo.groundtruth[0])
        t.update(demo.frames[1])
    with pytest.raises(ValueError, match=match):
        a.update(bad)
    ra, rb = a.update(demo.frames[2]), b.update(demo.frames[2])
    assert ra == rb


def test_cropped_planes_give_the_whole_frames_views():
    """The tracker's views of one frame's candidates from the cropped planes: the
    views of the gray and color planes (color, HOG, LBP) are the whole frame's;
    the intensity view differs by Tan-Triggs' statistics only (measured cosines
    0.989-0.996 to the whole frame's views)."""
    demo = make_demo_sequence(n_frames=3)
    t = Tracker(TrackerConfig(n_particles=50, seed=4, crop_planes=True, crop_refresh=0))
    t.init(demo.frames[0], demo.groundtruth[0])
    states = propagate(np.repeat(t._state[None], 50, axis=0), t.config.affine_std, np.random.default_rng(0))
    views = [
        t._sampler.views(t._prepare(demo.frames[1], "f", t._channels, 1.0, s), states, 1.0, t._work_box)
        for s in (None, states)
    ]
    for name, whole, crop in zip(t.config.views, *views):
        if name == "intensity":
            cos = np.sum(whole * crop, axis=0) / np.linalg.norm(whole, axis=0) / np.linalg.norm(crop, axis=0)
            assert cos.min() > 0.98 and not np.array_equal(whole, crop)
        else:
            np.testing.assert_array_equal(whole, crop, err_msg=name)


def test_crop_refresh_computes_the_whole_plane_every_kth_frame(monkeypatch):
    """``crop_refresh`` k: frames 0, k, 2k, ... are prepared whole, the others
    cropped with the last whole plane's Tan-Triggs divisors; k = 1 is the
    whole-plane tracker, box for box."""
    import smtmvt.sampling as sampling_module

    demo = make_demo_sequence(n_frames=10)
    cropped, given = [], []
    real = sampling_module.prepare_crop

    def spy(*args, **kwargs):
        given.append(kwargs.get("contrast"))
        return real(*args, **kwargs)

    monkeypatch.setattr(sampling_module, "prepare_crop", spy)
    t = Tracker(TrackerConfig(n_particles=60, seed=3, crop_planes=True, crop_refresh=4))
    t.init(demo.frames[0], demo.groundtruth[0])
    divisors = [t._sampler.tt_divisors]
    for f in demo.frames[1:]:
        n = len(given)
        t.update(f)
        cropped.append(len(given) > n)
        divisors.append(t._sampler.tt_divisors)
    assert cropped == [i % 4 != 0 for i in range(1, 10)]
    assert all(g == divisors[(i // 4) * 4] for i, g in zip([i for i in range(1, 10) if i % 4], given))
    assert divisors[4] != divisors[0] and divisors[3] == divisors[0]
    monkeypatch.setattr(sampling_module, "prepare_crop", real)
    boxes = []
    for cfg in (
        TrackerConfig(n_particles=60, seed=3, crop_planes=False),
        TrackerConfig(n_particles=60, seed=3, crop_planes=True, crop_refresh=1),
    ):
        t = Tracker(cfg)
        t.init(demo.frames[0], demo.groundtruth[0])
        boxes.append([t.update(f).box for f in demo.frames[1:]])
    assert boxes[0] == boxes[1]


def test_crop_refreshed_planes_give_the_whole_frames_views():
    """Between refreshes the crop of a frame, normalized with that frame's own
    divisors, gives every view of the whole frame (intensity up to the DoG's rounding)."""
    demo = make_demo_sequence(n_frames=3)
    t = Tracker(TrackerConfig(n_particles=50, seed=4, crop_planes=True, crop_refresh=5))
    t.init(demo.frames[0], demo.groundtruth[0])
    states = propagate(np.repeat(t._state[None], 50, axis=0), t.config.affine_std, np.random.default_rng(0))
    whole = t._sampler.views(t._prepare(demo.frames[0], "f", t._channels, 1.0, None), states, 1.0, t._work_box)
    t._frame_index = 1  # not a refresh frame: cropped, with frame 0's divisors
    prepared = t._prepare(demo.frames[0], "f", t._channels, 1.0, states)
    assert prepared.full_shape is not None
    for name, a, b in zip(t.config.views, whole, t._sampler.views(prepared, states, 1.0, t._work_box)):
        np.testing.assert_allclose(a, b, atol=1e-4, err_msg=name)


def test_crop_context_below_one_is_rejected():
    with pytest.raises(ValueError, match="crop_context"):
        TrackerConfig(crop_planes=True, crop_context=0.5)
    with pytest.raises(ValueError, match="crop_refresh"):
        TrackerConfig(crop_planes=True, crop_refresh=-1)


@pytest.mark.parametrize(
    "bad,match",
    [
        (np.full((12, 16, 3), np.nan, np.float32), "NaN"),
        (np.full((12, 16), 1e300), "infinite"),
        (np.zeros(50, np.uint8), "shape"),
        (np.zeros((60, 80), np.int32), "dtype"),
    ],
)
def test_check_frame_refuses_what_to_unit_range_refuses_without_converting(bad, match):
    from smtmvt.preprocess import check_frame, to_unit_range

    for check in (check_frame, to_unit_range):
        with pytest.raises(ValueError, match=rf"frame 7: .*{match}"):
            check(bad, "frame 7")
    good = np.arange(48, dtype=np.uint16).reshape(4, 4, 3)
    assert np.shares_memory(check_frame(good, "frame 7"), good)  # not converted
    alpha = np.zeros((4, 5, 4), np.float32)
    assert check_frame(alpha, "frame 7").shape == (4, 5, 3)
