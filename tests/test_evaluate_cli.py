"""``smtmvt evaluate`` / ``smtmvt report`` end to end, including a run killed and restarted."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from smtmvt.cli import main
from smtmvt.evaluation.cli import parse_tracker_options
from test_runner import DEFAULT_SPECS, evaluate_cli, make_otb_dataset


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return make_otb_dataset(tmp_path_factory.mktemp("otb"), n_frames=15)


def result_files(run_dir) -> dict:
    return {p.relative_to(run_dir).as_posix(): p for p in sorted(Path(run_dir, "results").rglob("*.txt"))}


def test_evaluate_no_report(dataset, tmp_path, capsys):
    run_dir = tmp_path / "run"
    args = ["--trackers", "opencv-kcf,opencv-medianflow", "--no-report", "--quiet"]
    rc = evaluate_cli(dataset, run_dir, *args)
    out, err = capsys.readouterr()
    assert rc == 0, err
    assert "6 pair(s) run (90 frames)" in out and str(run_dir / "results") in out
    files = result_files(run_dir)
    assert len(files) == 12  # 6 result files + 6 times files
    assert all(len(p.read_text().splitlines()) == 15 for p in files.values())
    assert not (run_dir / "report").exists()
    # a second call finds everything done
    rc = evaluate_cli(dataset, run_dir, *args)
    out, _ = capsys.readouterr()
    assert rc == 0 and "0 pair(s) run" in out and "6 already done" in out


def test_evaluate_with_report_then_report_command(dataset, tmp_path, capsys):
    run_dir = tmp_path / "run"
    rc = main(
        [
            "evaluate",
            "--dataset",
            str(dataset),
            "--trackers",
            "opencv-csrt,opencv-kcf",
            "--out",
            str(run_dir),
            "--quiet",
            "--workers",
            "2",
        ]
    )
    out, err = capsys.readouterr()
    assert rc == 0, err
    report = run_dir / "report"
    assert (report / "table.md").is_file() and (report / "success.png").is_file()
    assert (report / "precision.png").is_file()
    assert f"report: {report / 'table.md'}" in out
    table = (report / "table.md").read_text()
    for name in ["opencv-csrt", "opencv-kcf", *DEFAULT_SPECS]:
        assert name in table
    summary = json.loads((report / "summary.json").read_text())
    assert summary["trackers"]["opencv-csrt"]["auc"] > 0.6  # it tracks the squares

    # `report` rebuilds from stored results without re-running anything
    stamps = {k: p.stat().st_mtime_ns for k, p in result_files(run_dir).items()}
    (report / "table.md").unlink()
    rc = main(["report", str(run_dir)])
    out, err = capsys.readouterr()
    assert rc == 0, err
    assert (report / "table.md").read_text() == table
    assert {k: p.stat().st_mtime_ns for k, p in result_files(run_dir).items()} == stamps


def test_unknown_tracker_exit_1_and_known_ones_run(dataset, tmp_path, capsys):
    run_dir = tmp_path / "run"
    rc = main(
        [
            "evaluate",
            "--dataset",
            str(dataset),
            "--trackers",
            "opencv-kcf,opencv-kfc",
            "--sequences",
            "SquareA",
            "--out",
            str(run_dir),
            "--no-report",
            "--quiet",
        ]
    )
    out, err = capsys.readouterr()
    assert rc == 1
    assert "unknown tracker 'opencv-kfc'" in err and "opencv-csrt" in err  # lists the names
    assert (run_dir / "results" / "opencv-kcf" / "SquareA.txt").is_file()
    assert "1 pair(s) run" in out


def test_bad_dataset_errors_name_file_and_line(dataset, tmp_path, capsys):
    root = make_otb_dataset(tmp_path / "bad", n_frames=8)
    gt = root / "SquareB" / "groundtruth_rect.txt"
    lines = gt.read_text().splitlines()
    lines[4] = "1;2;3;4"
    gt.write_text("\n".join(lines) + "\n")
    (root / "SquareC" / "img" / "0003.png").unlink()
    rc = main(
        ["evaluate", "--dataset", str(root), "--trackers", "opencv-kcf", "--out", str(tmp_path / "run"), "--quiet"]
    )
    out, err = capsys.readouterr()
    assert rc == 1
    assert f"{gt}, line 5" in err
    assert "0003.png" in err
    assert (tmp_path / "run" / "results" / "opencv-kcf" / "SquareA.txt").is_file()
    assert (tmp_path / "run" / "report" / "table.md").is_file()  # the report is still built


def test_whole_command_errors_exit_2(tmp_path, capsys):
    rc = main(
        ["evaluate", "--dataset", str(tmp_path / "missing"), "--trackers", "opencv-kcf", "--out", str(tmp_path / "run")]
    )
    err = capsys.readouterr().err
    assert rc == 2 and "smtmvt evaluate: error: dataset folder not found" in err
    rc = main(
        [
            "evaluate",
            "--dataset",
            str(tmp_path),
            "--trackers",
            "opencv-kcf",
            "--out",
            str(tmp_path / "r"),
            "--tracker-option",
            "opencv-kcf=1",
        ]
    )
    assert rc == 2 and "TRACKER:KEY=VALUE" in capsys.readouterr().err
    rc = main(["report", str(tmp_path / "no-run")])
    assert rc == 2 and "run folder not found" in capsys.readouterr().err


def test_tracker_options_and_max_frames(dataset, tmp_path, capsys):
    assert parse_tracker_options(["smtmvt:n_particles=200", "opencv-kcf:detect_thresh=0.2", "x:name=abc"]) == {
        "smtmvt": {"n_particles": 200},
        "opencv-kcf": {"detect_thresh": 0.2},
        "x": {"name": "abc"},
    }
    run_dir = tmp_path / "run"
    quick = ("--trackers", "opencv-kcf", "--max-frames", "6", "--no-report", "--quiet")
    rc = evaluate_cli(
        dataset, run_dir, *quick, "--sequences", "SquareC", "--tracker-option", "opencv-kcf:detect_thresh=0.3"
    )
    out, err = capsys.readouterr()
    assert rc == 0, err
    assert "not OTB-compliant" in out
    assert len((run_dir / "results" / "opencv-kcf" / "SquareC.txt").read_text().splitlines()) == 6
    assert json.loads((run_dir / "run.json").read_text())["max_frames"] == 6
    rc = evaluate_cli(dataset, run_dir, *quick, "--tracker-option", "opencv-kcf:nope=1")
    err = capsys.readouterr().err
    assert rc == 1 and err.count("unknown option 'nope'") == 1  # reported once, not per sequence


def _cli(root, run_dir, *extra):
    return [
        sys.executable,
        "-m",
        "smtmvt.cli",
        "evaluate",
        "--dataset",
        str(root),
        "--out",
        str(run_dir),
        "--no-report",
        "--quiet",
        *extra,
    ]


def _env():
    return dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1] / "src"))


def _squares(root, n=8, n_frames=30):
    return make_otb_dataset(
        root,
        n_frames=n_frames,
        specs={f"Seq{k}": dict(start=(20 + 5 * k, 30), step=(1.5, 0.5), side=(30, 28)) for k in range(n)},
    )


def test_killed_run_restarts_without_redoing_finished_pairs(tmp_path):
    """Kill `smtmvt evaluate` (SIGKILL) once some pairs are written; the restart skips them."""
    root = _squares(tmp_path / "otb")
    run_dir = tmp_path / "run"
    cmd, env = _cli(root, run_dir, "--trackers", "opencv-kcf"), _env()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    deadline = time.monotonic() + 120
    finished = {}
    while time.monotonic() < deadline and proc.poll() is None:
        finished = {k: p for k, p in result_files(run_dir).items() if "/times/" not in k}
        if len(finished) >= 2:
            break
        time.sleep(0.01)
    assert proc.poll() is None, f"the run ended before it could be killed: {proc.communicate()}"
    proc.send_signal(signal.SIGKILL)
    proc.wait(30)
    finished = {k: p for k, p in result_files(run_dir).items() if "/times/" not in k}
    assert 2 <= len(finished) < 8
    for p in finished.values():  # what is there is whole
        assert len(p.read_text().splitlines()) == 30
    stamps = {k: p.stat().st_mtime_ns for k, p in finished.items()}

    rc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=300)
    assert rc.returncode == 0, rc.stderr
    assert f"{len(finished)} already done" in rc.stdout
    after = {k: p for k, p in result_files(run_dir).items() if "/times/" not in k}
    assert len(after) == 8
    assert all(len(p.read_text().splitlines()) == 30 for p in after.values())
    assert {k: after[k].stat().st_mtime_ns for k in finished} == stamps  # not redone
    assert json.loads((run_dir / "errors.json").read_text()) == []


def test_evaluate_on_real_data(otb_dir, tmp_path, capsys):
    rc = main(
        [
            "evaluate",
            "--dataset",
            str(otb_dir),
            "--trackers",
            "opencv-kcf,opencv-csrt",
            "--sequences",
            "CarDark,Jumping",
            "--max-frames",
            "30",
            "--out",
            str(tmp_path / "run"),
            "--no-report",
            "--quiet",
        ]
    )
    out, err = capsys.readouterr()
    assert rc == 0, err
    gt_first = (otb_dir / "CarDark" / "groundtruth_rect.txt").read_text().splitlines()[0]
    res = (tmp_path / "run" / "results" / "opencv-csrt" / "CarDark.txt").read_text().splitlines()
    assert len(res) == 30
    assert [float(v) for v in res[0].split(",")] == [float(v) for v in gt_first.replace("\t", ",").split(",")]
    # Jumping is grayscale PNG: the peers get 3-channel BGR and still run
    assert len((tmp_path / "run" / "results" / "opencv-kcf" / "Jumping.txt").read_text().splitlines()) == 30


def test_report_imports_published_results(otb_dir, otb_results_dir, tmp_path, capsys):
    """`report --import` scores a published tracker's per-frame results on our sequences:
    Struck's OTB-2013 run averages 0.67 overlap on Crossing (data README)."""
    run_dir = tmp_path / "run"
    rc = main(
        [
            "evaluate",
            "--dataset",
            str(otb_dir),
            "--trackers",
            "opencv-kcf",
            "--sequences",
            "Crossing",
            "--out",
            str(run_dir),
            "--no-report",
            "--quiet",
        ]
    )
    assert rc == 0
    capsys.readouterr()
    rc = main(["report", str(run_dir), "--import", f"{otb_results_dir / 'OPE' / 'STRUCK'}:struck-2013"])
    out, err = capsys.readouterr()
    assert rc == 0, err
    assert "imported struck-2013" in out
    summary = json.loads((run_dir / "report" / "summary.json").read_text())
    crossing = summary["trackers"]["struck-2013"]["sequences"]["Crossing"]
    assert crossing["avg_overlap"] == pytest.approx(0.67, abs=0.01)
    assert "struck-2013" in (run_dir / "report" / "table.md").read_text()


