"""Color view: per-channel color histograms of the raw (not normalized) patch.

Design
------
For RGB patches (C = 3) the descriptor is the concatenation of three
16-bin histograms, one per channel (R, G, B), 48 values. Per-channel
histograms were preferred over a joint RGB histogram (8x8x8 = 512 mostly empty
bins for a 32x32 patch, so one extra quantization flip moves mass between far
apart dimensions) and over HSV (hue is undefined, and jumps, on the gray and
dark pixels that dominate many OTB targets). 16 bins per channel give enough
resolution to tell similar colors apart while each bin still collects on
average 64 of the 1024 pixels.

Votes are split linearly between the two nearest bin centres (soft binning):
a value ``v`` in [0, 1] sits at position ``v * bins - 0.5`` on the bin axis,
bin ``k`` has its centre at ``(k + 0.5) / bins``, and values below the first
centre or above the last one go entirely to the end bin. Hard binning would
make the descriptor jump when a color drifts across a bin edge, which the
sparse-coding likelihood reads as an appearance change; soft binning makes it
a piecewise-linear function of the colors. Each channel's histogram is
divided by the number of pixels, so it sums to 1 (fractions of the patch).

Gray frames (C = 1) fall back to a single 16-bin gray-level histogram built
the same way (16 values, summing to 1). The dimension thus depends on C but is
fixed for a sequence, whose frames are all color or all gray.

Colors are expected in [0, 1]; values outside are clipped.
"""

from __future__ import annotations

import functools

import numpy as np
from numba import njit

from ..threads import run_blocks
from .cells import cell_map

__all__ = ["histogram_power", "COLOR_BINS", "color_histograms", "color_view", "soft_binning_matrix"]

COLOR_BINS = 16  # bins per channel


_LEVELS = 256  # colors are quantized to 8 bits before binning


def soft_binning_matrix(bins: int = COLOR_BINS, levels: int = _LEVELS) -> np.ndarray:
    """(levels, bins) float64 weights of each quantized level ``q / (levels - 1)``.

    Row ``q`` splits one vote between the two bin centres nearest to the value
    ``v = q / (levels - 1)``: with ``x = clip(v * bins - 0.5, 0, bins - 1)``,
    bin ``floor(x)`` gets ``1 - frac(x)`` and the next bin ``frac(x)``. Rows sum to 1.
    """
    v = np.arange(levels, dtype=np.float64) / (levels - 1)
    pos = np.clip(v * bins - 0.5, 0.0, bins - 1)
    lo = np.minimum(np.floor(pos).astype(np.intp), bins - 2)
    frac = pos - lo
    weights = np.zeros((levels, bins), dtype=np.float64)
    rows = np.arange(levels)
    weights[rows, lo] = 1.0 - frac
    weights[rows, lo + 1] += frac
    return weights


@njit(cache=True, nogil=True, boundscheck=False)
def _cell_histograms(colors, row_of_value, lo, w_lo, hi, w_hi, out):  # pragma: no cover - compiled
    """Soft histograms ``out[patch, bin, row]`` (float64, not yet divided by the cell
    area; bins before rows) of ``colors (n, P)``, each patch's P values (pixels x
    channels, flattened); value ``i`` counts in histogram row ``row_of_value[i]``
    (its cell and channel).

    One patch at a time (its level counts stay in cache): each value's level
    ``round(255 v)``, of ``v`` clipped to [0, 1], is computed in a vectorized
    loop, in float32 as ``floor(clip(255 v + 0.5, 0.5, 255.5))`` (round half
    up; clipping after the scale equals clipping to [0, 1] first; the value is
    positive, so truncation is the floor), then counted, the counts laid out
    ``(level, row)``. The counts are mapped to the bins by the soft-binning
    matrix W, whose rows have two nonzero weights (``w_lo`` at ``lo``, ``w_hi``
    at ``hi = lo + 1``, or a weight 0 at the last bin): 2 products per level
    instead of ``bins``, each bin summed in level order, all rows of a level at
    once (independent sums, so the loop vectorizes instead of waiting on one
    running sum; adding a zero product leaves a sum as it was, so levels with
    no votes need no test).
    """
    n, m = colors.shape
    rows = out.shape[2]
    levels = lo.shape[0]
    scale = np.float32(levels - 1)
    half = np.float32(0.5)
    top = np.float32(levels - 0.5)
    counts = np.zeros(levels * rows, dtype=np.int32)
    slot = np.empty(m, dtype=np.int64)
    for k in range(n):
        values = colors[k]
        for i in range(m):
            slot[i] = np.int64(min(max(values[i] * scale + half, half), top)) * rows + row_of_value[i]
        counts[:] = 0
        for i in range(m):
            counts[slot[i]] += 1
        hist = out[k]
        for q in range(levels):
            base = q * rows
            a, wa = lo[q], w_lo[q]
            for r in range(rows):
                hist[a, r] += counts[base + r] * wa
            b, wb = hi[q], w_hi[q]
            for r in range(rows):
                hist[b, r] += counts[base + r] * wb
    return out


