"""What a run folder knows about itself (issue 46): whether a folder is a run at all, the
settings each tracker's results were made with, and what each result started from; and
that killing ``evaluate`` at any moment loses nothing and changes nothing outside the run.

Data: the small synthetic OTB folders of :func:`test_runner.make_otb_dataset` (tests that
edit a ground truth make their own copy).
"""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import cv2
import numpy as np
import pytest

from smtmvt import __version__
from smtmvt.cli import main
from smtmvt.evaluation import make_tracker, register_tracker, run_evaluation, sequence_seed, unregister_tracker
from smtmvt.evaluation.rundir import RunDir
from test_repeat import Jitter
from test_runner import evaluate_cli, make_otb_dataset

KCF = ("--trackers", "opencv-kcf", "--no-report", "--quiet")


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return make_otb_dataset(tmp_path_factory.mktemp("otb"), n_frames=12)


def result_texts(run_dir) -> dict:
    """``{relative path: text}`` of every result file (not times, not records)."""
    results = Path(run_dir) / "results"
    return {
        p.relative_to(results).as_posix(): p.read_text()
        for p in sorted(results.rglob("*.txt"))
        if "times" not in p.parts
    }


def snapshot(root) -> dict:
    """``{relative path: bytes}`` of every file under ``root`` (None for folders)."""
    root = Path(root)
    return {p.relative_to(root).as_posix(): (p.read_bytes() if p.is_file() else None) for p in sorted(root.rglob("*"))}


def shift_first_box(dataset: Path, seq: str, dx: int) -> str:
    """Move ``seq``'s first ground-truth box ``dx`` pixels right; the new first line."""
    gt = dataset / seq / "groundtruth_rect.txt"
    lines = gt.read_text().splitlines()
    x, y, w, h = (int(v) for v in lines[0].split(","))
    lines[0] = f"{x + dx},{y},{w},{h}"
    gt.write_text("\n".join(lines) + "\n")
    return lines[0]


# ----------------------------------------------------------------------------- fault 1: a folder that is not a run


@pytest.mark.parametrize("trackers", ["nope", "opencv-kcf"])
def test_evaluate_refuses_a_folder_that_is_not_a_run_and_changes_nothing(dataset, tmp_path, capsys, trackers):
    """``--out`` at a user's folder (a git work tree with hidden temporaries): exit 2, one
    clear error, not a byte changed there, even when no tracker name is valid."""
    docs = tmp_path / "docs"
    (docs / ".git" / "objects").mkdir(parents=True)
    (docs / ".git" / "objects" / ".pack.a1b2c3d4.tmp").write_text("git's")
    (docs / ".draft.md.a1b2c3d4.tmp").write_text("an editor's")
    (docs / "notes.txt").write_text("mine")
    before = snapshot(docs)
    rc = evaluate_cli(dataset, docs, "--trackers", trackers, "--no-report", "--quiet")
    out, err = capsys.readouterr()
    assert rc == 2
    assert f"error: {docs} is not a run folder (no run.json) and is not empty" in err
    assert "removed" not in out + err
    assert snapshot(docs) == before


# ----------------------------------------------------------------------------- fault 2: one tracker, one setting


def test_other_tracker_options_on_a_run_are_refused_unless_overwrite(dataset, tmp_path, capsys):
    run_dir = tmp_path / "run"
    assert (
        evaluate_cli(
            dataset, run_dir, *KCF, "--sequences", "SquareA", "--tracker-option", "opencv-kcf:detect_thresh=0.3"
        )
        == 0
    )
    before = snapshot(run_dir / "results")
    capsys.readouterr()
    for other in (["--tracker-option", "opencv-kcf:detect_thresh=0.2"], []):  # another value, or none
        assert evaluate_cli(dataset, run_dir, *KCF, *other) == 2
        err = capsys.readouterr().err
        assert f"error: {run_dir}: results/opencv-kcf was made with other settings than this command's" in err
        assert f"options.detect_thresh: 0.3 -> {'0.2' if other else '(unset)'}" in err
        assert "--overwrite to discard the results of opencv-kcf" in err
        assert snapshot(run_dir / "results") == before  # nothing run, nothing lost
    recorded = json.loads((run_dir / "run.json").read_text())["tracker_settings"]["opencv-kcf"]
    assert recorded["options"] == {"detect_thresh": 0.3}
    assert recorded["versions"] == {"smtmvt": __version__, "opencv": cv2.__version__}
    # the same options resume it; other trackers of the run are not affected
    assert evaluate_cli(dataset, run_dir, *KCF, "--tracker-option", "opencv-kcf:detect_thresh=0.3") == 0
    assert "1 already done" in capsys.readouterr().out
    assert evaluate_cli(dataset, run_dir, "--trackers", "opencv-mosse", "--no-report", "--quiet") == 0
    # --overwrite discards that tracker's results (only) and recomputes them with the new options
    mosse = (run_dir / "results" / "opencv-mosse" / "SquareA.txt").read_text()
    capsys.readouterr()
    assert evaluate_cli(dataset, run_dir, *KCF, "--tracker-option", "opencv-kcf:detect_thresh=0.2", "--overwrite") == 0
    out = capsys.readouterr().out
    assert "3 pair(s) run" in out and "removed 6 result/times file(s) of opencv-kcf" in out
    settings = json.loads((run_dir / "run.json").read_text())["tracker_settings"]
    assert settings["opencv-kcf"]["options"] == {"detect_thresh": 0.2} and "opencv-mosse" in settings
    assert (run_dir / "results" / "opencv-mosse" / "SquareA.txt").read_text() == mosse


