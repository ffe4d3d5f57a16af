"""Batched candidate extraction: warp every particle's region to a patch.

All ``n`` candidates are sampled in one call of ``cv2.remap`` (bilinear): the
sampling grids of the ``n`` particles are stacked into one ``(n * ph, pw)`` map.
Pixels of a candidate that fall outside the image take the value of the
nearest border pixel (``BORDER_REPLICATE``), so a candidate partly outside the
frame is still a valid patch; :func:`inside_fraction` tells how much of it is
real.
"""

from __future__ import annotations

import cv2
import numpy as np
from numba import njit

from .geometry import REF

__all__ = ["sampling_grid", "remap_patches", "warp_patches", "inside_fraction"]


@njit(cache=True, nogil=True)
def _grid_kernel(params, u, v, scale, ox, oy, X, Y):  # pragma: no cover - compiled (tested through sampling_grid)
    half = np.float32(0.5)
    shifted = ox != np.float32(0.0) or oy != np.float32(0.0)
    for k in range(params.shape[0]):
        a11, a12, a21, a22, tx, ty = params[k]
        for i in range(v.shape[0]):
            for j in range(u.shape[0]):
                # float64, in the order numpy's broadcast expression used, then rounded to float32
                x = np.float32(a11 * u[j] + a12 * v[i] + tx)
                y = np.float32(a21 * u[j] + a22 * v[i] + ty)
                if scale != np.float32(1.0):  # float32, as the array expression (X + 0.5) * s - 0.5
                    x = (x + half) * scale - half
                    y = (y + half) * scale - half
                if shifted:  # float32, on a crop of the plane
                    x = x - ox
                    y = y - oy
                X[k, i, j] = x
                Y[k, i, j] = y
    return X, Y


def sampling_grid(params, size, plane_scale: float = 1.0, origin=(0.0, 0.0)) -> tuple[np.ndarray, np.ndarray]:
    """Image coordinates sampled for each particle.

    Patch pixel ``(i, j)`` (row, column) of a ``(ph, pw)`` patch sits at template
    coordinates ``u = ((j + 0.5) / pw - 0.5) * REF``, ``v = ((i + 0.5) / ph - 0.5) * REF``,
    so the patch covers the whole target whatever its size.

    Parameters
    ----------
    params : (n, 6) affine states (see :mod:`smtmvt.geometry`).
    size : (ph, pw) patch size in pixels.
    plane_scale : the coordinates on the image resized by this factor (pixel
        edges to pixel edges): ``(x + 0.5) s - 0.5``, in float32 after the
        rounding of ``x``.
    origin : (x, y), the coordinates returned are relative to this point of
        the plane (a crop of it whose pixel (0, 0) sits there: see
        :class:`smtmvt.preprocess.PreparedFrame`), subtracted in float32.

    Returns
    -------
    X, Y : (n, ph, pw) float32 image coordinates (0-based pixel centres),
    computed in float64 and rounded once (a compiled loop: no float64
    temporaries of the whole grid).
    """
    p = np.ascontiguousarray(np.atleast_2d(np.asarray(params, dtype=np.float64)))
    ph, pw = int(size[0]), int(size[1])
    u = ((np.arange(pw) + 0.5) / pw - 0.5) * REF
    v = ((np.arange(ph) + 0.5) / ph - 0.5) * REF
    X = np.empty((len(p), ph, pw), dtype=np.float32)
    Y = np.empty((len(p), ph, pw), dtype=np.float32)
    ox, oy = (np.float32(o) for o in origin)
    return _grid_kernel(p, u, v, np.float32(plane_scale), ox, oy, X, Y)


def remap_patches(image: np.ndarray, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """Bilinear samples of ``image`` at the grid ``X, Y (n, ph, pw)`` of :func:`sampling_grid`.

    Parameters
    ----------
    image : (H, W) or (H, W, C) float32 image, C <= 4.

    Returns
    -------
    (n, ph, pw) or (n, ph, pw, C) float32 patches. Pixels outside the image
    take the value of the nearest border pixel.
    """
    img = np.ascontiguousarray(image, dtype=np.float32)
    n, ph, pw = X.shape
    # cv2.remap limits map dimensions to < 32767: split very large batches.
    rows_per_chunk = max(1, 32000 // ph)
    chunks = []
    for s in range(0, n, rows_per_chunk):
        mx = X[s : s + rows_per_chunk].reshape(-1, pw)
        my = Y[s : s + rows_per_chunk].reshape(-1, pw)
        chunks.append(cv2.remap(img, mx, my, interpolation=cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE))
    out = chunks[0] if len(chunks) == 1 else np.concatenate(chunks, axis=0)
    return out.reshape((n, ph, pw) + img.shape[2:])


def warp_patches(image: np.ndarray, params, size) -> np.ndarray:
    """Warp all candidates of ``image`` to ``size`` in one bilinear remap.

    Parameters
    ----------
    image : (H, W) or (H, W, C) float32 image.
    params : (n, 6) affine states.
    size : (ph, pw) patch size in pixels.

    Returns
    -------
    (n, ph, pw) or (n, ph, pw, C) float32 patches.
    """
    X, Y = sampling_grid(params, size)
    return remap_patches(image, X, Y)


def inside_fraction(params, image_shape, size=(8, 8)) -> np.ndarray:
    """Fraction of each candidate's sample points that fall inside the image, ``(n,)``."""
    X, Y = sampling_grid(params, size)
    H, W = image_shape[:2]
    inside = (X >= -0.5) & (X <= W - 0.5) & (Y >= -0.5) & (Y <= H - 0.5)
    return inside.reshape(len(X), -1).mean(axis=1)
