"""TrackResult.confidence and .lost: the pure mapping (smtmvt.confidence) and the tracker's use of it."""

import math

import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.confidence import CONFIDENCE, LOST_BELOW, ConfidenceModel, Evidence, confidence
from smtmvt.demo import make_demo_sequence

FAST = TrackerConfig(n_particles=100, seed=0)


@pytest.fixture(scope="module")
def demo():
    return make_demo_sequence(n_frames=30)


# -- the mapping ------------------------------------------------------------------


def test_a_usual_frame_is_confident_and_its_value_is_the_bias_sigmoid():
    c = confidence(Evidence())
    assert c == pytest.approx(1.0 / (1.0 + math.exp(-CONFIDENCE.bias)))
    assert c > LOST_BELOW


def test_the_default_boundary_is_the_trackers_lost_floor():
    """Confidence 0.5 at a peak 0.4 times its mean (config.template_learn_floor) when the rest is usual."""
    floor = TrackerConfig().template_learn_floor
    assert confidence(Evidence(peak_ratio=floor)) == pytest.approx(0.5)
    assert confidence(Evidence(peak_ratio=0.9 * floor)) < LOST_BELOW < confidence(Evidence(peak_ratio=1.1 * floor))


@pytest.mark.parametrize(
    "field, low, high, rising",
    [
        ("peak_ratio", 0.2, 1.5, True),
        ("apce_ratio", 0.2, 1.5, True),
        ("cost_ratio", 0.5, 3.0, False),
        ("lost_frames", 0, 12, False),
    ],
)
def test_confidence_is_monotone_in_each_feature(field, low, high, rising):
    values = np.linspace(low, high, 25)
    if field == "lost_frames":
        values = np.arange(low, high + 1)
    c = np.array([confidence(Evidence(**{field: v})) for v in values])
    steps = np.diff(c)
    assert np.all(steps > 0) if rising else np.all(steps < 0), c
    assert np.all((c >= 0) & (c <= 1))


def test_extreme_evidence_stays_in_the_unit_interval():
    assert confidence(Evidence(cost_ratio=math.inf)) < 1e-6
    assert confidence(Evidence(peak_ratio=0.0)) < 1e-6
    assert confidence(Evidence(peak_ratio=-3.0)) == confidence(Evidence(peak_ratio=0.0))
    assert confidence(Evidence(peak_ratio=math.inf, apce_ratio=math.inf)) > 1 - 1e-6
    assert confidence(Evidence(lost_frames=10_000)) == pytest.approx(0.0, abs=1e-12)


def test_the_model_constants_are_what_the_score_uses():
    model = ConfidenceModel(bias=0.3, peak=2.0, apce=0.5, cost=1.0, streak=0.1)
    e = Evidence(peak_ratio=0.8, apce_ratio=1.3, cost_ratio=1.7, lost_frames=2)
    score = 0.3 + 2.0 * math.log(0.8) + 0.5 * math.log(1.3) - 1.0 * math.log(1.7) - 0.1 * 2
    assert confidence(e, model) == pytest.approx(1.0 / (1.0 + math.exp(-score)), rel=1e-12)


@pytest.mark.parametrize("name", ["peak", "apce", "cost", "streak"])
def test_negative_slopes_are_refused_by_name(name):
    with pytest.raises(ValueError, match=f"{name} must be a finite number >= 0, got -1"):
        ConfidenceModel(**{name: -1.0})


@pytest.mark.parametrize("field", ["peak_ratio", "apce_ratio", "cost_ratio"])
def test_nan_evidence_is_refused_by_name(field):
    with pytest.raises(ValueError, match=f"{field} is NaN"):
        confidence(Evidence(**{field: math.nan}))


# -- the tracker ------------------------------------------------------------------


def _run(tracker, frames):
    return [tracker.update(f) for f in frames]