def test_the_settings_record_holds_the_resolved_configuration():
    from smtmvt.evaluation.settings import settings_difference, tracker_settings

    default = tracker_settings(make_tracker("smtmvt", seed=0), {})
    small = tracker_settings(make_tracker("smtmvt", seed=0, n_particles=200), {"n_particles": 200, "seed": 3})
    assert default["tracker"] == "smtmvt.evaluation.trackers.SmtmvtAdapter"
    assert (default["config"]["n_particles"], small["config"]["n_particles"]) == (400, 200)
    assert "seed" not in default["config"]  # each pair has its own; the base seed is an option
    assert default["versions"] == {"smtmvt": __version__}
    assert json.loads(json.dumps(small)) == small  # what run.json gives back compares equal
    why = settings_difference(default, small)
    assert "config.n_particles: 400 -> 200" in why and "options.seed: (unset) -> 3" in why
    assert settings_difference(small, json.loads(json.dumps(small))) is None
    kcf = tracker_settings(make_tracker("opencv-kcf"), {})
    assert kcf["config"] is None and kcf["versions"]["opencv"] == cv2.__version__


def test_results_of_unknown_settings_are_refused_and_still_reported(dataset, tmp_path, capsys):
    """A run folder made before settings were recorded: its report still builds; evaluate
    does not add results of known settings to results of unknown ones (the safe choice)."""
    run_dir = tmp_path / "run"
    args = ("--trackers", "opencv-kcf", "--sequences", "SquareA", "--quiet")
    assert evaluate_cli(dataset, run_dir, *args) == 0
    info = json.loads((run_dir / "run.json").read_text())
    del info["tracker_settings"]
    (run_dir / "run.json").write_text(json.dumps(info))
    for record in (run_dir / "results").rglob("meta"):
        for p in record.iterdir():
            p.unlink()
        record.rmdir()
    before = snapshot(run_dir / "results")
    assert main(["report", str(run_dir)]) == 0
    capsys.readouterr()
    assert evaluate_cli(dataset, run_dir, *args) == 2
    err = capsys.readouterr().err
    assert "results/opencv-kcf holds results made before run folders recorded tracker settings" in err
    assert snapshot(run_dir / "results") == before
    assert evaluate_cli(dataset, run_dir, *args, "--overwrite") == 0
    assert "opencv-kcf" in json.loads((run_dir / "run.json").read_text())["tracker_settings"]


# ----------------------------------------------------------------------------- fault 3: what a result started from


