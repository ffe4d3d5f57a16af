"""Motion model: Gaussian random walk over affine states, and resampling.

Following L1-APG and MTT (see ``docs`` of the reference notes): each particle
``[a11, a12, a21, a22, tx, ty]`` is perturbed independently with standard
deviations ``std * [1, sc, sc, 1, sc, sc]`` where ``sc`` is the particle's scale
(:func:`smtmvt.geometry.affine_scale`); the diagonal terms ``a11`` and ``a22`` are
perturbed in log space (``a *= exp(N(0, std^2))``), so the relative scale change
per frame is ``std[0]``, ``std[3]``. The translation standard deviation is
``std[4] * sc`` pixels: with the 32-unit template frame, ``sc`` is about the
target size over 32, so the search radius grows with the target.
"""

from __future__ import annotations

import numpy as np

from .geometry import affine_scale

__all__ = ["propagate", "place", "pull_shape", "resample", "translation_std", "translation_distance"]


def propagate(
    params,
    std,
    rng: np.random.Generator,
    shift=None,
    spread=None,
    translation_power: float = 1.0,
    aspect_std: float | None = None,
) -> np.ndarray:
    """One step of the random walk.

    Parameters
    ----------
    params : (n, 6) affine states.
    std : (6,) relative standard deviations ``[a11, a12, a21, a22, tx, ty]``.
    rng : numpy Generator (the tracker's seeded generator).
    shift : optional (2,) translation ``(dx, dy)`` pixels added to every
        particle before the noise (a constant-velocity prediction), or
        (n, 2), one per particle.
    spread : optional (n,) factor multiplying every standard deviation of
        each particle (e.g. a fraction of the particles searching narrowly).
    translation_power : the translation std is ``std[4:] * sc ** translation_power``
        pixels: 1 (L1-APG, MTT) grows it with the target's size, 0.5 grows it
        as the square root (large targets move about as many pixels as small
        ones between frames).
    aspect_std : None perturbs ``a11`` and ``a22`` independently, by
        ``std[0]`` and ``std[3]`` in log space (L1-APG, MTT): the log scale
        ``(log a11 + log a22) / 2`` then moves by ``std / sqrt(2)`` and the log
        aspect ``log(a22 / a11)`` by ``sqrt(2) std``, twice as much. A float
        perturbs the scale and the aspect instead: both diagonal terms by the
        same ``exp(std[0] u)`` and the log aspect by ``aspect_std v`` (``u, v``
        the same standard normal draws), so a box's size can follow the
        target faster than its shape changes.

    Returns
    -------
    (n, 6) float64 new states.
    """
    p = np.array(params, dtype=np.float64, copy=True, ndmin=2)
    if shift is not None:
        p[:, 4:] += np.asarray(shift, dtype=np.float64)
    s = np.asarray(std, dtype=np.float64)
    sc = affine_scale(p)[:, None]
    t_std = translation_std(p, s, translation_power)
    noise = rng.standard_normal(p.shape)
    if spread is not None:
        noise *= np.asarray(spread, dtype=np.float64).reshape(-1, 1)
    if aspect_std is None:
        p[:, 0] *= np.exp(s[0] * noise[:, 0])
        p[:, 3] *= np.exp(s[3] * noise[:, 3])
    else:
        half = 0.5 * float(aspect_std) * noise[:, 3]
        p[:, 0] *= np.exp(s[0] * noise[:, 0] - half)
        p[:, 3] *= np.exp(s[0] * noise[:, 0] + half)
    p[:, 1] += s[1] * sc[:, 0] * noise[:, 1]
    p[:, 2] += s[2] * sc[:, 0] * noise[:, 2]
    p[:, 4:] += t_std * noise[:, 4:]
    return p


def pull_shape(params, reference, strength: float) -> np.ndarray:
    """Move each state's shape a fraction ``strength`` of the way back to ``reference``'s.

    The shape is the aspect ratio and the skew, what the random walk changes
    besides the scale and the position: with ``r = log(a22 / a11) / 2``, each
    state's ``r`` moves to ``r + strength (r_ref - r)`` at a fixed scale
    ``a11 a22``, and the off-diagonal terms to ``a12 + strength (a12_ref -
    a12)`` (likewise ``a21``). Position and scale are untouched. Applied every
    frame before the noise, it is a mean-reverting walk of the shape: the box's
    height and width can still follow the target, but a slow drift of the
    aspect (the likelihood preferring a part of the target) is pulled back.

    Parameters
    ----------
    params : (n, 6) affine states with ``a11, a22 > 0``.
    reference : (6,) the reference state (the first frame's).
    strength : in [0, 1]; 0 returns the states unchanged.

    Returns
    -------
    (n, 6) float64 states.
    """
    p = np.array(params, dtype=np.float64, copy=True, ndmin=2)
    if strength == 0:
        return p
    ref = np.asarray(reference, dtype=np.float64).reshape(6)
    r = 0.5 * np.log(p[:, 3] / p[:, 0])
    dr = strength * (0.5 * np.log(ref[3] / ref[0]) - r)
    p[:, 0] *= np.exp(-dr)
    p[:, 3] *= np.exp(dr)
    p[:, 1:3] += strength * (ref[1:3] - p[:, 1:3])
    return p


