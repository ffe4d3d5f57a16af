"""Foreground term: are a candidate's colors the target's more than its surroundings' are?

The views compare a candidate with the templates only; nothing in them says
what the target is *not*. A color model learned in the first frame does
(DAT, Possegger et al., CVPR 2015): with ``H_o`` the color histogram of the
target's box and ``H_s`` that of its surroundings (the box grown
``SURROUND`` times, less the box), the probability that a pixel of color bin
``b`` is the target's is ``P(b) = H_o(b) / (H_o(b) + H_s(b))`` (counts, so
the larger surroundings weigh as a prior; 0.5 for a color seen in neither).

Each frame the map ``P`` of the color plane is summed once (an integral
image), and every candidate box is scored by its *contrast*: the mean of ``P``
inside the box less the mean over the ring around it (the box grown ``RING``
times, less the box), in ``[-1, 1]``. A box on the background scores near 0;
a box inside the target leaves target pixels in its ring and a box larger
than the target takes background in, so both score less than the target's
own box. The tracker adds ``weight * (1 - contrast)`` to each candidate's
residual (``TrackerConfig.foreground_weight``), known before coding like the
anchor term, so bounded coding stays exact
(:func:`smtmvt.likelihood.observe`'s ``offset``). The model is the first
frame's and is never updated: updated from the chosen box (DAT's rule) it
measured no better (``docs/experiments.md#n16``).

The views of a box compare it with the templates only, and a candidate that
matches them about as well as the target (the lane markings and track
around Bolt's runner, the man crossing Walking2's) can win; the color
contrast tells the two apart. It fails where the first box holds much of a
colorful background (Singer2's screen): those colors then count as the
target's.
"""

from __future__ import annotations

import cv2
import numpy as np

__all__ = [
    "BINS",
    "SURROUND",
    "RING",
    "color_bins",
    "foreground_model",
    "foreground_map",
    "ring_window",
    "box_contrast",
]

#: Bins per color channel (joint RGB histogram of BINS**3 bins; gray: BINS**2 levels).
BINS = 8
#: The surroundings of the first box, for the model: the box grown this many times.
SURROUND = 3.0
#: The ring of a candidate box, for its contrast: the box grown this many times.
RING = 1.5


def color_bins(color: np.ndarray) -> np.ndarray:
    """Joint color bin of each pixel, ``(H, W)`` intp.

    ``color`` : (H, W, C) float in [0, 1], C = 3 (RGB: ``BINS`` levels per
    channel) or 1 (gray: ``BINS**2`` levels).
    """
    c = np.asarray(color)
    if c.ndim != 3 or c.shape[2] not in (1, 3):
        raise ValueError(f"expected an (H, W, 1) or (H, W, 3) color plane, got shape {c.shape}")
    levels = BINS if c.shape[2] == 3 else BINS * BINS
    q = np.minimum((np.clip(c, 0.0, 1.0) * levels).astype(np.intp), levels - 1)
    if c.shape[2] == 1:
        return q[:, :, 0]
    return (q[:, :, 0] * BINS + q[:, :, 1]) * BINS + q[:, :, 2]


def _edges(boxes, grow: float, shape) -> np.ndarray:
    """Pixel columns/rows ``x0, y0, x1, y1`` (``[y0, y1) x [x0, x1)``) of 0-based
    boxes ``(n, 4)`` grown about their centres, clipped to the plane: ``(4, n)`` intp."""
    b = np.atleast_2d(np.asarray(boxes, dtype=np.float64))
    cx, cy = b[:, 0] + b[:, 2] / 2.0, b[:, 1] + b[:, 3] / 2.0
    hw, hh = b[:, 2] * grow / 2.0, b[:, 3] * grow / 2.0
    H, W = shape[:2]
    return np.stack(
        [
            np.clip(np.rint(cx - hw), 0, W),
            np.clip(np.rint(cy - hh), 0, H),
            np.clip(np.rint(cx + hw), 0, W),
            np.clip(np.rint(cy + hh), 0, H),
        ]
    ).astype(np.intp)


def foreground_model(color: np.ndarray, box) -> np.ndarray:
    """``P(target | bin)`` for every bin, ``(n_bins,)`` float64 in [0, 1].

    ``color`` : (H, W, C) plane; ``box`` : (x, y, w, h) 0-based pixels of the
    target on it. The surroundings are the box grown ``SURROUND`` times, less
    the box, clipped to the plane.
    """
    bins = color_bins(color)
    n_bins = BINS**3 if np.shape(color)[2] == 3 else BINS**2
    x0, y0, x1, y1 = _edges(box, 1.0, bins.shape)[:, 0]
    X0, Y0, X1, Y1 = _edges(box, SURROUND, bins.shape)[:, 0]
    if x1 <= x0 or y1 <= y0:
        shown = tuple(np.asarray(box, dtype=float).tolist())  # plain numbers, not np.float64(...)
        raise ValueError(f"foreground model: box {shown} has no pixel inside the {bins.shape} plane")
    inside = np.bincount(bins[y0:y1, x0:x1].ravel(), minlength=n_bins).astype(np.float64)
    around = np.bincount(bins[Y0:Y1, X0:X1].ravel(), minlength=n_bins).astype(np.float64) - inside
    total = inside + around
    return np.where(total > 0, inside / np.where(total > 0, total, 1.0), 0.5)


def foreground_map(color: np.ndarray, model: np.ndarray, window=None) -> np.ndarray:
    """``P(target | color)`` of every pixel, ``(H, W)`` float32.

    ``window`` : optional ``(x0, y0, x1, y1)`` int: only the pixels
    ``[y0:y1, x0:x1]`` are computed, the others are 0 (see :func:`ring_window`).
    """
    lut = model.astype(np.float32)
    if window is None:
        return lut[color_bins(color)]
    x0, y0, x1, y1 = window
    out = np.zeros(np.shape(color)[:2], dtype=np.float32)
    out[y0:y1, x0:x1] = lut[color_bins(color[y0:y1, x0:x1])]
    return out


def ring_window(boxes, shape) -> tuple[int, int, int, int]:
    """The pixels ``(x0, y0, x1, y1)`` that :func:`box_contrast` reads for these
    boxes on a plane of ``shape``: their rings' extent, clipped to the plane."""
    x0, y0, x1, y1 = _edges(boxes, RING, shape)
    return int(x0.min()), int(y0.min()), int(x1.max()), int(y1.max())


def box_contrast(pmap: np.ndarray, boxes) -> np.ndarray:
    """Mean of ``pmap`` inside each box less its mean over the ring around it, ``(n,)`` float64.

    ``boxes`` : (n, 4) 0-based ``(x, y, w, h)`` pixels of ``pmap``'s plane. The
    ring is the box grown ``RING`` times less the box; both are clipped to the
    plane (a part with no pixel counts as mean 0).
    """
    S = cv2.integral(np.ascontiguousarray(pmap, dtype=np.float32), sdepth=cv2.CV_64F)

    def sums(e):
        x0, y0, x1, y1 = e
        return S[y1, x1] - S[y0, x1] - S[y1, x0] + S[y0, x0], (x1 - x0) * (y1 - y0)

    inner, a_in = sums(_edges(boxes, 1.0, pmap.shape))
    outer, a_out = sums(_edges(boxes, RING, pmap.shape))
    a_ring = a_out - a_in
    mean_in = np.where(a_in > 0, inner / np.maximum(a_in, 1), 0.0)
    mean_ring = np.where(a_ring > 0, (outer - inner) / np.maximum(a_ring, 1), 0.0)
    return mean_in - mean_ring
