"""smtmvt.loop.run_loop: the one loop that drives a tracker (track, evaluate, the sweep)."""

import numpy as np
import pytest

from smtmvt.loop import LoopPosition, run_loop
from smtmvt.results import TrackResult


class _Fake:
    """Records its calls; update moves the box one pixel right and returns what ``kind`` says."""

    def __init__(self, kind="result"):
        self.calls, self.kind, self.box = [], kind, None

    def init(self, frame, box):
        self.calls.append(("init", int(frame[0, 0])))
        self.box = np.asarray(box, dtype=float)

    def update(self, frame):
        self.calls.append(("update", int(frame[0, 0])))
        self.box = self.box + [1, 0, 0, 0]
        if self.kind == "bare":
            return tuple(self.box)
        if self.kind == "short":
            return self.box[:3]
        k = len(self.calls) - 1
        return TrackResult(tuple(self.box), 0.5, 0.0, False, None, k, confidence=0.1 * k, lost=k == 2)


def _frames(n):
    return [np.full((4, 5), i, dtype=np.uint8) for i in range(n)]


def test_init_on_the_first_frame_update_on_the_rest():
    t = _Fake()
    steps = list(run_loop(t, _frames(4), (1, 2, 3, 4)))
    assert t.calls == [("init", 0), ("update", 1), ("update", 2), ("update", 3)]
    assert [s.index for s in steps] == [0, 1, 2, 3]
    np.testing.assert_array_equal(
        np.array([s.box for s in steps]), [[1, 2, 3, 4], [2, 2, 3, 4], [3, 2, 3, 4], [4, 2, 3, 4]]
    )
    assert steps[0].box.dtype == np.float64 and all(s.seconds >= 0 for s in steps)


def test_confidence_and_lost_come_from_the_track_result():
    steps = list(run_loop(_Fake(), _frames(4), (1, 2, 3, 4)))
    assert [s.confidence for s in steps] == pytest.approx([1.0, 0.1, 0.2, 0.3])
    assert [s.lost for s in steps] == [False, False, True, False]


def test_a_bare_box_has_no_confidence():
    steps = list(run_loop(_Fake("bare"), _frames(3), (1, 2, 3, 4)))
    assert [s.confidence for s in steps] == [1.0, None, None]
    assert not any(s.lost for s in steps)


def test_the_limit_stops_before_reading_the_next_frame():
    read = []

    def frames():
        for i in range(10):
            read.append(i)
            yield np.full((4, 5), i, dtype=np.uint8)

    steps = list(run_loop(_Fake(), frames(), (1, 2, 3, 4), limit=3))
    assert len(steps) == 3 and read == [0, 1, 2]


def test_a_reading_error_leaves_the_position_at_that_frame():
    def frames():
        yield np.zeros((4, 5), dtype=np.uint8)
        yield np.ones((4, 5), dtype=np.uint8)
        raise OSError("frame file gone")

    position = LoopPosition()
    with pytest.raises(OSError, match="gone"):
        list(run_loop(_Fake(), frames(), (1, 2, 3, 4), position=position))
    assert (position.index, position.stage) == (2, "reading")


def test_a_wrong_box_from_update_is_a_clear_error_at_its_frame():
    position = LoopPosition()
    with pytest.raises(ValueError, match="returned 3 numbers, expected x, y, w, h"):
        list(run_loop(_Fake("short"), _frames(4), (1, 2, 3, 4), position=position))
    assert (position.index, position.stage) == (1, "tracking")


def test_a_start_box_of_other_than_four_numbers_is_refused():
    with pytest.raises(ValueError, match="start box"):
        list(run_loop(_Fake(), _frames(2), (1, 2, 3)))
