"""Tests of the SMTMVT solver against an independent cvxpy formulation."""

import re

import cvxpy as cp  # a pinned test dependency (requirements-dev.txt): missing means broken
import numpy as np
import pytest

from smtmvt.solvers import (
    SolverInfo,
    lipschitz_constant,
    reconstruction_residual,
    smtmvt_objective,
    solve_smtmvt,
)
from solver_instances import make_instance


# ---------------------------------------------------------------- helpers
def cvxpy_solve(X, D, lam, gamma):
    """Reference optimum of eq. generalOPT2 with CLARABEL at high accuracy."""
    K, N, n = len(X), D[0].shape[1], X[0].shape[1]
    C = [cp.Variable((N, n), nonneg=True) for _ in range(K)]
    E = [cp.Variable(x.shape) for x in X]
    fit = sum(cp.sum_squares(X[k] - D[k] @ C[k] - E[k]) for k in range(K))
    if K == 1:  # the nuclear norm of an (N, 1) matrix is the L2 norm of the column
        struct = sum(cp.norm(C[0][:, i], 2) for i in range(n))
    else:
        struct = sum(cp.normNuc(cp.hstack([C[k][:, i : i + 1] for k in range(K)])) for i in range(n))
    l1 = sum(cp.sum(c) for c in C) + sum(cp.sum(cp.abs(e)) for e in E)
    prob = cp.Problem(cp.Minimize(fit + lam * struct + gamma * l1))
    prob.solve(solver="CLARABEL", tol_gap_abs=1e-10, tol_gap_rel=1e-10, tol_feas=1e-10)
    assert prob.status == "optimal"
    return prob.value, np.stack([c.value for c in C]), [e.value for e in E]


def objective_by_loops(X, D, C, E, lam, gamma):
    """The objective written candidate by candidate, independently of the package."""
    K, n = len(X), X[0].shape[1]
    total = 0.0
    for k in range(K):
        total += np.linalg.norm(X[k] - D[k] @ C[k] - E[k], "fro") ** 2
        total += gamma * (C[k].sum() + np.abs(E[k]).sum())
    for i in range(n):
        Pi = np.column_stack([C[k][:, i] for k in range(K)])
        total += lam * np.linalg.norm(Pi, "nuc")
    return total


# ---------------------------------------------------------------- optimality
LAMS = [0.01, 0.1, 0.3, 1.0]
GAMMAS = [0.05, 0.25, 1.0]


@pytest.mark.parametrize("gamma", GAMMAS)
@pytest.mark.parametrize("lam", LAMS)
def test_admm_reaches_cvxpy_optimum(lam, gamma):
    seed = LAMS.index(lam) * 10 + GAMMAS.index(gamma)
    X, D = make_instance(seed, K=[3, 4][seed % 2], N=3 + seed % 4, n=2 + seed % 5)
    ref, C_ref, _ = cvxpy_solve(X, D, lam, gamma)
    for compiled in (True, False):  # both ADMM engines (tests/test_admm_kernel.py compares them closely)
        _check_against_reference(X, D, lam, gamma, ref, C_ref, compiled)


def _check_against_reference(X, D, lam, gamma, ref, C_ref, compiled):
    C, E, info = solve_smtmvt(X, D, lam=lam, gamma=gamma, tol=1e-8, max_iter=20000, return_info=True, compiled=compiled)

    assert info.converged
    assert C.shape == C_ref.shape and C.dtype == np.float64
    assert [e.shape for e in E] == [x.shape for x in X]
    assert np.all(C >= 0)
    obj = objective_by_loops(X, D, C, E, lam, gamma)
    assert obj == pytest.approx(info.objective, rel=1e-12)
    # Measured over these 12 cases (tol=1e-8): relative gap to CLARABEL's optimum
    # from -1.8e-11 to +5.1e-9, code error up to 2.1e-6 (lam=0.1, gamma=0.05).
    # not worse than the optimum (bound 20x the largest gap) ...
    assert obj <= ref * (1 + 1e-7)
    # ... and not better than it either (a constraint violation would show here;
    # CLARABEL's own relative accuracy is ~1e-10)
    assert obj >= ref * (1 - 1e-9)
    # the codes themselves (bound 10x the largest error: the problem need not be
    # strongly convex, but on these instances the minimizer is well determined)
    assert np.max(np.abs(C - C_ref)) <= 2e-5 * max(1.0, np.abs(C_ref).max())


