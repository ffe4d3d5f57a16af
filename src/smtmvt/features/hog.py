"""HOG view: histograms of oriented gradients, batched over patches.

:func:`hog_descriptors` reproduces ``skimage.feature.hog(image,
orientations, pixels_per_cell, cells_per_block, block_norm='L2-Hys',
feature_vector=True)`` (scikit-image 0.2x, single channel, no
``transform_sqrt``) on a whole stack of patches at once:

* gradients by central differences in the patch's float dtype, zero on the
  first and last row (for ``g_row``) and column (for ``g_col``);
* magnitude ``hypot(g_row, g_col)`` in float64 (here ``sqrt(g_row**2 +
  g_col**2)``, within one float64 ulp), orientation ``degrees(arctan2(g_row,
  g_col)) % 180`` in float64 (here bit-identical bins found without atan2
  except at bin edges, see :func:`_fast_bin`); bin ``i`` takes the
  orientations in ``[180 i / O, 180 (i + 1) / O)`` with the bin edges rounded
  to float32 as skimage does; an orientation that rounds to 180 falls in no bin;
* cell histogram = sum of the magnitudes over the cell's pixels divided by the
  cell's pixel count (no interpolation between cells or bins); pixels beyond
  the last full cell are ignored;
* L2-Hys block normalization with ``eps = 1e-5`` over every (overlapping)
  block; output ordered ``(block_row, block_col, cell_row, cell_col, bin)``.

Cell histograms are one compiled (numba) pass over the pixels of all patches
(about 2.5x less CPU time than the vectorized numpy version it replaced: 4 ms
against 11 ms for 400 patches of 32x32 on the 2-core development machine);
block normalization stays in numpy.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = [
    "hog_descriptors",
    "hog_view",
    "hog_dim",
    "orientation_bins",
    "bin_edges",
    "HOG_ORIENTATIONS",
    "HOG_CELL",
    "HOG_BLOCK",
]

HOG_ORIENTATIONS = 9
HOG_CELL = (8, 8)  # pixels per cell (rows, cols)
HOG_BLOCK = (2, 2)  # cells per block (rows, cols)
_EPS = 1e-5  # skimage's block-normalization epsilon


def hog_dim(
    shape: tuple[int, int],
    orientations: int = HOG_ORIENTATIONS,
    pixels_per_cell: tuple[int, int] = HOG_CELL,
    cells_per_block: tuple[int, int] = HOG_BLOCK,
) -> int:
    """Length of the HOG descriptor of a ``(H, W)`` patch (324 for 32x32)."""
    ncr, ncc = shape[0] // pixels_per_cell[0], shape[1] // pixels_per_cell[1]
    nbr, nbc = ncr - cells_per_block[0] + 1, ncc - cells_per_block[1] + 1
    return max(nbr, 0) * max(nbc, 0) * cells_per_block[0] * cells_per_block[1] * orientations


_NEAR_EDGE = 1e-9  # relative distance to a bin edge below which a pixel is binned by atan2


def bin_edges(orientations: int) -> np.ndarray:
    """skimage's bin edges in degrees, ``180 i / O`` rounded to float32, as float64 ``(O + 1,)``."""
    return np.array([np.float32(180.0 / orientations * i) for i in range(orientations + 1)], dtype=np.float64)


def _exact_bins(g_row: np.ndarray, g_col: np.ndarray, orientations: int) -> np.ndarray:
    """skimage's binning, with numpy's own float64 arctan2 (whose last bit can differ
    from the C library's, which compiled code would call).

    Returns bin indices in ``[0, orientations]``; ``orientations`` means no bin
    (an orientation that rounds to exactly 180 degrees).
    """
    orientation = np.arctan2(g_row.astype(np.float64), g_col.astype(np.float64)) * (180 / np.pi) % 180
    return np.searchsorted(bin_edges(orientations), orientation, side="right") - 1


