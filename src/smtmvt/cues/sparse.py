"""The sparse cue: the paper's model, each candidate coded over the template dictionary.

The dictionary of each view holds ``config.n_templates`` templates: the first
box's views, then jittered copies (:meth:`SparseCue.start`); the template
update replaces the least used one when the chosen candidate has moved away
from them (:class:`smtmvt.templates.TemplateSet`). A candidate's cost is its
residual ``sum_k ||D^k c^k - x^k||^2`` under the observation model
(``config.model``: SMTMVT's joint sparse coding, or a baseline of
:mod:`smtmvt.solvers`).

Unlike the other cues, the sparse cue scores the candidates *given* the sum
of the others' costs (:meth:`SparseCue.observe`): its bounded coding
(:func:`smtmvt.likelihood.observe`) codes only the candidates whose
likelihood can matter, and the other costs enter its bounds. The views after
the first ones computed for every candidate are computed only where the
bounds need them (``config.deferred_views``, :class:`DeferredViews`), each
bringing the part of the other cues' costs that comes with it
(:meth:`smtmvt.cues.Cue.view_cost`).
"""

from __future__ import annotations

import functools

import numpy as np

from ..correlation import augment_warps
from ..geometry import affine_to_box, box_to_affine
from ..likelihood import Observation, observe
from ..solvers import BOUNDED_CODING, SOLVERS, solve_smtmvt
from ..solvers.bounds import range_basis
from ..templates import TemplateSet, UpdateDecision
from .base import Choice, Cue, Scene, Start

__all__ = ["SparseCue", "DeferredViews", "template_states", "UPDATE_FLOOR_FRAMES", "TEMPLATE_JITTER"]

#: Frames whose update angles set the trigger of ``config.update_margin``.
UPDATE_FLOOR_FRAMES = 10

#: Standard deviation of the template boxes' corner jitter, pixels (L1-APG).
TEMPLATE_JITTER = 0.6


def template_states(state: np.ndarray, n: int, seed: int | None, augment: bool = False) -> np.ndarray:
    """The ``n`` template states ``(n, 6)``: the exact ``state`` ``(6,)``, then
    ``n - 1`` copies whose box corners are moved by about N(0, 0.6^2) pixels
    (drawn from a generator of ``seed + 1``, not the tracker's).

    ``augment`` (``config.template_augment``): the copies are instead the state
    warped about its centre by MOSSE's first-frame perturbations
    (:func:`smtmvt.correlation.augment_warps` of ``seed + 1``: a rotation of up
    to 0.1 radian, each entry of the 2 x 2 warp then moved by up to 0.1),
    ``A' = W A`` on the state's 2 x 2 part, its centre kept."""
    states = np.repeat(state[None], n, axis=0)
    if n > 1 and augment:
        warps = augment_warps(n - 1, None if seed is None else seed + 1)
        a = np.asarray(state[:4], dtype=np.float64).reshape(2, 2)
        states[1:, :4] = (warps @ a).reshape(n - 1, 4)
        return states
    rng = np.random.default_rng(None if seed is None else seed + 1)
    if n > 1:
        x, y, w, h = affine_to_box(state)
        jit = rng.normal(0.0, TEMPLATE_JITTER, size=(n - 1, 4))
        boxes = np.array([x, y, w, h]) + jit
        boxes[:, 2:] = np.maximum(boxes[:, 2:], 1.0)
        states[1:] = box_to_affine(boxes)
    return states


class DeferredViews:
    """The views of one frame's candidates that are computed only where the
    bounded coding needs them (``config.deferred_views``): one stage per view
    for :func:`smtmvt.likelihood.observe`, each returning the view of some
    candidates (weighted) and the part of the ``cues``' costs that comes with
    it; the blocks computed are kept, so that any candidate's views can be
    read back."""

    def __init__(self, scene: Scene, cues: list) -> None:
        if scene.patches is None:
            raise ValueError("deferred views need the scene's patches")
        self._scene, self._patches, self._cues = scene, scene.patches, cues
        views = scene.sampler.config.views
        #: deferred view index k -> [(candidate indices, (d_k, m) view)], in the order computed
        self.blocks: dict[int, list] = {k: [] for k in range(len(scene.views), len(views))}

    def stages(self) -> list:
        """``observe``'s ``deferred``: one ``stage(idx) -> (view, offset)`` per deferred view."""
        return [functools.partial(self._compute, k) for k in self.blocks]

    def _compute(self, k: int, idx: np.ndarray):
        sampler = self._scene.sampler
        name = sampler.config.views[k]
        (view,) = sampler.extract(self._patches.subset(idx, sampler.reads.get(name)), [name])
        self.blocks[k].append((idx, view))
        (weighted,) = sampler.weighted([view], first=k)
        offset = None
        for cue in self._cues:
            part = cue.view_cost(self._scene, k, weighted)
            if part is not None:
                offset = part if offset is None else offset + part
        return weighted, offset

    def views_of(self, i: int) -> list:
        """The K views ``(d_k,)`` float32 of candidate i (a deferred one zero where not computed)."""
        out = [Xk[:, i] for Xk in self._scene.views]
        for k, computed in self.blocks.items():
            hits = [view[:, j] for idx, view in computed for j in np.flatnonzero(idx == i)]
            out.append(hits[0] if hits else np.zeros(self._scene.templates.dictionaries[k].shape[0], np.float32))
        return out


