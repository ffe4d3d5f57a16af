"""``correlation_scales``: the correlation cue read at each candidate's size (SAMF's scales, per candidate)."""

import cv2
import numpy as np
import pytest
from scipy import ndimage

from smtmvt import Tracker, TrackerConfig
from smtmvt.correlation import CorrelationFilter, correlation_cost, peak_level, scaled_correlation_cost
from smtmvt.cues.correlation import CorrelationCue
from smtmvt.demo import make_demo_sequence
from smtmvt.geometry import box_to_affine


def _texture(h=240, w=320, seed=0):
    rng = np.random.default_rng(seed)
    img = cv2.GaussianBlur(rng.random((h, w)).astype(np.float32), (0, 0), 2.0)
    return (img - img.min()) / (img.max() - img.min())


def _zoomed(img, factor, centre):
    """``img`` scaled by ``factor`` about the frame point ``centre``."""
    cx, cy = centre
    M = np.float32([[factor, 0, cx * (1 - factor)], [0, factor, cy * (1 - factor)]])
    return cv2.warpAffine(img, M, (img.shape[1], img.shape[0]), borderMode=cv2.BORDER_REFLECT)


def _box_at(centre, size):
    s = np.asarray(size, dtype=np.float64)
    return np.array([*(np.asarray(centre) - (s - 1.0) / 2.0), *s])


BOX = np.array([140.0, 100.0, 40.0, 30.0])
CENTRE = box_to_affine(BOX)[4:]


def _levels(f, img, steps):
    return [(ls, *f.response(img, _box_at(CENTRE, BOX[2:] * np.exp(ls)))) for ls in steps]


def test_one_level_is_the_plain_cost():
    img = _texture()
    f = CorrelationFilter(img, BOX)
    r, win = f.response(img, BOX)
    centres = np.array([[160.0, 115.0], [150.0, 110.0], [120.0, 90.0]])
    for ref in (None, 0.8):
        np.testing.assert_allclose(
            scaled_correlation_cost([(0.0, r, win)], centres, [0.3, -0.2, 0.0], ref),
            correlation_cost(r, win, centres, ref),
            atol=1e-12,
        )


def test_levels_are_interpolated_in_log_side_and_clamped():
    img = _texture()
    f = CorrelationFilter(img, BOX)
    levels = _levels(f, _zoomed(img, 1.1, CENTRE), (-0.1, 0.0, 0.1))
    centres = np.array([[158.0, 113.0], [161.0, 116.0], [150.0, 110.0], [159.5, 114.5]])
    log_sides = np.array([-0.1, 0.05, 0.4, -0.025])
    # each level's response at the points, from scipy's bilinear sampling
    at = np.stack(
        [ndimage.map_coordinates(r, w.cells(centres)[:, ::-1].T, order=1, mode="constant") for _, r, w in levels]
    )
    r_i = np.array([at[0, 0], 0.5 * at[1, 1] + 0.5 * at[2, 1], at[2, 2], 0.25 * at[0, 3] + 0.75 * at[1, 3]])
    peak = max(r.max() for _, r, _ in levels)
    expected = (peak - np.clip(r_i, 0.0, peak)) / 0.9
    np.testing.assert_allclose(scaled_correlation_cost(levels, centres, log_sides, 0.9), expected, atol=1e-12)
    # without a reference, the best level's peak is the reference
    plain = scaled_correlation_cost(levels, centres, log_sides)
    np.testing.assert_allclose(plain, (peak - np.clip(r_i, 0.0, peak)) / peak, atol=1e-12)


@pytest.mark.parametrize("factor", [0.85, 1.2])
def test_the_cost_is_least_near_the_size_the_target_took(factor):
    img = _texture()
    f = CorrelationFilter(img, BOX)
    levels = _levels(f, _zoomed(img, factor, CENTRE), (-0.2, 0.0, 0.2))
    sides = np.array([-0.2, 0.0, 0.2])
    cost = scaled_correlation_cost(levels, np.tile(CENTRE, (3, 1)), sides)
    # the level nearest the size the target took costs least (the cost is linear between levels)
    nearest = int(np.argmin(np.abs(sides - np.log(factor))))
    assert nearest != 1 and np.argmin(cost) == nearest
    assert cost[nearest] < cost[1] - 0.05


def test_the_tracker_reads_the_cue_at_each_candidate_size():
    demo = make_demo_sequence(n_frames=3)
    frames, box = demo.frames, demo.groundtruth[0]
    t = Tracker(TrackerConfig(seed=0, correlation_scales=1, correlation_scale_step=0.1))
    t.init(frames[0], box)
    cue = t._corr
    assert isinstance(cue, CorrelationCue)
    _, detail = t.update_detailed(frames[1])
    # the cost the tracker added is the scaled one; the plain one differs where sizes differ
    before = Tracker(t.config)
    before.init(frames[0], box)
    response = before._response(frames[1])
    before._corr.judge(response)  # the cue's usual peak, as in the tracker's frame
    scaled = before._corr.scaled_costs(frames[1], response, detail.particles)
    np.testing.assert_allclose(detail.cue_costs["correlation"][: len(detail.particles)], scaled, atol=1e-12)
    assert np.max(np.abs(scaled - before._corr.costs(response, detail.particles))) > 1e-4


def test_peak_level_is_the_parabolas_vertex_between_ends():
    step = 0.05
    levels = np.arange(-4, 5) * step
    # a parabola in log side peaked at 0.07: its vertex, exactly
    peaks = 1.0 - (levels - 0.07) ** 2
    assert peak_level(peaks, step) == pytest.approx(0.07, abs=1e-12)
    # highest at an end: that end, no refinement
    assert peak_level(np.linspace(0.0, 1.0, 9), step) == pytest.approx(4 * step)
    assert peak_level(np.linspace(1.0, 0.0, 9), step) == pytest.approx(-4 * step)
    # one window: its own size
    assert peak_level([0.3], step) == 0.0


@pytest.mark.parametrize("factor", [0.9, 1.12])
def test_the_filter_reads_the_size_the_target_took(factor):
    img = _texture()
    t = Tracker(TrackerConfig(seed=0, report_read_size=4))
    t.init(np.dstack([img] * 3), BOX)
    cue = t._corr
    zoomed = np.dstack([_zoomed(img, factor, CENTRE)] * 3)
    read = cue.read_size(zoomed, BOX)
    np.testing.assert_allclose(box_to_affine(read)[4:], CENTRE, atol=1e-9)  # about the same centre
    assert read[2] / read[3] == pytest.approx(BOX[2] / BOX[3])
    assert np.log(read[2] / BOX[2]) == pytest.approx(np.log(factor), abs=0.03)


def test_reading_the_size_leaves_the_track_as_it_was():
    demo = make_demo_sequence(n_frames=12)
    frames, box = demo.frames, demo.groundtruth[0]
    plain, read = Tracker(TrackerConfig(seed=0)), Tracker(TrackerConfig(seed=0, report_read_size=2))
    plain.init(frames[0], box)
    read.init(frames[0], box)
    sizes = []
    for f in frames[1:]:
        a, b = plain.update(f), read.update(f)
        np.testing.assert_array_equal(plain._state, read._state)
        np.testing.assert_allclose(box_to_affine(np.array(b.box))[4:], box_to_affine(np.array(a.box))[4:], atol=1e-9)
        sizes.append(np.log(b.box[2] / a.box[2]))
    assert np.max(np.abs(sizes)) > 1e-3  # the reported size did change
