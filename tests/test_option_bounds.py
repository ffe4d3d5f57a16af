"""Sizes and counts are checked against sane bounds and types before any work (issue 46, fault 7).

``--repeat 99999999999999999999`` was stored and hung the next ``evaluate``;
``--tracker-option smtmvt:n_particles=1e9`` was rounded to an int and grew to 24 GB.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from smtmvt import TrackerConfig
from smtmvt.cli import main
from smtmvt.evaluation import run_evaluation
from smtmvt.evaluation.rundir import MAX_REPEAT, RunDir, RunDirError
from test_runner import evaluate_cli, make_otb_dataset


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return make_otb_dataset(tmp_path_factory.mktemp("otb"), n_frames=6)


@pytest.mark.parametrize(
    ("changes", "expected"),
    [
        ({"n_particles": 1e9}, "n_particles=1000000000.0: expected a whole number from 1 to 10000"),
        ({"n_particles": 2.5}, "n_particles=2.5: expected a whole number"),
        ({"n_particles": 200.0}, "n_particles=200.0: expected a whole number"),  # refused, not rounded
        ({"n_particles": 10_001}, "n_particles=10001: expected a whole number from 1 to 10000"),
        ({"n_particles": True}, "n_particles=True"),
        ({"n_templates": 1000}, "n_templates=1000: expected a whole number from 1 to 100"),
        ({"solver_max_iter": 10**9}, "solver_max_iter=1000000000"),
        ({"color_grid": 2.0}, "color_grid=2.0"),
        ({"feature_size": (32, 100_000)}, "feature_size=(32, 100000): expected two whole numbers from 8 to 256"),
        ({"frame_size": (320.5, 240)}, "frame_size=(320.5, 240): expected two whole numbers"),
        ({"alpha": "abc"}, "alpha='abc': expected a finite number"),
        ({"lam": float("inf")}, "lam=inf: expected a finite number"),
        ({"affine_std": (0.01, 0, 0, 0.01, 8, "x")}, "affine_std=(0.01, 0, 0, 0.01, 8, 'x')"),
    ],
)
def test_tracker_config_refuses_wrong_types_and_absurd_sizes(changes, expected):
    with pytest.raises(ValueError, match=re.escape(f"TrackerConfig: invalid {expected}")):
        TrackerConfig(**changes)


def test_tracker_config_accepts_the_bounds_and_numpy_integers():
    assert TrackerConfig(n_particles=10_000).n_particles == 10_000
    assert TrackerConfig(n_particles=np.int64(200), n_templates=np.int32(5)).n_particles == 200
    assert TrackerConfig(feature_size=[24, 24], frame_size=(320, 240)).feature_size == (24, 24)  # JSON lists
    assert TrackerConfig(blas_threads=None, aspect_std=None).blas_threads is None
    assert TrackerConfig.paper().n_particles == 400


def test_a_non_integral_tracker_option_is_refused_before_any_tracking(dataset, tmp_path, capsys):
    run_dir = tmp_path / "run"
    rc = evaluate_cli(dataset, run_dir, "--trackers", "smtmvt", "--tracker-option", "smtmvt:n_particles=2.5", "--quiet")
    err = capsys.readouterr().err
    assert rc == 1
    assert "smtmvt: cannot be created with options {'n_particles': 2.5}" in err
    assert "invalid n_particles=2.5: expected a whole number from 1 to 10000" in err
    assert not list(run_dir.glob("results/smtmvt/*.txt"))  # nothing was tracked
    (entry,) = json.loads((run_dir / "errors.json").read_text())
    assert entry["tracker"] == "smtmvt" and entry["sequence"] is None and "n_particles=2.5" in entry["error"]


def test_track_refuses_an_absurd_particle_count(dataset, tmp_path, capsys):
    out = tmp_path / "res.txt"
    rc = main(["track", str(dataset / "SquareA"), "--out", str(out), "--particles", "20000", "--quiet"])
    assert rc == 2 and "invalid n_particles=20000: expected a whole number from 1 to 10000" in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.parametrize("command", ["evaluate", "report"])
@pytest.mark.parametrize("value", ["99999999999999999999", "0", "1001", "2.5"])
def test_an_absurd_repeat_is_refused_by_the_command_line(dataset, tmp_path, capsys, command, value):
    run_dir = tmp_path / "run"
    args = ["evaluate", "--dataset", str(dataset), "--trackers", "opencv-kcf", "--out", str(run_dir)]
    args = args if command == "evaluate" else ["report", str(run_dir)]
    with pytest.raises(SystemExit) as info:
        main([*args, "--repeat", value])
    assert info.value.code == 2
    expected = f"from 1 to {MAX_REPEAT}" if value in ("1001", "99999999999999999999") else ">= 1"
    assert f"--repeat: expected a whole number {expected}, got '{value}'" in capsys.readouterr().err
    assert not run_dir.exists()


def test_an_absurd_repeat_is_refused_by_the_api_and_in_run_json(dataset, tmp_path, capsys):
    run_dir = tmp_path / "run"
    with pytest.raises(ValueError, match=f"repeat must be at most {MAX_REPEAT}, got {10**20}"):
        run_evaluation(dataset, ["opencv-kcf"], run_dir, repeat=10**20, progress=False, report=False)
    assert not run_dir.exists()
    # a run.json that holds one (written by an older version) is refused, not run
    run = run_evaluation(dataset, ["opencv-kcf"], run_dir, max_frames=3, progress=False, report=False)
    assert run.ok
    info = json.loads((run_dir / "run.json").read_text())
    (run_dir / "run.json").write_text(json.dumps({**info, "repeat": 10**20}))
    with pytest.raises(RunDirError, match=rf"run\.json: repeat must be at most {MAX_REPEAT}, got {10**20}"):
        RunDir(run_dir).info()
    rc = evaluate_cli(dataset, run_dir, "--trackers", "smtmvt", "--max-frames", "3", "--quiet")
    assert rc == 2 and f"repeat must be at most {MAX_REPEAT}" in capsys.readouterr().err
