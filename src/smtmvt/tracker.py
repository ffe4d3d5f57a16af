"""The SMTMVT tracker: a thin object over the pure functions of the package.

Data flows one way, one stage per module::

    frame --preprocess--> Tan-Triggs gray + color planes
          --motion------> n affine particles (random walk)
          --warp--------> candidate patches, one batched remap per plane
          --features----> K views, (d_k, n) normalized columns
          --solvers-----> codes C (K, N, n) and outliers E over the templates
          --likelihood--> p_i = exp(-alpha * (sum_k ||D^k c_i^k - x_i^k||^2 + a_i + f_i + r_i + m_i))
                          (a_i: the anchor term, smtmvt.anchor; f_i: the
                          foreground term, smtmvt.foreground; r_i: the
                          correlation term, smtmvt.correlation; m_i: the
                          motion term, smtmvt.motion.translation_distance)
          --state-------> best candidate = result; template update; resampling

Usage (like OpenCV's trackers)::

    tracker = Tracker(TrackerConfig(seed=0))
    tracker.init(first_frame, (x, y, w, h))      # 0-based pixels
    for frame in frames:
        result = tracker.update(frame)           # TrackResult
        x, y, w, h = result.box
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
from collections import defaultdict
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import cv2
import numpy as np
from threadpoolctl import ThreadpoolController

from .anchor import anchor_offsets
from .background import background_offsets, ring_states
from .confidence import LOST_BELOW, Evidence, confidence
from .config import TrackerConfig
from .correlation import CELL, CorrelationFilter, apce, clears, correlation_cost, peak_point
from .features import Patches, extract_views, intensity_template_size
from .features.coarse import GAMMA_FLOOR
from .features.tan_triggs import TAN_TRIGGS_GAMMA
from .foreground import RING, box_contrast, foreground_map, foreground_model, ring_window
from .geometry import (
    affine_extent,
    affine_scale,
    affine_to_box,
    box_inside_fraction,
    box_scaled,
    box_to_affine,
    box_with_aspect,
)
from .likelihood import Observation, observe
from .motion import place, propagate, pull_shape, resample, translation_distance, translation_std
from .preprocess import (
    PreparedFrame,
    check_frame,
    plane_window,
    prepare_crop,
    prepare_frame,
    resize_frame,
    sample_window,
    smooth,
    smooth_reach,
    to_unit_range,
)
from .scale import ScaleFilter
from .solvers import BOUNDED_CODING, SOLVERS, solve_smtmvt
from .solvers.bounds import range_basis
from .templates import TemplateSet
from .warp import inside_fraction, remap_patches, sampling_grid

__all__ = ["Tracker", "TrackResult", "FrameDetail", "track_frames"]

#: The "dog" intensity plane's outer Gaussian, in multiples of the inner one (Tan-Triggs' 2 / 1).
DOG_RATIO = 2.0

#: Frames whose update angles set the trigger of ``config.update_margin``.
UPDATE_FLOOR_FRAMES = 10

#: How far ``config.redetect_after``'s windows are moved, in box widths (x) and heights (y).
REDETECT_REACH = (0.5, 1.0)


@dataclass(frozen=True)
class TrackResult:
    """Outcome of one :meth:`Tracker.update`.

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
    frame_index : 0-based index of the frame since :meth:`Tracker.init`.
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


def _ratio(value: float, typical: float) -> float:
    """``value / typical`` for a positive ``typical``; else 1 where ``value`` is
    not above it and ``inf`` where it is (nothing to compare with)."""
    value, typical = float(value), float(typical)
    if typical > 0:
        return value / typical
    return 1.0 if value <= typical else math.inf


def _reshaped_box(box, reshape: tuple) -> np.ndarray:
    """``box`` ((4,) or (m, 4), working frame) as reported under ``reshape``
    ``(aspect, fraction, factor)`` (:meth:`Tracker._reshape`): its aspect ratio
    moved ``fraction`` of the way to ``aspect`` (:func:`box_with_aspect`), then
    its sides times ``factor`` (:func:`box_scaled`), about the same centre."""
    aspect, fraction, factor = reshape
    return box_scaled(box_with_aspect(box, aspect, fraction), factor)


@dataclass(frozen=True)
class FrameDetail:
    """What :meth:`Tracker.update_detailed` computed for one frame.

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
    """

    particles: np.ndarray
    observation: Observation
    best: int | None
    probe_boxes: np.ndarray
    scale: np.ndarray
    best_views: list | None = None
    reshape: tuple = (1.0, 0.0, 1.0)

    @property
    def boxes(self) -> np.ndarray:
        """(n, 4) boxes of the particles' states, 0-based pixels of the input frame."""
        return affine_to_box(self.particles).reshape(-1, 4) / np.tile(self.scale, 2)

    @property
    def reported_boxes(self) -> np.ndarray:
        """(n, 4) boxes the tracker would report for each particle (:attr:`boxes`
        reshaped as ``config.report_aspect`` and ``config.report_scale`` say),
        0-based pixels of the input frame."""
        work = _reshaped_box(affine_to_box(self.particles).reshape(-1, 4), self.reshape)
        return work / np.tile(self.scale, 2)

    @property
    def probe_likelihood(self) -> np.ndarray:
        """(m,) likelihoods of the probes (comparable with ``observation.likelihood[:n]``)."""
        return self.observation.likelihood[len(self.particles) :]


class _DeferredViews:
    """The views of one frame's candidates that are computed only where the
    bounded coding needs them (``config.deferred_views``): one stage per view
    for :func:`smtmvt.likelihood.observe`, each returning the view of some
    candidates (weighted) and its part of their anchor term; the blocks
    computed are kept, so that any candidate's views can be read back."""

    def __init__(self, tracker: Tracker, patches: Patches, X: list) -> None:
        self._tracker, self._patches, self._X = tracker, patches, X
        #: deferred view index k -> [(candidate indices, (d_k, m) view)], in the order computed
        self.blocks: dict[int, list] = {k: [] for k in range(len(X), len(tracker.config.views))}

    def stages(self) -> list:
        """``observe``'s ``deferred``: one ``stage(idx) -> (view, offset)`` per deferred view."""
        return [functools.partial(self._compute, k) for k in self.blocks]

    def _compute(self, k: int, idx: np.ndarray):
        t = self._tracker
        cfg = t.config
        (view,) = t._extract(self._patches.subset(idx, t._reads.get(cfg.views[k])), [cfg.views[k]])
        self.blocks[k].append((idx, view))
        (weighted,) = t._weighted([view], first=k)
        if not (cfg.anchor_weight and k in t._term_index):
            return weighted, None
        first = t._weighted([t._templates.dictionaries[k][:, 0]], first=k)
        return weighted, anchor_offsets([weighted], first, cfg.anchor_weight)

    def views_of(self, i: int) -> list:
        """The K views ``(d_k,)`` float32 of candidate i (a deferred one zero where not computed)."""
        out = [Xk[:, i] for Xk in self._X]
        for k, computed in self.blocks.items():
            hits = [view[:, j] for idx, view in computed for j in np.flatnonzero(idx == i)]
            out.append(hits[0] if hits else np.zeros(self._tracker._templates.dictionaries[k].shape[0], np.float32))
        return out