@pytest.mark.parametrize("seed", [0, 1])
def test_admm_reaches_optimum_in_least_absolute_deviations_regime(seed):
    """Small gamma and lam: the Huber loss is linear almost everywhere (a least
    absolute deviations fit). Here the primal residual (the change of the scaled
    duals, bounded by the clip at gamma/rho) is tiny from the first iterations while
    the split variables still move: stopping on either residual alone returns
    C near 0, 57-73% above the optimum. Both residuals small: measured gaps 1.5e-8
    and 7.5e-9 (bound 1e-6, ~70x)."""
    X, D = make_instance(seed)
    lam, gamma = 1e-5, 1e-4
    ref, C_ref, _ = cvxpy_solve(X, D, lam, gamma)
    C, E, info = solve_smtmvt(X, D, lam=lam, gamma=gamma, max_iter=20000, return_info=True)
    assert info.converged
    assert abs(info.objective - ref) <= 1e-6 * ref
    assert np.abs(C_ref).max() > 1  # the optimum is far from C = 0


def test_single_view_is_nonnegative_group_lasso():
    """K = 1: the nuclear norm of an (N, 1) matrix is the L2 norm of the column."""
    X, D = make_instance(7, K=1, N=4, n=5)
    ref, C_ref, _ = cvxpy_solve(X, D, 0.3, 0.25)
    C, E = solve_smtmvt(X, D, lam=0.3, gamma=0.25, tol=1e-9)
    assert C.shape == (1, 4, 5)
    # measured: relative gap -1.9e-11, code error 5.4e-9 (bounds ~50x and ~20x)
    assert smtmvt_objective(X, D, C, E, 0.3, 0.25) == pytest.approx(ref, rel=1e-9)
    assert np.allclose(C, C_ref, rtol=0, atol=1e-7)


@pytest.mark.parametrize("K", [1, 3])
def test_single_candidate(K):
    X, D = make_instance(11 + K, K=K, N=4, n=1)
    ref, C_ref, _ = cvxpy_solve(X, D, 0.5, 0.1)
    C, E = solve_smtmvt(X, D, lam=0.5, gamma=0.1, tol=1e-9)
    assert C.shape == (K, 4, 1)
    # measured: relative gap 1.3e-13 (K=1) and 7.3e-11 (K=3), code error 3e-13 and
    # 2.4e-7 (bounds ~14x and ~8x the K=3 values)
    assert smtmvt_objective(X, D, C, E, 0.5, 0.1) == pytest.approx(ref, rel=1e-9)
    assert np.allclose(C, C_ref, rtol=0, atol=2e-6)


def test_returned_E_is_optimal_for_returned_C():
    """E = S_{gamma/2}(X - DC) is the exact minimizer over E for fixed C:
    any perturbation of E can only increase the objective."""
    X, D = make_instance(3)
    C, E = solve_smtmvt(X, D, lam=0.1, gamma=0.25)
    base = smtmvt_objective(X, D, C, E, 0.1, 0.25)
    rng = np.random.default_rng(0)
    for _ in range(20):
        E2 = [e + 1e-3 * rng.standard_normal(e.shape) for e in E]
        assert smtmvt_objective(X, D, C, E2, 0.1, 0.25) > base


def test_zero_input_gives_zero_solution():
    _, D = make_instance(5, K=3, N=4, n=3)
    X = [np.zeros((Dk.shape[0], 3)) for Dk in D]
    for method in ("admm", "paper"):
        C, E, info = solve_smtmvt(X, D, method=method, return_info=True)
        assert np.all(C == 0), method
        assert all(np.all(e == 0) for e in E), method
        assert info.converged and info.iterations == 1, method


