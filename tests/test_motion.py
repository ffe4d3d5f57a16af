"""Random walk and resampling of the particle filter."""

import numpy as np
import pytest

from smtmvt.geometry import affine_scale, box_to_affine
from smtmvt.motion import place, propagate, resample


def test_propagate_statistics_scale_with_target():
    rng = np.random.default_rng(0)
    std = (0.01, 0.0005, 0.0005, 0.01, 4.0, 4.0)
    for box in [(100, 100, 32, 32), (100, 100, 128, 128)]:
        p0 = np.repeat(box_to_affine(box)[None], 20000, axis=0)
        p1 = propagate(p0, std, rng)
        sc = affine_scale(p0[:1])[0]
        # Translation std is std[4] * sc pixels.
        assert np.std(p1[:, 4] - p0[:, 4]) == pytest.approx(4.0 * sc, rel=0.03)
        # Diagonal terms perturbed in log space: relative change std 1%.
        assert np.std(np.log(p1[:, 0] / p0[:, 0])) == pytest.approx(0.01, rel=0.03)
        assert np.all(p1[:, 0] > 0) and np.all(p1[:, 3] > 0)


def test_propagate_is_seeded():
    p0 = np.repeat(box_to_affine((5, 5, 20, 20))[None], 10, axis=0)
    a = propagate(p0, (0.01, 0, 0, 0.01, 4, 4), np.random.default_rng(3))
    b = propagate(p0, (0.01, 0, 0, 0.01, 4, 4), np.random.default_rng(3))
    np.testing.assert_array_equal(a, b)


def test_resample_proportional_and_padded_with_best():
    p = np.arange(4 * 6, dtype=float).reshape(4, 6)
    out = resample(p, [0.0, 0.5, 0.3, 0.2], 10)
    ids = out[:, 0] / 6
    counts = np.bincount(ids.astype(int), minlength=4)
    assert counts.tolist() == [0, 5, 3, 2]
    out = resample(p, [0.0, 0.34, 0.33, 0.33], 10)  # floor -> 3+3+3, 1 slot for the best
    assert np.bincount((out[:, 0] / 6).astype(int), minlength=4).tolist() == [0, 4, 3, 3]


def test_resample_all_zero_or_nan_weights_collapse_to_one_particle():
    p = np.arange(3 * 6, dtype=float).reshape(3, 6)
    out = resample(p, [0.0, np.nan, 0.0], 5)
    assert out.shape == (5, 6) and np.all(out == out[0])


def test_propagate_shift_moves_every_particle_before_the_noise():
    p0 = np.repeat(box_to_affine((5, 5, 20, 20))[None], 7, axis=0)
    rng_a, rng_b = np.random.default_rng(4), np.random.default_rng(4)
    moved = propagate(p0, (0.01, 0, 0, 0.01, 4, 4), rng_a, shift=(3.0, -2.0))
    still = propagate(p0, (0.01, 0, 0, 0.01, 4, 4), rng_b)
    np.testing.assert_allclose(moved[:, 4:] - still[:, 4:], np.tile([3.0, -2.0], (7, 1)), atol=1e-12)
    np.testing.assert_array_equal(moved[:, :4], still[:, :4])


def test_propagate_spread_scales_each_particles_noise():
    p0 = np.repeat(box_to_affine((50, 50, 32, 32))[None], 20000, axis=0)
    spread = np.r_[np.full(10000, 0.25), np.ones(10000)]
    p1 = propagate(p0, (0.01, 0, 0, 0.01, 4.0, 4.0), np.random.default_rng(5), spread=spread)
    dx = p1[:, 4] - p0[:, 4]
    assert np.std(dx[:10000]) == pytest.approx(1.0, rel=0.03)
    assert np.std(dx[10000:]) == pytest.approx(4.0, rel=0.03)


def test_translation_power_half_grows_the_search_as_the_root_of_the_size():
    rng = np.random.default_rng(6)
    p0 = np.repeat(box_to_affine((100, 100, 128, 128))[None], 20000, axis=0)
    sc = affine_scale(p0[:1])[0]  # 4
    p1 = propagate(p0, (0, 0, 0, 0, 4.0, 4.0), rng, translation_power=0.5)
    assert np.std(p1[:, 4] - p0[:, 4]) == pytest.approx(4.0 * np.sqrt(sc), rel=0.03)


