"""The wider search after a loss (``TrackerConfig.redetect_after``)."""

import numpy as np
import pytest

from jump_sequences import jump_sequence
from smtmvt import Tracker, TrackerConfig
from smtmvt.demo import make_demo_sequence


@pytest.fixture(scope="module")
def demo():
    return make_demo_sequence(n_frames=40)


# The jump, 1.7 box widths (28 px): the target leaves the filter's window (1.25
# widths a side) and the reach of the tracker without the search. With the correlation
# term measured against the usual peak (the default, docs/experiments.md#n47) a weak
# response no longer pins the particles to its own peak, and the tracker without the
# search followed a 40-pixel jump on seeds 0 and 2; at 48 it follows on none of seeds
# 0-5, and the search finds the target on frame 5 on each of them (at 50 it is three
# frames late on seed 2: after the jump the box drifts about 11 px the other way, and
# the window one box width over reaches 28 + 35 px).
JUMP = 48
TARGET = 60.0 + JUMP  # the target's x from frame 3 on


def _jump_sequence(jump=JUMP, n=10):
    """The target jumps ``jump`` pixels to the right at frame 3 of ``n``."""
    return jump_sequence(jump, n=n, at=3, width=300)


def _xs(frames, box, **config):
    t = Tracker(TrackerConfig(n_particles=200, **config))
    t.init(frames[0], box)
    return np.array([t.update(f).box[0] for f in frames[1:]])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_wider_search_finds_a_target_that_jumped_out_of_the_window(seed):
    # the target leaves the filter's window and the random walk's reach (JUMP); it is
    # found in the window one box width over
    frames, box = _jump_sequence()
    walk = _xs(frames, box, seed=seed, redetect_after=0)
    wide = _xs(frames, box, seed=seed, redetect_after=2)
    # frames 3 and 4 (indices 2, 3) are the two lost ones: the same boxes as without the search
    np.testing.assert_array_equal(wide[:4], walk[:4])
    assert np.abs(walk[2:] - TARGET).min() > 30.0
    # from frame 5 on, on the target
    assert np.abs(wide[4:] - TARGET).max() <= 2.0


def test_the_wider_search_waits_for_as_many_lost_frames_as_configured():
    frames, box = _jump_sequence()
    three = _xs(frames, box, seed=0, redetect_after=3)
    two = _xs(frames, box, seed=0, redetect_after=2)
    assert abs(two[4] - TARGET) <= 2.0 and abs(three[4] - TARGET) > 30.0
    assert abs(three[5] - TARGET) <= 2.0


def test_a_target_that_stays_in_reach_is_tracked_as_without_the_search(demo):
    frames, box = demo.frames, demo.groundtruth[0]
    a = _xs(frames, box, seed=0, redetect_after=0)
    b = _xs(frames, box, seed=0, redetect_after=1)
    np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("value", [-1, 1.5])
def test_config_refuses_a_negative_or_fractional_count(value):
    with pytest.raises(ValueError, match="redetect_after"):
        TrackerConfig(redetect_after=value)


@pytest.mark.parametrize("near", [True, False])
def test_a_found_frame_teaches_only_when_the_chosen_box_is_at_the_peak(monkeypatch, near):
    # frame 5 is the one the wider search finds (above); where the box chosen there is
    # not within half its size of the peak, neither the filter nor the templates learn
    from smtmvt.cues import CorrelationCue
    from smtmvt.templates import TemplateSet

    frames, box = _jump_sequence()
    t = Tracker(TrackerConfig(n_particles=200, seed=0, redetect_after=2))
    t.init(frames[0], box)
    for f in frames[1:5]:
        t.update(f)
    angles = []
    real = TemplateSet.update

    def spy(self, *args, **kwargs):
        angles.append(kwargs["update_angle"])
        return real(self, *args, **kwargs)

    monkeypatch.setattr(TemplateSet, "update", spy)
    monkeypatch.setattr(CorrelationCue, "near_peak", lambda *a: near)
    before = t._corr.filter.model.A.copy()
    t.update(frames[5])
    assert t._corr.redetected
    assert len(angles) == 1
    if near:
        assert np.isfinite(angles[0]) and not np.array_equal(t._corr.filter.model.A, before)
    else:
        assert angles[0] == np.inf and np.array_equal(t._corr.filter.model.A, before)


# -- config.redetect_first and config.redetect_on_lost (docs/experiments.md#n55) --------


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_first_filters_search_finds_a_target_that_jumped_out_of_the_window(seed):
    frames, box = _jump_sequence()
    wide = _xs(frames, box, seed=seed, redetect_after=2, redetect_first=True)
    assert np.abs(wide[4:] - TARGET).max() <= 2.0


