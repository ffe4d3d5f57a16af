"""Scale filter: the target's scale judged by a one-dimensional correlation filter over scales.

The particles' likelihood judges scale poorly: a candidate a little smaller
than the target is explained by the templates about as well as the target,
one a little larger is not (part of it is background), so the random walk's
steps down in scale are kept and its steps up refused, and the box shrinks
(``docs/experiments.md#n42``). DSST (Danelljan et al., BMVC 2014; the scale
estimation of OpenCV's CSRT) judges scale apart from translation, with a
filter that treats growth and shrinking alike: at the target's centre, the
box grown and shrunk by ``STEP ** k`` (``k`` in ``-(N - 1) / 2 .. (N - 1) / 2``)
is resampled to one fixed size and described by cell features
(:func:`smtmvt.correlation.cell_features`); each factor's features are one
sample of a one-dimensional signal over the ``N`` factors, and a filter is
trained in the Fourier domain (over that dimension, one per feature) so that
its response is a Gaussian peaked on factor 1. On a new frame, at the new
centre, the response peaks at the factor by which the target changed size.

The tracker moves the chosen state's scale ``TrackerConfig.scale_filter`` of
the way (in log) to the filter's, and the whole particle cloud with it; the
filter learns from the final box at ``LEARNING_RATE`` on the frames the
correlation filter learns from (:mod:`smtmvt.correlation`'s gate).
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from .correlation import CELL, cell_features, gray_part

__all__ = ["N_SCALES", "STEP", "LEARNING_RATE", "MODEL_AREA", "factors", "model_size", "samples", "ScaleFilter"]

#: Number of scale factors sampled (DSST's 33).
N_SCALES = 33
#: Ratio of consecutive factors (DSST's 1.02).
STEP = 1.02
#: Rate at which each frame's filter enters the model (DSST's 0.025).
LEARNING_RATE = 0.025
#: Largest area of the resampled box, pixels (DSST's 512).
MODEL_AREA = 512.0
#: Standard deviation of the label's peak, in factors (DSST's sqrt(33) / 4).
LABEL_SIGMA = np.sqrt(N_SCALES) / 4.0
#: Ridge term, as a fraction of the mean of the features' energy spectrum.
REGULARIZATION = 1e-2


def factors(n: int = N_SCALES, step: float = STEP) -> np.ndarray:
    """The scale factors ``step ** k``, ``k = -(n - 1) / 2 .. (n - 1) / 2``, ``(n,)`` float64 (n odd)."""
    if n < 1 or n % 2 == 0:
        raise ValueError(f"scale filter: the number of scales must be odd and positive, got {n}")
    return step ** (np.arange(n) - (n - 1) / 2.0)


def model_size(box_size) -> tuple[int, int]:
    """``(height, width)`` pixels every sample is resampled to, for a box of
    ``box_size`` ``(w, h)`` frame pixels: the box's aspect, area at most
    ``MODEL_AREA``, each side a multiple of ``CELL`` and at least ``2 * CELL``."""
    w, h = float(box_size[0]), float(box_size[1])
    if not (w > 0 and h > 0):
        raise ValueError(f"scale filter: box size {tuple(np.asarray(box_size, dtype=float).tolist())} has no area")
    k = min(1.0, np.sqrt(MODEL_AREA / (w * h)))
    return tuple(CELL * max(2, int(round(s * k / CELL))) for s in (h, w))  # type: ignore[return-value]


def samples(frame: np.ndarray, centre, box_size, scales, size) -> np.ndarray:
    """The features of the box of ``box_size * f`` about ``centre`` for each
    factor ``f`` of ``scales``, resampled to ``size``: ``(d, n)`` float64, one
    column per factor, each times a Hann window over the factors.

    ``frame``: (H, W) or (H, W, C) image (its gray level: the mean of its
    first three channels over :func:`smtmvt.preprocess.white_level`);
    ``centre``: ``(x, y)`` frame pixels; ``box_size``: ``(w, h)`` frame pixels;
    the frame's border is replicated outside it.
    """
    sc = np.asarray(scales, dtype=np.float64)
    cx, cy = float(centre[0]), float(centre[1])
    w, h = float(box_size[0]), float(box_size[1])
    # the part of the frame the largest factor reads, border replicated
    hw, hh = 0.5 * w * sc.max() + 1.0, 0.5 * h * sc.max() + 1.0
    x0, y0 = int(np.floor(cx - hw)), int(np.floor(cy - hh))
    gray = gray_part(frame, x0, y0, int(np.ceil(cx + hw)) + 1, int(np.ceil(cy + hh)) + 1)
    H, W = size
    # one anti-aliasing blur for all factors (they span less than 2x): at the middle one's step
    step = min(w / W, h / H)
    if step > 1.0:
        gray = cv2.GaussianBlur(gray, (0, 0), sigmaX=0.5 * w / W, sigmaY=0.5 * h / H)
    imgs = np.empty((len(sc), H, W), np.float32)
    for k, s in enumerate(sc):
        # model pixel i's centre on the box's: centre + (i - (W - 1) / 2) * w s / W, in crop pixels
        sx, sy = w * s / W, h * s / H
        M = np.array([[sx, 0.0, cx - x0 - (W - 1) / 2.0 * sx], [0.0, sy, cy - y0 - (H - 1) / 2.0 * sy]])
        imgs[k] = cv2.warpAffine(
            gray, M, (W, H), flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP, borderMode=cv2.BORDER_REPLICATE
        )
    X = cell_features(imgs).reshape(len(sc), -1).T.astype(np.float64)
    return X * np.hanning(len(sc) + 2)[1:-1][None]


@dataclass(frozen=True)
class _Model:
    """Numerator ``A`` ``(d, n)`` complex128 and denominator ``B`` ``(n,)`` float64."""

    A: np.ndarray
    B: np.ndarray


class ScaleFilter:
    """The scale filter of one tracked target (DSST's), trained on the first box.

    Boxes are ``(x, y, w, h)`` 0-based frame pixels, centre ``(x + (w - 1) / 2,
    y + (h - 1) / 2)``.
    """

    def __init__(self, frame: np.ndarray, box, n: int = N_SCALES, step: float = STEP) -> None:
        b = np.asarray(box, dtype=np.float64)
        self.scales = factors(n, step)
        self.size = model_size(b[2:4])
        k = np.arange(n) - (n - 1) / 2.0
        label = np.exp(-0.5 * k**2 / LABEL_SIGMA**2)
        self._G = np.fft.fft(np.fft.ifftshift(label))  # peaked on index 0: factor 1
        self.model = self._train(frame, b)

    def _train(self, frame: np.ndarray, box) -> _Model:
        F = np.fft.fft(self._samples(frame, box), axis=1)
        return _Model(np.conj(self._G)[None] * F, np.sum(np.abs(F) ** 2, axis=0))

    def _samples(self, frame: np.ndarray, box) -> np.ndarray:
        b = np.asarray(box, dtype=np.float64)
        centre = (b[0] + (b[2] - 1) / 2.0, b[1] + (b[3] - 1) / 2.0)
        # ordered so that factor 1 sits at index 0, as the label's peak
        return np.fft.ifftshift(samples(frame, centre, b[2:4], self.scales, self.size), axes=1)

    def response(self, frame: np.ndarray, box) -> np.ndarray:
        """The response ``(n,)`` float64 over :attr:`scales` (in their order) at ``box``."""
        Z = np.fft.fft(self._samples(frame, box), axis=1)
        ridge = REGULARIZATION * float(np.mean(self.model.B)) + 1e-12
        r = np.real(np.fft.ifft(np.sum(np.conj(self.model.A) * Z, axis=0) / (self.model.B + ridge)))
        return np.fft.fftshift(r)

    def estimate(self, frame: np.ndarray, box) -> float:
        """The factor by which the target in ``frame`` about ``box``'s centre is
        larger than ``box``: the factor where :meth:`response` peaks, refined by
        a parabola through the peak and its neighbours (in log factor)."""
        r = self.response(frame, box)
        i = int(np.argmax(r))
        log_step = np.log(self.scales[1] / self.scales[0]) if len(r) > 1 else 0.0
        shift = 0.0
        if 0 < i < len(r) - 1:
            den = r[i - 1] - 2.0 * r[i] + r[i + 1]
            if den < 0:
                shift = float(np.clip(0.5 * (r[i - 1] - r[i + 1]) / den, -0.5, 0.5))
        return float(self.scales[i] * np.exp(shift * log_step))

    def rescale(self, frame: np.ndarray, chosen, last, fraction: float) -> float:
        """The factor on the ``chosen`` box's sides (``(4,)``, frame pixels)
        that moves its size ``sqrt(w h)`` ``fraction`` of the way, in log, to
        :meth:`estimate`'s at its centre, judged about the ``last`` box's size
        (``(4,)``, the box of the frame before)."""
        chosen = np.asarray(chosen, dtype=np.float64)
        last = np.asarray(last, dtype=np.float64)
        at = np.concatenate([chosen[:2] + (chosen[2:] - last[2:]) / 2.0, last[2:]])  # chosen centre, last size
        target = np.log(self.estimate(frame, at)) + 0.5 * np.log(last[2] * last[3])
        step = fraction * (target - 0.5 * np.log(chosen[2] * chosen[3]))
        return float(np.exp(step))

    def update(self, frame: np.ndarray, box, rate: float = LEARNING_RATE) -> None:
        """Blend in the filter trained on ``box`` in ``frame`` at ``rate``."""
        new = self._train(frame, box)
        self.model = _Model((1.0 - rate) * self.model.A + rate * new.A, (1.0 - rate) * self.model.B + rate * new.B)
