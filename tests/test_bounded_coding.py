"""Bounded coding: the least-squares bound, per-candidate solves, and skipping candidates."""

import copy
from contextlib import contextmanager

import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.demo import make_demo_sequence
from smtmvt.likelihood import FIRST_PASS, observe
from smtmvt.solvers import reconstruction_residual, solve_smtmvt
from smtmvt.solvers.bounds import least_squares_residuals, range_basis
from smtmvt.solvers.prox import singular_value_threshold
from solver_instances import make_instance


def _code(X, D):
    return solve_smtmvt(X, D, lam=0.1, gamma=0.25, tol=1e-8, max_iter=5000)


def test_least_squares_bound_equals_lstsq_and_bounds_every_code():
    X, D = make_instance(30, K=3, N=5, n=7)
    bound = least_squares_residuals(X, D)
    ref = np.zeros(7)
    for Xk, Dk in zip(X, D):
        coef, *_ = np.linalg.lstsq(Dk, Xk, rcond=None)
        ref += ((Dk @ coef - Xk) ** 2).sum(axis=0)
    np.testing.assert_allclose(bound, ref, rtol=1e-10, atol=1e-12)
    C, _ = _code(X, D)
    assert np.all(bound <= reconstruction_residual(X, D, C) + 1e-12)
    rng = np.random.default_rng(0)
    for _ in range(20):  # any code, not only the optimum
        Cr = np.abs(rng.standard_normal(C.shape))
        assert np.all(bound <= reconstruction_residual(X, D, Cr) + 1e-12)


def test_range_basis_drops_duplicate_templates():
    X, D = make_instance(31, K=1, N=4, n=3)
    Dd = np.column_stack([D[0], D[0][:, :2]])  # two duplicated templates
    Q = range_basis(Dd)
    assert Q.shape[1] == 4
    np.testing.assert_allclose(Q.T @ Q, np.eye(4), atol=1e-12)
    np.testing.assert_allclose(least_squares_residuals(X, [Dd]), least_squares_residuals(X, D), atol=1e-12)


def test_each_candidate_is_solved_independently():
    """The ADMM runs per candidate: a subset of the columns gets the same codes."""
    X, D = make_instance(32, K=4, N=6, n=9)
    C_all, _ = solve_smtmvt(X, D, tol=1e-6)
    for subset in ([0], [3, 7], [8, 1, 5]):
        C_sub, _ = solve_smtmvt([x[:, subset] for x in X], D, tol=1e-6)
        np.testing.assert_allclose(C_sub, C_all[:, :, subset], rtol=0, atol=1e-12)


def test_svt_per_slice_thresholds_equal_one_call_per_slice():
    rng = np.random.default_rng(3)
    P = rng.standard_normal((5, 6, 4))
    tau = np.array([0.0, 0.3, 1.0, 2.5, 10.0])
    out = singular_value_threshold(P, tau)
    for i in range(5):
        np.testing.assert_allclose(out[i], singular_value_threshold(P[i : i + 1], tau[i])[0], atol=1e-12)


def test_observe_skips_only_candidates_that_cannot_matter():
    X, D = make_instance(33, K=3, N=5, n=40)
    full = observe(X, D, _code, alpha=30.0, eps=0.0)
    eps = 1e-3
    pruned = observe(X, D, _code, alpha=30.0, eps=eps)
    assert full.coded.all() and 0 < pruned.coded.sum() < 40  # this instance does skip some
    best = int(np.argmax(full.likelihood))
    assert int(np.argmax(pruned.likelihood)) == best
    np.testing.assert_allclose(pruned.residual[pruned.coded], full.residual[pruned.coded], atol=1e-12)
    skipped = ~pruned.coded
    # the skipped candidates' exact likelihoods sum to less than eps times the best one
    assert full.likelihood[skipped].sum() <= eps * full.likelihood[best]
    assert np.all(pruned.likelihood[skipped] == 0) and np.all(np.isnan(pruned.residual[skipped]))


