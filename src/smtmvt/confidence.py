"""How sure the tracker is of each frame's box: ``TrackResult.confidence`` and ``.lost``.

The tracker already judges every frame's correlation response against the
responses before (:meth:`smtmvt.correlation.CorrelationFilter.judge`: its
peak and APCE, and their means over the frames before) and counts the
frames in a row whose peak fell below ``config.template_learn_floor`` times
its mean (the tracker's ``_lost``, which starts its wider search). With the
chosen candidate's cost (``-log(score) / alpha``: its residual plus the
likelihood's terms) against the median cost chosen before, these are the
:class:`Evidence` of one frame, all computed by tracking anyway.

:func:`confidence` maps them to [0, 1] by a logistic function of a linear
score (Platt scaling), increasing in the peak and APCE ratios and decreasing
in the cost ratio and the lost streak; a frame is ``lost`` when its
confidence is below :data:`LOST_BELOW`. The constants of
:class:`ConfidenceModel` are first guesses, not fitted: a logistic
regression of "tracked" (overlap with the ground truth at least 0.1) on
the four features (:meth:`Evidence.features`) fits them, so that the share
of frames at confidence ``c`` that are tracked is about ``c``
(``bench/lost_calibration.py`` measures that).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Evidence", "ConfidenceModel", "CONFIDENCE", "LOST_BELOW", "RATIO_FLOOR", "confidence"]

#: A frame is lost when its confidence is below this.
LOST_BELOW = 0.5
#: Ratios are clipped to ``[RATIO_FLOOR, 1 / RATIO_FLOOR]`` (a response with no positive
#: peak, a zero or infinite cost): the score stays finite.
RATIO_FLOOR = 1e-6


@dataclass(frozen=True)
class Evidence:
    """What one frame says of its box; every ratio is this frame's value over
    its typical value before (1: as usual; 1 on a frame with nothing before).

    Attributes
    ----------
    peak_ratio : the correlation response's peak over its mean over the frames
        before (``CorrelationFilter.judge``); 1 without the filter or its gates.
    apce_ratio : the response's APCE (:func:`smtmvt.correlation.apce`) over its mean.
    cost_ratio : the chosen candidate's cost ``-log(score) / alpha`` over the
        median of the costs chosen before; ``inf`` when no candidate was valid.
    lost_frames : frames in a row, this one included, whose response peak was
        below ``config.template_learn_floor`` times its mean (0: not this frame).
    drift : the chosen candidate's residual over the first frame's template
        alone, summed over its unit views (:func:`smtmvt.anchor.anchor_residuals`;
        0 to the number of views): how far the box is from what the first
        frame showed (0 without a chosen candidate).
    """

    peak_ratio: float = 1.0
    apce_ratio: float = 1.0
    cost_ratio: float = 1.0
    lost_frames: int = 0
    drift: float = 0.0

    def features(self) -> tuple[float, float, float, float, float]:
        """``(log peak_ratio, log apce_ratio, log cost_ratio, lost_frames, drift)``, the
        ratios clipped to ``[RATIO_FLOOR, 1 / RATIO_FLOOR]``: the inputs of
        :func:`confidence`'s linear score. Raises ValueError naming a NaN field
        or a negative ``lost_frames``."""
        for name in ("peak_ratio", "apce_ratio", "cost_ratio", "drift"):
            if math.isnan(getattr(self, name)):
                raise ValueError(f"confidence: {name} is NaN ({self})")
        if not (self.lost_frames >= 0):
            raise ValueError(f"confidence: lost_frames must be >= 0, got {self.lost_frames}")

        def log(r: float) -> float:
            return math.log(min(max(r, RATIO_FLOOR), 1.0 / RATIO_FLOOR))

        ratios = (log(self.peak_ratio), log(self.apce_ratio), log(self.cost_ratio))
        return (*ratios, float(self.lost_frames), float(self.drift))


@dataclass(frozen=True)
class ConfidenceModel:
    """The constants of :func:`confidence`: the score is
    ``bias + peak * log(peak_ratio) + apce * log(apce_ratio) - cost * log(cost_ratio)
    - streak * lost_frames - drift * drift``.

    The slopes must be >= 0 (the confidence then rises with the response's
    peak and APCE and falls with the cost and the lost streak). The defaults
    are first guesses: ``bias = peak * log(1 / 0.4)`` puts confidence 0.5 (the
    :data:`LOST_BELOW` line) at a peak 0.4 times its mean, the default
    ``template_learn_floor`` below which the tracker already calls a frame
    lost, with the other features at their usual values; a usual frame
    (every ratio 1, no streak) gets ``sigmoid(bias)``, about 0.975. ``drift``
    is 0: fitted, it ranks lost frames better but drops the streak, and a
    vanished target is then not called lost (docs/experiments.md#n53).
    """

    bias: float = 4.0 * math.log(1.0 / 0.4)
    peak: float = 4.0
    apce: float = 1.0
    cost: float = 1.5
    streak: float = 0.25
    drift: float = 0.0

    def __post_init__(self) -> None:
        for name in ("peak", "apce", "cost", "streak", "drift"):
            value = getattr(self, name)
            if not (value >= 0 and math.isfinite(value)):
                raise ValueError(f"ConfidenceModel: {name} must be a finite number >= 0, got {value}")
        if not math.isfinite(self.bias):
            raise ValueError(f"ConfidenceModel: bias must be finite, got {self.bias}")


#: The model :class:`smtmvt.Tracker` uses.
CONFIDENCE = ConfidenceModel()


def confidence(evidence: Evidence, model: ConfidenceModel = CONFIDENCE) -> float:
    """The confidence in [0, 1] of a frame's box given its ``evidence``:
    ``1 / (1 + exp(-score))``, ``score`` the linear score of :class:`ConfidenceModel`
    (about 0 for an infinite cost ratio, :data:`RATIO_FLOOR`). Monotone: never lower for a higher peak or
    APCE ratio, never higher for a higher cost ratio or drift or a longer lost streak."""
    log_peak, log_apce, log_cost, streak, drift = evidence.features()
    score = model.bias + model.peak * log_peak + model.apce * log_apce - model.cost * log_cost
    score -= model.streak * streak + model.drift * drift
    if score >= 0:
        return 1.0 / (1.0 + math.exp(-score))
    return math.exp(score) / (1.0 + math.exp(score))  # no overflow for a very negative score
