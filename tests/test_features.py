"""Tests of smtmvt.features: Tan-Triggs, the four views, the registry, normalization."""

import dataclasses
import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal
from scipy import ndimage as ndi
from skimage import data
from skimage.feature import hog as sk_hog
from skimage.feature import local_binary_pattern as sk_lbp

from smtmvt.features import (
    Patches,
    available_views,
    extract_views,
    intensity_template_size,
    normalize_columns,
    register_view,
    tan_triggs,
)
from smtmvt.features import views as views_module
from smtmvt.features.coarse import COARSE_SIGMA, coarse_view
from smtmvt.features.color import color_histograms, color_view, soft_binning_matrix
from smtmvt.features.hog import hog_descriptors, hog_dim, hog_view, orientation_bins
from smtmvt.features.lbp import lbp_codes, lbp_histograms, lbp_view
from smtmvt.features.tan_triggs import difference_of_gaussians


@pytest.fixture(scope="module")
def camera():
    return data.camera()  # (512, 512) uint8


@pytest.fixture(scope="module")
def camera_tt(camera):
    return tan_triggs(camera)


def _crops(image, size, count, rng):
    h, w = size
    rows = rng.integers(0, image.shape[0] - h, count)
    cols = rng.integers(0, image.shape[1] - w, count)
    return np.stack([image[r : r + h, c : c + w] for r, c in zip(rows, cols)]).astype(np.float32)


@pytest.fixture(scope="module")
def gray_patches(camera, camera_tt):
    """32x32 float32 patches: random, camera crops (raw and Tan-Triggs), tie-heavy, constant."""
    rng = np.random.default_rng(1)
    # 150 patches: more than two of the implementation's 64-patch blocks
    parts = [
        rng.standard_normal((40, 32, 32)).astype(np.float32) * 3,
        _crops(camera.astype(np.float32) / 255, (32, 32), 40, rng),
        _crops(camera_tt, (32, 32), 50, rng),
        # few distinct levels: many exactly equal neighbours and axis-aligned gradients
        rng.integers(0, 3, (18, 32, 32)).astype(np.float32) * np.float32(0.3),
        np.full((1, 32, 32), 1 / 3, dtype=np.float32),
        np.zeros((1, 32, 32), dtype=np.float32),
    ]
    return np.concatenate(parts)


def _skimage_hog(patch):
    return sk_hog(
        patch, orientations=9, pixels_per_cell=(8, 8), cells_per_block=(2, 2), block_norm="L2-Hys", feature_vector=True
    )


def _skimage_lbp(patch, P=8, R=1):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # skimage warns on float input
        return sk_lbp(patch, P, R, "uniform")


def _make_patches(n, rng, th=20, tw=20, size=32, channels=3):
    return Patches(
        intensity=rng.standard_normal((n, th, tw)).astype(np.float32),
        gray=rng.standard_normal((n, size, size)).astype(np.float32),
        color=rng.random((n, size, size, channels)).astype(np.float32),
    )


# --------------------------------------------------------------------------- HOG


def test_hog_matches_skimage(gray_patches):
    ours = hog_descriptors(gray_patches)
    ref = np.stack([_skimage_hog(p) for p in gray_patches])
    assert ours.shape == (len(gray_patches), 324) == ref.shape
    assert ours.dtype == np.float32
    assert_allclose(ours, ref, rtol=0, atol=1e-6)


def test_hog_matches_skimage_on_partial_cells(camera_tt):
    # 36x44: the last 4 rows/cols lie outside full cells and must be ignored.
    patches = _crops(camera_tt, (36, 44), 6, np.random.default_rng(2))
    ours = hog_descriptors(patches)
    ref = np.stack([_skimage_hog(p) for p in patches])
    assert ours.shape[1] == hog_dim((36, 44)) == ref.shape[1]
    assert_allclose(ours, ref, rtol=0, atol=1e-6)


def _skimage_bins(g_row, g_col, orientations):
    """skimage's binning, verbatim: float64 orientation, float32-rounded edges
    (``orientations`` = no bin, for an angle that rounds to exactly 180)."""
    orientation = np.rad2deg(np.arctan2(g_row.astype(np.float64), g_col.astype(np.float64))) % 180
    edges = np.array([np.float32(180.0 / orientations * i) for i in range(orientations + 1)], dtype=np.float64)
    return np.searchsorted(edges, orientation, side="right") - 1