def test_large_gamma_gives_zero_codes():
    """gamma above 2 max|D'X| makes C = 0 optimal (the L1 term dominates)."""
    X, D = make_instance(6)
    gamma = 2.0 * max(np.abs(Dk.T @ Xk).max() for Dk, Xk in zip(D, X)) * 1.01
    C, _ = solve_smtmvt(X, D, lam=0.1, gamma=gamma)
    assert np.all(C == 0)


# ---------------------------------------------------------------- the paper's iteration
@pytest.mark.parametrize("lam", [0.1, 1.0])
def test_paper_method_feasible_and_not_below_optimum(lam):
    X, D = make_instance(21, K=4, N=5, n=6)
    ref, _, _ = cvxpy_solve(X, D, lam, 0.25)
    C, E, info = solve_smtmvt(X, D, lam=lam, gamma=0.25, method="paper", max_iter=3000, return_info=True)
    assert info.method == "paper"
    assert np.all(C >= 0)
    gap = (info.objective - ref) / ref
    assert gap >= -1e-7
    # Measured on this instance: lam=1 -> gap 3.8% (3.6% after 300 iterations,
    # still 3.8% after 30000: the constant-step subgradient of the nuclear
    # norm stalls above the optimum); lam=0.1 -> gap 5.8e-5. Bounds: 1.3x and
    # 3.4x the measured gaps.
    assert gap < {0.1: 2e-4, 1.0: 0.05}[lam]


def _paper_step_by_hand(X, D, C, E, lam, gamma):
    """One step of the paper's iteration written from its formulas (module docstring
    of smtmvt.solvers.smtmvt), with L from the eigenvalues of the Hessian."""
    L = max(
        np.linalg.eigvalsh(2 * np.hstack([Dk, np.eye(len(Dk))]).T @ np.hstack([Dk, np.eye(len(Dk))])).max() for Dk in D
    )
    sigma = 1.0 / L
    K, N, n = C.shape
    R = [X[k] - D[k] @ C[k] - E[k] for k in range(K)]
    sub = np.zeros_like(C)  # subgradient of sum_i ||Pi_i(C)||_*: U V' of each (N, K) matrix
    for i in range(n):
        U, _, Vt = np.linalg.svd(np.column_stack([C[k][:, i] for k in range(K)]), full_matrices=False)
        sub[:, :, i] = (U @ Vt).T
    C_new = np.empty_like(C)
    E_new = []
    for k in range(K):
        grad_C = -2 * D[k].T @ R[k] + lam * sub[k] + gamma
        C_new[k] = np.maximum(C[k] - sigma * grad_C, 0)
        v = E[k] + sigma * 2 * R[k]  # E - sigma * grad_E, grad_E = -2 R
        E_new.append(np.sign(v) * np.maximum(np.abs(v) - sigma * gamma, 0))
    return C_new, E_new


def test_paper_method_takes_the_papers_step():
    """One iteration from a generic point (C > 0, so every Pi_i(C) has full rank and
    the subgradient is unique) is the formula: step 1/L, L = 2 max_k(||D^k||^2 + 1)."""
    X, D = make_instance(22, K=3, N=4, n=5)
    rng = np.random.default_rng(2)
    C0 = rng.uniform(0.05, 0.6, (3, 4, 5))
    E0 = [0.05 * rng.standard_normal(x.shape) for x in X]
    C_ref, E_ref = _paper_step_by_hand(X, D, C0, E0, 0.3, 0.25)
    assert 0 < np.mean(C_ref == 0) < 0.5 and 0 < np.mean(E_ref[0] == 0) < 1  # both projections act
    C1, E1, info = solve_smtmvt(X, D, lam=0.3, gamma=0.25, method="paper", C0=C0, E0=E0, max_iter=1, return_info=True)
    assert info.iterations == 1
    np.testing.assert_allclose(C1, C_ref, rtol=0, atol=1e-12)
    for k in range(3):
        np.testing.assert_allclose(E1[k], E_ref[k], rtol=0, atol=1e-12)


