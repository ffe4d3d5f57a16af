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

import numpy as np

__all__ = ["COLOR_BINS", "color_histograms", "color_view", "soft_binning_matrix"]

COLOR_BINS = 16  # bins per channel
BLOCK = 64       # patches per vectorized pass (cache-sized work buffers)


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
    counted per patch and channel with one integer ``bincount``, and the
    256-level counts are mapped to the bins by :func:`soft_binning_matrix`.
    """
    colors = np.asarray(colors)
    if colors.ndim != 4:
        raise ValueError(f"expected (n, H, W, C) colors, got shape {colors.shape}")
    if int(bins) < 2:
        raise ValueError(f"bins must be >= 2, got {bins}")
    bins = int(bins)
    n, h, w, c = colors.shape
    counts = np.empty((n * c, _LEVELS), dtype=np.float64)
    b = min(n, BLOCK)
    # Flat level index per (patch, channel): (patch * C + channel) * 256 + level. The
    # offsets are exact integers in float32 (< 2**24), added after rounding.
    offsets = np.ascontiguousarray(np.broadcast_to(
        (np.arange(b * c, dtype=np.float32) * _LEVELS).reshape(b, 1, 1, c), (b, h, w, c)))
    scaled = np.empty((b, h, w, c), dtype=np.float32)
    for start in range(0, n, b):  # blocks of patches keep the buffers in cache
        m = min(b, n - start)
        buf = scaled[:m]
        np.multiply(colors[start:start + m], np.float32(_LEVELS - 1), out=buf, casting="unsafe")
        buf += np.float32(0.5)
        np.clip(buf, np.float32(0.5), np.float32(_LEVELS - 0.5), out=buf)  # == clip to [0, 1] first
        np.floor(buf, out=buf)  # round half up to a level in [0, 255]
        buf += offsets[:m]
        counts[start * c:(start + m) * c] = np.bincount(
            buf.astype(np.intp).ravel(), minlength=m * c * _LEVELS).reshape(m * c, _LEVELS)
    hist = counts @ soft_binning_matrix(bins, _LEVELS)
    return (hist.reshape(n, c * bins) / (h * w)).astype(np.float32)


def color_view(patches) -> np.ndarray:
    """Color histogram view.

    Parameters
    ----------
    patches : Patches
        Uses ``patches.color``, ``(n, fh, fw, C)`` float32 in [0, 1].

    Returns
    -------
    (n, C * 16) float32 ndarray: 48 values for RGB, 16 for gray frames.
    """
    return color_histograms(patches.color, COLOR_BINS)
