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
    c = np.zeros((2, 4)); c[:, 2] = 1.0
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
    c = np.zeros((2, 4)); c[:, 1] = 0.5
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
    c = np.zeros((2, 4)); c[:, 1] = 0.2
    occluded_e = [np.r_[1.0, 1.0, 0, 0, 0, 0], np.zeros(6)]  # 2/6 > 0.25 of the intensity view
    d = ts.update([far, far], c, occluded_e, update_angle=30, occlusion_fraction=0.25)
    assert d.occluded and d.replaced is None
    clean = [np.zeros(6), np.zeros(6)]
    for _ in range(4):
        assert ts.update([far, far], c, clean, update_angle=30, occlusion_fraction=0.25).replaced is None
    assert ts.update([far, far], c, clean, update_angle=30, occlusion_fraction=0.25).replaced is not None


def test_anchor_check_blocks_a_replacement_far_from_the_first_template():
    far = _unit(np.r_[1.0, -1.0, 1.0, -1.0, 1.0, -1.0]).astype(np.float32)
    c = np.zeros((2, 4)); c[:, 1] = 0.2
    e = [np.zeros(6), np.zeros(6)]
    ts = _templates()
    cos0 = float(np.dot(far, ts.dictionaries[0][:, 0]))
    blocked = ts.update([far, far], c, e, update_angle=30, occlusion_fraction=0.25, anchor_cos=cos0 + 0.01)
    assert blocked.angle > 30 and blocked.replaced is None
    ts = _templates()
    allowed = ts.update([far, far], c, e, update_angle=30, occlusion_fraction=0.25, anchor_cos=cos0 - 0.01)
    assert allowed.replaced is not None
