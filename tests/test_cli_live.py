"""``smtmvt track`` on a live source (issue 51 item 5), without a camera or a display.

A short video recorded from real Crossing frames is played through the live capture
path (``--live``, or a camera index whose ``cv2.VideoCapture`` serves that file), and
OpenCV's window calls are replaced by fakes that record what they were shown and return
the keys and box a test wants.
"""

from __future__ import annotations

import dataclasses
import os
import signal
import time

import cv2
import numpy as np
import pytest

from smtmvt.cli import main
from smtmvt.commands.live import LOST_COLOR, TRACKED_COLOR, annotate, status_label
from smtmvt.data import read_boxes, read_scores
from smtmvt.data.live import is_live_source

N_FRAMES = 12
PARTICLES = "60"


@pytest.fixture(scope="module")
def recorded(otb_dir, tmp_path_factory):
    """``(video path, first box 0-based, frames RGB as the capture decodes them)``: the first
    frames of Crossing written to an MJPG .avi."""
    folder = otb_dir / "Crossing"
    files = sorted((folder / "img").glob("*.jpg"))[:N_FRAMES]
    first = cv2.imread(str(files[0]))
    path = tmp_path_factory.mktemp("live") / "crossing.avi"
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter.fourcc(*"MJPG"), 10, (first.shape[1], first.shape[0]))
    for f in files:
        writer.write(cv2.imread(str(f)))
    writer.release()
    cap = cv2.VideoCapture(str(path))
    frames = []
    while True:
        ok, frame = cap.read()
        if not ok:
            break
        frames.append(frame[:, :, ::-1].copy())
    cap.release()
    assert len(frames) == N_FRAMES
    box = read_boxes(folder / "groundtruth_rect.txt")[0]
    return path, tuple(float(v) for v in box), frames


class FakeWindow:
    """Stands for OpenCV's windows: records each image shown, answers ``waitKey`` with
    ``on_key(call number)`` (1-based) and ``selectROI`` with ``roi``."""

    def __init__(self) -> None:
        self.shown: list[np.ndarray] = []
        self.selected_on: list[np.ndarray] = []
        self.closed = 0
        self.roi = (0, 0, 0, 0)
        self.on_key = lambda n: -1
        self.keys = 0

    def imshow(self, name, image):
        self.shown.append(np.array(image))

    def waitKey(self, delay=0):  # OpenCV's name
        self.keys += 1
        return self.on_key(self.keys)

    def selectROI(self, name, image, *args):
        self.selected_on.append(np.array(image))
        return self.roi

    def destroyAllWindows(self):
        self.closed += 1


@pytest.fixture
def window(monkeypatch):
    fake = FakeWindow()
    for name in ("imshow", "waitKey", "selectROI", "destroyAllWindows"):
        monkeypatch.setattr(cv2, name, getattr(fake, name), raising=False)
    return fake


def box_arg(box) -> str:
    return ",".join(f"{v:g}" for v in box)


def live_args(recorded, out, *extra) -> list[str]:
    path, box, _ = recorded
    return ["track", str(path), "--live", "--out", str(out), "--particles", PARTICLES, "--quiet", *extra]


def test_lines_are_on_disk_as_frames_arrive_and_q_stops(recorded, tmp_path, window, capsys):
    out, scores = tmp_path / "res.txt", tmp_path / "scores.csv"
    seen = []

    def on_key(n):
        seen.append((len(out.read_text().splitlines()), len(scores.read_text().splitlines())))
        return ord("q") if n == 5 else -1

    window.on_key = on_key
    rc = main(live_args(recorded, out, "--box", box_arg(recorded[1]), "--show", "--scores", str(scores)))
    assert rc == 0, capsys.readouterr().err
    assert seen == [(n, n + 1) for n in range(1, 6)]  # one line per frame, on disk before the next frame
    assert len(read_boxes(out)) == 5 and len(read_scores(scores)[0]) == 5
    assert len(window.shown) == 5 and window.closed >= 1
    assert "5 frames (stopped by the key)" in capsys.readouterr().out


def test_escape_also_stops(recorded, tmp_path, window):
    out = tmp_path / "res.txt"
    window.on_key = lambda n: 27 if n == 2 else -1
    assert main(live_args(recorded, out, "--box", box_arg(recorded[1]), "--show")) == 0
    assert len(read_boxes(out)) == 2


