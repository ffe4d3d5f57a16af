"""The OPE runner: run folder layout, resume, crashes, bad input, parallel and Dask runs.

Data: small synthetic OTB folders (a textured square moving over blurred noise, PNG frames,
1-based comma ground truth) built in tmp folders by :func:`make_otb_dataset`.
"""

from __future__ import annotations

import functools
import json
import os
from pathlib import Path

import cv2
import numpy as np
import pytest

from smtmvt.data import open_otb_sequence, read_boxes
from smtmvt.evaluation import (
    OpenCVTracker,
    make_tracker,
    register_tracker,
    result_path,
    run_evaluation,
    sequence_seed,
    times_path,
    unregister_tracker,
)

DEFAULT_SPECS = {
    "SquareA": dict(start=(30, 40), step=(2.0, 1.0), side=(28, 24)),
    "SquareB": dict(start=(90, 40), step=(-2.0, 1.5), side=(26, 30)),
    "SquareC": dict(start=(50, 60), step=(1.0, -1.0), side=(32, 32)),
}


def make_otb_dataset(root, specs=None, n_frames=20, size=(120, 160), seed=0) -> Path:
    """OTB folder ``root/<Seq>/img/0001.png...`` + ``groundtruth_rect.txt`` (1-based x,y,w,h)."""
    specs = specs or DEFAULT_SPECS
    root = Path(root)
    rng = np.random.default_rng(seed)
    h, w = size
    for name, spec in specs.items():
        bg = cv2.GaussianBlur(rng.integers(0, 256, (h, w, 3)).astype(np.uint8), (0, 0), 3)
        bg = cv2.normalize(bg, np.empty_like(bg), 40, 160, cv2.NORM_MINMAX)
        tw, th = spec["side"]
        coarse = rng.integers(0, 256, (th // 4 + 1, tw // 4 + 1, 3)).astype(np.uint8)
        tex = cv2.resize(coarse, (tw, th), interpolation=cv2.INTER_NEAREST)
        tex[..., 0] = np.maximum(tex[..., 0], 150)
        img = root / name / "img"
        img.mkdir(parents=True, exist_ok=True)
        lines = []
        for i in range(spec.get("n", n_frames)):
            x = int(round(spec["start"][0] + spec["step"][0] * i))
            y = int(round(spec["start"][1] + spec["step"][1] * i))
            f = bg.copy()
            f[y : y + th, x : x + tw] = tex
            cv2.imwrite(str(img / f"{i + 1:04d}.png"), cv2.cvtColor(f, cv2.COLOR_RGB2BGR))
            lines.append(f"{x + 1},{y + 1},{tw},{th}")
        (root / name / "groundtruth_rect.txt").write_text("\n".join(lines) + "\n")
    return root


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return make_otb_dataset(tmp_path_factory.mktemp("otb"))


def read_result_texts(run_dir) -> dict:
    """``{(tracker, seq): text}`` of every result and times file... results only."""
    out = {}
    for p in sorted((Path(run_dir) / "results").glob("*/*.txt")):
        out[(p.parent.name, p.stem)] = p.read_text()
    return out


def errors_of(run_dir) -> list:
    return json.loads((Path(run_dir) / "errors.json").read_text())


# ----------------------------------------------------------------------------- test trackers


class ConstantVelocity:
    """Deterministic toy tracker: moves the box by a fixed step per frame."""

    def __init__(self, step=(1.0, 0.5), seed=None):
        self.step = step
        self.seed = seed

    def init(self, frame, box):
        assert frame.dtype == np.uint8 and frame.ndim == 3  # RGB frames reach the adapter
        self.box = np.array(box, float)

    def update(self, frame):
        self.box[:2] += self.step
        return tuple(self.box)


class Recorder(ConstantVelocity):
    """ConstantVelocity that logs (sequence-first-box, seed) of every init, in-process only."""

    calls: list = []

    def init(self, frame, box):
        super().init(frame, box)
        Recorder.calls.append((tuple(box), self.seed))


class CrashAt(ConstantVelocity):
    """Raises in ``update`` at frame ``frame`` when the first box is ``box``."""

    def __init__(self, first_box, frame, seed=None):
        super().__init__(seed=seed)
        self.first_box, self.frame = tuple(first_box), frame

    def init(self, frame, box):
        super().init(frame, box)
        self.i = 0
        self.armed = tuple(box) == self.first_box

    def update(self, frame):
        self.i += 1
        if self.armed and self.i == self.frame:
            raise RuntimeError("simulated tracker bug")
        return super().update(frame)


class DieAt(CrashAt):
    """Ends its process (as a segfault would) in ``update`` at frame ``frame`` of the sequence
    whose first box is ``first_box``."""

    def update(self, frame):
        self.i += 1
        if self.armed and self.i == self.frame:
            os._exit(3)
        return ConstantVelocity.update(self, frame)


@pytest.fixture
def registered():
    """Register test trackers; unregistered afterwards."""
    names = []

    def add(name, factory):
        register_tracker(name, factory, replace=True)
        names.append(name)

    yield add
    for n in names:
        unregister_tracker(n)


def first_box_of(dataset, seq):
    return open_otb_sequence(Path(dataset) / seq).first_box


# ----------------------------------------------------------------------------- layout


def test_run_writes_the_agreed_layout(dataset, tmp_path, registered):
    registered("test-cv", ConstantVelocity)
    run = run_evaluation(dataset, ["test-cv", "opencv-kcf"], tmp_path / "run", progress=False, report=False)
    assert run.ok and not run.errors
    assert sorted(run.done) == sorted((t, s) for t in ["test-cv", "opencv-kcf"] for s in DEFAULT_SPECS)
    assert run.frames == 2 * 3 * 20
    for tracker in ["test-cv", "opencv-kcf"]:
        for seq in DEFAULT_SPECS:
            rp, tp = result_path(run.run_dir, tracker, seq), times_path(run.run_dir, tracker, seq)
            assert rp == tmp_path / "run" / "results" / tracker / f"{seq}.txt"
            assert tp == tmp_path / "run" / "results" / tracker / "times" / f"{seq}_time.txt"
            lines = rp.read_text().splitlines()
            gt_lines = (dataset / seq / "groundtruth_rect.txt").read_text().splitlines()
            assert len(lines) == 20
            assert lines[0] == gt_lines[0]  # frame 1 is the ground truth, 1-based as in the file
            times = np.loadtxt(tp)
            assert times.shape == (20,) and (times >= 0).all()
    # 1-based on disk: the toy tracker's frame k box is first + k * step
    first = first_box_of(dataset, "SquareA")
    boxes = read_boxes(result_path(run.run_dir, "test-cv", "SquareA"))  # 0-based
    np.testing.assert_allclose(boxes[5], np.array(first) + [5.0, 2.5, 0, 0])
    info = json.loads((tmp_path / "run" / "run.json").read_text())
    assert info["dataset"] == str(Path(dataset).resolve())
    assert info["trackers"] == ["test-cv", "opencv-kcf"]
    assert info["sequences"] == list(DEFAULT_SPECS)
    assert info["attributes"] is None and info["published"] is None
    assert errors_of(tmp_path / "run") == []
    assert not list((tmp_path / "run").rglob("*.tmp"))


def test_results_equal_driving_the_adapter_directly(dataset, tmp_path):
    run = run_evaluation(dataset, "opencv-csrt", tmp_path / "run", sequences="SquareB", progress=False, report=False)
    seq = open_otb_sequence(dataset / "SquareB")
    t = make_tracker("opencv-csrt", seed=sequence_seed("SquareB"))
    t.init(seq[0], seq.first_box)
    expected = [seq.first_box] + [t.update(seq[i]) for i in range(1, len(seq))]
    np.testing.assert_allclose(read_boxes(result_path(run.run_dir, "opencv-csrt", "SquareB")), expected)
    # and it tracks: mean IoU against the ground truth
    from smtmvt.evaluation.metrics import overlap_ratio

    assert overlap_ratio(np.array(expected), seq.groundtruth).mean() > 0.85


def test_seeds_per_sequence_are_deterministic(dataset, tmp_path, registered):
    registered("test-rec", Recorder)
    Recorder.calls.clear()
    run_evaluation(dataset, ["test-rec"], tmp_path / "a", progress=False, report=False)
    run_evaluation(dataset, ["test-rec"], tmp_path / "b", progress=False, report=False)
    seeds = [s for _, s in Recorder.calls]
    assert seeds[:3] == seeds[3:]
    assert sorted(seeds[:3]) == sorted(sequence_seed(s) for s in DEFAULT_SPECS)
    assert len(set(seeds[:3])) == 3
    # a base seed in the tracker options shifts every sequence's seed
    Recorder.calls.clear()
    run_evaluation(
        dataset,
        ["test-rec"],
        tmp_path / "c",
        sequences=["SquareA"],
        progress=False,
        report=False,
        tracker_options={"test-rec": {"seed": 7, "step": (0.0, 0.0)}},
    )
    assert Recorder.calls == [(first_box_of(dataset, "SquareA"), sequence_seed("SquareA", 7))]


# ----------------------------------------------------------------------------- resume and crashes


def test_resume_recomputes_only_the_missing_pair(dataset, tmp_path, registered):
    registered("test-rec", Recorder)
    run_dir = tmp_path / "run"
    run_evaluation(dataset, ["test-rec", "opencv-kcf"], run_dir, progress=False, report=False)
    texts = read_result_texts(run_dir)
    stamps = {p: p.stat().st_mtime_ns for p in (run_dir / "results").rglob("*.txt")}
    result_path(run_dir, "test-rec", "SquareB").unlink()

    Recorder.calls.clear()
    run = run_evaluation(dataset, ["test-rec", "opencv-kcf"], run_dir, progress=False, report=False)
    assert run.done == [("test-rec", "SquareB")]
    assert len(run.skipped) == 5
    assert Recorder.calls == [(first_box_of(dataset, "SquareB"), sequence_seed("SquareB"))]
    for p, stamp in stamps.items():
        if p.name not in ("SquareB.txt", "SquareB_time.txt") or "opencv-kcf" in str(p):
            assert p.stat().st_mtime_ns == stamp, p  # untouched
    assert read_result_texts(run_dir) == texts  # recomputed identically


def test_short_result_file_is_recomputed(dataset, tmp_path):
    run_dir = tmp_path / "run"
    run_evaluation(dataset, ["opencv-kcf"], run_dir, sequences=["SquareA"], progress=False, report=False)
    rp = result_path(run_dir, "opencv-kcf", "SquareA")
    full = rp.read_text()
    rp.write_text("".join(full.splitlines(keepends=True)[:7]))
    run = run_evaluation(dataset, ["opencv-kcf"], run_dir, sequences=["SquareA"], progress=False, report=False)
    assert run.done == [("opencv-kcf", "SquareA")]
    assert any("7 lines for 20 frames" in n for n in run.notes)
    assert rp.read_text() == full


def test_crash_in_one_pair_is_recorded_and_rerun_completes(dataset, tmp_path, registered):
    box_b = first_box_of(dataset, "SquareB")
    registered("test-crash", functools.partial(CrashAt, box_b, 7))
    run_dir = tmp_path / "run"
    run = run_evaluation(dataset, ["test-crash", "opencv-kcf"], run_dir, progress=False, report=False)
    assert run.failed == [("test-crash", "SquareB")]
    assert len(run.done) == 5
    (err,) = errors_of(run_dir)
    assert err["tracker"] == "test-crash" and err["sequence"] == "SquareB"
    assert "frame 7" in err["error"] and "0008.png" in err["error"]
    assert "simulated tracker bug" in err["error"] and "RuntimeError" in err["error"]
    assert not result_path(run_dir, "test-crash", "SquareB").exists()  # nothing partial
    assert not times_path(run_dir, "test-crash", "SquareB").exists()
    assert not list(run_dir.rglob("*.tmp"))

    registered("test-crash", functools.partial(CrashAt, box_b, 10_000))  # the bug is fixed
    run = run_evaluation(dataset, ["test-crash", "opencv-kcf"], run_dir, progress=False, report=False)
    assert run.ok and run.done == [("test-crash", "SquareB")]
    assert errors_of(run_dir) == []
    assert len(result_path(run_dir, "test-crash", "SquareB").read_text().splitlines()) == 20


@pytest.mark.parametrize("workers", [1, 2])
def test_progress_bars_count_pairs_and_frames(dataset, tmp_path, capsys, workers):
    run_evaluation(
        dataset, ["opencv-kcf"], tmp_path / "run", sequences=["SquareA", "SquareC"], report=False, workers=workers
    )
    err = capsys.readouterr().err
    assert "2/2" in err and "40/40" in err and "41/40" not in err


# ----------------------------------------------------------------------------- bad input


@pytest.fixture
def bad_dataset(tmp_path):
    root = make_otb_dataset(tmp_path / "bad")
    (root / "SquareA" / "img" / "0005.png").unlink()  # missing image mid-sequence
    gt = root / "SquareB" / "groundtruth_rect.txt"
    lines = gt.read_text().splitlines()
    lines[2] = "92,41,26"  # malformed line 3
    gt.write_text("\n".join(lines) + "\n")
    (root / "SquareC" / "img" / "0009.png").write_bytes(b"not a png")  # unreadable image
    make_otb_dataset(root, specs={"Good": dict(start=(20, 20), step=(1.0, 1.0), side=(30, 30))})
    return root


def test_bad_input_is_reported_and_the_rest_runs(bad_dataset, tmp_path):
    run_dir = tmp_path / "run"
    run = run_evaluation(bad_dataset, ["opencv-kcf", "nonesuch"], run_dir, progress=False, report=False)
    assert not run.ok
    assert run.done == [("opencv-kcf", "Good")]
    assert len(result_path(run_dir, "opencv-kcf", "Good").read_text().splitlines()) == 20
    errors = {(e["tracker"], e["sequence"]): e["error"] for e in errors_of(run_dir)}
    assert set(errors) == {
        ("nonesuch", None),
        ("opencv-kcf", "SquareA"),
        ("opencv-kcf", "SquareB"),
        ("opencv-kcf", "SquareC"),
    }
    assert "0005.png" in errors[("opencv-kcf", "SquareA")]
    assert "groundtruth_rect.txt" in errors[("opencv-kcf", "SquareB")]
    assert "line 3" in errors[("opencv-kcf", "SquareB")]
    assert "0009.png" in errors[("opencv-kcf", "SquareC")] and "frame 8" in errors[("opencv-kcf", "SquareC")]
    assert "nonesuch" in errors[("nonesuch", None)] and "opencv-csrt" in errors[("nonesuch", None)]
    for seq in ["SquareA", "SquareB", "SquareC"]:
        assert not result_path(run_dir, "opencv-kcf", seq).exists()
    info = json.loads((run_dir / "run.json").read_text())
    assert info["trackers"] == ["opencv-kcf"]  # the unknown name is an error, not a tracker
    assert set(info["sequences"]) == {"SquareA", "SquareB", "SquareC", "Good"}


def test_unknown_sequence_name_is_an_error_and_others_run(dataset, tmp_path):
    run = run_evaluation(
        dataset, ["opencv-kcf"], tmp_path / "run", sequences="squarea,Nowhere", progress=False, report=False
    )
    assert run.done == [("opencv-kcf", "SquareA")]  # names match case-insensitively
    (err,) = run.errors
    assert err["sequence"] == "Nowhere" and "SquareB" in err["error"]  # lists what exists


def test_whole_run_problems_raise(dataset, tmp_path):
    with pytest.raises(FileNotFoundError, match="dataset folder not found"):
        run_evaluation(tmp_path / "nope", ["opencv-kcf"], tmp_path / "run", progress=False, report=False)
    with pytest.raises(ValueError, match="no tracker"):
        run_evaluation(dataset, "", tmp_path / "run", progress=False, report=False)
    run_evaluation(
        dataset, ["opencv-kcf"], tmp_path / "run", sequences=["SquareA"], progress=False, report=False, max_frames=3
    )
    other = make_otb_dataset(tmp_path / "other", specs={"SquareA": DEFAULT_SPECS["SquareA"]}, n_frames=3)
    with pytest.raises(ValueError, match="another --out"):
        run_evaluation(other, ["opencv-kcf"], tmp_path / "run", progress=False, report=False)


def test_run_json_is_merged_on_restart(dataset, tmp_path):
    run_dir = tmp_path / "run"
    run_evaluation(dataset, ["opencv-kcf"], run_dir, sequences=["SquareA"], progress=False, report=False, max_frames=4)
    run_evaluation(
        dataset,
        ["opencv-mosse", "opencv-kcf"],
        run_dir,
        sequences=["SquareC"],
        progress=False,
        report=False,
        max_frames=4,
    )
    info = json.loads((run_dir / "run.json").read_text())
    assert info["trackers"] == ["opencv-kcf", "opencv-mosse"]
    assert info["sequences"] == ["SquareA", "SquareC"]
    assert info["max_frames"] == 4
    assert len(result_path(run_dir, "opencv-mosse", "SquareC").read_text().splitlines()) == 4


# ----------------------------------------------------------------------------- parallel and Dask

PARALLEL_TRACKERS = ["opencv-kcf", "opencv-csrt", "opencv-medianflow", "test-mosse"]


@pytest.fixture(scope="module")
def sequential_run(dataset, tmp_path_factory):
    # a tracker registered at run time: its factory (a partial of a module-level class) is
    # pickled to the worker processes
    register_tracker("test-mosse", functools.partial(OpenCVTracker, "opencv-mosse"), replace=True)
    run_dir = tmp_path_factory.mktemp("seq") / "run"
    run = run_evaluation(dataset, PARALLEL_TRACKERS, run_dir, progress=False, report=False)
    assert run.ok
    yield read_result_texts(run_dir)
    unregister_tracker("test-mosse")


def test_process_pool_equals_sequential(dataset, tmp_path, sequential_run):
    run = run_evaluation(dataset, PARALLEL_TRACKERS, tmp_path / "run", workers=2, progress=False, report=False)
    assert run.ok and len(run.done) == 12
    assert read_result_texts(tmp_path / "run") == sequential_run
    assert len(list((tmp_path / "run" / "results").glob("*/times/*_time.txt"))) == 12


@pytest.fixture(scope="module")
def cluster():
    """A real Dask cluster of two worker processes (one thread each)."""
    import distributed  # pinned in requirements.txt: a missing one fails

    with distributed.LocalCluster(
        n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None, silence_logs=40
    ) as c:
        yield c


def test_dask_local_cluster_equals_sequential(dataset, tmp_path, sequential_run, cluster):
    import distributed

    run = run_evaluation(
        dataset, PARALLEL_TRACKERS, tmp_path / "run", scheduler=cluster.scheduler_address, progress=False, report=False
    )
    assert run.ok and len(run.done) == 12
    assert read_result_texts(tmp_path / "run") == sequential_run
    # errors travel back from the cluster too, and the rest is skipped on restart
    result_path(tmp_path / "run", "opencv-kcf", "SquareC").unlink()
    with distributed.Client(cluster) as client:
        run = run_evaluation(
            dataset, ["opencv-kcf", "nonesuch"], tmp_path / "run", scheduler=client, progress=False, report=False
        )
    assert run.done == [("opencv-kcf", "SquareC")] and len(run.skipped) == 2
    assert run.failed == [("nonesuch", None)]
    assert read_result_texts(tmp_path / "run") == sequential_run


@pytest.mark.slow
def test_smtmvt_same_boxes_in_process_pool_and_dask(dataset, tmp_path, cluster):
    """Our tracker gets the same per-sequence seed wherever it runs, so the boxes are equal."""
    common = dict(tracker_options={"smtmvt": {"n_particles": 40}}, max_frames=6, progress=False, report=False)
    here = run_evaluation(dataset, ["smtmvt"], tmp_path / "here", sequences=["SquareB"], **common)
    pool = run_evaluation(dataset, ["smtmvt"], tmp_path / "pool", workers=2, **common)
    dask = run_evaluation(dataset, ["smtmvt"], tmp_path / "dask", scheduler=cluster.scheduler_address, **common)
    assert here.ok and pool.ok and dask.ok, (here.errors, pool.errors, dask.errors)
    pool_texts = read_result_texts(tmp_path / "pool")
    assert read_result_texts(tmp_path / "dask") == pool_texts
    assert read_result_texts(tmp_path / "here")[("smtmvt", "SquareB")] == pool_texts[("smtmvt", "SquareB")]
    # and it tracks the squares (measured 0.93-0.94 on these 6 frames)
    from smtmvt.evaluation.metrics import overlap_ratio

    for seq in DEFAULT_SPECS:
        boxes = read_boxes(result_path(tmp_path / "pool", "smtmvt", seq))
        gt = open_otb_sequence(dataset / seq).groundtruth[:6]
        assert overlap_ratio(boxes, gt).mean() > 0.8, seq


def test_unreachable_scheduler_is_a_clear_error(dataset, tmp_path):
    import socket

    import dask

    with socket.socket() as s:  # a free port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with dask.config.set({"distributed.comm.timeouts.connect": "2s"}):
        with pytest.raises(OSError, match=f"cannot connect to the Dask scheduler at tcp://127.0.0.1:{port}"):
            run_evaluation(
                dataset,
                ["opencv-kcf"],
                tmp_path / "run",
                scheduler=f"tcp://127.0.0.1:{port}",
                progress=False,
                report=False,
            )


# ----------------------------------------------------------------------------- the run folder keeps its settings (issue 8)


def test_a_different_frame_limit_is_refused_and_nothing_is_lost(dataset, tmp_path):
    run_dir = tmp_path / "run"
    run_evaluation(dataset, ["opencv-kcf"], run_dir, progress=False, report=False)
    texts = read_result_texts(run_dir)
    with pytest.raises(ValueError, match=rf"{run_dir} was run with all frames.*--max-frames 5.*--overwrite"):
        run_evaluation(dataset, ["opencv-kcf"], run_dir, progress=False, report=False, max_frames=5)
    assert read_result_texts(run_dir) == texts  # every full result kept
    run = run_evaluation(dataset, ["opencv-kcf"], run_dir, progress=False, report=False, max_frames=5, overwrite=True)
    assert len(run.done) == 3 and any("--overwrite: removed" in n for n in run.notes)
    assert all(len(t.splitlines()) == 5 for t in read_result_texts(run_dir).values())
    assert json.loads((run_dir / "run.json").read_text())["max_frames"] == 5


def test_a_corrupt_line_is_recomputed_even_with_the_right_line_count(dataset, tmp_path):
    run_dir = tmp_path / "run"
    run_evaluation(dataset, ["opencv-kcf"], run_dir, sequences=["SquareA"], progress=False, report=False)
    rp = result_path(run_dir, "opencv-kcf", "SquareA")
    full = rp.read_text()
    lines = full.splitlines(keepends=True)
    lines[4] = "12,oops,3,4\n"
    rp.write_text("".join(lines))
    run = run_evaluation(dataset, ["opencv-kcf"], run_dir, sequences=["SquareA"], progress=False, report=False)
    assert run.done == [("opencv-kcf", "SquareA")]
    assert any("line 5" in n and "recomputing" in n for n in run.notes)
    assert rp.read_text() == full


def test_evaluate_does_not_take_imported_results_for_its_own(dataset, tmp_path, registered):
    """A tracker folder made by ``report --import`` is never counted as computed results."""
    from smtmvt.evaluation.imports import import_into_run

    run_dir = tmp_path / "run"
    run_evaluation(dataset, ["opencv-kcf"], run_dir, sequences=["SquareA"], progress=False, report=False)
    src = tmp_path / "foreign" / "test-cv"
    src.mkdir(parents=True)
    (src / "SquareA.txt").write_text(result_path(run_dir, "opencv-kcf", "SquareA").read_text())
    assert import_into_run(run_dir, src) == {"test-cv": ["SquareA"]}
    registered("test-cv", ConstantVelocity)
    run = run_evaluation(dataset, ["test-cv"], run_dir, sequences=["SquareA"], progress=False, report=False)
    assert run.failed == [("test-cv", None)]
    assert "imported" in run.errors[0]["error"] and "results/test-cv" in run.errors[0]["error"]
    assert result_path(run_dir, "test-cv", "SquareA").read_text() == (src / "SquareA.txt").read_text()


def test_a_second_run_on_a_locked_folder_is_a_clear_error(dataset, tmp_path):
    from smtmvt.evaluation.rundir import RunDir

    run_dir = tmp_path / "run"
    with RunDir(run_dir).locked("smtmvt evaluate", create=True):
        with pytest.raises(ValueError, match=f"{run_dir} is in use by smtmvt evaluate"):
            run_evaluation(dataset, ["opencv-kcf"], run_dir, progress=False, report=False)
    assert not (run_dir / "results").exists() and not (run_dir / "run.json").exists()


def test_opencv_mil_resumed_or_parallel_equals_uninterrupted(dataset, tmp_path):
    """MIL draws from an OpenCV random state that ``setRNGSeed`` does not reset: each pair runs
    in a fresh process, so the boxes do not depend on what a process ran before."""
    seqs = ["SquareA", "SquareB", "SquareC"]
    whole = tmp_path / "whole"
    run_evaluation(dataset, ["opencv-mil"], whole, sequences=seqs, progress=False, report=False)
    texts = read_result_texts(whole)
    resumed = tmp_path / "resumed"
    run_evaluation(dataset, ["opencv-mil"], resumed, sequences=seqs, progress=False, report=False)
    result_path(resumed, "opencv-mil", "SquareC").unlink()  # run third the first time, first now
    run = run_evaluation(dataset, ["opencv-mil"], resumed, sequences=seqs, progress=False, report=False)
    assert run.done == [("opencv-mil", "SquareC")]
    assert read_result_texts(resumed) == texts
    parallel = tmp_path / "parallel"
    run_evaluation(dataset, ["opencv-mil"], parallel, sequences=seqs, workers=2, progress=False, report=False)
    assert read_result_texts(parallel) == texts


def evaluate_cli(dataset, run_dir, *args) -> int:
    """``smtmvt evaluate --dataset DATASET --out RUN_DIR ARGS...`` in this process (exit status)."""
    from smtmvt.cli import main

    return main(["evaluate", "--dataset", str(dataset), "--out", str(run_dir), *args])


def test_a_worker_that_dies_fails_its_pair_only(dataset, tmp_path, registered):
    """A worker process that dies mid-pair is replaced; its pair is an error, the rest completes."""
    registered("test-die", functools.partial(DieAt, first_box_of(dataset, "SquareB"), 4))
    run = run_evaluation(dataset, ["test-die"], tmp_path / "run", workers=2, progress=False, report=False)
    assert sorted(run.done) == [("test-die", "SquareA"), ("test-die", "SquareC")]
    (err,) = run.errors
    assert err["sequence"] == "SquareB" and "worker failed (exit code 3" in err["error"]
    assert not result_path(tmp_path / "run", "test-die", "SquareB").exists()
