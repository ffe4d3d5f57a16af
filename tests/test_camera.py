"""The camera's motion between frames (smtmvt.camera) and the tracker following it
(``config.camera_motion``)."""

import cv2
import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.camera import SIDE, CameraMotion, frame_shift, reduced_gray
from smtmvt.demo import make_demo_sequence
from smtmvt.evaluation.metrics import overlap_ratio
from smtmvt.tracker import track_frames


def _texture(shape, seed):
    rng = np.random.default_rng(seed)
    t = cv2.GaussianBlur(rng.random(shape).astype(np.float32), (0, 0), 2.0)
    return (255 * (t - t.min()) / np.ptp(t)).astype(np.uint8)


@pytest.mark.parametrize("shape", [(240, 320, 3), (352, 624, 3), (120, 90), (480, 640, 3)])
@pytest.mark.parametrize("dxy", [(20, -12), (-36, 8), (0, 0)])
def test_frame_shift_finds_the_translation_of_the_whole_frame(shape, dxy):
    canvas = _texture((shape[0] + 80, shape[1] + 80, *shape[2:]), seed=1)
    x, y = 40, 40
    before = canvas[y : y + shape[0], x : x + shape[1]]
    # the content moves by dxy: the camera's window moves by -dxy
    after = canvas[y - dxy[1] : y - dxy[1] + shape[0], x - dxy[0] : x - dxy[0] + shape[1]]
    a, k = reduced_gray(before)
    b, k2 = reduced_gray(after)
    assert k == k2 and max(a.shape) <= SIDE
    assert np.allclose(frame_shift(a, b, k), dxy, atol=k)


def test_reduced_gray_is_opencvs_gray_of_the_area_mean():
    frame = _texture((300, 500, 3), seed=2)
    small, k = reduced_gray(frame)
    assert k == 4 and small.shape == (75, 125)
    blocks = frame[:300, :500].astype(np.float64).reshape(75, 4, 125, 4, 3).mean(axis=(1, 3))
    gray = blocks @ np.array([0.299, 0.587, 0.114])
    assert np.abs(small - gray).max() <= 1.0  # uint8 stays uint8: rounded after the mean and after the gray


def test_frame_shift_refuses_frames_of_two_sizes():
    with pytest.raises(ValueError, match="different shapes"):
        frame_shift(np.zeros((20, 30), np.float32), np.zeros((20, 31), np.float32), 1)


def test_a_move_is_proposed_only_past_half_the_box_and_against_the_frame_taken_last():
    canvas = _texture((300, 400, 3), seed=4)
    frame = lambda dx: canvas[40:240, 60 - dx : 360 - dx]  # noqa: E731  (the content moves dx right)
    camera = CameraMotion(frame(0))
    box = (100.0, 80.0, 30.0, 30.0)  # half its size: 15 px
    assert camera.propose(frame(12), box) is None
    camera.dropped()  # that frame is forgotten: the next is compared with frame(0)
    assert np.allclose(camera.propose(frame(24), box), (24, 0), atol=2)
    camera.taken()  # now frame(24) is the last one
    assert camera.propose(frame(36), box) is None  # 12 px from it
    assert camera.propose(frame(36), (100.0, 80.0, 20.0, 20.0)) is not None  # past half a smaller box


def test_the_hypotheses_are_the_large_move_then_the_last_followed_move_undone():
    canvas = _texture((300, 400, 3), seed=4)
    frame = lambda dx: canvas[40:240, 60 - dx : 360 - dx]  # noqa: E731
    camera = CameraMotion(frame(0))
    box = (100.0, 80.0, 30.0, 30.0)
    (shift,) = camera.hypotheses(frame(30), box)  # nothing followed yet: the move alone
    camera.follow(shift)
    camera.dropped()  # a frame not read whole follows nothing
    assert camera.followed is None and len(camera.hypotheses(frame(30), box)) == 1
    camera.follow(shift)
    camera.taken()
    np.testing.assert_array_equal(camera.followed, shift)
    assert [tuple(h) for h in camera.hypotheses(frame(30), box)] == [tuple(-shift)]  # still: the swing back only
    camera.taken()  # nothing followed on that frame
    assert camera.followed is None


