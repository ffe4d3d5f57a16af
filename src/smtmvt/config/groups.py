"""The groups of :class:`~smtmvt.config.TrackerConfig`, one per stage of the tracker.

Each field is one :func:`~smtmvt.config.checks.option` line: default, check (the valid
range, enforced and written into the group's docstring), doc (what and unit), and its flat
name where that differs (``correlation.weight`` is ``correlation_weight`` in the flat forms).
"docs/experiments.md#nN" is note [N] of the measurement log, "#f-NAME" the field's full entry
there. "paper X" is :meth:`TrackerConfig.paper`'s value where it differs from the default.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..solvers import METHODS, SOLVERS
from .checks import Choice, Flag, Group, Numbers, Real, Sizes, Views, Whole, group, invalid, option

__all__ = [
    "CodingConfig",
    "CorrelationConfig",
    "CuesConfig",
    "ExperimentalConfig",
    "FeaturesConfig",
    "MotionConfig",
    "ReportConfig",
    "TemplatesConfig",
]

_GATE = Numbers(2, ge=0)  # a learn gate's (b1, b2): two factors >= 0


@group("motion")
@dataclass(frozen=True)
class MotionConfig(Group):
    """The particle filter (:mod:`smtmvt.motion`): how many particles, how they move, and the
    wider search once the target seems lost."""

    n_particles: int = option(400, Whole(1, 10_000), "Particles (candidates) per frame (the paper's 400).")
    affine_std: tuple = option(
        (0.01, 0.0005, 0.0005, 0.01, 8.0, 8.0),
        Numbers(6, ge=0),
        "Stds of the random walk ``[a11, a12, a21, a22, tx, ty]``, translation in pixels times the\n"
        "target scale ``sc``: MTT's, scale and translation doubled (docs/experiments.md#f-affine_std).",
    )
    velocity: float = option(
        0.5, Real(0, 1), "Share of the last displacement added to each particle; paper 0 (docs/experiments.md#n7)."
    )
    redetect_after: int = option(
        10, Whole(0, 100_000), "Weak-peak frames before a wider search, 0 never; paper 0 (docs/experiments.md#n40)."
    )
    camera_motion: bool = option(
        True,
        Flag(),
        "Where the frame moved over half the box (phase correlation; or swings back after a move\n"
        "followed) and the filter seems lost at the prediction, the track moves with it if the\n"
        "filter peaks higher there (needs the correlation cue); paper False (docs/experiments.md#n60).",
    )


@group("features")
@dataclass(frozen=True)
class FeaturesConfig(Group):
    """The views each candidate is seen in (:mod:`smtmvt.features`) and how each frame's planes
    are sampled for them (:mod:`smtmvt.preprocess`)."""

    views: tuple = option(
        ("intensity", "color", "coarse", "hog", "lbp"),
        Views(empty=False),
        "The views; paper the four without ``coarse`` (docs/experiments.md#n29, #f-views).",
    )
    feature_size: tuple = option((32, 32), Sizes(8, 256), "Height, width (pixels) of the HOG, LBP and color patches.")
    frame_size: tuple | None = option(
        None,
        Sizes(16, 8_192, none=True),
        "Track on frames resized to ``(width, height)``, None as given; paper (320, 240).",
    )
    scale_normalize: bool = option(
        True, Flag(), "Planes at the target's first size; paper False (docs/experiments.md#f-scale_normalize)."
    )
    antialias: float = option(
        1.0, Real(ge=0), "Blur before sampling, in sampling steps; paper 0 (docs/experiments.md#n24)."
    )
    intensity_plane: str = option(
        "tan_triggs",
        Choice(("tan_triggs", "gray", "dog")),
        'The intensity view\'s plane; ``"dog"`` measured, not kept (docs/experiments.md#n28).',
    )
    hog_plane: str = option(
        "gray",
        Choice(("tan_triggs", "gray")),
        "The HOG view's plane; paper tan_triggs (docs/experiments.md#f-hog_plane).",
    )
    lbp_plane: str = option("gray", Choice(("tan_triggs", "gray")), "The LBP view's plane; paper tan_triggs.")
    color_grid: int = option(
        2, Whole(1, 16), "Cells per side of the color view's histograms; paper 1 (docs/experiments.md#n3)."
    )
    lbp_radius: float = option(
        1.0, Real(gt=0), "Radius of the LBP neighbours, patch pixels (docs/experiments.md#n21, #n22)."
    )
    histogram_power: float = option(
        0.5, Real(gt=0), "Power of the color and LBP histograms (0.5: Hellinger); paper 1 (docs/experiments.md#n6)."
    )
    crop_planes: bool = option(
        True, Flag(), "Planes on the candidates' window only, a speed setting; paper False (docs/experiments.md#n20)."
    )
    crop_context: float = option(
        3.0, Real(ge=1), "Box growth for Tan-Triggs' statistics at ``crop_refresh`` 0 (docs/experiments.md#n15)."
    )
    crop_refresh: int = option(
        10,
        Whole(0, 100_000),
        "Frames between whole planes for Tan-Triggs' divisors, 0 never; paper 0 (docs/experiments.md#n20).",
    )
    deferred_views: tuple = option(
        ("coarse", "hog", "lbp"),
        Views(empty=True),
        "Views computed only where the bounds need them, a speed setting; paper ('lbp',)\n"
        "(docs/experiments.md#n26, #f-deferred_views).",
    )


@group("coding")
@dataclass(frozen=True)
class CodingConfig(Group):
    """The observation model (:mod:`smtmvt.solvers`, :mod:`smtmvt.likelihood`): the candidates
    coded jointly over the templates, and the likelihood ``exp(-alpha * residual)``."""

    model: str = option(
        "smtmvt", Choice(SOLVERS), "The model, a key of :data:`smtmvt.solvers.SOLVERS` (docs/experiments.md#f-model)."
    )
    lam: float = option(0.1, Real(ge=0), "Weight of the per-candidate nuclear norm across views (paper: 0.1).")
    gamma: float = option(0.25, Real(ge=0), "Weight of the L1 penalties on C and E (paper: 0.25).")
    alpha: float = option(30.0, Real(gt=0), "Likelihood sharpness, ``p = exp(-alpha * residual)`` (paper: 30).")
    solver: str = option(
        "admm",
        Choice(METHODS),
        'SMTMVT\'s solver: ``"admm"`` (exact) or ``"paper"`` (the paper\'s subgradient step).',
        flat="solver",
    )
    tol: float = option(
        1e-3,
        Real(gt=0),
        "Relative change of the iterates at which the solver stops (docs/experiments.md#n12).",
        flat="solver_tol",
    )
    max_iter: int = option(200, Whole(1, 100_000), "Iteration cap of the solver.", flat="solver_max_iter")
    prune_eps: float = option(
        1e-3, Real(0, lt=1), "Bounded coding's tolerance, 0 codes every candidate (docs/experiments.md#f-prune_eps)."
    )


@group("cues")
@dataclass(frozen=True)
class CuesConfig(Group):
    """Terms the likelihood adds to each candidate's coded residual (the correlation term has
    its own group); each weight 0 turns its term off, as in the paper."""

    motion_weight: float = option(
        1.0, Real(ge=0), "Weight of the random walk's density of the step; paper 0 (docs/experiments.md#n27)."
    )
    anchor_weight: float = option(
        1.0,
        Real(ge=0),
        "Weight of :mod:`smtmvt.anchor`'s residual to the first template; paper 0 (docs/experiments.md#n11).",
    )
    foreground_weight: float = option(
        1.0,
        Real(ge=0),
        "Weight of :mod:`smtmvt.foreground`'s first-frame color model; paper 0 (docs/experiments.md#n16).",
    )
    term_views: tuple = option(
        ("intensity", "color", "hog"),
        Views(empty=True),
        "Views the anchor (and background) terms compare (docs/experiments.md#f-term_views).",
    )


@group("correlation")
@dataclass(frozen=True)
class CorrelationConfig(Group):
    """The correlation cue (:mod:`smtmvt.correlation`): a filter over gray and gradient-orientation
    cells learned online scores each candidate by its response and places particles at its peak."""

    weight: float = option(
        0.5, Real(ge=0), "Weight of the term, 0 off; paper 0 (docs/experiments.md#n32).", flat="correlation_weight"
    )
    particles: float = option(
        0.1,
        Real(0, 1),
        "Share of the particles placed about the response's peak; paper 0 (docs/experiments.md#n33, #n34).",
        flat="correlation_particles",
    )
    learn_gate: tuple = option(
        (0.7, 0.45),
        _GATE,
        "The filter learns where peak and APCE reach these times their means; paper (0, 0)\n"
        "(docs/experiments.md#n34, #n35).",
        flat="correlation_learn_gate",
    )
    rate: float = option(
        0.02, Real(gt=0, le=1), "The filter's learning rate (docs/experiments.md#n35).", flat="correlation_rate"
    )
    usual_peak: bool = option(
        True,
        Flag(),
        "Measure the term against the responses' mean peak before, not this frame's (False):\n"
        "measured better on both halves of docs/split.md (docs/experiments.md#n47).",
        flat="correlation_usual_peak",
    )


@group("templates")
@dataclass(frozen=True)
class TemplatesConfig(Group):
    """The target templates (:mod:`smtmvt.templates`): how many, and when one is replaced."""

    n_templates: int = option(10, Whole(1, 100), "Number of target templates N (paper: 10).")
    fixed_templates: int = option(1, Whole(1, 100), "The first templates, never replaced; at most ``n_templates``.")
    update_angle: float = option(
        60.0,
        Real(0, 180),
        "Degrees between the chosen candidate and its template, intensity view, above which one\n"
        "is replaced (docs/experiments.md#f-update_angle).",
    )
    occlusion_fraction: float = option(
        0.25, Real(0, 1), "Share of the intensity template flagged by E above which no template is replaced."
    )
    learn_gate: tuple = option(
        (0.7, 0.45),
        _GATE,
        "No template replaced where the correlation response fails this gate; paper (0, 0)\n(docs/experiments.md#n38).",
        flat="template_learn_gate",
    )
    learn_memory: int = option(
        20,
        Whole(0, 100_000),
        "Responses the gate compares with, 0 all (docs/experiments.md#n38).",
        flat="template_learn_memory",
    )
    learn_floor: float = option(
        0.4, Real(ge=0), "Least peak over its mean for the gate (docs/experiments.md#n38).", flat="template_learn_floor"
    )

    def _check_together(self) -> None:
        if self.fixed_templates > self.n_templates:
            raise invalid(
                "fixed_templates",
                self.fixed_templates,
                f"at most n_templates ({self.n_templates})",
                "templates.fixed_templates",
            )


@group("report")
@dataclass(frozen=True)
class ReportConfig(Group):
    """The box reported each frame (the tracking itself is unchanged by these)."""

    aspect: float = option(
        1.0,
        Real(0, 1),
        "How far the box's log aspect is moved to the first box's; paper 0 (docs/experiments.md#n23).",
        flat="report_aspect",
    )
    scale: float = option(
        1.03, Real(gt=0), "The box's sides times this; paper 1 (docs/experiments.md#n45).", flat="report_scale"
    )
    read_size: int = option(
        4,
        Whole(0, 10),
        "The box's size read by the correlation filter at its centre, the highest response over windows\n"
        "this many steps of 0.05 in log side each way; 0 off, paper 0 (docs/experiments.md#n64).",
        flat="report_read_size",
        neutral=0,
    )


@group("experimental")
@dataclass(frozen=True)
class ExperimentalConfig(Group):
    """Options measured and not kept: each default turns its option off (the tracker is then
    as without it). Their code stays, for the tests and ``bench/`` scripts that measure them;
    the figures are in the notes cited. Not part of the supported API: they may go."""

    translation_power: float = option(
        1.0,
        Real(0, 1),
        "Translation std ``affine_std[4:] * sc ** power``; 0.5 measured (docs/experiments.md#f-translation_power).",
    )
    aspect_std: float | None = option(
        None,
        Real(ge=0, none=True),
        "Std of the log aspect, None: a11, a22 apart (docs/experiments.md#n14, #f-aspect_std).",
    )
    velocity_fraction: float = option(
        1.0, Real(0, 1), "Share of the particles the velocity term moves (docs/experiments.md#n10)."
    )
    narrow_fraction: float = option(
        0.0, Real(0, 1), "Share of the particles drawn at ``narrow_scale`` times every std (docs/experiments.md#n5)."
    )
    narrow_scale: float = option(0.25, Real(gt=0), "See ``narrow_fraction``.")
    search_expand: float = option(
        1.0, Real(ge=1), "Most widening of the search after a bad frame, 1 off (docs/experiments.md#n14)."
    )
    shape_pull: float = option(
        0.0, Real(0, 1), "Pull of the particles' shape to the first box's (docs/experiments.md#n9)."
    )
    estimate: str = option(
        "best",
        Choice(("best", "mean")),
        'The state: the ``"best"`` particle or their weighted ``"mean"`` (docs/experiments.md#f-estimate).',
    )
    background_weight: float = option(
        0.0, Real(ge=0), "Weight of :mod:`smtmvt.background`'s term (docs/experiments.md#n13)."
    )
    background_samples: int = option(12, Whole(1, 1_000), "Boxes on the background ring.")
    background_measure: str = option(
        "nearest", Choice(("nearest", "nnls")), "The background term's ``b_i``: nearest box or NNLS."
    )
    correlation_first: float = option(
        0.0, Real(0, 1), "Share of the first box's filter in the correlation response (docs/experiments.md#n36)."
    )
    scale_push: float = option(
        0.0, Real(ge=0), "Weight of ``-log(s_i / s)``, toward larger boxes (docs/experiments.md#n42)."
    )
    scale_filter: float = option(
        0.0, Real(0, 1), "Share of the way to :mod:`smtmvt.scale`'s size (docs/experiments.md#n43)."
    )
    scale_refine: int = option(
        0,
        Whole(0, 10),
        "After the choice, the chosen centre scored at this many scale steps of the random walk's\n"
        "``affine_std[0]`` each way; the lowest cost gives the size, 0 off (docs/experiments.md#n61).",
    )
    correlation_scales: int = option(
        0,
        Whole(0, 5),
        "The correlation cue read at each candidate's size: responses over windows this many\n"
        "size steps each way of the prediction's, interpolated in log size; 0 off (docs/experiments.md#n62).",
    )
    correlation_scale_step: float = option(
        0.05, Real(gt=0, le=0.5), "Log side between those windows (docs/experiments.md#n62)."
    )
    cue_reliability: bool = option(
        False, Flag(), "Each cue's cost times its agreement with the choices (docs/experiments.md#n51)."
    )
    anchor_cos: float = option(
        -1.0,
        Real(-1, 1),
        "Least mean cosine to the first template for an update, -1 off (docs/experiments.md#f-anchor_cos).",
    )
    view_weights: tuple | None = option(
        None,
        Numbers(gt=0, none=True),
        "Weights of the views' residuals, one per view; None all 1 (docs/experiments.md#n1).",
    )
    update_margin: float | None = option(
        None,
        Real(ge=0, none=True),
        "Trigger at the first 10 frames' median angle plus this; None: ``update_angle`` (docs/experiments.md#n28).",
    )
    intensity_factor: float | None = option(
        None,
        Real(gt=0, none=True),
        "Intensity template px per box px; None the paper's rule (docs/experiments.md#n21).",
    )
    color_size: tuple | None = option(
        None,
        Sizes(2, 256, none=True),
        "The color patches' height, width, each >= ``color_grid``; None ``feature_size`` (docs/experiments.md#n12).",
    )