def test_package_reexports_lazily():
    code = (
        "import sys, smtmvt.evaluation as e\n"
        "assert 'matplotlib' not in sys.modules\n"
        "from smtmvt.evaluation import build_report, import_into_run, score_sequence, run_evaluation\n"
        "assert build_report.__module__ == 'smtmvt.evaluation.report'\n"
        "assert set(e.__all__) <= set(dir(e))\n"
        "for name in e.__all__: getattr(e, name)\n"
        "print('ok')\n"
    )
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1] / "src"))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


# ----------------------------------------------------------------------------- issue 8: nothing lost, no orphans


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM])
def test_killing_the_driver_ends_its_workers(tmp_path, sig):
    """SIGKILL or SIGTERM of ``evaluate --workers 2``: no worker is left behind; SIGTERM stops
    the run like Ctrl-C (exit 128 + 15), and what was written is whole."""
    import psutil  # pinned in requirements.txt: a missing one fails

    root = _squares(tmp_path / "otb", n=6, n_frames=40)
    run_dir = tmp_path / "run"
    err_file = tmp_path / "stderr.txt"  # not a pipe: orphaned workers would hold it open
    with open(err_file, "w") as err_out:
        proc = subprocess.Popen(
            _cli(root, run_dir, "--trackers", "opencv-csrt,opencv-boosting", "--workers", "2"),
            stdout=subprocess.DEVNULL,
            stderr=err_out,
            env=_env(),
        )
    deadline, workers = time.monotonic() + 120, []
    while time.monotonic() < deadline and proc.poll() is None:
        workers = [
            p for p in psutil.Process(proc.pid).children(recursive=True) if "multiprocessing" in " ".join(p.cmdline())
        ]
        if len(workers) >= 2 and any(run_dir.glob("results/*/*.txt")):
            break
        time.sleep(0.05)
    assert proc.poll() is None and len(workers) >= 2, err_file.read_text()
    proc.send_signal(sig)
    rc = proc.wait(60)
    err = err_file.read_text()
    if sig == signal.SIGTERM:
        assert rc == 128 + signal.SIGTERM and "terminated" in err, err
    _, alive = psutil.wait_procs(workers, timeout=15)
    for p in alive:  # do not leave them behind for the next test
        p.kill()
    assert not alive, "workers outlived the driver"
    for p in run_dir.glob("results/*/*.txt"):
        assert len(p.read_text().splitlines()) == 40
    if sig == signal.SIGTERM:  # SIGKILL may leave a hidden temporary file: the next start removes it
        assert not list(run_dir.rglob("*.tmp"))
    assert isinstance(json.loads((run_dir / "errors.json").read_text()), list)


