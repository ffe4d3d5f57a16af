"""bench/diagnose.py: the per-frame diagnosis against the ground truth (on the demo sequence)."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.demo import make_demo_sequence

_PATH = Path(__file__).resolve().parents[1] / "bench" / "diagnose.py"
_spec = importlib.util.spec_from_file_location("diagnose", _PATH)
assert _spec is not None and _spec.loader is not None
diagnose = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(diagnose)


class _Seq(list):
    def __init__(self, demo, n):
        super().__init__(demo.frames[:n])
        self.groundtruth = demo.groundtruth[:n]
        self.first_box = tuple(demo.groundtruth[0])
        self.name = "demo"


@pytest.fixture(scope="module")
def seq():
    return _Seq(make_demo_sequence(n_frames=40), 12)


@pytest.mark.parametrize("anchor", [0.0, 1.0])
def test_probing_the_ground_truth_leaves_the_tracking_unchanged(seq, anchor):
    # the reported box is the chosen particle's (the read size would report another)
    config = TrackerConfig(n_particles=80, seed=5, anchor_weight=anchor, report_read_size=0)
    rows = diagnose.diagnose(seq, config)
    tracker = Tracker(config)
    tracker.init(seq[0], seq.first_box)
    boxes = np.array([tracker.update(f).box for f in seq[1:]])
    overlaps = diagnose.overlap_ratio(boxes, np.asarray(seq.groundtruth[1:], dtype=float))
    np.testing.assert_allclose([r["overlap"] for r in rows], overlaps, atol=1e-12)
    assert [r["frame"] for r in rows] == list(range(2, len(seq) + 1))
    for r in rows:
        assert r["gt_rank"] >= 1 and r["best_particle_overlap"] >= r["overlap"] - 1e-12
        # the anchor term is anchor_weight times at most one per term view (3), 0 when off
        for key in ("gt_anchor", "chosen_anchor"):
            assert 0.0 <= r[key] <= 3.0 * anchor + 1e-9
    if anchor:
        assert max(r["chosen_anchor"] for r in rows) > 0


def test_classify_names_the_stage_at_fault():
    row = dict(overlap=0.3, gt_likelihood=0.1, chosen_likelihood=0.5, gt_residual_first=2.0, chosen_residual_first=1.0)
    assert diagnose.classify(row) == "model"
    assert diagnose.classify({**row, "gt_residual_first": 0.5}) == "drift"
    row = {**row, "gt_likelihood": 0.9, "best_particle_overlap": 0.2}
    assert diagnose.classify(row) == "search"
    assert diagnose.classify({**row, "best_particle_overlap": 0.7}) == "peak"
    assert diagnose.classify({**row, "overlap": 0.8}) == ""
