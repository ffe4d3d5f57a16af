"""The foreground cue: a color model of the first box against its surroundings (:mod:`smtmvt.foreground`).

At the first frame the cue learns the model (:func:`smtmvt.foreground.foreground_model`,
on the whole first frame); a candidate's cost is ``config.foreground_weight
* (1 - c_i)``, ``c_i`` the contrast of the foreground map inside its box
against the ring around it (:func:`smtmvt.foreground.box_contrast`). It
reads the planes ``RING`` times each box about its centre.
"""

from __future__ import annotations

import numpy as np

from ..foreground import RING, box_contrast, foreground_map, foreground_model, ring_window
from ..preprocess import PreparedFrame
from ..sampling import plane_boxes
from .base import Cue, Scene, Start

__all__ = ["ForegroundCue", "contrast"]


def contrast(model: np.ndarray, frame: PreparedFrame, states: np.ndarray, plane_scale: float) -> np.ndarray:
    """Foreground contrast (:func:`smtmvt.foreground.box_contrast`) of each
    state's box ``(m, 6)`` on the frame's color plane, ``(m,)`` float64, with
    the color ``model`` of :func:`smtmvt.foreground.foreground_model`."""
    boxes = plane_boxes(frame, states, plane_scale)
    window = ring_window(boxes, frame.shape)  # the map is needed only where the boxes' rings reach
    return box_contrast(foreground_map(frame.color, model, window), boxes)


class ForegroundCue(Cue):
    """``weight * (1 - c_i)``."""

    name = "foreground"
    reach = RING

    def __init__(self, weight: float) -> None:
        self.weight = weight
        self.model: np.ndarray | None = None

    @classmethod
    def from_config(cls, config, weight: float = 0.0) -> ForegroundCue | None:
        return cls(config.foreground_weight) if config.foreground_weight else None

    def start(self, start: Start) -> None:
        # the first box against its surroundings, on the whole frame
        self.model = foreground_model(start.prepared.color, start.work_box)

    def contrast(self, frame: PreparedFrame, states: np.ndarray, plane_scale: float) -> np.ndarray:
        """:func:`contrast` with the cue's model (after :meth:`start`)."""
        if self.model is None:
            raise RuntimeError("the foreground cue has not started")
        return contrast(self.model, frame, states, plane_scale)

    def cost(self, scene: Scene) -> np.ndarray:
        c = self.contrast(scene.prepared, scene.particles, scene.plane_scale)
        if len(scene.probes):
            c = np.concatenate([c, self.contrast(scene.probe_planes, scene.probes, scene.plane_scale)])
        return self.weight * (1.0 - c)