def test_a_second_command_on_a_run_folder_in_use_is_refused(dataset, tmp_path, capsys):
    """While a command holds a run folder (here: this test, as another evaluate would), a
    second one is refused at once and changes nothing; across processes see test_rundir."""
    from smtmvt.evaluation.rundir import RunDir

    run_dir = tmp_path / "run"
    with RunDir(run_dir).locked("smtmvt evaluate", create=True):
        rc = evaluate_cli(dataset, run_dir, "--trackers", "opencv-kcf", "--quiet")
    assert rc == 2
    assert f"{run_dir} is in use by smtmvt evaluate (pid {os.getpid()})" in capsys.readouterr().err
    assert sorted(p.name for p in run_dir.iterdir()) == [".lock"]


def test_evaluate_exits_1_when_the_report_has_gaps(dataset, tmp_path, capsys):
    run_dir = tmp_path / "run"
    args = ["evaluate", "--dataset", str(dataset), "--sequences", "SquareA", "--out", str(run_dir), "--quiet"]
    assert main([*args, "--trackers", "opencv-kcf,opencv-mosse"]) == 0
    (run_dir / "results" / "opencv-mosse" / "SquareA.txt").unlink()
    capsys.readouterr()
    assert main([*args, "--trackers", "opencv-kcf"]) == 1
    err = capsys.readouterr().err
    assert "opencv-mosse / SquareA: missing result file results/opencv-mosse/SquareA.txt" in err


