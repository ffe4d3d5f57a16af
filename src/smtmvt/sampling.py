"""The candidates' pixels: a frame's planes, cropped where the candidates read, and their patches and views.

The tracker works in a *working frame* (``config.frame_size``; the input frame
otherwise) and, with ``config.scale_normalize``, on planes resized so that the
target keeps its first size (``plane_scale``: plane pixels per working-frame
pixel). A :class:`Sampler` turns a frame into those planes
(:meth:`Sampler.prepare`, on the window the candidates read only with
``config.crop_planes``) and a batch of affine states ``(m, 6)`` (working
frame) into their :class:`~smtmvt.features.Patches` (:meth:`Sampler.patches`,
one batched remap per plane, each plane smoothed first against aliasing) and
views (:meth:`Sampler.views`, ``(d_k, m)`` float32 each).

Everything here depends on the frame and the states only, except three things
of the track passed in by the caller: the current box (its size sets the
anti-aliasing), the current state (about which Tan-Triggs takes its
statistics on a crop) and whether this frame's planes are whole
(``config.crop_refresh``).
"""

from __future__ import annotations

from collections.abc import Callable
from contextlib import AbstractContextManager, nullcontext
from typing import Any

import cv2
import numpy as np

from .config import TrackerConfig
from .features import Patches, extract_views, intensity_template_size
from .features.coarse import GAMMA_FLOOR
from .features.tan_triggs import TAN_TRIGGS_GAMMA
from .geometry import affine_extent, affine_to_box
from .preprocess import (
    PreparedFrame,
    plane_window,
    prepare_crop,
    prepare_frame,
    resize_frame,
    sample_window,
    smooth,
    smooth_reach,
    to_unit_range,
)
from .warp import remap_patches, sampling_grid

__all__ = ["Sampler", "DOG_RATIO", "plane_boxes", "plane_extent", "weighted_views"]

#: The "dog" intensity plane's outer Gaussian, in multiples of the inner one (Tan-Triggs' 2 / 1).
DOG_RATIO = 2.0


def plane_extent(params: np.ndarray, plane_scale: float) -> tuple:
    """Bounding box ``(x0, y0, x1, y1)`` of the states' squares ``(m, 6)`` on the plane."""
    x0, y0, x1, y1 = affine_extent(params)
    if plane_scale != 1.0:
        x0, y0, x1, y1 = ((v + 0.5) * plane_scale - 0.5 for v in (x0, y0, x1, y1))
    return x0, y0, x1, y1


def plane_boxes(frame: PreparedFrame, states: np.ndarray, plane_scale: float) -> np.ndarray:
    """The states' boxes ``(m, 4)`` in the pixels of the frame's planes (a crop's own)."""
    boxes = affine_to_box(states).reshape(-1, 4) * plane_scale
    boxes[:, 0] -= frame.origin[0]
    boxes[:, 1] -= frame.origin[1]
    return boxes


def weighted_views(views: list, weights, index) -> list:
    """``views`` (the views of indices ``index`` of ``config.views``) scaled by
    ``sqrt(weights[i])`` (unchanged when ``weights`` is None): the coding and
    the likelihood then weigh view i's squared residual by its weight."""
    if weights is None:
        return list(views)
    return [np.float32(np.sqrt(weights[i])) * v for i, v in zip(index, views)]


def color_and_raw(frame: PreparedFrame, sigma: float, win, X, Y) -> tuple[np.ndarray, np.ndarray]:
    """The color ``(n, fh, fw, C)`` and raw gray ``(n, fh, fw)`` patches on one
    grid ``(X, Y)`` and smoothing ``sigma``, sampled together: a gray frame's
    color plane is its gray plane, sampled once; an RGB frame's three channels
    and its gray plane are smoothed and sampled as one 4-channel plane (OpenCV
    samples 4 channels in about the time of 1, with the same values as each
    channel alone); the color channels are copied out by OpenCV (numpy's copy
    of a 3-of-4-channel view costs more than the sampling saves), the gray one
    is returned as a strided view (copied by the views that read it, and only
    for the candidates they are computed for when deferred)."""
    if frame.color.shape[2] == 1:  # prepare_frame: a gray frame's color plane is its gray plane
        color = remap_patches(smooth(frame.color, sigma, win), X, Y)
        return color, color[..., 0]
    plane = cv2.merge([frame.color[..., 0], frame.color[..., 1], frame.color[..., 2], frame.gray])
    both = remap_patches(smooth(plane, sigma, win), X, Y)
    n, ph, pw, _ = both.shape
    color = cv2.cvtColor(both.reshape(n * ph, pw, 4), cv2.COLOR_RGBA2RGB).reshape(n, ph, pw, 3)
    return color, both[..., 3]  # a strided view: copied only where a view reads it


