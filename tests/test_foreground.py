"""The foreground term: the first frame's color model and the boxes' contrast."""

import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.demo import make_demo_sequence
from smtmvt.evaluation.metrics import overlap_ratio
from smtmvt.foreground import (
    BINS,
    RING,
    SURROUND,
    box_contrast,
    color_bins,
    foreground_map,
    foreground_model,
    ring_window,
)


def _scene(h=120, w=160, box=(60, 40, 30, 20)):
    """A blue frame with a red box and, elsewhere, a green patch."""
    img = np.zeros((h, w, 3), np.float32)
    img[:, :, 2] = 0.9
    x, y, bw, bh = box
    img[y : y + bh, x : x + bw] = (0.9, 0.1, 0.1)
    img[5:15, 5:25] = (0.1, 0.9, 0.1)
    return img


def test_color_bins_are_the_joint_quantized_channels():
    c = np.array([[[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [0.5, 0.25, 0.999]]], np.float32)
    assert color_bins(c).tolist() == [[0, BINS**3 - 1, ((BINS // 2) * BINS + BINS // 4) * BINS + BINS - 1]]
    gray = np.array([[[0.0], [0.5], [1.0]]], np.float32)
    assert color_bins(gray).tolist() == [[0, BINS * BINS // 2, BINS * BINS - 1]]
    with pytest.raises(ValueError, match="color plane"):
        color_bins(np.zeros((4, 4, 2)))


def test_model_tells_the_box_colors_from_the_surroundings():
    img, box = _scene(), (60, 40, 30, 20)
    model = foreground_model(img, box)
    red, blue, green = (color_bins(img[y : y + 1, x : x + 1])[0, 0] for x, y in ((70, 45), (0, 0), (10, 10)))
    assert model[red] == 1.0  # only inside the box
    assert model[blue] == 0.0  # only around it
    # the green patch (rows 5-15) lies outside the surroundings (the box grown SURROUND = 3 times: rows 20-80)
    assert SURROUND == 3.0 and model[green] == 0.5  # never seen
    pmap = foreground_map(img, model)
    assert pmap.dtype == np.float32 and pmap[45, 70] == 1.0 and pmap[0, 0] == 0.0


def _mask(shape, box, grow):
    """Pixels of a box grown about its centre, edges rounded and clipped: brute force."""
    x, y, w, h = box
    cx, cy = x + w / 2, y + h / 2
    x0, x1 = (int(np.clip(np.rint(v), 0, shape[1])) for v in (cx - w * grow / 2, cx + w * grow / 2))
    y0, y1 = (int(np.clip(np.rint(v), 0, shape[0])) for v in (cy - h * grow / 2, cy + h * grow / 2))
    m = np.zeros(shape, bool)
    m[y0:y1, x0:x1] = True
    return m


def test_box_contrast_is_the_inside_mean_less_the_ring_mean():
    rng = np.random.default_rng(0)
    pmap = rng.random((50, 70)).astype(np.float32)
    p64 = pmap.astype(np.float64)
    boxes = np.column_stack(
        [rng.uniform(-10, 60, 40), rng.uniform(-10, 40, 40), rng.uniform(2, 30, 40), rng.uniform(2, 30, 40)]
    )
    for box, got in zip(boxes, box_contrast(pmap, boxes)):
        inner = _mask(pmap.shape, box, 1.0)
        ring = _mask(pmap.shape, box, RING) & ~inner
        ref = (p64[inner].mean() if inner.any() else 0.0) - (p64[ring].mean() if ring.any() else 0.0)
        assert got == pytest.approx(ref, abs=1e-9)


def test_the_true_box_has_the_highest_contrast():
    img, box = _scene(), (60, 40, 30, 20)
    pmap = foreground_map(img, foreground_model(img, box))
    x, y, w, h = box
    others = [(x + 8, y, w, h), (x, y - 6, w, h), (x + 5, y + 4, w - 10, h - 8), (x - 6, y - 4, w + 12, h + 8)]
    c = box_contrast(pmap, [box] + others)
    assert c[0] == pytest.approx(1.0) and np.all(c[1:] < c[0] - 0.1)


def test_foreground_term_moves_the_boxes_only_when_on():
    demo = make_demo_sequence(n_frames=30)
    # seed 1: with seed 0 the demo's first 30 frames choose the same particles with
    # the term or without (its contrast there spans only -0.12 to 0.03)
    cfg = TrackerConfig(n_particles=100, seed=1)

    def track(c):
        t = Tracker(c)
        t.init(demo.frames[0], demo.groundtruth[0])
        return np.array([demo.groundtruth[0]] + [t.update(f).box for f in demo.frames[1:]])

    assert cfg.foreground_weight == 1.0  # the default
    assert TrackerConfig.paper().foreground_weight == 0.0
    plain, with_term = track(cfg.replace(foreground_weight=0.0)), track(cfg)
    np.testing.assert_array_equal(with_term, track(cfg))
    assert not np.array_equal(plain, with_term)
    assert overlap_ratio(with_term, demo.groundtruth).mean() > 0.6
    with pytest.raises(ValueError, match="foreground_weight"):
        TrackerConfig(foreground_weight=-1.0)


def test_the_map_on_the_rings_window_gives_the_same_contrasts():
    rng = np.random.default_rng(1)
    img = rng.random((60, 80, 3)).astype(np.float32)
    model = foreground_model(img, (30, 20, 12, 10))
    boxes = np.column_stack(
        [rng.uniform(-5, 70, 30), rng.uniform(-5, 50, 30), rng.uniform(3, 15, 30), rng.uniform(3, 15, 30)]
    )
    for some in (boxes, boxes[:3], boxes[10:11]):
        window = ring_window(some, img.shape)
        part = foreground_map(img, model, window)
        np.testing.assert_array_equal(box_contrast(part, some), box_contrast(foreground_map(img, model), some))
    x0, y0, x1, y1 = ring_window(boxes[10:11], img.shape)
    assert not part[:y0].any() and not part[y1:].any() and not part[:, :x0].any() and not part[:, x1:].any()


def test_contrast_on_cropped_planes_equals_the_whole_frames():
    """With ``crop_planes`` the planes cover the candidates' rings too (a large
    target: its rings reach farther than the filters do)."""
    rng = np.random.default_rng(0)
    frames = [(rng.random((480, 480, 3)) * 255).astype(np.uint8) for _ in range(2)]
    box = (180.0, 190.0, 120.0, 100.0)
    cfg = TrackerConfig(n_particles=40, seed=0, foreground_weight=1.0, crop_planes=False)
    whole, crop = Tracker(cfg), Tracker(cfg.replace(crop_planes=True))
    for t in (whole, crop):
        t.init(frames[0], box)
    fg_whole, fg_crop = (next(c for c in t.cues if c.name == "foreground") for t in (whole, crop))
    np.testing.assert_array_equal(fg_whole.model, fg_crop.model)  # both from the whole first frame
    states = whole._motion.particles + rng.normal(0, 1, (40, 6)) * [0.02, 0, 0, 0.02, 10, 10]
    a = fg_whole.contrast(whole._prepare(frames[1], "f", whole._channels), states, 1.0)
    crop._frame_index = 1  # not a frame of config.crop_refresh's whole planes
    cropped = crop._prepare(frames[1], "f", crop._channels, 1.0, states)
    assert cropped.shape[0] < 480 and cropped.shape[1] < 480  # a crop
    np.testing.assert_allclose(fg_crop.contrast(cropped, states, 1.0), a, atol=1e-6)
