"""``report --import``: foreign results never write outside the run nor over our own (issue 8)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from smtmvt.cli import main
from test_runner import evaluate_cli, make_otb_dataset

KCF_ON_A_AND_B = ("--trackers", "opencv-kcf", "--sequences", "SquareA,SquareB", "--no-report", "--quiet")


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return make_otb_dataset(tmp_path_factory.mktemp("otb"), n_frames=12)


@pytest.fixture
def run_dir(dataset, tmp_path, capsys):
    run_dir = tmp_path / "run"
    assert evaluate_cli(dataset, run_dir, *KCF_ON_A_AND_B) == 0
    capsys.readouterr()
    return run_dir


def _files(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file())


@pytest.mark.parametrize("seq_name", ["../../escaped", "/ABS/escaped", "../escaped"])
def test_imported_sequence_names_cannot_leave_the_run(run_dir, tmp_path, capsys, seq_name):
    src = tmp_path / "OPE" / "EVIL"
    src.mkdir(parents=True)
    seq_name = seq_name.replace("/ABS", str(tmp_path / "abs"))
    (src / "SquareA.json").write_text(
        json.dumps([{"res": [[1, 1, 5, 5]] * 12, "resType": "rect", "seqName": seq_name}])
    )
    before = _files(tmp_path)
    assert main(["report", str(run_dir), "--import", str(src)]) == 2
    err = capsys.readouterr().err
    assert f"it names sequence {seq_name!r}, not a sequence of this run" in err
    assert "no results matched" in err
    assert _files(tmp_path) == before  # nothing written anywhere


def test_an_imported_tracker_name_must_be_a_folder_name(run_dir, tmp_path, capsys):
    src = tmp_path / "pysot" / "T"
    src.mkdir(parents=True)
    (src / "SquareA.txt").write_text("1,1,5,5\n" * 12)
    before = _files(run_dir)
    assert main(["report", str(run_dir), "--import", f"{src}:.."]) == 2
    assert "invalid tracker name '..'" in capsys.readouterr().err
    assert _files(run_dir) == before


def test_an_import_never_replaces_results_the_run_computed(run_dir, tmp_path, capsys):
    from scipy.io import savemat

    ours = (run_dir / "results" / "opencv-kcf" / "SquareA.txt").read_text()
    mats = tmp_path / "results_OPE"
    mats.mkdir()
    for seq in ("SquareA", "SquareB"):
        savemat(mats / f"{seq}_opencv-kcf.mat", {"result": np.tile([30.0, 40.0, 28.0, 24.0], (12, 1))})
    assert main(["report", str(run_dir), "--import", str(mats)]) == 0
    out = capsys.readouterr().out
    assert "imported as 'opencv-kcf-imported'" in out and "imported opencv-kcf-imported: 2 sequence" in out
    assert (run_dir / "results" / "opencv-kcf" / "SquareA.txt").read_text() == ours
    assert (run_dir / "results" / "opencv-kcf-imported" / "SquareA.txt").read_text().startswith("30,40,28,24")
    summary = json.loads((run_dir / "report" / "summary.json").read_text())
    assert summary["trackers"]["opencv-kcf-imported"]["imported"] and not summary["trackers"]["opencv-kcf"]["imported"]
    # and a later evaluate still has its own results, untouched
    dataset = json.loads((run_dir / "run.json").read_text())["dataset"]
    assert evaluate_cli(dataset, run_dir, *KCF_ON_A_AND_B) == 0
    assert "0 pair(s) run" in capsys.readouterr().out
    assert (run_dir / "results" / "opencv-kcf" / "SquareA.txt").read_text() == ours


# ----------------------------------------------------------------------------- issue 46: bad values, stale speed


GOOD = {"res": [[31, 41, 28, 24]] * 12, "resType": "rect", "seqName": "SquareA", "fps": 20}


@pytest.mark.parametrize(
    "change,what",
    [
        ({"seqName": {"a": 1}}, "'seqName' must be a text"),
        ({"seqName": ["SquareA"]}, "'seqName' must be a text"),
        ({"res": [["x", 1, 2, 3]] * 12}, "'res' is not an array of numbers"),
        ({"res": [[1, 2, 3, 4], [1, 2]]}, "'res' is not an array of numbers"),
        ({"res": [1, 2, 3, 4, 5]}, "'res' holds 5 numbers, not rows of 4"),
        ({"res": [[1, 2, 3, 4]] * 11 + [[1, 2, 1e999, 4]]}, "'res' row 12 is not finite"),
        ({"fps": "fast"}, "'fps' must be a number of frames per second"),
        ({"fps": -3}, "'fps' must be a number of frames per second"),
        ({"fps": [20]}, "'fps' must be a number of frames per second"),
        ({"startFrame": "first"}, "'startFrame' must be a frame number"),
        ({"resType": ["rect"]}, "'resType' must be a text"),
    ],
)
def test_a_malformed_json_result_is_an_error_naming_the_file(run_dir, tmp_path, capsys, change, what):
    src = tmp_path / "OPE" / "BAD"
    src.mkdir(parents=True)
    path = src / "SquareA.json"
    path.write_text(json.dumps([{**GOOD, **change}]))
    before = _files(run_dir)
    assert main(["report", str(run_dir), "--import", str(src)]) == 2
    err = capsys.readouterr().err
    assert f"error: {path}: {what}" in err, err
    assert "Traceback" not in err
    assert _files(run_dir) == before


def test_a_malformed_mat_result_is_an_error_naming_the_file(run_dir, tmp_path, capsys):
    from scipy.io import savemat

    mats = tmp_path / "results_OPE"
    mats.mkdir()
    path = mats / "SquareA_BAD.mat"
    savemat(path, {"results": [{"res": np.arange(10.0), "type": "rect", "fps": "fast"}]})
    assert main(["report", str(run_dir), "--import", str(mats)]) == 2
    assert f"error: {path}: 'res' holds 10 numbers, not rows of 4" in capsys.readouterr().err
    savemat(path, {"results": [{"res": np.tile([31.0, 41, 28, 24], (12, 1)), "type": "rect", "fps": "fast"}]})
    assert main(["report", str(run_dir), "--import", str(mats)]) == 2
    assert f"error: {path}: 'fps' must be a number of frames per second >= 0, got 'fast'" in capsys.readouterr().err


def test_a_reimport_without_a_speed_drops_the_earlier_speed(run_dir, tmp_path, capsys):
    src = tmp_path / "OPE" / "THEIRS"
    src.mkdir(parents=True)
    (src / "SquareA.json").write_text(json.dumps([GOOD]))
    main(["report", str(run_dir), "--import", str(src)])
    summary = json.loads((run_dir / "report" / "summary.json").read_text())
    assert summary["trackers"]["THEIRS"]["fps"] == pytest.approx(20.0)
    (src / "SquareA.json").write_text(json.dumps([{k: v for k, v in GOOD.items() if k != "fps"}]))
    main(["report", str(run_dir), "--import", str(src)])
    capsys.readouterr()
    summary = json.loads((run_dir / "report" / "summary.json").read_text())
    assert summary["trackers"]["THEIRS"]["fps"] is None  # unknown, not the first import's 20
    assert not (run_dir / "results" / "THEIRS" / "times" / "SquareA_time.txt").exists()
    meta = json.loads((run_dir / "results" / "THEIRS" / "import.json").read_text())
    assert meta["sequences"]["SquareA"]["fps"] is None
