"""A strong start (issue 48 item 4): the first filter and templates learned from
perturbed copies of the first box (``correlation_augment``, ``template_augment``)."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.correlation import (
    AUGMENT_COPIES,
    AUGMENT_SPREAD,
    CELL,
    CorrelationFilter,
    augment_warps,
    augmented_features,
    respond,
    train,
    window_at,
    window_features,
    window_shape,
)
from smtmvt.cues.sparse import template_states
from smtmvt.demo import make_demo_sequence
from smtmvt.geometry import box_to_affine


def _texture(h=240, w=320, seed=0):
    rng = np.random.default_rng(seed)
    img = cv2.GaussianBlur(rng.random((h, w)).astype(np.float32), (0, 0), 2.0)
    return (img - img.min()) / (img.max() - img.min())


def test_warps_are_small_and_determined_by_the_seed():
    w = augment_warps(AUGMENT_COPIES, 3)
    assert w.shape == (AUGMENT_COPIES, 2, 2) and w.dtype == np.float64
    np.testing.assert_array_equal(w, augment_warps(AUGMENT_COPIES, 3))
    assert not np.allclose(w, augment_warps(AUGMENT_COPIES, 4))
    # a rotation of at most 0.1 rad plus at most 0.1 per entry: within sin(0.1) + 0.1 of the identity
    assert np.abs(w - np.eye(2)).max() <= np.sin(AUGMENT_SPREAD) + AUGMENT_SPREAD + 1e-12
    assert np.abs(w - np.eye(2)).max() > 0.01  # and not the identity


def test_augmented_features_of_the_identity_are_the_windows():
    img, box = _texture(), np.array([120.0, 90.0, 48.0, 36.0])
    size = window_shape(box)
    win = window_at((box[0] + (box[2] - 1) / 2, box[1] + (box[3] - 1) / 2), box[2:], size)
    feats = augmented_features(img, win, np.stack([np.eye(2), augment_warps(1, 0)[0]]))
    assert feats.shape == (2, 10, size[0] // CELL, size[1] // CELL) and feats.dtype == np.float32
    np.testing.assert_allclose(feats[0], window_features(img, win), atol=1e-6)
    assert not np.allclose(feats[1], feats[0], atol=1e-3)


def test_train_on_samples_is_the_mean_of_their_filters():
    rng = np.random.default_rng(0)
    f = rng.random((3, 10, 8, 6))
    label = rng.random((8, 6))
    many = train(f, label)
    each = [train(x, label) for x in f]
    np.testing.assert_allclose(many.A, np.mean([m.A for m in each], axis=0))
    np.testing.assert_allclose(many.B, np.mean([m.B for m in each], axis=0))


def test_augmented_filter_is_determined_by_its_seed_and_still_peaks_on_the_target():
    img, box = _texture(), np.array([120.0, 90.0, 48.0, 36.0])
    plain = CorrelationFilter(img, box)
    a = CorrelationFilter(img, box, AUGMENT_COPIES, 5)
    np.testing.assert_array_equal(a.model.A, CorrelationFilter(img, box, AUGMENT_COPIES, 5).model.A)
    assert not np.allclose(a.model.A, plain.model.A)
    assert a.first is a.model
    r, _ = a.response(img, box)
    h, w = r.shape
    assert np.unravel_index(np.argmax(r), r.shape) == ((h - 1) // 2, (w - 1) // 2)
    # 0 copies: the filter of the first window alone
    np.testing.assert_array_equal(CorrelationFilter(img, box, 0, 5).model.A, plain.model.A)
    assert respond(plain.model, window_features(img, plain._window(box))).shape == r.shape


@pytest.fixture(scope="module")
def demo():
    return make_demo_sequence(n_frames=8)


@pytest.mark.parametrize("augment", [False, True])
def test_template_0_stays_the_exact_first_box(augment):
    state = box_to_affine(np.array([10.0, 20.0, 30.0, 40.0]))
    s = template_states(state, 10, 7, augment)
    assert s.shape == (10, 6)
    np.testing.assert_array_equal(s[0], state)
    np.testing.assert_array_equal(s, template_states(state, 10, 7, augment))  # the seed decides
    assert not np.allclose(s[1:], template_states(state, 10, 8, augment)[1:])
    assert len({tuple(r) for r in s.round(9)}) == 10  # all different


def test_augmented_templates_are_warps_about_the_centre():
    state = box_to_affine(np.array([10.0, 20.0, 30.0, 40.0]))
    s = template_states(state, 10, 7, True)
    np.testing.assert_array_equal(s[:, 4:], np.tile(state[4:], (10, 1)))  # the centre kept
    warps = augment_warps(9, 8)  # seed + 1
    np.testing.assert_allclose(s[1:, :4].reshape(9, 2, 2), warps @ state[:4].reshape(2, 2))
    # without the option, the L1-APG corner jitter: an axis-aligned state
    plain = template_states(state, 10, 7, False)
    np.testing.assert_array_equal(plain[:, [1, 2]], 0.0)


def test_the_options_are_off_by_default_and_change_the_start(demo):
    assert not TrackerConfig().correlation_augment and not TrackerConfig().template_augment
    assert not TrackerConfig.paper().correlation_augment and not TrackerConfig.paper().template_augment
    boxes = {}
    for name, opts in (("off", {}), ("corr", {"correlation_augment": True}), ("tmpl", {"template_augment": True})):
        t = Tracker(TrackerConfig(n_particles=60, seed=0, **opts))
        t.init(demo.frames[0], demo.groundtruth[0])
        boxes[name] = [t.update(f).box for f in demo.frames[1:4]]
    assert boxes["corr"] != boxes["off"] and boxes["tmpl"] != boxes["off"]