def test_observe_probes_are_coded_but_change_nothing():
    X, D = make_instance(34, K=3, N=5, n=30)
    valid = np.ones(30, dtype=bool)
    valid[-2:] = False
    probes = ~valid
    with_probes = observe(X, D, _code, alpha=30.0, valid=valid, eps=1e-3, always=probes)
    without = observe([x[:, :-2] for x in X], D, _code, alpha=30.0, eps=1e-3)
    assert with_probes.coded[-2:].all() and np.all(with_probes.likelihood[-2:] > 0)
    np.testing.assert_array_equal(with_probes.coded[:-2], without.coded)
    np.testing.assert_allclose(with_probes.likelihood[:-2], without.likelihood, rtol=1e-12)


def _assert_keeps_the_rule(lazy, full, eps):
    """``lazy`` (deferred views) chose as ``full`` (every candidate coded): the same
    best candidate, the same codes where coded (always complete), and the skipped
    candidates' exact likelihoods within eps of the best."""
    assert lazy.complete[lazy.coded].all()
    best = int(np.argmax(full.likelihood))
    assert int(np.argmax(lazy.likelihood)) == best
    np.testing.assert_allclose(lazy.residual[lazy.coded], full.residual[lazy.coded], atol=1e-12)
    skipped = ~lazy.coded
    assert skipped.any() and full.likelihood[skipped].sum() <= eps * full.likelihood[best]


def test_observe_with_deferred_views_keeps_the_rule():
    """The last view computed only where the bounds need it: the same best candidate
    and codes, every skipped candidate's likelihood within the rule's eps, and
    the deferred view computed for a fraction of the candidates only."""
    X, D = make_instance(35, K=3, N=5, n=60)
    eps = 1e-3
    full = observe(X, D, _code, alpha=30.0, eps=0.0)
    asked = []

    def deferred(idx):
        asked.append(np.array(idx))
        return X[2][:, idx], None

    lazy = observe(X[:2], D, _code, alpha=30.0, eps=eps, deferred=[deferred])
    computed = np.concatenate(asked)
    assert len(set(computed.tolist())) == len(computed)  # each candidate asked at most once
    assert FIRST_PASS <= len(computed) < 60  # the first pass, and not every candidate
    np.testing.assert_array_equal(np.sort(computed), np.flatnonzero(lazy.complete))
    _assert_keeps_the_rule(lazy, full, eps)
    # the views returned: every view where computed, zero columns elsewhere
    np.testing.assert_array_equal(lazy.views[2][:, lazy.complete], X[2][:, lazy.complete])
    assert not lazy.views[2][:, ~lazy.complete].any()
    # the bounds are lower bounds of the residuals (partial ones where the view is missing)
    assert np.all(lazy.bound <= full.residual + 1e-9)


def test_observe_without_deferred_views_is_unchanged_by_the_option():
    X, D = make_instance(36, K=3, N=5, n=40)
    a = observe(X, D, _code, alpha=30.0, eps=1e-3)
    b = observe(X, D, _code, alpha=30.0, eps=1e-3, deferred=[])
    np.testing.assert_array_equal(a.coded, b.coded)
    np.testing.assert_array_equal(a.likelihood, b.likelihood)
    assert b.complete.all()


