"""Correlation term: a discriminative correlation filter's response at each candidate.

The views compare a candidate with the templates; the foreground term with a
color model of the first frame. Neither learns, frame by frame, what tells
the target from the background *around it now*. A correlation filter does
(MOSSE, Bolme et al., CVPR 2010; multi-channel as in DSST, Danelljan et al.,
BMVC 2014): a linear filter ``h`` over a window about the target, trained in
the Fourier domain so that its correlation with the window's features is a
Gaussian peaked on the target's centre, and updated from every chosen box at
a small rate. Its response over a new frame's window peaks where the target
moved; every candidate is scored by the response at its centre.

The window is the box grown ``PADDING`` times about its centre, resampled so
that the box's square root of area spans ``BOX_PIXELS`` pixels (the window's
size in those pixels is fixed at the first frame; its size in the frame
follows the box's scale). The features per ``CELL`` x ``CELL`` cell: the
mean gray level and ``ORIENTATIONS`` unsigned gradient-orientation energies
(square roots of the cell's gradient magnitudes per orientation bin), all
times a Hann window.

The tracker adds ``weight * (r_max - r_i) / r_ref`` to each candidate's
residual (``TrackerConfig.correlation_weight``; :func:`correlation_cost`),
``r_i`` the response at its centre clipped to ``[0, r_max]``, ``r_max`` the
response's peak over the window and ``r_ref`` the mean peak of the filter's
responses before (``TrackerConfig.correlation_usual_peak``, the default;
``r_max`` on the first frame): 0 on the peak, ``weight * r_max / r_ref``
where the filter sees nothing of the target, so that a response weaker than
usual decides less (docs/experiments.md#n47). With the option off ``r_ref``
is ``r_max``, the term ``weight * (1 - r_i / r_max)``. It is known before
coding, so bounded coding stays exact (:func:`smtmvt.likelihood.observe`'s
``offset``).

The tracker also places a fraction of each frame's particles about the
response's peak (:func:`peak_point`; ``TrackerConfig.correlation_particles``),
so that the search reaches where the filter sees the target even when the
random walk does not; and it may let the filter learn only from frames whose
response is confident (:meth:`CorrelationFilter.judge` and :func:`clears`,
LMCF's peak and :func:`apce` test; ``TrackerConfig.correlation_learn_gate``),
so that an occluder or a look-alike that took the box does not enter the
filter; the template update may wait for the same test, made against the
last responses only (:meth:`CorrelationFilter.judged`;
``TrackerConfig.template_learn_gate``).

The response may also mix in, at a fixed share, the response of the filter
trained on the first box and never updated
(``TrackerConfig.correlation_first``), as the anchor term keeps the first
template in the likelihood.

It helps where the target's look drifts from the templates or a similar
object crosses it (Walking2, Bolt, Basketball, Freeman1), and costs where
the filter, trained on the tracker's own choices, follows a box that slid
off the target (Singer2): at weight 1 it cost as much as it gained, at 0.5
it gains on the mean (``docs/experiments.md#n32``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np
from numba import njit

from .geometry import box_to_affine
from .preprocess import white_level

__all__ = [
    "CELL",
    "PADDING",
    "BOX_PIXELS",
    "ORIENTATIONS",
    "LEARNING_RATE",
    "REGULARIZATION",
    "Window",
    "window_shape",
    "window_at",
    "window_features",
    "cell_features",
    "gray_part",
    "gaussian_label",
    "Filter",
    "train",
    "blend",
    "respond",
    "sample",
    "relative_scores",
    "correlation_cost",
    "scaled_correlation_cost",
    "peak_level",
    "peak_point",
    "apce",
    "clears",
    "CorrelationFilter",
]

#: Cell side, window pixels.
CELL = 4
#: The window: the box grown this many times about its centre.
PADDING = 2.5
#: The box's square root of area, in window pixels.
BOX_PIXELS = 48.0
#: Unsigned gradient-orientation bins per cell.
ORIENTATIONS = 9
#: Rate at which each frame's filter enters the model (KCF's 0.02).
LEARNING_RATE = 0.02
#: Ridge term added to the features' energy spectrum.
REGULARIZATION = 1e-2
#: Standard deviation of the label's peak, as a fraction of the box's square root of area (KCF's 0.1).
LABEL_SIGMA = 0.1


@dataclass(frozen=True)
class Window:
    """Where a window lies on the frame.

    ``origin`` : (x, y) frame pixel coordinates of the window's pixel (0, 0)
    centre; ``step`` : (sx, sy) frame pixels per window pixel; ``size`` :
    (height, width) window pixels, multiples of ``CELL``.
    """

    origin: tuple[float, float]
    step: tuple[float, float]
    size: tuple[int, int]

    def cells(self, points) -> np.ndarray:
        """Frame points ``(n, 2)`` ``(x, y)`` as cell coordinates ``(n, 2)``
        ``(u, v)`` (cell ``j``'s centre at ``j``), float64."""
        p = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        wx = (p[:, 0] - self.origin[0]) / self.step[0]
        wy = (p[:, 1] - self.origin[1]) / self.step[1]
        return np.stack([(wx + 0.5) / CELL - 0.5, (wy + 0.5) / CELL - 0.5], axis=1)

    def points(self, cells) -> np.ndarray:
        """Cell coordinates ``(n, 2)`` ``(u, v)`` as frame points ``(n, 2)``
        ``(x, y)``, float64: the inverse of :meth:`cells`."""
        c = np.asarray(cells, dtype=np.float64).reshape(-1, 2)
        wx = (c[:, 0] + 0.5) * CELL - 0.5
        wy = (c[:, 1] + 0.5) * CELL - 0.5
        return np.stack([self.origin[0] + wx * self.step[0], self.origin[1] + wy * self.step[1]], axis=1)


def window_shape(box) -> tuple[int, int]:
    """Window ``(height, width)`` in window pixels for a box ``(x, y, w, h)``:
    the box grown ``PADDING`` times, its square root of area ``BOX_PIXELS``,
    rounded to an odd number of whole cells (at least 5 a side), so that the
    window's centre is a cell's centre."""
    w, h = float(box[2]), float(box[3])
    if not (w > 0 and h > 0):
        raise ValueError(f"correlation window: box {tuple(np.asarray(box, dtype=float).tolist())} has no area")
    k = BOX_PIXELS / np.sqrt(w * h)
    cells = [max(5, int(round(PADDING * s * k / CELL))) for s in (h, w)]
    return (CELL * (cells[0] | 1), CELL * (cells[1] | 1))


def window_at(center, box_size, size) -> Window:
    """The window of ``size`` (height, width) window pixels centred on the
    frame point ``center`` ``(x, y)`` for a box of ``box_size`` ``(w, h)``
    frame pixels (``PADDING`` times the box spans the window)."""
    H, W = size
    sx = PADDING * float(box_size[0]) / W
    sy = PADDING * float(box_size[1]) / H
    # window pixel i's centre sits at origin + i * step; the window's centre ((W - 1) / 2) on center
    origin = (float(center[0]) - (W - 1) / 2.0 * sx, float(center[1]) - (H - 1) / 2.0 * sy)
    return Window(origin, (sx, sy), (int(H), int(W)))


def gray_part(frame: np.ndarray, x0: int, y0: int, x1: int, y1: int) -> np.ndarray:
    """The frame's gray level (the mean of its first three channels over
    :func:`smtmvt.preprocess.white_level`, clipped to [0, 1]) on columns
    ``x0 .. x1 - 1`` and rows ``y0 .. y1 - 1``, ``(y1 - y0, x1 - x0)`` float32,
    the frame's border replicated outside it. Only that part is converted."""
    f = np.asarray(frame)
    rows = np.clip(np.arange(y0, y1), 0, f.shape[0] - 1)
    cols = np.clip(np.arange(x0, x1), 0, f.shape[1] - 1)
    crop = f[rows][:, cols]
    if crop.ndim == 2:
        gray = crop.astype(np.float32)
    else:
        # numpy's float32 mean over the channels, summed in its order ((c0 + c1) + c2)
        # without its strided reduction, which costs twice as much
        gray = crop[:, :, 0].astype(np.float32)
        gray += crop[:, :, 1].astype(np.float32)
        gray += crop[:, :, 2].astype(np.float32)
        gray /= np.float32(3.0)
    return np.ascontiguousarray(np.clip(gray / white_level(f), 0.0, 1.0), dtype=np.float32)


def _resample(frame: np.ndarray, window: Window) -> np.ndarray:
    """The frame's gray level (the mean of its channels, in [0, 1]) on the
    window's pixels, ``(H, W)`` float32, the frame smoothed first where the
    window is coarser than the frame (anti-aliasing) and its border
    replicated outside it. Only the part of the frame the window reads is
    converted; a fourth (alpha) channel is left out."""
    H, W = window.size
    sx, sy = window.step
    x0, y0 = window.origin
    # the frame part the window reads (with a margin for the blur and interpolation)
    margin = 3.0 * max(sx, sy, 1.0)
    fx0, fy0 = int(np.floor(x0 - margin)), int(np.floor(y0 - margin))
    fx1, fy1 = int(np.ceil(x0 + (W - 1) * sx + margin)) + 1, int(np.ceil(y0 + (H - 1) * sy + margin)) + 1
    part = gray_part(frame, fx0, fy0, fx1, fy1)
    s = max(sx, sy)
    if s > 1.0:
        part = cv2.GaussianBlur(part, (0, 0), sigmaX=0.5 * sx if sx > 1 else 0.3, sigmaY=0.5 * sy if sy > 1 else 0.3)
    M = np.array([[sx, 0.0, x0 - fx0], [0.0, sy, y0 - fy0]], dtype=np.float64)
    return cv2.warpAffine(
        part, M, (W, H), flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP, borderMode=cv2.BORDER_REPLICATE
    )


def _hann(shape) -> np.ndarray:
    """Separable Hann window ``shape`` float32."""
    return np.outer(np.hanning(shape[0] + 2)[1:-1], np.hanning(shape[1] + 2)[1:-1]).astype(np.float32)


def window_features(frame: np.ndarray, window: Window) -> np.ndarray:
    """Cell features of the window, ``(C, h, w)`` float32, ``C = ORIENTATIONS + 1``.

    ``frame`` : (H, W) or (H, W, C) image, uint8, uint16 or float
    (:func:`smtmvt.preprocess.white_level`); its gray level is the mean of its channels (independent
    of their order). Channel 0 is the cell's mean gray
    level less 0.5; channels 1.. the square roots of the cell's mean gradient
    magnitude per unsigned orientation bin; all times a Hann window over the
    cells.
    """
    feats = cell_features(_resample(frame, window))
    return feats * _hann(feats.shape[1:])[None]


def cell_features(img: np.ndarray) -> np.ndarray:
    """Cell features of gray images ``(..., H, W)`` float32 in [0, 1] (``H``,
    ``W`` multiples of ``CELL``), ``(..., ORIENTATIONS + 1, H / CELL, W / CELL)``
    float32: each cell's mean gray level less 0.5, then the square roots of
    its mean gradient magnitude per unsigned orientation bin (no window
    applied). The gradient is the central difference, 0 on the border rows
    and columns (OpenCV's ``Sobel`` with ``ksize=1``, its border reflected);
    a pixel's bin is ``floor(mod(atan2(gy, gx), pi) * ORIENTATIONS / pi)``
    (the last bin closed), its magnitude ``hypot(gx, gy)``, all float32.

    Compiled (:func:`_gradient_bins`, :func:`_cell_sums`) and bit-identical
    to the same expressions in numpy (``tests/test_correlation.py`` holds
    that reference): the bins are found by which bin edges the gradient lies
    beyond, and the few pixels within a relative ``1e-5`` of an edge, where
    float32 ``atan2``'s rounding decides, by numpy's own expression; the cell
    sums add each row of a cell, then the rows, as numpy's ``sum`` does on
    one image (on a batch numpy adds in another order: the last bit of a
    batch's features, as :mod:`smtmvt.scale` computes them, moved with this
    code; the tracker's filter computes one window at a time).
    """
    img = np.asarray(img, dtype=np.float32)
    lead = img.shape[:-2]
    H, W = img.shape[-2:]
    if H % CELL or W % CELL or not (H and W):
        raise ValueError(f"cell features need images whose sides are multiples of {CELL}, got {H} x {W}")
    images = np.ascontiguousarray(img.reshape(-1, H, W))
    mag = np.empty_like(images)
    bins = np.empty(images.shape, np.intp)
    if _gradient_bins(images, *_INNER_EDGES, mag, bins):
        p, y, x = np.nonzero(bins < 0)
        # the central differences at those pixels, 0 on the border rows and columns
        dx = images[p, y, np.minimum(x + 1, W - 1)] - images[p, y, np.maximum(x - 1, 0)]
        dy = images[p, np.minimum(y + 1, H - 1), x] - images[p, np.maximum(y - 1, 0), x]
        gx = np.where((x > 0) & (x < W - 1), dx, np.float32(0.0))
        gy = np.where((y > 0) & (y < H - 1), dy, np.float32(0.0))
        angle = np.mod(np.arctan2(gy, gx), np.pi)
        bins[p, y, x] = np.minimum((angle * (ORIENTATIONS / np.pi)).astype(np.intp), ORIENTATIONS - 1)
    out = np.empty((len(images), ORIENTATIONS + 1, H // CELL, W // CELL), np.float32)
    _cell_sums(images, mag, bins, out)
    return out.reshape(*lead, *out.shape[1:])


#: cosines and sines of the interior bin edges ``i pi / ORIENTATIONS``, ``i = 1 .. ORIENTATIONS - 1``
_INNER_EDGES = (
    np.cos(np.arange(1, ORIENTATIONS) * (np.pi / ORIENTATIONS)),
    np.sin(np.arange(1, ORIENTATIONS) * (np.pi / ORIENTATIONS)),
)
#: relative distance to a bin edge within which numpy's float32 angle decides
_NEAR_EDGE = 1e-5


@njit(cache=True, nogil=True, boundscheck=False)
def _gradient_bins(images, cos_e, sin_e, mag, bins):  # pragma: no cover - compiled
    """Each pixel's gradient magnitude (float32 ``hypot``) into ``mag`` and its
    orientation bin into ``bins`` (``(n, H, W)`` each), ``-1`` where the
    gradient lies within ``_NEAR_EDGE`` of a bin edge (0 and pi included);
    returns how many such pixels. The gradient is folded into the upper
    half-plane (its orientation is modulo pi); its bin is the number of
    interior edges (``cos_e``, ``sin_e``) it lies beyond; a zero vertical
    gradient is bin 0."""
    n, H, W = images.shape
    near = 0
    for p in range(n):
        for y in range(H):
            for x in range(W):
                gx = np.float32(0.0)
                gy = np.float32(0.0)
                if 0 < x < W - 1:
                    gx = images[p, y, x + 1] - images[p, y, x - 1]
                if 0 < y < H - 1:
                    gy = images[p, y + 1, x] - images[p, y - 1, x]
                mag[p, y, x] = np.float32(math.hypot(gx, gy))
                if gy == 0.0:
                    bins[p, y, x] = 0
                    continue
                a, b = np.float64(gy), np.float64(gx)
                if a < 0.0:
                    a, b = -a, -b
                tol = _NEAR_EDGE * math.sqrt(a * a + b * b)
                count = -1
                if a > tol:
                    count = 0
                    for i in range(cos_e.shape[0]):
                        d = a * cos_e[i] - b * sin_e[i]
                        if abs(d) <= tol:
                            count = -1
                            break
                        count += d >= 0.0
                bins[p, y, x] = count
                near += count < 0
    return near


@njit(cache=True, nogil=True, boundscheck=False)
def _cell_sums(images, mag, bins, out):  # pragma: no cover - compiled
    """``out[p, 0]``: each cell's mean gray level less 0.5; ``out[p, 1 + k]``:
    the square root of its mean magnitude in bin ``k``; float32 sums of
    each of the cell's rows, then of the rows (numpy's order)."""
    n, H, W = images.shape
    count = np.float32(CELL * CELL)
    total = np.zeros(ORIENTATIONS, np.float32)
    row = np.zeros(ORIENTATIONS, np.float32)
    for p in range(n):
        for i in range(H // CELL):
            for j in range(W // CELL):
                total[:] = 0.0
                gray = np.float32(0.0)
                for dy in range(CELL):
                    row[:] = 0.0
                    gray_row = np.float32(0.0)
                    y = i * CELL + dy
                    for dx in range(CELL):
                        row[bins[p, y, j * CELL + dx]] += mag[p, y, j * CELL + dx]
                        gray_row += images[p, y, j * CELL + dx]
                    for k in range(ORIENTATIONS):
                        total[k] += row[k]
                    gray += gray_row
                out[p, 0, i, j] = gray / count - np.float32(0.5)
                for k in range(ORIENTATIONS):
                    out[p, 1 + k, i, j] = math.sqrt(total[k] / count)


def gaussian_label(cells_shape, box_cells: float) -> np.ndarray:
    """The desired response, ``(h, w)`` float64: a Gaussian of standard deviation
    ``LABEL_SIGMA * box_cells`` cells peaked on the window's centre
    (cell coordinate ``((w - 1) / 2, (h - 1) / 2)``)."""
    h, w = cells_shape
    sigma = max(LABEL_SIGMA * box_cells, 0.5)
    v = np.arange(h) - (h - 1) / 2.0
    u = np.arange(w) - (w - 1) / 2.0
    return np.exp(-0.5 * (v[:, None] ** 2 + u[None, :] ** 2) / sigma**2)


@dataclass(frozen=True)
class Filter:
    """A multi-channel correlation filter in the Fourier domain: numerator
    ``A`` ``(C, h, w)`` complex128 and denominator ``B`` ``(h, w)`` float64
    (the features' energy spectrum)."""

    A: np.ndarray
    B: np.ndarray


def train(features: np.ndarray, label: np.ndarray) -> Filter:
    """The filter whose correlation with ``features`` ``(C, h, w)`` is ``label``
    ``(h, w)`` (up to the ridge term): ``A_c = conj(G) F_c``,
    ``B = sum_c |F_c|^2``."""
    F = np.fft.fft2(features, axes=(-2, -1))
    G = np.fft.fft2(label)
    return Filter(np.conj(G)[None] * F, np.sum(np.abs(F) ** 2, axis=0))


def blend(model: Filter, new: Filter, rate: float) -> Filter:
    """``(1 - rate) * model + rate * new``, numerator and denominator alike."""
    return Filter((1.0 - rate) * model.A + rate * new.A, (1.0 - rate) * model.B + rate * new.B)


def respond(model: Filter, features: np.ndarray) -> np.ndarray:
    """The filter's response over a window's ``features`` ``(C, h, w)``,
    ``(h, w)`` float64: ``IFFT(sum_c conj(A_c) Z_c / (B + lambda))``, with
    ``lambda`` ``REGULARIZATION`` times the mean of ``B``; on the features it
    was trained on, about the label."""
    Z = np.fft.fft2(features, axes=(-2, -1))
    ridge = REGULARIZATION * float(np.mean(model.B)) + 1e-12
    return np.real(np.fft.ifft2(np.sum(np.conj(model.A) * Z, axis=0) / (model.B + ridge)))


def sample(response: np.ndarray, cells) -> np.ndarray:
    """The response at cell coordinates ``(n, 2)`` ``(u, v)``, bilinear,
    ``(n,)`` float64; 0 outside the window."""
    r = np.asarray(response, dtype=np.float64)
    h, w = r.shape
    c = np.asarray(cells, dtype=np.float64).reshape(-1, 2)
    u, v = c[:, 0], c[:, 1]
    inside = (u >= 0) & (u <= w - 1) & (v >= 0) & (v <= h - 1)
    u, v = np.clip(u, 0, w - 1), np.clip(v, 0, h - 1)
    u0, v0 = (
        np.minimum(np.floor(u).astype(np.intp), w - 2 if w > 1 else 0),
        np.minimum(np.floor(v).astype(np.intp), h - 2 if h > 1 else 0),
    )
    u1, v1 = np.minimum(u0 + 1, w - 1), np.minimum(v0 + 1, h - 1)
    fu, fv = u - u0, v - v0
    out = r[v0, u0] * (1 - fu) * (1 - fv) + r[v0, u1] * fu * (1 - fv) + r[v1, u0] * (1 - fu) * fv + r[v1, u1] * fu * fv
    return np.where(inside, out, 0.0)


def relative_scores(response: np.ndarray, window: Window, centres) -> np.ndarray:
    """``r_i / r_max`` clipped to [0, 1] for each frame point ``(n, 2)`` ``(x, y)``,
    ``r_i`` the ``response`` ``(h, w)`` over ``window`` at the point
    (:func:`sample`) and ``r_max`` its peak; ``(n,)`` float64 (all 0 for a
    response with no positive peak)."""
    peak = float(response.max())
    if not peak > 0:
        return np.zeros(len(np.asarray(centres).reshape(-1, 2)))
    return np.clip(sample(response, window.cells(centres)) / peak, 0.0, 1.0)


def correlation_cost(response: np.ndarray, window: Window, centres, reference: float | None = None) -> np.ndarray:
    """The correlation cue's cost of each frame point ``(n, 2)`` ``(x, y)``:
    ``(r_max - r_i) / reference``, ``r_i`` the ``response`` ``(h, w)`` over
    ``window`` at the point (:func:`sample`) clipped to ``[0, r_max]``, ``r_max``
    its peak; ``(n,)`` float64 in ``[0, r_max / reference]`` (all 0 for a
    response with no positive peak).

    ``reference`` : the peak the filter's responses usually reach (the tracker
    passes their mean over the frames before); None or not positive: ``r_max``,
    so that the cost is ``1 - r_i / r_max`` (:func:`relative_scores`). Measured
    against a usual peak, a response weaker than usual (an occluder, a target
    that changed) spreads its candidates' costs over a narrower range, and the
    other cues decide more: the cue weighs in as much as it is sure this frame
    (docs/experiments.md#n47).
    """
    n = len(np.asarray(centres).reshape(-1, 2))
    peak = float(response.max())
    if not peak > 0:
        return np.zeros(n)
    scale = reference if reference is not None and reference > 0 else peak
    return (1.0 - relative_scores(response, window, centres)) * (peak / scale)


def scaled_correlation_cost(levels, centres, log_sides, reference: float | None = None) -> np.ndarray:
    """:func:`correlation_cost` read at each point's size as well as its place.

    ``levels`` : ``[(log_side, response (h, w), Window), ...]`` the responses
    over windows of several sizes about one centre, sorted by ``log_side``
    (the log of the window's side over the reference window's);
    ``centres`` : ``(n, 2)`` frame points; ``log_sides`` : ``(n,)`` each
    point's box's log side over the reference's. ``r_i`` is the response at
    the point, interpolated linearly in log side between the two levels about
    its own (clamped to the outer ones), ``r_max`` the highest peak of all
    levels; the cost ``(r_max - r_i) / reference`` as :func:`correlation_cost`,
    ``(n,)`` float64 (SAMF, Li and Zhu, ECCV 2014 workshops, read per
    candidate instead of at the best scale's peak).
    """
    c = np.asarray(centres, dtype=np.float64).reshape(-1, 2)
    peak = max(float(r.max()) for _, r, _ in levels)
    if not peak > 0:
        return np.zeros(len(c))
    ls = np.array([lv[0] for lv in levels])
    at = np.stack([sample(r, w.cells(c)) for _, r, w in levels])  # (levels, n)
    q = np.clip(np.asarray(log_sides, dtype=np.float64), ls[0], ls[-1])
    hi = np.clip(np.searchsorted(ls, q), 1, len(ls) - 1) if len(ls) > 1 else np.zeros(len(q), dtype=np.intp)
    lo = np.maximum(hi - 1, 0)
    span = np.where(ls[hi] > ls[lo], ls[hi] - ls[lo], 1.0)
    f = np.clip((q - ls[lo]) / span, 0.0, 1.0)
    idx = np.arange(len(c))
    r_i = (1.0 - f) * at[lo, idx] + f * at[hi, idx]
    scale = reference if reference is not None and reference > 0 else peak
    return (peak - np.clip(r_i, 0.0, peak)) / scale


def peak_level(peaks, step: float) -> float:
    """The log side of the highest of ``peaks`` ``(2J + 1,)``, the responses'
    peaks over windows ``step`` apart in log side about the middle one (log
    side 0), refined by the parabola through it and its neighbours where it
    is not an end one; in ``[-J step, J step]``."""
    p = np.asarray(peaks, dtype=np.float64)
    J = (len(p) - 1) // 2
    k = int(np.argmax(p))
    level = float(k - J)
    if 0 < k < len(p) - 1:
        a, m, z = p[k - 1], p[k], p[k + 1]
        curve = a - 2.0 * m + z
        if curve < 0:
            level += 0.5 * (a - z) / curve
    return level * step


def peak_point(response: np.ndarray, window: Window) -> np.ndarray:
    """The frame point ``(2,)`` ``(x, y)`` of the centre of the cell where
    ``response`` ``(h, w)`` over ``window`` is highest (the first such cell)."""
    v, u = np.unravel_index(int(np.argmax(response)), response.shape)
    return window.points([(u, v)])[0]


def apce(response: np.ndarray) -> float:
    """Average peak-to-correlation energy of ``response`` ``(h, w)`` (LMCF,
    Wang et al., CVPR 2017): ``(r_max - r_min)^2 / mean((r - r_min)^2)``, a
    float >= 1 (1 for a flat response, ``h w`` for a single spike). High where
    the response is one sharp peak; falls where it spreads or has several."""
    r = np.asarray(response, dtype=np.float64)
    lo = float(r.min())
    energy = float(np.mean((r - lo) ** 2))
    if not energy > 0:
        return 1.0
    return (float(r.max()) - lo) ** 2 / energy


def clears(judged: tuple[tuple[float, float], np.ndarray] | None, gate: tuple[float, float]) -> bool:
    """Whether a response :meth:`CorrelationFilter.judge` judged is confident
    (LMCF's criterion): its peak at least ``gate[0]`` times, and its APCE at
    least ``gate[1]`` times, their means over the responses before; always on
    the first (``judged`` None)."""
    if judged is None:
        return True
    now, past = judged
    return bool(now[0] >= gate[0] * past[0] and now[1] >= gate[1] * past[1])


class CorrelationFilter:
    """The filter of one tracked target: trained on the first box, scored at
    candidates' centres, updated from each chosen box at ``LEARNING_RATE``.

    Boxes are ``(x, y, w, h)`` 0-based frame pixels; a box's centre is
    ``(x + (w - 1) / 2, y + (h - 1) / 2)`` (:func:`smtmvt.geometry.box_to_affine`'s).
    """

    def __init__(self, frame: np.ndarray, box) -> None:
        b = np.asarray(box, dtype=np.float64)
        self.size = window_shape(b)
        h, w = self.size[0] // CELL, self.size[1] // CELL
        self._label = gaussian_label((h, w), BOX_PIXELS / CELL)
        self.model = train(self._features(frame, b), self._label)
        #: the filter of the first box, never updated (:meth:`response`'s ``first``)
        self.first = self.model
        #: (peak, APCE) of each response judged by :meth:`judge`
        self.history: list[tuple[float, float]] = []
        self._history_sum = np.zeros(2)

    def judge(self, response: np.ndarray) -> tuple[tuple[float, float], np.ndarray] | None:
        """``(now, past)``: ``response``'s peak and :func:`apce`, and their means
        over the responses judged before (None on the first). Records ``now``
        in :attr:`history`. :func:`clears` says whether they pass a gate."""
        now = (float(np.max(response)), apce(response))
        past = self._history_sum / len(self.history) if self.history else None
        self.history.append(now)
        self._history_sum += now
        return None if past is None else (now, past)

    def judged(self, memory: int = 0) -> tuple[tuple[float, float], np.ndarray] | None:
        """``(now, past)`` of the response :meth:`judge` judged last: its peak
        and APCE, and their means over the ``memory`` responses judged just
        before it (all of them for 0, as :meth:`judge`); None before two are
        judged. A short memory lets a gate follow a response that weakens
        slowly (the target changes scale or look) and still refuse a sudden
        drop (an occluder, a look-alike)."""
        if len(self.history) < 2:
            return None
        before = self.history[-1 - memory : -1] if memory > 0 else self.history[:-1]
        return self.history[-1], np.mean(before, axis=0)

    def confident(self, response: np.ndarray, gate: tuple[float, float]) -> bool:
        """Whether ``response`` is confident enough to learn from (LMCF's
        criterion): :meth:`judge`, then :func:`clears` with ``gate``."""
        return clears(self.judge(response), gate)

    def _window(self, box) -> Window:
        """The window about ``box`` (its centre, its size)."""
        b = np.asarray(box, dtype=np.float64)
        return window_at(box_to_affine(b)[4:], b[2:4], self.size)

    def _features(self, frame: np.ndarray, box) -> np.ndarray:
        return window_features(frame, self._window(box))

    def response(self, frame: np.ndarray, box, first: float = 0.0) -> tuple[np.ndarray, Window]:
        """The response ``(h, w)`` over the window about ``box`` in ``frame``, and the window.

        ``first`` in [0, 1]: the response is ``(1 - first)`` times the model's
        plus ``first`` times that of the first box's filter (:attr:`first`,
        which no update changes), on the same window's features.
        """
        window = self._window(box)
        features = window_features(frame, window)
        r = respond(self.model, features)
        if first:
            r = (1.0 - first) * r + first * respond(self.first, features)
        return r, window

    def scores(self, frame: np.ndarray, box, centres) -> np.ndarray:
        """``r_i / r_max`` clipped to [0, 1] for each centre ``(n, 2)`` ``(x, y)``
        frame pixels, the window about ``box``; ``(n,)`` float64 (all 0 for a
        response with no positive peak)."""
        return relative_scores(*self.response(frame, box), centres)

    def update(self, frame: np.ndarray, box, rate: float = LEARNING_RATE) -> None:
        """Blend in the filter trained on ``box`` in ``frame`` at ``rate``."""
        self.model = blend(self.model, train(self._features(frame, box), self._label), rate)
