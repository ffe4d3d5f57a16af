"""Cue reliability (smtmvt.reliability): the agreement, its running mean, and the tracker with it on."""

import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.demo import make_demo_sequence
from smtmvt.reliability import Reliability, Scaled, agreement


def test_agreement_is_the_share_of_other_candidates_the_cue_finds_worse():
    cost = np.array([0.5, 0.2, 0.9, 0.5, 0.7])
    assert agreement(cost, 1) == pytest.approx(1.0)
    assert agreement(cost, 2) == pytest.approx(0.0)
    assert agreement(cost, 4) == pytest.approx(1 / 4)
    # a tie counts half
    assert agreement(cost, 0) == pytest.approx((2 + 0.5) / 4)
    # it does not depend on the cue's weight
    assert agreement(7.0 * cost, 4) == agreement(cost, 4)
    # a flat cue cannot rank; a non-finite cost is worse than any, and none at the choice
    assert agreement(np.full(5, 2.0), 3) is None
    assert agreement(np.array([np.inf, 1.0, 2.0]), 2) == pytest.approx(0.5)
    assert agreement(np.array([np.inf, 1.0, 2.0]), 0) is None


def test_reliability_is_the_mean_agreement_above_chance_and_skips_cues_that_cannot_rank():
    rel = Reliability(3)
    np.testing.assert_array_equal(rel.factors(), [1.0, 1.0, 1.0])
    a, b = np.array([0.0, 1.0, 2.0]), np.array([2.0, 1.0, 0.0])
    rel.observe([a, b, None], 0)
    rel.observe([a, np.ones(3), None], 1)
    # cue 0: agreements 1 and 0.5, mean 0.75 -> 0.5; cue 1: 0 once -> 0; cue 2 never seen
    np.testing.assert_allclose(rel.factors(), [0.5, 0.0, 1.0])


def test_scaled_multiplies_the_late_view_cost_only_when_there_is_one():
    class Late:
        def view_cost(self, scene, k, view):
            return None if k == 0 else np.array([1.0, 2.0])

    assert Scaled(Late(), 0.5).view_cost(None, 0, None) is None
    np.testing.assert_array_equal(Scaled(Late(), 0.5).view_cost(None, 1, None), [0.5, 1.0])


def test_the_tracker_with_reliability_tracks_the_demo_and_keeps_the_appearance_cues():
    seq = make_demo_sequence(n_frames=25, seed=3)
    tracker = Tracker(TrackerConfig(cue_reliability=True, seed=0))
    tracker.init(seq.frames[0], seq.groundtruth[0])
    for frame in seq.frames[1:]:
        tracker.update(frame)
    factors = tracker._reliability.factors()
    assert len(factors) == len(tracker._others) > 0
    assert np.all((factors >= 0) & (factors <= 1))
    # the demo's target is clear: the appearance cues rank the chosen states high
    by_name = dict(zip([cue.name for cue in tracker._others], factors))
    assert by_name["anchor"] > 0.5 and by_name["correlation"] > 0.5
    box = np.array(tracker.box)
    truth = np.asarray(seq.groundtruth[-1], dtype=float)
    assert np.hypot(*(box[:2] + box[2:] / 2 - truth[:2] - truth[2:] / 2)) < truth[2:].max() / 2
