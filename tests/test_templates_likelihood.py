"""Template update rule and likelihood."""

import numpy as np
import pytest

from smtmvt.likelihood import likelihoods
from smtmvt.templates import TemplateSet


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v)


def _templates(N=4, d=6, seed=0):
    rng = np.random.default_rng(seed)
    D = rng.normal(size=(d, N))
    D /= np.linalg.norm(D, axis=0)
    return TemplateSet([D.astype(np.float32).copy(), D.astype(np.float32).copy()])


def test_likelihood_formula_and_invalid():
    r = np.array([0.0, 0.1, np.nan, 0.2])
    p = likelihoods(r, 30.0, valid=[True, True, True, False])
    np.testing.assert_allclose(p, [1.0, np.exp(-3.0), 0.0, 0.0])


def test_similar_candidate_does_not_replace():
    ts = _templates()
    x = [ts.dictionaries[0][:, 2].copy(), ts.dictionaries[1][:, 2].copy()]
    c = np.zeros((2, 4))
    c[:, 2] = 1.0
    e = [np.zeros(6), np.zeros(6)]
    d = ts.update(x, c, e, update_angle=30, occlusion_fraction=0.25)
    assert d.replaced is None and d.angle == pytest.approx(0.0, abs=1e-3)
    # Importance grows for the template that explained the candidate.
    assert np.argmax(ts.weights) == 2


def test_dissimilar_candidate_replaces_least_important_never_first():
    ts = _templates()
    ts.weights = np.array([0.01, 0.5, 0.09, 0.4])
    D0 = ts.dictionaries[0].copy()
    x_new = _unit(D0[:, 1] + 1.5 * _unit(np.arange(6.0)))
    x = [x_new.astype(np.float32), x_new.astype(np.float32)]
    c = np.zeros((2, 4))
    c[:, 1] = 0.5
    e = [np.zeros(6), np.zeros(6)]
    d = ts.update(x, c, e, update_angle=30, occlusion_fraction=0.25)
    assert d.angle > 30
    assert d.replaced == 2  # least weight among templates 1..N-1 (template 0 has less but is fixed)
    np.testing.assert_allclose(ts.dictionaries[0][:, 2], x_new, atol=1e-6)
    np.testing.assert_array_equal(ts.dictionaries[0][:, 0], D0[:, 0])
    assert ts.weights.sum() == pytest.approx(1.0)


def test_occlusion_suspends_updates_for_five_frames():
    ts = _templates()
    far = _unit(np.ones(6)).astype(np.float32)
    c = np.zeros((2, 4))
    c[:, 1] = 0.2
    occluded_e = [np.r_[1.0, 1.0, 0, 0, 0, 0], np.zeros(6)]  # 2/6 > 0.25 of the intensity view
    d = ts.update([far, far], c, occluded_e, update_angle=30, occlusion_fraction=0.25)
    assert d.occluded and d.replaced is None
    clean = [np.zeros(6), np.zeros(6)]
    for _ in range(4):
        assert ts.update([far, far], c, clean, update_angle=30, occlusion_fraction=0.25).replaced is None
    assert ts.update([far, far], c, clean, update_angle=30, occlusion_fraction=0.25).replaced is not None


def test_anchor_check_blocks_a_replacement_far_from_the_first_template():
    far = _unit(np.r_[1.0, -1.0, 1.0, -1.0, 1.0, -1.0]).astype(np.float32)
    c = np.zeros((2, 4))
    c[:, 1] = 0.2
    e = [np.zeros(6), np.zeros(6)]
    ts = _templates()
    cos0 = float(np.dot(far, ts.dictionaries[0][:, 0]))
    blocked = ts.update([far, far], c, e, update_angle=30, occlusion_fraction=0.25, anchor_cos=cos0 + 0.01)
    assert blocked.angle > 30 and blocked.replaced is None
    ts = _templates()
    allowed = ts.update([far, far], c, e, update_angle=30, occlusion_fraction=0.25, anchor_cos=cos0 - 0.01)
    assert allowed.replaced is not None