def test_admm_beats_paper_at_lam_1():
    X, D = make_instance(21, K=4, N=5, n=6)
    _, _, exact = solve_smtmvt(X, D, lam=1.0, return_info=True)
    _, _, paper = solve_smtmvt(X, D, lam=1.0, method="paper", max_iter=3000, return_info=True)
    assert exact.objective < paper.objective * (1 - 1e-3)


# ---------------------------------------------------------------- api details
def test_info_and_iteration_cap():
    X, D = make_instance(8)
    C, E, info = solve_smtmvt(X, D, lam=0.1, gamma=0.25, max_iter=2, return_info=True)
    assert isinstance(info, SolverInfo)
    assert info.iterations == 2 and not info.converged
    C, E, info = solve_smtmvt(X, D, return_info=True)
    assert info.converged and 1 < info.iterations < 1000
    assert info.objective == pytest.approx(smtmvt_objective(X, D, C, E, 0.1, 0.25), rel=1e-12)
    for value in (info.primal_residual, info.dual_residual, info.rho):
        assert type(value) is float and np.isfinite(value) and value > 0


def test_float32_input_gives_float64_output_and_same_solution():
    X, D = make_instance(9)
    C64, E64 = solve_smtmvt(X, D, tol=1e-9)
    X32 = [x.astype(np.float32) for x in X]
    D32 = [d.astype(np.float32) for d in D]
    C32, E32 = solve_smtmvt(X32, D32, tol=1e-9)
    assert C32.dtype == np.float64 and all(e.dtype == np.float64 for e in E32)
    # same problem up to the float32 rounding of the data (measured 6.0e-8 apart)
    assert np.allclose(C32, C64, rtol=0, atol=1e-6)


def test_warm_start_is_used():
    X, D = make_instance(10, n=6)
    C, E, opt = solve_smtmvt(X, D, lam=0.3, tol=1e-10, max_iter=10000, return_info=True)
    # one iteration from the optimum stays near it; one from zero does not
    _, _, warm1 = solve_smtmvt(X, D, lam=0.3, C0=C, E0=E, max_iter=1, return_info=True)
    _, _, cold1 = solve_smtmvt(X, D, lam=0.3, max_iter=1, return_info=True)
    assert warm1.objective - opt.objective < 0.1 * (cold1.objective - opt.objective)
    # the paper's iteration continues from (C0, E0)
    _, _, paper5 = solve_smtmvt(X, D, lam=0.3, method="paper", C0=C, E0=E, max_iter=5, return_info=True)
    _, _, paper5_cold = solve_smtmvt(X, D, lam=0.3, method="paper", max_iter=5, return_info=True)
    assert paper5.objective - opt.objective < 0.1 * (paper5_cold.objective - opt.objective)


@pytest.mark.parametrize("seed", [3, 4])
def test_admm_warm_start_at_an_optimum_is_a_fixed_point(seed):
    """The docstring: the duals estimated from (C0, E0) are exact at an optimum whose
    Pi_i(C) have no singular values below 1e-6 s_max. On such an optimum (with some
    C = 0 entries, so that the off-support branch of U2 is used) one iteration must
    stay put and meet the stopping rule. Measured: C moves by 1.3e-12 and 2.1e-12
    (bound 1e-10); with the off-support U2 taking -D'U_R/beta (the sign before the
    fix) it moved by 0.054 and 0.040."""
    X, D = make_instance(seed, n=6)
    C, E, opt = solve_smtmvt(X, D, lam=0.1, tol=1e-12, max_iter=100000, return_info=True)
    sv = np.linalg.svd(C.transpose(2, 1, 0), compute_uv=False)
    assert opt.converged and (sv[:, -1] / sv[:, 0]).min() > 1e-3 and 0.05 < np.mean(C == 0) < 0.5
    C1, _, info = solve_smtmvt(X, D, lam=0.1, C0=C, E0=E, max_iter=1, return_info=True)
    assert np.abs(C1 - C).max() < 1e-10
    assert info.converged