class Tracker:
    """SMTMVT tracker (Javanmardi & Qi, ICME 2018).

    Parameters
    ----------
    config : TrackerConfig, optional
        All parameters; the paper's defaults when omitted.
    **overrides
        Shorthand for ``config.replace(**overrides)``.
    """

    def __init__(self, config: TrackerConfig | None = None, **overrides):
        config = config or TrackerConfig()
        self.config = config.replace(**overrides) if overrides else config
        self._initialized = False
        #: Seconds spent per stage since the last :meth:`init` (for ``bench/``).
        self.timings: defaultdict[str, float] = defaultdict(float)
        self._timing: set[str] = set()  # the stages being timed now
        self._threadpools = ThreadpoolController() if self.config.blas_threads else None

    @contextmanager
    def _blas_limit(self):
        if self._threadpools is None:
            yield
        else:
            with self._threadpools.limit(limits=self.config.blas_threads, user_api="blas"):
                yield

    # -- stages ------------------------------------------------------------
    @contextmanager
    def _timed(self, stage: str):
        """Add the block's time to ``timings[stage]``, once: a block of a stage
        already being timed (a deferred view's features inside observe's) is not
        counted again."""
        if stage in self._timing:
            yield
            return
        self._timing.add(stage)
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.timings[stage] += time.perf_counter() - t0
            self._timing.discard(stage)

    def _views(self, frame: PreparedFrame, params: np.ndarray, plane_scale: float = 1.0) -> list:
        """Candidate views ``[(d_k, m) float32]`` of the states ``params (m, 6)`` (see :meth:`_patches`)."""
        return self._extract(self._patches(frame, params, plane_scale), self.config.views)

    def _extract(self, patches: Patches, views) -> list:
        with self._timed("features"):
            return extract_views(patches, views, self._view_options)

    def _patches(self, frame: PreparedFrame, params: np.ndarray, plane_scale: float = 1.0) -> Patches:
        """The patches of the states ``params (m, 6)``.

        ``frame``'s planes may be the working frame resized by ``plane_scale``
        (plane pixels per working-frame pixel, see ``config.scale_normalize``):
        the sampling grids are mapped onto them (pixel edges to pixel edges).
        With ``config.antialias`` > 0 each plane is first smoothed by a Gaussian
        of ``antialias`` times the sampling step of the current target (its
        size on the plane over the patch size), so that sampling it on the
        patch grid does not alias.
        """
        cfg = self.config
        fs = cfg.feature_size
        cs = cfg.color_size or fs

        ox, oy = frame.origin

        def grid(size):
            return sampling_grid(params, size, plane_scale, frame.origin)

        with self._timed("warp"):
            # every plane is smoothed only where the samples read it
            x0, y0, x1, y1 = self._plane_extent(params, plane_scale)
            win = sample_window((x0 - ox, y0 - oy, x1 - ox, y1 - oy), frame.shape)
            sig_i, sig_f, sig_c = self._smoothing(plane_scale)
            X, Y = grid(fs)
            intensity = remap_patches(self._intensity_plane(frame, sig_i, win), *grid(self._intensity_size))
            gray = remap_patches(smooth(frame.normalized, sig_f, win), X, Y) if self._needs_gray else None
            raw: np.ndarray | None
            # sampled together on a crop only: on a whole plane the whole-plane merge and
            # smoothing output cost more than the 4-channel sampling saves (docs/stops.md#stop18)
            if self._needs_raw and cs == fs and sig_c == sig_f and frame.full_shape is not None:
                color, raw = self._color_and_raw(frame, sig_f, win, X, Y)
            else:
                XC, YC = (X, Y) if cs == fs else grid(cs)
                color = remap_patches(smooth(frame.color, sig_c, win), XC, YC).reshape(len(params), cs[0], cs[1], -1)
                raw = remap_patches(smooth(frame.gray, sig_f, win), X, Y) if self._needs_raw else None
            patches = Patches(intensity=intensity, gray=gray, color=color, raw=raw)
        return patches

    def _intensity_plane(self, frame: PreparedFrame, sigma: float, win) -> np.ndarray:
        """The plane the intensity patches are sampled from, smoothed by ``sigma``
        (``config.intensity_plane``; only ``win`` is computed): Tan-Triggs'
        output, the gray plane, or (``"dog"``) the gray plane after Tan-Triggs'
        gamma and a difference of Gaussians of ``sigma`` and ``DOG_RATIO sigma``:
        its band-pass at the template's resolution instead of the frame's (the
        gray plane is floored at ``GAMMA_FLOOR``, 1e-4 as for the coarse view,
        before the gamma, unlike Tan-Triggs', so a black pixel becomes 0.16,
        not 0; measured so in docs/experiments.md#n28)."""
        kind = self.config.intensity_plane
        if kind == "tan_triggs":
            return smooth(frame.normalized, sigma, win)
        if kind == "gray":
            return smooth(frame.gray, sigma, win)
        g = np.power(np.maximum(frame.gray, GAMMA_FLOOR), np.float32(TAN_TRIGGS_GAMMA))
        return smooth(g, sigma, win) - smooth(g, DOG_RATIO * sigma, win)

    @staticmethod
    def _color_and_raw(frame: PreparedFrame, sigma: float, win, X, Y) -> tuple[np.ndarray, np.ndarray]:
        """The color ``(n, fh, fw, C)`` and raw gray ``(n, fh, fw)`` patches on one
        grid and smoothing, sampled together: a gray frame's color plane is its
        gray plane, sampled once; an RGB frame's three channels and its gray
        plane are smoothed and sampled as one 4-channel plane (OpenCV samples 4
        channels in about the time of 1, with the same values as each channel
        alone); the color channels are copied out by OpenCV (numpy's copy of a
        3-of-4-channel view costs more than the sampling saves), the gray one is
        returned as a strided view (copied by the views that read it, and only
        for the candidates they are computed for when deferred)."""
        if frame.color.shape[2] == 1:  # prepare_frame: a gray frame's color plane is its gray plane
            color = remap_patches(smooth(frame.color, sigma, win), X, Y)
            return color, color[..., 0]
        plane = cv2.merge([frame.color[..., 0], frame.color[..., 1], frame.color[..., 2], frame.gray])
        both = remap_patches(smooth(plane, sigma, win), X, Y)
        n, ph, pw, _ = both.shape
        color = cv2.cvtColor(both.reshape(n * ph, pw, 4), cv2.COLOR_RGBA2RGB).reshape(n, ph, pw, 3)
        return color, both[..., 3]  # a strided view: copied only where a view reads it

    def _smoothing(self, plane_scale: float) -> tuple[float, float, float]:
        """Anti-aliasing sigmas (plane pixels) of the intensity, feature-size and
        color patches: ``config.antialias`` times the current target's sampling step."""
        cfg = self.config
        fs = cfg.feature_size
        cs = cfg.color_size or fs
        w, h = self._work_box[2] * plane_scale, self._work_box[3] * plane_scale
        steps = (
            max(w / self._intensity_size[1], h / self._intensity_size[0]),
            max(w / fs[1], h / fs[0]),
            max(w / cs[1], h / cs[0]),
        )
        sig_i, sig_f, sig_c = (cfg.antialias * step for step in steps)
        return sig_i, sig_f, sig_c

    def _contrast(self, frame: PreparedFrame, states: np.ndarray, plane_scale: float) -> np.ndarray:
        """Foreground contrast (:func:`smtmvt.foreground.box_contrast`) of each
        state's box on the frame's color plane, ``(m,)`` float64 (the term on)."""
        if self._fg_model is None:
            raise RuntimeError("the foreground term is off (config.foreground_weight 0)")
        boxes = self._plane_boxes(frame, states, plane_scale)
        window = ring_window(boxes, frame.shape)  # the map is needed only where the boxes' rings reach
        return box_contrast(foreground_map(frame.color, self._fg_model, window), boxes)

    @staticmethod
    def _plane_boxes(frame: PreparedFrame, states: np.ndarray, plane_scale: float) -> np.ndarray:
        """The states' boxes ``(m, 4)`` in the pixels of the frame's planes (a crop's own)."""
        boxes = affine_to_box(states).reshape(-1, 4) * plane_scale
        boxes[:, 0] -= frame.origin[0]
        boxes[:, 1] -= frame.origin[1]
        return boxes

    @staticmethod
    def _plane_extent(params: np.ndarray, plane_scale: float) -> tuple:
        """Bounding box ``(x0, y0, x1, y1)`` of the states' squares on the plane."""
        x0, y0, x1, y1 = affine_extent(params)
        if plane_scale != 1.0:
            x0, y0, x1, y1 = ((v + 0.5) * plane_scale - 0.5 for v in (x0, y0, x1, y1))
        return x0, y0, x1, y1

    def _background_views(self, frame: PreparedFrame, plane_scale: float = 1.0) -> list | None:
        """The background term's dictionary (:mod:`smtmvt.background`): the term
        views (weighted, as :meth:`_terms_of`) of ``config.background_samples``
        boxes on a ring around the current state, in the frame it was just
        estimated in (where the ring does not overlap the target); None when the
        term is off. The next frame's candidates are compared with them: an
        object that was beside the target then is background now."""
        cfg = self.config
        if not cfg.background_weight:
            return None
        ring = ring_states(self._state, cfg.background_samples, self._rng)
        views = self._extract(self._patches(frame, ring, plane_scale), [cfg.views[i] for i in self._term_index])
        return self._weighted(views, index=self._term_index)

    def _terms_of(self, views: list) -> list:
        """The term views (``config.term_views``) among ``views`` (the first
        ``len(views)`` of ``config.views``, in that order: the deferred ones may
        be left out), weighted as by :meth:`_weighted`."""
        index = [i for i in self._term_index if i < len(views)]
        return self._weighted([views[i] for i in index], index=index)

    def _weighted(self, views: list, first: int = 0, index=None) -> list:
        """``views`` (views ``first, first + 1, ...`` of ``config.views``, or the
        views of indices ``index``) scaled by ``sqrt(config.view_weights)``
        (unchanged when None): the coding and the likelihood then weigh view k's
        squared residual by its weight."""
        w = self.config.view_weights
        if w is None:
            return list(views)
        if index is None:
            index = range(first, first + len(views))
        return [np.float32(np.sqrt(w[i])) * v for i, v in zip(index, views)]

    def _template_states(self, state: np.ndarray) -> np.ndarray:
        """The N template states: the exact first box, then N-1 jittered copies.

        The jitter moves the box corners by about N(0, 0.6^2) pixels (L1-APG).
        """
        N = self.config.n_templates
        rng = np.random.default_rng(None if self.config.seed is None else self.config.seed + 1)
        states = np.repeat(state[None], N, axis=0)
        if N > 1:
            x, y, w, h = affine_to_box(state)
            jit = rng.normal(0.0, 0.6, size=(N - 1, 4))
            boxes = np.array([x, y, w, h]) + jit
            boxes[:, 2:] = np.maximum(boxes[:, 2:], 1.0)
            states[1:] = box_to_affine(boxes)
        return states

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
        and the velocity, the templates, the correlation and scale filters and
        their response history, the foreground model, the lost streak, the
        costs ``confidence`` compares with, the frame count and ``timings``;
        the random generator is seeded again from ``config.seed``. Kept: the
        config, the BLAS thread-pool controller and the numba kernels (compiled
        once per process). So the boxes that follow are those of a new
        ``Tracker(config)`` started with ``init(frame, box)``. A refused
        ``box`` raises ValueError as :meth:`init`'s does.
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

    def _init(self, frame: np.ndarray, box) -> None:
        b = np.asarray(box, dtype=np.float64).reshape(-1)
        shown = tuple(b.tolist())  # plain numbers in messages, not np.float64(...)
        if b.size != 4 or not np.all(np.isfinite(b)):
            raise ValueError(f"init: box must be 4 finite numbers (x, y, w, h), got {shown}")
        if b[2] <= 0 or b[3] <= 0:
            raise ValueError(f"init: box {shown} has zero or negative size")
        cfg = self.config
        # planes computed on the candidates' window only (the background ring reads farther)
        self._crop = bool(cfg.crop_planes and not cfg.background_weight)
        self._tt_divisors: tuple | None = None  # config.crop_refresh: the last whole plane's Tan-Triggs divisors
        self._frame_index = 0
        shape = np.shape(frame)
        if cfg.frame_size is None or len(shape) < 2:
            self._scale = np.ones(2)
        else:
            self._scale = np.array([cfg.frame_size[0] / shape[1], cfg.frame_size[1] / shape[0]])
        prepared = self._prepare(frame, "init frame", None)
        self._frame_shape = (int(shape[0]), int(shape[1]))
        self._channels = prepared.color.shape[2]
        wb = self._to_work(b)
        inside = box_inside_fraction(wb, prepared.shape)
        if inside < 0.25:
            raise ValueError(
                f"init: box {shown} is mostly outside the {shape[1]}x{shape[0]} image ({inside:.0%} inside)"
            )
        self.timings = defaultdict(float)
        # in the working frame, as the paper
        self._intensity_size = intensity_template_size(wb[2], wb[3], cfg.intensity_factor)
        self._view_options: dict[str, dict[str, Any]] = {
            "color": {"grid": cfg.color_grid, "power": cfg.histogram_power},
            "hog": {"plane": cfg.hog_plane},
            "lbp": {"radius": cfg.lbp_radius, "plane": cfg.lbp_plane, "power": cfg.histogram_power},
        }
        # the feature-size gray planes the views read (only those are warped; a
        # registered view of another name may read either)
        read = {"hog": {cfg.hog_plane}, "lbp": {cfg.lbp_plane}, "coarse": {"gray"}, "intensity": set(), "color": set()}
        planes = set().union(*(read.get(view, {"gray", "tan_triggs"}) for view in cfg.views))
        self._needs_raw, self._needs_gray = "gray" in planes, "tan_triggs" in planes
        # the Patches arrays each built-in view reads (a deferred view gets only those)
        array_of = {"gray": "raw", "tan_triggs": "gray"}
        self._reads = {view: {array_of[p] for p in read[view]} | ({view} & {"intensity", "color"}) for view in read}
        # the views from this index on are computed only where the bounds need them
        n_first = len(cfg.views)
        # (the background term's views are needed for every candidate: never deferred while it is on)
        eager = set(cfg.term_views) if cfg.background_weight else set()
        while n_first > 0 and cfg.views[n_first - 1] in set(cfg.deferred_views) - eager:
            n_first -= 1
        self._n_first = n_first if n_first > 0 and self._prune_eps(cfg.n_particles) > 0 else len(cfg.views)
        # the views of the background and anchor terms (config.term_views)
        self._term_index = [cfg.views.index(v) for v in cfg.term_views if v in cfg.views]
        self._rng = np.random.default_rng(cfg.seed)
        self._state = box_to_affine(wb)
        self._init_state = self._state.copy()
        self._velocity = np.zeros(2)
        self._residuals: list[float] = []  # the chosen candidates' residuals (config.search_expand)
        self._expand = 1.0
        # velocity_fraction of the particles, evenly spread over the indices, take the velocity term
        i = np.arange(cfg.n_particles)
        moved = np.floor((i + 1) * cfg.velocity_fraction) > np.floor(i * cfg.velocity_fraction)
        self._velocity_share = None if moved.all() else moved.astype(np.float64)[:, None]
        # the first narrow_fraction of the particles search with narrow_scale times the std
        self._spread = None
        if cfg.narrow_fraction > 0:
            self._spread = np.ones(cfg.n_particles)
            self._spread[: int(round(cfg.narrow_fraction * cfg.n_particles))] = cfg.narrow_scale
        self._work_box = tuple(float(v) for v in wb)
        self._box = tuple(float(v) for v in b)
        # the foreground term's color model: the first box against its surroundings, on the whole frame
        self._fg_model = foreground_model(prepared.color, wb) if cfg.foreground_weight else None
        # the correlation term's filter, on the frame as given (not the working frame)
        self._filter = CorrelationFilter(frame, b) if cfg.correlation_weight or cfg.correlation_particles else None
        # the scale filter (config.scale_filter), on the frame as given
        self._scaler = ScaleFilter(frame, b) if cfg.scale_filter else None
        t_states = self._template_states(self._state)
        if self._crop and not cfg.crop_refresh:  # the templates' planes as every later frame's
            prepared = self._prepare(frame, "init frame", self._channels, 1.0, t_states)
        self._templates = TemplateSet([np.array(v, dtype=np.float32) for v in self._views(prepared, t_states)])
        self._bases: list | None = None  # range_basis of each weighted dictionary, kept until a template changes
        self._particles = np.repeat(self._state[None], cfg.n_particles, axis=0)
        self._weights = np.full(cfg.n_particles, 1.0 / cfg.n_particles)
        self._background = self._background_views(prepared)
        self._intensity_index = cfg.views.index("intensity") if "intensity" in cfg.views else None
        self._first_angles: list[float] = []  # the update rule's angles on the first frames (update_margin)
        # config.redetect_after: frames in a row the target seemed lost, the last state the
        # filter learned from, and whether this frame's response came from the wider search
        self._lost = 0
        self._costs: list[float] = []  # the chosen candidates' costs (TrackResult.confidence)
        self._peak_ref: float | None = None  # the correlation responses' mean peak before this frame
        self._last_learned = self._state.copy()
        self._redetected = False
        self._initialized = True

    # -- the working frame (config.frame_size) ------------------------------
    def _prepare(self, frame, where: str, channels, plane_scale: float = 1.0, states=None):
        """The frame's planes at ``plane_scale`` times the working frame's size.

        With ``states`` (m, 6) and ``config.crop_planes``, only the window of
        them that those states' patches read (:func:`prepare_crop`).
        """
        cfg = self.config
        if np.ndim(frame) < 2:
            to_unit_range(frame, where)  # raises, naming the frame and its shape
        shape = np.shape(frame)
        size = self._plane_size(shape, plane_scale)
        # config.crop_refresh: the whole plane (init's first call is frame 0, so the divisors are always set)
        refresh = bool(cfg.crop_refresh) and self._frame_index % cfg.crop_refresh == 0
        if states is not None and self._crop and not refresh:
            plane_shape = (shape[0], shape[1]) if size is None else (size[1], size[0])
            sigmas = self._smoothing(plane_scale)
            reach = smooth_reach(max(*sigmas, DOG_RATIO * sigmas[0] if cfg.intensity_plane == "dog" else 0.0)) + 1
            if cfg.foreground_weight:  # the foreground term reads the rings around the boxes
                states = np.array(states, dtype=np.float64)
                states[:, :4] *= RING
            window = plane_window(self._plane_extent(states, plane_scale), plane_shape, reach)
            scale = (self._scale[0] * plane_scale, self._scale[1] * plane_scale)
            if cfg.crop_refresh:  # Tan-Triggs' statistics: the last whole plane's
                return prepare_crop(frame, where, channels, window, scale, plane_shape, contrast=self._tt_divisors)
            # Tan-Triggs' statistics: the current box grown by crop_context about its centre
            context = self._state.copy()
            context[:4] *= cfg.crop_context
            stats = plane_window(self._plane_extent(context[None], plane_scale), plane_shape)
            return prepare_crop(frame, where, channels, window, scale, plane_shape, stats)
        if size is not None:
            frame = resize_frame(to_unit_range(frame, where), size)
        prepared = prepare_frame(frame, where, channels)
        if refresh:
            self._tt_divisors = prepared.contrast
        return prepared

    def _plane_size(self, shape, plane_scale: float) -> tuple[int, int] | None:
        """``(width, height)`` of the planes for an input frame of ``shape``, or None
        when they are the input frame's own."""
        size = self.config.frame_size
        if size is None and plane_scale == 1.0:
            return None
        if size is None:
            size = (shape[1], shape[0])
        return max(2, int(round(size[0] * plane_scale))), max(2, int(round(size[1] * plane_scale)))

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

    def _update(self, frame: np.ndarray, probes=None):
        """One frame: particles -> planes -> views -> codes -> likelihoods -> state."""
        if not self._initialized:
            raise RuntimeError("update called before init")
        self._check_frame(frame)
        self._frame_index += 1
        rng_state = self._rng.bit_generator.state
        plane_scale = self._plane_scale()
        probe_boxes = np.zeros((0, 4)) if probes is None else np.asarray(probes, dtype=np.float64).reshape(-1, 4)
        probe_states = box_to_affine(self._to_work(probe_boxes)).reshape(-1, 6)
        try:
            response = self._response(frame)
            particles = self._propagate(response)
            with self._timed("preprocess"):
                prepared, probe_planes = self._prepare_candidates(frame, particles, probe_states, plane_scale)
        except Exception:
            # a frame that cannot be read leaves the tracker as it was
            self._rng.bit_generator.state = rng_state
            self._frame_index -= 1
            raise
        judged = self._judge(response)
        # config.correlation_usual_peak: the correlation cue's scale, the mean peak of the responses before
        self._peak_ref = float(judged[1][0]) if judged is not None and self.config.correlation_usual_peak else None
        obs, views_of = self._observe(prepared, probe_planes, particles, probe_states, plane_scale, response)
        learn = self._templates_learn(judged) and (not self._redetected or self._near_peak(obs, particles, response))
        result, detail = self._decide(particles, obs, views_of, probe_boxes, prepared, plane_scale, learn, frame)
        learns = self._filter_learns(judged) and (not self._redetected or self._near_peak(None, None, response))
        if self._scaler is not None and detail.best is not None and learns:
            with self._timed("likelihood"):
                self._scaler.update(frame, self._box)
        self._lost = self._lost + 1 if self._seems_lost(judged) else 0
        if self._filter is not None and detail.best is not None and learns:
            self._last_learned = self._state.copy()
            with self._timed("likelihood"):
                self._filter.update(frame, self._from_work(self._work_box), self.config.correlation_rate)
        evidence = self._evidence(result.score, judged)
        c = confidence(evidence)
        return dataclasses.replace(result, confidence=c, lost=c < LOST_BELOW, evidence=evidence), detail

    def _evidence(self, score: float, judged) -> Evidence:
        """This frame's :class:`Evidence`: the ``judged`` response's peak and
        APCE over their means before (:meth:`_judge`; 1 and 1 when None), the
        chosen candidate's cost ``-log(score) / alpha`` over the median cost
        chosen before (recorded here; ``inf`` for ``score`` 0), and the lost
        streak (``_lost``, updated this frame)."""
        peak = apce_ratio = 1.0
        if judged is not None:
            now, past = judged
            peak, apce_ratio = _ratio(now[0], past[0]), _ratio(now[1], past[1])
        cost = -math.log(score) / self.config.alpha if score > 0 else math.inf
        cost_ratio = _ratio(cost, float(np.median(self._costs))) if self._costs else 1.0
        if math.isfinite(cost):
            self._costs.append(cost)
        return Evidence(peak, apce_ratio, cost_ratio, self._lost)

    def _check_frame(self, frame) -> None:
        """Raise ValueError for a frame that cannot be read (shape, dtype, NaN) or whose
        height and width differ from ``init``'s frame; nothing is changed before."""
        where = f"frame {self._frame_index + 1}"
        h, w = check_frame(frame, where).shape[:2]
        h0, w0 = self._frame_shape
        if (h, w) != (h0, w0):
            raise ValueError(
                f"update: {where} is {w}x{h} pixels but init's frame was {w0}x{h0}: "
                "every frame must have the first frame's size (call init again for another size)"
            )

    def _seems_lost(self, judged) -> bool:
        """Whether this frame's ``judged`` response (:meth:`_judge`) says the
        target is lost: its peak below ``config.template_learn_floor`` times
        its mean over the frames before."""
        if judged is None:
            return False
        now, past = judged
        return bool(now[0] < self.config.template_learn_floor * past[0])

    def _near_peak(self, obs, particles, response) -> bool:
        """Whether the box chosen this frame (with ``obs``: the most likely of
        ``particles``, before :meth:`_decide` makes it the state; else the
        state) lies within half its size of the peak of ``response``."""
        if obs is None:
            state = self._state
        else:
            p = obs.likelihood[: len(particles)]
            state = particles[int(np.argmax(p))] if np.any(p > 0) else self._state
        box = self._from_work(affine_to_box(state))
        centre = box_to_affine(box)[4:]
        return bool(np.hypot(*(centre - peak_point(*response))) <= 0.5 * np.sqrt(box[2] * box[3]))

    def _response(self, frame) -> tuple | None:
        """The correlation filter's response over its window about this frame's
        prediction, ``(response (h, w), Window)`` (:mod:`smtmvt.correlation`),
        or None without the filter (the frame was checked by :meth:`_check_frame`)."""
        if self._filter is None:
            return None
        cfg = self.config
        with self._timed("likelihood"):
            box = self._from_work(affine_to_box(self._predicted()))
            response = self._filter.response(frame, box, cfg.correlation_first)
            self._redetected = False
            if cfg.redetect_after and self._lost >= cfg.redetect_after:
                found = self._redetect(frame, box, response)
                if found is not None:
                    response, self._redetected = found, True
            return response

    def _redetect(self, frame, box, response) -> tuple | None:
        """The wider search of ``config.redetect_after``: the best response
        over the windows about ``box`` (frame pixels) moved by half and by one
        box size in the eight directions, and about the last state the filter
        learned from; the response over the window centred on their highest
        peak where it beats ``response`` and passes the filter's learn gate
        against the frames before; else None."""
        assert self._filter is not None
        if not self._filter.history:
            return None
        cfg = self.config
        b = np.asarray(box, dtype=np.float64)
        moves = [(r * dx, r * dy) for r in REDETECT_REACH for dx in (-1, 0, 1) for dy in (-1, 0, 1) if dx or dy]
        boxes = [b + np.array([mx * b[2], my * b[3], 0.0, 0.0]) for mx, my in moves]
        last = self._from_work(affine_to_box(self._last_learned))
        lb = b.copy()
        lb[:2] = last[:2] + (last[2:] - b[2:]) / 2.0  # the last learned centre, this frame's size
        if np.hypot(*(lb[:2] - b[:2])) > 0.5 * np.sqrt(b[2] * b[3]):
            boxes.append(lb)
        best = max((self._filter.response(frame, c, cfg.correlation_first) for c in boxes), key=lambda rw: rw[0].max())
        # judged on the window centred on that peak: off the window's centre the Hann
        # window weakens the target and its APCE says little
        centred = b.copy()
        centred[:2] = peak_point(*best) - (b[2:] - 1.0) / 2.0
        best = self._filter.response(frame, centred, cfg.correlation_first)
        if not best[0].max() > response[0].max():
            return None
        past = np.mean(self._filter.history, axis=0)
        now = (float(best[0].max()), apce(best[0]))
        return best if clears((now, past), cfg.correlation_learn_gate) else None

    def _judge(self, response):
        """This frame's ``response`` judged against the responses before
        (:meth:`CorrelationFilter.judge`: ``(now, past)``, None on the first),
        or None without the filter or without a gate to judge it by."""
        cfg = self.config
        if response is None or not any(cfg.correlation_learn_gate + cfg.template_learn_gate):
            return None
        assert self._filter is not None
        return self._filter.judge(response[0])

    def _templates_learn(self, judged) -> bool:
        """Whether the template update may replace a template this frame
        (``config.template_learn_gate``): always without the gate or on the
        first judged frame; else only when the response clears the gate
        against the mean of the ``config.template_learn_memory`` responses
        before (:meth:`CorrelationFilter.judged`) and its peak is at least
        ``config.template_learn_floor`` times its mean over all of them
        (``judged``, :meth:`_judge`)."""
        cfg = self.config
        if not any(cfg.template_learn_gate) or judged is None:
            return True
        assert self._filter is not None
        recent = clears(self._filter.judged(cfg.template_learn_memory), cfg.template_learn_gate)
        return recent and not self._seems_lost(judged)

    def _filter_learns(self, judged) -> bool:
        """Whether the correlation filter learns from this frame's box: always
        without ``config.correlation_learn_gate``, else only when the
        ``judged`` response (:meth:`_judge`) clears it (:func:`clears`)."""
        gate = self.config.correlation_learn_gate
        return not any(gate) or clears(judged, gate)

    def _propagate(self, response=None) -> np.ndarray:
        """This frame's ``(n, 6)`` particles: the last frame's resampled by their
        likelihoods, then moved by the random walk (and the velocity term); with
        the correlation filter's ``response`` (:meth:`_response`) and
        ``config.correlation_particles``, that fraction of them (the last ones,
        where resampling puts copies of the best) placed about its peak."""
        cfg = self.config
        with self._timed("motion"):
            particles = resample(self._particles, self._weights, cfg.n_particles)
            if cfg.shape_pull:
                particles = pull_shape(particles, self._init_state, cfg.shape_pull)
            shift = cfg.velocity * self._velocity if cfg.velocity else None
            if shift is not None and self._velocity_share is not None:
                shift = self._velocity_share * shift
            std = cfg.affine_std
            if self._expand > 1.0:  # config.search_expand: a wider search after a poorly explained frame
                std = (*std[:4], std[4] * self._expand, std[5] * self._expand)
            moved = propagate(particles, std, self._rng, shift, self._spread, cfg.translation_power, cfg.aspect_std)
            count = int(round(cfg.correlation_particles * len(moved)))
            if response is not None and count:
                r, window = response
                # about the peak cell's centre (as the centre of a one-pixel box, to map it to the
                # working frame as box centres are), half a cell's standard deviation
                point = box_to_affine(self._to_work(np.array([[*peak_point(r, window), 1.0, 1.0]])))[0, 4:]
                step = np.asarray(window.step) * self._scale  # frame pixels per window pixel, working frame
                moved = place(moved, count, point, 0.5 * CELL * step, self._rng)
            # each particle's own prediction (its parent moved by the velocity term) and the
            # random walk's translation std there, for the motion term
            predicted = particles[:, 4:] + (0.0 if shift is None else shift)
            if self._redetected and count:  # the wider search's particles: no motion term
                predicted[len(moved) - count :] = moved[len(moved) - count :, 4:]
            self._steps = (predicted, translation_std(particles, std, cfg.translation_power))
            return moved

    def _prepare_candidates(self, frame, particles, probe_states, plane_scale: float):
        """The frame's planes for the particles, and those for the probes (the
        same planes, or on a crop the probes' own, so that they do not move the
        particles' window)."""
        where = f"frame {self._frame_index}"
        prepared = self._prepare(frame, where, self._channels, plane_scale, particles)
        probe_planes = prepared
        if len(probe_states) and prepared.full_shape is not None:
            probe_planes = self._prepare(frame, where, self._channels, plane_scale, probe_states)
        return prepared, probe_planes

    def _observe(self, prepared, probe_planes, particles, probe_states, plane_scale: float, response=None):
        """Views, codes and likelihoods of the particles followed by the probes
        (``response``: the correlation filter's, :meth:`_response`):
        ``(Observation, views_of)``, ``views_of(i)`` the K views ``(d_k,)``
        float32 of candidate i (a deferred view zero where it was not computed)."""
        cfg = self.config
        n = len(particles)
        states = np.concatenate([particles, probe_states])
        full = prepared.plane_shape
        work_shape = (int(round(full[0] / plane_scale)), int(round(full[1] / plane_scale)))
        patches = self._patches(prepared, particles, plane_scale)
        if len(probe_states):
            patches = patches.joined(self._patches(probe_planes, probe_states, plane_scale))
        # the views computed for every candidate; the deferred ones as the bounds need them
        now = cfg.views[: self._n_first]
        X = self._extract(patches, now)
        with self._timed("likelihood"):
            offset = self._offsets(X, prepared, probe_planes, particles, probe_states, plane_scale, response)
        # A candidate mostly outside the image is not a valid observation.
        with self._timed("motion"):
            valid = inside_fraction(states, work_shape) >= 0.5
        is_probe = np.arange(len(states)) >= n
        later = _DeferredViews(self, patches, X)
        dictionaries = self._weighted(self._templates.dictionaries)
        if self._bases is None:  # the templates changed
            self._bases = [range_basis(Dk) for Dk in dictionaries]
        obs = observe(
            self._weighted(X),
            dictionaries,
            self._code,
            cfg.alpha,
            valid=valid & ~is_probe,
            eps=self._prune_eps(n),
            always=is_probe,
            timed=self._timed,
            deferred=later.stages(),
            bases=self._bases,
            offset=offset,
        )
        return obs, later.views_of

    def _offsets(self, X, prepared, probe_planes, particles, probe_states, plane_scale: float, response=None):
        """Each candidate's terms added to its residual (background, anchor,
        motion, foreground, correlation; ``(n + m,)``), or None when all are off."""
        cfg = self.config
        offset = None
        # the term views at hand: a deferred one brings its part of the anchor term when it is
        # computed (_DeferredViews); none is deferred with the background term
        X_terms = self._terms_of(X) if cfg.anchor_weight or cfg.background_weight else []
        if self._background is not None and X_terms:
            offset = background_offsets(X_terms, self._background, cfg.background_weight, cfg.background_measure)
        if cfg.anchor_weight and X_terms:
            first = self._terms_of([Dk[:, 0] for Dk in self._templates.dictionaries[: len(X)]])
            anchor = anchor_offsets(X_terms, first, cfg.anchor_weight)
            offset = anchor if offset is None else offset + anchor
        if cfg.motion_weight:
            d2 = translation_distance(particles, *self._steps)
            if len(probe_states):
                d2 = np.concatenate([d2, self._probe_distance(probe_states)])
            motion = cfg.motion_weight * 0.5 * d2 / cfg.alpha
            offset = motion if offset is None else offset + motion
        if cfg.scale_push:
            push = -cfg.scale_push * self._log_scale(np.concatenate([particles, probe_states]))
            offset = push if offset is None else offset + push
        if cfg.foreground_weight:
            contrast = self._contrast(prepared, particles, plane_scale)
            if len(probe_states):
                contrast = np.concatenate([contrast, self._contrast(probe_planes, probe_states, plane_scale)])
            fg = cfg.foreground_weight * (1.0 - contrast)
            offset = fg if offset is None else offset + fg
        if response is not None and cfg.correlation_weight:
            corr = self._correlation(response, np.concatenate([particles, probe_states]))
            offset = corr if offset is None else offset + corr
        return offset

    def _log_scale(self, states: np.ndarray) -> np.ndarray:
        """``log(s_i / s)`` of each state ``(n, 6)``: its box's size ``sqrt(w h)``
        against the last state's, ``(n,)``."""
        wh = affine_to_box(states).reshape(-1, 4)[:, 2:]
        w0, h0 = affine_to_box(self._state)[2:]
        return 0.5 * np.log(wh[:, 0] * wh[:, 1] / (w0 * h0))

    def _correlation(self, response, states: np.ndarray) -> np.ndarray:
        """The correlation term of each state ``(n, 6)`` (working frame):
        ``weight * (r_max - r_i) / r_ref`` (:func:`smtmvt.correlation.correlation_cost`)
        from the filter's ``response`` (:meth:`_response`), ``r_ref`` this
        frame's peak ``r_max``, or with ``config.correlation_usual_peak`` the
        mean peak of the responses before (``r_max`` on the first), ``(n,)``."""
        centres = box_to_affine(self._from_work(affine_to_box(states)))[:, 4:]
        r, window = response
        return self.config.correlation_weight * correlation_cost(r, window, centres, self._peak_ref)

    def _predicted(self) -> np.ndarray:
        """This frame's prediction ``(6,)``: the last state, its translation
        moved by the velocity term."""
        cfg = self.config
        predicted = self._state.copy()
        if cfg.velocity:
            predicted[4:] += cfg.velocity * self._velocity
        return predicted

    def _probe_distance(self, states: np.ndarray) -> np.ndarray:
        """(m,) squared distance of each probe's translation from this frame's
        prediction (the last state moved by the velocity term), in the random
        walk's standard deviations at the last state's scale
        (:func:`smtmvt.motion.translation_distance`): the motion term of a
        probe, which has no parent particle."""
        cfg = self.config
        return translation_distance(
            states, self._predicted()[4:], translation_std(self._state, cfg.affine_std, cfg.translation_power)
        )

    def _decide(
        self, particles, obs, views_of, probe_boxes, prepared, plane_scale: float, learn: bool, frame: np.ndarray
    ):
        """The state from the likelihoods: the best particle (or their mean),
        its scale moved toward the scale filter's (:meth:`_rescaled`), the
        template update (no template replaced unless ``learn``) and the next
        frame's resampling weights."""
        cfg = self.config
        p = obs.likelihood[: len(particles)]
        if not np.any(p > 0):
            # Nothing explains the frame: keep the previous state (no NaN ever leaves).
            self._particles = np.repeat(self._state[None], cfg.n_particles, axis=0)
            self._weights = np.full(cfg.n_particles, 1.0 / cfg.n_particles)
            result = TrackResult(self._box, 0.0, float("inf"), True, None, self._frame_index)
            return result, FrameDetail(particles, obs, None, probe_boxes, self._scale, None, self._reshape())
        best = int(np.argmax(p))
        views = views_of(best)
        with self._timed("update"):
            decision = self._templates.update(
                views,
                obs.C[:, :, best],
                [Ek[:, best] for Ek in obs.E],
                update_angle=self._update_angle() if learn else np.inf,
                occlusion_fraction=cfg.occlusion_fraction,
                intensity_view=self._intensity_index,
                anchor_cos=cfg.anchor_cos,
                fixed=cfg.fixed_templates,
            )
        if len(self._first_angles) < UPDATE_FLOOR_FRAMES:
            self._first_angles.append(decision.angle)
        if decision.replaced is not None:
            self._bases = None  # a dictionary column changed: its range bases are recomputed
        state = (p / p.sum()) @ particles if cfg.estimate == "mean" else particles[best].copy()
        if self._scaler is not None:
            with self._timed("likelihood"):
                factor = self._rescaled(frame, state)
            state[:4] *= factor
            particles = particles.copy()
            particles[:, :4] *= factor
        self._velocity = np.zeros(2) if self._redetected else state[4:] - self._state[4:]
        self._expand = self._search_expand(float(obs.residual[best]))
        self._state = state
        self._work_box = tuple(float(v) for v in affine_to_box(self._state))
        self._box = tuple(float(v) for v in self._from_work(self._reported(self._work_box)))
        self._particles, self._weights = particles, p
        self._background = self._background_views(prepared, plane_scale)
        result = TrackResult(
            box=self._box,
            score=float(p[best]),
            residual=float(obs.residual[best]),
            occluded=decision.occluded,
            template_replaced=decision.replaced,
            frame_index=self._frame_index,
        )
        best_views = [v.copy() for v in views]
        return result, FrameDetail(particles, obs, best, probe_boxes, self._scale, best_views, self._reshape())

    def _rescaled(self, frame, state: np.ndarray) -> float:
        """The factor on ``state``'s scale (``(6,)``, working frame) that moves
        it ``config.scale_filter`` of the way, in log, to the scale filter's
        estimate (:meth:`smtmvt.scale.ScaleFilter.estimate`) at its centre,
        judged about the last reported box's size."""
        assert self._scaler is not None
        chosen = self._from_work(self._reported(affine_to_box(state)))
        last = np.asarray(self._box, dtype=np.float64)
        at = np.concatenate([chosen[:2] + (chosen[2:] - last[2:]) / 2.0, last[2:]])  # chosen centre, last size
        target = np.log(self._scaler.estimate(frame, at)) + 0.5 * np.log(last[2] * last[3])
        step = self.config.scale_filter * (target - 0.5 * np.log(chosen[2] * chosen[3]))
        return float(np.exp(step))

    def _update_angle(self) -> float:
        """The template update's trigger this frame, degrees: ``config.update_angle``,
        or with ``config.update_margin`` and once the first
        ``UPDATE_FLOOR_FRAMES`` frames are seen, the median of their angles plus
        the margin where that is lower."""
        margin = self.config.update_margin
        if margin is None or len(self._first_angles) < UPDATE_FLOOR_FRAMES:
            return self.config.update_angle
        return min(self.config.update_angle, float(np.median(self._first_angles)) + margin)

    def _reshape(self) -> tuple[float, float, float]:
        """``(aspect, fraction, factor)`` of the reported boxes: the first box's
        aspect ratio ``h / w`` (working frame), ``config.report_aspect`` and
        ``config.report_scale``."""
        first = affine_to_box(self._init_state)
        return float(first[3] / first[2]), float(self.config.report_aspect), float(self.config.report_scale)

    def _reported(self, work_box) -> np.ndarray:
        """The box reported for the state's box ``work_box`` (working frame): its
        aspect ratio moved ``config.report_aspect`` of the way (in log) to the
        first box's, at the same centre and area (:func:`box_with_aspect`),
        then its sides times ``config.report_scale`` (:func:`box_scaled`)."""
        return _reshaped_box(work_box, self._reshape())

    def _search_expand(self, residual: float) -> float:
        """Factor on the next frame's translation std (``config.search_expand``):
        the chosen residual over the median of the residuals chosen so far,
        within ``[1, search_expand]``."""
        cap = self.config.search_expand
        if cap <= 1.0:
            return 1.0
        self._residuals.append(residual)
        typical = float(np.median(self._residuals))
        if not typical > 0:
            return 1.0
        return float(np.clip(residual / typical, 1.0, cap))

    def _prune_eps(self, n: int) -> float:
        """Bounded coding's ``eps`` for n particles: 0 (code all) for models it is not exact for."""
        if self.config.model not in BOUNDED_CODING:
            return 0.0
        return min(self.config.prune_eps, 0.5 / n)

    def _code(self, X, D):
        """The observation model's solver on candidate views ``X`` (a subset of columns)."""
        cfg = self.config
        if cfg.model == "smtmvt":
            return solve_smtmvt(
                X, D, lam=cfg.lam, gamma=cfg.gamma, method=cfg.solver, tol=cfg.solver_tol, max_iter=cfg.solver_max_iter
            )
        return SOLVERS[cfg.model](X, D, tol=cfg.solver_tol, max_iter=cfg.solver_max_iter)

    @property
    def box(self) -> tuple:
        """Current box ``(x, y, w, h)``, 0-based pixels."""
        if not self._initialized:
            raise RuntimeError("tracker not initialized")
        return self._box


def track_frames(tracker: Tracker, frames, box):
    """Run ``tracker`` over ``frames``: ``init`` on the first with ``box``, ``update`` on the rest.

    Parameters
    ----------
    tracker : Tracker (or any object with the same ``init`` / ``update``).
    frames : iterable of frames; read lazily, one at a time.
    box : (x, y, w, h) 0-based pixels, the target in the first frame.

    Yields
    ------
    (frame, box, seconds) per frame: the frame, its 0-based box (``box`` itself
    for the first frame) and the seconds spent in ``init`` / ``update`` only
    (reading the frame is not counted).
    """
    for i, frame in enumerate(frames):
        t0 = time.perf_counter()
        if i == 0:
            tracker.init(frame, box)
            out = tuple(float(v) for v in box)
        else:
            out = tracker.update(frame).box
        yield frame, out, time.perf_counter() - t0
