"""Preprocessing on the window the candidates read: extent, window, plane mapping, equality."""

import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.demo import make_demo_sequence
from smtmvt.features import tan_triggs
from smtmvt.geometry import affine_extent, box_to_affine
from smtmvt.motion import propagate
from smtmvt.preprocess import color_channels, crop_window, prepare_frame, smooth, smooth_reach
from smtmvt.warp import remap_patches, sampling_grid


@pytest.fixture(scope="module")
def demo():
    return make_demo_sequence(n_frames=12)


def _states(rng, n=50):
    start = np.repeat(box_to_affine(np.array([140.0, 90.0, 40.0, 30.0]))[None], n, axis=0)
    states = propagate(start, [0.05, 0.05, 0.05, 0.05, 6.0, 6.0], rng)
    states[0, 1] = 0.4  # a strong shear
    return states


def test_affine_extent_bounds_every_sample_point_and_is_tight():
    rng = np.random.default_rng(0)
    states = _states(rng)
    x0, y0, x1, y1 = affine_extent(states)
    X, Y = sampling_grid(states, (64, 48))
    assert x0 <= X.min() and X.max() <= x1 and y0 <= Y.min() and Y.max() <= y1
    # a sample grid's outer points sit half a patch pixel inside the corners
    assert X.min() - x0 < 3.0 and x1 - X.max() < 3.0 and Y.min() - y0 < 3.0 and y1 - Y.max() < 3.0
    with pytest.raises(ValueError, match="at least one"):
        affine_extent(np.zeros((0, 6)))


@pytest.mark.parametrize(
    "extent,expected",
    [
        ((50.2, 40.7, 80.5, 60.0), (40, 30, 92, 71)),  # inside: grown by the margin
        ((-30.0, -5.0, 20.0, 10.0), (0, 0, 31, 21)),  # clipped at the top-left border
        ((300.0, 230.0, 400.0, 300.0), (290, 220, 320, 240)),  # clipped at the bottom-right border
        ((500.0, 100.0, 600.0, 110.0), (318, 90, 320, 121)),  # beyond the frame: its last 2 columns
        ((-90.0, -80.0, -60.0, -70.0), (0, 0, 2, 2)),
    ],
)
def test_crop_window(extent, expected):
    assert crop_window(extent, 10.0, (240, 320)) == expected


def test_crop_window_rejects_a_non_finite_extent():
    with pytest.raises(ValueError, match="not finite"):
        crop_window((0.0, np.nan, 5.0, 5.0), 1.0, (10, 10))


def test_smooth_reach_is_the_kernel_radius():
    """Smoothing an impulse spreads it exactly ``smooth_reach`` pixels."""
    for sigma in (0.2, 0.5, 1.0, 1.7, 3.2):
        impulse = np.zeros((61, 61), np.float32)
        impulse[30, 30] = 1.0
        nonzero = np.flatnonzero(smooth(impulse, sigma)[30] != 0)
        assert nonzero[-1] - 30 == smooth_reach(sigma), sigma


def test_window_planes_are_the_frames_except_for_the_equalization_scale(demo):
    frame = demo.frames[3]
    whole = prepare_frame(frame)
    x0, y0, x1, y1 = 100, 60, 220, 170
    part = prepare_frame(frame, window=(x0, y0, x1, y1))
    assert part.origin == (x0, y0) and part.shape == (110, 120)
    np.testing.assert_array_equal(part.gray, whole.gray[y0:y1, x0:x1])
    np.testing.assert_array_equal(part.color, whole.color[y0:y1, x0:x1])
    # Tan-Triggs of the window's own pixels: its filters are local, so away from the
    # window's border (8 px) the plane is the frame's up to the equalization constants
    # (means over the window), a positive scale before the tanh compression.
    np.testing.assert_array_equal(part.normalized, tan_triggs(whole.gray[y0:y1, x0:x1]))
    a, b = part.normalized[10:-10, 10:-10], whole.normalized[y0 + 10 : y1 - 10, x0 + 10 : x1 - 10]
    assert np.corrcoef(a.ravel(), b.ravel())[0, 1] > 0.97  # measured 0.985 (the tanh saturates apart)
    with pytest.raises(ValueError, match="not inside"):
        prepare_frame(frame, window=(300, 0, 330, 20))


@pytest.mark.parametrize("scale", [1.0, 0.6, 1.5])
def test_to_plane_maps_states_onto_the_window(demo, scale):
    """Patches sampled on a (resized) window through ``to_plane`` are those of the
    (resized) frame: the raw gray plane, whose values do not depend on the window."""
    frame = demo.frames[2]
    states = _states(np.random.default_rng(1), 20)
    window = crop_window(affine_extent(states), 4.0 / scale, frame.shape[:2])
    part = prepare_frame(frame, window=window, plane_scale=scale)
    got = remap_patches(part.gray, *sampling_grid(part.to_plane(states), (32, 32)))
    H, W = frame.shape[:2]
    whole = prepare_frame(frame, plane_scale=scale)
    sx, sy = whole.scale
    assert abs(sx - scale) < 0.01 and abs(sy - scale) < 0.01
    ref = remap_patches(whole.gray, *sampling_grid(whole.to_plane(states), (32, 32)))
    if scale == 1.0:
        np.testing.assert_allclose(got, ref, atol=1e-5)
    else:  # resizing a window and resizing the frame round the sizes apart: close, not equal
        assert np.abs(got - ref).mean() < 0.01


def test_color_channels():
    rgb = np.zeros((4, 5, 3), np.uint8)
    rgb[..., 1] = 9
    assert color_channels(rgb) == 3 and color_channels(rgb[..., 0]) == 1
    assert color_channels(np.repeat(rgb[..., 1:2], 3, axis=2)) == 1
    with pytest.raises(ValueError, match="shape"):
        color_channels(np.zeros((4, 5, 2), np.uint8))


def test_tracker_views_from_the_window_match_the_whole_frames(demo):
    """The tracker's views of its particles, prepared on their window, against the
    same views prepared on the whole frame: color, HOG and LBP equal up to the
    sample points' rounding, intensity within the equalization's effect."""
    t = Tracker(TrackerConfig(seed=0, n_particles=60, scale_normalize=False))
    t.init(demo.frames[0], demo.groundtruth[0])
    t.update(demo.frames[1])
    states = propagate(t._particles, t.config.affine_std, np.random.default_rng(2))
    assert t._plane_scale() == 1.0
    windowed = t.views_of(demo.frames[2], states)
    whole = t._views(prepare_frame(demo.frames[2], channels=t._channels), states)
    for name, a, b in zip(t.config.views, windowed, whole):
        if name == "intensity":
            cos = np.einsum("ij,ij->j", a, b)
            assert cos.min() > 0.96, cos.min()  # measured 0.979
        else:
            # equal but for the sample points' float32 rounding (relative to another
            # origin), which moves a few of OpenCV's 1/32-pixel bilinear steps
            np.testing.assert_allclose(a, b, atol=1e-3, err_msg=name)
            assert np.abs(a - b).mean() < 1e-5, name
