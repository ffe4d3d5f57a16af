"""Boxes <-> affine states, and batched warping checked against cv2.warpAffine."""

import cv2
import numpy as np
import pytest

from smtmvt.geometry import REF, affine_scale, affine_to_box, box_scaled, box_to_affine, box_with_aspect
from smtmvt.warp import inside_fraction, sampling_grid, warp_patches


def test_box_affine_roundtrip():
    rng = np.random.default_rng(0)
    boxes = np.column_stack(
        [rng.uniform(-20, 300, 50), rng.uniform(-20, 200, 50), rng.uniform(2, 150, 50), rng.uniform(2, 150, 50)]
    )
    np.testing.assert_allclose(affine_to_box(box_to_affine(boxes)), boxes, atol=1e-12)
    np.testing.assert_allclose(affine_to_box(box_to_affine(boxes[0])), boxes[0], atol=1e-12)


def _centre(b):
    """Centres ``(m, 2)`` of 0-based boxes ``(m, 4)``, OTB's ``x + (w - 1) / 2``."""
    return np.column_stack([b[:, 0] + (b[:, 2] - 1) / 2, b[:, 1] + (b[:, 3] - 1) / 2])


def test_box_with_aspect_keeps_centre_and_area_and_moves_the_log_aspect():
    boxes = np.array([[10.0, 20.0, 30.0, 60.0], [-5.0, 3.0, 12.5, 4.0]])
    for fraction in (0.0, 0.25, 1.0):
        out = box_with_aspect(boxes, 1.5, fraction)
        np.testing.assert_allclose(_centre(out), _centre(boxes), atol=1e-12)
        np.testing.assert_allclose(out[:, 2] * out[:, 3], boxes[:, 2] * boxes[:, 3], rtol=1e-12)
        want = (1 - fraction) * np.log(boxes[:, 3] / boxes[:, 2]) + fraction * np.log(1.5)
        np.testing.assert_allclose(np.log(out[:, 3] / out[:, 2]), want, atol=1e-12)
    np.testing.assert_array_equal(box_with_aspect(boxes, 1.5, 0.0), boxes)
    np.testing.assert_allclose(box_with_aspect(boxes[0], 0.5), [-5.0, 35.0, 60.0, 30.0], atol=1e-12)  # 30x60 -> 60x30
    with pytest.raises(ValueError, match="fraction"):
        box_with_aspect(boxes, 1.5, 1.5)
    with pytest.raises(ValueError, match="aspect"):
        box_with_aspect(boxes, 0.0)


def test_box_scaled_keeps_centre_and_scales_sides():
    boxes = np.array([[10.0, 20.0, 30.0, 60.0], [-5.0, 3.0, 12.5, 4.0]])
    for factor in (0.5, 1.0, 1.07):
        out = box_scaled(boxes, factor)
        np.testing.assert_allclose(_centre(out), _centre(boxes), atol=1e-12)
        np.testing.assert_allclose(out[:, 2:], factor * boxes[:, 2:], rtol=1e-12)
    np.testing.assert_allclose(box_scaled(boxes[0], 2.0), [-5.0, -10.0, 60.0, 120.0], atol=1e-12)
    np.testing.assert_array_equal(boxes[0], [10.0, 20.0, 30.0, 60.0])  # the input is not changed
    with pytest.raises(ValueError, match="factor"):
        box_scaled(boxes, 0.0)


def test_affine_of_box_centre_and_scale():
    p = box_to_affine((10, 20, 64, 32))
    # OTB centre convention x + (w - 1) / 2, in 0-based pixel centres.
    assert p[4] == pytest.approx(10 + 63 / 2)
    assert p[5] == pytest.approx(20 + 31 / 2)
    assert p[0] == pytest.approx(64 / REF) and p[3] == pytest.approx(32 / REF)
    assert affine_scale(p)[0] == pytest.approx(np.sqrt((4 + 1) / 2))


def test_patch_at_box_size_samples_the_box_pixels_exactly():
    img = np.arange(60 * 80, dtype=np.float32).reshape(60, 80)
    box = (7, 11, 20, 13)
    patch = warp_patches(img, box_to_affine(box)[None], (13, 20))[0]
    np.testing.assert_allclose(patch, img[11:24, 7:27], atol=1e-3)


def _warp_affine_reference(img, p, size):
    """cv2.warpAffine with the same map: dst(i, j) = src(M @ [j, i, 1])."""
    ph, pw = size
    a11, a12, a21, a22, tx, ty = p
    su, sv = REF / pw, REF / ph
    # u = (j + 0.5) * su - REF/2, v = (i + 0.5) * sv - REF/2
    M = np.array(
        [
            [a11 * su, a12 * sv, a11 * (0.5 * su - REF / 2) + a12 * (0.5 * sv - REF / 2) + tx],
            [a21 * su, a22 * sv, a21 * (0.5 * su - REF / 2) + a22 * (0.5 * sv - REF / 2) + ty],
        ]
    )
    return cv2.warpAffine(
        img, M, (pw, ph), flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP, borderMode=cv2.BORDER_REPLICATE
    )