def test_a_changed_first_box_is_recomputed_not_already_done(tmp_path, capsys):
    ds = make_otb_dataset(tmp_path / "otb", n_frames=12)
    run_dir = tmp_path / "run"
    args = ("--trackers", "opencv-kcf,opencv-mosse", "--no-report", "--quiet")
    assert evaluate_cli(ds, run_dir, *args) == 0
    first = (ds / "SquareB" / "groundtruth_rect.txt").read_text().splitlines()[0]
    before = result_texts(run_dir)
    corrected = shift_first_box(ds, "SquareB", 4)
    capsys.readouterr()
    assert evaluate_cli(ds, run_dir, *args) == 0
    out = capsys.readouterr().out
    assert "2 pair(s) run" in out and "4 already done" in out
    assert (
        f"note: results/opencv-kcf/SquareB.txt: SquareB's first ground-truth box is now {corrected}; "
        f"the result started from {first}; recomputing"
    ) in out
    after = result_texts(run_dir)
    for tracker in ("opencv-kcf", "opencv-mosse"):
        assert after[f"{tracker}/SquareB.txt"].splitlines()[0] == corrected
    assert {k: v for k, v in after.items() if "SquareB" not in k} == {
        k: v for k, v in before.items() if "SquareB" not in k
    }
    fresh = tmp_path / "fresh"  # what an uninterrupted run on the corrected data gives
    assert evaluate_cli(ds, fresh, *args) == 0
    assert result_texts(fresh) == after
    record = json.loads((run_dir / "results" / "opencv-kcf" / "meta" / "SquareB.json").read_text())
    assert record["first_box"] == [float(v) for v in corrected.split(",")]
    assert (record["n_frames"], record["sequence_frames"], record["seed"]) == (12, 12, sequence_seed("SquareB"))


def test_a_changed_frame_count_is_recomputed_under_a_frame_limit(tmp_path, capsys):
    ds = make_otb_dataset(tmp_path / "otb", n_frames=12)
    run_dir = tmp_path / "run"
    args = (*KCF, "--max-frames", "8")
    assert evaluate_cli(ds, run_dir, *args) == 0
    for k in (11, 12):  # SquareC re-extracted with 10 frames: still more than 8
        (ds / "SquareC" / "img" / f"{k:04d}.png").unlink()
    gt = ds / "SquareC" / "groundtruth_rect.txt"
    gt.write_text("\n".join(gt.read_text().splitlines()[:10]) + "\n")
    capsys.readouterr()
    assert evaluate_cli(ds, run_dir, *args) == 0
    out = capsys.readouterr().out
    assert "1 pair(s) run" in out and "2 already done" in out
    assert "results/opencv-kcf/SquareC.txt: SquareC now has 10 frames; the result was made when it had 12" in out
    assert (
        json.loads((run_dir / "results" / "opencv-kcf" / "meta" / "SquareC.json").read_text())["sequence_frames"] == 10
    )


def test_a_result_without_its_record_is_checked_by_its_first_line(tmp_path):
    """A command killed between writing a result and its record leaves a result without a
    record: its first line is the first box it started from."""
    ds = make_otb_dataset(tmp_path / "otb", n_frames=12)
    run_dir = tmp_path / "run"

    def run():
        return run_evaluation(ds, ["opencv-kcf"], run_dir, sequences=["SquareA"], progress=False, report=False)

    run()
    record = RunDir(run_dir).record_path("opencv-kcf", "SquareA")
    written = record.read_text()
    record.unlink()
    assert run().skipped == [("opencv-kcf", "SquareA")]
    assert record.read_text() == written  # written again, as an uninterrupted run has it
    record.unlink()
    shift_first_box(ds, "SquareA", -3)
    again = run()
    assert again.done == [("opencv-kcf", "SquareA")] and record.is_file()
    assert any("SquareA's first ground-truth box is now" in n for n in again.notes)


def test_every_repeat_of_a_changed_sequence_is_recomputed(tmp_path):
    register_tracker("test-jitter", Jitter, replace=True)
    try:
        ds = make_otb_dataset(tmp_path / "otb", n_frames=12)
        run_dir = tmp_path / "run"

        def run():
            return run_evaluation(ds, ["test-jitter"], run_dir, repeat=2, progress=False, report=False)

        assert len(run().done) == 6
        shift_first_box(ds, "SquareC", 2)
        again = run()
        assert sorted(again.done) == [("test-jitter", "SquareC"), ("test-jitter", "SquareC", 1)]
        assert len(again.skipped) == 4
        assert json.loads(RunDir(run_dir).record_path("test-jitter", "SquareC", 1).read_text())["seed"] == (
            sequence_seed("SquareC", 0, 1)
        )
        assert np.isfinite(RunDir(run_dir).read_result("test-jitter", "SquareC", 1, 12)).all()
    finally:
        unregister_tracker("test-jitter")


# ----------------------------------------------------------------------------- fault injection


_EXIT = {  # what a killed evaluate may return: its own code, or the signal's before its handlers exist
    signal.SIGKILL: {-signal.SIGKILL},
    signal.SIGINT: {130, -signal.SIGINT},
    signal.SIGTERM: {143, -signal.SIGTERM},
}


