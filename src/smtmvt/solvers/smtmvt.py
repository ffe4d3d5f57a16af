r"""The SMTMVT sparse-coding problem and its solvers.

Problem (Javanmardi & Qi, ICME 2018, eq. generalOPT2)::

    minimize_{C >= 0, E}  sum_k ||X^k - D^k C^k - E^k||_F^2
                          + lam * sum_i ||Pi_i(C)||_*
                          + gamma * (1'C1 + ||E||_1)

with K views; view k has candidates ``X^k`` (d_k, n), templates ``D^k``
(d_k, N), codes ``C^k`` (N, n) and outliers ``E^k`` (d_k, n).
``Pi_i(C)`` is the (N, K) matrix whose column k is ``c_i^k``, candidate i's
code in view k; its nuclear norm couples the views of one candidate.

Default method, ``"admm"`` (exact, provably convergent)
-------------------------------------------------------
1. *Exact elimination of E.* For fixed C the problem in E is separable,
   ``min_e (r - e)^2 + gamma |e|``, solved by ``e = S_{gamma/2}(r)`` with value
   the Huber function ``h(r) = r^2`` (``|r| <= gamma/2``), ``gamma |r| - gamma^2/4``
   (beyond). So the problem equals ``min_C H(X - DC) + g1(C) + g2(C)`` with
   ``H = sum h`` over all residual entries, ``g1 = lam sum_i ||Pi_i(C)||_*``,
   ``g2 = gamma 1'C1 + indicator(C >= 0)``, and ``E* = S_{gamma/2}(X - D C*)``.
2. *Splitting.* With ``x = C`` and ``z = (R, Z1, Z2)`` the constraints
   ``D^k C^k + R^k = X^k``, ``sqrt(beta) (C - Z1) = 0``, ``sqrt(beta) (C - Z2) = 0``
   make this the standard two-block ADMM form ``min f(z) s.t. A x + B z = c``
   with ``f(z) = H(R) + g1(Z1) + g2(Z2)`` (separable), ``B = -I`` and
   ``A = [D; sqrt(beta) I; sqrt(beta) I]`` of full column rank. With scaled
   duals ``(U_R, U1, U2)`` one iteration is::

       C   <- (D'D + 2 beta I)^-1 [D'(X - R + U_R) + beta (Z1 - U1 + Z2 - U2)]
       R   <- prox_{H/rho}(X - DC + U_R)      (closed form, prox.huber_prox)
       Z1  <- SVT_{lam/(rho beta)}(C + U1)    (batched over candidates)
       Z2  <- max(C + U2 - gamma/(rho beta), 0)
       U   <- U + (A x + B z - c)

   The C step is an N x N linear system per view, factored once (it does not
   depend on rho). The R step costs two (d_k x N) x (N x n) products per view.
3. *Convergence.* f is closed, proper and convex, A is injective, so two-block
   ADMM converges for every rho > 0: residuals -> 0, objective -> optimum,
   iterates -> a minimizer (Boyd et al. 2011, sec. 3.2 and appendix A;
   Eckstein & Bertsekas 1992). rho is adapted by residual balancing (He, Yang &
   Wang 2000) only during the first 200 iterations, at most 30 times (per
   candidate); after that rho is constant and the theorem applies from that
   point on. No step size is
   involved (the Lipschitz constant below is only needed by ``"paper"``).

*One ADMM per candidate.* The problem separates over candidates (every term
is a sum over them), so each candidate i runs its own ADMM with its own
penalty rho_i, balanced on its own residuals, and its own stopping test; its
result is taken at the first iteration where it passes. A candidate's code
therefore does not depend on which candidates are solved with it, which is
what makes coding only some of them exact (:func:`smtmvt.likelihood.observe`).
The iterations stay batched over the candidates still running, in one of two
engines of the same iteration: a compiled numba loop (default,
:mod:`smtmvt.solvers._admm_kernel`, about 3x faster at tracker size) or
numpy array operations (``compiled=False``, the reference it is tested against).

*Stopping rule* (Boyd et al. 2011, sec. 3.3; :mod:`smtmvt.solvers._admm_rules`),
per candidate: stop when both
``r_pri <= tol * max(||A x||, sqrt(beta) ||(Z1, Z2)||, ||x||) + 1e-14`` and
``r_dual <= tol * rho * max(||D'U_R||, beta ||U1||, beta ||U2||) + 1e-14``
(the norms of that candidate's columns; the primal scale omits ``||R||`` from
Boyd's ``||B z||``, which changes it by at most a factor 2 since
``||R|| ~ ||X - DC|| <= ||X|| + ||A x||``), where ``r_pri = ||A x + B z - c||`` (the
change of the scaled duals) and ``r_dual = rho ||A'B (z - z_prev)||`` (the
change of the split variables). Both are relative changes of the iterates.
(Boyd's dual scale ``||A'y||`` cannot be used: the x-part of the objective
is zero, so ``A'y`` equals the dual residual and tends to 0; the scale is the
largest of its terms instead.)
On return C is ``Z2`` (exactly >= 0) and E is ``S_{gamma/2}(X - DC)``, the
optimal E for that C.

The paper's method, ``"paper"``
-------------------------------
Proximal (sub)gradient on the joint variable (C, E) with a constant step
``sigma = 1/L``: the smooth part ``F(C, E) = sum_k ||X^k - D^k C^k - E^k||_F^2``
has gradient ``-2 [D^k, I]' R^k`` per view (R^k = X^k - D^k C^k - E^k) and
Hessian ``2 [D^k, I]'[D^k, I]``, block diagonal over views and candidates, whose
norm is ``2 ||[D^k, I]||_2^2 = 2 (||D^k||_2^2 + 1)`` (because
``[D, I][D, I]' = D D' + I``). Hence ``L = 2 max_k (||D^k||_2^2 + 1)``. One step::

    C <- max(C - sigma (grad_C F + lam * U_i V_i' + gamma), 0)
    E <- S_{sigma gamma}(E - sigma grad_E F)

with ``U_i V_i'`` a subgradient of ``||Pi_i(C)||_*`` (thin SVD, nonzero singular
values). A subgradient step with constant step size does not converge to the
optimum in general; it stalls above it: at lam=1 by 3.8% (the small instance
of tests/test_solver.py) and 4.7% (bench/bench_solver.py, tracker size), at
lam=0.1 by 6e-5 and 5e-4. It stops when the
relative change ``||(C, E)_new - (C, E)|| <= tol ||(C, E)_new||`` or at
``max_iter``.

Dtypes: inputs may be float32, float64 or integer; all computation is float64
and the outputs are always float64 (the Gram-matrix SVT needs float64
accuracy, see :func:`smtmvt.solvers.prox.singular_value_threshold`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ._admm_kernel import run_candidates
from ._admm_rules import ABS_FLOOR, penalty_factor, tolerances
from ._inputs import check_params, check_views, check_warm_start
from .prox import nuclear_norms, singular_value_threshold, soft_threshold

__all__ = [
    "SolverInfo",
    "METHODS",
    "solve_smtmvt",
    "smtmvt_objective",
    "reconstruction_residual",
    "lipschitz_constant",
]

METHODS = ("admm", "paper")

_ABS_FLOOR = ABS_FLOOR


@dataclass(frozen=True)
class SolverInfo:
    """Diagnostics of one solve.

    Attributes
    ----------
    method : str
    iterations : int
        Iterations performed (SMTMVT's ADMM: by the slowest candidate).
    converged : bool
        Whether the stopping rule was met before ``max_iter`` (by every candidate).
    objective : float
        ``smtmvt_objective`` of the returned (C, E).
    primal_residual, dual_residual : float
        ADMM: the last ``r_pri`` and ``r_dual`` (absolute). ``"paper"``: the
        last relative change of (C, E), and NaN.
    rho : float
        Final ADMM penalty (SMTMVT's ADMM: the median over candidates; NaN for ``"paper"``).
    parts : dict or None
        Model-specific components of the solution (e.g. ``P`` and ``Q`` of
        the MTMVT models, whose C is ``P + Q``); None for SMTMVT.
    mean_iterations : float
        SMTMVT's ADMM: iterations per candidate, averaged (NaN otherwise).
    """

    method: str
    iterations: int
    converged: bool
    objective: float
    primal_residual: float
    dual_residual: float
    rho: float = float("nan")
    parts: dict | None = field(default=None, compare=False)
    mean_iterations: float = float("nan")


def _check_codes(C, K: int, N: int, n: int) -> np.ndarray:
    C = np.asarray(C, dtype=np.float64)
    if C.shape != (K, N, n):
        raise ValueError(f"C must have shape (K, N, n) = {(K, N, n)}, got {C.shape}")
    return C


def smtmvt_objective(X, D, C, E, lam: float, gamma: float) -> float:
    """Value of the SMTMVT objective (eq. generalOPT2) at (C, E).

    Parameters
    ----------
    X, D : lists of K arrays (d_k, n) and (d_k, N)
    C : array (K, N, n)
    E : list of K arrays (d_k, n)
    lam, gamma : float >= 0

    Returns
    -------
    float. The constraint C >= 0 is not checked here (the value of the
    penalties is computed as written: ``gamma * C.sum()``).
    """
    X, D, K, N, n = check_views(X, D)
    C = _check_codes(C, K, N, n)
    _, E = check_warm_start(None, E, K, N, n, X)
    fit = sum(float(np.sum((X[k] - D[k] @ C[k] - E[k]) ** 2)) for k in range(K))
    nuc = float(nuclear_norms(C.transpose(2, 1, 0)).sum())
    l1 = float(C.sum()) + sum(float(np.abs(e).sum()) for e in E)
    return fit + lam * nuc + gamma * l1


def reconstruction_residual(X, D, C) -> np.ndarray:
    """Per-candidate reconstruction error ``sum_k ||D^k c_i^k - x_i^k||^2``.

    The outliers E are *not* subtracted (this is the error used by the
    paper's likelihood ``p_i = exp(-alpha * residual_i)``).

    Returns
    -------
    ndarray (n,), float64, squared feature units.
    """
    X, D, K, N, n = check_views(X, D)
    C = _check_codes(C, K, N, n)
    out = np.zeros(n)
    for k in range(K):
        r = D[k] @ C[k] - X[k]
        out += np.einsum("ij,ij->j", r, r)
    return out


def lipschitz_constant(D) -> float:
    """``L = 2 max_k (||D^k||_2^2 + 1)``: Lipschitz constant of the gradient
    of ``sum_k ||X^k - D^k C^k - E^k||_F^2`` in the joint variable (C, E)."""
    return 2.0 * max(float(np.linalg.norm(np.asarray(Dk, dtype=np.float64), 2)) ** 2 + 1.0 for Dk in D)


def solve_smtmvt(
    X,
    D,
    lam: float = 0.1,
    gamma: float = 0.25,
    method: str = "admm",
    tol: float = 1e-6,
    max_iter: int = 1000,
    C0=None,
    E0=None,
    return_info: bool = False,
    compiled: bool = True,
):
    """Solve the SMTMVT sparse-coding problem (see the module docstring).

    Parameters
    ----------
    X : list of K arrays (d_k, n)
        Candidate features per view (one column per candidate).
    D : list of K arrays (d_k, N)
        Template dictionaries per view (one column per template).
    lam : float >= 0
        Weight of the per-candidate nuclear norm across views.
    gamma : float >= 0
        Weight of the L1 penalties on C and E.
    method : {"admm", "paper"}
        ``"admm"`` (default) reaches the exact optimum; ``"paper"`` is the
        paper's constant-step proximal subgradient iteration.
    tol : float > 0
        Relative tolerance of the stopping rule (see the module docstring).
    max_iter : int >= 1
        Iteration cap.
    C0 : array (K, N, n), optional
        Warm start for C.
    E0 : list of K arrays (d_k, n), optional
        Warm start for E. ``"paper"`` starts from it; ``"admm"`` (where E is
        eliminated) uses it, with C0, to estimate the dual of the residual
        block; without E0 it takes the optimal ``S_{gamma/2}(X - D C0)``.
        Ignored without C0.
    return_info : bool
        Also return a :class:`SolverInfo`.
    compiled : bool
        ``"admm"`` only: run the compiled engine (default) or the batched
        numpy one; the same iteration (see :func:`_solve_admm`).

    Returns
    -------
    C : ndarray (K, N, n), float64, >= 0
    E : list of K float64 arrays (d_k, n)
    info : SolverInfo, only if ``return_info``
    """
    X, D, K, N, n = check_views(X, D)
    check_params(lam=lam, gamma=gamma)
    if not (np.isfinite(tol) and tol > 0):
        raise ValueError(f"tol must be > 0, got {tol!r}")
    if int(max_iter) != max_iter or max_iter < 1:
        raise ValueError(f"max_iter must be an integer >= 1, got {max_iter!r}")
    C0, E0 = check_warm_start(C0, E0, K, N, n, X)
    lam, gamma, max_iter = float(lam), float(gamma), int(max_iter)
    if method == "admm":
        C, info = _solve_admm(X, D, lam, gamma, tol, max_iter, C0, E0, compiled=compiled)
        E = [soft_threshold(X[k] - D[k] @ C[k], gamma / 2.0) for k in range(K)]
    elif method == "paper":
        C, E, info = _solve_paper(X, D, lam, gamma, tol, max_iter, C0, E0)
    else:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    if not return_info:
        return C, E
    obj = smtmvt_objective(X, D, C, E, lam, gamma)
    info = SolverInfo(method=method, objective=obj, **info)
    return C, E, info


def _solve_admm(X, D, lam, gamma, tol, max_iter, C0, E0, rho=2.0, beta=0.5, compiled=True):
    """ADMM on the E-eliminated problem, one independent ADMM per candidate.

    The problem separates over candidates, so each candidate runs its own
    ADMM: its own rho (balanced on its own residuals), its own stopping test,
    and its result is recorded at the iteration where it first meets that
    test. A candidate's result therefore does not depend on which other
    candidates are solved with it (up to the last bits of floating-point
    sums), which makes solving a subset of them exact (see
    :func:`smtmvt.likelihood.observe`).

    Two engines run the same iteration from the same start
    (:func:`_admm_start`), both batched over the candidates still running
    and dropping the finished ones once they are a fifth of the batch:
    ``compiled`` (default) is one numba loop
    (:mod:`smtmvt.solvers._admm_kernel`); the numpy engine
    (:func:`_admm_batched`) is the readable reference the compiled one is
    tested against.
    """
    K, N, n = len(X), D[0].shape[1], X[0].shape[1]
    G = np.stack([Dk.T @ Dk for Dk in D])  # (K, N, N)
    Minv = np.linalg.inv(G + 2.0 * beta * np.eye(N))  # SPD, eigenvalues >= 2 beta
    DX = np.stack([D[k].T @ X[k] for k in range(K)])  # (K, N, n)
    rho = np.full(n, float(rho))
    state = _admm_start(X, D, G, DX, lam, gamma, C0, E0, rho, beta)
    if compiled:
        C_out, iterations, converged, r_pri_out, r_dual_out, rho_out = run_candidates(
            X, D, G, Minv, DX, state, rho, lam, gamma, beta, tol, max_iter
        )
    else:
        C_out, iterations, converged, r_pri_out, r_dual_out, rho_out = _admm_batched(
            X, D, G, Minv, DX, state, rho, lam, gamma, beta, tol, max_iter
        )
    info = dict(
        iterations=int(iterations.max(initial=0)),
        converged=bool(converged.all()),
        primal_residual=float(np.sqrt(np.sum(r_pri_out**2))),
        dual_residual=float(np.sqrt(np.sum(r_dual_out**2))),
        rho=float(np.median(rho_out)) if n else float("nan"),
        mean_iterations=float(iterations.mean()) if n else 0.0,
    )
    return C_out, info


def _admm_start(X, D, G, DX, lam, gamma, C0, E0, rho, beta) -> dict:
    """The starting iterates ``Z1, Z2, U1, U2, DtUR, DtR`` ``(K, N, n)`` and ``UR``
    (list of K ``(d_k, n)``): zeros, or estimated from the warm start ``C0``."""
    K, N, n = DX.shape
    if C0 is None:
        zeros = np.zeros((K, N, n))
        return dict(
            Z1=zeros.copy(),
            Z2=zeros.copy(),
            U1=zeros.copy(),
            U2=zeros.copy(),
            UR=[np.zeros_like(x) for x in X],
            DtUR=zeros.copy(),
            DtR=DX.copy(),  # R = X - D*0
        )
    UR = []
    for k in range(K):
        Rk = X[k] - D[k] @ C0[k]
        Ek = soft_threshold(Rk, gamma / 2.0) if E0 is None else E0[k]
        UR.append(np.clip(2.0 * (Rk - Ek) / rho, -gamma / rho, gamma / rho))
    DtUR = np.stack([D[k].T @ UR[k] for k in range(K)])
    # Duals estimated from the optimality conditions at C0: U_R is the
    # Huber gradient / rho; U1 = lam/(rho beta) U V' keeps
    # SVT(C0 + U1) = C0; U2 = gamma/(rho beta) on the support keeps
    # Z2 = C0 there; off the support U2 takes the rest of the sum
    # U1 + U2 = D'U_R / beta required by the C step's fixed point. Exact at an optimum
    # whose Pi_i(C) have no singular values below 1e-6 s_max, approximate
    # otherwise; any start converges anyway.
    U1 = (lam / (rho * beta)) * _nuclear_subgradient(C0, rtol=1e-6)
    t2 = gamma / (rho * beta)
    U2 = np.where(C0 > 0, t2, np.minimum(DtUR / beta - U1, t2))
    return dict(Z1=C0.copy(), Z2=C0.copy(), U1=U1, U2=U2, UR=UR, DtUR=DtUR, DtR=DX - G @ C0)


def _admm_batched(X, D, G, Minv, DX, state, rho, lam, gamma, beta, tol, max_iter):
    """The numpy engine of :func:`_solve_admm`: every candidate's ADMM, batched.

    Returns ``(C, iterations, converged, r_pri, r_dual, rho)`` as
    :func:`smtmvt.solvers._admm_kernel.run_candidates`.
    """
    K, N, n = DX.shape
    x_norm = np.sqrt(sum(np.einsum("ij,ij->j", x, x) for x in X))  # (n,)
    Z1, Z2, U1, U2, DtUR, DtR = (state[key] for key in ("Z1", "Z2", "U1", "U2", "DtUR", "DtR"))
    UR = list(state["UR"])
    rho = rho.copy()
    X = list(X)

    C_out = np.zeros((K, N, n))
    iterations = np.zeros(n, dtype=int)
    converged = np.zeros(n, dtype=bool)
    r_pri_out = np.full(n, np.inf)
    r_dual_out = np.full(n, np.inf)
    rho_out = rho.copy()
    live = np.arange(n)  # candidates (global index) in the working arrays
    open_ = np.ones(n, dtype=bool)  # working candidates not finished yet
    n_adapt = np.zeros(n, dtype=int)
    it = 0
    for it in range(1, max_iter + 1):
        # C step: (D'D + 2 beta I) C = D'(X - R + U_R) + beta (Z1 - U1 + Z2 - U2)
        C = Minv @ (DX - DtR + DtUR + beta * (Z1 - U1 + Z2 - U2))
        GC = G @ C
        # R step (Huber prox), written so that only U_R is stored:
        # V = X - DC + U_R, U_R_new = clip(2V/(2+rho)), R_new = V - U_R_new
        # (R itself is only needed through D'R, updated below).
        DtUn, dr_sq = _huber_step(X, D, C, UR, rho, gamma)
        DtR_new = DX - GC + DtUR - DtUn
        # Z steps
        tz = 1.0 / (rho * beta)
        Z1_new = singular_value_threshold((C + U1).transpose(2, 1, 0), lam * tz).transpose(2, 1, 0)
        Z2_new = np.maximum(C + U2 - gamma * tz, 0.0)
        D1 = C - Z1_new
        D2 = C - Z2_new
        U1 += D1
        U2 += D2
        # per-candidate residuals and scales (sums over views and templates)
        r_pri = np.sqrt(dr_sq + beta * (_col_sq(D1) + _col_sq(D2)))
        r_dual = rho * np.sqrt(_col_sq((DtR_new - DtR) + beta * ((Z1_new - Z1) + (Z2_new - Z2))))
        ax = np.sqrt(np.maximum(np.einsum("kij,kij->j", C, GC), 0.0) + 2.0 * beta * _col_sq(C))
        bz = np.sqrt(beta * (_col_sq(Z1_new) + _col_sq(Z2_new)))
        DtUR, DtR, Z1, Z2 = DtUn, DtR_new, Z1_new, Z2_new
        scale_dual = rho * np.sqrt(np.maximum(_col_sq(DtUR), beta**2 * np.maximum(_col_sq(U1), _col_sq(U2))))
        eps_pri, eps_dual = tolerances(tol, np.maximum(np.maximum(ax, bz), x_norm[live]), scale_dual)
        done = open_ & (r_pri <= eps_pri) & (r_dual <= eps_dual)
        if it == max_iter:
            done = open_.copy()
        if done.any():
            g = live[done]
            C_out[:, :, g] = Z2[:, :, done]
            iterations[g] = it
            converged[g] = (r_pri[done] <= eps_pri[done]) & (r_dual[done] <= eps_dual[done])
            r_pri_out[g], r_dual_out[g], rho_out[g] = r_pri[done], r_dual[done], rho[done]
            open_ &= ~done
            if not open_.any():
                break
            if (~open_).sum() * 5 >= len(live):  # drop the finished candidates
                keep = open_
                live, open_, rho, n_adapt = live[keep], open_[keep], rho[keep], n_adapt[keep]
                X = [x[:, keep] for x in X]
                UR = [u[:, keep] for u in UR]
                DX, DtR, DtUR = DX[:, :, keep], DtR[:, :, keep], DtUR[:, :, keep]
                Z1, Z2, U1, U2 = Z1[:, :, keep], Z2[:, :, keep], U1[:, :, keep], U2[:, :, keep]
                r_pri, eps_pri, r_dual, eps_dual = r_pri[keep], eps_pri[keep], r_dual[keep], eps_dual[keep]
        # residual balancing on normalized residuals, early iterations only
        factor = penalty_factor(it, n_adapt, r_pri, eps_pri, r_dual, eps_dual)
        if np.any(factor != 1.0):
            _rescale(factor, rho, [U1, U2, DtUR, *UR])
            n_adapt += factor != 1.0

    return C_out, iterations, converged, r_pri_out, r_dual_out, rho_out


def _huber_step(X, D, C, UR, rho, gamma):
    """The R step of :func:`_admm_batched` (the Huber prox), written so that only ``U_R``
    is stored: ``V = X - D C + U_R``, ``U_R <- clip(2 V / (2 + rho), +-gamma / rho)`` (in
    place, each view's ``(d_k, n)``); returns ``D' U_R`` ``(K, N, n)`` and each candidate's
    squared change of ``U_R`` ``(n,)``. ``R`` itself is only needed through ``D' R``."""
    c, th = 2.0 / (2.0 + rho), gamma / rho
    neg_th = -th
    dr_sq = np.zeros(C.shape[2])
    DtUn = np.empty_like(C)
    for k in range(len(D)):
        v = D[k] @ C[k]
        np.subtract(X[k], v, out=v)
        v += UR[k]
        v *= c
        u_new = np.maximum(np.minimum(v, th, out=v), neg_th, out=v)  # clip (faster than np.clip)
        du = u_new - UR[k]
        dr_sq += np.einsum("ij,ij->j", du, du)
        UR[k] = u_new
        np.matmul(D[k].T, u_new, out=DtUn[k])
    return DtUn, dr_sq


def _rescale(factor, rho, scaled) -> None:
    """Residual balancing's change of penalty, in place: ``rho *= factor`` (``rho`` the
    ``(n,)`` array of the candidates' penalties, changed in place: the caller's too)
    and each of the ``scaled`` (scaled duals, their ``D'`` products) divided by it."""
    rho *= factor
    for u in scaled:
        u /= factor


def _col_sq(A: np.ndarray) -> np.ndarray:
    """Per-candidate sum of squares of a (K, N, m) array, ``(m,)``."""
    return np.einsum("kij,kij->j", A, A)


def _nuclear_subgradient(C: np.ndarray, rtol: float = 1e-12) -> np.ndarray:
    """A subgradient of ``sum_i ||Pi_i(C)||_*`` at C (K, N, n): ``U_i V_i'``
    over the singular values above ``rtol * max(1, s_max)``."""
    P = C.transpose(2, 1, 0)  # (n, N, K)
    U, s, Vt = np.linalg.svd(P, full_matrices=False)
    keep = s > rtol * np.maximum(1.0, s[..., :1])
    S = (U * keep[..., None, :]) @ Vt
    return S.transpose(2, 1, 0)


def _solve_paper(X, D, lam, gamma, tol, max_iter, C0, E0):
    """The paper's constant-step proximal subgradient iteration."""
    K, N, n = len(X), D[0].shape[1], X[0].shape[1]
    sigma = 1.0 / lipschitz_constant(D)
    C = np.zeros((K, N, n)) if C0 is None else np.maximum(C0, 0.0)
    E = [np.zeros_like(x) for x in X] if E0 is None else [e.copy() for e in E0]
    change = np.inf
    converged = False
    it = 0
    for it in range(1, max_iter + 1):  # noqa: B007 - `it` is reported after the loop
        R = [X[k] - D[k] @ C[k] - E[k] for k in range(K)]
        gC = np.stack([-2.0 * (D[k].T @ R[k]) for k in range(K)]) + gamma
        if lam > 0:
            gC += lam * _nuclear_subgradient(C)
        C_new = np.maximum(C - sigma * gC, 0.0)
        E_new = [soft_threshold(E[k] + 2.0 * sigma * R[k], sigma * gamma) for k in range(K)]
        d_sq = float(np.vdot(C_new - C, C_new - C)) + sum(float(np.vdot(a - b, a - b)) for a, b in zip(E_new, E))
        x_sq = float(np.vdot(C_new, C_new)) + sum(float(np.vdot(a, a)) for a in E_new)
        C, E = C_new, E_new
        change = np.sqrt(d_sq) / max(np.sqrt(x_sq), _ABS_FLOOR)
        if np.sqrt(d_sq) <= tol * np.sqrt(x_sq) + _ABS_FLOOR:
            converged = True
            break
    info = dict(iterations=it, converged=converged, primal_residual=float(change), dual_residual=float("nan"))
    return C, E, info