def place(params, count: int, point, std, rng: np.random.Generator) -> np.ndarray:
    """The last ``count`` states moved about ``point``: a proposal from outside
    the random walk (the correlation filter's peak, ``TrackerConfig.correlation_particles``).

    Parameters
    ----------
    params : (n, 6) affine states.
    count : how many of the last states to move (0 <= count <= n); their shape
        (``a11 .. a22``) is kept.
    point : (2,) translation ``(tx, ty)`` pixels they are placed about.
    std : (2,) standard deviations ``(sx, sy)`` pixels of the normal noise
        added to ``point``.
    rng : numpy Generator (the tracker's seeded generator); draws ``(count, 2)``
        standard normals, nothing when ``count`` is 0.

    Returns
    -------
    (n, 6) float64 new states (a copy).
    """
    p = np.array(params, dtype=np.float64, copy=True, ndmin=2)
    if not 0 <= count <= len(p):
        raise ValueError(f"place: count {count} is not between 0 and the {len(p)} states")
    if count:
        noise = rng.standard_normal((count, 2)) * np.asarray(std, dtype=np.float64)
        p[len(p) - count :, 4:] = np.asarray(point, dtype=np.float64) + noise
    return p


def resample(params, weights, n: int) -> np.ndarray:
    """Deterministic proportional resampling (L1-APG / MTT).

    Each particle is copied ``floor(n * w_i)`` times (weights normalized to sum
    to 1); the remaining slots are filled with the best particle. If every
    weight is zero or not finite, all ``n`` particles become the best one.

    Parameters
    ----------
    params : (m, 6) states.
    weights : (m,) non-negative weights.
    n : number of particles to return.

    Returns
    -------
    (n, 6) float64 states.
    """
    p = np.atleast_2d(np.asarray(params, dtype=np.float64))
    w = np.asarray(weights, dtype=np.float64)
    w = np.where(np.isfinite(w) & (w > 0), w, 0.0)
    best = int(np.argmax(w)) if w.sum() > 0 else 0
    total = w.sum()
    if total <= 0:
        return np.repeat(p[best : best + 1], n, axis=0)
    counts = np.floor(n * w / total).astype(int)
    idx = np.repeat(np.arange(len(p)), counts)[:n]
    if len(idx) < n:
        idx = np.concatenate([idx, np.full(n - len(idx), best)])
    return p[idx].copy()


def translation_std(params, std, translation_power: float = 1.0) -> np.ndarray:
    """The random walk's translation standard deviations at each state,
    ``std[4:] * sc ** translation_power`` pixels (``sc`` the state's scale, see
    :func:`propagate`), ``(n, 2)`` float64."""
    p = np.atleast_2d(np.asarray(params, dtype=np.float64))
    return np.asarray(std, dtype=np.float64)[4:] * affine_scale(p)[:, None] ** translation_power


def translation_distance(params, predicted, std) -> np.ndarray:
    """Squared distance of each state's translation from its predicted one, in
    standard deviations of the random walk: ``sum_j ((t_ij - p_ij) / std_ij)^2``.

    Parameters
    ----------
    params : (n, 6) affine states.
    predicted : (2,) or (n, 2) predicted translations ``(tx, ty)``, pixels
        (one for all states, or one each: a particle's parent moved by the
        velocity term).
    std : (2,) or (n, 2) translation standard deviations, pixels (>= 0).

    Returns
    -------
    (n,) float64 >= 0; ``exp(-d / 2)`` is the random walk's Gaussian density
    of the translation, up to a constant. Along an axis of std 0 (a walk that
    does not move) a state on the prediction is at distance 0 and any other
    at infinity.
    """
    p = np.atleast_2d(np.asarray(params, dtype=np.float64))
    diff = p[:, 4:] - np.asarray(predicted, dtype=np.float64)
    std = np.broadcast_to(np.asarray(std, dtype=np.float64), diff.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(std > 0, diff / np.where(std > 0, std, 1.0), np.where(diff == 0, 0.0, np.inf))
    return (z**2).sum(1)