def test_paper_method_stopping_rule_is_the_relative_change():
    """info.primal_residual of the paper's iteration is the last relative change
    ||(C, E)_k - (C, E)_{k-1}|| / ||(C, E)_k||, and it stops at the first k where that is
    <= tol; at the iteration cap it reports not converged."""
    X, D = make_instance(23)
    kw = dict(lam=0.3, gamma=0.25, method="paper")
    states = [(np.zeros((3, 5, 4)), [np.zeros_like(x) for x in X])]
    changes = [np.inf]
    for k in range(1, 31):
        C, E, info = solve_smtmvt(X, D, max_iter=k, return_info=True, **kw)
        assert info.iterations == k and info.converged is False and np.isnan(info.dual_residual)
        Cp, Ep = states[-1]
        step = np.sqrt(np.sum((C - Cp) ** 2) + sum(np.sum((a - b) ** 2) for a, b in zip(E, Ep)))
        size = np.sqrt(np.sum(C**2) + sum(np.sum(a**2) for a in E))
        changes.append(step / size)
        assert info.primal_residual == pytest.approx(changes[-1], rel=1e-9)
        states.append((C, E))
    tol = changes[20]
    first = next(k for k in range(1, 31) if changes[k] <= tol)
    _, _, info = solve_smtmvt(X, D, tol=tol, max_iter=1000, return_info=True, **kw)
    assert info.converged is True and info.iterations == first
    assert info.primal_residual == pytest.approx(changes[first], rel=1e-9)


def test_warm_start_estimates_the_residual_dual_from_E0():
    """E0 enters the ADMM's first iterate (the dual of the residual block), as documented:
    the same C0 with another E0 gives another first step."""
    X, D = make_instance(10, n=6)
    C, E = solve_smtmvt(X, D, lam=0.3, tol=1e-10, max_iter=10000)
    C_a, _ = solve_smtmvt(X, D, lam=0.3, C0=C, E0=E, max_iter=1)
    C_b, _ = solve_smtmvt(X, D, lam=0.3, C0=C, E0=[e + 0.2 for e in E], max_iter=1)
    assert np.abs(C_a - C_b).max() > 1e-3


def test_any_start_reaches_the_optimum():
    X, D = make_instance(10, n=6)
    _, _, opt = solve_smtmvt(X, D, lam=0.3, tol=1e-9, return_info=True)
    rng = np.random.default_rng(0)
    C0 = rng.standard_normal((3, 5, 6))  # even infeasible (negative) starts
    C, _, info = solve_smtmvt(X, D, lam=0.3, tol=1e-9, C0=C0, return_info=True)
    assert info.converged and np.all(C >= 0)
    assert info.objective == pytest.approx(opt.objective, rel=1e-10)  # measured 3.5e-12 apart


def test_reconstruction_residual_excludes_E():
    X, D = make_instance(12)
    C, E = solve_smtmvt(X, D)
    res = reconstruction_residual(X, D, C)
    assert res.shape == (X[0].shape[1],)
    expected = [sum(np.sum((D[k] @ C[k][:, i] - X[k][:, i]) ** 2) for k in range(len(X))) for i in range(X[0].shape[1])]
    assert np.allclose(res, expected, rtol=1e-12)
    assert np.any(np.abs(E[0]) > 0)  # E is nonzero, yet not part of the residual


def test_objective_matches_loops():
    X, D = make_instance(13)
    rng = np.random.default_rng(1)
    C = np.abs(rng.standard_normal((3, 5, 4)))
    E = [rng.standard_normal(x.shape) for x in X]
    assert smtmvt_objective(X, D, C, E, 0.3, 0.7) == pytest.approx(objective_by_loops(X, D, C, E, 0.3, 0.7), rel=1e-12)


