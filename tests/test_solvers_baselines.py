"""The comparison observation models (L1T, MTT, MTMVT-LS, MTMVT-LAD) against cvxpy.

For each model the cvxpy problem is written independently from the package;
the package's solution is scored by cvxpy's own objective expression.
"""

import cvxpy as cp  # a pinned test dependency (requirements-dev.txt): missing means broken
import numpy as np
import pytest

from smtmvt.solvers import SOLVERS, solve_smtmvt
from smtmvt.solvers.baselines import mtmvt_objective, solve_l1t, solve_mtmvt_lad, solve_mtmvt_ls, solve_mtt
from solver_instances import make_instance

# Relative gap of our objective to CLARABEL's, measured on the instances below (tol 1e-9):
# l1t -8.4e-11, mtt -4.9e-11, mtmvt-ls -9.9e-11, mtmvt-lad +2.4e-9. Bounds ~10x those.
GAP_BELOW, GAP_ABOVE = 1e-9, 3e-8


def _solve(prob):
    prob.solve(solver="CLARABEL", tol_gap_abs=1e-9, tol_gap_rel=1e-9, tol_feas=1e-9)
    assert prob.status == "optimal"
    return prob.value


def _score(prob, assignments):
    """cvxpy objective value with the variables set to our solution."""
    for var, val in assignments:
        var.value = val
    return prob.objective.value


@pytest.fixture(scope="module")
def inst():
    X, D = make_instance(31, K=3, N=4, n=5)
    return X, D, len(X), D[0].shape[1], X[0].shape[1]


def test_l1t_matches_cvxpy(inst):
    X, D, K, N, n = inst
    lam = 0.1
    C = [cp.Variable((N, n)) for _ in range(K)]
    E = [cp.Variable(x.shape) for x in X]
    obj = sum(cp.sum_squares(X[k] - D[k] @ C[k] - E[k]) + lam * (cp.sum(C[k]) + cp.sum(cp.abs(E[k]))) for k in range(K))
    prob = cp.Problem(cp.Minimize(obj), [c >= 0 for c in C])
    ref = _solve(prob)
    Cs, Es, info = solve_l1t(X, D, lam=lam, tol=1e-9, max_iter=20000, return_info=True)
    assert info.converged and np.all(Cs >= 0)
    ours = _score(prob, list(zip(C, Cs)) + list(zip(E, Es)))
    assert ours == pytest.approx(info.objective, rel=1e-10)
    assert ref * (1 - GAP_BELOW) <= ours <= ref * (1 + GAP_ABOVE)


def test_l1t_is_smtmvt_without_nuclear_norm(inst):
    X, D, *_ = inst
    C1, E1 = solve_l1t(X, D, lam=0.2, tol=1e-10, max_iter=20000)
    C2, E2 = solve_smtmvt(X, D, lam=0.0, gamma=0.2, tol=1e-10, max_iter=20000)
    assert np.allclose(C1, C2, rtol=0, atol=1e-7)  # measured 4.0e-9


def test_mtt_matches_cvxpy(inst):
    X, D, K, N, n = inst
    lam = 0.1
    C = [cp.Variable((N, n)) for _ in range(K)]
    E = [cp.Variable(x.shape) for x in X]
    obj = sum(
        cp.sum_squares(X[k] - D[k] @ C[k] - E[k])
        + lam * (cp.sum(cp.norm(C[k], 2, axis=1)) + cp.sum(cp.norm(E[k], 2, axis=1)))
        for k in range(K)
    )
    prob = cp.Problem(cp.Minimize(obj))
    ref = _solve(prob)
    Cs, Es, info = solve_mtt(X, D, lam=lam, tol=1e-9, max_iter=20000, return_info=True)
    assert info.converged
    ours = _score(prob, list(zip(C, Cs)) + list(zip(E, Es)))
    assert ours == pytest.approx(info.objective, rel=1e-10)
    assert ref * (1 - GAP_BELOW) <= ours <= ref * (1 + GAP_ABOVE)
    # joint sparsity: whole template rows switch off together across candidates
    row_norms = np.linalg.norm(Cs, axis=2)
    assert np.all((row_norms == 0) | (row_norms > 1e-6))


