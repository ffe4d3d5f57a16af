"""bench/sweep.py's error split (the scored overlap, and the overlap with the true size or centre)
and its filter of complete sequences."""

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