def test_pull_shape_moves_aspect_and_skew_only():
    from smtmvt.geometry import affine_to_box, box_to_affine
    from smtmvt.motion import pull_shape

    ref = box_to_affine(np.array([10.0, 10.0, 30.0, 60.0]))
    ref[1], ref[2] = 0.02, -0.01
    rng = np.random.default_rng(3)
    states = propagate(np.repeat(ref[None], 30, axis=0), [0.2, 0.05, 0.05, 0.2, 5.0, 5.0], rng)
    np.testing.assert_array_equal(pull_shape(states, ref, 0.0), states)
    for strength in (0.25, 1.0):
        pulled = pull_shape(states, ref, strength)
        # position and scale a11 * a22 are kept
        np.testing.assert_allclose(pulled[:, 4:], states[:, 4:])
        np.testing.assert_allclose(pulled[:, 0] * pulled[:, 3], states[:, 0] * states[:, 3])
        # the log-aspect and the skew move the given fraction of the way to the reference's
        r, r_ref, r_new = (0.5 * np.log(p[..., 3] / p[..., 0]) for p in (states, ref, pulled))
        np.testing.assert_allclose(r_new - r, strength * (r_ref - r), atol=1e-12)
        np.testing.assert_allclose(pulled[:, 1:3] - states[:, 1:3], strength * (ref[1:3] - states[:, 1:3]), atol=1e-15)
    full = affine_to_box(pull_shape(states, ref, 1.0))
    np.testing.assert_allclose(full[:, 3] / full[:, 2], 2.0, rtol=1e-3)  # the reference's 60 / 30


def test_aspect_std_moves_scale_and_aspect_by_their_own_deviations():
    p0 = np.repeat(box_to_affine((100, 100, 40, 80))[None], 40000, axis=0)
    std = (0.01, 0.0, 0.0, 0.01, 4.0, 4.0)
    for aspect in (0.004, 0.02):
        p1 = propagate(p0, std, np.random.default_rng(7), aspect_std=aspect)
        log_scale = 0.5 * np.log(p1[:, 0] * p1[:, 3] / (p0[:, 0] * p0[:, 3]))
        log_aspect = np.log((p1[:, 3] / p1[:, 0]) / (p0[:, 3] / p0[:, 0]))
        assert np.std(log_scale) == pytest.approx(0.01, rel=0.03)
        assert np.std(log_aspect) == pytest.approx(aspect, rel=0.03)
        assert abs(np.corrcoef(log_scale, log_aspect)[0, 1]) < 0.03
    # without it the axes move independently: the aspect twice as much as the scale
    p1 = propagate(p0, std, np.random.default_rng(7))
    log_scale = 0.5 * np.log(p1[:, 0] * p1[:, 3] / (p0[:, 0] * p0[:, 3]))
    log_aspect = np.log((p1[:, 3] / p1[:, 0]) / (p0[:, 3] / p0[:, 0]))
    assert np.std(log_scale) == pytest.approx(0.01 / np.sqrt(2), rel=0.03)
    assert np.std(log_aspect) == pytest.approx(0.01 * np.sqrt(2), rel=0.03)


def test_aspect_std_zero_keeps_the_aspect_and_the_random_stream():
    p0 = np.repeat(box_to_affine((10, 20, 30, 45))[None], 50, axis=0)
    std = (0.02, 0.0, 0.0, 0.02, 4.0, 4.0)
    fixed = propagate(p0, std, np.random.default_rng(8), aspect_std=0.0)
    np.testing.assert_allclose(fixed[:, 3] / fixed[:, 0], 1.5, rtol=1e-12)
    free = propagate(p0, std, np.random.default_rng(8))
    # the same draws: the translation is unchanged, only the shape noise is recombined
    np.testing.assert_array_equal(fixed[:, 4:], free[:, 4:])
    np.testing.assert_allclose(fixed[:, 0] / p0[:, 0], free[:, 0] / p0[:, 0], rtol=1e-12)