class Sampler:
    """A frame's planes and the patches and views of affine states on them.

    Parameters
    ----------
    config : TrackerConfig
        The views and how they are sampled (``views``, ``feature_size``,
        ``color_size``, ``intensity_factor``, ``intensity_plane``,
        ``antialias``, ``frame_size``, ``crop_*``, view options).
    scale : (2,) float
        Working-frame pixels per input pixel (x, y).
    first_box : (4,) float
        The first box, working frame: it sets the intensity template's size.
    crop : bool
        Planes on the candidates' window only (``config.crop_planes``, unless
        a cue reads beyond the candidates' boxes: :attr:`smtmvt.cues.Cue.whole_frame`).
    grow : float >= 1
        Factor on the states' boxes for the window cropped: the cues read the
        planes that far around each box (:attr:`smtmvt.cues.Cue.reach`).
    timed : optional ``timed(stage)`` context manager factory (as
        :meth:`smtmvt.Tracker`'s), timing ``"warp"`` and ``"features"``.
    """

    def __init__(self, config: TrackerConfig, scale, first_box, crop: bool, grow: float = 1.0, timed=None) -> None:
        cfg = self.config = config
        self.scale = np.asarray(scale, dtype=np.float64)
        self.crop, self.grow = crop, grow
        self._timed: Callable[[str], AbstractContextManager] = timed or (lambda stage: nullcontext())
        #: config.crop_refresh: the last whole plane's Tan-Triggs divisors
        self.tt_divisors: tuple | None = None
        # in the working frame, as the paper
        self.intensity_size = intensity_template_size(first_box[2], first_box[3], cfg.intensity_factor)
        self.view_options: dict[str, dict[str, Any]] = {
            "color": {"grid": cfg.color_grid, "power": cfg.histogram_power},
            "hog": {"plane": cfg.hog_plane},
            "lbp": {"radius": cfg.lbp_radius, "plane": cfg.lbp_plane, "power": cfg.histogram_power},
        }
        # the feature-size gray planes the views read (only those are warped; a
        # registered view of another name may read either)
        read = {"hog": {cfg.hog_plane}, "lbp": {cfg.lbp_plane}, "coarse": {"gray"}, "intensity": set(), "color": set()}
        planes = set().union(*(read.get(view, {"gray", "tan_triggs"}) for view in cfg.views))
        self.needs_raw, self.needs_gray = "gray" in planes, "tan_triggs" in planes
        # the Patches arrays each built-in view reads (a deferred view gets only those)
        array_of = {"gray": "raw", "tan_triggs": "gray"}
        self.reads = {view: {array_of[p] for p in read[view]} | ({view} & {"intensity", "color"}) for view in read}

    # -- planes ------------------------------------------------------------
    def prepare(
        self, frame, where: str, channels, plane_scale: float, states, *, box, state, frame_index: int
    ) -> PreparedFrame:
        """The frame's planes at ``plane_scale`` times the working frame's size.

        With ``states`` (m, 6) and ``crop``, only the window of them that those
        states' patches read (:func:`prepare_crop`), their boxes grown by
        ``grow``; Tan-Triggs' statistics are then the last whole plane's
        (``config.crop_refresh``, whose frames ``frame_index`` get whole planes)
        or those of the current ``state`` (6,) grown by ``config.crop_context``.
        ``box`` is the current box (working frame, its size sets the smoothing).
        """
        cfg = self.config
        if np.ndim(frame) < 2:
            to_unit_range(frame, where)  # raises, naming the frame and its shape
        shape = np.shape(frame)
        size = self._plane_size(shape, plane_scale)
        # config.crop_refresh: the whole plane (init's first call is frame 0, so the divisors are always set)
        refresh = bool(cfg.crop_refresh) and frame_index % cfg.crop_refresh == 0
        if states is not None and self.crop and not refresh:
            plane_shape = (shape[0], shape[1]) if size is None else (size[1], size[0])
            sigmas = self.smoothing(plane_scale, box)
            reach = smooth_reach(max(*sigmas, DOG_RATIO * sigmas[0] if cfg.intensity_plane == "dog" else 0.0)) + 1
            if self.grow != 1.0:  # a cue reads around the boxes
                states = np.array(states, dtype=np.float64)
                states[:, :4] *= self.grow
            window = plane_window(plane_extent(states, plane_scale), plane_shape, reach)
            scale = (self.scale[0] * plane_scale, self.scale[1] * plane_scale)
            if cfg.crop_refresh:  # Tan-Triggs' statistics: the last whole plane's
                return prepare_crop(frame, where, channels, window, scale, plane_shape, contrast=self.tt_divisors)
            # Tan-Triggs' statistics: the current box grown by crop_context about its centre
            context = np.array(state, dtype=np.float64)
            context[:4] *= cfg.crop_context
            stats = plane_window(plane_extent(context[None], plane_scale), plane_shape)
            return prepare_crop(frame, where, channels, window, scale, plane_shape, stats)
        if size is not None:
            frame = resize_frame(to_unit_range(frame, where), size)
        prepared = prepare_frame(frame, where, channels)
        if refresh:
            self.tt_divisors = prepared.contrast
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

    def smoothing(self, plane_scale: float, box) -> tuple[float, float, float]:
        """Anti-aliasing sigmas (plane pixels) of the intensity, feature-size and
        color patches: ``config.antialias`` times the sampling step of a target
        of ``box``'s size (working frame)."""
        cfg = self.config
        fs = cfg.feature_size
        cs = cfg.color_size or fs
        w, h = box[2] * plane_scale, box[3] * plane_scale
        steps = (
            max(w / self.intensity_size[1], h / self.intensity_size[0]),
            max(w / fs[1], h / fs[0]),
            max(w / cs[1], h / cs[0]),
        )
        sig_i, sig_f, sig_c = (cfg.antialias * step for step in steps)
        return sig_i, sig_f, sig_c

    def intensity_plane(self, frame: PreparedFrame, sigma: float, win) -> np.ndarray:
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

    # -- patches and views --------------------------------------------------
    def patches(self, frame: PreparedFrame, params: np.ndarray, plane_scale: float, box) -> Patches:
        """The patches of the states ``params (m, 6)``.

        ``frame``'s planes may be the working frame resized by ``plane_scale``
        (plane pixels per working-frame pixel, see ``config.scale_normalize``):
        the sampling grids are mapped onto them (pixel edges to pixel edges).
        With ``config.antialias`` > 0 each plane is first smoothed by a Gaussian
        of ``antialias`` times the sampling step of a target of ``box``'s size
        (its size on the plane over the patch size), so that sampling it on the
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
            x0, y0, x1, y1 = plane_extent(params, plane_scale)
            win = sample_window((x0 - ox, y0 - oy, x1 - ox, y1 - oy), frame.shape)
            sig_i, sig_f, sig_c = self.smoothing(plane_scale, box)
            X, Y = grid(fs)
            intensity = remap_patches(self.intensity_plane(frame, sig_i, win), *grid(self.intensity_size))
            gray = remap_patches(smooth(frame.normalized, sig_f, win), X, Y) if self.needs_gray else None
            raw: np.ndarray | None
            # sampled together on a crop only: on a whole plane the whole-plane merge and
            # smoothing output cost more than the 4-channel sampling saves (docs/stops.md#stop18)
            if self.needs_raw and cs == fs and sig_c == sig_f and frame.full_shape is not None:
                color, raw = color_and_raw(frame, sig_f, win, X, Y)
            else:
                XC, YC = (X, Y) if cs == fs else grid(cs)
                color = remap_patches(smooth(frame.color, sig_c, win), XC, YC).reshape(len(params), cs[0], cs[1], -1)
                raw = remap_patches(smooth(frame.gray, sig_f, win), X, Y) if self.needs_raw else None
            return Patches(intensity=intensity, gray=gray, color=color, raw=raw)

    def extract(self, patches: Patches, views) -> list:
        """The views named ``views`` of ``patches``, ``[(d_k, m) float32]``."""
        with self._timed("features"):
            return extract_views(patches, views, self.view_options)

    def views(self, frame: PreparedFrame, params: np.ndarray, plane_scale: float, box, views=None) -> list:
        """The views ``[(d_k, m) float32]`` (``views``, default ``config.views``)
        of the states ``params (m, 6)`` (see :meth:`patches`)."""
        return self.extract(
            self.patches(frame, params, plane_scale, box), self.config.views if views is None else views
        )

    def weighted(self, views: list, first: int = 0, index=None) -> list:
        """``views`` (views ``first, first + 1, ...`` of ``config.views``, or the
        views of indices ``index``) weighted by ``config.view_weights``
        (:func:`weighted_views`)."""
        if index is None:
            index = range(first, first + len(views))
        return weighted_views(views, self.config.view_weights, index)

    @property
    def term_index(self) -> list[int]:
        """The indices in ``config.views`` of ``config.term_views`` (the anchor's and the background's)."""
        cfg = self.config
        return [cfg.views.index(v) for v in cfg.term_views if v in cfg.views]

    def terms_of(self, views: list) -> list:
        """The term views (``config.term_views``) among ``views`` (the first
        ``len(views)`` of ``config.views``, in that order: the deferred ones may
        be left out), weighted as by :meth:`weighted`."""
        index = [i for i in self.term_index if i < len(views)]
        return self.weighted([views[i] for i in index], index=index)
