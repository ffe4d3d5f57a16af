"""Proximal operators used by the sparse-coding solvers.

All functions are pure, work on float64 numpy arrays and are batched: the
operators that act per candidate take a stack whose first axis indexes the
candidates, so no Python loop over candidates is needed.

References: Parikh & Boyd, "Proximal Algorithms", Found. Trends Optim. 1(3), 2014
(sections 6.5.1 soft thresholding, 6.7.3 singular value thresholding).
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "soft_threshold",
    "nonneg_shrink",
    "singular_value_threshold",
    "nuclear_norms",
    "huber_prox",
    "group_shrink",
    "group_huber_prox",
]


def soft_threshold(V: np.ndarray, tau: float) -> np.ndarray:
    """Elementwise ``sign(V) * max(|V| - tau, 0)``: the prox of ``tau * ||.||_1``.

    Parameters
    ----------
    V : ndarray, any shape
    tau : float >= 0

    Returns
    -------
    ndarray, same shape and dtype as ``V`` (a new array).
    """
    return np.sign(V) * np.maximum(np.abs(V) - tau, 0.0)


def nonneg_shrink(V: np.ndarray, tau: float) -> np.ndarray:
    """``max(V - tau, 0)``: the prox of ``tau * <1, .> + indicator(. >= 0)``."""
    return np.maximum(V - tau, 0.0)


def _gram_factors(P: np.ndarray, tau):
    """Eigen-decomposition of the small Gram matrix of each slice of ``P``.

    ``tau`` is a float or an array of one threshold per slice (``P.shape[:-2]``).

    Returns ``(V, s, f, left)``: eigenvectors ``V`` of the Gram matrix,
    singular values ``s`` of the slices, shrink factors ``f = max(1 - tau/s, 0)``
    and whether the Gram matrix is the left one (``P P^T``).
    """
    left = P.shape[-2] < P.shape[-1]
    Pt = np.swapaxes(P, -1, -2)
    M = P @ Pt if left else Pt @ P
    w, V = np.linalg.eigh(M)
    s = np.sqrt(np.maximum(w, 0.0))
    tau = np.asarray(tau, dtype=np.float64)[..., None]  # one threshold per slice
    with np.errstate(divide="ignore", invalid="ignore"):
        f = np.where(s > tau, 1.0 - tau / s, 0.0)
    return V, s, f, left


def singular_value_threshold(P: np.ndarray, tau) -> np.ndarray:
    """Singular value thresholding of every slice of a stack.

    ``SVT_tau(P_i) = U_i diag(max(s_i - tau, 0)) V_i^T`` for each
    ``P_i = U_i diag(s_i) V_i^T``; it is the prox of ``tau * ||P_i||_*``.

    Computed from the eigen-decomposition of the small Gram matrix
    ``P_i^T P_i`` (or ``P_i P_i^T`` when that is smaller):
    ``SVT_tau(P_i) = P_i V_i diag(max(1 - tau/s_i, 0)) V_i^T``. It is about three
    times faster than a batched ``np.linalg.svd`` for the (400, 10, 4) stacks of
    the tracker. Accuracy: the squared singular values carry an absolute error of
    about ``eps * s_max^2``, hence the kept singular values (all > tau) an error
    of about ``eps * s_max^2 / tau``; with float64 and tau >= 1e-8 * s_max this is
    far below any solver tolerance. Singular values <= tau are set to zero
    exactly, so their (possibly ill-determined) directions do not matter.

    Parameters
    ----------
    P : ndarray, shape (n, a, b), float64
        Stack of n matrices.
    tau : float >= 0, or (n,) array of one threshold per slice
        Threshold.

    Returns
    -------
    ndarray, shape (n, a, b), float64.
    """
    P = np.asarray(P, dtype=np.float64)
    V, _, f, left = _gram_factors(P, tau)
    W = (V * f[..., None, :]) @ np.swapaxes(V, -1, -2)
    return W @ P if left else P @ W


def nuclear_norms(P: np.ndarray) -> np.ndarray:
    """Nuclear norm of each slice of a stack ``P`` (n, a, b) -> (n,).

    Uses ``np.linalg.svd`` (singular values only), i.e. full accuracy.
    """
    P = np.asarray(P, dtype=np.float64)
    if P.shape[-1] == 0 or P.shape[-2] == 0:
        return np.zeros(P.shape[:-2])
    return np.linalg.svd(P, compute_uv=False).sum(axis=-1)


def huber_prox(V: np.ndarray, gamma: float, rho: float) -> np.ndarray:
    """Prox of ``h_gamma / rho`` where ``h_gamma(r) = min_e (r - e)^2 + gamma |e|``.

    ``h_gamma`` is the Huber function ``r^2`` for ``|r| <= gamma/2`` and
    ``gamma |r| - gamma^2 / 4`` beyond. Its prox,
    ``argmin_r h_gamma(r) + rho/2 (r - v)^2``, is ``v - clip(2 v / (2 + rho),
    -gamma/rho, gamma/rho)`` (elementwise). Shapes: any; returns a new array.
    """
    return V - np.clip(V * (2.0 / (2.0 + rho)), -gamma / rho, gamma / rho)


def group_shrink(V: np.ndarray, tau: float, axis) -> np.ndarray:
    """Block soft thresholding: the prox of ``tau * sum_g ||V_g||_2``.

    The groups are the slices obtained by reducing over ``axis`` (an int or a
    tuple of ints): ``V_g * max(1 - tau / ||V_g||_2, 0)``.
    """
    norms = np.sqrt(np.sum(V * V, axis=axis, keepdims=True))
    with np.errstate(divide="ignore", invalid="ignore"):
        f = np.where(norms > tau, 1.0 - tau / norms, 0.0)
    return V * f


def group_huber_prox(V: np.ndarray, gamma: float, rho: float, axis) -> np.ndarray:
    """Prox of ``h / rho`` with ``h(r) = min_e ||r - e||_2^2 + gamma ||e||_2`` per group.

    The groups are the slices reduced over ``axis``. ``h`` is the group Huber
    function (``||r||^2`` for ``||r|| <= gamma/2``, ``gamma ||r|| - gamma^2/4``
    beyond) and its prox is ``v - P(2 v / (2 + rho))`` with ``P`` the projection
    onto the L2 ball of radius ``gamma / rho`` (the vector form of
    :func:`huber_prox`). The minimizing ``e`` is ``group_shrink(r, gamma/2)``.
    """
    W = V * (2.0 / (2.0 + rho))
    norms = np.sqrt(np.sum(W * W, axis=axis, keepdims=True))
    radius = gamma / rho
    with np.errstate(divide="ignore", invalid="ignore"):
        f = np.where(norms > radius, radius / norms, 1.0)
    return V - W * f
