"""What the tracker returns for a frame: :class:`TrackResult` and, in detail, :class:`FrameDetail`."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .confidence import Evidence
from .geometry import affine_to_box, box_scaled, box_with_aspect
from .likelihood import Observation

__all__ = ["TrackResult", "FrameDetail", "evidence", "ratio", "reshaped_box"]


@dataclass(frozen=True)
class TrackResult:
    """Outcome of one :meth:`smtmvt.Tracker.update`.

    Attributes
    ----------
    box : (x, y, w, h) floats, 0-based pixels.
    score : likelihood ``exp(-alpha * (residual + terms))`` of the chosen
        candidate, in (0, 1], ``terms`` the anchor and background terms
        (:mod:`smtmvt.anchor`, :mod:`smtmvt.background`; 0 when off); low
        values mean the target is poorly explained (lost or occluded).
    residual : its reconstruction residual ``sum_k ||D^k c^k - x^k||^2``.
    occluded : the outlier term flagged this frame as occluded.
    template_replaced : index of the template replaced this frame, or None.
    frame_index : 0-based index of the frame since :meth:`smtmvt.Tracker.init`.
    confidence : float in [0, 1], how sure the tracker is that ``box`` is on
        the target (:func:`smtmvt.confidence.confidence` of ``evidence``;
        monotone in it, to be calibrated: see :mod:`smtmvt.confidence`).
    lost : ``confidence`` below :data:`smtmvt.confidence.LOST_BELOW` (0.5):
        the tracker believes the target is lost (occluded, out of view, or
        the box slid off it).
    evidence : the frame's :class:`smtmvt.confidence.Evidence` (the
        correlation response's peak and APCE ratios, the chosen cost's
        ratio, the lost streak) that ``confidence`` was computed from.
    """

    box: tuple
    score: float
    residual: float
    occluded: bool
    template_replaced: int | None
    frame_index: int
    confidence: float = 1.0
    lost: bool = False
    evidence: Evidence = Evidence()


def ratio(value: float, typical: float) -> float:
    """``value / typical`` for a positive ``typical``; else 1 where ``value`` is
    not above it and ``inf`` where it is (nothing to compare with)."""
    value, typical = float(value), float(typical)
    if typical > 0:
        return value / typical
    return 1.0 if value <= typical else math.inf


def evidence(score: float, judged, costs: list, lost: int, alpha: float, drift: float = 0.0) -> Evidence:
    """A frame's :class:`~smtmvt.confidence.Evidence`: the ``judged`` correlation
    response's peak and APCE over their means before
    (:meth:`smtmvt.correlation.CorrelationFilter.judge`; 1 and 1 when None),
    the chosen candidate's cost ``-log(score) / alpha`` over the median of
    ``costs``, those chosen before (appended to it here; ``inf`` for ``score``
    0), the ``lost`` streak, and the chosen candidate's ``drift`` (its residual
    over the first frame's templates, :func:`smtmvt.anchor.anchor_residuals`)."""
    peak = apce_ratio = 1.0
    if judged is not None:
        now, past = judged
        peak, apce_ratio = ratio(now[0], past[0]), ratio(now[1], past[1])
    cost = -math.log(score) / alpha if score > 0 else math.inf
    cost_ratio = ratio(cost, float(np.median(costs))) if costs else 1.0
    if math.isfinite(cost):
        costs.append(cost)
    return Evidence(peak, apce_ratio, cost_ratio, lost, drift)


def reshaped_box(box, reshape: tuple) -> np.ndarray:
    """``box`` ((4,) or (m, 4), working frame) as reported under ``reshape``
    ``(aspect, fraction, factor)`` (:meth:`smtmvt.Tracker`'s ``_reshape``): its aspect ratio
    moved ``fraction`` of the way to ``aspect`` (:func:`box_with_aspect`), then
    its sides times ``factor`` (:func:`box_scaled`), about the same centre."""
    aspect, fraction, factor = reshape
    return box_scaled(box_with_aspect(box, aspect, fraction), factor)


@dataclass(frozen=True)
class FrameDetail:
    """What :meth:`smtmvt.Tracker.update_detailed` computed for one frame.

    Attributes
    ----------
    particles : (n, 6) float64 affine states of the frame's candidates, in
        the tracker's working frame (``config.frame_size``).
    observation : :class:`smtmvt.likelihood.Observation` of the n particles
        followed by the m probes (likelihoods, residuals, bounds, codes).
    best : index of the chosen particle, or None when no candidate was valid.
    probe_boxes : (m, 4) float64 probe boxes, 0-based pixels of the input frame.
    scale : (2,) float64 working-frame pixels per input pixel (x, y).
    best_views : the chosen particle's K views, ``(d_k,)`` float32 each (None
        when no candidate was valid).
    reshape : ``(aspect, fraction, factor)``, how a state's box is reported
        (``config.report_aspect``: its aspect ratio moved ``fraction`` of the
        way to the first box's ``aspect``, in the working frame; then
        ``config.report_scale``: its width and height times ``factor``).
    cue_costs : ``{name: (n + m,) float64 or None}``, each cue's cost of the
        particles then the probes (the sparse cue's is ``observation.residual``),
        as the cue gave it (before ``config.cue_reliability``'s factors; without the
        part that comes with a deferred view, :meth:`smtmvt.cues.Cue.view_cost`).
    """

    particles: np.ndarray
    observation: Observation
    best: int | None
    probe_boxes: np.ndarray
    scale: np.ndarray
    best_views: list | None = None
    reshape: tuple = (1.0, 0.0, 1.0)
    cue_costs: dict = field(default_factory=dict)

    @property
    def boxes(self) -> np.ndarray:
        """(n, 4) boxes of the particles' states, 0-based pixels of the input frame."""
        return affine_to_box(self.particles).reshape(-1, 4) / np.tile(self.scale, 2)

    @property
    def reported_boxes(self) -> np.ndarray:
        """(n, 4) boxes the tracker would report for each particle (:attr:`boxes`
        reshaped as ``config.report_aspect`` and ``config.report_scale`` say),
        0-based pixels of the input frame."""
        work = reshaped_box(affine_to_box(self.particles).reshape(-1, 4), self.reshape)
        return work / np.tile(self.scale, 2)

    @property
    def probe_likelihood(self) -> np.ndarray:
        """(m,) likelihoods of the probes (comparable with ``observation.likelihood[:n]``)."""
        return self.observation.likelihood[len(self.particles) :]
