"""Tracker configuration: one frozen dataclass holding every parameter.

The model's parameters are the paper's (Javanmardi & Qi, ICME 2018, section
"Experimental Results"): lambda 0.1, gamma 0.25, alpha 30, 400 particles, 10
templates. Where the paper is silent the default is named with its source.
:meth:`TrackerConfig.paper` is the paper's tracker; the defaults differ from
it in how the views are sampled (``scale_normalize``, ``antialias``,
``hog_plane``, ``lbp_plane``), in a 2x2 grid of color histograms
(``color_grid``), in comparing the histograms by their square roots
(``histogram_power``), in a fifth view, the coarse one (``views``), in a
constant-velocity term in the motion model (``velocity``), in a motion term
that weighs each candidate by the random walk's density (``motion_weight``),
in an anchor term toward the first template in the likelihood
(``anchor_weight``), in a foreground term from a color model of the first
frame (``foreground_weight``), in a correlation term from a filter learned
online (``correlation_weight``), in a confidence test on the template update
(``template_learn_gate``), in a wider search once the target seems lost
(``redetect_after``), in computing each frame's planes on the
candidates' window only (``crop_planes``, a speed setting) and the coarse
and HOG views only where the bounds need them (``deferred_views``, a speed
setting), in reporting each box at the first box's aspect ratio
(``report_aspect``) and with its sides 1.03 times the state's
(``report_scale``; the tracking itself is unchanged by either) and in not resizing
frames to 320x240, the best configuration measured.

How each default was chosen, the table of measured changes and the notes
[1] to [45] that the fields cite (mean average overlap over the 18
sequences of ``shared/data/otb`` and ``extra``, later 29 with the held-out
set, over the evaluation's seeds) are in ``docs/experiments.md``: a
field's "docs/experiments.md#nN" is the note [N] there.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, fields, replace
from typing import Any

from .solvers import SOLVERS

__all__ = ["TrackerConfig"]


def _is_gate(gate) -> bool:
    """Whether ``gate`` is a learn gate's ``(b1, b2)``: two factors, each >= 0."""
    return len(gate) == 2 and all(0 <= g for g in gate)


#: Whole-number fields and their bounds (inclusive). Beyond them a run only grows in memory
#: and time (``n_particles=1e9`` grew to 24 GB); a float, even 200.0, is refused, never rounded.
_WHOLE_NUMBERS = {
    "n_particles": (1, 10_000),
    "n_templates": (1, 100),
    "background_samples": (1, 1_000),
    "template_learn_memory": (0, 100_000),
    "redetect_after": (0, 100_000),
    "solver_max_iter": (1, 100_000),
    "fixed_templates": (1, 100),
    "crop_refresh": (0, 100_000),
    "color_grid": (1, 16),
    "blas_threads": (1, 1_024),
}
#: ``(a, b)`` pixel sizes: the bounds of each side (inclusive).
_SIZES = {"feature_size": (8, 256), "color_size": (2, 256), "frame_size": (16, 8_192)}
#: Tuples of real numbers (their lengths and signs are checked with the other fields).
_NUMBER_TUPLES = ("affine_std", "correlation_learn_gate", "template_learn_gate")


def _is_whole(value) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def _is_finite(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool) and math.isfinite(value)


def _number_problem(config: TrackerConfig) -> tuple[str, str] | None:
    """``(field, what it must be)`` for the first numeric field of ``config`` of the wrong
    type or out of bounds; None when they all are fine. ``None`` passes where the field
    allows it; the float fields must be finite numbers."""
    for f in fields(config):
        value = getattr(config, f.name)
        if value is None and "None" in str(f.type):
            continue
        if f.name in _WHOLE_NUMBERS:
            lo, hi = _WHOLE_NUMBERS[f.name]
            if not (_is_whole(value) and lo <= value <= hi):
                return f.name, f"a whole number from {lo} to {hi}"
        elif f.name in _SIZES:
            lo, hi = _SIZES[f.name]
            if not (isinstance(value, (tuple, list)) and len(value) == 2 and all(_is_whole(v) for v in value)):
                return f.name, "two whole numbers"
            if not all(lo <= v <= hi for v in value):
                return f.name, f"two whole numbers from {lo} to {hi}"
        elif f.name in _NUMBER_TUPLES:
            if not (isinstance(value, (tuple, list)) and all(_is_finite(v) for v in value)):
                return f.name, "a tuple of finite numbers"
        elif f.type in ("float", "float | None") and not _is_finite(value):
            return f.name, "a finite number"
    return None


