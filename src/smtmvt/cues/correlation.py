"""The correlation cue: a correlation filter learned online (:mod:`smtmvt.correlation`).

The filter is trained on the first box and updated from each chosen box (in
the input frame's pixels, not the working frame's). Each frame it responds
over a window about the prediction (:meth:`CorrelationCue.respond`, with
``config.redetect_after`` a wider search once the target seems lost), and
that response serves four ends:

* the cost, ``config.correlation_weight * (r_max - r_i) / r_ref`` at each
  candidate's centre (:func:`smtmvt.correlation.correlation_cost`);
* the proposal: ``config.correlation_particles`` of the particles placed
  about its peak (:meth:`CorrelationCue.place`);
* the gates: whether the filter, the scale filter and the templates may
  learn from the frame (``config.correlation_learn_gate``,
  ``config.template_learn_gate``), judged against the responses before;
* the evidence of :mod:`smtmvt.confidence` (the peak and APCE ratios).

After the choice the filter also reads the reported box's size, over
windows of several sizes about its centre (``config.report_read_size``,
:meth:`CorrelationCue.read_size`); the track does not see that size.

The cue is on when either of ``correlation_weight`` and
``correlation_particles`` is; with the weight 0 it costs nothing.
"""

from __future__ import annotations

import numpy as np

from ..correlation import (
    CELL,
    PADDING,
    CorrelationFilter,
    apce,
    clears,
    correlation_cost,
    peak_level,
    peak_point,
    scaled_correlation_cost,
)
from ..geometry import affine_to_box, box_scaled, box_to_affine
from ..motion import place
from .base import Choice, Cue, Scene, Start

__all__ = ["CorrelationCue", "REDETECT_REACH", "READ_STEP"]

#: How far ``config.redetect_after``'s windows are moved, in box widths (x) and heights (y).
REDETECT_REACH = (0.5, 1.0)
#: Log side between the windows of ``config.report_read_size``.
READ_STEP = 0.05


