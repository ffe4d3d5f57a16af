"""SMTMVT's per-candidate ADMM as one compiled (numba) loop.

The same iteration, stopping rule and residual balancing as the numpy engine
:func:`smtmvt.solvers.smtmvt._admm_batched` (the docstring of
:mod:`smtmvt.solvers.smtmvt` states the method): one independent ADMM per
candidate, batched over the candidates still running, the finished ones
dropped from the working arrays once they are a fifth of them. The products
with the dictionaries stay batched BLAS calls (``np.dot`` inside numba: a
``(d_k, N)`` by ``(N, m)`` product reuses the dictionary over the m
candidates, which one product per candidate cannot); the rest (the Huber
prox, the SVT of each candidate's ``N x K`` code matrix, the residuals and
penalties) are compiled loops instead of the numpy engine's ~60 array
operations per iteration, whose call overhead dominated at tracker size. Only
the order of floating-point sums differs from the numpy engine (results agree
to about 1e-12, ``tests/test_admm_kernel.py``).

Layouts (prepared by :func:`run_candidates`): the K dictionaries stacked as
one ``(d, N)`` array, the candidates' views and residual duals as one
``(d, n)`` array each (view k in rows ``off[k]:off[k+1]``), the per-candidate
blocks as ``(K, N, n)``.

Threads (``TrackerConfig.threads``, :func:`smtmvt.threads.current`): one
kernel source compiled twice, ``_run`` (one thread, ``prange`` is ``range``)
and ``_run_parallel`` (numba's threads run the ``prange`` loops only). Each
iteration runs the views in parallel (each view's products are the same whole
BLAS calls as on one thread) and then blocks of candidates (each candidate's
sums in the one-thread order), so the results are bit for bit the same for
any number of threads (``tests/test_threads.py``). Splitting the candidates
into batches instead would not be: a BLAS product's last bits depend on the
batch's width. A batch of fewer than ``2 * PARALLEL_MIN`` candidates runs on
one thread.
"""

from __future__ import annotations

import types
from typing import Any

import numpy as np
from numba import njit, prange

from ..threads import current as current_threads
from ._admm_rules import ABS_FLOOR, ADAPT_EVERY, ADAPT_MAX, ADAPT_RATIO, ADAPT_UNTIL

__all__ = ["run_candidates", "symmetric_eigen", "PARALLEL_MIN"]

#: Candidates per thread below which a batch is solved on one thread: each
#: iteration of the threaded kernel waits for its threads twice, which a small
#: batch (the bounded coding's, tens of candidates) does not repay.
PARALLEL_MIN = 64


