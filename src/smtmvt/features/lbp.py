"""LBP view: uniform rotation-invariant local binary patterns, per-cell histograms.

:func:`lbp_codes` reproduces ``skimage.feature.local_binary_pattern(image, P,
R, method='uniform')`` exactly, batched over a stack of patches:

* neighbour ``i`` of pixel ``(r, c)`` sits at ``(r + rp[i], c + cp[i])`` with
  ``rp = round(-R sin(2 pi i / P), 5)`` and ``cp = round(R cos(2 pi i / P), 5)``;
* its value is skimage's bilinear interpolation in float64, evaluated with the
  same operations in the same order (``top = (1 - dc) a + dc b``,
  ``bottom = (1 - dc) c + dc d``, ``(1 - dr) top + dr bottom``, where
  ``dr = (r + rp) - floor(r + rp)`` depends on ``r`` in its last bits), with
  pixels outside the patch read as 0 (skimage's constant mode, cval 0);
* bit ``i`` is ``value_i - centre >= 0``;
* the code is the number of set bits when the bit string has at most two
  0/1 transitions counted over the ``P - 1`` adjacent pairs (skimage does not
  count the wrap-around pair), else ``P + 1``. Codes lie in ``[0, P + 1]``.

Integer neighbour offsets need no interpolation (the formula returns the pixel
itself exactly), so for P = 8, R = 1 only the four diagonal neighbours are
interpolated.

:func:`lbp_histograms` then counts the codes over a ``grid x grid`` layout of
cells. The view uses a 4x4 grid: on the default 32x32 feature patch that is
8x8-pixel cells, the same cells as the HOG view, so the LBP view keeps the
target's coarse spatial layout (a single global histogram would not tell a
face from the same textures rearranged); 64 pixels per cell still fill a
10-bin histogram reasonably. Each cell's histogram is divided by the cell's
pixel count (fractions summing to 1 per cell).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .cells import cell_map
from .color import histogram_power

__all__ = ["lbp_codes", "lbp_histograms", "lbp_view", "LBP_P", "LBP_R", "LBP_GRID"]

LBP_P = 8
LBP_R = 1.0
LBP_GRID = 4  # cells per side


@njit(cache=True, nogil=True, boundscheck=False)
def _lbp_kernel(images, rp, cp, pad, out):  # pragma: no cover - compiled (tested through lbp_codes)
    """Uniform LBP codes of ``images (n, h, w)`` into ``out (n, h, w) uint8``.

    Row by row, so that every inner loop runs over the columns and vectorizes:
    the patch is copied into a zero-padded float64 buffer (skimage's constant
    mode, cval 0); neighbour ``i`` is interpolated for the whole row, then the
    bits, their count and the 0/1 transitions are accumulated per column.
    """
    n, h, w = images.shape
    P = rp.shape[0]
    buf = np.zeros((h + 2 * pad, w + 2 * pad))
    value = np.empty((P, w))
    ones = np.empty(w, np.int64)
    changes = np.empty(w, np.int64)
    prev = np.empty(w, np.int64)
    # Integer parts of the column offsets, and the interpolation weight of each
    # column as skimage computes it: (c + cp) - floor(c + cp), exact per column.
    # (floor(c + cp) == c + floor(cp): cp has 5 decimals, so c + cp never rounds
    # across an integer.)
    c_lo = np.empty(P, np.int64)
    c_hi = np.empty(P, np.int64)
    dcs = np.empty((P, w))
    for i in range(P):
        c_lo[i] = int(math.floor(cp[i])) + pad
        c_hi[i] = int(math.ceil(cp[i])) + pad
        for c in range(w):
            x = c + cp[i]
            dcs[i, c] = x - math.floor(x)
    # The loops read and write 1-d row slices (contiguous, with their offsets
    # taken once per row): about twice as fast as the same arithmetic indexed
    # in 2-d, which the compiler does not vectorize as well.
    for k in range(n):
        img = images[k]
        for r in range(h):
            brow = buf[r + pad]
            irow = img[r]
            for c in range(w):
                brow[c + pad] = irow[c]
        for r in range(h):
            centre = buf[r + pad][pad : pad + w]
            for i in range(P):
                y = r + rp[i]
                dr = y - math.floor(y)
                lo_row = buf[int(math.floor(y)) + pad]
                hi_row = buf[int(math.ceil(y)) + pad]
                a_lo = lo_row[c_lo[i] : c_lo[i] + w]
                a_hi = lo_row[c_hi[i] : c_hi[i] + w]
                b_lo = hi_row[c_lo[i] : c_lo[i] + w]
                b_hi = hi_row[c_hi[i] : c_hi[i] + w]
                v = value[i]
                dci = dcs[i]
                if dr == 0.0 and c_lo[i] == c_hi[i]:
                    # integer offset: skimage's formula returns the pixel exactly
                    for c in range(w):
                        v[c] = a_lo[c]
                else:
                    for c in range(w):
                        dc = dci[c]
                        top = (1 - dc) * a_lo[c] + dc * a_hi[c]
                        bottom = (1 - dc) * b_lo[c] + dc * b_hi[c]
                        v[c] = (1 - dr) * top + dr * bottom
            v0 = value[0]
            for c in range(w):
                bit = 1 if v0[c] >= centre[c] else 0
                ones[c] = bit
                prev[c] = bit
                changes[c] = 0
            for i in range(1, P):
                vi = value[i]
                for c in range(w):
                    bit = 1 if vi[c] >= centre[c] else 0
                    ones[c] += bit
                    changes[c] += bit ^ prev[c]
                    prev[c] = bit
            orow = out[k, r]
            for c in range(w):
                orow[c] = ones[c] if changes[c] <= 2 else P + 1
    return out


def lbp_codes(images: np.ndarray, P: int = LBP_P, R: float = LBP_R) -> np.ndarray:
    """Uniform LBP codes of a stack of gray patches (skimage's ``'uniform'``).

    Parameters
    ----------
    images : (n, H, W) real ndarray
        Gray patches, finite values; compared in float64 like skimage.
    P : int
        Number of circular neighbours (1 <= P <= 32).
    R : float
        Radius in pixels (> 0).

    Returns
    -------
    (n, H, W) uint8 ndarray with codes in ``[0, P + 1]``, equal to
    ``skimage.feature.local_binary_pattern(images[i], P, R, 'uniform')``.

    Notes
    -----
    A compiled (numba) loop, about 3x faster than the vectorized numpy version
    it replaced (400 patches of 32x32: 6 ms against 17 ms of CPU time on the
    2-core development machine), and written on row slices since stop 21
    (60 patches: 0.68 against 1.22 ms, the same codes). The bilinear interpolation is evaluated with
    skimage's operations in skimage's order, in float64, so the values are
    bit-identical; ``value - centre >= 0`` is evaluated as ``value >= centre``,
    the same test for finite doubles (with gradual underflow, ``a - b == 0``
    only when ``a == b``).
    """
    images = np.asarray(images)
    if images.ndim != 3:
        raise ValueError(f"expected (n, H, W) patches, got shape {images.shape}")
    P = int(P)
    if not 1 <= P <= 32 or not R > 0:
        raise ValueError(f"need 1 <= P <= 32 and R > 0, got P={P}, R={R}")
    angles = 2 * np.pi * np.arange(P, dtype=np.double) / P
    rp = np.round(-R * np.sin(angles), 5)
    cp = np.round(R * np.cos(angles), 5)
    pad = int(np.ceil(R))  # |offsets| <= R, so floor/ceil of r + offset stay within the pad
    out = np.empty(images.shape, dtype=np.uint8)
    if images.size == 0:
        return out
    if images.dtype not in (np.float32, np.float64):
        images = images.astype(np.float64)
    return _lbp_kernel(np.ascontiguousarray(images), rp, cp, pad, out)


def lbp_histograms(codes: np.ndarray, n_codes: int, grid: int = LBP_GRID) -> np.ndarray:
    """Per-cell code histograms over a ``grid x grid`` layout of cells.

    Parameters
    ----------
    codes : (n, H, W) integer ndarray
        Codes in ``[0, n_codes)``.
    n_codes : int
        Number of distinct codes (``P + 2`` for uniform LBP).
    grid : int
        Cells per side; cell ``j`` along an axis of length L covers pixels
        ``[j L // grid, (j + 1) L // grid)`` (equal cells when ``grid`` divides L).

    Returns
    -------
    (n, grid * grid * n_codes) float32 ndarray ordered ``(cell_row, cell_col,
    code)``; each cell's histogram is divided by its pixel count (sums to 1).
    """
    codes = np.asarray(codes)
    if codes.ndim != 3:
        raise ValueError(f"expected (n, H, W) codes, got shape {codes.shape}")
    n, h, w = codes.shape
    grid = int(grid)
    if not 1 <= grid <= min(h, w):
        raise ValueError(f"grid must be in [1, {min(h, w)}] for {h}x{w} patches, got {grid}")
    cell = cell_map(h, w, grid)
    idx = (np.arange(n)[:, None, None] * (grid * grid) + cell) * n_codes + codes
    code_counts = np.bincount(idx.ravel(), minlength=n * grid * grid * n_codes)
    pixels = np.bincount(cell.ravel(), minlength=grid * grid)  # pixels per cell
    hist = code_counts.reshape(n, grid * grid, n_codes) / pixels[:, None]
    return hist.reshape(n, -1).astype(np.float32)


def lbp_view(patches, radius: float = LBP_R, plane: str = "tan_triggs", power: float = 1.0) -> np.ndarray:
    """LBP view on the Tan-Triggs gray patches (or the raw gray ones).

    Parameters
    ----------
    patches : Patches
        Uses ``patches.plane(plane)``, ``(n, fh, fw)`` float32.
    radius : float
        Radius of the 8 neighbours, pixels of the feature patch (default 1).
    plane : ``"tan_triggs"`` (``patches.gray``, the paper) or ``"gray"`` (``patches.raw``).
    power : float > 0
        Histogram values raised to this power (see :func:`smtmvt.features.color.histogram_power`).

    Returns
    -------
    (n, 4 * 4 * 10) = (n, 160) float32 ndarray: uniform LBP (P = 8, codes
    0..9) histograms over a 4x4 grid of cells.
    """
    codes = lbp_codes(patches.plane(plane), LBP_P, radius)
    return histogram_power(lbp_histograms(codes, LBP_P + 2, LBP_GRID), power)