def test_lipschitz_constant_bounds_the_gradient():
    """L = 2 max_k(||D^k||^2 + 1) is attained by the Hessian 2 [D, I]'[D, I]."""
    _, D = make_instance(14, K=2)
    L = lipschitz_constant(D)
    Hmax = max(
        np.linalg.eigvalsh(2 * np.hstack([Dk, np.eye(Dk.shape[0])]).T @ np.hstack([Dk, np.eye(Dk.shape[0])])).max()
        for Dk in D
    )
    assert L == pytest.approx(Hmax, rel=1e-10)


# ---------------------------------------------------------------- input errors
def test_mismatched_feature_dimension_is_named():
    X, D = make_instance(15)
    D[1] = D[1][:-1]
    with pytest.raises(ValueError, match=r"X\[1\].*D\[1\]"):
        solve_smtmvt(X, D)


def test_mismatched_candidates_is_named():
    X, D = make_instance(15)
    X[2] = X[2][:, :-1]
    with pytest.raises(ValueError, match=r"X\[2\].*candidates"):
        solve_smtmvt(X, D)


def test_mismatched_templates_is_named():
    X, D = make_instance(15)
    D[1] = D[1][:, :-1]
    with pytest.raises(ValueError, match=r"D\[1\].*templates"):
        solve_smtmvt(X, D)


def test_view_count_mismatch():
    X, D = make_instance(15)
    with pytest.raises(ValueError, match="views"):
        solve_smtmvt(X, D[:2])


def test_single_array_instead_of_list():
    X, D = make_instance(15)
    with pytest.raises(ValueError, match=r"X must be a list"):
        solve_smtmvt(X[0], D)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(lam=-1.0), "lam"),
        (dict(gamma=float("nan")), "gamma"),
        (dict(tol=0.0), "tol"),
        (dict(max_iter=0), "max_iter"),
        (dict(method="fast"), "method"),
        (dict(C0=np.zeros((3, 5, 3))), "C0"),
        (dict(E0=[np.zeros((2, 2))] * 3), "E0"),
    ],
)
def test_bad_parameters_are_named(kwargs, name):
    X, D = make_instance(15)
    with pytest.raises(ValueError, match=name):
        solve_smtmvt(X, D, **kwargs)


def test_integer_views_one_row_views_and_one_template_are_accepted():
    X, D = make_instance(16, K=2, N=1, n=3)
    X[1], D[1] = X[1][:1], D[1][:1]  # d_k = 1
    C, E = solve_smtmvt(X, D)
    assert C.shape == (2, 1, 3)
    Xi = [np.round(10 * x).astype(np.int32) for x in X]
    Di = [np.round(10 * d).astype(np.int64) for d in D]
    Ci, _ = solve_smtmvt(Xi, Di, tol=1e-10, max_iter=10000)
    Cf, _ = solve_smtmvt([x.astype(float) for x in Xi], [d.astype(float) for d in Di], tol=1e-10, max_iter=10000)
    np.testing.assert_array_equal(Ci, Cf)


def _views(edit=None):
    """Instance 15 (K=3, N=5, n=4), optionally with ``edit(X, D)`` applied."""
    X, D = make_instance(15)
    if edit is not None:
        edit(X, D)
    return X, D


def _set(lst, k, fn):
    lst[k] = fn(lst[k])


def _infinite_E0(X):
    E0 = [np.zeros_like(x) for x in X]
    E0[1][0, 0] = np.inf
    return E0