def test_tracked_frames_are_confident_and_a_vanished_target_is_lost(demo):
    """The demo target tracked over 6 frames, then 4 black frames: nothing of it is left."""
    t = Tracker(FAST)
    t.init(demo.frames[0], demo.groundtruth[0])
    tracked = _run(t, demo.frames[1:7])
    gone = _run(t, [np.zeros_like(demo.frames[0])] * 4)
    assert all(not r.lost and r.confidence > LOST_BELOW for r in tracked), [r.confidence for r in tracked]
    assert all(r.lost and r.confidence < LOST_BELOW for r in gone), [r.confidence for r in gone]
    assert gone[-1].evidence.lost_frames >= 2  # the tracker's own streak is in the evidence
    for r in tracked + gone:
        assert r.confidence == confidence(r.evidence)
        assert r.lost == (r.confidence < LOST_BELOW)
        assert 0.0 <= r.confidence <= 1.0


def test_evidence_ratios_are_the_filters_judgement_and_the_cost_median(demo):
    t = Tracker(FAST)
    t.init(demo.frames[0], demo.groundtruth[0])
    results = _run(t, demo.frames[1:6])
    first = results[0].evidence  # nothing before the first update to compare with
    assert (first.peak_ratio, first.apce_ratio, first.cost_ratio, first.lost_frames) == (1.0, 1.0, 1.0, 0)
    history = np.array(t._corr.filter.history)  # (peak, APCE) of each update's response
    costs = [-math.log(r.score) / FAST.alpha for r in results]
    for i in range(1, len(results)):
        e = results[i].evidence
        assert e.peak_ratio == pytest.approx(history[i, 0] / history[:i, 0].mean())
        assert e.apce_ratio == pytest.approx(history[i, 1] / history[:i, 1].mean())
        assert e.cost_ratio == pytest.approx(costs[i] / np.median(costs[:i]))


def test_drift_is_the_chosen_box_residual_over_the_first_template(demo):
    t = Tracker(FAST)
    t.init(demo.frames[0], demo.groundtruth[0])
    first = [Dk[:, 0].astype(np.float64) for Dk in t._sparse.templates.dictionaries]
    for frame in demo.frames[1:4]:
        result, detail = t.update_detailed(frame)
        # by hand: sum over the unit views of 1 - max(cos, 0)^2
        by_hand = sum(
            float(x @ x) - max(float(tk @ x), 0.0) ** 2 / float(tk @ tk)
            for x, tk in zip([v.astype(np.float64) for v in detail.best_views], first)
        )
        assert result.evidence.drift == pytest.approx(max(by_hand, 0.0), abs=1e-9)
        assert 0.0 <= result.evidence.drift <= len(first)
    # a black frame is far from the first frame's target
    result, _ = t.update_detailed(np.zeros_like(demo.frames[0]))
    assert result.evidence.drift > 0.5


def test_reinit_tracks_as_a_new_tracker_started_there(demo):
    """After tracking, losing the target and reinit, nothing learned before is left."""
    box = demo.groundtruth[10]
    used = Tracker(FAST)
    used.init(demo.frames[0], demo.groundtruth[0])
    _run(used, list(demo.frames[1:5]) + [np.zeros_like(demo.frames[0])] * 3)
    used.reinit(demo.frames[10], box)
    fresh = Tracker(FAST)
    fresh.init(demo.frames[10], box)
    a, b = _run(used, demo.frames[11:15]), _run(fresh, demo.frames[11:15])
    assert a == b  # boxes, scores, confidence, lost, evidence, frame indices
    assert used.box == fresh.box


def test_reinit_refuses_a_bad_box_by_value(demo):
    t = Tracker(FAST)
    t.init(demo.frames[0], demo.groundtruth[0])
    with pytest.raises(ValueError, match=r"\(1.0, 2.0, 0.0, 5.0\)"):
        t.reinit(demo.frames[1], (1, 2, 0, 5))


def test_evidence_holds_plain_floats(demo):
    t = Tracker(FAST)
    t.init(demo.frames[0], demo.groundtruth[0])
    e = _run(t, demo.frames[1:3])[-1].evidence
    assert all(type(v) is float for v in (e.peak_ratio, e.apce_ratio, e.cost_ratio)) and type(e.lost_frames) is int


def test_a_negative_lost_streak_is_refused_by_value():
    with pytest.raises(ValueError, match="lost_frames must be >= 0, got -2"):
        confidence(Evidence(lost_frames=-2))