def test_weights_after_an_update_computed_by_hand():
    """L1T: w <- w exp(mean_k c_k), normalized; the replaced template gets the median weight."""
    ts = _templates()
    w0 = np.array([0.1, 0.2, 0.3, 0.4])
    ts.weights = w0.copy()
    c = np.array([[0.2, 0.0, 0.6, 0.1], [0.4, 0.2, 0.2, 0.1]])  # views x templates
    x = [ts.dictionaries[0][:, 2].copy(), ts.dictionaries[1][:, 2].copy()]  # equal to template 2: no replacement
    e = [np.zeros(6), np.zeros(6)]
    d = ts.update(x, c, e, update_angle=30, occlusion_fraction=0.25)
    w = w0 * np.exp(c.mean(axis=0))
    w /= w.sum()
    assert d.replaced is None
    np.testing.assert_allclose(ts.weights, w, rtol=1e-12)

    # now a candidate far from every template: the lightest of templates 1..3 is replaced
    far = _unit(np.r_[1.0, -1.0, 1.0, -1.0, 1.0, -1.0]).astype(np.float32)
    d = ts.update([far, far], c, e, update_angle=30, occlusion_fraction=0.25)
    w = w * np.exp(c.mean(axis=0))
    w /= w.sum()
    j = 1 + int(np.argmin(w[1:]))
    assert d.replaced == j
    w[j] = np.median(w)
    np.testing.assert_allclose(ts.weights, w / w.sum(), rtol=1e-12)


def test_the_template_compared_is_the_largest_coefficient_not_the_heaviest():
    ts = _templates()
    ts.weights = np.array([0.1, 0.6, 0.2, 0.1])  # template 1 is the heaviest
    c = np.zeros((2, 4))
    c[:, 2] = 0.9  # template 2 has the largest coefficient
    x = [ts.dictionaries[0][:, 2].copy(), ts.dictionaries[1][:, 2].copy()]
    d = ts.update(x, c, [np.zeros(6), np.zeros(6)], update_angle=30, occlusion_fraction=0.25)
    assert d.angle == pytest.approx(0.0, abs=1e-3)  # measured against template 2, identical
    assert d.replaced is None
    # against the heaviest template the angle would exceed the threshold
    cos1 = float(np.dot(x[0], ts.dictionaries[0][:, 1]))
    assert np.degrees(np.arccos(np.clip(cos1, -1, 1))) > 30


def test_an_occlusion_fraction_equal_to_the_threshold_is_not_an_occlusion():
    ts = _templates(d=8)
    far = _unit(np.r_[1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0]).astype(np.float32)
    c = np.zeros((2, 4))
    c[:, 1] = 0.2
    at_threshold = [np.r_[1.0, 1.0, 0, 0, 0, 0, 0, 0], np.zeros(8)]  # exactly 2/8 = 0.25
    d = ts.update([far, far], c, at_threshold, update_angle=30, occlusion_fraction=0.25)
    assert d.occlusion == 0.25 and not d.occluded and d.replaced is not None
    above = [np.r_[1.0, 1.0, 1.0, 0, 0, 0, 0, 0], np.zeros(8)]
    d = _templates(d=8).update([far, far], c, above, update_angle=30, occlusion_fraction=0.25)
    assert d.occluded and d.replaced is None


def test_fixed_templates_are_never_replaced():
    ts = _templates()
    ts.weights = np.array([0.1, 0.05, 0.15, 0.7])  # template 1 is the lightest, but fixed
    D0 = [Dk.copy() for Dk in ts.dictionaries]
    far = _unit(np.r_[1.0, -1.0, 1.0, -1.0, 1.0, -1.0]).astype(np.float32)
    c = np.zeros((2, 4))
    c[:, 3] = 0.1
    d = ts.update([far, far], c, [np.zeros(6), np.zeros(6)], update_angle=30, occlusion_fraction=0.25, fixed=2)
    assert d.replaced == 2
    np.testing.assert_array_equal(ts.dictionaries[0][:, :2], D0[0][:, :2])


def test_initial_weights_are_uniform_and_sum_to_one():
    ts = _templates(N=5)
    np.testing.assert_allclose(ts.weights, np.full(5, 0.2), rtol=1e-15)


