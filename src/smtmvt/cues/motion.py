"""The motion cue: the random walk's density at each candidate (:mod:`smtmvt.motion`).

A particle's cost is ``config.motion_weight * d^2 / (2 alpha)``, ``d^2`` its
translation's squared distance from its own prediction (its parent moved by
the velocity term) in the random walk's standard deviations
(:func:`smtmvt.motion.translation_distance`): with the likelihood's ``alpha``
the weight multiplies the log of a Gaussian density. A probe, which has no
parent, is measured from the frame's prediction at the last state's scale.
"""

from __future__ import annotations

import numpy as np

from ..motion import translation_distance, translation_std
from .base import Cue, Scene

__all__ = ["MotionCue"]


class MotionCue(Cue):
    """``weight * 0.5 * d_i^2 / alpha``."""

    name = "motion"

    def __init__(self, config) -> None:
        self.config = config

    @classmethod
    def from_config(cls, config, weight: float = 0.0) -> MotionCue | None:
        return cls(config) if config.motion_weight else None

    def cost(self, scene: Scene) -> np.ndarray:
        cfg = self.config
        d2 = translation_distance(scene.particles, *scene.steps)
        if len(scene.probes):
            std = translation_std(scene.state, cfg.affine_std, cfg.translation_power)
            d2 = np.concatenate([d2, translation_distance(scene.probes, scene.predicted[4:], std)])
        return cfg.motion_weight * 0.5 * d2 / cfg.alpha