# (X, D) edit, solver keyword arguments (a function of X), the message's start
_INPUT_ERRORS = [
    (lambda X, D: X.__setitem__(slice(None), [5.0]), None, "X[0] must be 2-D, got shape ()"),
    (lambda X, D: _set(X, 1, lambda x: x[..., None]), None, "X[1] must be 2-D, got shape "),
    (
        lambda X, D: _set(D, 2, lambda d: d.astype(complex)),
        None,
        "D[2] must be a real float or integer array, got dtype complex128",
    ),
    (
        lambda X, D: _set(X, 2, lambda x: x[:, :-1]),
        None,
        "X[2] has 3 columns (candidates) but X[0] has 4: every view must hold the same n candidates",
    ),
    (
        lambda X, D: _set(D, 1, lambda d: d[:, :-1]),
        None,
        "D[1] has 4 columns (templates) but D[0] has 5: every view must hold the same N templates",
    ),
    (lambda X, D: (_set(X, 0, lambda x: x[:0]), _set(D, 0, lambda d: d[:0])), None, "X[0] has zero rows (d_k = 0)"),
    (
        lambda X, D: X.__setitem__(slice(None), [x[:, :0] for x in X]),
        None,
        "X has zero columns: there must be at least one candidate",
    ),
    (
        lambda X, D: D.__setitem__(slice(None), [d[:, :0] for d in D]),
        None,
        "D has zero columns: there must be at least one template",
    ),
    (None, lambda X: dict(lam="big"), "lam must be a number, got 'big'"),
    (None, lambda X: dict(C0=np.full((3, 5, 4), np.nan)), "C0 contains NaN or infinite values"),
    (None, lambda X: dict(C0=np.zeros((3, 5, 4)), E0=5), "E0 must be a list of K arrays shaped like X"),
    (None, lambda X: dict(C0=np.zeros((3, 5, 4)), E0=[np.zeros((2, 2))] * 2), "E0 must hold K=3 arrays, got 2"),
    (None, lambda X: dict(C0=np.zeros((3, 5, 4)), E0=_infinite_E0(X)), "E0[1] contains NaN or infinite values"),
]


@pytest.mark.parametrize("edit, kwargs, message", _INPUT_ERRORS)
def test_input_errors_say_what_is_wrong(edit, kwargs, message):
    X, D = _views(edit)
    with pytest.raises(ValueError, match="^" + re.escape(message)):
        solve_smtmvt(X, D, **(kwargs(X) if kwargs else {}))


def test_input_errors_name_the_argument_and_the_sizes():
    X, D = make_instance(15)
    with pytest.raises(ValueError, match=re.escape("X must be a list of K 2-D arrays, got float")):
        solve_smtmvt(5.0, D)
    with pytest.raises(
        ValueError,
        match=re.escape(
            "D must be a list of K 2-D arrays (one per view), got a single 2-D array; wrap it as [D] for one view"
        ),
    ):
        solve_smtmvt(X, D[0])
    with pytest.raises(ValueError, match="^" + re.escape("X must hold at least one view, got an empty sequence")):
        solve_smtmvt([], [])
    D[1] = D[1][:-2]
    rows = f"X[1] has {X[1].shape[0]} rows but D[1] has {D[1].shape[0]}: the feature dimension d_k of a view must match"
    assert X[1].shape[0] not in (X[1].shape[1], D[1].shape[0]) and D[1].shape[0] != D[1].shape[1]  # distinguishable
    with pytest.raises(ValueError, match="^" + re.escape(rows) + "$"):
        solve_smtmvt(X, D)


def test_objective_checks_the_shape_of_C():
    X, D = make_instance(15)
    with pytest.raises(ValueError, match=re.escape("C must have shape (K, N, n) = (3, 5, 4), got (3, 4, 4)")):
        smtmvt_objective(X, D, np.zeros((3, 4, 4)), [np.zeros_like(x) for x in X], 0.1, 0.25)


def test_nan_input_rejected():
    X, D = make_instance(15)
    X[0][0, 0] = np.nan
    with pytest.raises(ValueError, match=r"X\[0\].*NaN"):
        solve_smtmvt(X, D)