def test_weights_are_computed_in_float64_whatever_the_codes_dtype():
    ts, ref = _templates(), _templates()
    c = np.array([[0.2, 0.0, 0.6, 0.1], [0.4, 0.2, 0.2, 0.1]])
    x = [ts.dictionaries[0][:, 2].copy(), ts.dictionaries[1][:, 2].copy()]
    e = [np.zeros(6), np.zeros(6)]
    ts.update(x, c.astype(np.float32), e, update_angle=30, occlusion_fraction=0.25)
    ref.update(x, c.astype(np.float32).astype(np.float64), e, update_angle=30, occlusion_fraction=0.25)
    np.testing.assert_allclose(ts.weights, ref.weights, rtol=1e-15)


@pytest.mark.parametrize("code", [-1000.0, 1000.0])
def test_extreme_codes_keep_the_weights_finite(code):
    """exp(mean c) is clipped: codes far outside any real range neither underflow all weights to 0 nor overflow."""
    ts = _templates()
    w0 = np.array([0.1, 0.2, 0.3, 0.4])
    ts.weights = w0.copy()
    c = np.zeros((2, 4))
    c[:, 1] = code
    if code < 0:
        c[:] = code  # every template: all of them would underflow to 0
    x = [ts.dictionaries[0][:, 1].copy(), ts.dictionaries[1][:, 1].copy()]
    ts.update(x, c, [np.zeros(6), np.zeros(6)], update_angle=180, occlusion_fraction=0.25)  # no replacement
    assert np.all(np.isfinite(ts.weights)) and ts.weights.sum() == pytest.approx(1.0)
    clipped = w0 * np.exp(np.clip(c.mean(axis=0), -50, 50))
    np.testing.assert_allclose(ts.weights, clipped / clipped.sum(), rtol=1e-12)


def test_without_an_intensity_view_occlusion_and_angle_use_every_view():
    ts = _templates()
    D = [Dk.astype(np.float64) for Dk in ts.dictionaries]
    c = np.zeros((2, 4))
    c[:, 3] = 0.5  # j* = 3
    x = [_unit(D[0][:, 3] + 0.3 * D[0][:, 1]), _unit(D[1][:, 3] + 2.0 * D[1][:, 2])]
    e = [np.r_[0.5, 0, 0, 0, 0, 0], np.r_[0, -0.5, 0.25, 0, 0, 0]]  # 3 of 12 entries non-zero, all |e| < 1
    d = ts.update(x, c, e, update_angle=90, occlusion_fraction=0.5, intensity_view=None)
    assert d.occlusion == pytest.approx(3 / 12, abs=1e-15)
    cos = np.mean([np.dot(x[0], D[0][:, 3]), np.dot(x[1], D[1][:, 3])])
    assert d.angle == pytest.approx(np.degrees(np.arccos(cos)), abs=1e-4)
    # with intensity view 0, the angle and occlusion are view 0's only
    d0 = _templates().update(x, c, e, update_angle=90, occlusion_fraction=0.5, intensity_view=0)
    assert d0.occlusion == pytest.approx(1 / 6, abs=1e-15)
    assert d0.angle == pytest.approx(np.degrees(np.arccos(np.dot(x[0], D[0][:, 3]))), abs=1e-4)
    assert abs(d0.angle - d.angle) > 5  # the two rules differ here


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_a_cosine_rounded_past_one_gives_a_finite_angle(sign):
    """Views are normalized, but rounding can put a cosine just outside [-1, 1]: the angle is then 0 or 180.

    The candidate is (minus) template 0 scaled by 1 + 1e-5, so its cosines with template 0 are
    +-(1 + 1e-5). The opposite one is replaced: the default anchor_cos -1 checks nothing, even a
    cosine below -1.
    """
    ts = _templates()
    w0 = ts.weights.copy()
    c = np.zeros((2, 4))
    c[:, 0] = 0.5  # j* = 0
    x = [sign * (1 + 1e-5) * Dk[:, 0].astype(np.float64) for Dk in ts.dictionaries]
    d = ts.update(x, c, [np.zeros(6), np.zeros(6)], update_angle=30, occlusion_fraction=0.25)
    assert d.angle == (0.0 if sign > 0 else 180.0)
    w = w0 * np.exp(c.mean(axis=0))
    assert d.replaced == (None if sign > 0 else 1 + int(np.argmin(w[1:])))