def test_observe_computes_deferred_views_in_order_each_where_still_needed():
    """Two deferred views: the second asked only of candidates that have the first,
    and of fewer of them; the best candidate, the codes and the rule as coding all."""
    X, D = make_instance(37, K=4, N=5, n=80)
    eps = 1e-3
    full = observe(X, D, _code, alpha=30.0, eps=0.0)
    asked: list = [[], []]

    def stage(j):
        def compute(idx):
            if j == 1:  # view 3 only after view 2
                assert np.isin(idx, np.concatenate(asked[0])).all()
            asked[j].append(np.array(idx))
            return X[2 + j][:, idx], None

        return compute

    lazy = observe(X[:2], D, _code, alpha=30.0, eps=eps, deferred=[stage(0), stage(1)])
    first, second = (np.concatenate(a) for a in asked)
    assert len(set(first.tolist())) == len(first) and len(set(second.tolist())) == len(second)
    assert 16 <= len(second) < len(first) < 80  # this instance stops some candidates after view 2
    np.testing.assert_array_equal(np.sort(second), np.flatnonzero(lazy.complete))
    _assert_keeps_the_rule(lazy, full, eps)
    assert np.all(lazy.bound <= full.residual + 1e-9)
    with pytest.raises(ValueError, match="deferred"):
        observe(X[:2], D, _code, alpha=30.0, eps=eps, deferred=[stage(0)])  # view 3 has no stage


def test_observe_adds_a_deferred_views_offset_when_it_is_computed():
    """An offset that is a sum over the views (as the anchor term), its last view's
    part deferred with that view: the likelihoods of the coded candidates are those
    of the whole offset known up front, and the skipped ones stay within the rule."""
    X, D = make_instance(38, K=3, N=5, n=60)
    eps = 1e-3
    rng = np.random.default_rng(1)
    parts = 0.05 * rng.random((2, 60))  # the offset's parts over views 0-1 and view 2
    full = observe(X, D, _code, alpha=30.0, eps=0.0, offset=parts.sum(axis=0))

    def deferred(idx):
        return X[2][:, idx], parts[1, idx]

    lazy = observe(X[:2], D, _code, alpha=30.0, eps=eps, offset=parts[0], deferred=[deferred])
    _assert_keeps_the_rule(lazy, full, eps)
    np.testing.assert_allclose(lazy.likelihood[lazy.coded], full.likelihood[lazy.coded], rtol=1e-10)
    # without its deferred part the offset would make the coded likelihoods too high
    early = observe(X[:2], D, _code, alpha=30.0, eps=eps, offset=parts[0], deferred=[lambda i: (X[2][:, i], None)])
    assert np.all(early.likelihood[early.coded] > full.likelihood[early.coded])


@pytest.fixture(scope="module")
def demo():
    return make_demo_sequence(n_frames=12)


def _boxes(demo, config, probes=False):
    t = Tracker(config)
    t.init(demo.frames[0], demo.groundtruth[0])
    out = []
    for i in range(1, len(demo.frames)):
        if probes:
            r, detail = t.update_detailed(demo.frames[i], probes=[demo.groundtruth[i], (5, 5, 20, 20)])
            assert detail.probe_likelihood.shape == (2,)
        else:
            r = t.update(demo.frames[i])
        out.append(r.box)
    return np.array(out)


def test_tracker_boxes_do_not_depend_on_bounded_coding_or_probes(demo):
    cfg = TrackerConfig(n_particles=120, seed=4, deferred_views=())
    pruned = _boxes(demo, cfg)
    np.testing.assert_array_equal(pruned, _boxes(demo, cfg.replace(prune_eps=0.0)))
    np.testing.assert_array_equal(pruned, _boxes(demo, cfg, probes=True))


@pytest.mark.parametrize("deferred", [("lbp",), ("hog", "lbp")])
def test_deferred_views_choose_the_same_box_from_the_same_particles(demo, deferred):
    """With the LBP view deferred (and HOG, a term view of the anchor term, before
    it), each frame's chosen particle is the one computing every view chooses, with
    the same score (the same particles: the state is copied across)."""
    cfg = TrackerConfig(n_particles=200, seed=5, deferred_views=deferred)
    assert cfg.anchor_weight > 0 and "hog" in cfg.term_views
    lazy, eager = Tracker(cfg), Tracker(cfg.replace(deferred_views=()))
    for t in (lazy, eager):
        t.init(demo.frames[0], demo.groundtruth[0])
    for frame in demo.frames[1:]:
        eager._rng = copy.deepcopy(lazy._rng)
        eager._motion.particles, eager._motion.weights = lazy._motion.particles.copy(), lazy._motion.weights.copy()
        ra, da = lazy.update_detailed(frame)
        rb, db = eager.update_detailed(frame)
        assert da.best == db.best and ra.box == rb.box
        assert ra.residual == pytest.approx(rb.residual, rel=1e-9)
        assert ra.score == pytest.approx(rb.score, rel=1e-9)  # the anchor term over every term view
        eager._sparse.templates = copy.deepcopy(lazy._sparse.templates)


