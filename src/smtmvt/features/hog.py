"""HOG view: histograms of oriented gradients, batched over patches.

:func:`hog_descriptors` reproduces ``skimage.feature.hog(image,
orientations, pixels_per_cell, cells_per_block, block_norm='L2-Hys',
feature_vector=True)`` (scikit-image 0.2x, single channel, no
``transform_sqrt``) on a whole stack of patches at once:

* gradients by central differences in the patch's float dtype, zero on the
  first and last row (for ``g_row``) and column (for ``g_col``);
* magnitude ``hypot(g_row, g_col)`` (here ``sqrt(g_row**2 + g_col**2)`` in
  the patch dtype, within one float32 ulp of skimage's float64 ``hypot``),
  orientation ``degrees(arctan2(g_row, g_col)) % 180`` in float64 (here
  bit-identical bins from a float32 shortcut, see :func:`_orientation_bins`); bin ``i`` takes the
  orientations in ``[180 i / O, 180 (i + 1) / O)`` with the bin edges rounded
  to float32 as skimage does; an orientation that rounds to 180 falls in no bin;
* cell histogram = sum of the magnitudes over the cell's pixels divided by the
  cell's pixel count (no interpolation between cells or bins); pixels beyond
  the last full cell are ignored;
* L2-Hys block normalization with ``eps = 1e-5`` over every (overlapping)
  block; output ordered ``(block_row, block_col, cell_row, cell_col, bin)``.

Cell histograms are computed for ``BLOCK`` patches at a time (vectorized
within the block), which keeps the work buffers in cache and is about 1.4x
faster than a single pass over 400 patches.
"""

from __future__ import annotations

import numpy as np

__all__ = ["hog_descriptors", "hog_view", "hog_dim",
           "HOG_ORIENTATIONS", "HOG_CELL", "HOG_BLOCK"]

HOG_ORIENTATIONS = 9
HOG_CELL = (8, 8)   # pixels per cell (rows, cols)
HOG_BLOCK = (2, 2)  # cells per block (rows, cols)
_EPS = 1e-5         # skimage's block-normalization epsilon
BLOCK = 64          # patches per vectorized pass (cache-sized work buffers)


def hog_dim(shape: tuple[int, int], orientations: int = HOG_ORIENTATIONS,
            pixels_per_cell: tuple[int, int] = HOG_CELL,
            cells_per_block: tuple[int, int] = HOG_BLOCK) -> int:
    """Length of the HOG descriptor of a ``(H, W)`` patch (324 for 32x32)."""
    ncr, ncc = shape[0] // pixels_per_cell[0], shape[1] // pixels_per_cell[1]
    nbr, nbc = ncr - cells_per_block[0] + 1, ncc - cells_per_block[1] + 1
    return max(nbr, 0) * max(nbc, 0) * cells_per_block[0] * cells_per_block[1] * orientations


_NEAR_EDGE = 1e-3  # degrees; a float32 orientation this close to a bin edge is redone in float64


def _exact_bins(g_row: np.ndarray, g_col: np.ndarray, orientations: int) -> np.ndarray:
    """skimage's binning, verbatim: float64 orientation, float32-rounded edges.

    Returns bin indices in ``[0, orientations]``; ``orientations`` means no bin
    (an orientation that rounds to exactly 180 degrees).
    """
    orientation = np.arctan2(g_row.astype(np.float64), g_col.astype(np.float64)) * (180 / np.pi) % 180
    edges = np.array([np.float32(180.0 / orientations * i) for i in range(orientations + 1)],
                     dtype=np.float64)
    return np.searchsorted(edges, orientation, side="right") - 1


def _orientation_bins(g_row: np.ndarray, g_col: np.ndarray, orientations: int) -> np.ndarray:
    """Orientation bin of every pixel, identical to skimage's float64 binning.

    The bins are found from a float32 ``arctan2`` (3x faster than float64);
    the float32 bin position is within 1e-5 bins (2e-4 degrees) of the exact
    one, so only pixels within ``_NEAR_EDGE`` degrees of a bin edge can differ
    from skimage's binning, and those (about 1e-4 of them) are recomputed with
    :func:`_exact_bins`. Returns ``(...)`` intp in ``[0, orientations]``.
    """
    per_bin = np.float32(orientations / np.pi)  # bins per radian over 180 degrees
    pos = np.arctan2(g_row.astype(np.float32), g_col.astype(np.float32)) * per_bin  # [-O, O]
    pos += np.float32(orientations) * (pos < 0)  # 180-degree periodicity -> [0, O]
    low = np.floor(pos)
    frac = pos - low
    margin = np.float32(_NEAR_EDGE * orientations / 180.0)
    near = np.flatnonzero((frac < margin) | (frac > 1 - margin))
    # Values of O (and any bin an edge could flip) are among the `near` pixels.
    bins = low.astype(np.intp).ravel()
    if near.size:
        bins[near] = _exact_bins(g_row.ravel()[near], g_col.ravel()[near], orientations)
    return bins.reshape(pos.shape)