def _evaluate_command(dataset: Path, run_dir: Path) -> list[str]:
    src = Path(__file__).resolve().parents[1] / "src"
    return [
        sys.executable,
        "-c",
        f"import sys; sys.path.insert(0, {str(src)!r}); from smtmvt.cli import main; sys.exit(main())",
        "evaluate",
        "--dataset",
        str(dataset),
        "--out",
        str(run_dir),
        "--trackers",
        "opencv-kcf,opencv-mosse",
        "--no-report",
        "--quiet",
    ]


def _outside(root: Path, runs: Path) -> dict:
    """``{path: (bytes, mtime_ns, mode)}`` of every file under ``root`` but outside ``runs``."""
    return {
        p: (p.read_bytes(), p.stat().st_mtime_ns, p.stat().st_mode)
        for p in sorted(root.rglob("*"))
        if p.is_file() and runs not in p.parents
    }


def _run_files(run_dir: Path) -> dict:
    """``{relative path: bytes}`` of a run folder, times files (seconds: never the same) and
    the lock (it names the pid) left out."""
    return {k: v for k, v in snapshot(run_dir).items() if "/times/" not in k and k != ".lock"}


def _kill_at_a_random_moment(proc, run_dir: Path, sig, rng: random.Random, duration: float) -> None:
    """Send ``sig`` to ``proc`` at a moment drawn from ``rng``: a time after its start
    (``duration``: an uninterrupted run's), or just after its n-th result file appears.
    Both land while it works: the time within the first half of the reference run's (a
    run on a machine less loaded than the reference's can take half as long), the n-th
    file before the last of the 8."""
    target = rng.randint(1, 7)
    if rng.random() < 0.4 or len(list(run_dir.glob("results/*/*.txt"))) >= target:
        time.sleep(rng.uniform(0.05, 0.5) * duration)
    else:
        deadline = time.monotonic() + 3 * duration
        while proc.poll() is None and time.monotonic() < deadline:
            if len(list(run_dir.glob("results/*/*.txt"))) >= target:
                break
            time.sleep(0.002)
        time.sleep(rng.uniform(0.0, 0.02))
    proc.send_signal(sig)


def test_evaluate_killed_at_random_moments_resumes_to_the_uninterrupted_results(tmp_path):
    """SIGKILL, SIGINT or SIGTERM at moments drawn from a fixed seed (10 kills over 6 runs,
    some killed again while resuming): each resumed run's folder is byte for byte the
    uninterrupted one's (times files aside), what was written before a kill is kept, not
    redone, and no file outside the run folder (the dataset, a user's hidden temporaries
    beside it) is touched."""
    specs = {f"Seq{k}": dict(start=(12 + 4 * k, 20), step=(1.0, 0.5), side=(24, 22)) for k in range(4)}
    dataset = make_otb_dataset(tmp_path / "otb", specs=specs, n_frames=30, size=(80, 100))
    (dataset / ".notes.txt.a1b2c3d4.tmp").write_text("a user's")
    (tmp_path / ".draft.md.a1b2c3d4.tmp").write_text("a user's")
    runs = tmp_path / "runs"
    runs.mkdir()
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    t0 = time.perf_counter()
    reference = subprocess.run(_evaluate_command(dataset, runs / "reference"), env=env, capture_output=True, text=True)
    duration = time.perf_counter() - t0
    assert reference.returncode == 0, reference.stderr
    expected = _run_files(runs / "reference")
    assert len([k for k in expected if k.endswith(".txt")]) == 8
    outside = _outside(tmp_path, runs)

    rng = random.Random(46)
    plan = [[rng.choice(list(_EXIT)) for _ in range(n)] for n in (1, 2, 1, 2, 1, 3)]
    interrupted = 0
    for k, signals in enumerate(plan):
        run_dir = runs / f"run-{k}"
        for sig in signals:
            cmd = _evaluate_command(dataset, run_dir)
            proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            _kill_at_a_random_moment(proc, run_dir, sig, rng, duration)
            _, err = proc.communicate(timeout=60)
            assert proc.returncode in _EXIT[sig] | {0}, (sig, proc.returncode, err.decode())
            interrupted += proc.returncode != 0
            kept = {k: v for k, v in _run_files(run_dir).items() if k.endswith(".txt")} if run_dir.is_dir() else {}
            assert all(expected[k] == v for k, v in kept.items())  # what is there is whole and right
        results = [p for p in run_dir.rglob("*.txt") if "times" not in p.parts] if run_dir.is_dir() else []
        stamps = {p: p.stat().st_mtime_ns for p in results}  # a times file without its result is redone
        resumed = subprocess.run(_evaluate_command(dataset, run_dir), env=env, capture_output=True, text=True)
        assert resumed.returncode == 0, resumed.stderr
        assert _run_files(run_dir) == expected, f"run {k} after {signals}"
        assert {p: p.stat().st_mtime_ns for p in stamps} == stamps  # kept, not redone
        assert _outside(tmp_path, runs) == outside
    assert interrupted >= len(plan)  # most kills landed while the command was working