@dataclass(frozen=True)
class TrackerConfig:
    """All parameters of :class:`smtmvt.Tracker`; :meth:`paper` gives the paper's tracker.

    A field's line says what it is, its unit, default and valid range. The evidence is in
    ``docs/experiments.md``: "#nN" is note [N] there, "#f-NAME" the field's former full entry.

    Attributes
    ----------
    lam : float >= 0
        Weight of the per-candidate nuclear norm across views (paper: 0.1).
    gamma : float >= 0
        Weight of the L1 penalties on C and E (paper: 0.25).
    alpha : float > 0
        Likelihood sharpness, ``p = exp(-alpha * residual)`` (paper: 30).
    n_particles : int in [1, 10000]
        Number of particles / candidates per frame (paper: 400). Every whole-number
        field must be an int within its bounds (``_WHOLE_NUMBERS``, ``_SIZES``: a float
        is refused, never rounded), every float field a finite number.
    n_templates : int >= 1
        Number of target templates N (paper: 10).
    views : tuple of str
        The views (:func:`smtmvt.features.available_views`); default the paper's four and
        ``"coarse"`` (docs/experiments.md#n29, #f-views).
    affine_std : tuple of 6 floats >= 0
        Stds of the random walk ``[a11, a12, a21, a22, tx, ty]``, translation in pixels times ``sc``;
        default MTT's, scale and translation doubled (docs/experiments.md#f-affine_std).
    translation_power : float in [0, 1]
        Translation std ``affine_std[4:] * sc ** power`` px; default 1 (docs/experiments.md#f-translation_power).
    aspect_std : float >= 0 or None
        Std of the log aspect; None (default): a11, a22 apart (docs/experiments.md#n14, #f-aspect_std).
    narrow_fraction, narrow_scale : float
        Fraction in [0, 1] of the particles drawn at ``narrow_scale`` (> 0) times every std; default 0
        and 0.25 (docs/experiments.md#n5, #f-narrow_fraction).
    estimate : str
        The state: ``"best"`` particle (default) or ``"mean"`` (docs/experiments.md#f-estimate).
    report_aspect : float in [0, 1]
        Reported box's log aspect moved this far to the first box's; default 1, 0 the paper
        (docs/experiments.md#n23, #f-report_aspect).
    report_scale : float > 0
        Reported box's sides times this; default 1.03, 1 the paper (docs/experiments.md#n45, #f-report_scale).
    velocity : float in [0, 1]
        Share of the last displacement added to each particle; default 0.5 (docs/experiments.md#n7, #f-velocity).
    velocity_fraction : float in [0, 1]
        Share of the particles the velocity term moves; default 1 (docs/experiments.md#n10, #f-velocity_fraction).
    search_expand : float >= 1
        Most widening of the search after a bad frame; default 1, off (docs/experiments.md#n14, #f-search_expand).
    shape_pull : float in [0, 1]
        Pull of the particles' shape to the first box's; default 0 (docs/experiments.md#n9, #f-shape_pull).
    background_weight : float >= 0
        Weight of :mod:`smtmvt.background`'s term; default 0 (docs/experiments.md#n13, #f-background_weight).
    background_samples : int >= 1
        Boxes on the background ring; default 12.
    background_measure : str
        The background term's ``b_i``: ``"nearest"`` (default) or ``"nnls"``.
    anchor_weight : float >= 0
        Weight of :mod:`smtmvt.anchor`'s term; default 1, 0 the paper (docs/experiments.md#n11, #f-anchor_weight).
    foreground_weight : float >= 0
        Weight of :mod:`smtmvt.foreground`'s term; default 1, 0 the paper (docs/experiments.md#n16,
        #f-foreground_weight).
    correlation_weight : float >= 0
        Weight of :mod:`smtmvt.correlation`'s term; default 0.5, 0 the paper (docs/experiments.md#n32,
        #f-correlation_weight).
    correlation_particles : float in [0, 1]
        Share of the particles placed at the filter's peak; default 0.1 (docs/experiments.md#n33, #n34,
        #f-correlation_particles).
    correlation_learn_gate : (float, float), each >= 0
        The filter learns only where peak and APCE reach these times their means; default (0.7, 0.45)
        (docs/experiments.md#n34, #n35, #f-correlation_learn_gate).
    template_learn_gate : (float, float), each >= 0
        No template replaced where the response fails this gate; default (0.7, 0.45), (0, 0) the
        paper (docs/experiments.md#n38, #f-template_learn_gate).
    template_learn_memory : int >= 0
        Responses the template gate compares with, 0 all; default 20 (docs/experiments.md#n38,
        #f-template_learn_memory).
    template_learn_floor : float >= 0
        Least peak over its mean for the template gate; default 0.4 (docs/experiments.md#n38,
        #f-template_learn_floor).
    correlation_rate : float in (0, 1]
        The filter's learning rate; default 0.02 (docs/experiments.md#n35, #f-correlation_rate).
    correlation_first : float in [0, 1]
        Share of the first box's filter in the response; default 0 (docs/experiments.md#n36,
        #f-correlation_first).
    correlation_usual_peak : bool
        Measure the correlation term against the responses' mean peak before,
        ``weight * (r_max - r_i) / r_ref``, instead of this frame's own peak; default True
        (measured better on both halves of docs/split.md: docs/experiments.md#n47), False the term before.
    redetect_after : int >= 0
        Weak-peak frames before a wider search; default 10, 0 off (docs/experiments.md#n40, #f-redetect_after).
    motion_weight : float >= 0
        Weight of the random walk's density; default 1, 0 the paper (docs/experiments.md#n27, #f-motion_weight).
    scale_push : float >= 0
        Weight of ``-log(s_i / s)`` (larger boxes); default 0 (docs/experiments.md#n42, #f-scale_push).
    scale_filter : float in [0, 1]
        Share of the way to :mod:`smtmvt.scale`'s size; default 0 (docs/experiments.md#n43, #f-scale_filter).
    term_views : tuple of str
        Views of the anchor and background terms; default intensity, color, HOG (docs/experiments.md#f-term_views).
    feature_size : (int, int), each >= 8
        Height, width (pixels) of the HOG, LBP and color patches; default (32, 32).
    intensity_factor : float > 0 or None
        Intensity template px per box px; None (default): the paper's (docs/experiments.md#n21,
        #f-intensity_factor).
    color_size : (int, int) or None
        Color patches' height, width; None (default): ``feature_size`` (docs/experiments.md#n12,
        #f-color_size).
    model : str
        A key of :data:`smtmvt.solvers.SOLVERS`: ``"smtmvt"`` (default) or a comparison model
        (docs/experiments.md#f-model).
    solver : str
        Method of the SMTMVT solver: ``"admm"`` (exact ADMM, converges to the optimum; default)
        or ``"paper"`` (the paper's subgradient step).
    solver_tol : float > 0
        Relative change of the iterates at which the solver stops; default 1e-3 (docs/experiments.md#n12).
    solver_max_iter : int >= 1
        Iteration cap of the solver inside the tracker; default 200.
    update_angle : float
        Template update trigger, degrees, intensity view; default 60 (docs/experiments.md#f-update_angle).
    update_margin : float >= 0 or None
        A number: trigger at the first 10 frames' median plus this; None (default): ``update_angle``
        (docs/experiments.md#n28, #f-update_margin).
    fixed_templates : int in [1, n_templates]
        The first templates, never replaced (L1T keeps only the first); default 1.
    anchor_cos : float
        Least mean cosine to the first template for an update; -1 (default): off
        (docs/experiments.md#f-anchor_cos).
    view_weights : tuple of float > 0 or None
        Weights of the views' residuals; None (default): all 1 (docs/experiments.md#n1, #f-view_weights).
    occlusion_fraction : float
        Fraction of the intensity template flagged by E above which the frame is treated as
        occluded and no template is replaced (L1-APG: 0.25).
    prune_eps : float in [0, 1)
        Bounded coding's tolerance, 0 codes all; default 1e-3 (docs/experiments.md#f-prune_eps).
    frame_size : (int, int) or None
        Track on frames resized to ``(width, height)`` (the paper: 320x240); None (default): as given.
    scale_normalize : bool
        Planes at the target's first size; default True (docs/experiments.md#f-scale_normalize).
    crop_planes : bool
        Planes on the candidates' window only; default True (docs/experiments.md#n20, #f-crop_planes).
    crop_context : float >= 1
        Box growth for Tan-Triggs' statistics at ``crop_refresh`` 0; default 3 (docs/experiments.md#n15,
        #f-crop_context).
    crop_refresh : int >= 0
        Frames between whole planes for Tan-Triggs' divisors; default 10 (docs/experiments.md#n20,
        #f-crop_refresh).
    antialias : float >= 0
        Blur before sampling, in steps; default 1, 0 the paper (docs/experiments.md#n24, #f-antialias).
    intensity_plane : str
        ``"tan_triggs"`` (default), ``"gray"`` or ``"dog"`` (docs/experiments.md#n28, #f-intensity_plane).
    hog_plane, lbp_plane : str
        ``"tan_triggs"`` (the paper) or ``"gray"`` (default) (docs/experiments.md#f-hog_plane).
    color_grid : int >= 1
        Cells per side of the color view; default 2, 1 the paper (docs/experiments.md#n3, #f-color_grid).
    lbp_radius : float > 0
        LBP neighbours' radius, patch px; default 1 (docs/experiments.md#n21, #n22, #f-lbp_radius).
    histogram_power : float > 0
        Power of the color and LBP histograms; default 0.5, 1 the paper (docs/experiments.md#n6).
    deferred_views : tuple of str
        Views computed only where the bounds need them; default coarse, HOG, LBP
        (docs/experiments.md#n26, #n29, #f-deferred_views).
    blas_threads : int or None
        BLAS threads in the tracker, None: as set; default 1 (docs/experiments.md#f-blas_threads).
    seed : int or None
        Seed of the particle filter's random generator; the same seed gives the same boxes.
    """

    lam: float = 0.1
    gamma: float = 0.25
    alpha: float = 30.0
    n_particles: int = 400
    n_templates: int = 10
    views: tuple = ("intensity", "color", "coarse", "hog", "lbp")
    affine_std: tuple = (0.01, 0.0005, 0.0005, 0.01, 8.0, 8.0)
    translation_power: float = 1.0
    aspect_std: float | None = None
    narrow_fraction: float = 0.0
    narrow_scale: float = 0.25
    estimate: str = "best"
    report_aspect: float = 1.0
    report_scale: float = 1.03
    velocity: float = 0.5
    velocity_fraction: float = 1.0
    search_expand: float = 1.0
    shape_pull: float = 0.0
    background_weight: float = 0.0
    background_samples: int = 12
    background_measure: str = "nearest"
    anchor_weight: float = 1.0
    foreground_weight: float = 1.0
    correlation_weight: float = 0.5
    correlation_particles: float = 0.1
    correlation_learn_gate: tuple[float, float] = (0.7, 0.45)
    template_learn_gate: tuple[float, float] = (0.7, 0.45)
    template_learn_memory: int = 20
    template_learn_floor: float = 0.4
    correlation_rate: float = 0.02
    correlation_first: float = 0.0
    correlation_usual_peak: bool = True
    redetect_after: int = 10
    motion_weight: float = 1.0
    scale_push: float = 0.0
    scale_filter: float = 0.0
    term_views: tuple = ("intensity", "color", "hog")
    feature_size: tuple = (32, 32)
    intensity_factor: float | None = None
    color_size: tuple | None = None
    model: str = "smtmvt"
    solver: str = "admm"
    solver_tol: float = 1e-3
    solver_max_iter: int = 200
    update_angle: float = 60.0
    update_margin: float | None = None
    occlusion_fraction: float = 0.25
    fixed_templates: int = 1
    anchor_cos: float = -1.0
    view_weights: tuple | None = None
    prune_eps: float = 1e-3
    frame_size: tuple | None = None
    scale_normalize: bool = True
    crop_planes: bool = True
    crop_context: float = 3.0
    crop_refresh: int = 10
    antialias: float = 1.0
    intensity_plane: str = "tan_triggs"
    hog_plane: str = "gray"
    lbp_plane: str = "gray"
    color_grid: int = 2
    lbp_radius: float = 1.0
    histogram_power: float = 0.5
    deferred_views: tuple = ("coarse", "hog", "lbp")
    blas_threads: int | None = 1
    seed: int | None = 0

    def __post_init__(self):
        problem = _number_problem(self)
        if problem is not None:
            name, expected = problem
            raise ValueError(f"TrackerConfig: invalid {name}={getattr(self, name)!r}: expected {expected}")
        checks = {
            "lam": self.lam >= 0,
            "gamma": self.gamma >= 0,
            "alpha": self.alpha > 0,
            "n_particles": int(self.n_particles) >= 1,
            "n_templates": int(self.n_templates) >= 1,
            "views": len(self.views) >= 1,
            "model": self.model in SOLVERS,
            "affine_std": len(self.affine_std) == 6 and all(s >= 0 for s in self.affine_std),
            "feature_size": len(self.feature_size) == 2 and min(self.feature_size) >= 8,
            "color_size": self.color_size is None
            or (len(self.color_size) == 2 and min(self.color_size) >= max(2, int(self.color_grid))),
            "solver_tol": self.solver_tol > 0,
            "solver_max_iter": int(self.solver_max_iter) >= 1,
            "prune_eps": 0 <= self.prune_eps < 1,
            "frame_size": self.frame_size is None or (len(self.frame_size) == 2 and min(self.frame_size) >= 16),
            "antialias": self.antialias >= 0,
            "intensity_plane": self.intensity_plane in ("tan_triggs", "gray", "dog"),
            "hog_plane": self.hog_plane in ("tan_triggs", "gray"),
            "lbp_plane": self.lbp_plane in ("tan_triggs", "gray"),
            "color_grid": int(self.color_grid) >= 1,
            "lbp_radius": self.lbp_radius > 0,
            "histogram_power": self.histogram_power > 0,
            "velocity": 0 <= self.velocity <= 1,
            "report_aspect": 0 <= self.report_aspect <= 1,
            "report_scale": self.report_scale > 0,
            "shape_pull": 0 <= self.shape_pull <= 1,
            "velocity_fraction": 0 <= self.velocity_fraction <= 1,
            "search_expand": self.search_expand >= 1,
            "background_weight": self.background_weight >= 0,
            "background_samples": int(self.background_samples) >= 1,
            "background_measure": self.background_measure in ("nearest", "nnls"),
            "anchor_weight": self.anchor_weight >= 0,
            "foreground_weight": self.foreground_weight >= 0,
            "correlation_weight": self.correlation_weight >= 0,
            "correlation_particles": 0 <= self.correlation_particles <= 1,
            "correlation_learn_gate": _is_gate(self.correlation_learn_gate),
            "template_learn_gate": _is_gate(self.template_learn_gate),
            "template_learn_memory": int(self.template_learn_memory) == self.template_learn_memory
            and self.template_learn_memory >= 0,
            "template_learn_floor": self.template_learn_floor >= 0,
            "correlation_rate": 0 < self.correlation_rate <= 1,
            "correlation_first": 0 <= self.correlation_first <= 1,
            "correlation_usual_peak": isinstance(self.correlation_usual_peak, bool),
            "redetect_after": int(self.redetect_after) == self.redetect_after and self.redetect_after >= 0,
            "motion_weight": self.motion_weight >= 0,
            "scale_push": self.scale_push >= 0,
            "scale_filter": 0 <= self.scale_filter <= 1,
            "estimate": self.estimate in ("best", "mean"),
            "fixed_templates": 1 <= int(self.fixed_templates) <= int(self.n_templates),
            "narrow_fraction": 0 <= self.narrow_fraction <= 1,
            "narrow_scale": self.narrow_scale > 0,
            "translation_power": 0 <= self.translation_power <= 1,
            "crop_context": self.crop_context >= 1,
            "intensity_factor": self.intensity_factor is None or self.intensity_factor > 0,
            "crop_refresh": int(self.crop_refresh) == self.crop_refresh and self.crop_refresh >= 0,
            "aspect_std": self.aspect_std is None or self.aspect_std >= 0,
            "update_margin": self.update_margin is None or self.update_margin >= 0,
        }
        for name, ok in checks.items():
            if not ok:
                raise ValueError(f"TrackerConfig: invalid {name}={getattr(self, name)!r}")
        object.__setattr__(self, "term_views", tuple(self.term_views))
        object.__setattr__(self, "views", tuple(self.views))
        object.__setattr__(self, "deferred_views", tuple(self.deferred_views))
        object.__setattr__(self, "affine_std", tuple(float(s) for s in self.affine_std))
        object.__setattr__(self, "correlation_learn_gate", tuple(float(g) for g in self.correlation_learn_gate))
        object.__setattr__(self, "template_learn_gate", tuple(float(g) for g in self.template_learn_gate))
        object.__setattr__(self, "feature_size", tuple(int(s) for s in self.feature_size))
        if self.color_size is not None:
            object.__setattr__(self, "color_size", tuple(int(s) for s in self.color_size))
        if self.frame_size is not None:
            object.__setattr__(self, "frame_size", tuple(int(s) for s in self.frame_size))
        if self.view_weights is not None:
            weights = tuple(float(w) for w in self.view_weights)
            if len(weights) != len(self.views) or not all(w > 0 and math.isfinite(w) for w in weights):
                raise ValueError(
                    f"TrackerConfig: invalid view_weights={self.view_weights!r}: "
                    f"one positive number per view ({len(self.views)})"
                )
            object.__setattr__(self, "view_weights", weights)

    @classmethod
    def paper(cls, **changes) -> TrackerConfig:
        """The tracker as the paper describes it, with our documented choices where it is silent.

        Paper values: lambda 0.1, gamma 0.25, alpha 30, 400 particles, 10
        templates, the four views, the exact solver of its model. Our choices
        where the paper is silent (measured in the first tracker issue): the
        random walk ``affine_std`` (MTT's with translation 8), the template
        update angle 60 degrees on the intensity view and occlusion fraction
        0.25 (L1T/L1-APG style rule). Frames are resized to 320x240 as in the
        paper's experiments. Every field is spelled out, so the
        defaults of :class:`TrackerConfig` may move on without changing it.
        ``changes`` override fields (e.g. ``seed``).
        """
        base: dict[str, Any] = dict(
            lam=0.1,
            gamma=0.25,
            alpha=30.0,
            n_particles=400,
            n_templates=10,
            views=("intensity", "color", "hog", "lbp"),
            affine_std=(0.01, 0.0005, 0.0005, 0.01, 8.0, 8.0),
            translation_power=1.0,
            aspect_std=None,
            narrow_fraction=0.0,
            narrow_scale=0.25,
            estimate="best",
            report_aspect=0.0,
            report_scale=1.0,
            velocity=0.0,
            velocity_fraction=1.0,
            search_expand=1.0,
            shape_pull=0.0,
            background_weight=0.0,
            background_samples=12,
            background_measure="nearest",
            anchor_weight=0.0,
            foreground_weight=0.0,
            correlation_weight=0.0,
            correlation_particles=0.0,
            correlation_learn_gate=(0.0, 0.0),
            template_learn_gate=(0.0, 0.0),
            template_learn_memory=20,
            template_learn_floor=0.4,
            redetect_after=0,
            motion_weight=0.0,
            scale_push=0.0,
            scale_filter=0.0,
            term_views=("intensity", "color", "hog"),
            feature_size=(32, 32),
            intensity_factor=None,
            color_size=None,
            model="smtmvt",
            solver="admm",
            solver_tol=1e-3,
            solver_max_iter=200,
            update_angle=60.0,
            update_margin=None,
            occlusion_fraction=0.25,
            fixed_templates=1,
            anchor_cos=-1.0,
            view_weights=None,
            frame_size=(320, 240),
            scale_normalize=False,
            crop_planes=False,
            crop_context=3.0,
            crop_refresh=0,
            antialias=0.0,
            intensity_plane="tan_triggs",
            hog_plane="tan_triggs",
            lbp_plane="tan_triggs",
            color_grid=1,
            lbp_radius=1.0,
            histogram_power=1.0,
            deferred_views=("lbp",),
        )
        base.update(changes)
        return cls(**base)

    def replace(self, **changes) -> TrackerConfig:
        """A copy with some fields changed."""
        return replace(self, **changes)
