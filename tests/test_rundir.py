"""RunDir: the one owner of a run folder's paths, lock, settings and writes (issue 8)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from smtmvt.evaluation.rundir import RunDir, RunDirError, RunInfo, RunLockedError


def test_layout_of_a_run_folder(tmp_path):
    run = RunDir(tmp_path / "run")
    root = (tmp_path / "run").resolve()
    assert run.result_path("kcf", "Girl") == root / "results" / "kcf" / "Girl.txt"
    assert run.times_path("kcf", "Girl") == root / "results" / "kcf" / "times" / "Girl_time.txt"
    assert run.result_path("kcf", "Girl", repeat=2) == root / "results" / "kcf" / "repeat-2" / "Girl.txt"
    assert run.times_path("kcf", "Girl", repeat=2) == root / "results" / "kcf" / "repeat-2" / "times" / "Girl_time.txt"
    assert (run.run_json, run.errors_json, run.report_dir) == (root / "run.json", root / "errors.json", root / "report")
    assert not (tmp_path / "run").exists()  # constructing it does no I/O


@pytest.mark.parametrize("tracker", ["..", ".", "a/b", "", "/abs", ".hidden", "x y"])
def test_tracker_names_that_are_not_folder_names_are_refused(tmp_path, tracker):
    with pytest.raises(ValueError, match="invalid tracker name"):
        RunDir(tmp_path).result_path(tracker, "Girl")


@pytest.mark.parametrize("seq", ["../../x", "/abs/path/x", "a/b", "..", ".hidden", "", "a\\b"])
def test_sequence_names_that_are_not_file_names_are_refused(tmp_path, seq):
    with pytest.raises(ValueError, match="invalid sequence name"):
        RunDir(tmp_path).result_path("kcf", seq)


def test_writes_stay_inside_the_run(tmp_path):
    run = RunDir(tmp_path / "run")
    run.write_text("report/a.txt", "a")
    assert (tmp_path / "run" / "report" / "a.txt").read_text() == "a"
    for outside in (tmp_path / "x.txt", "../x.txt", tmp_path / "run" / ".." / "x.txt"):
        with pytest.raises(RunDirError, match="outside the run folder"):
            run.write_text(outside, "x")
    assert not (tmp_path / "x.txt").exists()
    # a folder inside the run that is a link (to anywhere) is not written through
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    os.symlink(elsewhere, tmp_path / "run" / "linked")
    with pytest.raises(RunDirError, match="symbolic link"):
        run.write_text("linked/a.txt", "x")
    assert list(elsewhere.iterdir()) == []
    # a link in place of a file is replaced, its target untouched
    target = tmp_path / "target.md"
    target.write_text("mine")
    os.symlink(target, tmp_path / "run" / "report" / "t.md")
    run.write_text("report/t.md", "report")
    assert target.read_text() == "mine"
    assert not (tmp_path / "run" / "report" / "t.md").is_symlink()


def test_result_files_are_read_strictly(tmp_path):
    run = RunDir(tmp_path)
    run.write_result("kcf", "Girl", np.zeros((3, 4)) + [0, 0, 5, 5], times=[0.1, 0.2, 0.3])
    assert run.result_problem("kcf", "Girl", 3) is None
    np.testing.assert_array_equal(run.read_result("kcf", "Girl"), [[1, 1, 5, 5]] * 3)  # 1-based as written
    np.testing.assert_allclose(run.read_times("kcf", "Girl"), [0.1, 0.2, 0.3])
    assert "3 lines for 4 frames" in run.result_problem("kcf", "Girl", 4)
    path = run.result_path("kcf", "Girl")
    path.write_text("1,1,5,5\n1,1,oops,5\n1,1,5,5\n")  # the right count, a corrupt line
    assert "line 2" in run.result_problem("kcf", "Girl", 3)
    path.write_text("1,1,5,5\n\n1,1,5,5\n1,1,5,5\n")  # a blank line would shift every later box
    assert "line 2" in run.result_problem("kcf", "Girl", 3)
    path.write_text("1,1,5,5\nNaN,NaN,NaN,NaN\n1,1,5,5\n")  # we never write a non-finite box
    assert "line 2" in run.result_problem("kcf", "Girl", 3)
    assert run.result_problem("kcf", "Nope", 3) == "missing"


def test_one_reader_of_run_json(tmp_path):
    run = RunDir(tmp_path)
    with pytest.raises(RunDirError, match="not a run folder"):
        run.info()
    run.run_json.write_text('{"dataset": "/d", "max_frames": 5, "note": "kept"}')
    info = run.info()
    assert (info.dataset, info.max_frames, info.repeat, info.extra) == ("/d", 5, 1, {"note": "kept"})
    run.save_info(info)
    assert json.loads(run.run_json.read_text())["note"] == "kept"
    run.run_json.write_text("{not json")
    with pytest.raises(RunDirError, match="run.json: not valid JSON"):
        run.info()
    run.run_json.write_text('{"max_frames": 0}')
    with pytest.raises(RunDirError, match="max_frames must be a whole number >= 1"):
        run.info()


def test_settle_keeps_one_frame_limit_and_repeat_count(tmp_path):
    run = RunDir(tmp_path / "run")
    ds = tmp_path
    info, _ = run.settle(ds, trackers=["a"], sequences=["S"], max_frames=None, repeat=None)
    assert (info.max_frames, info.repeat) == (None, 1)
    with pytest.raises(RunDirError, match=r"was run with all frames.*asks for --max-frames 5.*--overwrite"):
        run.settle(ds, trackers=["a"], sequences=["S"], max_frames=5, repeat=None)
    info, _ = run.settle(ds, trackers=["b"], sequences=["S"], max_frames=None, repeat=3)
    assert info.repeat == 3 and run.info().trackers == ["a", "b"]
    info, notes = run.settle(ds, trackers=["a"], sequences=["S"], max_frames=None, repeat=2)
    assert info.repeat == 2 and run.info().repeat == 3  # a smaller count: this command only
    assert any("holds 3 repeats" in n for n in notes)
    assert run.settle(ds, trackers=["a"], sequences=["S"], max_frames=None, repeat=None)[0].repeat == 3
    run.write_result("a", "S", np.ones((2, 4)))
    info, notes = run.settle(ds, trackers=["a"], sequences=["S"], max_frames=5, repeat=None, overwrite=True)
    assert info.max_frames == 5 and not run.results_dir.exists()
    assert any("--overwrite: removed 1" in n for n in notes)


def test_a_folder_with_results_but_no_run_json_is_not_taken_over(tmp_path):
    (tmp_path / "results" / "x").mkdir(parents=True)
    (tmp_path / "results" / "x" / "S.txt").write_text("1,1,1,1\n")
    with pytest.raises(RunDirError, match=r"is not a run folder \(no run.json\) and is not empty \(results\)"):
        RunDir(tmp_path).settle(tmp_path, trackers=["a"], sequences=["S"], max_frames=None, repeat=None)


def test_lock_gives_a_clear_error_to_a_second_command(tmp_path):
    run = RunDir(tmp_path / "run")
    with pytest.raises(FileNotFoundError, match="run folder not found"):
        with run.locked("smtmvt report"):
            pass
    assert not (tmp_path / "run").exists()  # nothing created for a report of no run
    with run.locked("smtmvt evaluate", create=True):
        with run.locked("nested"):  # re-entrant for the holder
            pass
        with pytest.raises(
            RunLockedError, match=rf"{tmp_path / 'run'} is in use by smtmvt evaluate \(pid {os.getpid()}\)"
        ):
            with RunDir(tmp_path / "run").locked("smtmvt report", create=True):
                pass
        code = (
            "import sys\nfrom smtmvt.evaluation.rundir import RunDir, RunLockedError\n"
            f"try:\n    RunDir({str(tmp_path / 'run')!r}).locked('x', create=True).__enter__()\n"
            "except RunLockedError as e:\n    print(e); sys.exit(3)\n"
        )
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
        assert out.returncode == 3 and "in use by smtmvt evaluate" in out.stdout
    with RunDir(tmp_path / "run").locked("again", create=True):  # released
        pass


def test_run_info_round_trip():
    info = RunInfo(dataset="/d", trackers=["a"], sequences=["S"], max_frames=4, repeat=2)
    assert RunInfo.from_json(info.to_json(), Path("run.json")) == info


def test_temporaries_of_a_killed_command_are_removed_on_the_next_start(tmp_path):
    run = RunDir(tmp_path / "run")
    run.settle(tmp_path, trackers=["a"], sequences=["S"], max_frames=None, repeat=None)
    stale = run.results_dir / "a" / ".S.txt.x1y2z3w4.tmp"  # what SIGKILL during a write leaves
    stale.parent.mkdir(parents=True)
    stale.write_text("1,1")
    _, notes = run.settle(tmp_path, trackers=["a"], sequences=["S"], max_frames=None, repeat=None)
    assert not stale.exists() and any("removed 1 temporary file" in n for n in notes)


# ----------------------------------------------------------------------------- issue 46: nothing lost


def _tree(root: Path) -> dict:
    """``{relative path: bytes}`` of every file under ``root`` (links as their target)."""
    return {
        p.relative_to(root).as_posix(): (os.readlink(p).encode() if p.is_symlink() else p.read_bytes())
        for p in sorted(root.rglob("*"))
        if p.is_file() or p.is_symlink()
    }


@pytest.mark.parametrize("create", [False, True])
def test_a_folder_that_is_not_a_run_is_refused_and_left_as_it_is(tmp_path, create):
    docs = tmp_path / "docs"  # a user's folder: a git work tree with hidden temporaries
    (docs / ".git" / "objects").mkdir(parents=True)
    (docs / ".git" / "objects" / ".pack.x1y2z3w4.tmp").write_text("git's")
    (docs / ".notes.txt.abcdefgh.tmp").write_text("an editor's")
    (docs / "notes.txt").write_text("mine")
    before = _tree(docs)
    run = RunDir(docs)
    with pytest.raises(RunDirError, match=rf"{docs} is not a run folder \(no run.json\) and is not empty"):
        if create:
            with run.locked("smtmvt evaluate", create=True):
                pass
        else:
            run.settle(tmp_path, trackers=["a"], sequences=["S"], max_frames=None, repeat=None)
    assert _tree(docs) == before and not (docs / ".lock").exists()


def test_a_new_or_empty_folder_or_one_left_before_run_json_becomes_a_run(tmp_path):
    for folder in (tmp_path / "new", tmp_path / "empty"):
        (tmp_path / "empty").mkdir(exist_ok=True)
        with RunDir(folder).locked("smtmvt evaluate", create=True) as run:
            run.settle(tmp_path, trackers=["a"], sequences=["S"], max_frames=None, repeat=None)
        assert RunDir(folder).info().trackers == ["a"]
    left = tmp_path / "left"  # a command killed after taking the lock, while writing run.json
    left.mkdir()
    (left / ".lock").write_text("smtmvt evaluate (pid 1)\n")
    (left / ".run.json.k1l2m3n4.tmp").write_text("{")
    with RunDir(left).locked("smtmvt evaluate", create=True) as run:
        _, notes = run.settle(tmp_path, trackers=["a"], sequences=["S"], max_frames=None, repeat=None)
    assert sorted(p.name for p in left.iterdir()) == [".lock", "run.json"]
    assert any("removed 1 temporary file" in n for n in notes)


def test_clean_up_touches_only_the_files_the_run_writes(tmp_path):
    run = RunDir(tmp_path / "run")
    run.settle(tmp_path, trackers=["a"], sequences=["S"], max_frames=None, repeat=None)
    run.write_result("a", "S", np.ones((2, 4)), times=[0.1, 0.2], repeat=1)
    ours = [  # what SIGKILL during a write of the run leaves
        run.root / ".errors.json.q1w2e3r4.tmp",
        run.root / ".run.json.q1w2e3r4.tmp",
        run.result_path("a", "S").parent / ".S.txt.q1w2e3r4.tmp",
        run.times_path("a", "S", 1).parent / ".S_time.txt.q1w2e3r4.tmp",
        run.report_dir / ".table.md.q1w2e3r4.tmp",
    ]
    theirs = [  # a user's own files in the run folder, or reached through a link in it
        run.root / ".notes.md.q1w2e3r4.tmp",
        run.root / "notes" / ".draft.q1w2e3r4.tmp",
        tmp_path / "elsewhere" / ".x.txt.q1w2e3r4.tmp",
    ]
    for p in ours + theirs:
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text("partial")
    os.symlink(tmp_path / "elsewhere", run.results_dir / "a" / "linked")
    _, notes = run.settle(tmp_path, trackers=["a"], sequences=["S"], max_frames=None, repeat=None)
    assert [p for p in ours if p.exists()] == []
    assert [p for p in theirs if not p.exists()] == []
    assert any(f"removed {len(ours)} temporary file" in n for n in notes)


def test_segment_files_of_tre_and_sre_runs(tmp_path):
    run = RunDir(tmp_path / "run")
    root = (tmp_path / "run").resolve()
    tre = root / "results" / "kcf" / "tre" / "Girl"
    assert run.result_path("kcf", "Girl", part=("tre", "seg-03")) == tre / "seg-03.txt"
    assert run.times_path("kcf", "Girl", part=("tre", "seg-03")) == tre / "times" / "seg-03_time.txt"
    assert run.record_path("kcf", "Girl", 2, part=("sre", "left")) == (
        root / "results" / "kcf" / "repeat-2" / "sre" / "Girl" / "meta" / "left.json"
    )
    with pytest.raises(ValueError, match="protocol 'ope' has no segments"):
        run.result_path("kcf", "Girl", part=("ope", "x"))
    with pytest.raises(ValueError, match="invalid sequence name"):
        run.result_path("kcf", "Girl", part=("tre", "../x"))
    run.write_result("kcf", "Girl", np.ones((3, 4)), np.ones(3), part=("tre", "seg-01"), record={"start": 4})
    assert run.result_problem("kcf", "Girl", 3, part=("tre", "seg-01")) is None
    assert "seg-01.txt: 3 lines for 2 frames of Girl tre seg-01" in run.result_problem(
        "kcf", "Girl", 2, part=("tre", "seg-01")
    )
    assert run.result_problem("kcf", "Girl", 3) == "missing"  # the OPE file is another file
    assert run.read_record("kcf", "Girl", part=("tre", "seg-01")) == {"start": 4}


def test_errors_are_kept_per_part_and_run_json_keeps_its_protocols(tmp_path):
    run = RunDir(tmp_path / "run")
    run.root.mkdir()
    log = run.errors()
    log.set("kcf", "Girl", "boom", 0, "tre/seg-02")
    log.set("kcf", "Girl", "bang", 0, "tre/seg-05")
    log.set("kcf", "Girl", "ope", 0)
    log.clear("kcf", "Girl", 0, "tre/seg-02")
    entries = json.loads(run.errors_json.read_text())
    assert entries == [
        {"tracker": "kcf", "sequence": "Girl", "repeat": 0, "error": "bang", "part": "tre/seg-05"},
        {"tracker": "kcf", "sequence": "Girl", "repeat": 0, "error": "ope"},
    ]
    assert run.errors().as_list() == entries  # read back as written
    run = RunDir(tmp_path / "run2")
    info, _ = run.settle(tmp_path, trackers=["a"], sequences=["S"], max_frames=None, repeat=None, protocols=["tre"])
    assert info.protocols == ["tre"]  # a new folder holds this command's only
    run.settle(tmp_path, trackers=["a"], sequences=["S"], max_frames=None, repeat=None, protocols=["sre", "ope"])
    assert run.info().protocols == ["ope", "tre", "sre"]
    run.run_json.write_text('{"dataset": "/d"}')
    assert run.info().protocols == ["ope"]  # a run made before TRE and SRE
    run.run_json.write_text('{"protocols": ["ope", "xre"]}')
    with pytest.raises(RunDirError, match="protocols must be among ope, tre, sre"):
        run.info()
