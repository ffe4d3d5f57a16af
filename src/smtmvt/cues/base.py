"""What a cue is: one term of the likelihood, with what it reads, scores and learns.

Every candidate ``i`` of a frame (the n particles, then the m probes of
:meth:`smtmvt.Tracker.update_detailed`) gets the likelihood

    ``p_i = exp(-alpha (r_i + sum_c cost_c(i)))``

``r_i`` the sparse cue's residual (the paper's: the candidate coded over the
template dictionary, :mod:`smtmvt.cues.sparse`), ``cost_c`` the cost of every
other cue ``c`` the configuration turns on, summed in the registry's order
(:data:`CUES`). A cue is a small object with four steps, all optional but
:meth:`Cue.cost`:

* :meth:`Cue.start` (a :class:`Start`): learn what it needs from the first
  frame and box;
* :meth:`Cue.cost` (a :class:`Scene`): the ``(n + m,)`` float64 cost of the
  frame's candidates, in the residual's units (it multiplies a likelihood by
  ``exp(-alpha cost)``; known before coding, it enters the bounded coding's
  bounds, :func:`smtmvt.likelihood.observe`), or None for none this frame;
* :meth:`Cue.view_cost`: the part of its cost that comes with a view computed
  late (``config.deferred_views``), for a cost that is a sum over the views;
* :meth:`Cue.learn` (the :class:`Scene` and the :class:`Choice`): update
  itself from the box chosen.

A cue is made from the configuration by its factory, ``factory(config,
weight) -> Cue | None`` (None: the cue is off), registered under its name
with :func:`register_cue`. The built-in cues read their weights from
:class:`~smtmvt.TrackerConfig` (``anchor_weight``, ...); a cue registered
from outside (a test's, an experiment's) gets ``weight`` from the tracker's
``cue_weights`` (``Tracker(config, cue_weights={"name": 2.0})``; 0 when not
given), so registering it changes no tracker that does not ask for it::

    class Rightward(Cue):
        name = "rightward"
        def __init__(self, weight): self.weight = weight
        def cost(self, scene):
            x = scene.states[:, 4]
            return self.weight * (x.max() - x)

    register_cue("rightward", lambda config, w: Rightward(w) if w else None)
    tracker = Tracker(config, cue_weights={"rightward": 0.1})

(``tests/test_cues.py`` does that.) A cue of the package is a module of
:mod:`smtmvt.cues` whose factory reads its weight from the configuration,
registered in ``smtmvt/cues/__init__.py``: the place of that line is its place
in the sum (the floats are added in that order; a cue that is off adds nothing,
so adding one changes no box of a configuration that leaves it off).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from ..config import TrackerConfig
    from ..features import Patches
    from ..preprocess import PreparedFrame
    from ..sampling import Sampler
    from ..templates import TemplateSet

__all__ = ["Cue", "Start", "Scene", "Choice", "CUES", "register_cue", "unregister_cue", "make_cues", "CueFactory"]


@dataclass(frozen=True)
class Start:
    """The first frame, as :meth:`Cue.start` sees it.

    Attributes
    ----------
    frame : the input frame as given ((H, W) or (H, W, 3)).
    box : (4,) float64 the first box ``(x, y, w, h)``, input-frame pixels.
    work_box : (4,) float64 the same box in the working frame.
    state : (6,) float64 its affine state (working frame).
    prepared : the whole frame's planes (working frame, plane scale 1).
    sampler : the :class:`~smtmvt.sampling.Sampler` of the track.
    rng : the tracker's seeded generator (draw from it only in :meth:`Cue.start`
        and :meth:`Cue.learn`: the order of the draws is part of the boxes).
    """

    frame: np.ndarray
    box: np.ndarray
    work_box: np.ndarray
    state: np.ndarray
    prepared: PreparedFrame
    sampler: Sampler
    rng: np.random.Generator


@dataclass
class Scene:
    """One frame's candidates and the track before them, as the cues see them.

    States are affine ``(6,)`` rows in the working frame
    (:mod:`smtmvt.geometry`); the candidates are the n particles, then the m probes.

    Attributes
    ----------
    frame : the input frame as given.
    index : its index since :meth:`smtmvt.Tracker.init`.
    particles : (n, 6) float64 the particles.
    probes : (m, 6) float64 the probes (m may be 0).
    prepared : the planes the particles were sampled on (a crop with
        ``config.crop_planes``; :mod:`smtmvt.sampling`).
    probe_planes : those of the probes (``prepared`` itself unless cropped).
    plane_scale : plane pixels per working-frame pixel.
    state : (6,) the last frame's state; ``box`` (4,) its box (working frame).
    predicted : (6,) this frame's prediction (``state`` moved by the velocity term).
    steps : ``(predicted (n, 2), std (n, 2))``: each particle's own predicted
        translation and the random walk's standard deviation there
        (:func:`smtmvt.motion.translation_distance`).
    patches : the candidates' :class:`~smtmvt.features.Patches` (for views computed late).
    views : the views computed for every candidate: the first ``len(views)`` of
        ``config.views``, ``(d_k, n + m)`` float32, not weighted (the others
        are deferred: :meth:`Cue.view_cost`).
    sampler : the track's :class:`~smtmvt.sampling.Sampler`.
    templates : the sparse cue's :class:`~smtmvt.templates.TemplateSet` (its
        first template is the first frame's target).
    response : the correlation filter's ``(response, Window)`` this frame, or
        None without it (:mod:`smtmvt.cues.correlation`).
    judged : that response judged against those before
        (:meth:`smtmvt.correlation.CorrelationFilter.judge`), or None.
    rng : the tracker's seeded generator (draw from it only in :meth:`Cue.learn`:
        the order of the draws is part of the boxes).
    """

    frame: np.ndarray
    index: int
    particles: np.ndarray
    probes: np.ndarray
    prepared: PreparedFrame
    probe_planes: PreparedFrame
    plane_scale: float
    state: np.ndarray
    box: tuple
    predicted: np.ndarray
    steps: tuple
    views: list
    sampler: Sampler
    templates: TemplateSet
    response: tuple | None = None
    judged: tuple | None = None
    patches: Patches | None = None
    rng: np.random.Generator | None = None

    @functools.cached_property
    def states(self) -> np.ndarray:
        """(n + m, 6) the particles followed by the probes."""
        return np.concatenate([self.particles, self.probes])

    @functools.cached_property
    def term_views(self) -> list:
        """The term views (``config.term_views``) among :attr:`views`, weighted
        by ``config.view_weights`` (:meth:`smtmvt.sampling.Sampler.terms_of`)."""
        return self.sampler.terms_of(self.views)


@dataclass(frozen=True)
class Choice:
    """The frame's outcome, as :meth:`Cue.learn` sees it.

    Attributes
    ----------
    best : index of the chosen particle (:meth:`Cue.learn` is called only
        for a frame with a valid candidate).
    confident : whether the appearance may be learned from this frame (the
        correlation filter's ``config.template_learn_gate``; the sparse cue
        replaces no template otherwise).
    state : (6,) the new state; ``work_box`` (4,) its box (working frame).
    box : (4,) the box reported (input frame).
    likelihood : (n + m,) the candidates' likelihoods.
    """

    best: int
    confident: bool
    state: np.ndarray
    work_box: tuple
    box: tuple
    likelihood: np.ndarray


class Cue:
    """One term of the likelihood (see the module docstring). Subclasses set
    :attr:`name` and define :meth:`cost`; the other steps do nothing here.

    Class attributes a cue may set, for what it reads of the frame:

    * ``whole_frame``: it reads the planes beyond the candidates' boxes (the
      planes are then never cropped, ``config.crop_planes``);
    * ``reach``: it reads the planes this many times each candidate's box
      about its centre (the crop is grown to hold them);
    * :meth:`eager_views`: views it needs for every candidate (never deferred).
    """

    name: str = ""
    whole_frame: bool = False
    reach: float = 1.0
    #: the stage of :attr:`smtmvt.Tracker.timings` its learning is counted in
    stage: str = "likelihood"

    def eager_views(self) -> tuple:
        """Names of the views this cue needs for every candidate."""
        return ()

    def start(self, start: Start) -> None:
        """Learn from the first frame (nothing by default)."""

    def cost(self, scene: Scene) -> np.ndarray | None:
        """``(n + m,)`` float64 cost of the scene's candidates, or None for none."""
        raise NotImplementedError

    def view_cost(self, scene: Scene, k: int, view: np.ndarray) -> np.ndarray | None:
        """The part of the cost of some candidates that comes with their view
        ``k`` of ``config.views``, computed late (weighted, ``(d_k, m')``):
        ``(m',)`` float64, or None (by default: the cost does not depend on it)."""
        return None

    def learn(self, scene: Scene, choice: Choice) -> None:
        """Learn from the frame's choice (nothing by default)."""