@pytest.mark.parametrize("deferred", [("lbp",), ("hog", "lbp")])
def test_deferred_views_leave_the_lbp_view_out_for_most_candidates(deferred):
    """Where the tracker follows its target, the bounds settle most candidates before
    their LBP view is computed. On the demo at 40 frames, not the module's 12: at 12 its
    events come three times as fast, the correlation filter's peak falls to 0.12-0.38 of
    its mean from frame 5 on, and the correlation term, measured against that mean
    (docs/experiments.md#n47), then spreads the candidates' offsets over too narrow a
    range to settle their bounds: there the LBP view is needed for the median frame's
    90% of the candidates (48% with each frame's own peak as the scale; at 40 frames 4%
    either way)."""
    demo = make_demo_sequence(n_frames=40)
    t = Tracker(TrackerConfig(n_particles=200, seed=5, deferred_views=deferred))
    t.init(demo.frames[0], demo.groundtruth[0])
    partial = [t.update_detailed(frame)[1].observation.complete.mean() for frame in demo.frames[1:]]
    assert np.median(partial) < 0.5  # the LBP view was left out for most candidates


def test_frame_size_tracks_in_the_working_frame_and_maps_boxes_back(demo):
    """Frames upscaled 2x and tracked at frame_size = the original size give twice the boxes."""
    frames = demo.frames[:6]
    H, W = frames[0].shape[:2]
    big = [np.repeat(np.repeat(f, 2, axis=0), 2, axis=1) for f in frames]
    # without the correlation filter, which reads the input frame itself (its window is
    # resampled to a fixed size, so a 2x frame gives nearly, not exactly, the same response,
    # and a particle placed at its peak or a resampling count can differ)
    cfg = TrackerConfig(n_particles=60, seed=2, correlation_weight=0.0, correlation_particles=0.0)
    box = np.asarray(demo.groundtruth[0], dtype=float)

    def run(fr, b, c):
        t = Tracker(c)
        t.init(fr[0], b)
        return np.array([t.update(f).box for f in fr[1:]])

    small = run(frames, box, cfg)
    scaled = run(big, 2 * box, cfg.replace(frame_size=(W, H)))
    np.testing.assert_allclose(scaled, 2 * small, rtol=1e-12)


def test_mean_estimate_is_the_likelihood_weighted_mean_state(demo):
    from smtmvt.geometry import affine_to_box

    # a flat likelihood (small alpha), so that the mean is not just the best particle
    t = Tracker(
        TrackerConfig(
            n_particles=80, seed=5, estimate="mean", alpha=1.0, report_aspect=0.0, report_scale=1.0, report_read_size=0
        )
    )
    t.init(demo.frames[0], demo.groundtruth[0])
    for f in demo.frames[1:4]:
        r, d = t.update_detailed(f)
        p = d.observation.likelihood[: len(d.particles)]
        mean_state = (p / p.sum()) @ d.particles
        np.testing.assert_allclose(r.box, affine_to_box(mean_state), rtol=1e-12)
        assert np.abs(np.asarray(r.box) - d.boxes[d.best]).max() > 0.01  # not the best particle