def test_evaluate_refuses_another_frame_limit_on_a_run_folder(dataset, tmp_path, capsys):
    run_dir = tmp_path / "run"
    args = ["--trackers", "opencv-kcf", "--sequences", "SquareA", "--no-report", "--quiet"]
    assert evaluate_cli(dataset, run_dir, *args) == 0
    before = (run_dir / "results" / "opencv-kcf" / "SquareA.txt").read_text()
    capsys.readouterr()
    assert evaluate_cli(dataset, run_dir, *args, "--max-frames", "5") == 2
    assert f"{run_dir} was run with all frames" in capsys.readouterr().err
    assert (run_dir / "results" / "opencv-kcf" / "SquareA.txt").read_text() == before
    assert evaluate_cli(dataset, run_dir, *args, "--max-frames", "5", "--overwrite") == 0
    assert len((run_dir / "results" / "opencv-kcf" / "SquareA.txt").read_text().splitlines()) == 5


@pytest.mark.parametrize("option", ["--max-frames", "--workers", "--repeat"])
@pytest.mark.parametrize("value", ["0", "-1"])
def test_evaluate_numbers_must_be_positive(dataset, tmp_path, capsys, option, value):
    with pytest.raises(SystemExit) as info:
        evaluate_cli(dataset, tmp_path / "r", "--trackers", "opencv-kcf", option, value)
    assert info.value.code == 2
    assert f"{option}: expected a whole number >= 1, got {value!r}" in capsys.readouterr().err
    assert not (tmp_path / "r").exists()
