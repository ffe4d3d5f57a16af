"""The SMTMVT tracker: an orchestrator of the cues, frame after frame.

Each frame, one step per module::

    predict  particles: the last frame's resampled and moved by the random walk
             (smtmvt.particles), some placed at the correlation peak (cues.correlation)
    sample   the frame's planes about them, the candidates' patches and views (smtmvt.sampling)
    score    p_i = exp(-alpha (r_i + sum_c cost_c(i))): r_i the sparse cue's residual over
             the templates (cues.sparse, the paper's), cost_c each other cue's (smtmvt.cues)
    choose   the best candidate (or the mean), its scale moved toward the scale filter's
    learn    each cue learns from the choice (the templates, the background, the filter)

The paper's tracker (``TrackerConfig.paper()``) is the sparse cue alone; the
default adds the anchor, motion, foreground and correlation cues.

Usage (like OpenCV's trackers)::

    tracker = Tracker(TrackerConfig(seed=0))
    tracker.init(first_frame, (x, y, w, h))      # 0-based pixels
    for frame in frames:
        result = tracker.update(frame)           # TrackResult
        x, y, w, h = result.box
"""

from __future__ import annotations

import dataclasses
from collections import defaultdict
from contextlib import contextmanager, nullcontext
from functools import partial
from typing import Any

import numpy as np
from threadpoolctl import ThreadpoolController

from .anchor import anchor_residuals
from .camera import CameraMotion
from .confidence import LOST_BELOW, confidence
from .config import TrackerConfig
from .cues import Choice, CorrelationCue, Cue, Scene, SparseCue, Start, make_cues
from .geometry import affine_scale, affine_to_box, box_inside_fraction, box_to_affine, checked_box
from .likelihood import Observation
from .particles import ParticleFilter
from .preprocess import PreparedFrame, check_same_size
from .reliability import Reliability, Scaled
from .results import FrameDetail, TrackResult, reshaped_box
from .results import evidence as frame_evidence
from .sampling import Sampler
from .scale import ScaleFilter
from .threads import limit as threads_limit
from .timing import StageTimer
from .warp import inside_fraction

__all__ = ["Tracker", "TrackResult", "FrameDetail", "track_frames"]