def test_translation_distance_is_in_standard_deviations():
    from smtmvt.motion import translation_distance

    states = np.array([[1.0, 0, 0, 1.0, 10.0, 20.0], [2.0, 0, 0, 2.0, 13.0, 16.0]])
    d = translation_distance(states, (10.0, 20.0), (3.0, 2.0))
    np.testing.assert_allclose(d, [0.0, (3 / 3) ** 2 + (4 / 2) ** 2])
    # a walk that does not move along x: only a state on the prediction is at a finite distance
    np.testing.assert_array_equal(translation_distance(states, (10.0, 20.0), (0.0, 2.0)), [0.0, np.inf])


def _first_frame_probes(cfg, probes_of):
    """Track the demo's first two frames with ``cfg`` and score ``probes_of(box)``
    (box: the first box, (4,) float64) on the second: ``(residuals, likelihoods)``
    of the probes."""
    from smtmvt import Tracker
    from smtmvt.demo import make_demo_sequence

    demo = make_demo_sequence(n_frames=2)
    t = Tracker(cfg)
    t.init(demo.frames[0], demo.groundtruth[0])
    box = np.asarray(demo.groundtruth[0], dtype=np.float64)
    _, detail = t.update_detailed(demo.frames[1], probes=probes_of(box))
    return detail.observation.residual[cfg.n_particles :], detail.probe_likelihood


def test_motion_term_weighs_each_candidate_by_the_random_walks_density():
    """On the first frame (no velocity yet) the prediction is the first box: a
    probe moved (dx, dy) pixels keeps its residual, and its likelihood falls by
    exp(-w d / 2), d = (dx^2 + dy^2) / (std * sc)^2."""
    from smtmvt import TrackerConfig
    from smtmvt.demo import make_demo_sequence

    box = np.asarray(make_demo_sequence(n_frames=1).groundtruth[0], dtype=np.float64)
    moves = np.array([[0.0, 0.0], [6.0, 0.0], [0.0, -9.0], [4.0, 5.0]])
    cfg = TrackerConfig(n_particles=50, seed=1)
    assert cfg.motion_weight == 1.0 and TrackerConfig.paper().motion_weight == 0.0

    def moved(b):
        return np.c_[b[:2] + moves, np.tile(b[2:], (len(moves), 1))]

    r0, p0 = _first_frame_probes(cfg.replace(motion_weight=0.0), moved)
    r2, p2 = _first_frame_probes(cfg.replace(motion_weight=2.0), moved)
    np.testing.assert_array_equal(r0, r2)
    sc = affine_scale(box_to_affine(box[None]))[0]
    d = (moves**2).sum(1) / (cfg.affine_std[4] * sc) ** 2
    assert d[1:].min() > 0.1  # the moves are a fair part of a standard deviation
    np.testing.assert_allclose(np.log(p2 / p0), -2.0 * d / 2, rtol=1e-9, atol=1e-12)
    with pytest.raises(ValueError, match="motion_weight"):
        TrackerConfig(motion_weight=-1.0)


def test_motion_term_weighs_each_particle_by_its_own_step():
    """A particle's motion term is the random walk's density of its own step,
    from its parent (on the first frame every parent is the first state, with
    no velocity yet): among the particles coded with and without the term, the
    residuals agree and the likelihoods differ by exp(-w d / 2)."""
    from smtmvt import Tracker, TrackerConfig
    from smtmvt.demo import make_demo_sequence

    demo = make_demo_sequence(n_frames=2)
    # only the walk's particles: those placed at the correlation filter's peak all take short steps
    cfg = TrackerConfig(n_particles=60, seed=1, correlation_particles=0.0)

    def first_frame(weight):
        t = Tracker(cfg.replace(motion_weight=weight))
        t.init(demo.frames[0], demo.groundtruth[0])
        return t.update_detailed(demo.frames[1])[1]

    plain, weighed = first_frame(0.0), first_frame(1.5)
    np.testing.assert_array_equal(plain.particles, weighed.particles)
    start = box_to_affine(np.asarray(demo.groundtruth[0], dtype=np.float64)[None])[0]
    d = (((weighed.particles[:, 4:] - start[4:]) / (cfg.affine_std[4] * affine_scale(start[None])[0])) ** 2).sum(1)
    both = plain.observation.coded & weighed.observation.coded
    assert both.sum() >= 5 and np.ptp(d[both]) > 0.2  # steps of different lengths
    np.testing.assert_array_equal(plain.observation.residual[both], weighed.observation.residual[both])
    ratio = weighed.observation.likelihood[both] / plain.observation.likelihood[both]
    np.testing.assert_allclose(np.log(ratio), -1.5 * d[both] / 2, rtol=1e-9, atol=1e-12)