def _panned_sequence(jump, n=24, at=12, target_moves=True):
    """A checkered 28x32 target on a textured background seen through a 200x260
    window of a larger scene; at frame ``at`` the window jumps ``jump`` px left
    (the whole picture moves right). With ``target_moves`` False the target is
    drawn on the frame instead (a camera following it: only the background
    moves). Returns (frames, first box, true boxes)."""
    scene = _texture((200, 260 + 2 * abs(jump) + 40, 3), seed=5)
    yy, xx = np.mgrid[0:32, 0:28]
    target = np.where(((yy // 8) + (xx // 7)) % 2 == 0, 250, 30).astype(np.uint8)
    target = np.stack([target, 255 - target // 2, target // 3], axis=2)
    x0 = abs(jump) + 20
    frames, boxes = [], []
    for i in range(n):
        origin = x0 - (jump if i >= at else 0)
        s = scene.copy()
        tx = x0 + 100  # the target's place in the scene
        if target_moves:
            s[80:112, tx : tx + 28] = target
        f = s[:, origin : origin + 260].copy()
        box_x = tx - origin if target_moves else 100
        if not target_moves:
            f[80:112, box_x : box_x + 28] = target
        frames.append(f)
        boxes.append((box_x, 80, 28, 32))
    return frames, np.array(boxes[0], dtype=float), np.array(boxes, dtype=float)


def _track(frames, box, **options):
    return np.array([b for _, b, _ in track_frames(Tracker(TrackerConfig(seed=0, **options)), frames, box)])


def test_the_track_follows_a_camera_jerk_that_carries_the_target_out_of_the_window():
    frames, box, truth = _panned_sequence(jump=45)
    followed = _track(frames, box, camera_motion=True)
    plain = _track(frames, box, camera_motion=False)
    assert overlap_ratio(followed[12:], truth[12:]).min() > 0.6  # from the jump's frame on
    assert overlap_ratio(plain[12:13], truth[12:13])[0] < 0.3  # without it the jump's frame is missed


def test_a_camera_that_follows_the_target_does_not_move_the_track():
    frames, box, truth = _panned_sequence(jump=45, target_moves=False)
    followed = _track(frames, box, camera_motion=True)
    assert overlap_ratio(followed, truth).min() > 0.6


def test_a_slowly_panning_camera_leaves_the_boxes_as_without_the_option():
    demo = make_demo_sequence(n_frames=30)  # its camera pans a pixel or two a frame
    frames, box = demo.frames, demo.groundtruth[0]
    assert np.array_equal(_track(frames, box, camera_motion=True), _track(frames, box, camera_motion=False))


def _peaked(peak, width):
    """A (20, 20) response with one Gaussian peak of height ``peak`` and std ``width``
    cells (a wide peak has a low APCE)."""
    yy, xx = np.mgrid[0:20, 0:20]
    return peak * np.exp(-((yy - 10.0) ** 2 + (xx - 10.0) ** 2) / (2 * width**2)), None


def test_the_filter_prefers_the_moved_window_only_where_the_prediction_lost_the_target():
    from smtmvt.correlation import CorrelationFilter, apce
    from smtmvt.cues import CorrelationCue

    cue = CorrelationCue(TrackerConfig())  # learn gate (0.7, 0.45): peak and APCE against their means
    frame = _texture((120, 160, 3), seed=6)
    cue.filter = CorrelationFilter(frame, (60.0, 40.0, 30.0, 30.0))
    sure, lost, found, weak = _peaked(1.0, 1.0), _peaked(0.3, 1.0), _peaked(0.9, 1.0), _peaked(0.35, 6.0)
    assert not cue.prefers(lost, found)  # nothing judged before: no mean to judge by
    cue.filter.history = [(1.0, apce(sure[0]))] * 3
    assert not cue.prefers(sure, found)  # the prediction holds the target: no move
    assert cue.prefers(lost, found)  # lost here, a confident peak there
    assert cue.prefers(lost, weak)  # higher there, though not confident: the camera's move says where
    assert not cue.prefers(lost, _peaked(0.25, 1.0))  # lower there
    assert not cue.prefers(found, lost)
    off = CorrelationCue(TrackerConfig(correlation_learn_gate=(0.0, 0.0)))
    off.filter, off.filter.history = cue.filter, cue.filter.history
    assert not off.prefers(lost, found)  # without a gate nothing is judged lost