def _drifted_cue(first_history=True):
    """A correlation cue whose filter learned the target (a checkered block at x 60)
    on frame 0, and whose model has since drifted onto another bright block (its
    checks as stripes) at x 180; the frame holds both, 60 px away from a
    prediction at x 120: ``(cue, frame, predicted box)``."""
    from smtmvt.correlation import CorrelationFilter, apce, train
    from smtmvt.cues import CorrelationCue
    from smtmvt.geometry import box_to_affine

    frames, box = jump_sequence(0, n=1, at=1, width=300)
    frame = frames[0].copy()
    stripes = np.where(np.arange(28) // 7 % 2 == 0, 250, 30).astype(np.uint8)
    look_alike = np.broadcast_to(stripes[None, :, None], (32, 28, 3))
    cue = CorrelationCue(TrackerConfig(redetect_first=True))
    cue.filter = CorrelationFilter(frame, box)  # the first filter: the target
    drifted = box + np.array([120.0, 0, 0, 0])
    frame[80:112, 180:208] = look_alike
    cue.filter.model = train(cue.filter._features(frame, drifted), cue.filter._label)
    cue.scale = np.ones(2)
    cue.last_learned = box_to_affine(drifted)
    predicted = box + np.array([60.0, 0, 0, 0])
    r, rf, _ = cue.filter.both(frame, box)
    cue.filter.history = [(1.0, 1.0)]
    if first_history:
        cue.first_history = [(float(rf.max()), apce(rf))]
    cue.respond(frame, predicted, search=False)  # sets first_now about the prediction
    return cue, frame, predicted


def test_the_first_filters_search_proposes_the_target_where_the_model_finds_its_look_alike():
    from smtmvt.correlation import peak_point

    cue, frame, predicted = _drifted_cue()
    by_model = cue._redetect(frame, predicted, cue.filter.response(frame, predicted))
    proposal = cue._propose(frame, predicted)
    assert proposal is not None
    assert abs(peak_point(*proposal)[0] - (60 + 13.5)) <= 4.0
    # the drifted model's own search goes to the look-alike, or finds nothing
    assert by_model is None or abs(peak_point(*by_model)[0] - (180 + 13.5)) <= 4.0


def test_the_first_filters_search_waits_for_a_frame_the_model_learned_from():
    cue, frame, predicted = _drifted_cue(first_history=False)
    assert cue._propose(frame, predicted) is None


def _state_at(point):
    """The state of a 28 x 32 box centred on ``point`` (x, y)."""
    from smtmvt.geometry import box_to_affine

    return box_to_affine(np.array([point[0] - 13.5, point[1] - 15.5, 28.0, 32.0]))


def test_a_proposal_adds_a_place_and_takes_none_away():
    # with a proposal, candidates are scored by the response and the proposal, each
    # measured against its filter's usual peak: the place more usual for its filter
    # costs 0, the other what it lacks of that; without one, by the response alone
    from smtmvt.correlation import peak_point

    cue, frame, predicted = _drifted_cue()
    cue.weight, cue.peak_ref = 1.0, 1.0  # the model's usual peak
    response = cue.respond(frame, predicted, search=True)
    assert cue.proposal is not None
    points = [peak_point(*response), peak_point(*cue.proposal), np.array([280.0, 10.0])]
    states = np.array([_state_at(p) for p in points])
    here, there = response[0].max() / cue.peak_ref, cue.proposal[0].max() / cue.first_history[0][0]
    assert there > here  # the drifted model's response is weak, the first filter's usual
    np.testing.assert_allclose(cue.costs(response, states), [there - here, 0.0, there], atol=1e-9)
    cue.proposal = None
    np.testing.assert_allclose(cue.costs(response, states), [0.0, here, here], atol=1e-9)


def test_one_response_costs_as_the_correlation_cost():
    from smtmvt.correlation import Window, correlation_cost, correlation_cost_over

    rng = np.random.default_rng(0)
    r = rng.random((12, 10)) - 0.2
    window = Window(origin=(5.0, 7.0), step=(1.5, 1.5), size=(48, 40))
    centres = rng.uniform(0, 80, (50, 2))
    for reference in (None, 0.5, 2.0):
        np.testing.assert_allclose(
            correlation_cost_over([(r, window, reference)], centres), correlation_cost(r, window, centres, reference)
        )
    assert not correlation_cost_over([(-r - 1, window, None)], centres).any()


def test_a_state_taken_at_the_proposal_is_a_jump_and_teaches_nothing():
    from smtmvt.correlation import peak_point

    cue, frame, predicted = _drifted_cue()
    response = cue.respond(frame, predicted, search=True)

    there, here = _state_at(peak_point(*cue.proposal)), _state_at(peak_point(*response))
    assert cue.jumped(there, response) and not cue.jumped(here, response)
    gate = ((1.0, 1.0), np.array([1.0, 1.0]))  # a response as strong as usual
    assert not cue.learns(gate, there, response) and cue.learns(gate, here, response)
    assert not cue.templates_learn(None, there, response) and cue.templates_learn(None, here, response)


def test_the_first_filters_history_grows_on_the_frames_the_model_learns_from(demo):
    t = Tracker(TrackerConfig(n_particles=200, seed=0, redetect_first=True))
    t.init(demo.frames[0], demo.groundtruth[0])
    learned = 0
    for f in demo.frames[1:12]:
        before = t._corr.filter.model.A.copy()
        t.update(f)
        learned += not np.array_equal(before, t._corr.filter.model.A)
    assert learned >= 5 and len(t._corr.first_history) == learned


def test_the_search_follows_the_lost_flag_with_redetect_on_lost(monkeypatch):
    from smtmvt.cues import CorrelationCue

    frames, box = _jump_sequence()
    searched = []
    real = CorrelationCue.respond

    def spy(self, frame, box, search):
        searched.append(search)
        return real(self, frame, box, search)

    monkeypatch.setattr(CorrelationCue, "respond", spy)
    t = Tracker(TrackerConfig(n_particles=200, seed=0, redetect_after=0, redetect_on_lost=True))
    t.init(frames[0], box)
    lost = [t.update(f).lost for f in frames[1:]]
    assert searched == [False] + lost[:-1]
    assert any(lost)  # the jump is flagged, so the search ran
    assert abs(t.update(frames[-1]).box[0] - TARGET) <= 2.0