def test_live_boxes_are_the_trackers_on_the_same_frames_to_the_end(recorded, tmp_path):
    """Without a stop, every frame of the source is tracked, each line the box (and
    confidence) of a Tracker driven by hand on the frames the capture decodes."""
    from smtmvt import Tracker, TrackerConfig

    _, box, frames = recorded
    out, scores = tmp_path / "res.txt", tmp_path / "scores.csv"
    assert main(live_args(recorded, out, "--box", box_arg(box), "--seed", "2", "--scores", str(scores))) == 0
    tracker = Tracker(TrackerConfig(seed=2, n_particles=int(PARTICLES)))
    tracker.init(frames[0], box)
    results = [tracker.update(f) for f in frames[1:]]
    written, confidence, lost = read_scores(scores)
    np.testing.assert_allclose(read_boxes(out), [box] + [r.box for r in results], rtol=0, atol=1e-9)
    np.testing.assert_allclose(written, read_boxes(out), rtol=0, atol=1e-9)
    np.testing.assert_allclose(confidence, [1.0] + [r.confidence for r in results], rtol=0, atol=1e-12)
    assert list(lost) == [False] + [r.lost for r in results]
    assert np.abs(np.array([r.box for r in results]) - box).max() > 0.5  # the boxes moved


def test_max_frames_bounds_a_live_run_and_its_video(recorded, tmp_path, capsys):
    out, video = tmp_path / "res.txt", tmp_path / "v.avi"
    assert (
        main(live_args(recorded, out, "--box", box_arg(recorded[1]), "--max-frames", "3", "--video", str(video))) == 0
    )
    assert len(read_boxes(out)) == 3
    assert "3 frames (--max-frames)" in capsys.readouterr().out
    cap = cv2.VideoCapture(str(video))
    count = 0
    while cap.grab():
        count += 1
    cap.release()
    assert count == 3


def test_a_live_file_is_never_written_over(recorded, tmp_path, capsys):
    path = tmp_path / "clip.avi"
    path.write_bytes(recorded[0].read_bytes())
    before = path.read_bytes()
    assert main(["track", str(path), "--live", "--box", box_arg(recorded[1]), "--out", str(path)]) == 2
    assert "live source" in capsys.readouterr().err
    assert path.read_bytes() == before


def test_select_draws_the_first_box(recorded, tmp_path, window):
    _, _, frames = recorded
    out = tmp_path / "res.txt"
    window.roi = (200, 148, 20, 52)
    assert main(live_args(recorded, out, "--select", "--max-frames", "3")) == 0
    assert out.read_text().splitlines()[0] == "201,149,20,52"  # 1-based on disk
    assert len(window.selected_on) == 1
    np.testing.assert_array_equal(window.selected_on[0], frames[0][:, :, ::-1])  # BGR, the first frame
    assert window.closed >= 1


def test_a_cancelled_selection_is_an_error_and_writes_nothing(recorded, tmp_path, window, capsys):
    out = tmp_path / "res.txt"
    window.roi = (0, 0, 0, 0)
    assert main(live_args(recorded, out, "--select")) == 2
    assert "--select: no box was drawn" in capsys.readouterr().err
    assert not out.exists()


