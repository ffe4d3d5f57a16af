"""A frame whose correlation peak is weak holds the prediction (``TrackerConfig.weak_peak_hold``)."""

import numpy as np
import pytest

from jump_sequences import jump_sequence
from smtmvt import Tracker, TrackerConfig
from smtmvt.demo import make_demo_sequence


def _run(frames, box, **config):
    """The centre x of each box after the first, pixels, and the tracker."""
    t = Tracker(TrackerConfig(n_particles=200, redetect_after=0, **config))
    t.init(frames[0], box)
    boxes = np.array([t.update(f).box for f in frames[1:]])
    return boxes[:, 0] + boxes[:, 2] / 2.0, t


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_hold_keeps_the_box_where_it_was_going_while_the_peak_is_weak(seed):
    # the target leaves the filter's window at frame 3 (a jump of 40 pixels, out of
    # reach): its peak there is weak. Trusted, the most likely particle wanders to the
    # background about 10 pixels left; held, the box is the prediction: each frame it
    # moves by the velocity term's share (0.5) of the displacement before, and every
    # particle starts from it.
    frames, box = jump_sequence(40, n=10, at=3, width=300)
    trust, _ = _run(frames, box, seed=seed, weak_peak_hold=False)
    hold, t = _run(frames, box, seed=seed, weak_peak_hold=True)
    np.testing.assert_array_equal(hold[:2], trust[:2])
    assert np.abs(trust[2:] - trust[1]).max() > 8.0
    share = TrackerConfig().velocity
    steps = np.diff(hold[1:])
    expected = (hold[1] - hold[0]) * share ** np.arange(1, len(steps) + 1)
    np.testing.assert_allclose(steps, expected, atol=1e-6)
    np.testing.assert_array_equal(t._particles, np.repeat(t._state[None], len(t._particles), axis=0))


def test_hold_changes_nothing_while_the_peak_stays_strong():
    demo = make_demo_sequence(n_frames=40)
    frames, box = demo.frames, demo.groundtruth[0]
    a, _ = _run(frames, box, seed=0, weak_peak_hold=False)
    b, _ = _run(frames, box, seed=0, weak_peak_hold=True)
    np.testing.assert_array_equal(a, b)


def test_config_refuses_a_value_that_is_not_a_bool():
    with pytest.raises(ValueError, match="weak_peak_hold"):
        TrackerConfig(weak_peak_hold="yes")