@njit(cache=True, nogil=True)
def _fast_bin(g_row, g_col, cos_e, sin_e):  # pragma: no cover - compiled
    """skimage's bin of one gradient (float64), or -1 where only atan2 can tell.

    The gradient is folded into the upper half-plane (``(g_row, g_col)`` and
    its negation have the same orientation modulo 180 degrees); its bin is
    then the number of interior edges ``e`` it lies beyond, ``g_row cos e -
    g_col sin e >= 0``. ``g_row == 0`` is bin 0 (skimage: ``atan2(+-0, g_col)``
    is 0 or +-180 degrees, and ``% 180`` makes both 0). Elsewhere within a
    relative ``1e-9`` of an edge (0/180 degrees included), the geometric test
    and skimage's rounded float64 angle could disagree: -1 asks the caller
    for :func:`_exact_bins`.
    """
    if g_row == 0.0:
        return 0
    s = 1.0 if g_row > 0 else -1.0
    a = g_row * s
    b = g_col * s
    tol = _NEAR_EDGE * math.sqrt(a * a + b * b)
    if a <= tol:
        return -1
    count = 0
    for i in range(1, cos_e.shape[0] - 1):
        x = a * cos_e[i] - b * sin_e[i]
        if abs(x) <= tol:
            return -1
        count += x >= 0
    return count


@njit(cache=True, nogil=True)
def _bins_kernel(g_row, g_col, cos_e, sin_e, out):  # pragma: no cover - compiled
    for i in range(g_row.shape[0]):
        out[i] = _fast_bin(np.float64(g_row[i]), np.float64(g_col[i]), cos_e, sin_e)
    return out


def _edge_trig(orientations: int):
    rad = bin_edges(orientations) * (np.pi / 180)
    return np.cos(rad), np.sin(rad)


def orientation_bins(g_row: np.ndarray, g_col: np.ndarray, orientations: int) -> np.ndarray:
    """Orientation bin of each gradient, identical to skimage's float64 binning.

    ``g_row``, ``g_col``: arrays of one shape (float32 or float64). Returns intp
    bins in ``[0, orientations]``; ``orientations`` means no bin (an angle that
    rounds to exactly 180 degrees, as in skimage).
    """
    shape = np.shape(g_row)
    g_row = np.ascontiguousarray(g_row).ravel()
    g_col = np.ascontiguousarray(g_col).ravel()
    out = np.empty(g_row.size, dtype=np.intp)
    cos_e, sin_e = _edge_trig(orientations)
    _bins_kernel(g_row, g_col, cos_e, sin_e, out)
    near = np.flatnonzero(out < 0)
    out[near] = _exact_bins(g_row[near], g_col[near], orientations)
    return out.reshape(shape)