@pytest.mark.parametrize("channels", [None, 3])
def test_warp_matches_cv2_warpaffine(channels):
    from skimage import data

    img = data.astronaut().astype(np.float32) / 255.0
    if channels is None:
        img = cv2.cvtColor(img, cv2.COLOR_RGB2GRAY)
    rng = np.random.default_rng(1)
    base = box_to_affine((200, 180, 60, 90))
    params = np.repeat(base[None], 40, axis=0)
    params[:, :4] *= rng.uniform(0.8, 1.2, (40, 4))
    params[:, 1] += rng.normal(0, 0.3, 40)  # rotation / shear
    params[:, 2] += rng.normal(0, 0.3, 40)
    params[:, 4:] += rng.normal(0, 30, (40, 2))
    params[0, 4:] = (-10, -15)  # mostly outside: replicated border
    size = (24, 17)
    got = warp_patches(img, params, size)
    assert got.shape == (40,) + size + (() if channels is None else (3,))
    for k in range(40):
        ref = _warp_affine_reference(img, params[k], size)
        # OpenCV interpolates with 1/32-pixel fixed-point weights: tolerance in intensity units.
        np.testing.assert_allclose(got[k], ref, atol=2e-3)


def test_sampling_grid_and_inside_fraction():
    p = box_to_affine(np.array([[0, 0, 10, 10], [-100, -100, 10, 10], [-5, 0, 10, 10]]))
    X, Y = sampling_grid(p, (10, 10))
    np.testing.assert_allclose(X[0, 0], np.arange(10), atol=1e-5)
    f = inside_fraction(p, (50, 50), size=(10, 10))
    assert f[0] == 1.0 and f[1] == 0.0 and f[2] == pytest.approx(0.5)


def test_large_batch_split_into_remap_chunks():
    """Above 32000 patch rows cv2.remap is called chunk by chunk (its maps must stay
    below 32767 rows): every chunk must warp its own particles, the last one partial."""
    from skimage import data

    img = cv2.cvtColor(data.astronaut().astype(np.float32) / 255.0, cv2.COLOR_RGB2GRAY)
    rng = np.random.default_rng(4)
    n, size = 1100, (64, 6)  # 500 particles per chunk: chunks of 500, 500 and 100
    assert n * size[0] > 2 * 32000
    params = np.repeat(box_to_affine((200, 180, 60, 90))[None], n, axis=0)
    params[:, :4] *= rng.uniform(0.7, 1.3, (n, 4))
    params[:, 4:] += rng.normal(0, 80, (n, 2))
    got = warp_patches(img, params, size)
    assert got.shape == (n,) + size
    for k in range(n):
        np.testing.assert_allclose(got[k], _warp_affine_reference(img, params[k], size), atol=2e-3)


@pytest.mark.parametrize("channels", [(), (3,)])
def test_inside_fraction_edges_are_inclusive_on_all_four_sides(channels):
    """Pixel centres are 0..W-1, so the image spans [-0.5, W - 0.5] x [-0.5, H - 0.5]: a
    sample point exactly on an edge is inside, a quarter pixel beyond it is not. A 10x10
    box at size (10, 10) samples the points x + 0..9, y + 0..9. The image is not square,
    so W and H cannot be swapped."""
    shape = (40, 60) + channels  # H = 40, W = 60
    boxes = np.array(
        [
            [-0.5, 5, 10, 10],  # first column on the left edge
            [50.5, 5, 10, 10],  # last column on the right edge, x = W - 0.5
            [5, -0.5, 10, 10],  # top edge
            [5, 30.5, 10, 10],  # last row on the bottom edge, y = H - 0.5
            [-0.75, 5, 10, 10],  # one column a quarter pixel beyond each edge
            [50.75, 5, 10, 10],
            [5, -0.75, 10, 10],
            [5, 30.75, 10, 10],
            [45.5, 25.5, 10, 10],  # inside, 5 px from the right and bottom edges
            [55.5, 35.5, 10, 10],  # 5 columns x 5 rows inside
        ]
    )
    f = inside_fraction(box_to_affine(boxes), shape, size=(10, 10))
    np.testing.assert_allclose(f, [1, 1, 1, 1, 0.9, 0.9, 0.9, 0.9, 1, 0.25], rtol=0, atol=1e-12)


def test_any_image_dtype_gives_float32_patches():
    """warp_patches converts the image to float32 first: a uint8 or float64 image gives
    the patches of its float32 copy, as float32."""
    rng = np.random.default_rng(6)
    img8 = rng.integers(0, 256, (50, 70), dtype=np.uint8)
    params = box_to_affine(np.array([[10.3, 12.7, 20, 15], [30, 5, 25, 30]]))
    ref = warp_patches(img8.astype(np.float32), params, (9, 11))
    for img in (img8, img8.astype(np.float64)):
        got = warp_patches(img, params, (9, 11))
        assert got.dtype == np.float32
        np.testing.assert_array_equal(got, ref)


@pytest.mark.parametrize("scale", [0.25, 0.7, 1.3, 3.9])
def test_sampling_grid_on_a_resized_plane_is_the_float32_expression(scale):
    """``plane_scale`` maps the grid as ``(X + 0.5) s - 0.5`` in float32, bit for bit."""
    rng = np.random.default_rng(8)
    params = np.tile([1.2, 0.1, -0.05, 0.9, 150.0, 60.0], (50, 1)) + rng.normal(0, 0.5, (50, 6))
    X, Y = sampling_grid(params, (25, 9))
    half, s = np.float32(0.5), np.float32(scale)
    Xs, Ys = sampling_grid(params, (25, 9), scale)
    np.testing.assert_array_equal(Xs, (X + half) * s - half)
    np.testing.assert_array_equal(Ys, (Y + half) * s - half)
    assert Xs.dtype == np.float32