@functools.lru_cache(maxsize=16)
def _grid_layout(h: int, w: int, c: int, grid: int, bins: int) -> tuple[np.ndarray, ...]:
    """What :func:`_cell_histograms` needs for ``(h, w, c)`` patches, memoized
    (it depends on the sizes only; the arrays are read-only): each value's
    histogram row, each level's two bins and weights, each row's pixel count."""
    cell = cell_map(h, w, grid)  # (h, w)
    row_of_value = (cell[:, :, None] * c + np.arange(c)).ravel()  # histogram row of each (y, x, channel)
    W = soft_binning_matrix(bins, _LEVELS)
    levels = np.arange(_LEVELS)
    lo = np.argmax(W > 0, axis=1)  # each level's first bin; the second is lo + 1 (weight 0 past the end)
    hi = np.minimum(lo + 1, bins - 1)
    w_lo = W[levels, lo]
    w_hi = np.where(lo + 1 < bins, W[levels, hi], 0.0)
    area = np.bincount(cell.ravel(), minlength=grid * grid).astype(np.float64)
    area_of_row = np.repeat(area, c)  # row = cell * c + channel
    arrays = (row_of_value, lo, w_lo, hi, w_hi, area_of_row)
    for a in arrays:
        a.flags.writeable = False
    return arrays


@njit(cache=True, nogil=True, boundscheck=False)
def _divided(hist, area_of_row, out):  # pragma: no cover - compiled
    """``out[k, row * bins + b] = float32(hist[k, b, row] / area_of_row[row])``:
    the histograms laid out ``(row, bin)`` and divided by their cell's pixel
    count in float64, then rounded to float32 (numpy's transpose, division and
    ``astype``, without their temporaries)."""
    n, bins, rows = hist.shape
    for k in range(n):
        for r in range(rows):
            a = area_of_row[r]
            for b in range(bins):
                out[k, r * bins + b] = np.float32(hist[k, b, r] / a)
    return out


def _grid_histograms(colors: np.ndarray, grid: int, bins: int) -> np.ndarray:
    """(n, grid * grid * C * bins) float32 soft histograms of the cells of a
    ``grid x grid`` layout (cell ``j`` along an axis of length L covers
    ``[j L // grid, (j + 1) L // grid)``), each channel of a cell summing to 1."""
    n, h, w, c = colors.shape
    row_of_value, lo, w_lo, hi, w_hi, area_of_row = _grid_layout(h, w, c, grid, bins)
    hist = np.zeros((n, bins, grid * grid * c))
    flat = np.ascontiguousarray(colors, dtype=np.float32).reshape(n, h * w * c)

    def block(b: slice) -> None:  # each patch on its own: blocks on threads (smtmvt.threads)
        _cell_histograms(flat[b], row_of_value, lo, w_lo, hi, w_hi, hist[b])

    run_blocks(block, n)
    return _divided(hist, area_of_row, np.empty((n, grid * grid * c * bins), dtype=np.float32))


def color_histograms(colors: np.ndarray, bins: int = COLOR_BINS) -> np.ndarray:
    """Soft-binned per-channel histograms of a stack of color patches.

    Parameters
    ----------
    colors : (n, H, W, C) float ndarray
        Colors in [0, 1] (clipped), C channels.
    bins : int
        Bins per channel (>= 2).

    Returns
    -------
    (n, C * bins) float32 ndarray; channel c occupies ``[c * bins, (c + 1) * bins)``
    and sums to 1.

    Notes
    -----
    Values are first rounded to 8 bits (``round(255 v)``, the precision of
    the source frames; it moves a vote by at most 1/32 of a bin at 16 bins),
    counted per patch and channel by a compiled (numba) loop, and the
    256-level counts are mapped to the bins by :func:`soft_binning_matrix`.
    """
    colors = np.asarray(colors)
    if colors.ndim != 4:
        raise ValueError(f"expected (n, H, W, C) colors, got shape {colors.shape}")
    if int(bins) < 2:
        raise ValueError(f"bins must be >= 2, got {bins}")
    return _grid_histograms(colors, 1, int(bins))


def color_view(patches, grid: int = 1, power: float = 1.0) -> np.ndarray:
    """Color histogram view, over the whole patch or per cell of a ``grid x grid`` layout.

    Parameters
    ----------
    patches : Patches
        Uses ``patches.color``, ``(n, fh, fw, C)`` float32 in [0, 1].
    grid : int
        Cells per side. 1 (the paper's view): one histogram of the whole
        patch. A histogram of the whole box barely depends on where the box
        is (measured on 18 OTB sequences: a box shifted by half its size is as
        similar to the first-frame template as the true box); per cell, the
        histograms keep the colors' layout. Cell ``j`` along an axis of length
        L covers ``[j L // grid, (j + 1) L // grid)``.
    power : float > 0
        Each histogram value is raised to this power (0.5: the Hellinger
        embedding, whose L2 distances weigh small bins more; 1: the histogram).

    Returns
    -------
    (n, grid * grid * C * 16) float32 ndarray, ordered ``(cell_row, cell_col,
    channel, bin)``: 48 values for RGB, 16 for gray frames at ``grid = 1``.
    """
    colors = patches.color
    if colors is None:
        raise ValueError("Patches.color (the color patches) was not given")
    grid = int(grid)
    if grid == 1:
        return histogram_power(color_histograms(colors, COLOR_BINS), power)
    _, h, w, _ = colors.shape
    if not 1 <= grid <= min(h, w):
        raise ValueError(f"color grid must be in [1, {min(h, w)}] for {h}x{w} patches, got {grid}")
    return histogram_power(_grid_histograms(colors, grid, COLOR_BINS), power)


def histogram_power(hist: np.ndarray, power: float) -> np.ndarray:
    """``hist ** power`` (float32, nonnegative input); ``hist`` itself at power 1."""
    if not power > 0:
        raise ValueError(f"histogram power must be > 0, got {power!r}")
    if power == 1.0:
        return hist
    if power == 0.5:  # the same values as np.power (every float32 in [0, 1] checked), 4x faster
        return np.sqrt(hist, dtype=np.float32)
    return np.power(hist, np.float32(power), dtype=np.float32)
