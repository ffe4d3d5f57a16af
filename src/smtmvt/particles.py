"""The particle filter's prediction: where this frame's candidates are drawn.

A :class:`ParticleFilter` keeps, from frame to frame, the particles (affine
states ``(n, 6)``, working frame) and their likelihoods, the target's
velocity and how far to search. Each frame (:meth:`ParticleFilter.propagate`)
the particles are resampled by their likelihoods and moved by the random
walk of :mod:`smtmvt.motion` (with ``config.velocity`` and its share of the
particles, ``config.narrow_fraction``'s narrower search, ``config.shape_pull``,
``config.search_expand``); a proposal may then move some of them (the
correlation cue places a share about its peak). After the choice
(:meth:`ParticleFilter.chosen`) the weights are the particles' likelihoods.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .config import TrackerConfig
from .motion import propagate, pull_shape, resample, translation_std

__all__ = ["ParticleFilter"]


class ParticleFilter:
    """The particles of a track and its motion model.

    Parameters
    ----------
    config : TrackerConfig
        ``n_particles``, ``affine_std``, ``translation_power``, ``aspect_std``,
        ``velocity``, ``velocity_fraction``, ``narrow_fraction``,
        ``narrow_scale``, ``shape_pull``, ``search_expand``.
    state : (6,) float64
        The first state: every particle starts there.

    Attributes
    ----------
    particles : (n, 6) the last frame's particles; ``weights`` (n,) their likelihoods.
    velocity : (2,) the last frame's move (working-frame pixels).
    expand : factor on the next frame's translation std (``config.search_expand``).
    steps : ``(predicted (n, 2), std (n, 2))`` of the last :meth:`propagate`:
        each particle's predicted translation (its parent moved by the velocity
        term) and the random walk's translation std there (the motion cue's).
    """

    def __init__(self, config: TrackerConfig, state: np.ndarray) -> None:
        cfg = self.config = config
        n = cfg.n_particles
        self.init_state = np.array(state, dtype=np.float64)
        self.velocity = np.zeros(2)
        self.residuals: list[float] = []  # the chosen candidates' residuals (config.search_expand)
        self.expand = 1.0
        # velocity_fraction of the particles, evenly spread over the indices, take the velocity term
        i = np.arange(n)
        moved = np.floor((i + 1) * cfg.velocity_fraction) > np.floor(i * cfg.velocity_fraction)
        self.velocity_share = None if moved.all() else moved.astype(np.float64)[:, None]
        # the first narrow_fraction of the particles search with narrow_scale times the std
        self.spread = None
        if cfg.narrow_fraction > 0:
            self.spread = np.ones(n)
            self.spread[: int(round(cfg.narrow_fraction * n))] = cfg.narrow_scale
        self.steps: tuple | None = None
        self.keep(self.init_state)

    def predicted(self, state: np.ndarray) -> np.ndarray:
        """This frame's prediction ``(6,)``: ``state`` (the last one), its
        translation moved by the velocity term."""
        predicted = state.copy()
        if self.config.velocity:
            predicted[4:] += self.config.velocity * self.velocity
        return predicted

    def propagate(self, rng: np.random.Generator, proposal: Callable | None = None) -> np.ndarray:
        """This frame's ``(n, 6)`` particles: the last frame's resampled by their
        likelihoods, then moved by the random walk (and the velocity term).

        ``proposal(moved, rng) -> (moved, count, own)`` may then replace the
        last ``count`` of them; with ``own`` true they have no parent for the
        motion cue (their predicted translation is their own). Sets :attr:`steps`.
        """
        cfg = self.config
        particles = resample(self.particles, self.weights, cfg.n_particles)
        if cfg.shape_pull:
            particles = pull_shape(particles, self.init_state, cfg.shape_pull)
        shift = cfg.velocity * self.velocity if cfg.velocity else None
        if shift is not None and self.velocity_share is not None:
            shift = self.velocity_share * shift
        std = cfg.affine_std
        if self.expand > 1.0:  # config.search_expand: a wider search after a poorly explained frame
            std = (*std[:4], std[4] * self.expand, std[5] * self.expand)
        moved = propagate(particles, std, rng, shift, self.spread, cfg.translation_power, cfg.aspect_std)
        count, own = 0, False
        if proposal is not None:
            moved, count, own = proposal(moved, rng)
        predicted = particles[:, 4:] + (0.0 if shift is None else shift)
        if own and count:
            predicted[len(moved) - count :] = moved[len(moved) - count :, 4:]
        self.steps = (predicted, translation_std(particles, std, cfg.translation_power))
        return moved

    def keep(self, state: np.ndarray) -> None:
        """Every particle at ``state``, all weights equal (no candidate explained the frame)."""
        n = self.config.n_particles
        self.particles = np.repeat(state[None], n, axis=0)
        self.weights = np.full(n, 1.0 / n)

    def chosen(self, particles: np.ndarray, likelihood: np.ndarray, velocity: np.ndarray, residual: float) -> None:
        """After the choice: the ``particles`` (n, 6) and their ``likelihood``
        (n,) for the next resampling, the target's ``velocity`` (2,) and the
        chosen ``residual`` (:meth:`search_expand`)."""
        self.particles, self.weights = particles, likelihood
        self.velocity = velocity
        self.expand = self.search_expand(residual)

    def search_expand(self, residual: float) -> float:
        """Factor on the next frame's translation std (``config.search_expand``):
        the chosen residual over the median of the residuals chosen so far,
        within ``[1, search_expand]``."""
        cap = self.config.search_expand
        if cap <= 1.0:
            return 1.0
        self.residuals.append(residual)
        typical = float(np.median(self.residuals))
        if not typical > 0:
            return 1.0
        return float(np.clip(residual / typical, 1.0, cap))