class Tracker:
    """SMTMVT tracker (Javanmardi & Qi, ICME 2018).

    Parameters
    ----------
    config : TrackerConfig, optional
        All parameters; the paper's defaults when omitted.
    cue_weights : dict, optional
        ``{name: weight}`` for cues registered outside the package
        (:func:`smtmvt.cues.register_cue`); the built-in cues are weighted by
        ``config``.
    **overrides
        Shorthand for ``config.replace(**overrides)``.
    """

    def __init__(self, config: TrackerConfig | None = None, cue_weights: dict | None = None, **overrides):
        config = config or TrackerConfig()
        self.config = config.replace(**overrides) if overrides else config
        self._cue_weights = dict(cue_weights or {})
        make_cues(self.config, self._cue_weights)  # refuse unknown names now, not at init
        self._initialized = False
        self._timer = StageTimer()
        self._threadpools = ThreadpoolController() if self.config.blas_threads else None

    @property
    def cues(self) -> tuple[Cue, ...]:
        """The cues of the track (after :meth:`init`; the sparse cue first)."""
        if not self._initialized:
            raise RuntimeError("tracker not initialized")
        return (self._sparse, *self._others)

    @contextmanager
    def _blas_limit(self):
        """The block with ``config.blas_threads`` BLAS threads and ``config.threads``
        threads for the per-candidate work (:func:`smtmvt.threads.limit`)."""
        pools = self._threadpools
        blas = nullcontext() if pools is None else pools.limit(limits=self.config.blas_threads, user_api="blas")
        with blas, threads_limit(self.config.threads):
            yield

    def _timed(self, stage: str):
        """A block of ``stage`` timed in :attr:`timings` (:meth:`StageTimer.timed`)."""
        return self._timer.timed(stage)

    @property
    def timings(self) -> defaultdict[str, float]:
        """Seconds spent per stage since the last :meth:`init` (for ``bench/``)."""
        return self._timer.seconds

    # -- public API --------------------------------------------------------
    def init(self, frame: np.ndarray, box) -> None:
        """Start tracking the object in ``box`` of ``frame``.

        Parameters
        ----------
        frame : (H, W) or (H, W, 3) RGB image, uint8 / uint16 / float.
        box : (x, y, w, h) 0-based pixels; w and h must be positive and at
            least a quarter of the box must lie inside the frame.

        Calling ``init`` again re-initializes the tracker on a new target.
        """
        with self._blas_limit():
            self._init(frame, box)

    def reinit(self, frame: np.ndarray, box) -> None:
        """Restart tracking from ``box`` of ``frame`` (say, after ``TrackResult.lost``,
        from a detector's box), without building a new tracker.

        ``frame`` and ``box`` are as for :meth:`init` (the frame may have another
        size). Everything learned is dropped: the target state, the particles
        and the velocity, the cues (the templates, the correlation filter and
        its response history, the foreground model, ...), the scale filter,
        the lost streak, the costs ``confidence`` compares with, the frame
        count and ``timings``; the random generator is seeded again from
        ``config.seed``. Kept: the config, the BLAS thread-pool controller and
        the numba kernels (compiled once per process). So the boxes that
        follow are those of a new ``Tracker(config)`` started with
        ``init(frame, box)``. A refused ``box`` raises ValueError as
        :meth:`init`'s does.
        """
        self.init(frame, box)

    def update(self, frame: np.ndarray) -> TrackResult:
        """Track the target into ``frame``; returns a :class:`TrackResult`.

        ``frame`` must have the height and width of ``init``'s frame (boxes refer to
        one pixel grid): another size is a ValueError naming both, and the tracker's
        state is left as it was.
        """
        with self._blas_limit():
            return self._update(frame)[0]

    def update_detailed(self, frame: np.ndarray, probes=None) -> tuple[TrackResult, FrameDetail]:
        """:meth:`update`, also returning what was computed (:class:`FrameDetail`).

        ``probes`` : optional (m, 4) 0-based boxes ``(x, y, w, h)`` scored as extra
        candidates of this frame (for example the ground truth, in
        ``bench/diagnose.py``). They are coded like the particles but take no
        part in the choice, the resampling or the template update, so the
        tracker's state is the same as without them.
        """
        with self._blas_limit():
            return self._update(frame, probes)

    @property
    def box(self) -> tuple:
        """Current box ``(x, y, w, h)``, 0-based pixels."""
        if not self._initialized:
            raise RuntimeError("tracker not initialized")
        return self._box

    # -- init ----------------------------------------------------------------
    def _init(self, frame: np.ndarray, box) -> None:
        b = checked_box(box, "init")
        cfg = self.config
        self._frame_index = 0
        shape = np.shape(frame)
        if cfg.frame_size is None or len(shape) < 2:
            self._scale = np.ones(2)
        else:
            self._scale = np.array([cfg.frame_size[0] / shape[1], cfg.frame_size[1] / shape[0]])
        wb = self._to_work(b)
        cues = make_cues(cfg, self._cue_weights)
        # planes computed on the candidates' window only, unless a cue reads beyond it
        crop = bool(cfg.crop_planes and not any(c.whole_frame for c in cues))
        grow = max([1.0, *(c.reach for c in cues)])
        self._sampler = Sampler(cfg, self._scale, wb, crop, grow, self._timed)
        prepared = self._sampler.prepare(frame, "init frame", None, 1.0, None, box=wb, state=None, frame_index=0)
        self._frame_shape = (int(shape[0]), int(shape[1]))
        self._channels = prepared.color.shape[2]
        inside = box_inside_fraction(wb, prepared.shape)
        if inside < 0.25:
            raise ValueError(
                f"init: box {tuple(b.tolist())} is mostly outside the {shape[1]}x{shape[0]} image ({inside:.0%} inside)"
            )
        self._timer = StageTimer()
        self._rng = np.random.default_rng(cfg.seed)
        self._state = box_to_affine(wb)
        self._init_state = self._state.copy()
        self._motion = ParticleFilter(cfg, self._state)
        self._work_box = tuple(float(v) for v in wb)
        self._box = tuple(float(v) for v in b)
        # the scale filter (config.scale_filter), on the frame as given
        self._scaler = ScaleFilter(frame, b) if cfg.scale_filter else None
        start = Start(frame, b, wb, self._state, prepared, self._sampler, self._rng)
        for cue in cues:
            cue.start(start)
        self._sparse = next(c for c in cues if isinstance(c, SparseCue))  # always on
        self._others = [c for c in cues if c is not self._sparse]
        self._corr = next((c for c in cues if isinstance(c, CorrelationCue)), None)
        self._n_first = self._sparse.first_views(cues)
        self._lost = 0  # frames in a row the target seemed lost (config.redetect_after)
        self._costs: list[float] = []  # the chosen candidates' costs (TrackResult.confidence)
        self._reliability = Reliability(len(self._others)) if cfg.cue_reliability else None
        # config.camera_motion (it asks the correlation filter)
        self._camera = CameraMotion(frame) if cfg.camera_motion and self._corr is not None else None
        self._initialized = True

    # -- the working frame (config.frame_size) and its planes -----------------
    def _prepare(self, frame, where: str, channels, plane_scale: float = 1.0, states=None) -> PreparedFrame:
        """The frame's planes (:meth:`smtmvt.sampling.Sampler.prepare`, about the current state)."""
        track: dict[str, Any] = {"box": self._work_box, "state": self._state, "frame_index": self._frame_index}
        return self._sampler.prepare(frame, where, channels, plane_scale, states, **track)

    def _plane_scale(self) -> float:
        """Plane pixels per working pixel for the next frame (``config.scale_normalize``)."""
        if not self.config.scale_normalize:
            return 1.0
        s = float(affine_scale(self._init_state)[0] / affine_scale(self._state)[0])
        return float(np.clip(s, 0.25, 4.0))

    def _to_work(self, boxes) -> np.ndarray:
        """0-based boxes of the input frame -> of the working frame."""
        return np.asarray(boxes, dtype=np.float64) * np.tile(self._scale, 2)

    def _from_work(self, boxes) -> np.ndarray:
        """0-based boxes of the working frame -> of the input frame."""
        return np.asarray(boxes, dtype=np.float64) / np.tile(self._scale, 2)

    # -- one frame -----------------------------------------------------------
    def _update(self, frame: np.ndarray, probes=None):
        """One frame: predict, sample, score, choose, learn."""
        if not self._initialized:
            raise RuntimeError("update called before init")
        check_same_size(frame, f"frame {self._frame_index + 1}", self._frame_shape)
        self._frame_index += 1
        rng_state = self._rng.bit_generator.state
        probe_boxes = np.zeros((0, 4)) if probes is None else np.asarray(probes, dtype=np.float64).reshape(-1, 4)
        probe_states = box_to_affine(self._to_work(probe_boxes)).reshape(-1, 6)
        kept = (self._state, self._work_box, self._box, self._motion.particles)
        try:
            response = self._response(frame)
            particles = self._propagate(response)
            planes = self._planes(frame, particles, probe_states)
        except Exception:
            # a frame that cannot be read leaves the tracker as it was
            self._rng.bit_generator.state = rng_state
            self._frame_index -= 1
            self._state, self._work_box, self._box, self._motion.particles = kept
            if self._camera is not None:
                self._camera.dropped()
            raise
        if self._camera is not None:
            self._camera.taken()
        scene = self._sample(frame, particles, probe_states, planes, response)
        obs, costs = self._score(scene)
        result, detail = self._choose(scene, obs, probe_boxes, costs)
        if self._reliability is not None and detail.best is not None:
            self._reliability.observe(costs, detail.best)  # read from the next frame on
        corr = self._corr
        self._lost = self._lost + 1 if corr is not None and corr.seems_lost(scene.judged) else 0
        drift = self._drift(detail.best_views)
        evidence = frame_evidence(result.score, scene.judged, self._costs, self._lost, self.config.alpha, drift)
        c = confidence(evidence)
        return dataclasses.replace(result, confidence=c, lost=c < LOST_BELOW, evidence=evidence), detail

    def _drift(self, views) -> float:
        """The chosen candidate's residual over the first frame's template alone,
        summed over its ``views`` (:func:`smtmvt.anchor.anchor_residuals`; 0 for None)."""
        if views is None:
            return 0.0
        assert self._sparse.templates is not None
        first = [Dk[:, 0] for Dk in self._sparse.templates.dictionaries]
        return float(anchor_residuals([v[:, None] for v in views], first)[0])

    def _response(self, frame) -> tuple | None:
        """The correlation filter's response about this frame's prediction,
        ``(response (h, w), Window)`` (:meth:`CorrelationCue.respond`), or None
        without the correlation cue."""
        if self._corr is None:
            return None
        with self._timed("likelihood"):
            box = self._from_work(affine_to_box(self._motion.predicted(self._state)))
            response = self._corr.respond(frame, box, self._lost)
            if self._camera is not None:
                response = self._camera_response(frame, box, response)
            return response

    def _camera_response(self, frame, box, response: tuple) -> tuple:
        """``config.camera_motion``: the filter's response about the prediction
        ``box`` moved by each of the camera's hypotheses
        (:meth:`smtmvt.camera.CameraMotion.hypotheses`: its move since the last
        frame where it exceeds half the box, then the last frame's followed move
        undone); at the first the filter prefers (:meth:`CorrelationCue.prefers`:
        the prediction's response fails the learn gate and the moved one's peak
        is higher), the track (state, boxes, particles) moves by it and that
        response is returned, else ``response``."""
        assert self._corr is not None and self._corr.filter is not None and self._camera is not None
        hypotheses = self._camera.hypotheses(frame, box)  # (also keeps this frame for the next)
        if self._corr.redetected:
            return response
        for shift in hypotheses:
            moved = np.asarray(box, dtype=np.float64) + np.array([shift[0], shift[1], 0.0, 0.0])
            other = self._corr.filter.response(frame, moved, self.config.correlation_first)
            if self._corr.prefers(response, other):
                self._move_track(shift)
                self._camera.follow(shift)
                return other
        return response

    def _move_track(self, shift: np.ndarray) -> None:
        """Move the state, the particles and the boxes by ``shift`` (input-frame pixels)."""
        d = shift * self._scale  # working-frame pixels
        self._state = self._state.copy()
        self._state[4:] += d
        self._motion.particles = self._motion.particles.copy()
        self._motion.particles[:, 4:] += d
        self._work_box = tuple(float(v) for v in affine_to_box(self._state))
        self._box = tuple(float(v) for v in np.asarray(self._box) + np.array([shift[0], shift[1], 0.0, 0.0]))

    def _propagate(self, response=None) -> np.ndarray:
        """Predict: this frame's ``(n, 6)`` particles (:meth:`ParticleFilter.propagate`),
        with the correlation filter's ``response`` some placed about its peak
        (:meth:`CorrelationCue.place`)."""
        proposal = None if response is None or self._corr is None else partial(self._corr.place, response=response)
        with self._timed("motion"):
            return self._motion.propagate(self._rng, proposal)

    def _planes(self, frame, particles: np.ndarray, probes: np.ndarray) -> tuple:
        """``(prepared, probe_planes, plane_scale)``: the frame's planes about the
        particles, and the probes' (the same planes, or on a crop their own, so
        that they do not move the particles' window)."""
        plane_scale = self._plane_scale()
        where = f"frame {self._frame_index}"
        with self._timed("preprocess"):
            prepared = self._prepare(frame, where, self._channels, plane_scale, particles)
            probe_planes = prepared
            if len(probes) and prepared.full_shape is not None:
                probe_planes = self._prepare(frame, where, self._channels, plane_scale, probes)
        return prepared, probe_planes, plane_scale

    def _sample(self, frame, particles: np.ndarray, probes: np.ndarray, planes: tuple, response) -> Scene:
        """Sample: the candidates' patches on their ``planes`` (:meth:`_planes`)
        and the views computed for all of them, with the correlation response
        judged (:meth:`CorrelationCue.judge`), as a :class:`Scene`."""
        prepared, probe_planes, plane_scale = planes
        judged = None if self._corr is None else self._corr.judge(response)
        sampler = self._sampler
        patches = sampler.patches(prepared, particles, plane_scale, self._work_box)
        if len(probes):
            patches = patches.joined(sampler.patches(probe_planes, probes, plane_scale, self._work_box))
        # the views computed for every candidate; the deferred ones as the bounds need them
        X = sampler.extract(patches, self.config.views[: self._n_first])
        motion = self._motion
        assert self._sparse.templates is not None and motion.steps is not None
        return Scene(
            frame=frame, index=self._frame_index, particles=particles, probes=probes, prepared=prepared,
            probe_planes=probe_planes, plane_scale=plane_scale, state=self._state, box=self._work_box,
            predicted=motion.predicted(self._state), steps=motion.steps, views=X, sampler=sampler,
            templates=self._sparse.templates, response=response, judged=judged, patches=patches, rng=self._rng,
        )  # fmt: skip

    def _score(self, scene: Scene) -> tuple[Observation, list]:
        """Score: each cue's cost summed in the cues' order (a cue off adds
        nothing), then the sparse cue's bounded coding with that sum as offset.
        Returns the observation and the other cues' costs as they gave them
        (before ``config.cue_reliability``'s factors; None for a cue with none)."""
        with self._timed("likelihood"):
            costs = [cue.cost(scene) for cue in self._others]
            terms: list = costs
            others: list = self._others
            if self._reliability is not None:
                # each cue's cost times its reliability (config.cue_reliability)
                factors = self._reliability.factors()
                terms = [None if c is None else c * f for c, f in zip(costs, factors)]
                others = [Scaled(cue, f) for cue, f in zip(self._others, factors)]
            offset = None
            for cost in terms:
                if cost is not None:
                    offset = cost if offset is None else offset + cost
        # A candidate mostly outside the image is not a valid observation.
        with self._timed("motion"):
            full, s = scene.prepared.plane_shape, scene.plane_scale
            work_shape = (int(round(full[0] / s)), int(round(full[1] / s)))
            valid = inside_fraction(scene.states, work_shape) >= 0.5
        return self._sparse.observe(scene, others, offset, valid, self._timed), costs

    def _choose(self, scene: Scene, obs: Observation, probe_boxes, costs: list) -> tuple[TrackResult, FrameDetail]:
        """Choose and learn: the best particle (or their mean), its scale refined
        (:meth:`_refined_scale`) or moved toward the scale filter's
        (:meth:`ScaleFilter.rescale`) where configured; then every cue learns
        from it (the sparse cue's template update first) and the next frame's
        resampling weights are set. ``costs``: the other cues' costs (:meth:`_score`),
        kept in the :class:`FrameDetail`."""
        cfg = self.config
        cue_costs = {cue.name: c for cue, c in zip(self._others, costs)}
        particles = scene.particles
        p = obs.likelihood[: len(particles)]
        reshape = self._reshape()
        if not np.any(p > 0):
            # Nothing explains the frame: keep the previous state (no NaN ever leaves).
            self._motion.keep(self._state)
            result = TrackResult(self._box, 0.0, float("inf"), True, None, self._frame_index)
            return result, FrameDetail(particles, obs, None, probe_boxes, self._scale, None, reshape, cue_costs)
        best = int(np.argmax(p))
        corr = self._corr
        confident = corr is None or corr.templates_learn(scene.judged, particles[best], scene.response)
        state = (p / p.sum()) @ particles if cfg.estimate == "mean" else particles[best].copy()
        if cfg.scale_refine:  # (its stages time themselves)
            particles = _resized(state, particles, self._refined_scale(scene, best))
        if self._scaler is not None:
            with self._timed("likelihood"):
                chosen = self._from_work(reshaped_box(affine_to_box(state), reshape))
                factor = self._scaler.rescale(scene.frame, chosen, self._box, cfg.scale_filter)
            particles = _resized(state, particles, factor)
        velocity = np.zeros(2) if corr is not None and corr.redetected else state[4:] - self._state[4:]
        self._motion.chosen(particles, p, velocity, float(obs.residual[best]))
        self._state = state
        self._work_box = tuple(float(v) for v in affine_to_box(self._state))
        self._box = tuple(float(v) for v in self._from_work(reshaped_box(self._work_box, reshape)))
        if self._scaler is not None and (corr is None or corr.learns(scene.judged, state, scene.response)):
            with self._timed("likelihood"):
                self._scaler.update(scene.frame, self._box)
        if cfg.report_read_size and corr is not None:  # the reported box only: the track is as without it
            with self._timed("likelihood"):
                self._box = tuple(float(v) for v in corr.read_size(scene.frame, self._box))
        choice = Choice(best, confident, state, self._work_box, self._box, obs.likelihood)
        for cue in self.cues:
            with self._timed(cue.stage):
                cue.learn(scene, choice)
        decision = self._sparse.decision
        assert decision is not None
        score, residual = float(p[best]), float(obs.residual[best])
        result = TrackResult(self._box, score, residual, decision.occluded, decision.replaced, self._frame_index)
        best_views = [v.copy() for v in self._sparse.views_of(best)]
        return result, FrameDetail(particles, obs, best, probe_boxes, self._scale, best_views, reshape, cue_costs)

    def _refined_scale(self, scene: Scene, best: int) -> float:
        """``config.scale_refine``: the factor on the chosen particle's size, among
        ``exp(j * affine_std[0])`` for ``|j| <= scale_refine``, whose box at its centre
        costs least (the sparse residual plus every cue's cost, as the particles were
        scored; every sibling shares the chosen particle's motion step). The sparse
        cue's record of the frame (its coding, for the template update) is kept."""
        cfg, sampler, sparse = self.config, self._sampler, self._sparse
        factors = np.exp(np.arange(-cfg.scale_refine, cfg.scale_refine + 1) * cfg.affine_std[0])
        states = np.repeat(scene.particles[best][None], len(factors), axis=0)
        states[:, :4] *= factors[:, None]
        patches = sampler.patches(scene.prepared, states, scene.plane_scale, self._work_box)
        views = sampler.extract(patches, cfg.views[: self._n_first])
        steps = tuple(np.repeat(a[best : best + 1], len(states), axis=0) for a in scene.steps)
        siblings = dataclasses.replace(
            scene, particles=states, probes=np.zeros((0, 6)), patches=patches, views=views, steps=steps
        )
        kept = sparse.obs, sparse.deferred
        try:
            obs, _ = self._score(siblings)
        finally:
            sparse.obs, sparse.deferred = kept
        if not np.any(obs.likelihood > 0):
            return 1.0
        return float(factors[int(np.argmax(obs.likelihood))])

    def _reshape(self) -> tuple[float, float, float]:
        """``(aspect, fraction, factor)`` of the reported boxes: the first box's
        aspect ratio ``h / w`` (working frame), ``config.report_aspect`` and
        ``config.report_scale`` (:func:`smtmvt.results.reshaped_box`)."""
        first = affine_to_box(self._init_state)
        return float(first[3] / first[2]), float(self.config.report_aspect), float(self.config.report_scale)


def _resized(state: np.ndarray, particles: np.ndarray, factor: float) -> np.ndarray:
    """Scale ``state``'s size (``[:4]``, in place) by ``factor``; return a copy of
    ``particles`` (n, 6) scaled alike, so that the next frame's search is about the new size."""
    state[:4] *= factor
    particles = particles.copy()
    particles[:, :4] *= factor
    return particles


def track_frames(tracker: Tracker, frames, box):
    """Run ``tracker`` over ``frames``: ``init`` on the first with ``box``, ``update`` on the rest
    (:func:`smtmvt.loop.run_loop`, the one loop, in its plainest form).

    Parameters
    ----------
    tracker : Tracker (or any object with the same ``init`` / ``update``).
    frames : iterable of frames; read lazily, one at a time.
    box : (x, y, w, h) 0-based pixels, the target in the first frame.

    Yields
    ------
    (frame, box, seconds) per frame: the frame, its 0-based box as a tuple of 4 floats
    (``box`` itself for the first frame) and the seconds spent in ``init`` / ``update``
    only (reading the frame is not counted).
    """
    from .loop import run_loop

    for step in run_loop(tracker, frames, box):
        yield step.frame, tuple(float(v) for v in step.box), step.seconds
