"""The compiled ADMM engine against the numpy one (the same iteration), and its eigen-solver."""

import numpy as np
import pytest

from smtmvt.solvers import solve_smtmvt
from smtmvt.solvers._admm_kernel import symmetric_eigen
from solver_instances import make_instance

# (K, N, n, lam, gamma): the tracker's shape, fewer templates than views (the
# SVT's left Gram matrix), one view, one candidate, no nuclear norm, codes all zero
CASES = [
    (4, 10, 30, 0.1, 0.25),
    (5, 3, 7, 0.3, 0.1),
    (1, 6, 9, 0.1, 0.25),
    (3, 5, 1, 1.0, 0.05),
    (3, 5, 8, 0.0, 0.2),
    (2, 4, 6, 0.1, 50.0),
]


def _both(X, D, **kw):
    a = solve_smtmvt(X, D, return_info=True, compiled=True, **kw)
    b = solve_smtmvt(X, D, return_info=True, compiled=False, **kw)
    return a, b


@pytest.mark.parametrize("K,N,n,lam,gamma", CASES)
@pytest.mark.parametrize("tol", [1e-3, 1e-8])
def test_compiled_engine_runs_the_same_iteration(K, N, n, lam, gamma, tol):
    """Same codes to rounding, and the same iteration counts and penalties: every
    candidate stops at the same iteration in both engines."""
    X, D = make_instance(100 * K + N + n, K=K, N=N, n=n)
    (Ca, Ea, ia), (Cb, Eb, ib) = _both(X, D, lam=lam, gamma=gamma, tol=tol, max_iter=5000)
    assert Ca.shape == Cb.shape == (K, N, n) and Ca.dtype == np.float64
    assert np.max(np.abs(Ca - Cb)) <= 1e-10 * max(1.0, np.abs(Cb).max())
    assert all(np.allclose(ea, eb, rtol=0, atol=1e-10) for ea, eb in zip(Ea, Eb))
    assert (ia.iterations, ia.mean_iterations, ia.converged) == (ib.iterations, ib.mean_iterations, ib.converged)
    assert ia.rho == ib.rho
    assert ia.primal_residual == pytest.approx(ib.primal_residual, rel=1e-6)
    assert ia.dual_residual == pytest.approx(ib.dual_residual, rel=1e-6)


def test_compiled_engine_from_a_warm_start_and_at_the_cap():
    X, D = make_instance(7, K=4, N=6, n=12)
    C0 = solve_smtmvt(X, D, tol=1e-2)[0] * 1.3
    (Ca, _, ia), (Cb, _, ib) = _both(X, D, tol=1e-7, max_iter=5000, C0=C0)
    assert np.max(np.abs(Ca - Cb)) <= 1e-10 and ia.mean_iterations == ib.mean_iterations
    # warm start used: fewer iterations than from zero
    assert ia.mean_iterations < solve_smtmvt(X, D, tol=1e-7, max_iter=5000, return_info=True)[2].mean_iterations
    (Ca, _, ia), (Cb, _, ib) = _both(X, D, tol=1e-12, max_iter=4)
    assert ia.iterations == ib.iterations == 4 and not ia.converged and not ib.converged
    assert np.max(np.abs(Ca - Cb)) <= 1e-12


def test_compiled_engine_keeps_each_candidate_independent_of_the_batch():
    """Bounded coding needs it: a candidate's code is the same whatever is solved with it."""
    X, D = make_instance(11, K=4, N=8, n=20)
    C_all = solve_smtmvt(X, D, tol=1e-4)[0]
    for subset in ([3], [0, 19], list(range(5, 17))):
        C_sub = solve_smtmvt([x[:, subset] for x in X], D, tol=1e-4)[0]
        assert np.max(np.abs(C_sub - C_all[:, :, subset])) <= 1e-12


@pytest.mark.parametrize(
    "name",
    ["random", "repeated", "rank_one", "zero", "diagonal", "ill_scaled"],
)
def test_symmetric_eigen_matches_lapack(name):
    rng = np.random.default_rng(len(name))
    m = 4
    Q, _ = np.linalg.qr(rng.standard_normal((m, m)))
    w_true = {
        "random": rng.random(m) * 3,
        "repeated": np.array([2.0, 2.0, 2.0, 0.5]),
        "rank_one": np.array([5.0, 0.0, 0.0, 0.0]),
        "zero": np.zeros(m),
        "diagonal": None,
        "ill_scaled": np.array([1e6, 1.0, 1e-6, 1e-12]),
    }[name]
    A = np.diag([3.0, -1.0, 0.5, 2.0]) if w_true is None else (Q * w_true) @ Q.T
    A = (A + A.T) / 2
    V = np.empty((m, m))
    w = symmetric_eigen(A.copy(), V)
    ref = np.linalg.eigvalsh(A)
    scale = max(1.0, np.abs(ref).max())
    assert np.allclose(np.sort(w), ref, rtol=0, atol=1e-13 * scale)
    assert np.allclose(V.T @ V, np.eye(m), atol=1e-13)
    assert np.allclose((V * w) @ V.T, A, rtol=0, atol=1e-13 * scale)