def test_admm_tolerances_and_penalty_rule_as_documented():
    """Residual balancing (Boyd et al. 3.4.1): rho x2 when the scaled primal residual is more than
    ADAPT_RATIO times the dual one, x0.5 when less than 1/ADAPT_RATIO, on every ADAPT_EVERY-th
    iteration up to ADAPT_UNTIL, at most ADAPT_MAX changes."""
    from smtmvt.solvers import _admm_rules as rules

    eps_pri, eps_dual = rules.tolerances(1e-4, 3.0, np.array([2.0, 5.0]))
    assert eps_pri == 1e-4 * 3.0 + rules.ABS_FLOOR
    np.testing.assert_array_equal(eps_dual, 1e-4 * np.array([2.0, 5.0]) + rules.ABS_FLOOR)

    it = rules.ADAPT_EVERY * 2
    mu = rules.ADAPT_RATIO
    # per-entry ratios (r_pri / eps_pri) / (r_dual / eps_dual): above mu, equal to mu, between, 1/mu, below, dual 0
    r_pri = np.array([2 * mu, mu, 1.0, 1 / mu, 0.5 / mu, 1.0])
    r_dual = np.array([1.0, 1.0, 1.0, 1.0, 1.0, 0.0])
    f = rules.penalty_factor(it, np.zeros(6), r_pri, 1.0, r_dual, 1.0)
    np.testing.assert_array_equal(f, [2.0, 1.0, 1.0, 1.0, 0.5, 2.0])
    # at most ADAPT_MAX changes per entry
    n_adapt = np.array([rules.ADAPT_MAX - 1, rules.ADAPT_MAX, rules.ADAPT_MAX + 1, 0, rules.ADAPT_MAX, 0])
    np.testing.assert_array_equal(
        rules.penalty_factor(it, n_adapt, r_pri, 1.0, r_dual, 1.0), [2.0, 1.0, 1.0, 1.0, 1.0, 2.0]
    )
    # only on every ADAPT_EVERY-th iteration, up to ADAPT_UNTIL included
    for it_off in (it + 1, rules.ADAPT_UNTIL + rules.ADAPT_EVERY):
        off = rules.penalty_factor(it_off, np.zeros(6), r_pri, 1.0, r_dual, 1.0)
        assert isinstance(off, np.ndarray) and off.shape == (6,) and np.all(off == 1.0)
    assert rules.ADAPT_UNTIL % rules.ADAPT_EVERY == 0
    np.testing.assert_array_equal(rules.penalty_factor(rules.ADAPT_UNTIL, np.zeros(6), r_pri, 1.0, r_dual, 1.0)[0], 2.0)
    # a scalar ADMM gets a float: 2, 0.5 or 1, also off the schedule
    for it_s, rp, expect in ((it, 10 * mu, 2.0), (it, 0.1 / mu, 0.5), (it, 1.0, 1.0), (it + 1, 10 * mu, 1.0)):
        out = rules.penalty_factor(it_s, 0, rp, 1.0, 1.0, 1.0)
        assert type(out) is float and out == expect


def test_admm_info_aggregates_the_independent_per_candidate_runs():
    """One ADMM per candidate: the batch's info is the per-candidate runs' (max and mean iterations,
    root sum of squares of the residuals, median rho); the iteration cap is exact."""
    X, D = make_instance(41, K=3, N=5, n=5)
    _, _, info = solve_smtmvt(X, D, tol=1e-6, return_info=True)
    singles = [solve_smtmvt([x[:, [i]] for x in X], D, tol=1e-6, return_info=True)[2] for i in range(5)]
    its = [s.iterations for s in singles]
    assert type(info.iterations) is int and info.iterations == max(its) and len(set(its)) > 1
    assert info.mean_iterations == pytest.approx(np.mean(its), rel=1e-15)
    assert info.converged
    assert info.primal_residual == pytest.approx(np.sqrt(sum(s.primal_residual**2 for s in singles)), rel=1e-12)
    assert info.dual_residual == pytest.approx(np.sqrt(sum(s.dual_residual**2 for s in singles)), rel=1e-12)
    assert info.rho == pytest.approx(np.median([s.rho for s in singles]), rel=1e-15)
    # the cap: exactly max_iter iterations, not converged
    _, _, capped = solve_smtmvt(X, D, tol=1e-12, max_iter=3, return_info=True)
    assert capped.iterations == 3 and capped.mean_iterations == 3.0 and not capped.converged
