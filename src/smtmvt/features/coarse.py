"""Coarse view: the gray patch's band-pass at the template's own resolution.

The intensity view reads Tan-Triggs' plane, the frame's difference of
Gaussians of 1 and 2 pixels: fine texture whatever the target's size. Where
two objects share it (the man who crosses Walking2's woman, the players around
Soccer's face) the intensity view cannot tell them apart. This view keeps the
target's layout at a coarser band, set by the target's size instead of the
frame's pixels: the gray patch (the feature size, ``Patches.raw``, already
smoothed by the tracker's anti-aliasing, about one patch pixel), Tan-Triggs'
gamma (``TAN_TRIGGS_GAMMA``, after flooring at ``GAMMA_FLOOR``), minus its
Gaussian blur of ``COARSE_SIGMA`` patch pixels (so that, with the
anti-aliasing's one pixel, the two bands are 1 and 2 patch pixels: Tan-Triggs'
DoG at the template's scale), then averaged over 2x2 pixel blocks (a 32x32
patch gives 256 values; an odd last row or column is dropped).

The blur is scipy's ``gaussian_filter1d`` (``mode="nearest"``, ``truncate=4``)
along each axis, applied with the 2x2 average as two small matrices per patch
size (:func:`coarse_operators`), so the whole view is two matrix products per
axis over all patches: ``L p R^T``.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy.ndimage import gaussian_filter1d

from .tan_triggs import TAN_TRIGGS_GAMMA

__all__ = ["COARSE_SIGMA", "GAMMA_FLOOR", "coarse_operators", "coarse_view"]

#: The blur subtracted from the patch, patch pixels: with the anti-aliasing's one
#: pixel, ``sqrt(1 + 3) = 2`` pixels in all.
COARSE_SIGMA = math.sqrt(3.0)
#: The gray patch is floored here before the gamma (a black pixel gives 0.16).
GAMMA_FLOOR = 1e-4


@lru_cache(maxsize=16)
def coarse_operators(n: int) -> tuple[np.ndarray, np.ndarray]:
    """``(P, Q)``, each ``(n // 2, n)`` float32, for one axis of ``n`` pixels:
    ``P`` averages pixel pairs, ``Q = P B`` averages pairs of the blurred
    axis (``B`` the ``(n, n)`` matrix of ``gaussian_filter1d`` of sigma
    ``COARSE_SIGMA``, ``mode="nearest"``). Read-only arrays (cached)."""
    if n < 2:
        raise ValueError(f"the coarse view needs patches of at least 2 x 2 pixels, got a side of {n}")
    pairs = np.zeros((n // 2, n))
    for i in range(n // 2):
        pairs[i, 2 * i : 2 * i + 2] = 0.5
    blur = gaussian_filter1d(np.eye(n), COARSE_SIGMA, axis=0, mode="nearest")
    P, Q = pairs.astype(np.float32), (pairs @ blur).astype(np.float32)
    P.setflags(write=False)
    Q.setflags(write=False)
    return P, Q


def coarse_view(patches) -> np.ndarray:
    """Coarse band-pass of the gray patches (module docstring).

    Parameters
    ----------
    patches : Patches
        Uses ``patches.raw``, ``(n, fh, fw)`` float32 gray in [0, 1].

    Returns
    -------
    (n, (fh // 2) * (fw // 2)) float32 ndarray, row-major block order.
    """
    x = patches.raw
    if x is None:
        raise ValueError("Patches.raw (the gray plane before Tan-Triggs) was not given")
    n, h, w = x.shape
    # exp(gamma log g): numpy's vectorized float32 exp and log, twice as fast as
    # np.power; in place on the one copy that np.maximum makes
    g = np.maximum(x, np.float32(GAMMA_FLOOR))
    np.log(g, out=g)
    g *= np.float32(TAN_TRIGGS_GAMMA)
    np.exp(g, out=g)
    Ph, Qh = coarse_operators(h)
    Pw, Qw = coarse_operators(w)
    # rows first (one (n h, w) product per operator), then columns
    flat = g.reshape(n * h, w)
    near = (flat @ Pw.T).reshape(n, h, w // 2)
    wide = (flat @ Qw.T).reshape(n, h, w // 2)
    out = np.matmul(Ph, near) - np.matmul(Qh, wide)
    return np.ascontiguousarray(out.reshape(n, -1), dtype=np.float32)