@pytest.fixture(scope="module")
def shared_and_outlier():
    """Candidates 1..4 mix templates 0 and 1; candidate 0 is template 3 alone.
    With lam_q < lam_p < lam_q sqrt(n) both P and Q are partly active."""
    X, D = make_instance(31, K=3, N=4, n=5)
    rng = np.random.default_rng(5)
    for k in range(3):
        d = X[k].shape[0]
        X[k] = D[k][:, :2] @ np.abs(rng.standard_normal((2, 5))) + 0.02 * rng.standard_normal((d, 5))
        X[k][:, 0] = 2 * D[k][:, 3] + 0.02 * rng.standard_normal(d)
    return X, D, 3, 4, 5


@pytest.mark.parametrize("loss", ["ls", "lad"])
def test_mtmvt_matches_cvxpy(shared_and_outlier, loss):
    X, D, K, N, n = shared_and_outlier
    lam_p, lam_q = 0.2, 0.15
    P = [cp.Variable((N, n)) for _ in range(K)]
    Q = [cp.Variable((N, n)) for _ in range(K)]
    fit = sum(
        cp.sum_squares(X[k] - D[k] @ (P[k] + Q[k])) if loss == "ls" else cp.sum(cp.abs(X[k] - D[k] @ (P[k] + Q[k])))
        for k in range(K)
    )
    rows = sum(cp.norm(cp.hstack([P[k][j, :] for k in range(K)]), 2) for j in range(N))
    cols = sum(cp.norm(cp.hstack([Q[k][:, i] for k in range(K)]), 2) for i in range(n))
    prob = cp.Problem(cp.Minimize(fit + lam_p * rows + lam_q * cols))
    ref = _solve(prob)
    solver = solve_mtmvt_ls if loss == "ls" else solve_mtmvt_lad
    Cs, Es, info = solver(X, D, lam_p=lam_p, lam_q=lam_q, tol=1e-9, max_iter=50000, return_info=True)
    assert info.converged
    Ps, Qs = info.parts["P"], info.parts["Q"]
    assert np.allclose(Cs, Ps + Qs)
    # both group structures are exercised: some groups on, some exactly off
    p_rows = np.linalg.norm(Ps, axis=(0, 2))
    q_cols = np.linalg.norm(Qs, axis=(0, 1))
    assert np.any(p_rows == 0) and np.any(p_rows > 0.1)
    assert q_cols.argmax() == 0 and q_cols[0] > 1.0  # the outlier candidate lives in Q
    assert all(np.all(e == 0) for e in Es)
    ours = _score(prob, list(zip(P, Ps)) + list(zip(Q, Qs)))
    assert ours == pytest.approx(info.objective, rel=1e-10)
    assert ref * (1 - GAP_BELOW) <= ours <= ref * (1 + GAP_ABOVE)


def test_registry_calling_convention(inst):
    X, D, K, N, n = inst
    assert set(SOLVERS) == {"smtmvt", "l1t", "mtt", "mtmvt-ls", "mtmvt-lad"}
    for name, solver in SOLVERS.items():
        C, E = solver(X, D)
        assert C.shape == (K, N, n) and C.dtype == np.float64, name
        assert [e.shape for e in E] == [x.shape for x in X], name