def _cell_histograms(images: np.ndarray, orientations: int,
                     pixels_per_cell: tuple[int, int]) -> np.ndarray:
    """(n, H, W) float -> (n, n_cells_row, n_cells_col, orientations) float64."""
    n, h, w = images.shape
    cr, cc = pixels_per_cell
    ncr, ncc = h // cr, w // cc
    g_row = np.zeros_like(images)
    g_col = np.zeros_like(images)
    g_row[:, 1:-1, :] = images[:, 2:, :] - images[:, :-2, :]
    g_col[:, :, 1:-1] = images[:, :, 2:] - images[:, :, :-2]
    # Only the pixels inside full cells vote.
    g_row = g_row[:, : ncr * cr, : ncc * cc]
    g_col = g_col[:, : ncr * cr, : ncc * cc]
    # skimage takes hypot in float64; the float32 magnitude differs by < 1 float32 ulp.
    magnitude = np.sqrt(g_row * g_row + g_col * g_col)
    if g_row.dtype == np.float32:
        bins = _orientation_bins(g_row, g_col, orientations)
    else:  # the float32 shortcut could flush tiny float64 gradients; bin them exactly
        bins = _exact_bins(g_row, g_col, orientations)
    dropped = bins == orientations
    if dropped.any():  # rare: orientation rounded to 180 degrees, in no bin (as skimage)
        magnitude = np.where(dropped, 0, magnitude)
        bins = np.where(dropped, 0, bins)
    cell_row = (np.arange(ncr * cr) // cr)[:, None]
    cell_col = (np.arange(ncc * cc) // cc)[None, :]
    cell = cell_row * ncc + cell_col  # (H', W')
    idx = (np.arange(n)[:, None, None] * (ncr * ncc) + cell) * orientations + bins
    hist = np.bincount(idx.ravel(), weights=magnitude.ravel(),
                       minlength=n * ncr * ncc * orientations)
    return hist.reshape(n, ncr, ncc, orientations) / (cr * cc)


def hog_descriptors(images: np.ndarray, orientations: int = HOG_ORIENTATIONS,
                    pixels_per_cell: tuple[int, int] = HOG_CELL,
                    cells_per_block: tuple[int, int] = HOG_BLOCK) -> np.ndarray:
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
    hist = np.empty((n, ncr, ncc, orientations), dtype=np.float64)
    for start in range(0, n, BLOCK):  # blocks of patches keep the buffers in cache
        stop = min(n, start + BLOCK)
        hist[start:stop] = _cell_histograms(images[start:stop], orientations, pixels_per_cell)
    # blocks[:, r, c, i, j, :] = hist[:, r + i, c + j, :]
    blocks = np.empty((n, nbr, nbc, br, bc, orientations), dtype=np.float64)
    for i in range(br):
        for j in range(bc):
            blocks[:, :, :, i, j, :] = hist[:, i:i + nbr, j:j + nbc, :]
    blocks = blocks.reshape(n, nbr, nbc, -1)
    norm = np.sqrt(np.sum(blocks ** 2, axis=-1, keepdims=True) + _EPS ** 2)
    blocks = np.minimum(blocks / norm, 0.2)
    norm = np.sqrt(np.sum(blocks ** 2, axis=-1, keepdims=True) + _EPS ** 2)
    blocks = blocks / norm
    return blocks.reshape(n, -1).astype(np.float32)


def hog_view(patches) -> np.ndarray:
    """HOG view on the Tan-Triggs gray patches.

    Parameters
    ----------
    patches : Patches
        Uses ``patches.gray``, ``(n, fh, fw)`` float32.

    Returns
    -------
    (n, d) float32 ndarray; 9 orientations, 8x8 px cells, 2x2 cell blocks,
    L2-Hys: ``d = 324`` for the default 32x32 feature size.
    """
    return hog_descriptors(patches.gray, HOG_ORIENTATIONS, HOG_CELL, HOG_BLOCK)
