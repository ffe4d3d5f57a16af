"""Tests of the proximal operators against direct definitions."""

import warnings

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from smtmvt.solvers.prox import (
    group_huber_prox,
    group_shrink,
    huber_prox,
    nonneg_shrink,
    nuclear_norms,
    singular_value_threshold,
    soft_threshold,
)


def svt_by_svd(P, tau):
    U, s, Vt = np.linalg.svd(P, full_matrices=False)
    return (U * np.maximum(s - tau, 0)[..., None, :]) @ Vt


@pytest.mark.parametrize("shape", [(50, 10, 4), (30, 3, 5), (20, 4, 1), (10, 1, 4), (5, 6, 6)])
@pytest.mark.parametrize("tau", [0.0, 1e-3, 0.3, 2.0])
def test_svt_matches_svd(shape, tau):
    rng = np.random.default_rng(sum(shape))
    P = rng.standard_normal(shape)
    P[::3] = P[::3, :, :1] * rng.standard_normal((1, 1, shape[2]))  # some rank-1 slices
    P[1] = 0.0  # a zero slice
    out = singular_value_threshold(P, tau)
    assert out.shape == P.shape
    assert np.allclose(out, svt_by_svd(P, tau), atol=1e-10)


def test_svt_is_the_prox_of_the_nuclear_norm():
    """Random perturbations never beat the SVT output in the prox objective."""
    rng = np.random.default_rng(0)
    P = rng.standard_normal((1, 6, 3))
    tau = 0.7
    Z = singular_value_threshold(P, tau)

    def prox_obj(Y):
        return tau * nuclear_norms(Y)[0] + 0.5 * np.sum((Y - P) ** 2)

    best = prox_obj(Z)
    for _ in range(200):
        assert prox_obj(Z + 1e-3 * rng.standard_normal(Z.shape)) >= best - 1e-15


def test_nuclear_norms():
    rng = np.random.default_rng(1)
    P = rng.standard_normal((7, 5, 3))
    assert np.allclose(nuclear_norms(P), [np.linalg.norm(p, "nuc") for p in P])


def test_soft_and_nonneg_shrink():
    v = np.array([-2.0, -0.5, 0.0, 0.5, 2.0])
    assert np.array_equal(soft_threshold(v, 1.0), [-1.0, 0.0, 0.0, 0.0, 1.0])
    assert np.array_equal(nonneg_shrink(v, 1.0), [0.0, 0.0, 0.0, 0.0, 1.0])


@pytest.mark.parametrize("gamma, rho", [(0.25, 2.0), (1.0, 0.3), (0.05, 10.0)])
def test_huber_prox_by_scalar_minimization(gamma, rho):
    """h(r) = min_e (r - e)^2 + gamma|e|; its prox matches a 1-D numerical minimization."""

    def h(r):
        e = np.sign(r) * max(abs(r) - gamma / 2, 0)
        return (r - e) ** 2 + gamma * abs(e)

    for v in np.linspace(-2, 2, 41):
        res = minimize_scalar(
            lambda r, v=v: h(r) + rho / 2 * (r - v) ** 2, bounds=(-5, 5), method="bounded", options={"xatol": 1e-12}
        )
        assert huber_prox(np.array([v]), gamma, rho)[0] == pytest.approx(res.x, abs=1e-6)


def test_group_shrink():
    V = np.array([[3.0, 4.0], [0.3, 0.4]])  # row norms 5 and 0.5
    out = group_shrink(V, 1.0, axis=1)
    assert np.allclose(out, [[3.0 * 0.8, 4.0 * 0.8], [0.0, 0.0]])


@pytest.mark.parametrize("gamma", [0.0, 0.5])
def test_group_huber_prox_of_zero_groups_is_silent(gamma):
    """All-zero groups (and gamma = 0, a zero radius) are ordinary input inside the
    solvers: exact results, no divide/invalid warnings."""
    V = np.zeros((3, 4))
    V[1] = [3.0, 4.0, 0.0, 0.0]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = group_huber_prox(V, gamma, 2.0, axis=1)
    W = V * 0.5  # 2 v / (2 + rho)
    expected = V - W * min(1.0, (gamma / 2.0) / 2.5)  # row 1: ||W|| = 2.5, radius gamma/rho
    np.testing.assert_allclose(out, expected, rtol=0, atol=1e-15)


def test_zero_and_rank_deficient_inputs_are_silent():
    """Zero singular values, zero groups: exact results without divide/invalid warnings
    (they are ordinary inside the solvers: C = 0 at the start, empty groups)."""
    rng = np.random.default_rng(3)
    P = np.zeros((4, 5, 3))
    P[1] = np.outer(rng.standard_normal(5), rng.standard_normal(3))  # rank 1
    P[2, :, 0] = 1.0  # rank 1, zero columns
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        svt = singular_value_threshold(P, 0.1)
        svt_wide = singular_value_threshold(np.swapaxes(P, 1, 2), 0.1)  # the other Gram side
        svt0 = singular_value_threshold(P, 0.0)  # 0 / 0 for the zero singular values
        gs = group_shrink(np.zeros((3, 4)), 0.5, axis=1)
        gs0 = group_shrink(np.zeros((3, 4)), 0.0, axis=1)
    np.testing.assert_allclose(svt, svt_by_svd(P, 0.1), rtol=0, atol=1e-12)
    np.testing.assert_allclose(svt_wide, svt_by_svd(np.swapaxes(P, 1, 2), 0.1), rtol=0, atol=1e-12)
    np.testing.assert_allclose(svt0, P, rtol=0, atol=1e-12)
    assert not gs.any() and not gs0.any()


def test_nuclear_norms_of_rows_and_empty_matrices():
    rng = np.random.default_rng(4)
    rows = rng.standard_normal((6, 1, 3))  # a 1 x K matrix: its nuclear norm is its L2 norm
    np.testing.assert_allclose(nuclear_norms(rows), np.linalg.norm(rows[:, 0, :], axis=1), rtol=1e-14)
    for shape in [(4, 0, 3), (4, 3, 0)]:
        out = nuclear_norms(np.zeros(shape))
        assert out.shape == (4,) and not out.any()