@njit(cache=True, nogil=True, boundscheck=False)
def _cells_kernel(images, cell_rows, cell_cols, cos_e, sin_e, out, near):  # pragma: no cover - compiled
    """Add each pixel's gradient magnitude to ``out[patch, cell row, cell col, bin]``.

    The binning of :func:`_fast_bin`, written row by row so that the loops over
    the columns vectorize. Pixels it cannot bin are skipped and listed in
    ``near`` (rows: patch, row, column, g_row, g_col); returns their count.
    """
    n, h, w = images.shape
    H = (h // cell_rows) * cell_rows
    W = (w // cell_cols) * cell_cols
    n_edges = cos_e.shape[0] - 1
    g_row = np.empty(W)
    g_col = np.empty(W)
    a = np.empty(W)
    b = np.empty(W)
    mag = np.empty(W)
    closest = np.empty(W)
    count = np.empty(W, np.int64)
    m = 0
    for k in range(n):
        img = images[k]
        for r in range(H):
            # central differences in the patch dtype, zero on the border (skimage)
            for c in range(W):
                g_row[c] = np.float64(img[r + 1, c] - img[r - 1, c]) if 0 < r < h - 1 else 0.0
                g_col[c] = np.float64(img[r, c + 1] - img[r, c - 1]) if 0 < c < w - 1 else 0.0
            for c in range(W):  # fold into the upper half-plane
                s = 1.0 if g_row[c] >= 0 else -1.0
                a[c] = g_row[c] * s
                b[c] = g_col[c] * s
                mag[c] = math.sqrt(g_row[c] * g_row[c] + g_col[c] * g_col[c])
                closest[c] = a[c]
                count[c] = 0
            for i in range(1, n_edges):
                ce = cos_e[i]
                se = sin_e[i]
                for c in range(W):
                    x = a[c] * ce - b[c] * se
                    count[c] += x >= 0
                    closest[c] = min(closest[c], abs(x))
            rc = r // cell_rows
            for c in range(W):
                if g_row[c] == 0.0:
                    bin_ = 0
                elif closest[c] <= _NEAR_EDGE * mag[c]:
                    near[m, 0] = k
                    near[m, 1] = r
                    near[m, 2] = c
                    near[m, 3] = g_row[c]
                    near[m, 4] = g_col[c]
                    m += 1
                    continue
                else:
                    bin_ = count[c]
                out[k, rc, c // cell_cols, bin_] += mag[c]
    return m


def _cell_histograms(images: np.ndarray, orientations: int, pixels_per_cell: tuple[int, int]) -> np.ndarray:
    """(n, H, W) float -> (n, n_cells_row, n_cells_col, orientations) float64."""
    n, h, w = images.shape
    cr, cc = pixels_per_cell
    hist = np.zeros((n, h // cr, w // cc, orientations))
    near = np.empty((n * (h // cr) * cr * (w // cc) * cc, 5))
    cos_e, sin_e = _edge_trig(orientations)
    m = _cells_kernel(np.ascontiguousarray(images), cr, cc, cos_e, sin_e, hist, near)
    if m:  # the pixels binned by atan2 (rare on real images)
        k, r, c, g_row, g_col = near[:m].T
        bins = _exact_bins(g_row, g_col, orientations)
        keep = bins < orientations  # an angle rounded to 180 falls in no bin (skimage)
        idx = (k[keep].astype(np.intp), r[keep].astype(np.intp) // cr, c[keep].astype(np.intp) // cc, bins[keep])
        np.add.at(hist, idx, np.sqrt(g_row[keep] ** 2 + g_col[keep] ** 2))
    return hist / (cr * cc)


def hog_descriptors(
    images: np.ndarray,
    orientations: int = HOG_ORIENTATIONS,
    pixels_per_cell: tuple[int, int] = HOG_CELL,
    cells_per_block: tuple[int, int] = HOG_BLOCK,
) -> np.ndarray:
    """HOG descriptors (L2-Hys) of a stack of gray patches.

    Parameters
    ----------
    images : (n, H, W) float ndarray
        Gray patches (any real scale; float32 is what the tracker passes).
    orientations : int
        Orientation bins over [0, 180) degrees.
    pixels_per_cell : (int, int)
        Cell size in pixels (rows, cols).
    cells_per_block : (int, int)
        Block size in cells (rows, cols).

    Returns
    -------
    (n, d) float32 ndarray with ``d = hog_dim((H, W), ...)``, each row equal to
    ``skimage.feature.hog(images[i], ..., block_norm='L2-Hys',
    feature_vector=True)`` up to float rounding (skimage accumulates cells in
    float32).
    """
    images = np.asarray(images)
    if images.ndim != 3:
        raise ValueError(f"expected (n, H, W) patches, got shape {images.shape}")
    if images.dtype == np.float16:
        images = images.astype(np.float32)  # skimage computes float16 input in float32
    elif images.dtype not in (np.float32, np.float64):
        images = images.astype(np.float64)
    n, h, w = images.shape
    br, bc = cells_per_block
    ncr, ncc = h // pixels_per_cell[0], w // pixels_per_cell[1]
    nbr, nbc = ncr - br + 1, ncc - bc + 1
    if nbr <= 0 or nbc <= 0:
        raise ValueError(
            f"patches of {h}x{w} px are too small for HOG with {pixels_per_cell} px cells "
            f"and {cells_per_block} cell blocks; need at least "
            f"{br * pixels_per_cell[0]}x{bc * pixels_per_cell[1]} px"
        )
    hist = _cell_histograms(images, orientations, pixels_per_cell)
    if br * bc * orientations > 128:  # beyond _pairwise_sum's one level: numpy's expression
        return _normalized_blocks(hist, br, bc)
    out = np.empty((n, nbr, nbc, br * bc * orientations), dtype=np.float32)
    _blocks_kernel(np.ascontiguousarray(hist), br, bc, _EPS**2, out)
    return out.reshape(n, -1)


def _normalized_blocks(hist: np.ndarray, br: int, bc: int) -> np.ndarray:
    """L2-Hys blocks of ``hist (n, ncr, ncc, o)`` as numpy array expressions, ``(n, d)`` float32."""
    n, ncr, ncc, orientations = hist.shape
    nbr, nbc = ncr - br + 1, ncc - bc + 1
    # blocks[:, r, c, i, j, :] = hist[:, r + i, c + j, :]
    blocks = np.empty((n, nbr, nbc, br, bc, orientations), dtype=np.float64)
    for i in range(br):
        for j in range(bc):
            blocks[:, :, :, i, j, :] = hist[:, i : i + nbr, j : j + nbc, :]
    blocks = blocks.reshape(n, nbr, nbc, -1)
    norm = np.sqrt(np.sum(blocks**2, axis=-1, keepdims=True) + _EPS**2)
    blocks = np.minimum(blocks / norm, 0.2)
    norm = np.sqrt(np.sum(blocks**2, axis=-1, keepdims=True) + _EPS**2)
    blocks = blocks / norm
    return blocks.reshape(n, -1).astype(np.float32)


@njit(cache=True, nogil=True, boundscheck=False)
def _pairwise_sum(a, m):  # pragma: no cover - compiled
    """``sum(a[:m])`` in numpy's summation order for ``m <= 128`` (8 running sums, then
    the tail), so that the result equals ``np.sum`` bit for bit."""
    if m < 8:
        res = 0.0
        for i in range(m):
            res += a[i]
        return res
    r0, r1, r2, r3, r4, r5, r6, r7 = a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7]
    i = 8
    while i < m - (m % 8):
        r0 += a[i]
        r1 += a[i + 1]
        r2 += a[i + 2]
        r3 += a[i + 3]
        r4 += a[i + 4]
        r5 += a[i + 5]
        r6 += a[i + 6]
        r7 += a[i + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < m:
        res += a[i]
        i += 1
    return 0.0 + res


@njit(cache=True, nogil=True, boundscheck=False)
def _blocks_kernel(hist, br, bc, eps2, out):  # pragma: no cover - compiled
    """L2-Hys of every block of ``br x bc`` cells of ``hist (n, ncr, ncc, o)`` into
    ``out (n, nbr, nbc, br * bc * o)`` float32, block values ordered (cell row, cell
    col, orientation): ``v / sqrt(|v|^2 + eps2)``, clipped at 0.2, normalized again.
    The squared norms are summed in numpy's order (:func:`_pairwise_sum`, a block
    has at most 128 values at the defaults' 36), so the result equals the
    array expression of skimage's ``_hog_normalize_block`` bit for bit."""
    n, ncr, ncc, o = hist.shape
    nbr, nbc, m = out.shape[1], out.shape[2], out.shape[3]
    v = np.empty(m)
    sq = np.empty(m)
    for k in range(n):
        for r in range(nbr):
            for c in range(nbc):
                t = 0
                for i in range(br):
                    for j in range(bc):
                        for b in range(o):
                            v[t] = hist[k, r + i, c + j, b]
                            t += 1
                for t in range(m):
                    sq[t] = v[t] * v[t]
                norm = math.sqrt(_pairwise_sum(sq, m) + eps2)
                for t in range(m):
                    v[t] = min(v[t] / norm, 0.2)
                    sq[t] = v[t] * v[t]
                norm = math.sqrt(_pairwise_sum(sq, m) + eps2)
                for t in range(m):
                    out[k, r, c, t] = np.float32(v[t] / norm)
    return out


def hog_view(patches, plane: str = "tan_triggs") -> np.ndarray:
    """HOG view on the Tan-Triggs gray patches (or the raw gray ones).

    Parameters
    ----------
    patches : Patches
        Uses ``patches.plane(plane)``, ``(n, fh, fw)`` float32.
    plane : ``"tan_triggs"`` (``patches.gray``, the paper) or ``"gray"`` (``patches.raw``).

    Returns
    -------
    (n, d) float32 ndarray; 9 orientations, 8x8 px cells, 2x2 cell blocks,
    L2-Hys: ``d = 324`` for the default 32x32 feature size.
    """
    return hog_descriptors(patches.plane(plane), HOG_ORIENTATIONS, HOG_CELL, HOG_BLOCK)
