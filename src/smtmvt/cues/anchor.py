"""The anchor cue: keep the box on what the first frame showed (:mod:`smtmvt.anchor`).

Its cost is ``config.anchor_weight`` times each candidate's nonnegative
least-squares residual over the first template alone, summed over the term
views (``config.term_views``, weighted by ``config.view_weights``); a term
view computed late (``config.deferred_views``) brings its part when it is
computed (:meth:`AnchorCue.view_cost`).
"""

from __future__ import annotations

import numpy as np

from ..anchor import anchor_offsets
from .base import Cue, Scene

__all__ = ["AnchorCue"]


class AnchorCue(Cue):
    """``weight * sum_k min_{c >= 0} ||c t^k - x_i^k||^2`` over the term views."""

    name = "anchor"

    def __init__(self, weight: float) -> None:
        self.weight = weight

    @classmethod
    def from_config(cls, config, weight: float = 0.0) -> AnchorCue | None:
        return cls(config.anchor_weight) if config.anchor_weight else None

    def cost(self, scene: Scene) -> np.ndarray | None:
        X_terms = scene.term_views
        if not X_terms:
            return None
        first = scene.sampler.terms_of([Dk[:, 0] for Dk in scene.templates.dictionaries[: len(scene.views)]])
        return anchor_offsets(X_terms, first, self.weight)

    def view_cost(self, scene: Scene, k: int, view: np.ndarray) -> np.ndarray | None:
        if k not in scene.sampler.term_index:
            return None
        first = scene.sampler.weighted([scene.templates.dictionaries[k][:, 0]], first=k)
        return anchor_offsets([view], first, self.weight)