def run_candidates(X, D, G, Minv, DX, state, rho, lam, gamma, beta, tol, max_iter):
    """Run every candidate's ADMM to its stopping point.

    Parameters
    ----------
    X, D : lists of K arrays ``(d_k, n)`` and ``(d_k, N)``, float64.
    G, Minv : ``(K, N, N)`` Gram matrices ``D'D`` and ``(D'D + 2 beta I)^-1``.
    DX : ``(K, N, n)``, ``D'X``.
    state : dict of the starting iterates ``Z1, Z2, U1, U2, DtUR, DtR``
        ``(K, N, n)`` and ``UR`` (list of K ``(d_k, n)``); not modified.
    rho : ``(n,)`` starting penalties.

    Threads: :func:`smtmvt.threads.current`'s (1 outside a tracker), at most
    one per ``PARALLEL_MIN`` candidates.

    Returns ``(C, iterations, converged, r_pri, r_dual, rho)``: ``C (K, N, n)``
    (each candidate's final ``Z2``), and per candidate the iterations run,
    whether the stopping rule was met, the last residuals and the final penalty.
    """
    off = np.concatenate([[0], np.cumsum([Xk.shape[0] for Xk in X])]).astype(np.int64)

    def rows(arrays):
        return np.ascontiguousarray(np.concatenate([np.asarray(a, dtype=np.float64) for a in arrays], axis=0))

    def block(A):
        return np.array(A, dtype=np.float64, order="C")  # a copy: the kernel updates it in place

    n = X[0].shape[1]
    chunks = max(1, min(current_threads(), n // PARALLEL_MIN))
    run = _run if chunks == 1 else _run_parallel
    return run(
        rows(D),
        off,
        rows(X),
        rows(state["UR"]),
        np.ascontiguousarray(G),
        np.ascontiguousarray(Minv),
        block(DX),
        block(state["Z1"]),
        block(state["Z2"]),
        block(state["U1"]),
        block(state["U2"]),
        block(state["DtUR"]),
        block(state["DtR"]),
        np.array(rho, dtype=np.float64),
        float(lam),
        float(gamma),
        float(beta),
        float(tol),
        int(max_iter),
        chunks,
    )


@njit(cache=True, nogil=True)
def symmetric_eigen(A, V):
    """Eigen-decomposition of a small symmetric matrix by cyclic Jacobi rotations.

    ``A (m, m)`` is overwritten (its diagonal ends as the eigenvalues, which are
    returned, unsorted); ``V (m, m)`` receives the eigenvectors as columns, so
    that ``A_in = V diag(w) V'``. Sweeps stop when the off-diagonal mass is
    below ``1e-32`` of the total (float64 rounding), at most 50.
    """
    m = A.shape[0]
    V[:, :] = 0.0
    for i in range(m):
        V[i, i] = 1.0
    for _sweep in range(50):
        off = 0.0
        total = 0.0
        for p in range(m):
            total += A[p, p] * A[p, p]
            for q in range(p + 1, m):
                off += A[p, q] * A[p, q]
        total += 2.0 * off
        if off <= 1e-28 * total:
            break
        for p in range(m - 1):
            for q in range(p + 1, m):
                apq = A[p, q]
                if apq == 0.0:
                    continue
                theta = (A[q, q] - A[p, p]) / (2.0 * apq)
                t = 1.0 / (abs(theta) + np.sqrt(theta * theta + 1.0))
                if theta < 0.0:
                    t = -t
                c = 1.0 / np.sqrt(t * t + 1.0)
                s = t * c
                for r in range(m):  # A <- A J
                    arp, arq = A[r, p], A[r, q]
                    A[r, p] = c * arp - s * arq
                    A[r, q] = s * arp + c * arq
                for r in range(m):  # A <- J' A
                    apr, aqr = A[p, r], A[q, r]
                    A[p, r] = c * apr - s * aqr
                    A[q, r] = s * apr + c * aqr
                for r in range(m):  # V <- V J
                    vrp, vrq = V[r, p], V[r, q]
                    V[r, p] = c * vrp - s * vrq
                    V[r, q] = s * vrp + c * vrq
    w = np.empty(m)
    for i in range(m):
        w[i] = A[i, i]
    return w


@njit(cache=True, nogil=True)
def _svt(P, tau, out, M, V):
    """``out = SVT_tau(P)`` for one ``(N, K)`` matrix, from the eigen-decomposition
    of its smaller Gram matrix (as :func:`smtmvt.solvers.prox.singular_value_threshold`);
    ``M`` and ``V`` are ``(m, m)`` work arrays, ``m = min(N, K)``."""
    N, K = P.shape
    left = N < K
    m = M.shape[0]
    for a in range(m):
        for b in range(a, m):
            acc = 0.0
            if left:
                for j in range(K):
                    acc += P[a, j] * P[b, j]
            else:
                for j in range(N):
                    acc += P[j, a] * P[j, b]
            M[a, b] = acc
            M[b, a] = acc
    w = symmetric_eigen(M, V)
    f = np.zeros(m)
    for j in range(m):
        s = np.sqrt(max(w[j], 0.0))
        if s > tau:
            f[j] = 1.0 - tau / s
    # W = V diag(f) V' (in M); out = W P (left) or P W (right)
    for a in range(m):
        for b in range(m):
            acc = 0.0
            for j in range(m):
                acc += V[a, j] * f[j] * V[b, j]
            M[a, b] = acc
    if left:
        for a in range(N):
            for j in range(K):
                acc = 0.0
                for b in range(N):
                    acc += M[a, b] * P[b, j]
                out[a, j] = acc
    else:
        for a in range(N):
            for j in range(K):
                acc = 0.0
                for b in range(K):
                    acc += P[a, b] * M[b, j]
                out[a, j] = acc


@njit(cache=True, nogil=True)
def _keep_columns(A, keep):
    """Columns ``keep`` of a ``(r, m)`` array, as a new C-contiguous array."""
    out = np.empty((A.shape[0], keep.shape[0]))
    for r in range(A.shape[0]):
        for j in range(keep.shape[0]):
            out[r, j] = A[r, keep[j]]
    return out


@njit(cache=True, nogil=True)
def _keep_blocks(A, keep):
    """Candidates ``keep`` of a ``(K, N, m)`` array, as a new C-contiguous array."""
    K, N = A.shape[0], A.shape[1]
    out = np.empty((K, N, keep.shape[0]))
    for k in range(K):
        for t in range(N):
            for j in range(keep.shape[0]):
                out[k, t, j] = A[k, t, keep[j]]
    return out


def _run_py(Dcat, off, X, UR, G, Minv, DX, Z1, Z2, U1, U2, DtUR, DtR, rho, lam, gamma, beta, tol, max_iter, chunks):
    K, N, n = DX.shape
    d = X.shape[0]
    m_gram = min(N, K)
    C_out = np.zeros((K, N, n))
    iterations = np.zeros(n, dtype=np.int64)
    converged = np.zeros(n, dtype=np.bool_)
    r_pri_out = np.full(n, np.inf)
    r_dual_out = np.full(n, np.inf)
    rho_out = rho.copy()
    x_norm = np.sqrt(np.sum(X * X, axis=0))
    live = np.arange(n)
    open_ = np.ones(n, dtype=np.bool_)
    n_adapt = np.zeros(n, dtype=np.int64)
    for it in range(1, max_iter + 1):
        m = live.shape[0]
        # One view per thread (its products with its dictionary, whole BLAS calls as with
        # one thread): the C step (D'D + 2 beta I) C = D'(X - R + U_R) + beta (Z1 - U1 + Z2 - U2),
        # the R step (Huber prox) on U_R only, then D'U_R.
        C = np.empty((K, N, m))
        GC = np.empty((K, N, m))
        DtUn = np.empty((K, N, m))
        du_sq = np.empty((d, m))  # each change of U_R squared, summed per candidate below
        shrink = 2.0 / (2.0 + rho)
        th = gamma / rho
        for k in prange(K):
            a, b = off[k], off[k + 1]
            rhs = np.empty((N, m))
            for t in range(N):
                for j in range(m):
                    rhs[t, j] = (
                        DX[k, t, j]
                        - DtR[k, t, j]
                        + DtUR[k, t, j]
                        + beta * (Z1[k, t, j] - U1[k, t, j] + Z2[k, t, j] - U2[k, t, j])
                    )
            C[k] = np.dot(Minv[k], rhs)
            GC[k] = np.dot(G[k], C[k])
            V = np.dot(Dcat[a:b], C[k])
            for r in range(b - a):
                for j in range(m):
                    u = min(max(shrink[j] * (X[a + r, j] - V[r, j] + UR[a + r, j]), -th[j]), th[j])
                    du = u - UR[a + r, j]
                    du_sq[a + r, j] = du * du
                    UR[a + r, j] = u
            DtUn[k] = np.dot(Dcat[a:b].T, UR[a:b])
        # Z steps, duals, and each candidate's residuals and scales
        r_pri = np.empty(m)
        r_dual = np.empty(m)
        eps_pri = np.empty(m)
        eps_dual = np.empty(m)
        for c in prange(chunks):  # one block of candidates per thread, with its work arrays
            P = np.empty((N, K))
            S = np.empty((N, K))
            Mw = np.empty((m_gram, m_gram))
            Vw = np.empty((m_gram, m_gram))
            for j in range(c * m // chunks, (c + 1) * m // chunks):
                dr_sq = 0.0  # in the order (view, row), as one thread adds them
                for r in range(d):
                    dr_sq += du_sq[r, j]
                tz = 1.0 / (rho[j] * beta)
                for k in range(K):
                    for t in range(N):
                        P[t, k] = C[k, t, j] + U1[k, t, j]
                _svt(P, lam * tz, S, Mw, Vw)
                cgc = sq_d1 = sq_d2 = sq_c = sq_z1 = sq_z2 = sq_dual = sq_u1 = sq_u2 = sq_dtur = 0.0
                for k in range(K):
                    for t in range(N):
                        c_ = C[k, t, j]
                        cgc += c_ * GC[k, t, j]
                        dtr_new = DX[k, t, j] - GC[k, t, j] + DtUR[k, t, j] - DtUn[k, t, j]
                        z1n = S[t, k]
                        z2n = max(c_ + U2[k, t, j] - gamma * tz, 0.0)
                        d1 = c_ - z1n
                        d2 = c_ - z2n
                        U1[k, t, j] += d1
                        U2[k, t, j] += d2
                        sq_d1 += d1 * d1
                        sq_d2 += d2 * d2
                        sq_c += c_ * c_
                        sq_z1 += z1n * z1n
                        sq_z2 += z2n * z2n
                        e = (dtr_new - DtR[k, t, j]) + beta * ((z1n - Z1[k, t, j]) + (z2n - Z2[k, t, j]))
                        sq_dual += e * e
                        Z1[k, t, j] = z1n
                        Z2[k, t, j] = z2n
                        DtR[k, t, j] = dtr_new
                        DtUR[k, t, j] = DtUn[k, t, j]
                        sq_u1 += U1[k, t, j] * U1[k, t, j]
                        sq_u2 += U2[k, t, j] * U2[k, t, j]
                        sq_dtur += DtUn[k, t, j] * DtUn[k, t, j]
                r_pri[j] = np.sqrt(dr_sq + beta * (sq_d1 + sq_d2))
                r_dual[j] = rho[j] * np.sqrt(sq_dual)
                ax = np.sqrt(max(cgc, 0.0) + 2.0 * beta * sq_c)
                bz = np.sqrt(beta * (sq_z1 + sq_z2))
                scale_dual = rho[j] * np.sqrt(max(sq_dtur, beta**2 * max(sq_u1, sq_u2)))
                eps_pri[j] = tol * max(max(ax, bz), x_norm[live[j]]) + ABS_FLOOR
                eps_dual[j] = tol * scale_dual + ABS_FLOOR
        # finished candidates: record their result
        n_open = 0
        for j in range(m):
            if not open_[j]:
                continue
            met = r_pri[j] <= eps_pri[j] and r_dual[j] <= eps_dual[j]
            if met or it == max_iter:
                g = live[j]
                for k in range(K):
                    for t in range(N):
                        C_out[k, t, g] = Z2[k, t, j]
                iterations[g] = it
                converged[g] = met
                r_pri_out[g], r_dual_out[g], rho_out[g] = r_pri[j], r_dual[j], rho[j]
                open_[j] = False
            else:
                n_open += 1
        if n_open == 0:
            break
        if (m - n_open) * 5 >= m:  # drop the finished candidates
            keep = np.flatnonzero(open_)
            live, open_, rho, n_adapt = live[keep], open_[keep], rho[keep], n_adapt[keep]
            r_pri, eps_pri, r_dual, eps_dual = r_pri[keep], eps_pri[keep], r_dual[keep], eps_dual[keep]
            X, UR = _keep_columns(X, keep), _keep_columns(UR, keep)
            DX, DtR, DtUR = _keep_blocks(DX, keep), _keep_blocks(DtR, keep), _keep_blocks(DtUR, keep)
            Z1, Z2, U1, U2 = (
                _keep_blocks(Z1, keep),
                _keep_blocks(Z2, keep),
                _keep_blocks(U1, keep),
                _keep_blocks(U2, keep),
            )
        # residual balancing, early iterations only (smtmvt.solvers._admm_rules.penalty_factor)
        if it <= ADAPT_UNTIL and it % ADAPT_EVERY == 0:
            for j in range(live.shape[0]):
                if n_adapt[j] >= ADAPT_MAX:
                    continue
                ratio = (r_pri[j] / eps_pri[j]) / max(r_dual[j] / eps_dual[j], 1e-300)
                factor = 2.0 if ratio > ADAPT_RATIO else (0.5 if ratio < 1.0 / ADAPT_RATIO else 1.0)
                if factor == 1.0:
                    continue
                rho[j] *= factor
                for k in range(K):
                    for t in range(N):
                        U1[k, t, j] /= factor
                        U2[k, t, j] /= factor
                        DtUR[k, t, j] /= factor
                for r in range(d):
                    UR[r, j] /= factor
                n_adapt[j] += 1
    return C_out, iterations, converged, r_pri_out, r_dual_out, rho_out


def _named(fn, name: str):
    """``fn`` as a new function named ``name`` (numba names its cache files after a
    function's qualified name: two dispatchers of one function would share them)."""
    out = types.FunctionType(fn.__code__, fn.__globals__, name, fn.__defaults__, fn.__closure__)
    out.__qualname__ = name
    return out


#: One thread: ``prange`` is ``range``.
_run = njit(cache=True, nogil=True)(_named(_run_py, "_run"))
#: Several: only the ``prange`` loops (over candidates, or blocks of them) run in
#: parallel; numba's own parallelization of array expressions stays off (its
#: reductions would sum in another order), so every candidate's arithmetic is
#: the one-thread kernel's, whatever the number of threads.
_PRANGE_ONLY: Any = {  # (numba empties the dict it is given: a copy goes)
    "comprehension": False,
    "reduction": False,
    "inplace_binop": False,
    "setitem": False,
    "numpy": False,
    "stencil": False,
    "fusion": False,
    "prange": True,
}
_run_parallel = njit(cache=True, nogil=True, parallel=dict(_PRANGE_ONLY))(_named(_run_py, "_run_parallel"))  # type: ignore[call-overload]
