r"""A small ADMM engine for the comparison observation models.

It solves, over m coefficient blocks ``C_1..C_m`` (each (K, N, n))::

    minimize  sum_k f(X^k - D^k S^k) + sum_b g_b(C_b),   S = C_1 + ... + C_m

for a loss ``f`` and block penalties ``g_b`` with cheap proximal operators.
It is the same scheme as :mod:`smtmvt.solvers.smtmvt` (which is tuned for the
SMTMVT model): with ``x = (C_b)`` and ``z = (R, Z_b)`` the constraints
``D S + R = X`` and ``sqrt(beta) (C_b - Z_b) = 0`` give a two-block ADMM with an
injective ``A``, which converges for every rho > 0 when f and the g_b are
closed, proper and convex (Boyd et al. 2011, sec. 3.2). One iteration::

    S   <- (D'D + (beta/m) I)^-1 [D'(X - R + U_R) + (beta/m) sum_b a_b],
           a_b = Z_b - U_b
    C_b <- a_b + (S - sum_b a_b) / m     (closest blocks with that sum)
    R   <- prox_{f/rho}(X - D S + U_R)
    Z_b <- prox_{g_b/(rho beta)}(C_b + U_b)
    U   <- U + (A x + B z - c)

Stopping rule and rho adaptation are those of the SMTMVT solver
(:mod:`smtmvt.solvers._admm_rules`), applied here to the whole problem at once
(these models couple the candidates): relative primal and dual residuals below
tol; residual balancing during the first 200 iterations only.
"""

from __future__ import annotations

import numpy as np

from ._admm_rules import penalty_factor, tolerances

__all__ = ["admm_blocks"]


def admm_blocks(X, D, loss_prox, block_proxes, tol, max_iter, rho=2.0, beta=0.5, adapt=True):
    """Run the ADMM above.

    Parameters
    ----------
    X, D : lists of K float64 arrays (d_k, n), (d_k, N) (already validated)
    loss_prox : callable ``(V, rho) -> R``
        ``argmin_R f(R) + rho/2 ||R - V||^2`` for one view's (d_k, n) array.
    block_proxes : list of m callables ``(V, t) -> Z``
        ``argmin_Z g_b(Z) + 1/(2t) ||Z - V||^2`` on (K, N, n) arrays.
    tol : float > 0
    max_iter : int >= 1
    adapt : bool
        Residual balancing of rho during the first iterations (the default).
        Off for the LAD loss: there it drives rho away from where the
        iterates make progress (tracker-size instance, 100 candidates: the
        objective stalls 47% above the optimum with it, 0.3% above after 200
        iterations without it).

    Returns
    -------
    blocks : list of m arrays (K, N, n), the ``Z_b`` (exactly in the domain
        of each g_b)
    info : dict with iterations, converged, primal_residual, dual_residual, rho
    """
    K, N, n = len(X), D[0].shape[1], X[0].shape[1]
    m = len(block_proxes)
    G = np.stack([Dk.T @ Dk for Dk in D])
    DX = np.stack([D[k].T @ X[k] for k in range(K)])
    Minv = np.linalg.inv(G + (beta / m) * np.eye(N))
    x_norm = np.sqrt(sum(float(np.vdot(x, x)) for x in X))

    Z = [np.zeros((K, N, n)) for _ in range(m)]
    U = [np.zeros((K, N, n)) for _ in range(m)]
    UR = [np.zeros_like(x) for x in X]
    DtUR = np.zeros((K, N, n))
    DtR = DX.copy()  # R = X - D*0
    r_pri = r_dual = np.inf
    converged = False
    n_adapt = 0
    it = 0
    for it in range(1, max_iter + 1):
        a = [Zb - Ub for Zb, Ub in zip(Z, U)]
        a_sum = sum(a)
        S = Minv @ (DX - DtR + DtUR + (beta / m) * a_sum)
        C = [ab + (S - a_sum) / m for ab in a]
        GS = G @ S
        DtUn, dr_sq = _loss_step(X, D, S, UR, loss_prox, rho)
        DtR_new = DX - GS + DtUR - DtUn
        dDtR = DtR_new - DtR
        Z_new = [prox(Cb + Ub, 1.0 / (rho * beta)) for prox, Cb, Ub in zip(block_proxes, C, U)]
        pri_sq = dr_sq
        dual_sq = 0.0
        for b in range(m):
            diff = C[b] - Z_new[b]
            U[b] += diff
            pri_sq += beta * float(np.vdot(diff, diff))
            dual_sq += float(np.sum((dDtR + beta * (Z_new[b] - Z[b])) ** 2))
        r_pri = np.sqrt(pri_sq)
        r_dual = rho * np.sqrt(dual_sq)
        ax = np.sqrt(max(float(np.vdot(S, GS)), 0.0) + beta * sum(float(np.vdot(c, c)) for c in C))
        bz = np.sqrt(beta * sum(float(np.vdot(z, z)) for z in Z_new))
        DtUR, DtR, Z = DtUn, DtR_new, Z_new
        scale_dual = rho * max([np.linalg.norm(DtUR)] + [beta * np.linalg.norm(u) for u in U])
        eps_pri, eps_dual = tolerances(tol, max(ax, bz, x_norm), scale_dual)
        if r_pri <= eps_pri and r_dual <= eps_dual:
            converged = True
            break
        factor = penalty_factor(it, n_adapt, r_pri, eps_pri, r_dual, eps_dual) if adapt else 1.0
        if factor != 1.0:
            rho *= factor
            U, UR, DtUR = [u / factor for u in U], [u / factor for u in UR], DtUR / factor
            n_adapt += 1
    info = dict(
        iterations=it, converged=converged, primal_residual=float(r_pri), dual_residual=float(r_dual), rho=float(rho)
    )
    return Z, info


def _loss_step(X, D, S, UR, loss_prox, rho):
    """The loss block's step of :func:`admm_blocks`: for each view ``k``,
    ``V = X_k - D_k S_k + U_R,k`` and ``U_R,k <- V - prox(V)`` (in place in the list
    ``UR``); returns ``D' U_R`` ``(K, N, n)`` and the squared change of ``U_R`` (float)."""
    dr_sq = 0.0
    DtUn = np.empty(S.shape)
    for k in range(len(X)):
        V = X[k] - D[k] @ S[k] + UR[k]
        u_new = V - loss_prox(V, rho)
        du = u_new - UR[k]
        dr_sq += float(np.vdot(du, du))
        UR[k] = u_new
        DtUn[k] = D[k].T @ u_new
    return DtUn, dr_sq