# ----------------------------------------------------------------------------- a field added later


def test_an_experimental_option_at_its_default_is_the_settings_of_before_it_existed():
    """A record that lacks an experimental option and one that holds it at its default (off)
    are the same settings; one set, or any other field missing, is a difference."""
    from smtmvt.evaluation.settings import settings_difference, tracker_settings

    now = tracker_settings(make_tracker("smtmvt", seed=0), {})
    before = json.loads(json.dumps(now))
    del before["config"]["scale_filter"]  # experimental, default 0
    assert settings_difference(before, now) is None
    filtered = tracker_settings(make_tracker("smtmvt", seed=0, scale_filter=0.5), {"scale_filter": 0.5})
    assert "config.scale_filter: (unset) -> 0.5" in settings_difference(before, filtered)
    del before["config"]["camera_motion"]  # not experimental: its absence is a difference
    assert settings_difference(before, now) == "config.camera_motion: (unset) -> true"


def test_an_option_at_its_neutral_value_is_the_settings_of_before_it_existed():
    """``report_read_size`` declares 0 neutral (the reported box as before it): the paper's
    tracker (0) matches a record made before the field; the default (4) does not."""
    from smtmvt.evaluation.settings import settings_difference, tracker_settings

    paper = tracker_settings(make_tracker("smtmvt-paper", seed=0), {})
    before = json.loads(json.dumps(paper))
    del before["config"]["report_read_size"]
    assert settings_difference(before, paper) is None
    default = tracker_settings(make_tracker("smtmvt", seed=0), {})
    before = json.loads(json.dumps(default))
    del before["config"]["report_read_size"]
    assert settings_difference(before, default) == "config.report_read_size: (unset) -> 4"


def test_a_run_made_before_an_experimental_option_resumes_and_keeps_its_record(tmp_path, capsys):
    """A folder whose record and result records predate an experimental option: the same
    command finds its results done (nothing recomputed) and leaves run.json's record as it
    was; a record that lacks a field that is not experimental is refused as before."""
    from smtmvt.evaluation.settings import settings_digest

    ds = make_otb_dataset(tmp_path / "otb", n_frames=6)
    run_dir = tmp_path / "run"
    args = ("--trackers", "smtmvt", "--sequences", "SquareA", "--tracker-option", "smtmvt:n_particles=20")
    assert evaluate_cli(ds, run_dir, *args, "--no-report", "--quiet") == 0

    def backdate(field: str) -> None:
        """Rewrite the folder as a version without ``field`` would have written it."""
        info = json.loads((run_dir / "run.json").read_text())
        record = info["tracker_settings"]["smtmvt"]
        del record["config"][field]
        (run_dir / "run.json").write_text(json.dumps(info))
        for meta in (run_dir / "results" / "smtmvt").rglob("meta/*.json"):
            m = json.loads(meta.read_text())
            meta.write_text(json.dumps({**m, "settings": settings_digest(record)}))

    backdate("scale_filter")
    stored = json.loads((run_dir / "run.json").read_text())["tracker_settings"]["smtmvt"]
    before = result_texts(run_dir)
    capsys.readouterr()
    assert evaluate_cli(ds, run_dir, *args, "--no-report") == 0
    out = capsys.readouterr().out
    assert "1 already done" in out and "recomputing" not in out
    assert result_texts(run_dir) == before
    assert json.loads((run_dir / "run.json").read_text())["tracker_settings"]["smtmvt"] == stored

    backdate("camera_motion")
    assert evaluate_cli(ds, run_dir, *args, "--no-report", "--quiet") == 2
    assert "config.camera_motion: (unset) -> true" in capsys.readouterr().err
    assert result_texts(run_dir) == before
