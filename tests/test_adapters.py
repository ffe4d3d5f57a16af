"""The interfaces users already know: OpenCV's (TrackerSMTMVT) and got10k's (SMTMVTGot10k)."""

import json
import subprocess
import sys

import cv2
import numpy as np
import pytest

import smtmvt
from smtmvt import Tracker, TrackerConfig, TrackerSMTMVT
from smtmvt.demo import make_demo_sequence

FAST = TrackerConfig(n_particles=60, seed=0)
CUT = 5  # frames of the real sequence the tests use


@pytest.fixture(scope="module")
def crossing(otb_dir):
    """The first CUT frames of OTB Crossing as OpenCV reads them (BGR uint8), and its first box (0-based ints)."""
    files = sorted((otb_dir / "Crossing" / "img").glob("*.jpg"))[:CUT]
    first = (otb_dir / "Crossing" / "groundtruth_rect.txt").read_text().splitlines()[0]
    x, y, w, h = (int(v) for v in first.replace(",", " ").split())
    return [cv2.imread(str(f)) for f in files], (x - 1, y - 1, w, h)


def _drive(tracker, frames, box):
    """The OpenCV call pattern: init on the first frame, update on the rest."""
    started = tracker.init(frames[0], box)
    return started, [tracker.update(f) for f in frames[1:]]


# -- OpenCV ------------------------------------------------------------------------


def test_driven_like_csrt_it_returns_what_csrt_returns(crossing):
    frames, box = crossing
    ours = _drive(TrackerSMTMVT.create(FAST), frames, box)
    theirs = _drive(cv2.TrackerCSRT.create(), frames, box)
    assert ours[0] is None and theirs[0] is None  # init returns None (OpenCV 4.5+)
    for (ok, rect), (cv_ok, cv_rect) in zip(ours[1], theirs[1]):
        assert type(ok) is type(cv_ok) is bool and ok and cv_ok
        assert type(rect) is type(cv_rect) is tuple and len(rect) == len(cv_rect) == 4
        assert [type(v) for v in rect] == [type(v) for v in cv_rect] == [int] * 4
        assert max(abs(a - b) for a, b in zip(rect[:2], cv_rect[:2])) < 15  # both follow the walker


def test_its_boxes_are_the_trackers_on_the_rgb_frames_rounded(crossing):
    frames, box = crossing
    _, updates = _drive(TrackerSMTMVT.create(FAST), frames, box)
    direct = Tracker(FAST)
    direct.init(frames[0][:, :, ::-1], box)
    expected = [direct.update(f[:, :, ::-1]).box for f in frames[1:]]
    assert [rect for _, rect in updates] == [tuple(int(round(v)) for v in b) for b in expected]


def test_bgr_frames_are_turned_to_rgb():
    """On colourful frames the tracker given the BGR frames as RGB tracks otherwise
    (its float boxes differ): the adapter's boxes are those of the RGB frames."""
    demo = make_demo_sequence(n_frames=30)
    bgr = [np.ascontiguousarray(f[:, :, ::-1]) for f in demo.frames[:6]]
    box = tuple(int(round(v)) for v in demo.groundtruth[0])
    t = TrackerSMTMVT.create(FAST)
    t.init(bgr[0], box)
    adapted = []
    for f in bgr[1:]:
        t.update(f)
        assert t.result is not None
        adapted.append(t.result.box)

    def boxes(frames):
        tracker = Tracker(FAST)
        tracker.init(frames[0], box)
        return [tracker.update(f).box for f in frames[1:]]

    assert adapted == boxes(demo.frames[:6])
    assert adapted != boxes(bgr)  # BGR read as RGB


def test_ok_is_false_when_the_target_is_lost(crossing):
    frames, box = crossing
    t = TrackerSMTMVT.create(FAST)
    t.init(frames[0], box)
    assert all(t.update(f)[0] for f in frames[1:])
    black = np.zeros_like(frames[0])
    oks = [t.update(black)[0] for _ in range(3)]
    assert oks == [False] * 3 and t.result is not None and t.result.lost


def test_create_refuses_what_is_not_a_config():
    with pytest.raises(TypeError, match=r"got \{'n_particles': 10\}"):
        TrackerSMTMVT.create({"n_particles": 10})


def test_init_refuses_a_box_that_is_not_four_numbers(crossing):
    frames, _ = crossing
    with pytest.raises(ValueError, match=r"\(x, y, w, h\), got \(1, 2, 3\)"):
        TrackerSMTMVT.create(FAST).init(frames[0], (1, 2, 3))


# -- got10k ------------------------------------------------------------------------


def test_import_smtmvt_does_not_import_got10k():
    code = "import sys, smtmvt; assert 'got10k' not in sys.modules; smtmvt.SMTMVTGot10k; assert 'got10k' in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_got10k_boxes_are_one_based_around_the_trackers(crossing):
    frames, box = crossing
    rgb = [f[:, :, ::-1] for f in frames]
    g = smtmvt.SMTMVTGot10k(FAST)
    g.init(rgb[0], np.array(box, dtype=float) + [1, 1, 0, 0])
    direct = Tracker(FAST)
    direct.init(rgb[0], box)
    for f in rgb[1:]:
        np.testing.assert_array_equal(g.update(f), np.array(direct.update(f).box) + [1, 1, 0, 0])
    assert g.is_deterministic and not smtmvt.SMTMVTGot10k(TrackerConfig(seed=None)).is_deterministic


def _tiny_otb(root, otb_dir, version):
    """An OTB root got10k's ``OTB(root, version)`` accepts without downloading: a
    folder for every sequence of ``version`` (got10k downloads any that is missing),
    empty but for Crossing cut to CUT frames (only folders with a ground-truth file count)."""
    from got10k.datasets import OTB

    for name in OTB._OTB__version_dict[version]:  # got10k's own list of the version's names
        (root / name).mkdir(parents=True, exist_ok=True)
    img = root / "Crossing" / "img"
    img.mkdir()
    for f in sorted((otb_dir / "Crossing" / "img").glob("*.jpg"))[:CUT]:
        (img / f.name).write_bytes(f.read_bytes())
    lines = (otb_dir / "Crossing" / "groundtruth_rect.txt").read_text().splitlines()[:CUT]
    (root / "Crossing" / "groundtruth_rect.txt").write_text("\n".join(lines) + "\n")


def test_got10k_experiment_otb_runs_it_unchanged(otb_dir, tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    from got10k.experiments import ExperimentOTB

    monkeypatch.chdir(tmp_path)  # the result and report folders below are relative: under tmp_path
    _tiny_otb(tmp_path / "OTB", otb_dir, 2013)
    experiment = ExperimentOTB(str(tmp_path / "OTB"), version=2013, result_dir="results", report_dir="reports")
    assert experiment.dataset.seq_names == ["Crossing"]
    experiment.run(smtmvt.SMTMVTGot10k(FAST, name="SMTMVT-test"))
    performance = experiment.report(["SMTMVT-test"])
    overall = performance["SMTMVT-test"]["overall"]
    assert 0.5 < overall["success_score"] <= 1.0 and 0.0 < overall["precision_score"] <= 1.0
    saved = json.loads((tmp_path / "reports" / "OTB2013" / "SMTMVT-test" / "performance.json").read_text())
    assert saved["SMTMVT-test"]["overall"]["success_score"] == overall["success_score"]
    boxes = np.loadtxt(tmp_path / "results" / "OTB2013" / "SMTMVT-test" / "Crossing.txt", delimiter=",")
    assert boxes.shape == (CUT, 4)
