"""bench/sweep.py: its error split (the scored overlap, and the overlap with the true size or
centre), its filter of complete sequences, and its runs as ``smtmvt evaluate`` run folders (one per
data folder, scored as the report scores them, beside the sweep folders of before)."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from smtmvt.evaluation.metrics import score_sequence

_PATH = Path(__file__).resolve().parents[1] / "bench" / "sweep.py"
_spec = importlib.util.spec_from_file_location("sweep", _PATH)
assert _spec is not None and _spec.loader is not None
sweep = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(sweep)


@pytest.fixture
def gt():
    rng = np.random.default_rng(3)
    g = np.column_stack([rng.uniform(10, 200, (40, 2)), rng.uniform(8, 60, (40, 2))])
    g[7] = 0.0  # an invalid ground-truth frame, left out of the score
    return g


def test_its_overlap_is_the_scored_average_overlap(gt):
    rng = np.random.default_rng(4)
    boxes = gt + rng.normal(0, 4, gt.shape)
    boxes[:, 2:] = np.abs(boxes[:, 2:]) + 1
    boxes[12] = np.nan  # a failed box, repaired as the toolkit does
    split = sweep.error_split(boxes, gt)
    assert split["ao"] == pytest.approx(score_sequence(boxes, gt).avg_overlap, abs=1e-12)
    assert split["ao"] < 0.95


def test_a_box_twice_the_size_about_the_true_centre_loses_only_to_size(gt):
    c = gt[:, :2] + gt[:, 2:] / 2
    boxes = np.column_stack([c - gt[:, 2:], 2 * gt[:, 2:]])
    split = sweep.error_split(boxes, gt)
    # frame 1 is the truth (overlap 1); the 38 other valid frames hold the truth in 4x its area
    assert split["ao"] == pytest.approx((1 + 38 * 0.25) / 39)
    assert split["ao_true_size"] == pytest.approx(1.0)
    assert split["ao_true_centre"] == pytest.approx(split["ao"])
    assert split["log_area"] == pytest.approx(np.log(4.0))
    assert split["dx"] == pytest.approx(0.0, abs=1e-12)
    assert split["dy"] == pytest.approx(0.0, abs=1e-12)


def test_a_shifted_box_of_the_true_size_loses_only_to_position(gt):
    boxes = gt + np.column_stack([0.25 * gt[:, 2], -0.5 * gt[:, 3], 0 * gt[:, 2:]])
    split = sweep.error_split(boxes, gt)
    assert split["ao"] < 0.5
    assert split["ao_true_centre"] == pytest.approx(1.0)
    assert split["ao_true_size"] == pytest.approx(split["ao"])
    assert split["log_area"] == pytest.approx(0.0, abs=1e-12)
    assert split["dx"] == pytest.approx(0.25)
    assert split["dy"] == pytest.approx(-0.5)


def test_complete_only_keeps_sequences_every_tag_finished_on_every_seed():
    runs = {
        "a": {("Bolt", 0): 1, ("Bolt", 1): 2, ("Girl", 0): 3, ("Girl", 1): 4, ("Dog1", 0): 5},
        "b": {("Bolt", 0): 6, ("Bolt", 1): 7, ("Girl", 0): 8},
    }
    kept = sweep.complete_only(runs)
    assert kept == {"a": {("Bolt", 0): 1, ("Bolt", 1): 2}, "b": {("Bolt", 0): 6, ("Bolt", 1): 7}}
    # only seed 0 asked for: Girl is complete there, Dog1 is not (tag b lacks it)
    kept0 = sweep.complete_only({t: {k: v for k, v in r.items() if k[1] == 0} for t, r in runs.items()}, [0])
    assert sorted(s for s, _ in kept0["a"]) == ["Bolt", "Girl"]
    assert sweep.complete_only(runs, [0, 1, 2]) == {"a": {}, "b": {}}


# --------------------------------------------------------------------------- run folders


def _dataset(root: Path, gts: dict) -> Path:
    """An OTB folder: one sequence per entry of ``gts`` (0-based (n, 4) boxes), black frames."""
    import cv2

    for name, gt in gts.items():
        (root / name / "img").mkdir(parents=True)
        for k in range(len(gt)):
            cv2.imwrite(str(root / name / "img" / f"{k + 1:04d}.jpg"), np.zeros((48, 64, 3), np.uint8))
        (root / name / "groundtruth_rect.txt").write_text(
            "".join(",".join(f"{v:g}" for v in b + [1, 1, 0, 0]) + "\n" for b in gt)
        )
    return root


def _run_folder(run_dir: Path, dataset: Path, results: dict, repeat: int) -> None:
    """A run folder of tracker smtmvt holding ``results`` ({(seq, k): 0-based boxes}), as evaluate writes it."""
    from smtmvt.evaluation.rundir import RunDir

    run = RunDir(run_dir)
    with run.locked("test", create=True):
        run.settle(
            dataset, trackers=["smtmvt"], sequences=sorted({s for s, _ in results}), max_frames=None, repeat=repeat
        )
        for (seq, k), boxes in results.items():
            run.write_result("smtmvt", seq, boxes, np.full(len(boxes), 0.1), k)


def _boxes(gt, shift, rng):
    b = gt + rng.normal(0, shift, gt.shape)
    b[:, 2:] = np.abs(b[:, 2:]) + 1
    return b


def test_show_scores_evaluate_run_folders_as_the_report_does(tmp_path):
    rng = np.random.default_rng(5)
    gts = {"Aa": np.tile([[10.0, 12.0, 20.0, 16.0]], (6, 1)), "Bb": np.tile([[5.0, 6.0, 14.0, 18.0]], (5, 1))}
    data = _dataset(tmp_path / "otb", gts)
    results = {(s, k): _boxes(gt, 2 + 3 * k, rng) for s, gt in gts.items() for k in (0, 1)}
    del results[("Bb", 1)]  # a repeat not done yet
    _run_folder(tmp_path / "runs" / "T" / "otb", data, results, repeat=2)
    recs = sweep._load(tmp_path / "runs" / "T", None)
    assert sorted(recs) == [("Aa", 0), ("Aa", 1), ("Bb", 0)]
    for (s, k), rec in recs.items():
        assert rec["avg_overlap"] == pytest.approx(score_sequence(results[s, k], gts[s]).avg_overlap, abs=1e-9)
        assert rec["folder"] == "otb" and rec["fps"] == pytest.approx(10.0)
    assert sorted(sweep._load(tmp_path / "runs" / "T", "1-1")) == [("Aa", 1)]  # seed index 1 only
    # the error split reads the ground truth through the run folder: its boxes' own origin
    split = sweep.error_split(recs["Aa", 0]["boxes"], sweep._groundtruth(recs["Aa", 0], {}, []))
    assert split["ao"] == pytest.approx(recs["Aa", 0]["avg_overlap"], abs=1e-12)


def test_show_compares_a_run_folder_tag_with_a_sweep_folder_of_before(tmp_path, capsys):
    import argparse
    import json

    gt = np.tile([[10.0, 12.0, 20.0, 16.0]], (6, 1))
    data = _dataset(tmp_path / "otb", {"Aa": gt})
    _run_folder(tmp_path / "runs" / "new" / "otb", data, {("Aa", 0): gt.copy()}, repeat=1)
    old = tmp_path / "runs" / "old"
    old.mkdir()
    rec = {
        "sequence": "Aa",
        "k": 0,
        "seed": 1,
        "avg_overlap": 0.5,
        "auc": 0.5,
        "fps": 3.0,
        "boxes": gt.tolist(),
        "folder": "otb",
    }
    (old / "Aa#0.json").write_text(json.dumps(rec))
    split = tmp_path / "split.json"
    split.write_text(json.dumps({"tune": ["Aa"], "check": ["Zz"]}))
    args = argparse.Namespace(
        tags=["old", "new"], out=str(tmp_path / "runs"), seeds=None, complete=True, split=str(split)
    )
    sweep.show(args)
    out = capsys.readouterr().out.splitlines()
    assert out[0].split() == ["sequence", "old", "new"]
    assert out[1].split() == ["Aa", "0.500", "(1)", "1.000", "(1)"]
    assert out[2].startswith("old: mean 0.500 over 1 sequences; per seed 0.500; otb 0.500 (1); 3.0 fps")
    assert out[3] == "  tune 0.500 (1 of 1); check nan (0 of 1)"
    assert out[4].startswith("new: mean 1.000 over 1 sequences; per seed 1.000; otb 1.000 (1); 10.0 fps")


def test_the_configuration_is_json_or_a_json_file_and_never_names_the_seed(tmp_path):
    assert sweep.read_config('{"n_particles": 200}') == {"n_particles": 200}
    f = tmp_path / "c.json"
    f.write_text('{"correlation_usual_peak": false}')
    assert sweep.read_config(str(f)) == {"correlation_usual_peak": False}
    with pytest.raises(SystemExit, match="seed"):
        sweep.read_config('{"seed": 3}')
    with pytest.raises(SystemExit, match="not JSON"):
        sweep.read_config("{n_particles: 200}")
    with pytest.raises(SystemExit, match="cannot read"):
        sweep.read_config(str(tmp_path / "missing.json"))


def test_run_makes_an_evaluate_run_folder_per_data_folder_and_refuses_another_config(tmp_path):
    import argparse

    import cv2

    from smtmvt.demo import make_demo_sequence
    from smtmvt.evaluation.rundir import RunDir

    demo = make_demo_sequence(n_frames=5, size=(60, 80))
    root = tmp_path / "otb"
    (root / "Demo" / "img").mkdir(parents=True)
    for k, frame in enumerate(demo.frames):
        cv2.imwrite(str(root / "Demo" / "img" / f"{k + 1:04d}.png"), np.ascontiguousarray(frame[:, :, ::-1]))
    (root / "Demo" / "groundtruth_rect.txt").write_text(
        "".join(",".join(f"{v:g}" for v in np.asarray(b) + [1, 1, 0, 0]) + "\n" for b in demo.groundtruth)
    )
    args = argparse.Namespace(
        tag="T", data=[str(root)], config='{"n_particles": 20}', seeds="2", workers=1,
        out=str(tmp_path / "runs"), sequences=None, quiet=True,
    )  # fmt: skip
    sweep.run(args)
    run = RunDir(tmp_path / "runs" / "T" / "otb")
    info = run.info()
    assert info.trackers == ["smtmvt"] and info.repeat == 2 and info.sequences == ["Demo"]
    assert all(run.result_path("smtmvt", "Demo", k).is_file() for k in (0, 1))
    assert sorted(sweep._load(tmp_path / "runs" / "T", None)) == [("Demo", 0), ("Demo", 1)]
    with pytest.raises(SystemExit, match="other settings"):
        sweep.run(argparse.Namespace(**{**vars(args), "config": '{"n_particles": 30}'}))


def test_loss_spans_are_the_runs_of_frames_under_a_tenth(gt):
    boxes = gt.copy()
    far = gt + np.column_stack([10 * gt[:, 2], 0 * gt[:, 1:]])  # no overlap at all
    boxes[10:14] = far[10:14]  # 4 frames: too short to count
    boxes[20:26] = far[20:26]  # 6 frames, recovered after
    boxes[33:] = far[33:]  # lost to the end
    assert sweep.loss_spans(boxes, gt) == [(21, 6, False), (34, 7, True)]
    assert sweep.loss_spans(boxes, gt, least=4) == [(11, 4, False), (21, 6, False), (34, 7, True)]
    assert sweep.loss_spans(gt, gt) == []


def test_an_invalid_truth_frame_neither_counts_nor_breaks_a_span(gt):
    # frame 8 (index 7) has no valid truth: a span over it is one span of the valid frames
    boxes = gt + np.column_stack([10 * gt[:, 2], 0 * gt[:, 1:]])
    boxes[:4] = gt[:4]
    boxes[12:] = gt[12:]
    assert sweep.loss_spans(boxes, gt) == [(5, 7, False)]