def test_show_draws_the_box_with_its_confidence_and_lost(recorded, tmp_path, window, monkeypatch):
    """Frame 3 is reported lost: its box is drawn red, the others green, each with its text
    above the box (pixels there differ from the frame's)."""
    from smtmvt import Tracker

    _, box, frames = recorded
    original, calls = Tracker.update, []

    def update(self, frame, *args, **kwargs):
        result = original(self, frame, *args, **kwargs)
        calls.append(1)
        return dataclasses.replace(result, confidence=0.2, lost=True) if len(calls) == 2 else result

    monkeypatch.setattr(Tracker, "update", update)
    out, scores = tmp_path / "res.txt", tmp_path / "scores.csv"
    args = live_args(recorded, out, "--box", box_arg(box), "--show", "--max-frames", "4", "--scores", str(scores))
    assert main(args) == 0
    boxes, _, lost = read_scores(scores)
    assert list(lost) == [False, False, True, False]
    assert len(window.shown) == 4
    for i, shown in enumerate(window.shown):
        x, y, w, h = (int(round(v)) for v in boxes[i])
        color = (LOST_COLOR if lost[i] else TRACKED_COLOR)[::-1]  # BGR
        assert tuple(shown[y, x + w // 2]) == color  # the box's top edge
        text = np.abs(shown[y - 12 : y - 4, x : x + 20].astype(int) - frames[i][y - 12 : y - 4, x : x + 20, ::-1])
        assert text.max() > 60  # the confidence text, above the box
        untouched = np.abs(
            shown[y + 6 : y + h - 6, x + 4 : x + w - 4].astype(int)
            - frames[i][..., ::-1][y + 6 : y + h - 6, x + 4 : x + w - 4]
        )
        assert untouched.max() == 0  # inside the box, the frame as it came


def test_status_label_and_annotate():
    frame = np.full((60, 80, 3), 90, np.uint8)
    assert status_label(0.934, False) == "0.93" and status_label(0.21, True) == "lost 0.21"
    sure, unsure, lost = (
        annotate(frame, (20, 30, 30, 20), c, k) for c, k in ((0.93, False), (0.21, False), (0.21, True))
    )
    band = (slice(16, 27), slice(20, 60))  # where the text goes
    assert not np.array_equal(sure[band], unsure[band])  # the number is drawn
    assert not np.array_equal(unsure[band], lost[band])  # and "lost"
    assert tuple(sure[30, 35]) == TRACKED_COLOR[::-1] and tuple(lost[30, 35]) == LOST_COLOR[::-1]


@pytest.mark.parametrize("how", ["ctrl-c", "failure"])
def test_a_stopped_or_failed_run_keeps_the_lines_tracked(recorded, tmp_path, window, monkeypatch, capsys, how):
    from smtmvt import Tracker

    out, scores = tmp_path / "res.txt", tmp_path / "scores.csv"
    if how == "ctrl-c":
        # as from a terminal: a test run started in the background (``cmd &`` without job
        # control) inherits SIGINT ignored, and the command then rightly ignores Ctrl-C too
        previous = signal.signal(signal.SIGINT, signal.default_int_handler)

        def on_key(n):
            if n == 4:
                os.kill(os.getpid(), signal.SIGINT)
                time.sleep(0.2)  # the handler raises here
            return -1

        window.on_key = on_key
    else:
        original, calls = Tracker.update, []

        def update(self, frame, *args, **kwargs):
            calls.append(1)
            if len(calls) == 4:
                raise ValueError("frame refused")
            return original(self, frame, *args, **kwargs)

        monkeypatch.setattr(Tracker, "update", update)
    try:
        rc = main(live_args(recorded, out, "--box", box_arg(recorded[1]), "--show", "--scores", str(scores)))
    finally:
        if how == "ctrl-c":
            signal.signal(signal.SIGINT, previous)
    err = capsys.readouterr().err
    assert rc == (130 if how == "ctrl-c" else 2), err
    assert "4 lines kept in" in err
    assert len(read_boxes(out)) == 4 and len(read_scores(scores)[0]) == 4


def test_a_live_source_needs_a_box_before_the_camera_is_opened(tmp_path, monkeypatch, capsys):
    opened = []
    monkeypatch.setattr(cv2, "VideoCapture", lambda *a: opened.append(a))
    out = tmp_path / "res.txt"
    assert main(["track", "0", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "camera 0" in err and "--box" in err and "--select" in err
    assert opened == [] and not out.exists()


@pytest.mark.parametrize(
    ("source", "argument"), [("1", 1), ("rtsp://camera.local/stream", "rtsp://camera.local/stream")]
)
def test_camera_index_and_url_go_to_the_capture(recorded, tmp_path, monkeypatch, source, argument):
    path, box, _ = recorded
    real, given = cv2.VideoCapture, []

    def capture(arg):
        given.append(arg)
        return real(str(path))

    monkeypatch.setattr(cv2, "VideoCapture", capture)
    out = tmp_path / "res.txt"
    args = ["track", source, "--out", str(out), "--box", box_arg(box), "--max-frames", "2", "--particles", PARTICLES]
    assert main([*args, "--quiet"]) == 0
    assert given == [argument] and type(given[0]) is type(argument)
    assert len(read_boxes(out)) == 2


def test_a_source_that_does_not_open_is_named(tmp_path, monkeypatch, capsys):
    class Closed:
        def isOpened(self):
            return False

        def release(self):
            pass

    monkeypatch.setattr(cv2, "VideoCapture", lambda arg: Closed())
    out = tmp_path / "res.txt"
    assert main(["track", "rtsp://nowhere/x", "--box", "1,1,5,5", "--out", str(out)]) == 2
    assert "cannot open stream rtsp://nowhere/x" in capsys.readouterr().err
    assert not out.exists()


def test_show_and_select_on_a_file_say_to_add_live(recorded, tmp_path, capsys):
    for option in ("--show", "--select"):
        assert main(["track", str(recorded[0]), option, "--out", str(tmp_path / "r.txt")]) == 2
        err = capsys.readouterr().err
        assert option in err and "--live" in err


def test_show_without_window_support_is_a_clear_error(recorded, tmp_path, monkeypatch, capsys):
    def no_window(*args):
        raise cv2.error("The function is not implemented. Rebuild the library with GTK+")

    monkeypatch.setattr(cv2, "imshow", no_window)
    out = tmp_path / "res.txt"
    assert main(live_args(recorded, out, "--box", box_arg(recorded[1]), "--show")) == 2
    err = capsys.readouterr().err
    assert "--show needs a window" in err and "not implemented" in err
    assert "1 lines kept" in err


def test_what_is_live(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "clip.avi").write_bytes(b"x")
    (tmp_path / "7").mkdir()
    os.mkfifo(tmp_path / "pipe")
    assert is_live_source("0") and is_live_source("12")
    assert is_live_source("rtsp://host/s") and is_live_source("http://host/v.mjpg") and is_live_source("https://h/x")
    assert is_live_source("pipe")  # neither a regular file nor a folder: a device, a pipe
    assert not is_live_source("clip.avi") and not is_live_source("7")  # an existing file or folder
    assert not is_live_source("missing.avi") and not is_live_source("frames/*.png")