def test_hog_orientation_bins_equal_skimage_float64_binning():
    rng = np.random.default_rng(3)
    g_row = np.concatenate(
        [
            rng.integers(-4, 5, 200_000),
            rng.standard_normal(200_000),
            [-1e-30, 1e-30, 0.0, -0.0, 0.0, 1.0, -1.0],
        ]
    ).astype(np.float32)
    g_col = np.concatenate(
        [
            rng.integers(-4, 5, 200_000),
            rng.standard_normal(200_000),
            [1.0, -1.0, -1.0, -1.0, 0.0, 0.0, 0.0],
        ]
    ).astype(np.float32)
    exact = _skimage_bins(g_row, g_col, 9)
    assert_array_equal(orientation_bins(g_row, g_col, 9), exact)
    # gradients on the bin edges themselves (the atan2 fallback), float64 too
    angles = np.radians(np.arange(0, 360, 20.0))
    for scale in (1.0, 3.7e-3, 250.0):
        r, c = scale * np.sin(angles), scale * np.cos(angles)
        for nudge in (0.0, 1e-12, -1e-12):
            assert_array_equal(orientation_bins(r + nudge, c, 9), _skimage_bins(r + nudge, c, 9))
    # skimage's quirk: an angle that rounds to 180 degrees falls in no bin.
    assert exact[400_000] == 9


def test_hog_rejects_too_small_patches():
    with pytest.raises(ValueError, match="too small"):
        hog_descriptors(np.zeros((2, 12, 32), dtype=np.float32))


# --------------------------------------------------------------------------- LBP


def test_lbp_codes_equal_skimage(gray_patches):
    ours = lbp_codes(gray_patches)
    ref = np.stack([_skimage_lbp(p) for p in gray_patches])
    assert ours.dtype == np.uint8
    assert_array_equal(ours, ref)


@pytest.mark.parametrize("P,R", [(8, 2), (16, 2), (8, 1.5), (4, 1)])
def test_lbp_codes_equal_skimage_other_radii(gray_patches, P, R):
    subset = gray_patches[::4, :24, :29]
    ref = np.stack([_skimage_lbp(p, P, R) for p in subset])
    assert_array_equal(lbp_codes(subset, P, R), ref)