def test_nonnegative_bound_equals_scipy_nnls_and_bounds_every_nonnegative_code():
    from scipy.optimize import nnls

    from smtmvt.solvers.bounds import NNLS_MARGIN, nonnegative_residuals

    X, D = make_instance(35, K=3, N=6, n=9)
    bound = nonnegative_residuals(X, D)
    ref = np.zeros(9)
    for Xk, Dk in zip(X, D):
        for i in range(9):
            ref[i] += nnls(Dk, Xk[:, i])[1] ** 2
    np.testing.assert_allclose(bound, ref - 3 * NNLS_MARGIN, rtol=0, atol=1e-12)
    assert np.all(bound >= least_squares_residuals(X, D))
    assert np.any(bound > least_squares_residuals(X, D) + 1e-3)  # strictly tighter here
    C, _ = _code(X, D)
    assert np.all(bound <= reconstruction_residual(X, D, C))
    rng = np.random.default_rng(1)
    for _ in range(20):
        assert np.all(bound <= reconstruction_residual(X, D, np.abs(rng.standard_normal(C.shape))))


def _fast_code(X, D):
    return solve_smtmvt(X, D, lam=0.1, gamma=0.25, tol=1e-6)


def _rule(bound, residual, alpha, eps, valid):
    """The coded set of the module docstring's rule, from the bounds and the first pass's residuals."""
    order = np.flatnonzero(valid)[np.argsort(bound[valid], kind="stable")]
    first, rest = order[:FIRST_PASS], order[FIRST_PASS:]
    best = residual[first].min()
    tail = np.cumsum(np.exp(-alpha * (bound[rest] - best))[::-1])[::-1]  # bounds skipped from each position on
    expected = np.zeros(len(bound), dtype=bool)
    expected[first] = True
    expected[rest[tail > eps]] = True
    return expected


def test_observe_codes_exactly_the_candidates_of_the_rule():
    """A case where the second pass codes some candidates and skips others (default eps 1e-3)."""
    from smtmvt.solvers.bounds import nonnegative_residuals

    X, D = make_instance(36, K=2, N=4, n=40)
    valid = np.ones(40, dtype=bool)
    valid[[3, 17]] = False
    stages = []

    @contextmanager
    def timed(stage):
        stages.append(stage)
        yield

    obs = observe(X, D, _fast_code, alpha=3.0, valid=valid.astype(int), timed=timed)  # integer flags work too
    np.testing.assert_array_equal(obs.bound, nonnegative_residuals(X, D))
    expected = _rule(obs.bound, obs.residual, 3.0, 1e-3, valid)
    np.testing.assert_array_equal(obs.coded, expected)
    assert 16 < obs.coded.sum() < 38 and not obs.coded[[3, 17]].any()
    assert set(stages) == {"likelihood", "solve"} and stages.count("solve") == 2  # two passes
    # codes, outliers and likelihoods of the coded candidates are the solver's; zero elsewhere
    idx = np.flatnonzero(obs.coded)
    C, E = _fast_code([x[:, idx] for x in X], D)
    np.testing.assert_allclose(obs.C[:, :, idx], C, atol=1e-12)
    assert not obs.C[:, :, ~obs.coded].any()
    for k in range(2):
        np.testing.assert_allclose(obs.E[k][:, idx], E[k], atol=1e-12)
        assert not obs.E[k][:, ~obs.coded].any()
    np.testing.assert_allclose(
        obs.likelihood[idx], np.exp(-3.0 * reconstruction_residual(X, D, obs.C)[idx]), rtol=1e-12
    )
    assert np.all(obs.likelihood[~obs.coded] == 0)


def test_observe_eps_zero_codes_every_valid_candidate_with_the_least_squares_bound():
    """Even where every other candidate's bound underflows against the best (alpha 1e4)."""
    X, D = make_instance(37, K=1, N=4, n=20)  # a single view works too
    valid = np.ones(20, dtype=bool)
    valid[5] = False
    obs = observe(X, D, _fast_code, alpha=1e4, valid=valid, eps=0.0)
    np.testing.assert_array_equal(obs.coded, valid)
    np.testing.assert_array_equal(obs.bound, least_squares_residuals(X, D))
    assert obs.likelihood[5] == 0 and np.isnan(obs.residual[5])


