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
    assert main(["track", str(root / "img"), "--out", str(out), "--box", box, "--max-frames", "3",
                 "--particles", "50", "--video", str(video), "--quiet"]) == 0
    assert len(out.read_text().splitlines()) == 3
    assert video.stat().st_size > 1000


@pytest.mark.parametrize("args,match", [
    (["--box", "1,2,3"], "--box must be four numbers"),
    (["--box", "1,2,0,5"], "zero or negative size"),
])
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
