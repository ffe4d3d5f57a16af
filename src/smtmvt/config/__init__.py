"""Tracker configuration: :class:`TrackerConfig`, every parameter, grouped by stage.

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
(``report_aspect``), with its sides 1.03 times the state's
(``report_scale``) and at the size the correlation filter reads at its centre
(``report_read_size``; the tracking itself is unchanged by these) and in not resizing
frames to 320x240, the best configuration measured (fields named by their flat names).

How each default was chosen, the table of measured changes and the notes
[1] to [45] that the fields cite (mean average overlap over the 18
sequences of ``shared/data/otb`` and ``extra``, later 29 with the held-out
set, over the evaluation's seeds) are in ``docs/experiments.md``: a
field's "docs/experiments.md#nN" is the note [N] there.

The groups and their fields are declared in :mod:`smtmvt.config.groups` (each field's
default, check and doc on one line), with the checks of :mod:`smtmvt.config.checks`.
"""

from __future__ import annotations

import dataclasses
import difflib
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from .checks import CheckError, Whole, flat_name, invalid
from .groups import (
    CodingConfig,
    CorrelationConfig,
    CuesConfig,
    ExperimentalConfig,
    FeaturesConfig,
    MotionConfig,
    ReportConfig,
    TemplatesConfig,
)

__all__ = [
    "FLAT",
    "GROUPS",
    "CodingConfig",
    "CorrelationConfig",
    "CuesConfig",
    "ExperimentalConfig",
    "FeaturesConfig",
    "MotionConfig",
    "ReportConfig",
    "TemplatesConfig",
    "TrackerConfig",
]

#: The groups, in the tracker's order: ``TrackerConfig``'s field name -> its class.
GROUPS: dict[str, type[Any]] = {  # each a Group
    "motion": MotionConfig,
    "features": FeaturesConfig,
    "coding": CodingConfig,
    "cues": CuesConfig,
    "correlation": CorrelationConfig,
    "templates": TemplatesConfig,
    "report": ReportConfig,
    "experimental": ExperimentalConfig,
}
#: Every field's flat name -> ``(group, field)``: ``"correlation_weight" -> ("correlation", "weight")``.
FLAT: dict[str, tuple[str, str]] = {
    flat_name(f): (g, f.name) for g, cls in GROUPS.items() for f in dataclasses.fields(cls)
}
#: The fields of the run, not of a stage, and their checks.
_RUN = {"blas_threads": Whole(1, 1_024, none=True), "threads": Whole(1, 1_024, none=True), "seed": Whole(0, none=True)}
assert len(FLAT) == sum(len(dataclasses.fields(c)) for c in GROUPS.values())  # unique flat names
assert not set(FLAT) & {*_RUN, *GROUPS, *dir(object)}