@pytest.mark.parametrize("name", ["l1t", "mtt", "mtmvt-ls", "mtmvt-lad"])
def test_iteration_cap_and_info(inst, name):
    """max_iter=1 is allowed and honoured; info names the model and holds numbers."""
    X, D, *_ = inst
    solver = SOLVERS[name]
    _, _, info = solver(X, D, max_iter=1, return_info=True)
    assert info.iterations == 1 and info.converged is False
    _, _, info = solver(X, D, max_iter=3, return_info=True)
    assert info.iterations == 3 and info.converged is False and info.method == name
    for value in (info.primal_residual, info.dual_residual, info.rho, info.objective):
        assert type(value) is float and np.isfinite(value) and value > 0
    _, _, info = solver(X, D, tol=1e-2, max_iter=5000, return_info=True)
    assert info.converged is True and 3 < info.iterations < 5000


def test_mtmvt_objective_loss():
    X, D = make_instance(32, K=2, N=3, n=4)
    rng = np.random.default_rng(0)
    P, Q = rng.standard_normal((2, 3, 4)), rng.standard_normal((2, 3, 4))
    ls = mtmvt_objective(X, D, P, Q, 0.2, 0.1, loss="ls")
    assert mtmvt_objective(X, D, P, Q, 0.2, 0.1) == ls  # least squares by default
    assert mtmvt_objective(X, D, P, Q, 0.2, 0.1, loss="lad") != ls
    with pytest.raises(ValueError, match="^loss must be 'ls' or 'lad', got 'l2'$"):
        mtmvt_objective(X, D, P, Q, 0.2, 0.1, loss="l2")


@pytest.mark.parametrize(
    "solver, kwargs, name",
    [
        (solve_l1t, dict(lam=-1), "lam"),
        (solve_mtmvt_lad, dict(lam_p=-1), "lam_p"),
        (solve_mtt, dict(tol=0), "tol"),
        (solve_mtmvt_ls, dict(lam_q=-0.1), "lam_q"),
        (solve_mtmvt_lad, dict(max_iter=0), "max_iter"),
    ],
)
def test_bad_parameters_are_named(inst, solver, kwargs, name):
    X, D, *_ = inst
    with pytest.raises(ValueError, match=name):
        solver(X, D, **kwargs)


def test_shape_errors_are_named(inst):
    X, D, *_ = inst
    with pytest.raises(ValueError, match=r"X\[1\].*D\[1\]"):
        solve_mtt(X, [D[0], D[1][:-1], D[2]])


def _lad_reference(X, D, lam_p, lam_q):
    """cvxpy's optimum of the MTMVT-LAD problem, written independently of the package."""
    K, N, n = len(X), D[0].shape[1], X[0].shape[1]
    P = [cp.Variable((N, n)) for _ in range(K)]
    Q = [cp.Variable((N, n)) for _ in range(K)]
    fit = sum(cp.sum(cp.abs(X[k] - D[k] @ (P[k] + Q[k]))) for k in range(K))
    rows = sum(cp.norm(cp.hstack([P[k][j, :] for k in range(K)]), 2) for j in range(N))
    cols = sum(cp.norm(cp.hstack([Q[k][:, i] for k in range(K)]), 2) for i in range(n))
    return _solve(cp.Problem(cp.Minimize(fit + lam_p * rows + lam_q * cols)))


def test_mtmvt_lad_at_the_trackers_budget_is_near_the_optimum():
    """The tracker's setting (TrackerConfig.paper: tol 1e-3, 200 iterations) on an
    instance of the tracker's shape (4 views, 10 templates, unit columns): the
    objective within 1% of cvxpy's (measured 0.13%, 0.40% with residual balancing); balancing, on for the
    other models, is off for LAD (on the tracker's own instances it stalled 47% above)."""
    X, D = make_instance(7, K=4, N=10, n=60, d_range=(40, 120))
    X = [x / np.linalg.norm(x, axis=0) for x in X]
    ref = _lad_reference(X, D, 0.1, 0.5)
    _, _, info = solve_mtmvt_lad(X, D, tol=1e-3, max_iter=200, return_info=True)
    assert ref <= info.objective * (1 + 1e-9)
    assert info.objective <= ref * 1.01
