"""The ``smtmvt track`` and ``smtmvt demo`` sub-commands end to end (small and fast)."""

import json

import cv2
import numpy as np
import pytest

from smtmvt.cli import main
from smtmvt.data import read_boxes
from smtmvt.demo import make_demo_sequence


@pytest.fixture(scope="module")
def otb_folder(tmp_path_factory):
    """A 6-frame OTB folder written from the demo sequence (PNG, tab-separated gt)."""
    root = tmp_path_factory.mktemp("seq") / "Demo"
    (root / "img").mkdir(parents=True)
    seq = make_demo_sequence(n_frames=30)
    for i in range(6):
        cv2.imwrite(str(root / "img" / f"{i + 1:04d}.png"), seq.frames[i][:, :, ::-1])
    lines = ["\t".join(f"{v:.12g}" for v in b + np.array([1, 1, 0, 0])) for b in seq.groundtruth[:6]]
    (root / "groundtruth_rect.txt").write_text("\n".join(lines) + "\n")
    return root, seq.groundtruth[:6]


def test_track_writes_one_based_otb_lines(otb_folder, tmp_path, capsys):
    root, gt = otb_folder
    out = tmp_path / "res.txt"
    assert main(["track", str(root), "--out", str(out), "--particles", "60", "--quiet"]) == 0
    boxes = read_boxes(out)  # 0-based
    assert boxes.shape == (6, 4)
    np.testing.assert_allclose(boxes[0], gt[0], atol=1e-9)
    first_line = out.read_text().splitlines()[0].split(",")
    np.testing.assert_allclose([float(v) for v in first_line], gt[0] + [1, 1, 0, 0], atol=1e-9)
    text = capsys.readouterr().out
    assert "mean overlap" in text and "fps" in text


def test_track_lines_are_the_boxes_of_the_tracker_driven_directly(otb_folder, tmp_path):
    """Every line, not only the first: the boxes a Tracker with the same seed and
    particle count gives when driven by hand on the same frames."""
    from smtmvt import Tracker, TrackerConfig

    root, gt = otb_folder
    out = tmp_path / "res.txt"
    assert main(["track", str(root), "--out", str(out), "--particles", "60", "--seed", "3", "--quiet"]) == 0
    written = read_boxes(out)  # 0-based

    frames = [cv2.imread(str(p))[:, :, ::-1] for p in sorted((root / "img").glob("*.png"))]
    tracker = Tracker(TrackerConfig(seed=3, n_particles=60))
    tracker.init(frames[0], gt[0])
    expected = np.array([gt[0]] + [tracker.update(f).box for f in frames[1:]])
    assert written.shape == expected.shape == (6, 4)
    np.testing.assert_allclose(written, expected, rtol=0, atol=1e-9)
    assert np.abs(expected[1:] - gt[0]).max() > 0.5  # the boxes moved: not just the start box


def test_track_with_box_max_frames_and_video(otb_folder, tmp_path):
    root, gt = otb_folder
    out, video = tmp_path / "res.txt", tmp_path / "v.gif"
    box = ",".join(f"{v:g}" for v in gt[0])
    assert (
        main(
            [
                "track",
                str(root / "img"),
                "--out",
                str(out),
                "--box",
                box,
                "--max-frames",
                "3",
                "--particles",
                "50",
                "--video",
                str(video),
                "--quiet",
            ]
        )
        == 0
    )
    assert len(out.read_text().splitlines()) == 3
    assert video.stat().st_size > 1000


@pytest.mark.parametrize(
    "args,match",
    [
        (["--box", "1,2,3"], "--box must be four numbers"),
        (["--box", "1,2,0,5"], "zero or negative size"),
    ],
)
def test_track_bad_box_is_a_clear_error(otb_folder, tmp_path, capsys, args, match):
    root, _ = otb_folder
    with pytest.raises(SystemExit) if "four" in match else _no_raise():
        rc = main(["track", str(root), "--out", str(tmp_path / "r.txt"), "--quiet"] + args)
        assert rc == 2
    assert match in capsys.readouterr().err


def test_track_missing_source_names_it(tmp_path, capsys):
    missing = tmp_path / "nope"
    assert main(["track", str(missing), "--out", str(tmp_path / "r.txt")]) == 2
    assert str(missing) in capsys.readouterr().err


def test_track_source_without_groundtruth_needs_box(otb_folder, tmp_path, capsys):
    root, _ = otb_folder
    assert main(["track", str(root / "img" / "*.png"), "--out", str(tmp_path / "r.txt"), "--quiet"]) == 2
    assert "--box" in capsys.readouterr().err