class CorrelationCue(Cue):
    """The filter, its response each frame, and what is judged from it."""

    name = "correlation"

    def __init__(self, config) -> None:
        self.config = config
        self.weight = config.correlation_weight
        self.filter: CorrelationFilter | None = None
        self.scale = np.ones(2)  # working-frame pixels per input pixel
        #: whether this frame's response came from the wider search (config.redetect_after)
        self.redetected = False
        #: the correlation responses' mean peak before this frame (config.correlation_usual_peak)
        self.peak_ref: float | None = None
        self.last_learned = np.zeros(6)  # the last state the filter learned from

    @classmethod
    def from_config(cls, config, weight: float = 0.0) -> CorrelationCue | None:
        return cls(config) if config.correlation_weight or config.correlation_particles else None

    def start(self, start: Start) -> None:
        # on the frame as given (not the working frame)
        self.filter = CorrelationFilter(start.frame, start.box)
        self.scale = start.sampler.scale
        self.last_learned = start.state.copy()

    def _input_box(self, states) -> np.ndarray:
        """Working-frame states ``(6,)`` or ``(n, 6)`` -> their boxes, input-frame pixels."""
        return affine_to_box(states) / np.tile(self.scale, 2)

    # -- this frame's response --------------------------------------------------
    def respond(self, frame, box, lost: int) -> tuple:
        """The response over the window about ``box`` (the prediction, input-frame
        pixels), ``(response (h, w), Window)``; after ``lost`` frames in a row
        that seemed lost (``config.redetect_after``) the wider search's where it is better."""
        assert self.filter is not None
        cfg = self.config
        response = self.filter.response(frame, box, cfg.correlation_first)
        self.redetected = False
        if cfg.redetect_after and lost >= cfg.redetect_after:
            found = self._redetect(frame, box, response)
            if found is not None:
                response, self.redetected = found, True
        return response

    def _redetect(self, frame, box, response) -> tuple | None:
        """The wider search of ``config.redetect_after``: the best response
        over the windows about ``box`` (frame pixels) moved by half and by one
        box size in the eight directions, and about the last state the filter
        learned from; the response over the window centred on their highest
        peak where it beats ``response`` and passes the filter's learn gate
        against the frames before; else None."""
        assert self.filter is not None
        if not self.filter.history:
            return None
        cfg = self.config
        b = np.asarray(box, dtype=np.float64)
        moves = [(r * dx, r * dy) for r in REDETECT_REACH for dx in (-1, 0, 1) for dy in (-1, 0, 1) if dx or dy]
        boxes = [b + np.array([mx * b[2], my * b[3], 0.0, 0.0]) for mx, my in moves]
        last = self._input_box(self.last_learned)
        lb = b.copy()
        lb[:2] = last[:2] + (last[2:] - b[2:]) / 2.0  # the last learned centre, this frame's size
        if np.hypot(*(lb[:2] - b[:2])) > 0.5 * np.sqrt(b[2] * b[3]):
            boxes.append(lb)
        best = max((self.filter.response(frame, c, cfg.correlation_first) for c in boxes), key=lambda rw: rw[0].max())
        # judged on the window centred on that peak: off the window's centre the Hann
        # window weakens the target and its APCE says little
        centred = b.copy()
        centred[:2] = peak_point(*best) - (b[2:] - 1.0) / 2.0
        best = self.filter.response(frame, centred, cfg.correlation_first)
        if not best[0].max() > response[0].max():
            return None
        return best if self._clears_gate(best[0]) else None

    def _clears_gate(self, r: np.ndarray) -> bool:
        """Whether the response ``r`` clears ``config.correlation_learn_gate``
        against the mean of the responses judged before (:func:`clears`), without
        recording it; needs one judged before."""
        assert self.filter is not None
        past = np.mean(self.filter.history, axis=0)
        return clears(((float(r.max()), apce(r)), past), self.config.correlation_learn_gate)

    def prefers(self, response, other) -> bool:
        """Whether ``other`` (a response over another window, ``(response,
        Window)``) should replace this frame's ``response``: ``response`` fails
        ``config.correlation_learn_gate`` against the responses judged before
        (:func:`clears`; nothing is recorded: the prediction seems to have lost
        the target) and ``other``'s peak is the higher. False before the first
        response is judged, and with the gate off."""
        assert self.filter is not None
        if not self.filter.history or not any(self.config.correlation_learn_gate):
            return False
        return not self._clears_gate(response[0]) and bool(other[0].max() > response[0].max())

    def place(self, moved: np.ndarray, rng: np.random.Generator, response) -> tuple[np.ndarray, int, bool]:
        """A proposal for :meth:`smtmvt.particles.ParticleFilter.propagate`:
        ``moved`` (n, 6) with its last ``config.correlation_particles`` share
        (where resampling puts copies of the best) placed about the peak of
        ``response`` (:func:`smtmvt.motion.place`); how many were placed; and
        whether they have no parent for the motion cue (a wider search's)."""
        count = int(round(self.config.correlation_particles * len(moved)))
        if not count:
            return moved, 0, self.redetected
        r, window = response
        # about the peak cell's centre (as the centre of a one-pixel box, to map it to the
        # working frame as box centres are), half a cell's standard deviation
        peak = np.array([[*peak_point(r, window), 1.0, 1.0]]) * np.tile(self.scale, 2)
        point = box_to_affine(peak)[0, 4:]
        step = np.asarray(window.step) * self.scale  # frame pixels per window pixel, working frame
        return place(moved, count, point, 0.5 * CELL * step, rng), count, self.redetected

    # -- the gates ----------------------------------------------------------------
    def judge(self, response):
        """This frame's ``response`` judged against the responses before
        (:meth:`CorrelationFilter.judge`: ``(now, past)``, None on the first),
        or None without a gate to judge it by. Sets :attr:`peak_ref`."""
        cfg = self.config
        judged = None
        if any(cfg.correlation_learn_gate + cfg.template_learn_gate):
            assert self.filter is not None
            judged = self.filter.judge(response[0])
        # config.correlation_usual_peak: the correlation cue's scale, the mean peak of the responses before
        self.peak_ref = float(judged[1][0]) if judged is not None and cfg.correlation_usual_peak else None
        return judged

    def seems_lost(self, judged) -> bool:
        """Whether the ``judged`` response says the target is lost: its peak
        below ``config.template_learn_floor`` times its mean over the frames before."""
        if judged is None:
            return False
        now, past = judged
        return bool(now[0] < self.config.template_learn_floor * past[0])

    def near_peak(self, state: np.ndarray, response) -> bool:
        """Whether ``state``'s box (working frame) lies within half its size of
        the peak of ``response``."""
        box = self._input_box(state)
        centre = box_to_affine(box)[4:]
        return bool(np.hypot(*(centre - peak_point(*response))) <= 0.5 * np.sqrt(box[2] * box[3]))

    def templates_learn(self, judged, state: np.ndarray, response) -> bool:
        """Whether the template update may replace a template this frame, the
        chosen particle's ``state``: with ``config.template_learn_gate`` only
        when the response clears the gate against the mean of the
        ``config.template_learn_memory`` responses before and does not
        :meth:`seems_lost`; after a wider search only near its peak."""
        cfg = self.config
        if any(cfg.template_learn_gate) and judged is not None:
            assert self.filter is not None
            recent = clears(self.filter.judged(cfg.template_learn_memory), cfg.template_learn_gate)
            if not (recent and not self.seems_lost(judged)):
                return False
        return not self.redetected or self.near_peak(state, response)

    def learns(self, judged, state: np.ndarray, response) -> bool:
        """Whether the filter (and the scale filter) learn from this frame's
        new ``state``: the ``judged`` response clears
        ``config.correlation_learn_gate`` (:func:`clears`) and, after a wider
        search, the state is near its peak."""
        gate = self.config.correlation_learn_gate
        return (not any(gate) or clears(judged, gate)) and (not self.redetected or self.near_peak(state, response))

    # -- the cue ------------------------------------------------------------------
    def costs(self, response, states: np.ndarray) -> np.ndarray:
        """``weight * (r_max - r_i) / r_ref`` at the centre of each state ``(n, 6)``
        (working frame) on ``response`` (:meth:`respond`), ``r_ref`` its peak
        ``r_max`` or with ``config.correlation_usual_peak`` the mean peak before
        (:attr:`peak_ref`), ``(n,)``."""
        centres = box_to_affine(self._input_box(states))[:, 4:]
        r, window = response
        return self.weight * correlation_cost(r, window, centres, self.peak_ref)

    def scaled_costs(self, frame, response, states: np.ndarray) -> np.ndarray:
        """``config.correlation_scales``: :meth:`costs` read at each state's
        size too (:func:`smtmvt.correlation.scaled_correlation_cost`): the
        filter's responses over windows about ``response``'s centre
        ``config.correlation_scale_step`` apart in log side, ``response``'s
        own in the middle, ``(n,)``."""
        assert self.filter is not None
        cfg = self.config
        r0, w0 = response
        H, W = w0.size
        size = np.array([w0.step[0] * W, w0.step[1] * H]) / PADDING  # the window's box (w, h), frame pixels
        centre = np.array(w0.origin) + (np.array([W, H]) - 1.0) / 2.0 * np.array(w0.step)
        own = np.array([*(centre - (size - 1.0) / 2.0), *size])  # the box whose window it is
        levels = []
        for j in range(-cfg.correlation_scales, cfg.correlation_scales + 1):
            ls = j * cfg.correlation_scale_step
            if j == 0:
                levels.append((0.0, r0, w0))
                continue
            levels.append((ls, *self.filter.response(frame, box_scaled(own, np.exp(ls)), cfg.correlation_first)))
        boxes = self._input_box(states)
        log_sides = 0.5 * np.log(boxes[:, 2] * boxes[:, 3] / (size[0] * size[1]))
        centres = box_to_affine(boxes)[:, 4:]
        return self.weight * scaled_correlation_cost(levels, centres, log_sides, self.peak_ref)

    def read_size(self, frame, box) -> np.ndarray:
        """``config.report_read_size``: ``box`` ``(4,)`` (input-frame pixels)
        about its centre at the size the filter reads there: the filter's
        responses over ``2 J + 1`` windows ``READ_STEP`` apart in log side
        about ``box``'s (``J`` the option), the log side of the highest peak
        (:func:`smtmvt.correlation.peak_level`)."""
        assert self.filter is not None
        cfg = self.config
        J, step = cfg.report_read_size, READ_STEP
        peaks = [
            float(self.filter.response(frame, box_scaled(box, np.exp(j * step)), cfg.correlation_first)[0].max())
            for j in range(-J, J + 1)
        ]
        return box_scaled(box, np.exp(peak_level(peaks, step)))

    def cost(self, scene: Scene) -> np.ndarray | None:
        """:meth:`costs` of the scene's candidates (:meth:`scaled_costs` with
        ``config.correlation_scales``); None with the weight 0."""
        if scene.response is None or not self.weight:
            return None
        if self.config.correlation_scales:
            return self.scaled_costs(scene.frame, scene.response, scene.states)
        return self.costs(scene.response, scene.states)

    def learn(self, scene: Scene, choice: Choice) -> None:
        assert self.filter is not None
        if self.learns(scene.judged, choice.state, scene.response):
            self.last_learned = choice.state.copy()
            self.filter.update(
                scene.frame, np.asarray(choice.work_box) / np.tile(self.scale, 2), self.config.correlation_rate
            )
