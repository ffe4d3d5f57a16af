"""The scale-push cue: favour larger boxes (``config.scale_push``, docs/experiments.md#n42).

Its cost is ``-scale_push * log(s_i / s)``, ``s_i = sqrt(w_i h_i)`` the
candidate's box size and ``s`` the last state's: negative for a box larger
than the last one.
"""

from __future__ import annotations

import numpy as np

from ..geometry import affine_to_box
from .base import Cue, Scene

__all__ = ["ScalePushCue", "log_scale"]


def log_scale(states: np.ndarray, state: np.ndarray) -> np.ndarray:
    """``log(s_i / s)`` of each state ``(n, 6)``: its box's size ``sqrt(w h)``
    against ``state``'s ``(6,)``, ``(n,)``."""
    wh = affine_to_box(states).reshape(-1, 4)[:, 2:]
    w0, h0 = affine_to_box(state)[2:]
    return 0.5 * np.log(wh[:, 0] * wh[:, 1] / (w0 * h0))


class ScalePushCue(Cue):
    """``-weight * log(s_i / s)``."""

    name = "scale_push"

    def __init__(self, weight: float) -> None:
        self.weight = weight

    @classmethod
    def from_config(cls, config, weight: float = 0.0) -> ScalePushCue | None:
        return cls(config.scale_push) if config.scale_push else None

    def cost(self, scene: Scene) -> np.ndarray:
        return -self.weight * log_scale(scene.states, scene.state)