@pytest.mark.parametrize("grid", [4, 2, 3])
def test_lbp_histograms_equal_ones_from_skimage_codes(gray_patches, grid):
    codes = np.stack([_skimage_lbp(p) for p in gray_patches]).astype(int)
    n, h, w = codes.shape
    bounds_r = [j * h // grid for j in range(grid + 1)]
    bounds_c = [j * w // grid for j in range(grid + 1)]
    ref = np.zeros((n, grid, grid, 10))
    for i in range(n):
        for a in range(grid):
            for b in range(grid):
                cell = codes[i, bounds_r[a] : bounds_r[a + 1], bounds_c[b] : bounds_c[b + 1]]
                ref[i, a, b] = np.bincount(cell.ravel(), minlength=10) / cell.size
    ours = lbp_histograms(lbp_codes(gray_patches), 10, grid)
    assert ours.shape == (n, grid * grid * 10)
    assert_allclose(ours, ref.reshape(n, -1), rtol=0, atol=1e-7)


def test_hog_and_lbp_views_on_the_raw_gray_plane(gray_patches):
    tt, raw = gray_patches[:40], gray_patches[40:80]
    patches = Patches(tt[:, :20, :20], tt, np.zeros(tt.shape + (3,), np.float32), raw=raw)
    assert_array_equal(hog_view(patches, plane="gray"), hog_descriptors(raw))
    assert_array_equal(hog_view(patches), hog_descriptors(tt))
    assert_array_equal(lbp_view(patches, plane="gray"), lbp_histograms(lbp_codes(raw), 10, 4))
    no_raw = Patches(tt[:, :20, :20], tt, np.zeros(tt.shape + (3,), np.float32))
    with pytest.raises(ValueError, match="raw"):
        hog_view(no_raw, plane="gray")
    with pytest.raises(ValueError, match="plane"):
        lbp_view(patches, plane="sobel")


def test_lbp_view_is_4x4_grid_of_10_codes(gray_patches):
    patches = Patches(gray_patches[:, :20, :20], gray_patches, np.zeros(gray_patches.shape + (3,), np.float32))
    out = lbp_view(patches)
    assert out.shape == (len(gray_patches), 160)
    assert_allclose(out.reshape(-1, 16, 10).sum(axis=2), 1.0, atol=1e-6)


# --------------------------------------------------------------------------- Tan-Triggs


def _tan_triggs_reference(image01, gamma=0.2, s0=1.0, s1=2.0, alpha=0.1, tau=10.0):
    """Direct float64 transcription of Tan & Triggs (2010) with scipy filters."""
    x = np.power(image01, gamma)
    x = ndi.gaussian_filter(x, s0, mode="reflect") - ndi.gaussian_filter(x, s1, mode="reflect")
    x = x / np.mean(np.abs(x) ** alpha) ** (1 / alpha)
    x = x / np.mean(np.minimum(tau, np.abs(x)) ** alpha) ** (1 / alpha)
    return tau * np.tanh(x / tau)


def test_tan_triggs_matches_direct_reference(camera):
    ours = tan_triggs(camera)
    assert ours.dtype == np.float32 and ours.shape == camera.shape
    ref = _tan_triggs_reference(camera / 255.0)
    assert_allclose(ours, ref, rtol=0, atol=2e-4)


@pytest.mark.parametrize("tau", [10.0, 3.0])
def test_tan_triggs_output_range(camera, tau):
    rng = np.random.default_rng(4)
    for image in (camera, rng.random((60, 80)), rng.integers(0, 2, (40, 40)).astype(np.uint8) * 255):
        out = tan_triggs(image, tau=tau)
        assert np.all(np.isfinite(out))
        assert out.min() >= -tau and out.max() <= tau
        assert np.abs(out).max() > 0.25 * tau  # not collapsed to ~0


def test_tan_triggs_invariant_to_input_scale(camera):
    base = tan_triggs(camera)
    assert_allclose(tan_triggs(camera.astype(np.uint16) * 257), base, rtol=0, atol=1e-4)
    assert_allclose(tan_triggs(camera / 255.0), base, rtol=0, atol=1e-4)
    assert_allclose(tan_triggs(camera.astype(np.float32) * 7.3), base, rtol=0, atol=1e-4)


def test_tan_triggs_constant_image_gives_zeros():
    for image in (
        np.full((30, 40), 77, np.uint8),
        np.full((30, 40), 0.37),
        np.zeros((30, 40), np.float32),
        np.full((30, 40), 65535, np.uint16),
    ):
        out = tan_triggs(image)
        assert not np.isnan(out).any()
        assert_array_equal(out, 0)


def test_tan_triggs_negative_floats_are_clipped():
    image = np.random.default_rng(5).random((40, 50))
    shifted = image.copy()
    shifted[image < 0.2] = -5.0  # clipped to 0, same as setting them to 0
    zeroed = image.copy()
    zeroed[image < 0.2] = 0.0
    assert_array_equal(tan_triggs(shifted), tan_triggs(zeroed))


def test_tan_triggs_removes_smooth_illumination_gradient(camera):
    image = camera / 255.0
    h, w = image.shape
    yy, xx = np.mgrid[0:h, 0:w]
    for light in (0.3 + 0.7 * xx / (w - 1), 0.25 + 0.75 * (xx + yy) / (h + w - 2)):
        lit = image * light
        raw_change = np.linalg.norm(lit - image) / np.linalg.norm(image)
        a, b = tan_triggs(image), tan_triggs(lit)
        tt_change = np.linalg.norm(b - a) / np.linalg.norm(a)
        assert raw_change > 0.3
        assert tt_change < 0.1 * raw_change


def test_difference_of_gaussians_matches_scipy(camera):
    x = np.power(camera / 255.0, 0.2).astype(np.float32)
    ref = ndi.gaussian_filter(x.astype(np.float64), 1.0, mode="reflect") - ndi.gaussian_filter(
        x.astype(np.float64), 2.0, mode="reflect"
    )
    assert_allclose(difference_of_gaussians(x, 1.0, 2.0), ref, rtol=0, atol=2e-6)
    ref0 = x - ndi.gaussian_filter(x.astype(np.float64), 2.0, mode="reflect")
    assert_allclose(difference_of_gaussians(x, 0.0, 2.0), ref0, rtol=0, atol=2e-6)


def test_tan_triggs_rejects_bad_input():
    with pytest.raises(ValueError, match="gray"):
        tan_triggs(np.zeros((4, 4, 3), np.uint8))
    with pytest.raises(TypeError, match="dtype"):
        tan_triggs(np.zeros((4, 4), np.int32))
    with pytest.raises(ValueError, match="sigma"):
        tan_triggs(np.zeros((8, 8), np.uint8), sigma0=2.0, sigma1=1.0)


# --------------------------------------------------------------------------- color


def test_color_histogram_channels_sum_to_one():
    colors = np.random.default_rng(6).random((5, 32, 32, 3)).astype(np.float32)
    hist = color_histograms(colors)
    assert hist.shape == (5, 48) and hist.dtype == np.float32
    assert_allclose(hist.reshape(5, 3, 16).sum(axis=2), 1.0, atol=1e-6)
    assert np.all(hist >= 0)


def test_color_histogram_soft_binning():
    colors = np.empty((1, 4, 4, 3), np.float32)
    colors[..., 0] = 2.5 / 16  # centre of bin 2: all mass in bin 2
    colors[..., 1] = 3.0 / 16  # half-way between the centres of bins 2 and 3
    colors[..., 2] = 1.0  # beyond the last centre: all in bin 15
    hist = color_histograms(colors).reshape(3, 16)
    expected = np.zeros((3, 16))
    expected[0, 2] = 1.0
    expected[1, 2] = expected[1, 3] = 0.5
    expected[2, 15] = 1.0
    # values are rounded to 8 bits first: 2.5/16 -> 40/255, 3/16 -> 48/255
    assert_allclose(hist, expected, atol=0.02)
    assert hist[0, 2] > 0.98 and abs(hist[1, 2] - hist[1, 3]) < 0.04


def test_color_histogram_red_vs_blue():
    red = np.zeros((1, 32, 32, 3), np.float32)
    red[..., 0] = 0.9
    blue = np.zeros((1, 32, 32, 3), np.float32)
    blue[..., 2] = 0.9
    h_red, h_blue = color_histograms(red)[0], color_histograms(blue)[0]
    assert np.abs(h_red - h_blue).sum() > 3.0  # two channels fully moved: L1 distance 4
    assert h_red[:16][14] > 0.5 and h_red[32:][0] == 1.0
    assert h_blue[32:][14] > 0.5 and h_blue[:16][0] == 1.0


def test_color_gray_fallback():
    rng = np.random.default_rng(7)
    patches = _make_patches(4, rng, channels=1)
    hist = color_view(patches)
    assert hist.shape == (4, 16)
    assert np.all(np.isfinite(hist))
    assert_allclose(hist.sum(axis=1), 1.0, atol=1e-6)
    (X,) = extract_views(patches, ("color",))
    assert X.shape == (16, 4) and np.all(np.isfinite(X))


def test_color_grid_is_the_histograms_of_the_cells():
    rng = np.random.default_rng(8)
    patches = _make_patches(3, rng)
    out = color_view(patches, grid=2)
    c = patches.color
    cells = [c[:, :16, :16], c[:, :16, 16:], c[:, 16:, :16], c[:, 16:, 16:]]
    ref = np.concatenate([color_histograms(np.ascontiguousarray(q)) for q in cells], axis=1)
    assert out.shape == (3, 4 * 48)
    assert_array_equal(out, ref)
    assert_array_equal(color_view(patches, grid=1), color_histograms(c))
    with pytest.raises(ValueError, match="grid"):
        color_view(patches, grid=33)


@pytest.mark.parametrize("shape, grid", [((5, 13, 11, 3), 2), ((5, 13, 11, 3), 3), ((3, 9, 14, 1), 4)])
def test_color_grid_on_uneven_cells_equals_the_histograms_of_the_slices(shape, grid):
    """The one-pass cell counting equals one histogram per slice ``[j L // grid, (j + 1) L // grid)``."""

    class _Colors:
        color = np.random.default_rng(9).random(shape, dtype=np.float32) * 1.2 - 0.1

    n, h, w, _ = shape
    rows = [j * h // grid for j in range(grid + 1)]
    cols = [j * w // grid for j in range(grid + 1)]
    c = _Colors.color
    ref = np.concatenate(
        [
            color_histograms(np.ascontiguousarray(c[:, rows[i] : rows[i + 1], cols[j] : cols[j + 1]]))
            for i in range(grid)
            for j in range(grid)
        ],
        axis=1,
    )
    assert_array_equal(color_view(_Colors, grid=grid), ref)


@pytest.mark.parametrize("spread", [1.0, 0.2])
def test_color_histograms_equal_the_level_order_sums_bit_for_bit(spread):
    """The compiled histograms equal the soft-binning matrix applied to each patch's
    8-bit level counts, summed in level order in float64 (the kernel's order),
    on patches that reach every level and on patches that reach few of them."""
    rng = np.random.default_rng(21)
    colors = (0.3 + spread * rng.random((6, 12, 10, 3))).astype(np.float32)
    W = soft_binning_matrix()
    level = np.floor(np.clip(colors * np.float32(255) + np.float32(0.5), 0.5, 255.5)).astype(int)
    ref = np.zeros((6, 3, 16))
    counts = np.stack([[np.bincount(level[i, ..., c].ravel(), minlength=256) for c in range(3)] for i in range(6)])
    for q in range(256):
        for b in np.flatnonzero(W[q]):
            ref[:, :, b] += counts[:, :, q] * W[q, b]
    expected = (ref / (12 * 10)).astype(np.float32).reshape(6, 48)
    assert_array_equal(color_histograms(colors), expected)
    if spread < 1:
        assert len(np.unique(level)) < 128  # most levels unused


def test_color_values_outside_unit_range_are_clipped():
    colors = np.full((1, 8, 8, 3), 1.7, np.float32)
    colors[..., 1] = -0.3
    hist = color_histograms(colors).reshape(3, 16)
    assert hist[0, 15] == 1.0 and hist[1, 0] == 1.0


# --------------------------------------------------------------------------- coarse


def _coarse_reference(raw):
    """The coarse view written out with scipy: gamma, minus the 2-D Gaussian
    blur (mode nearest), 2x2 block means (odd last row/column dropped)."""
    g = np.power(np.maximum(raw.astype(np.float64), 1e-4), 0.2)
    out = []
    for p in g:
        d = p - ndi.gaussian_filter(p, COARSE_SIGMA, mode="nearest")
        h, w = (d.shape[0] // 2) * 2, (d.shape[1] // 2) * 2
        out.append(d[:h, :w].reshape(h // 2, 2, w // 2, 2).mean(axis=(1, 3)).ravel())
    return np.stack(out)


@pytest.mark.parametrize("shape", [(7, 32, 32), (3, 31, 18)])
def test_coarse_view_matches_scipy(shape):
    raw = np.random.default_rng(31).random(shape).astype(np.float32)
    raw[0, :3, :3] = 0.0  # the floor before the gamma
    ours = coarse_view(Patches(None, None, None, raw))
    assert ours.shape == (shape[0], (shape[1] // 2) * (shape[2] // 2)) and ours.dtype == np.float32
    assert_allclose(ours, _coarse_reference(raw), atol=2e-6)


def test_coarse_view_band_pass():
    # a constant patch has no band-pass content; a coarse blob does, and the
    # normalized view is the same for any gain of the gray patch (the gamma turns
    # a gain into a gain)
    flat = coarse_view(Patches(None, None, None, np.full((1, 32, 32), 0.4, np.float32)))
    assert np.abs(flat).max() < 1e-6
    yy, xx = np.mgrid[:32, :32]
    blob = (0.2 + 0.6 * np.exp(-((yy - 12.0) ** 2 + (xx - 20.0) ** 2) / 18.0)).astype(np.float32)
    a, b = (extract_views(Patches(None, None, None, (k * blob)[None]), ("coarse",))[0][:, 0] for k in (1.0, 0.5))
    assert np.abs(a).max() > 0.1
    assert_allclose(a, b, atol=1e-5)
    # the blob's centre block (row 6, column 10 of 16) is where the view peaks
    assert np.argmax(a) == 6 * 16 + 10


def test_coarse_view_needs_raw():
    with pytest.raises(ValueError, match="Patches.raw"):
        coarse_view(_make_patches(2, np.random.default_rng(1)))


# --------------------------------------------------------------------------- extract_views


def test_available_views_default_order():
    assert available_views()[:4] == ("intensity", "color", "hog", "lbp")


def test_extract_views_shapes_and_normalization():
    rng = np.random.default_rng(8)
    n = 37
    patches = _make_patches(n, rng, th=15, tw=11)
    out = extract_views(patches)
    assert [X.shape for X in out] == [(165, n), (48, n), (324, n), (160, n)]
    for X in out:
        assert X.dtype == np.float32 and X.flags.c_contiguous
        assert np.all(np.isfinite(X))
        assert_allclose(np.linalg.norm(X, axis=0), 1.0, atol=1e-5)
        assert_allclose(X.mean(axis=0), 0.0, atol=1e-6)


def test_extract_views_constant_patches_have_no_nan():
    n = 3
    patches = Patches(
        intensity=np.full((n, 10, 10), 2.5, np.float32),
        gray=np.full((n, 32, 32), 2.5, np.float32),
        color=np.full((n, 32, 32, 3), 0.5, np.float32),
    )
    out = dict(zip(available_views(), extract_views(patches, available_views()[:4])))
    for X in out.values():
        assert not np.isnan(X).any()
    assert_array_equal(out["intensity"], 0)  # constant template -> zero column
    assert_array_equal(out["hog"], 0)  # no gradient anywhere
    # constant colour: one bin per channel, still a proper (non-constant) column
    assert_allclose(np.linalg.norm(out["color"], axis=0), 1.0, atol=1e-5)


def test_extract_views_batch_equals_one_at_a_time():
    rng = np.random.default_rng(9)
    patches = _make_patches(150, rng)  # spans three 64-patch blocks
    batch = extract_views(patches)
    for i in (0, 1, 63, 64, 100, 127, 128, 149):
        single = extract_views(patches.subset([i]))
        for X, x in zip(batch, single):
            assert_array_equal(X[:, i], x[:, 0])


def test_extract_views_single_name_and_order():
    rng = np.random.default_rng(10)
    patches = _make_patches(3, rng)
    hog_only = extract_views(patches, ("hog",))
    both = extract_views(patches, ("lbp", "hog"))
    assert len(hog_only) == 1 and len(both) == 2
    assert_array_equal(both[1], hog_only[0])
    assert both[0].shape == (160, 3)


def test_extract_views_unknown_name_lists_available():
    patches = _make_patches(2, np.random.default_rng(11))
    with pytest.raises(ValueError, match="intensity, color, hog, lbp"):
        extract_views(patches, ("intensity", "sift"))


def test_register_view(monkeypatch):
    monkeypatch.setattr(views_module, "VIEW_REGISTRY", dict(views_module.VIEW_REGISTRY))

    def mean_gray(patches):
        g = patches.gray
        return np.stack([g.mean(axis=(1, 2)), g.std(axis=(1, 2))], axis=1).astype(np.float32)

    register_view("mean_gray", mean_gray)
    assert available_views()[-1] == "mean_gray"
    patches = _make_patches(4, np.random.default_rng(12))
    (X,) = extract_views(patches, ("mean_gray",))
    assert X.shape == (2, 4)
    with pytest.raises(ValueError, match="already registered"):
        register_view("mean_gray", mean_gray)
    register_view("mean_gray", mean_gray, replace=True)
    register_view("bad", lambda p: np.zeros((p.n + 1, 3), np.float32))
    with pytest.raises(ValueError, match="returned shape"):
        extract_views(patches, ("bad",))


def test_registry_unchanged_by_register_view_test():
    assert available_views() == ("intensity", "color", "hog", "lbp", "coarse")


# --------------------------------------------------------------------------- Patches


def test_patches_validation():
    rng = np.random.default_rng(13)
    ok = _make_patches(3, rng)
    with pytest.raises(ValueError, match="number of patches"):
        Patches(ok.intensity[:2], ok.gray, ok.color)
    with pytest.raises(ValueError, match=r"\(n, fh, fw\)"):
        Patches(ok.intensity, ok.gray[0], ok.color)
    with pytest.raises(ValueError, match="C = 3"):
        Patches(ok.intensity, ok.gray, np.zeros((3, 32, 32, 2), np.float32))
    small = Patches(ok.intensity, ok.gray, np.zeros((3, 16, 16, 3), np.float32))  # the color view's own size
    assert small.color.shape == (3, 16, 16, 3)
    with pytest.raises(ValueError, match="feature size"):
        Patches(ok.intensity, ok.gray, ok.color, raw=ok.gray[:, :16])
    with pytest.raises(ValueError, match="one patch per candidate"):
        Patches(ok.intensity, ok.gray[:2], ok.color)
    with pytest.raises(ValueError, match="at least one"):
        Patches(ok.intensity[:0], ok.gray[:0], ok.color[:0])
    converted = Patches(ok.intensity.astype(np.float64), ok.gray, ok.color)
    assert converted.intensity.dtype == np.float32
    with pytest.raises(dataclasses.FrozenInstanceError):
        converted.gray = ok.gray
    with pytest.raises(ValueError, match="Patches.raw has shape"):
        Patches(ok.intensity, ok.gray, ok.color, ok.gray[:, :16])


def test_patches_without_a_plane_name_it_when_a_view_needs_it():
    """A plane no view reads may be left out (None); a view that reads it says which one is missing."""
    rng = np.random.default_rng(16)
    ok = _make_patches(3, rng)
    no_gray = Patches(ok.intensity, None, ok.color, raw=ok.gray)
    assert no_gray.subset([0, 2]).gray is None and no_gray.subset([0, 2]).raw.shape == (2, 32, 32)
    (hog,) = extract_views(no_gray, ("hog",), {"hog": {"plane": "gray"}})
    assert_array_equal(hog, extract_views(ok, ("hog",))[0])  # raw here holds the same values as gray
    with pytest.raises(ValueError, match="Patches.gray"):
        extract_views(no_gray, ("hog",))
    with pytest.raises(ValueError, match="Patches.raw"):
        extract_views(Patches(ok.intensity, ok.gray, ok.color), ("lbp",), {"lbp": {"plane": "gray"}})


def test_patches_subset_keeps_only_the_arrays_asked_for():
    """A deferred view gets the patches of its own array only; a view whose array is
    missing names it; a strided float32 array is kept as it is (no copy), and the
    views read it as they read its contiguous copy."""
    rng = np.random.default_rng(17)
    ok = _make_patches(4, rng)
    raw_only = Patches(ok.intensity, ok.gray, ok.color, raw=ok.gray).subset([3, 1], keep={"raw"})
    assert raw_only.intensity is None and raw_only.color is None and raw_only.gray is None
    assert raw_only.n == 2
    assert_array_equal(raw_only.raw, ok.gray[[3, 1]])
    (hog,) = extract_views(raw_only, ("hog",), {"hog": {"plane": "gray"}})
    assert_array_equal(hog, extract_views(ok.subset([3, 1]), ("hog",))[0])
    with pytest.raises(ValueError, match="Patches.color"):
        extract_views(raw_only, ("color",))
    with pytest.raises(ValueError, match="Patches.intensity"):
        extract_views(raw_only, ("intensity",))
    with pytest.raises(ValueError, match="at least one array"):
        Patches(None, None, None)
    four = np.stack([ok.gray, ok.gray[:, ::-1], ok.gray.T.transpose(2, 1, 0), ok.gray], axis=-1)  # (n, h, w, 4)
    strided = Patches(ok.intensity, None, ok.color, raw=four[..., 3])
    assert np.shares_memory(strided.raw, four) and not strided.raw.flags.c_contiguous
    for view in ("hog", "lbp"):
        options = {view: {"plane": "gray"}}
        assert_array_equal(extract_views(strided, (view,), options)[0], extract_views(ok, (view,))[0])


# --------------------------------------------------------------------------- normalize_columns


def test_normalize_columns_basic():
    V = np.array([[1.0, 3.0], [2.0, 3.0], [3.0, 3.0], [6.0, 3.0]])
    out = normalize_columns(V)
    assert out.dtype == np.float32
    expected = (V[:, 0] - 3.0) / np.linalg.norm(V[:, 0] - 3.0)
    assert_allclose(out[:, 0], expected, rtol=1e-6)
    assert_array_equal(out[:, 1], 0)  # constant column -> zero vector, no NaN


def test_normalize_columns_constant_columns_never_nan():
    rng = np.random.default_rng(14)
    values = rng.standard_normal(50) * 1e3
    V = np.tile(values, (500, 1))  # 50 constant float64 columns, inexact means
    out = normalize_columns(V)
    assert not np.isnan(out).any()
    assert_array_equal(out, 0)
    assert_array_equal(normalize_columns(np.zeros((7, 3), np.float32)), 0)
    assert normalize_columns(np.zeros((0, 3))).shape == (0, 3)


def test_normalize_columns_keeps_tiny_real_variation():
    # one float32 ulp of variation around 1000 is real data, not rounding noise
    col = np.full(64, 1000.0, np.float32)
    col[5] = np.nextafter(np.float32(1000.0), np.float32(2000.0))
    out = normalize_columns(col[:, None])
    assert_allclose(np.linalg.norm(out), 1.0, atol=1e-6)
    assert out[5, 0] > 0.9


# --------------------------------------------------------------------------- intensity


@pytest.mark.parametrize(
    "w,h,expected",
    [
        (60, 90, (30, 20)),  # shorter side >= 20: one third
        (20, 40, (13, 7)),  # shorter side exactly 20: one third (20/3 = 6.67 -> 7)
        (45, 33, (11, 15)),
        (21, 22.5, (8, 7)),  # 7.5 rounds up
        (19, 40, (20, 10)),  # shorter side < 20: one half (9.5 rounds up)
        (10, 12, (6, 5)),
        (6, 5, (4, 4)),  # floor of 4 px per side
        (40, 7, (4, 20)),
    ],
)
def test_intensity_template_size(w, h, expected):
    assert intensity_template_size(w, h) == expected


def test_intensity_template_size_rejects_bad_sizes():
    for w, h in [(0, 10), (10, -1), (np.nan, 10), (np.inf, 30)]:
        with pytest.raises(ValueError):
            intensity_template_size(w, h)


def test_intensity_view_is_flattened_template():
    rng = np.random.default_rng(15)
    patches = _make_patches(3, rng, th=6, tw=9)
    (X,) = extract_views(patches, ("intensity",))
    assert X.shape == (54, 3)
    assert_allclose(X[:, 1], normalize_columns(patches.intensity[1].reshape(-1, 1))[:, 0])


def test_soft_binning_of_level_counts_equals_the_matrix_product():
    """The histograms are ``counts @ soft_binning_matrix()``, computed from the two nonzero
    weights of each level (the first and last levels have one)."""
    from smtmvt.features.color import _LEVELS, _grid_histograms, soft_binning_matrix

    rng = np.random.default_rng(13)
    colors = rng.random((7, 12, 10, 3), dtype=np.float32)
    colors[0] = 0.0  # level 0 only
    colors[1] = 1.0  # level 255 only
    levels = np.floor(np.clip(colors * 255 + 0.5, 0.5, 255.5)).astype(int)
    counts = np.stack(
        [np.stack([np.bincount(levels[k, ..., ch].ravel(), minlength=_LEVELS) for ch in range(3)]) for k in range(7)]
    )
    ref = (counts @ soft_binning_matrix()).reshape(7, -1) / (12 * 10)
    assert_allclose(_grid_histograms(colors, 1, 16), ref, rtol=1e-6, atol=1e-7)
    assert _grid_histograms(colors, 1, 16)[0, 0] == 1.0 and _grid_histograms(colors, 1, 16)[1, 15] == 1.0


def test_histogram_power_raises_the_color_and_lbp_histograms(gray_patches):
    """power 0.5 is the Hellinger embedding: the square roots of the histogram values."""
    rng = np.random.default_rng(10)
    patches = _make_patches(4, rng)
    for grid in (1, 2):
        hist = color_view(patches, grid=grid)
        assert_allclose(color_view(patches, grid=grid, power=0.5), np.sqrt(hist), rtol=1e-6)
        assert_array_equal(color_view(patches, grid=grid, power=1.0), hist)
    lbp_patches = Patches(gray_patches[:, :20, :20], gray_patches, np.zeros(gray_patches.shape + (3,), np.float32))
    hist = lbp_view(lbp_patches)
    root = lbp_view(lbp_patches, power=0.5)
    assert_allclose(root, np.sqrt(hist), rtol=1e-6)
    assert_allclose((root**2).reshape(-1, 16, 10).sum(axis=2), 1.0, atol=1e-5)
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(ValueError, match="power"):
            color_view(patches, power=bad)


def test_histogram_square_root_equals_the_power_one_half_bit_for_bit():
    """power 0.5 is taken by np.sqrt (faster): the values of np.power, edges and
    subnormals included; other powers are np.power's."""
    from smtmvt.features.color import histogram_power

    rng = np.random.default_rng(4)
    tiny = np.float32(np.finfo(np.float32).smallest_subnormal)
    h = np.concatenate([rng.random(100_000, dtype=np.float32), [0.0, 1.0, tiny, 1e-38, 0.5, 0.25]]).astype(np.float32)
    assert_array_equal(histogram_power(h, 0.5), np.power(h, np.float32(0.5), dtype=np.float32))
    assert histogram_power(h, 0.5).dtype == np.float32
    assert_array_equal(histogram_power(h, 0.3), np.power(h, np.float32(0.3), dtype=np.float32))


def test_histogram_power_is_a_checked_tracker_option():
    from smtmvt import TrackerConfig

    assert TrackerConfig().histogram_power == 0.5 and TrackerConfig.paper().histogram_power == 1.0
    with pytest.raises(ValueError, match="histogram_power"):
        TrackerConfig(histogram_power=0.0)


@pytest.mark.parametrize("block", [(1, 1), (2, 2), (3, 3), (2, 3), (4, 4)])
def test_hog_block_kernel_equals_the_numpy_expression_bit_for_bit(block):
    """The compiled L2-Hys sums each block's squares in numpy's pairwise order, so it
    gives the array expression's descriptors exactly (4x4 blocks, 144 values, take the
    array expression itself)."""
    from smtmvt.features.hog import _cell_histograms, _normalized_blocks, hog_descriptors

    rng = np.random.default_rng(21)
    images = (rng.random((12, 40, 40)) ** 3).astype(np.float32)
    images[0] = 0.5  # no gradient: all-zero cells
    hist = _cell_histograms(images, 9, (8, 8))
    assert_array_equal(hog_descriptors(images, cells_per_block=block), _normalized_blocks(hist, *block))


def test_normalize_columns_equals_its_float64_array_expression_bit_for_bit():
    """The compiled normalization against the array expression it replaces (centre in
    float64, divide by the norm, constant columns to zero), on 60 random shapes."""

    def reference(V):
        X = V.astype(np.float64)
        X -= X.mean(axis=0, keepdims=True)
        norm = np.sqrt(np.einsum("ij,ij->j", X, X))
        constant = norm <= 1e-9 * (np.abs(V).max(axis=0, initial=0.0) * np.sqrt(V.shape[0]))
        X *= np.where(constant, 0.0, 1.0 / np.where(constant, 1.0, norm))
        return X.astype(np.float32)

    rng = np.random.default_rng(22)
    for trial in range(60):
        d, n = int(rng.integers(1, 400)), int(rng.integers(1, 300))
        V = (rng.standard_normal((d, n)) * 10 ** rng.uniform(-3, 3) + rng.uniform(-5, 5)).astype(np.float32)
        V[:, 0] = 1.5  # a constant column
        if trial % 2:
            V = V.astype(np.float64)
        assert_array_equal(normalize_columns(V), reference(V), err_msg=f"trial {trial}")


def test_cell_map_splits_each_axis_into_nearly_equal_runs():
    from smtmvt.features.cells import cell_map

    cells = cell_map(7, 10, 3)  # rows 2 / 2 / 3 (edges 0, 2, 4, 7), columns 3 / 3 / 4
    assert cells.shape == (7, 10)
    assert cells[:, 0].tolist() == [0, 0, 3, 3, 6, 6, 6]
    assert cells[0].tolist() == [0, 0, 0, 1, 1, 1, 2, 2, 2, 2]
    assert np.bincount(cells.ravel()).tolist() == [6, 6, 8, 6, 6, 8, 9, 9, 12]


def test_intensity_template_size_with_a_factor():
    assert intensity_template_size(114, 162, 0.5) == (81, 57)
    assert intensity_template_size(114, 162) == (54, 38)  # the paper's third
    assert intensity_template_size(17, 50, 0.25) == (13, 4)  # at least 4 pixels a side
    with pytest.raises(ValueError, match="factor"):
        intensity_template_size(40, 40, 0.0)