class SparseCue(Cue):
    """The template dictionary and the observation model's coding over it."""

    name = "sparse"
    stage = "update"

    def __init__(self, config) -> None:
        self.config = config
        self.templates: TemplateSet | None = None
        self.bases: list | None = None  # range_basis of each weighted dictionary, kept until a template changes
        self.first_angles: list[float] = []  # the update rule's angles on the first frames (update_margin)
        self.intensity_index = config.views.index("intensity") if "intensity" in config.views else None
        #: the last frame's observation and deferred views (:meth:`observe`), and template update (:meth:`learn`)
        self.obs: Observation | None = None
        self.deferred: DeferredViews | None = None
        self.decision: UpdateDecision | None = None

    @classmethod
    def from_config(cls, config, weight: float = 0.0) -> SparseCue:
        return cls(config)

    def start(self, start: Start) -> None:
        cfg, sampler = self.config, start.sampler
        states = template_states(start.state, cfg.n_templates, cfg.seed, cfg.template_augment)
        prepared = start.prepared
        if sampler.crop and not cfg.crop_refresh:  # the templates' planes as every later frame's
            channels = prepared.color.shape[2]
            where = "init frame"
            prepared = sampler.prepare(
                start.frame, where, channels, 1.0, states, box=start.work_box, state=start.state, frame_index=0
            )
        views = sampler.views(prepared, states, 1.0, start.work_box)
        self.templates = TemplateSet([np.array(v, dtype=np.float32) for v in views])

    def cost(self, scene: Scene) -> np.ndarray | None:
        """None: the sparse cue's cost is the residual of :meth:`observe`, which takes the others' as its offset."""
        return None

    def prune_eps(self, n: int) -> float:
        """Bounded coding's ``eps`` for n particles: 0 (code all) for models it is not exact for."""
        if self.config.model not in BOUNDED_CODING:
            return 0.0
        return min(self.config.prune_eps, 0.5 / n)

    def first_views(self, cues) -> int:
        """How many of ``config.views`` are computed for every candidate: all
        but the deferred ones at the end (``config.deferred_views``), which are
        computed only where the bounded coding needs them; a view some cue
        needs for every candidate (:meth:`~smtmvt.cues.Cue.eager_views`) is
        never deferred, nor any when every candidate is coded."""
        cfg = self.config
        n_first = len(cfg.views)
        eager = set().union(*(c.eager_views() for c in cues))
        while n_first > 0 and cfg.views[n_first - 1] in set(cfg.deferred_views) - eager:
            n_first -= 1
        return n_first if n_first > 0 and self.prune_eps(cfg.n_particles) > 0 else len(cfg.views)

    def code(self, X, D):
        """The observation model's solver on candidate views ``X`` (a subset of columns)."""
        cfg = self.config
        if cfg.model == "smtmvt":
            return solve_smtmvt(
                X, D, lam=cfg.lam, gamma=cfg.gamma, method=cfg.solver, tol=cfg.solver_tol, max_iter=cfg.solver_max_iter
            )
        return SOLVERS[cfg.model](X, D, tol=cfg.solver_tol, max_iter=cfg.solver_max_iter)

    def observe(self, scene: Scene, cues: list, offset, valid, timed=None) -> Observation:
        """Code the scene's candidates that can matter (:func:`smtmvt.likelihood.observe`)
        and their likelihoods ``exp(-alpha (residual + offset))``.

        ``cues`` are the other cues (their :meth:`~smtmvt.cues.Cue.view_cost`), ``offset``
        ``(n + m,)`` the sum of their costs (or None), ``valid`` (n + m,) bool
        the particles that may be chosen; the probes are coded whatever their
        bound and take no part in the rule.
        """
        assert self.templates is not None
        n = len(scene.particles)
        is_probe = np.arange(n + len(scene.probes)) >= n
        self.deferred = DeferredViews(scene, cues)
        sampler = scene.sampler
        dictionaries = sampler.weighted(self.templates.dictionaries)
        if self.bases is None:  # the templates changed
            self.bases = [range_basis(Dk) for Dk in dictionaries]
        self.obs = observe(
            sampler.weighted(scene.views),
            dictionaries,
            self.code,
            self.config.alpha,
            valid=valid & ~is_probe,
            eps=self.prune_eps(n),
            always=is_probe,
            timed=timed,
            deferred=self.deferred.stages(),
            bases=self.bases,
            offset=offset,
        )
        return self.obs

    def views_of(self, i: int) -> list:
        """The K views ``(d_k,)`` float32 of candidate i of the last :meth:`observe`."""
        assert self.deferred is not None
        return self.deferred.views_of(i)

    def update_angle(self) -> float:
        """The template update's trigger this frame, degrees: ``config.update_angle``,
        or with ``config.update_margin`` and once the first
        ``UPDATE_FLOOR_FRAMES`` frames are seen, the median of their angles plus
        the margin where that is lower."""
        margin = self.config.update_margin
        if margin is None or len(self.first_angles) < UPDATE_FLOOR_FRAMES:
            return self.config.update_angle
        return min(self.config.update_angle, float(np.median(self.first_angles)) + margin)

    def learn(self, scene: Scene, choice: Choice) -> None:
        """The template update from the chosen candidate of the last
        :meth:`observe` (no template replaced unless ``choice.confident``),
        recorded in :attr:`decision`."""
        assert self.templates is not None and self.obs is not None
        cfg, obs, best = self.config, self.obs, choice.best
        decision = self.templates.update(
            self.views_of(best),
            obs.C[:, :, best],
            [Ek[:, best] for Ek in obs.E],
            update_angle=self.update_angle() if choice.confident else np.inf,
            occlusion_fraction=cfg.occlusion_fraction,
            intensity_view=self.intensity_index,
            anchor_cos=cfg.anchor_cos,
            fixed=cfg.fixed_templates,
        )
        if len(self.first_angles) < UPDATE_FLOOR_FRAMES:
            self.first_angles.append(decision.angle)
        if decision.replaced is not None:
            self.bases = None  # a dictionary column changed: its range bases are recomputed
        self.decision = decision