def test_a_particles_step_is_its_own_random_draw():
    """After a frame (a velocity, resampled parents of several kinds) each
    particle's step from its own prediction, in standard deviations, is the
    standard normal pair the random walk drew for its translation."""
    from smtmvt import Tracker, TrackerConfig
    from smtmvt.demo import make_demo_sequence
    from smtmvt.motion import translation_distance

    demo = make_demo_sequence(n_frames=3)
    t = Tracker(TrackerConfig(n_particles=80, seed=2))
    t.init(demo.frames[0], demo.groundtruth[0])
    t.update(demo.frames[1])
    assert np.abs(t._motion.velocity).max() > 0.1  # the prediction is moved
    draws = np.random.Generator(type(t._rng.bit_generator)())
    draws.bit_generator.state = t._rng.bit_generator.state
    moved = t._propagate()
    noise = draws.standard_normal(moved.shape)
    np.testing.assert_allclose(translation_distance(moved, *t._motion.steps), (noise[:, 4:] ** 2).sum(1), rtol=1e-9)


def test_place_moves_the_last_states_about_the_point_and_keeps_their_shape():
    rng = np.random.default_rng(0)
    p = np.tile(box_to_affine(np.array([10.0, 20.0, 30.0, 40.0])), (2000, 1))
    p[:, 0] *= np.linspace(0.9, 1.1, 2000)
    out = place(p, 1500, (200.0, -50.0), (2.0, 5.0), rng)
    np.testing.assert_array_equal(out[:500], p[:500])
    np.testing.assert_array_equal(out[:, :4], p[:, :4])
    moved = out[500:, 4:]
    np.testing.assert_allclose(moved.mean(axis=0), (200.0, -50.0), atol=0.3)
    np.testing.assert_allclose(moved.std(axis=0), (2.0, 5.0), rtol=0.06)
    # the draws are the generator's next (count, 2) standard normals
    again = np.random.default_rng(0).standard_normal((1500, 2))
    np.testing.assert_allclose(moved, (200.0, -50.0) + again * (2.0, 5.0), rtol=1e-12)
    # nothing placed: the same states, no draw
    state = rng.bit_generator.state
    np.testing.assert_array_equal(place(p, 0, (0.0, 0.0), (1.0, 1.0), rng), p)
    assert rng.bit_generator.state == state
    with pytest.raises(ValueError, match="count 2001"):
        place(p, 2001, (0.0, 0.0), (1.0, 1.0), rng)


def test_scale_term_favours_the_larger_of_two_candidates_by_their_size_ratio():
    """With ``scale_push`` b each candidate's residual gains -b log(s_i / s), s
    the last state's size sqrt(w h): probes about the first box's centre,
    grown or shrunk, keep their coded residual and their likelihood changes by
    exp(alpha b log(s_i / s)); 0 (the default) adds nothing; a negative
    weight is refused."""
    from smtmvt import TrackerConfig

    factors = np.array([0.8, 0.95, 1.0, 1.1, 1.25])
    cfg = TrackerConfig(n_particles=50, seed=1)
    assert cfg.scale_push == 0.0

    def resized(b):
        centre = b[:2] + b[2:] / 2
        return np.array([[*(centre - b[2:] * f / 2), *(b[2:] * f)] for f in factors])

    r0, p0 = _first_frame_probes(cfg, resized)
    r1, p1 = _first_frame_probes(cfg.replace(scale_push=0.3), resized)
    np.testing.assert_array_equal(r0, r1)
    assert np.all(p0 > 0)
    np.testing.assert_allclose(np.log(p1 / p0), cfg.alpha * 0.3 * np.log(factors), rtol=1e-6, atol=1e-9)
    with pytest.raises(ValueError, match="scale_push"):
        TrackerConfig(scale_push=-0.1)
