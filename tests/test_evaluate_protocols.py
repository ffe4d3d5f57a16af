"""``evaluate --protocol tre|sre`` end to end on tiny folders: where each run starts and with
which box (worked by hand from the OTB toolkit's ``splitSeqTRE.m`` / ``shiftInitBB.m``),
resuming per segment, errors per sequence and protocol, repeats, and the report.

Data: :func:`test_runner.make_otb_dataset` squares (160 x 120 PNG frames), 25 frames each
(a TRE segment needs 20), one of 15 frames for the "too short" case.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from smtmvt.data import read_boxes
from smtmvt.evaluation import RunDir, register_tracker, run_evaluation, unregister_tracker
from smtmvt.evaluation.metrics import score_sequence
from test_repeat import Jitter
from test_runner import ConstantVelocity, evaluate_cli, make_otb_dataset

SPECS = {
    "SquareA": dict(start=(30, 40), step=(1.0, 0.5), side=(28, 24)),
    "SquareB": dict(start=(90, 40), step=(-1.0, 0.5), side=(26, 30)),
}
N = 25
# 25 frames, all valid: the last start f with 25 - f + 1 >= 20 is f = 6, so E = 6;
# floor(1 : 6/19 : 6) = floor(1, 1.32, 1.63, 1.95, 2.26, 2.58, 2.89, 3.21, 3.53, 3.84, 4.16,
# 4.47, 4.79, 5.11, 5.42, 5.74) (16 values), then 6: 17 segments from these 1-based frames.
TRE_STARTS_1BASED = [1, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5, 5, 5, 6]
# SquareA's first box, 1-based: [31 41 28 24]; br = (58, 64); 0.1 w = 2.8, 0.1 h = 2.4;
# centre (45, 53); the image is 160 x 120, so nothing is clipped.
SRE_SQUARE_A = {
    "left": [28, 41, 28, 24],  # 31 - ceil(2.8)
    "right": [34, 41, 28, 24],
    "up": [31, 38, 28, 24],  # 41 - ceil(2.4)
    "down": [31, 44, 28, 24],
    "topLeft": [28, 39, 31, 26],  # x = round(28.2), y = round(38.6); w = 58 - 28 + 1, h = 64 - 39 + 1
    "topRight": [31, 39, 31, 26],  # br_x = round(60.8) = 61
    "bottomLeft": [28, 41, 31, 26],  # br_y = round(66.4) = 66
    "bottomRight": [31, 41, 31, 26],
    "scale_8": [34, 43, 22, 19],  # round([33.8 43.4 22.4 19.2])
    "scale_9": [32, 42, 25, 22],  # round([32.4 42.2 25.2 21.6])
    "scale_11": [30, 40, 31, 26],  # round([29.6 39.8 30.8 26.4])
    "scale_12": [28, 39, 34, 29],  # round([28.2 38.6 33.6 28.8])
}


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return make_otb_dataset(tmp_path_factory.mktemp("otb"), specs=SPECS, n_frames=N)


@pytest.fixture
def trackers():
    register_tracker("test-cv", ConstantVelocity, deterministic=True, replace=True)
    register_tracker("test-jitter", Jitter, replace=True)
    yield
    unregister_tracker("test-cv")
    unregister_tracker("test-jitter")


def groundtruth(dataset, seq) -> np.ndarray:
    return read_boxes(dataset / seq / "groundtruth_rect.txt", one_based=True)


def test_tre_runs_start_where_the_toolkit_starts_them(dataset, tmp_path, trackers):
    run = run_evaluation(dataset, ["test-cv"], tmp_path / "run", protocols="tre", progress=False, report=False)
    assert run.ok and len(run.done) == 2 * len(TRE_STARTS_1BASED)
    rd = RunDir(tmp_path / "run")
    for seq in SPECS:
        gt = groundtruth(dataset, seq)
        for k, first in enumerate(TRE_STARTS_1BASED, start=1):
            boxes = rd.read_result("test-cv", seq, part=("tre", f"seg-{k:02d}"))
            assert len(boxes) == N - first + 1  # from its start frame to the end
            assert boxes[0].tolist() == gt[first - 1].tolist()  # that frame's ground-truth box
            assert rd.read_record("test-cv", seq, part=("tre", f"seg-{k:02d}"))["start"] == first - 1
        assert not rd.result_path("test-cv", seq, part=("tre", "seg-18")).exists()
    assert not rd.result_path("test-cv", "SquareA").exists()  # no OPE asked for
    assert json.loads(rd.run_json.read_text())["protocols"] == ["tre"]


def test_sre_runs_start_from_the_toolkits_shifted_boxes(dataset, tmp_path, trackers):
    run = run_evaluation(dataset, ["test-cv"], tmp_path / "run", protocols="sre", progress=False, report=False)
    assert run.ok and len(run.done) == 2 * 12
    rd = RunDir(tmp_path / "run")
    for shift, box in SRE_SQUARE_A.items():
        boxes = rd.read_result("test-cv", "SquareA", part=("sre", shift))
        assert len(boxes) == N and boxes[0].tolist() == box, shift


def test_tre_resumes_per_segment(dataset, tmp_path, trackers):
    out = tmp_path / "run"
    run_evaluation(dataset, ["test-cv"], out, protocols=["tre"], progress=False, report=False)
    rd = RunDir(out)
    rd.result_path("test-cv", "SquareB", part=("tre", "seg-05")).unlink()
    short = rd.result_path("test-cv", "SquareA", part=("tre", "seg-17"))
    short.write_text("".join(short.read_text().splitlines(keepends=True)[:-1]))
    kept = rd.result_path("test-cv", "SquareA", part=("tre", "seg-01")).stat().st_mtime_ns
    again = run_evaluation(dataset, ["test-cv"], out, protocols="tre", progress=False, report=False)
    assert sorted(again.done) == [
        ("test-cv", "SquareA", 0, "tre", "seg-17"),
        ("test-cv", "SquareB", 0, "tre", "seg-05"),
    ]
    assert len(again.skipped) == 2 * len(TRE_STARTS_1BASED) - 2
    assert any("seg-17" in n and "recomputing" in n for n in again.notes)
    assert rd.result_path("test-cv", "SquareA", part=("tre", "seg-01")).stat().st_mtime_ns == kept


def test_a_sequence_too_short_for_tre_is_an_error_of_that_sequence(tmp_path, trackers):
    data = make_otb_dataset(tmp_path / "otb", specs={**SPECS, "Short": dict(SPECS["SquareA"], n=15)}, n_frames=N)
    run = run_evaluation(data, ["test-cv"], tmp_path / "run", protocols="ope,tre", progress=False, report=True)
    (err,) = run.errors
    assert err["sequence"] == "Short" and err["part"] == "tre"
    assert "no TRE run" in err["error"] and "15 frames" in err["error"]
    assert RunDir(tmp_path / "run").result_path("test-cv", "Short").exists()  # its OPE ran
    tre = run.report["protocols"]["tre"]
    assert tre["trackers"]["test-cv"]["n_sequences"] == 2 and "Short" in tre["trackers"]["test-cv"]["errors"]
    assert run.report["trackers"]["test-cv"]["n_sequences"] == 3  # OPE has all three
    assert any(e.get("protocol") == "tre" and e["sequence"] == "Short" for e in run.report["errors"])


def test_repeats_of_a_stochastic_tracker_run_each_segment_with_its_own_seed(dataset, tmp_path, trackers):
    Jitter.seeds.clear()
    out = tmp_path / "run"
    run = run_evaluation(dataset, ["test-jitter"], out, protocols="sre", repeat=2, progress=False, report=True)
    assert run.ok and len(run.done) == 2 * 12 * 2
    assert len(set(Jitter.seeds)) == len(Jitter.seeds) == 48  # one seed per sequence, shift and repeat
    rd = RunDir(out)
    assert rd.result_path("test-jitter", "SquareA", 1, part=("sre", "left")).is_file()
    entry = run.report["protocols"]["sre"]["trackers"]["test-jitter"]
    assert entry["n_runs"] == 2 and entry["auc_std"] is not None and entry["auc_std"] > 0


def _pooled_auc(rd: RunDir, dataset, seq: str, starts_1based, protocol: str, names) -> float:
    """Pooled success AUC of a sequence, computed here from the result files: hits summed over
    the runs over their summed lengths (genPerfMat.m)."""
    gt = groundtruth(dataset, seq)
    hits, frames = np.zeros(21), 0
    for first, name in zip(starts_1based, names, strict=True):
        boxes = rd.read_result("test-cv", seq, part=(protocol, name))
        score = score_sequence(boxes, gt[first - 1 :])
        hits += score.success * len(boxes)
        frames += len(boxes)
    return float(np.mean(hits / frames))


def test_report_scores_each_protocol_by_pooling_its_runs(dataset, tmp_path, trackers, capsys):
    out = tmp_path / "run"
    assert evaluate_cli(dataset, out, "--trackers", "test-cv", "--protocol", "ope,tre,sre", "--quiet") == 0
    printed = capsys.readouterr().out
    assert "TRE:" in printed and "SRE:" in printed and "report/tre/index.html" in printed
    summary = json.loads((out / "report" / "summary.json").read_text())
    rd = RunDir(out)
    tre_names = [f"seg-{k:02d}" for k in range(1, len(TRE_STARTS_1BASED) + 1)]
    sre_names = list(SRE_SQUARE_A)
    for protocol, starts, names in (("tre", TRE_STARTS_1BASED, tre_names), ("sre", [1] * 12, sre_names)):
        sub = summary["protocols"][protocol]
        per_seq = sub["trackers"]["test-cv"]["sequences"]
        for seq in SPECS:
            assert per_seq[seq]["auc"] == pytest.approx(_pooled_auc(rd, dataset, seq, starts, protocol, names))
        mean = np.mean([per_seq[s]["auc"] for s in SPECS])
        assert sub["trackers"]["test-cv"]["auc"] == pytest.approx(mean)
        folder = out / "report" / protocol
        for name in ("success.png", "precision.svg", "table.md", "index.html", "summary.json"):
            assert (folder / name).is_file(), name
        assert f"Success plots of {protocol.upper()}" in (folder / "success.svg").read_text()
    # the SRE runs start off target, so they score below OPE on a tracker that never corrects
    assert summary["protocols"]["sre"]["trackers"]["test-cv"]["auc"] < summary["trackers"]["test-cv"]["auc"]
    table = (out / "report" / "table.md").read_text()
    assert "| Tracker | OPE AUC | OPE precision | TRE AUC | TRE precision | SRE AUC | SRE precision |" in table
    assert "href='tre/index.html'" in (out / "report" / "index.html").read_text()


def test_a_run_without_ope_reports_only_its_protocols(dataset, tmp_path, trackers):
    out = tmp_path / "run"
    run = run_evaluation(dataset, ["test-cv"], out, protocols="tre", progress=False, report=True)
    assert run.ok and run.report["trackers"] == {} and list(run.report["protocols"]) == ["tre"]
    assert not run.report["errors"]  # no OPE result is missing: OPE was not asked for
    assert sorted(p.name for p in (out / "report").iterdir()) == ["index.html", "summary.json", "tre"]


def test_the_toolkits_omitted_start_frames_apply_to_an_otb_matrix(tmp_path, trackers):
    spec = {"Matrix": dict(start=(10, 10), step=(0.5, 0.25), side=(16, 12))}
    data = make_otb_dataset(tmp_path / "otb", specs=spec, n_frames=60, size=(48, 64))
    run = run_evaluation(data, ["test-cv"], tmp_path / "run", protocols="tre", progress=False, report=True)
    assert run.ok
    rd = RunDir(tmp_path / "run")
    # initOmit/matrix.txt "36 40": the last segment starts at frame 41 (test_protocols works it out)
    assert rd.read_record("test-cv", "Matrix", part=("tre", "seg-20"))["start"] == 40
    assert len(rd.read_result("test-cv", "Matrix", part=("tre", "seg-20"))) == 20
    assert run.report["protocols"]["tre"]["trackers"]["test-cv"]["n_sequences"] == 1


def test_an_unknown_protocol_is_refused_before_anything_runs(dataset, tmp_path, capsys):
    with pytest.raises(SystemExit) as stop:
        evaluate_cli(dataset, tmp_path / "run", "--trackers", "opencv-mosse", "--protocol", "ope,xre")
    assert stop.value.code == 2
    assert "protocol xre: expected one or more of ope, tre, sre" in capsys.readouterr().err
    assert not (tmp_path / "run").exists()