#: ``factory(config, weight) -> Cue | None``.
CueFactory = Callable[["TrackerConfig", float], "Cue | None"]

#: The registered cues, in the order their costs are summed: name -> factory.
CUES: dict[str, CueFactory] = {}

#: The names of the cues the package defines (weighted by the configuration).
BUILT_IN: set[str] = set()


def register_cue(name: str, factory: CueFactory, *, built_in: bool = False) -> None:
    """Register ``factory`` under ``name`` (after the cues registered before).

    ``factory(config, weight)`` returns the cue for a tracker of ``config``,
    or None when it is off; ``weight`` is ``Tracker(cue_weights=...)``'s entry
    for ``name`` (0 when absent; the built-in cues read the configuration
    instead). Registering a name again replaces its factory in place.
    """
    if not name or not isinstance(name, str):
        raise ValueError(f"a cue's name must be a non-empty str, got {name!r}")
    CUES[name] = factory
    if built_in:
        BUILT_IN.add(name)


def unregister_cue(name: str) -> None:
    """Remove the cue ``name`` (a built-in one cannot be removed)."""
    if name in BUILT_IN:
        raise ValueError(f"{name!r} is a built-in cue: turn it off in the configuration")
    del CUES[name]


def make_cues(config: TrackerConfig, cue_weights: dict[str, Any] | None = None) -> list[Cue]:
    """The cues ``config`` (and ``cue_weights``, for cues registered outside
    the package) turns on, in the registry's order."""
    weights = dict(cue_weights or {})
    unknown = set(weights) - set(CUES)
    if unknown:
        raise ValueError(f"cue_weights: no cue named {sorted(unknown)} (registered: {list(CUES)})")
    given = set(weights) & BUILT_IN
    if given:
        raise ValueError(f"cue_weights: {sorted(given)} are weighted by the configuration, not cue_weights")
    cues = []
    for name, factory in CUES.items():
        cue = factory(config, float(weights.get(name, 0.0)))
        if cue is not None:
            cues.append(cue)
    return cues
