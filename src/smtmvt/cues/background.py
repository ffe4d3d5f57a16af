"""The background cue: tell the target from what surrounded it (:mod:`smtmvt.background`).

After each frame the cue takes the term views (``config.term_views``) of
``config.background_samples`` boxes on a ring around the chosen state
(:func:`smtmvt.background.ring_states`, drawn from the tracker's generator);
the next frame's candidates that look like them cost
``config.background_weight * (b_max - b_i)``. It reads the planes far beyond
the candidates (no cropped planes) and needs its views for every candidate
(none deferred).
"""

from __future__ import annotations

import numpy as np

from ..background import background_offsets, ring_states
from .base import Choice, Cue, Scene, Start

__all__ = ["BackgroundCue"]


class BackgroundCue(Cue):
    """``weight * (b_max - b_i)``, ``b_i`` the candidate's residual over the ring's views."""

    name = "background"
    whole_frame = True

    def __init__(self, config) -> None:
        self.config = config
        self.weight = config.background_weight
        #: the ring's term views, weighted (K_terms arrays (d_k, m))
        self.views: list | None = None

    @classmethod
    def from_config(cls, config, weight: float = 0.0) -> BackgroundCue | None:
        return cls(config) if config.background_weight else None

    def eager_views(self) -> tuple:
        return tuple(self.config.term_views)

    def _ring(self, sampler, prepared, state, box, rng, plane_scale: float = 1.0) -> list:
        """The term views (weighted) of the ring about ``state`` in ``prepared``."""
        ring = ring_states(state, self.config.background_samples, rng)
        index = sampler.term_index
        views = sampler.views(prepared, ring, plane_scale, box, [self.config.views[i] for i in index])
        return sampler.weighted(views, index=index)

    def start(self, start: Start) -> None:
        self.views = self._ring(start.sampler, start.prepared, start.state, start.work_box, start.rng)

    def cost(self, scene: Scene) -> np.ndarray | None:
        if self.views is None or not scene.term_views:
            return None
        return background_offsets(scene.term_views, self.views, self.weight, self.config.background_measure)

    def learn(self, scene: Scene, choice: Choice) -> None:
        # in the frame the state was just estimated in: an object beside the target now is background next
        assert scene.rng is not None
        self.views = self._ring(
            scene.sampler, scene.prepared, choice.state, choice.work_box, scene.rng, scene.plane_scale
        )