def test_thresholds_are_strict_for_the_angle_and_inclusive_for_the_anchor():
    """Replacement needs angle > update_angle (equal: kept) and anchor cosine >= anchor_cos (equal: replaced)."""
    far = _unit(np.r_[1.0, -1.0, 1.0, -1.0, 1.0, -1.0]).astype(np.float32)
    c = np.zeros((2, 4))
    c[:, 1] = 0.2
    e = [np.zeros(6), np.zeros(6)]
    angle = _templates().update([far, far], c, e, update_angle=30, occlusion_fraction=0.25).angle
    assert angle > 30
    assert _templates().update([far, far], c, e, update_angle=angle, occlusion_fraction=0.25).replaced is None
    ts = _templates()
    cos0 = float(np.mean([float(np.dot(far, Dk[:, 0])) for Dk in ts.dictionaries]))  # as update computes it
    d = ts.update([far, far], c, e, update_angle=30, occlusion_fraction=0.25, anchor_cos=cos0)
    assert d.replaced is not None


def test_when_every_template_is_fixed_none_is_replaced():
    ts = _templates()
    D0 = [Dk.copy() for Dk in ts.dictionaries]
    far = _unit(np.r_[1.0, -1.0, 1.0, -1.0, 1.0, -1.0]).astype(np.float32)
    c = np.zeros((2, 4))
    c[:, 1] = 0.2
    d = ts.update([far, far], c, [np.zeros(6), np.zeros(6)], update_angle=30, occlusion_fraction=0.25, fixed=4)
    assert d.angle > 30 and d.replaced is None
    for Dk, D0k in zip(ts.dictionaries, D0):
        np.testing.assert_array_equal(Dk, D0k)


@pytest.mark.parametrize("margin", [4.0, 200.0])
def test_update_margin_sets_the_trigger_from_the_first_frames_angles(monkeypatch, margin):
    """With ``update_margin`` the rule is given ``update_angle`` on the first 10
    frames, then the median of their angles plus the margin, or
    ``update_angle`` where that is lower."""
    from smtmvt import Tracker, TrackerConfig
    from smtmvt.demo import make_demo_sequence

    calls = []  # (trigger given, angle measured) per frame
    update = TemplateSet.update

    def spy(self, *args, **kwargs):
        decision = update(self, *args, **kwargs)
        calls.append((kwargs["update_angle"], decision.angle))
        return decision

    monkeypatch.setattr(TemplateSet, "update", spy)
    # the first 14 frames of the 40-frame demo (its scale change), which the tracker
    # follows (overlap 0.93 falling to 0.46 as the target grows): the first 10 angles'
    # median is 52, below update_angle - 4 = 56, so that margin 4 takes the other branch
    # than 200. In the 14-frame demo, every event in these frames, 60 particles lose the
    # target from frame 2 and the angles depend on where the box wanders: with the
    # correlation term against its usual peak (docs/experiments.md#n47) their median is 67
    demo = make_demo_sequence(n_frames=40)
    frames = demo.frames[:14]
    # without the template gate, which gives an infinite trigger on the frames it refuses
    cfg = TrackerConfig(n_particles=60, seed=0, update_margin=margin, template_learn_gate=(0.0, 0.0))
    assert TrackerConfig().update_margin is None and TrackerConfig.paper().update_margin is None
    t = Tracker(cfg)
    t.init(frames[0], demo.groundtruth[0])
    for frame in frames[1:]:
        t.update(frame)
    triggers, angles = np.array(calls).T
    np.testing.assert_array_equal(triggers[:10], cfg.update_angle)
    expected = min(cfg.update_angle, float(np.median(angles[:10])) + margin)
    assert expected < cfg.update_angle if margin == 4.0 else expected == cfg.update_angle
    np.testing.assert_array_equal(triggers[10:], expected)
    with pytest.raises(ValueError, match="update_margin"):
        TrackerConfig(update_margin=-1.0)