@dataclass(frozen=True, init=False)
class TrackerConfig:
    """All parameters of :class:`smtmvt.Tracker`, grouped by the stage they set.

    ::

        from smtmvt.config import CorrelationConfig, TrackerConfig

        cfg = TrackerConfig(seed=0)                                  # the defaults
        cfg = TrackerConfig(correlation=CorrelationConfig(weight=0.25), seed=1)
        cfg.correlation.weight                                       # 0.25
        cfg = cfg.replace(correlation={"rate": 0.05})                # a copy, one field changed
        TrackerConfig.paper(seed=3)                                  # the paper's tracker

    Each group's ``help()`` lists its fields: what, unit, default, valid range and the
    evidence (``docs/experiments.md#nN``). A group given as None is its defaults; as a dict,
    its defaults (the current values in :meth:`replace`) with those fields changed.

    Attributes
    ----------
    motion : MotionConfig
        The particle filter: particles, random walk, velocity, the search after a loss.
    features : FeaturesConfig
        The views, and how each frame's planes are sampled for them.
    coding : CodingConfig
        The observation model: joint sparse coding, its solver, the likelihood's sharpness.
    cues : CuesConfig
        The likelihood's other terms: motion, anchor (first template), foreground.
    correlation : CorrelationConfig
        The correlation filter's term, its particles and its learning.
    templates : TemplatesConfig
        The target templates and when one is replaced.
    report : ReportConfig
        The box reported each frame (the tracking is unchanged by it).
    experimental : ExperimentalConfig
        Options measured and not kept, each off by default; they may go.
    blas_threads : a whole number from 1 to 1024 or None; default 1
        BLAS threads in the tracker, None: as set outside (docs/experiments.md#f-blas_threads).
    threads : a whole number from 1 to 1024 or None; default None
        Threads for the per-candidate work (the coding's per-candidate loops,
        :mod:`smtmvt.threads`); None: all the cores this process may use, or
        ``SMTMVT_THREADS`` where set (``smtmvt evaluate``'s workers set 1). The boxes
        are the same for every number of threads.
    seed : a whole number >= 0 or None; default 0
        Seed of the particle filter's random generator: the same seed gives the same boxes.

    Notes
    -----
    Flat names. Each field also has a name unique across the groups, its flat name: the
    field's own (``cues.anchor_weight`` is ``anchor_weight``) or, in four groups, with the
    prefix ``correlation_``, ``template_``, ``report_`` or ``solver_`` (``correlation.weight``
    is ``correlation_weight``, ``coding.tol`` is ``solver_tol``; the table is :data:`FLAT`).
    A flat name works wherever a field does: ``TrackerConfig(anchor_weight=2.0)``,
    ``cfg.replace(anchor_weight=2.0)``, ``TrackerConfig.paper(seed=3)``, the read
    ``cfg.anchor_weight`` (the tracker's), JSON (``TrackerConfig(**json.loads(text))``, flat
    keys or groups as ``{"correlation": {"weight": 0.25}}``) and ``smtmvt evaluate
    --tracker-option smtmvt:anchor_weight=2``. Flat keywords apply after the groups given.
    :meth:`to_flat` gives the flat dict, the form ``run.json`` records.

    Checks. Every value is checked when a configuration is made (a float where a whole
    number is due is refused, never rounded; tuples may come as JSON lists); a refused value
    raises ValueError naming the field, the value and what was expected::

        TrackerConfig: invalid correlation_weight=-1.0: expected a finite number >= 0 (correlation.weight)

    and an unknown name raises TypeError.
    """

    motion: MotionConfig
    features: FeaturesConfig
    coding: CodingConfig
    cues: CuesConfig
    correlation: CorrelationConfig
    templates: TemplatesConfig
    report: ReportConfig
    experimental: ExperimentalConfig
    blas_threads: int | None
    threads: int | None
    seed: int | None

    def __init__(
        self,
        *,
        motion: MotionConfig | Mapping | None = None,
        features: FeaturesConfig | Mapping | None = None,
        coding: CodingConfig | Mapping | None = None,
        cues: CuesConfig | Mapping | None = None,
        correlation: CorrelationConfig | Mapping | None = None,
        templates: TemplatesConfig | Mapping | None = None,
        report: ReportConfig | Mapping | None = None,
        experimental: ExperimentalConfig | Mapping | None = None,
        blas_threads: int | None = 1,
        threads: int | None = None,
        seed: int | None = 0,
        **flat: Any,
    ) -> None:
        given = dict(
            motion=motion,
            features=features,
            coding=coding,
            cues=cues,
            correlation=correlation,
            templates=templates,
            report=report,
            experimental=experimental,
        )
        changes: dict[str, dict[str, Any]] = {name: {} for name in GROUPS}
        for key, value in flat.items():
            if key not in FLAT:
                raise TypeError(f"TrackerConfig: unknown option {key!r}{_did_you_mean(key)}")
            name, field = FLAT[key]
            changes[name][field] = value
        for name, cls in GROUPS.items():
            object.__setattr__(self, name, _group(name, cls, given[name], changes[name]))
        # The flat names as plain attributes too: the tracker reads them each frame, at a
        # field's cost (through __getattr__ a read costs ten times as much).
        for key, (name, field) in FLAT.items():
            object.__setattr__(self, key, getattr(getattr(self, name), field))
        for key, value in (("blas_threads", blas_threads), ("threads", threads), ("seed", seed)):
            try:
                object.__setattr__(self, key, _RUN[key](value))
            except CheckError as exc:
                raise invalid(key, value, exc.expected) from None
        self._check_across_groups()

    def _check_across_groups(self) -> None:
        weights, views = self.experimental.view_weights, self.features.views
        if weights is not None and len(weights) != len(views):
            where = "experimental.view_weights"
            raise invalid("view_weights", weights, f"one positive number per view ({len(views)})", where)
        size, grid = self.experimental.color_size, self.features.color_grid
        if size is not None and min(size) < max(2, grid):
            raise invalid("color_size", size, f"sides of at least color_grid ({grid}) and 2", "experimental.color_size")

    def __getattr__(self, name: str) -> Any:
        """A field's flat name reads the field (``cfg.anchor_weight`` is ``cfg.cues.anchor_weight``;
        ``__init__`` stores them, this answers where it could not, e.g. ``object.__new__``)."""
        where = FLAT.get(name)
        if where is None:
            raise AttributeError(f"'TrackerConfig' object has no attribute {name!r}{_did_you_mean(name)}")
        return getattr(object.__getattribute__(self, where[0]), where[1])

    def replace(self, **changes: Any) -> TrackerConfig:
        """A copy with some fields changed: flat names, groups, or a group's fields as a dict
        (``cfg.replace(correlation={"weight": 0.25})`` keeps the group's other fields)."""
        kept: dict[str, Any] = {name: getattr(self, name) for name in (*GROUPS, *_RUN)}
        for name, value in changes.items():
            is_group_dict = name in GROUPS and isinstance(value, Mapping)
            kept[name] = _group(name, GROUPS[name], kept[name], dict(value)) if is_group_dict else value
        return type(self)(**kept)

    def to_flat(self) -> dict[str, Any]:
        """Every field by its flat name, in the groups' order, then ``blas_threads``, ``threads`` and ``seed``:
        ``TrackerConfig(**cfg.to_flat()) == cfg``; what ``run.json`` records."""
        values = {key: getattr(getattr(self, name), field) for key, (name, field) in FLAT.items()}
        return {**values, "blas_threads": self.blas_threads, "threads": self.threads, "seed": self.seed}

    @classmethod
    def paper(cls, **changes: Any) -> TrackerConfig:
        """The tracker as the paper describes it, with our documented choices where it is silent.

        Paper values: lambda 0.1, gamma 0.25, alpha 30, 400 particles, 10 templates, the four
        views, the exact solver of its model. Our choices where the paper is silent (measured
        in the first tracker issue): the random walk ``affine_std`` (MTT's with translation 8),
        the template update angle 60 degrees on the intensity view and occlusion fraction
        0.25 (L1T/L1-APG style rule). Frames are resized to 320x240 as in the paper's
        experiments. Every field is spelled out (in ``_PAPER``), so the defaults may move on
        without changing it. ``changes`` override fields as in :meth:`replace` (e.g. ``seed``).
        """
        return cls(**{name: GROUPS[name](**fields) for name, fields in _PAPER.items()}).replace(**changes)


