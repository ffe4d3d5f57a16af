"""IVT (smtmvt.ivt): the incremental SVD against a batch SVD of the same data, the
state's geometry, and the tracker on a real sequence."""

import numpy as np
import pytest

from smtmvt.geometry import box_to_affine
from smtmvt.ivt import IVTConfig, IVTTracker, geom_to_affine, incremental_svd, subspace_distance


def _batches(seed, d=40, sizes=(5, 5, 4, 5)):
    rng = np.random.default_rng(seed)
    basis = rng.standard_normal((d, 6))
    return [basis @ rng.standard_normal((6, m)) + 0.05 * rng.standard_normal((d, m)) + 3.0 for m in sizes]


def _incremental(batches, forgetting, max_basis=None):
    U, s, mean, n = None, None, None, 0.0
    for b in batches:
        U, s, mean, n = incremental_svd(b, U, s, mean, n, forgetting, max_basis)
    return U, s, mean, n


def _same_subspace(U1, U2):
    return np.abs(U1 @ U1.T - U2 @ U2.T).max()


def test_forgetting_one_is_the_batch_svd_of_all_samples():
    batches = _batches(1)
    U, s, mean, n = _incremental(batches, 1.0)
    A = np.hstack(batches)
    mu = A.mean(axis=1)
    Ub, sb, _ = np.linalg.svd(A - mu[:, None], full_matrices=False)
    r = len(s)
    assert n == A.shape[1]
    assert np.abs(mean - mu).max() < 1e-12  # measured 8.9e-16
    assert np.abs(s - sb[:r]).max() < 1e-10 * sb[0]  # measured 1.4e-14 relative
    assert np.all(sb[r:] ** 2 <= 1e-6 * np.sum(sb**2))  # only the negligible ones dropped
    assert _same_subspace(U, Ub[:, :r]) < 1e-8  # measured 9.4e-13


def test_forgetting_below_one_is_the_svd_of_the_weighted_data():
    """f < 1: the samples of the k-th update from the last weigh f**k in the mean, and
    their centred columns (with each update's mean-shift column) f**k in the SVD."""
    f, batches = 0.8, _batches(2)
    U, s, mean, n = _incremental(batches, f)
    T = len(batches)
    w = [f ** (T - 1 - k) for k in range(T)]
    columns = [w[0] * (batches[0] - batches[0].mean(axis=1, keepdims=True))]
    for k in range(1, T):
        seen = np.hstack(batches[:k])
        weights = np.concatenate([np.full(b.shape[1], f ** (k - 1 - j)) for j, b in enumerate(batches[:k])])
        mu_seen, n_seen, m = np.average(seen, axis=1, weights=weights), weights.sum(), batches[k].shape[1]
        mu_k = batches[k].mean(axis=1)
        shift = np.sqrt(n_seen * m / (n_seen + m)) * (mu_seen - mu_k)
        columns.append(w[k] * np.column_stack([batches[k] - mu_k[:, None], shift]))
    Ub, sb, _ = np.linalg.svd(np.hstack(columns), full_matrices=False)
    all_weights = np.concatenate([np.full(b.shape[1], w[k]) for k, b in enumerate(batches)])
    assert n == pytest.approx(all_weights.sum(), rel=1e-12)
    assert np.abs(mean - np.average(np.hstack(batches), axis=1, weights=all_weights)).max() < 1e-12
    r = len(s)
    assert np.abs(s - sb[:r]).max() < 1e-10 * sb[0]
    assert _same_subspace(U, Ub[:, :r]) < 1e-8
    # and forgetting changes the answer (the test can fail)
    assert np.abs(_incremental(batches, 1.0)[1][:r] - s).max() > 1e-3 * s[0]


def test_max_basis_keeps_the_leading_vectors():
    U, s, _, _ = _incremental(_batches(3), 1.0, max_basis=3)
    U_all, s_all, _, _ = _incremental(_batches(3), 1.0)
    assert U.shape[1] == 3 and np.allclose(s, s_all[:3], rtol=1e-2)
    assert np.allclose(U.T @ U, np.eye(3), atol=1e-10)


def test_incremental_svd_refuses_bad_input():
    with pytest.raises(ValueError, match="forgetting must be in"):
        incremental_svd(np.ones((4, 2)), forgetting=1.5)
    with pytest.raises(ValueError, match=r"shape \(4,\)"):
        incremental_svd(np.ones(4))
    with pytest.raises(ValueError, match="invalid sigma=0"):
        IVTConfig(sigma=0)


def test_subspace_distance_is_the_residual_of_the_projection():
    rng = np.random.default_rng(4)
    U, _ = np.linalg.qr(rng.standard_normal((10, 3)))
    mean, X = rng.standard_normal(10), rng.standard_normal((10, 6))
    inside = mean[:, None] + U @ rng.standard_normal((3, 6))
    assert np.allclose(subspace_distance(inside, U, mean), 0, atol=1e-20 + 1e-24)
    coef = np.linalg.lstsq(U, X - mean[:, None], rcond=None)[0]
    expected = np.sum((X - mean[:, None] - U @ coef) ** 2, axis=0)
    assert np.allclose(subspace_distance(X, U, mean), expected)


def test_geometry_of_the_state():
    box = np.array([10.0, 20.0, 48.0, 24.0])
    a = box_to_affine(box)
    geom = [a[4], a[5], a[0], 0.0, a[3] / a[0], 0.0]
    assert np.allclose(geom_to_affine(geom)[0], a)
    # a rotation by theta turns the template's u axis by theta and keeps its lengths
    M = geom_to_affine([0, 0, 2.0, 0.3, 0.5, 0.0])[0]
    assert np.allclose(M[[0, 2]], 2.0 * np.array([np.cos(0.3), np.sin(0.3)]))
    assert np.hypot(M[1], M[3]) == pytest.approx(1.0)


def test_ivt_tracks_crossing(otb_dir):
    from smtmvt import open_sequence

    seq = open_sequence(otb_dir / "Crossing")
    tracker = IVTTracker(IVTConfig(seed=0))
    tracker.init(seq[0], seq.first_box)
    boxes = np.array([seq.first_box] + [tracker.update(seq[i]) for i in range(1, 20)])
    gt = np.asarray(seq.groundtruth[:20])
    lo, hi = np.maximum(boxes[:, :2], gt[:, :2]), np.minimum(boxes[:, :2] + boxes[:, 2:], gt[:, :2] + gt[:, 2:])
    inter = np.prod(np.clip(hi - lo, 0, None), axis=1)
    iou = inter / (np.prod(boxes[:, 2:], axis=1) + np.prod(gt[:, 2:], axis=1) - inter)
    assert iou.mean() > 0.5  # measured 0.79
    assert tracker._U is not None and tracker._U.shape[1] <= 16  # the subspace was learned