def test_observe_an_invalid_probe_does_not_set_the_best_likelihood():
    """A probe (always, not valid) reconstructed exactly must not lower the best residual of the rule."""
    X, D = make_instance(36, K=2, N=4, n=40)
    X = [np.column_stack([Xk, Dk @ np.array([0.3, 0.2, 0.0, 0.1])]) for Xk, Dk in zip(X, D)]  # residual ~0
    valid = np.r_[np.ones(40, dtype=bool), False]
    obs = observe(X, D, _fast_code, alpha=3.0, valid=valid, always=~valid)
    assert obs.coded[40] and obs.residual[40] < np.nanmin(obs.residual[:40])  # it would be the best
    np.testing.assert_array_equal(obs.coded[:40], observe([x[:, :40] for x in X], D, _fast_code, alpha=3.0).coded)


def test_bounds_are_computed_in_float64_from_float32_views_and_templates():
    """The tracker's templates are float32: the bounds are those of the float64 copies."""
    from smtmvt.solvers.bounds import nonnegative_residuals

    X, D = make_instance(38, K=2, N=5, n=6)
    X32, D32 = [x.astype(np.float32) for x in X], [d.astype(np.float32) for d in D]
    X64, D64 = [x.astype(np.float64) for x in X32], [d.astype(np.float64) for d in D32]
    np.testing.assert_allclose(least_squares_residuals(X32, D32), least_squares_residuals(X64, D64), rtol=0, atol=1e-12)
    np.testing.assert_allclose(nonnegative_residuals(X32, D32), nonnegative_residuals(X64, D64), rtol=0, atol=1e-12)
    # a sum over the views: a single view works, and two single views add up to both
    one_by_one = nonnegative_residuals(X[:1], D[:1]) + nonnegative_residuals(X[1:], D[1:])
    # (up to the margins: each value is lowered by NNLS_MARGIN per view, or is the least-squares bound)
    np.testing.assert_allclose(one_by_one, nonnegative_residuals(X, D), rtol=0, atol=2e-9)


def test_range_basis_rank_is_relative_to_the_largest_singular_value():
    rng = np.random.default_rng(39)
    u, v2, v3, w = (rng.standard_normal(12) for _ in range(4))
    # singular values about 1e6, 4, 3 and 1e-5 (relative 1e-11 < rtol 1e-10: dropped)
    D = np.column_stack([1e6 * u, v2, v3, v2 + 1e-5 * w])
    assert range_basis(D).shape == (12, 3)
    assert range_basis(1e-8 * D).shape == (12, 3)  # scale-free
    # a zero dictionary has an empty range: the bound is ||x||^2; so has one without templates
    X = [rng.standard_normal((12, 3))]
    assert range_basis(np.zeros((12, 4))).shape == (12, 0) and range_basis(np.zeros((12, 0))).shape == (12, 0)
    np.testing.assert_allclose(least_squares_residuals(X, [np.zeros((12, 4))]), (X[0] ** 2).sum(axis=0), rtol=1e-14)


def test_tracker_keeps_the_range_bases_of_its_current_templates(demo):
    """The bases the tracker keeps between frames are those of its dictionaries as they
    are, also after template replacements (the demo replaces some)."""
    from smtmvt.solvers.bounds import range_basis

    t = Tracker(TrackerConfig(n_particles=60, seed=2))
    t.init(demo.frames[0], demo.groundtruth[0])
    replaced = 0
    for frame in demo.frames[1:40]:
        replaced += t.update(frame).template_replaced is not None
        if t._sparse.bases is not None:
            for Q, Dk in zip(t._sparse.bases, t._sparse.templates.dictionaries):
                np.testing.assert_array_equal(Q, range_basis(Dk))
    assert replaced >= 2
