"""bench/lost_calibration.py: the precision and recall of lost, the reliability table, and a tiny run."""

import importlib.util
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

_PATH = Path(__file__).resolve().parents[1] / "bench" / "lost_calibration.py"
_spec = importlib.util.spec_from_file_location("lost_calibration", _PATH)
assert _spec is not None and _spec.loader is not None
calib = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(calib)


def test_precision_and_recall_count_lost_against_not_tracked():
    lost = np.array([True, True, False, False, True, False])
    tracked = np.array([False, True, False, True, False, True])
    # called lost: frames 0, 1, 4; truly lost: 0, 2, 4; both: 0, 4
    assert calib.precision_recall(lost, tracked) == pytest.approx((2 / 3, 2 / 3))
    p, r = calib.precision_recall(np.zeros(3, bool), np.ones(3, bool))
    assert np.isnan(p) and np.isnan(r)


def test_reliability_bins_mean_share_and_count():
    confidence = np.array([0.05, 0.15, 0.12, 0.95, 1.0, 0.99, 0.5])
    tracked = np.array([False, True, False, True, True, False, True])
    table = calib.reliability(confidence, tracked, bins=10)
    assert table.shape == (10, 3) and table[:, 2].sum() == len(confidence)
    np.testing.assert_allclose(table[0], [0.05, 0.0, 1])
    np.testing.assert_allclose(table[1], [0.135, 0.5, 2])
    np.testing.assert_allclose(table[5], [0.5, 1.0, 1])
    np.testing.assert_allclose(table[9], [(0.95 + 1.0 + 0.99) / 3, 2 / 3, 3])  # 1.0 in the last, closed bin
    assert np.isnan(table[3, :2]).all() and table[3, 2] == 0
    expected = (1 * 0.05 + 2 * abs(0.5 - 0.135) + 1 * 0.5 + 3 * abs(2 / 3 - 0.98)) / 7
    assert calib.calibration_error(table) == pytest.approx(expected)


def test_reliability_refuses_confidence_outside_the_unit_interval():
    with pytest.raises(ValueError, match="from -0.1 to 0.5"):
        calib.reliability(np.array([-0.1, 0.5]), np.array([True, False]))


def test_a_tiny_run_prints_the_tables_and_saves_the_diagram(otb_dir, tmp_path, monkeypatch, capsys):
    """Crossing cut to 6 frames: the script runs end to end on a real sequence."""
    seq = tmp_path / "data" / "Crossing"
    (seq / "img").mkdir(parents=True)
    for f in sorted((otb_dir / "Crossing" / "img").glob("*.jpg"))[:6]:
        shutil.copy(f, seq / "img" / f.name)
    lines = (otb_dir / "Crossing" / "groundtruth_rect.txt").read_text().splitlines()[:6]
    (seq / "groundtruth_rect.txt").write_text("\n".join(lines) + "\n")
    png, rows = tmp_path / "out" / "rel.png", tmp_path / "frames.csv"
    argv = ["lost_calibration.py", "--data", str(tmp_path / "data"), "--config", '{"n_particles": 60}']
    argv += ["--plot", str(png), "--frames-out", str(rows)]
    monkeypatch.setattr(sys, "argv", argv)
    calib.main()
    out = capsys.readouterr().out
    assert "Crossing seed 0: 5 frames" in out and "lost: precision" in out
    assert "expected calibration error" in out and out.count("\n[") == calib.BINS
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    header, *frames = rows.read_text().splitlines()
    assert header.split(",")[-len(calib.FEATURES) :] == list(calib.FEATURES) and len(frames) == 5


def test_an_unknown_sequence_is_named(otb_dir, monkeypatch):
    monkeypatch.setattr(sys, "argv", ["x", "--data", str(otb_dir), "--sequences", "NoSuchSeq"])
    with pytest.raises(SystemExit, match="nosuchseq not found"):
        calib.main()