def _group(name: str, cls: type[Any], given: Any, changes: dict[str, Any]) -> Any:
    """Group ``name`` (of class ``cls``) made from ``given`` (None, a dict or a ``cls``) and
    the field ``changes``."""
    if given is None or isinstance(given, Mapping):
        fields = {**(given or {}), **changes}
        unknown = sorted(set(fields) - {f.name for f in dataclasses.fields(cls)})
        if unknown:
            raise TypeError(f"TrackerConfig: unknown field {unknown[0]!r} of {name} ({cls.__name__})")
        return cls(**fields)
    if isinstance(given, cls):
        group: Any = given
        return dataclasses.replace(group, **changes) if changes else group
    raise TypeError(f"TrackerConfig: {name} must be a {cls.__name__} or a dict of its fields, got {given!r}")


def _did_you_mean(name: str) -> str:
    close = difflib.get_close_matches(name, [*FLAT, *GROUPS, *_RUN], n=3)
    return f" (did you mean {', '.join(repr(c) for c in close)}?)" if close else ""


#: :meth:`TrackerConfig.paper`'s every field, by group.
_PAPER: dict[str, dict[str, Any]] = {
    "motion": dict(
        n_particles=400,
        affine_std=(0.01, 0.0005, 0.0005, 0.01, 8.0, 8.0),
        velocity=0.0,
        redetect_after=0,
        camera_motion=False,
    ),
    "features": dict(
        views=("intensity", "color", "hog", "lbp"),
        feature_size=(32, 32),
        frame_size=(320, 240),
        scale_normalize=False,
        antialias=0.0,
        intensity_plane="tan_triggs",
        hog_plane="tan_triggs",
        lbp_plane="tan_triggs",
        color_grid=1,
        lbp_radius=1.0,
        histogram_power=1.0,
        crop_planes=False,
        crop_context=3.0,
        crop_refresh=0,
        deferred_views=("lbp",),
    ),
    "coding": dict(
        model="smtmvt", lam=0.1, gamma=0.25, alpha=30.0, solver="admm", tol=1e-3, max_iter=200, prune_eps=1e-3
    ),
    "cues": dict(motion_weight=0.0, anchor_weight=0.0, foreground_weight=0.0, term_views=("intensity", "color", "hog")),
    "correlation": dict(weight=0.0, particles=0.0, learn_gate=(0.0, 0.0), rate=0.02, usual_peak=False),
    "templates": dict(
        n_templates=10,
        fixed_templates=1,
        update_angle=60.0,
        occlusion_fraction=0.25,
        learn_gate=(0.0, 0.0),
        learn_memory=20,
        learn_floor=0.4,
    ),
    "report": dict(aspect=0.0, scale=1.0, read_size=0),
    "experimental": dict(
        translation_power=1.0,
        aspect_std=None,
        velocity_fraction=1.0,
        narrow_fraction=0.0,
        narrow_scale=0.25,
        search_expand=1.0,
        shape_pull=0.0,
        estimate="best",
        background_weight=0.0,
        background_samples=12,
        background_measure="nearest",
        correlation_first=0.0,
        scale_push=0.0,
        scale_filter=0.0,
        cue_reliability=False,
        anchor_cos=-1.0,
        view_weights=None,
        update_margin=None,
        intensity_factor=None,
        color_size=None,
    ),
}