def test_demo_writes_its_outputs(tmp_path, capsys):
    out = tmp_path / "demo"
    assert main(["demo", "--out", str(out), "--frames", "12", "--quiet"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    # 12 frames squeeze the whole path into a few large jumps: the figure is
    # not a quality measure here, but it must be the overlap of the files written.
    from smtmvt.evaluation.metrics import overlap_ratio

    res, gt = read_boxes(out / "demo_result.txt"), read_boxes(out / "demo_groundtruth.txt")
    assert summary["frames"] == 12
    assert summary["mean_overlap"] == pytest.approx(overlap_ratio(res, gt).mean(), abs=1e-9)
    np.testing.assert_allclose(res[0], gt[0], atol=1e-9)
    for name in ("demo.gif", "overlap.png", "demo_result.txt", "demo_groundtruth.txt"):
        assert (out / name).stat().st_size > 0
    assert len(read_boxes(out / "demo_result.txt")) == 12
    assert f"mean overlap {summary['mean_overlap']:.3f}" in capsys.readouterr().out


class _no_raise:
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


# ----------------------------------------------------------------------------- nothing clobbered (issue 8)


def _complete_result(otb_folder, tmp_path):
    root, _ = otb_folder
    out = tmp_path / "res.txt"
    assert main(["track", str(root), "--out", str(out), "--particles", "40", "--quiet"]) == 0
    return root, out, out.read_bytes()


def test_track_refuses_to_write_over_the_groundtruth(otb_folder, tmp_path, capsys):
    root, _ = otb_folder
    gt = root / "groundtruth_rect.txt"
    before = gt.read_bytes()
    assert main(["track", str(root), "--out", str(gt), "--particles", "40", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "ground truth" in err and str(gt) in err
    assert gt.read_bytes() == before
    other = tmp_path / "gt.txt"
    other.write_bytes(before)
    assert main(["track", str(root), "--groundtruth", str(other), "--out", str(other), "--quiet"]) == 2
    assert other.read_bytes() == before


def test_track_checks_the_outputs_before_tracking(otb_folder, tmp_path, capsys):
    root, out, before = _complete_result(otb_folder, tmp_path)
    capsys.readouterr()
    not_a_folder = tmp_path / "file.txt"
    not_a_folder.write_text("x")
    video = not_a_folder / "v.mp4"
    assert main(["track", str(root), "--out", str(out), "--video", str(video), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert str(video) in err and "not a folder" in err
    assert out.read_bytes() == before  # the complete result is kept
    assert (
        main(["track", str(root), "--out", str(tmp_path / "v.mkv2"), "--video", str(tmp_path / "v.bmp"), "--quiet"])
        == 2
    )
    assert ".bmp" in capsys.readouterr().err
    assert not (tmp_path / "v.mkv2").exists()


def test_track_failing_midway_writes_nothing(otb_folder, tmp_path, capsys):
    root, out, before = _complete_result(otb_folder, tmp_path)
    broken = tmp_path / "Broken"
    (broken / "img").mkdir(parents=True)
    for f in sorted((root / "img").iterdir()):
        (broken / "img" / f.name).write_bytes(f.read_bytes())
    (broken / "groundtruth_rect.txt").write_bytes((root / "groundtruth_rect.txt").read_bytes())
    (broken / "img" / "0004.png").write_bytes(b"not a png")
    capsys.readouterr()
    assert main(["track", str(broken), "--out", str(out), "--particles", "40", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "0004.png" in err and f"nothing written to {out}" in err
    assert out.read_bytes() == before


def test_track_video_failing_after_tracking_keeps_the_complete_result(otb_folder, tmp_path, capsys, monkeypatch):
    from smtmvt import visualize

    root, _ = otb_folder
    out = tmp_path / "res.txt"

    def fail(self):
        raise OSError("disk full")

    monkeypatch.setattr(visualize.VideoSink, "close", fail)
    rc = main(
        ["track", str(root), "--out", str(out), "--video", str(tmp_path / "v.gif"), "--particles", "40", "--quiet"]
    )
    assert rc == 2 and "disk full" in capsys.readouterr().err
    assert len(read_boxes(out)) == 6  # tracking was complete: its result is written whole


@pytest.mark.parametrize("value", ["0", "-1", "x"])
def test_track_max_frames_must_be_positive(otb_folder, tmp_path, capsys, value):
    root, _ = otb_folder
    with pytest.raises(SystemExit) as info:
        main(["track", str(root), "--out", str(tmp_path / "r.txt"), "--max-frames", value])
    assert info.value.code == 2
    assert f"--max-frames: expected a whole number >= 1, got {value!r}" in capsys.readouterr().err
    assert not (tmp_path / "r.txt").exists()


def test_track_box_may_start_with_a_minus_sign(otb_folder, tmp_path):
    """``--box -5,10,20,20`` (partly left of the image) is a box, not an unknown option."""
    root, _ = otb_folder
    out = tmp_path / "r.txt"
    assert (
        main(
            [
                "track",
                str(root),
                "--out",
                str(out),
                "--box",
                "-5,10,20,20",
                "--max-frames",
                "2",
                "--particles",
                "40",
                "--quiet",
            ]
        )
        == 0
    )
    assert out.read_text().splitlines()[0] == "-4,11,20,20"  # 1-based on disk


def test_video_sink_refuses_a_frame_of_another_size(tmp_path):
    """OpenCV's writer silently drops frames of another size (11 of 20 in issue 8)."""
    from smtmvt.visualize import VideoSink

    for name in ("v.avi", "v.gif"):
        sink = VideoSink(tmp_path / name)
        sink.add(np.zeros((24, 32, 3), np.uint8))
        with pytest.raises(ValueError, match=r"frame 1 is 40x24 pixels, frame 0 is 32x24"):
            sink.add(np.zeros((24, 40, 3), np.uint8))


def test_track_scores_file_has_the_trackers_confidence_and_lost(otb_folder, tmp_path):
    """--scores: a header, then per frame the result file's box (1-based) and the
    confidence and lost a Tracker with the same seed gives when driven by hand."""
    from smtmvt import Tracker, TrackerConfig
    from smtmvt.data.scores import SCORES_HEADER, read_scores

    root, gt = otb_folder
    out, scores = tmp_path / "res.txt", tmp_path / "scores.csv"
    args = ["track", str(root), "--out", str(out), "--scores", str(scores), "--particles", "60", "--seed", "2"]
    assert main([*args, "--quiet"]) == 0
    lines = scores.read_text().splitlines()
    assert lines[0] == SCORES_HEADER == "frame,x,y,w,h,confidence,lost"
    assert [line.split(",")[0] for line in lines[1:]] == ["1", "2", "3", "4", "5", "6"]
    assert [line.split(",")[1:5] for line in lines[1:]] == [line.split(",") for line in out.read_text().splitlines()]
    boxes, confidence, lost = read_scores(scores)
    np.testing.assert_array_equal(boxes, read_boxes(out))

    frames = [cv2.imread(str(p))[:, :, ::-1] for p in sorted((root / "img").glob("*.png"))]
    tracker = Tracker(TrackerConfig(seed=2, n_particles=60))
    tracker.init(frames[0], gt[0])
    results = [tracker.update(f) for f in frames[1:]]
    assert confidence.tolist() == [1.0] + [r.confidence for r in results]
    assert lost.tolist() == [False] + [r.lost for r in results]


def test_track_without_scores_writes_no_scores_file(otb_folder, tmp_path):
    root, _ = otb_folder
    assert main(["track", str(root), "--out", str(tmp_path / "res.txt"), "--particles", "40", "--quiet"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["res.txt"]


@pytest.mark.parametrize("same", ["--out", "ground truth"])
def test_track_scores_refuses_the_result_file_and_the_groundtruth(otb_folder, tmp_path, capsys, same):
    root, _ = otb_folder
    out = tmp_path / "res.txt"
    scores = out if same == "--out" else root / "groundtruth_rect.txt"
    before = (root / "groundtruth_rect.txt").read_bytes()
    rc = main(["track", str(root), "--out", str(out), "--scores", str(scores), "--particles", "40", "--quiet"])
    err = capsys.readouterr().err
    assert rc == 2 and "--scores" in err and str(scores) in err
    assert not out.exists() and (root / "groundtruth_rect.txt").read_bytes() == before


def test_track_failing_midway_writes_no_scores(otb_folder, tmp_path, capsys):
    root, _ = otb_folder
    broken = tmp_path / "Broken"
    (broken / "img").mkdir(parents=True)
    for f in sorted((root / "img").iterdir()):
        (broken / "img" / f.name).write_bytes(f.read_bytes())
    (broken / "groundtruth_rect.txt").write_bytes((root / "groundtruth_rect.txt").read_bytes())
    (broken / "img" / "0003.png").write_bytes(b"not a png")
    scores = tmp_path / "scores.csv"
    rc = main(["track", str(broken), "--out", str(tmp_path / "r.txt"), "--scores", str(scores), "--particles", "40"])
    assert rc == 2 and not scores.exists() and not (tmp_path / "r.txt").exists()
    assert [p.name for p in tmp_path.iterdir()] == ["Broken"]  # no temporary file left either


def test_scores_files_refuse_what_is_not_their_format(tmp_path):
    from smtmvt.data.scores import read_scores, write_scores

    box = [[1.0, 2.0, 3.0, 4.0]] * 2
    with pytest.raises(ValueError, match=r"confidence of frame 2 is 1\.5, not in \[0, 1\]"):
        write_scores(tmp_path / "s.csv", box, [0.5, 1.5], [False, False])
    with pytest.raises(ValueError, match=r"2 boxes but confidence of shape \(3,\)"):
        write_scores(tmp_path / "s.csv", box, [0.5, 0.5, 0.5], [False, False])
    (tmp_path / "h.csv").write_text("2,3,4,5,6,0.5,0\n")
    with pytest.raises(ValueError, match="line 1 must be the header"):
        read_scores(tmp_path / "h.csv")
    (tmp_path / "l.csv").write_text("frame,x,y,w,h,confidence,lost\n1,2,3,4,5,0.5,2\n")
    with pytest.raises(ValueError, match="line 2 is not"):
        read_scores(tmp_path / "l.csv")
    write_scores(tmp_path / "ok.csv", box, [0.25, 1.0], [True, False])
    boxes, confidence, lost = read_scores(tmp_path / "ok.csv")
    np.testing.assert_array_equal(boxes, box)
    assert confidence.tolist() == [0.25, 1.0] and lost.tolist() == [True, False]
