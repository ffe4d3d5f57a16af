"""``smtmvt evaluate`` on the same 40 real frames in every layout: the same AUC where no frame
is absent, and each toolkit's absent-frame rule where some are."""

from __future__ import annotations

import json

import numpy as np
import pytest

from layout_folders import cut, write_all
from smtmvt.cli import main
from smtmvt.data import read_boxes
from smtmvt.evaluation.metrics import PRECISION_THRESHOLDS, SUCCESS_THRESHOLDS, center_error, overlap_ratio

LAYOUTS = ("otb", "got10k", "lasot", "uav123", "vot")
ABSENT = (10, 11, 25, 26, 27)
TRACKER = "opencv-kcf"  # deterministic and fast


def _evaluate(dataset, run_dir) -> dict:
    rc = main(["evaluate", "--dataset", str(dataset), "--out", str(run_dir), "--trackers", TRACKER, "--quiet"])
    assert rc == 0
    summary = json.loads((run_dir / "report" / "summary.json").read_text())
    (seq,) = summary["sequences"]
    return {
        "summary": summary,
        "seq": seq,
        "boxes": read_boxes(run_dir / "results" / TRACKER / f"{seq}.txt", one_based=True),
    }


@pytest.fixture(scope="module")
def runs(otb_dir, tmp_path_factory):
    base = tmp_path_factory.mktemp("layouts")
    clean = write_all(base / "clean", otb_dir / "Crossing")
    absent = write_all(base / "absent", otb_dir / "Crossing", absent=ABSENT)
    out = {("clean", k): _evaluate(p, base / "runs" / f"clean-{k}") for k, p in clean.items()}
    out.update({("absent", k): _evaluate(p, base / "runs" / f"absent-{k}") for k, p in absent.items() if k != "otb"})
    return out


@pytest.mark.parametrize("layout", LAYOUTS[1:])
def test_the_same_frames_score_the_same_auc_in_every_layout(runs, layout):
    ref, got = runs["clean", "otb"], runs["clean", layout]
    np.testing.assert_array_equal(got["boxes"], ref["boxes"])
    t_ref, t_got = ref["summary"]["trackers"][TRACKER], got["summary"]["trackers"][TRACKER]
    for key in ("auc", "precision20", "avg_overlap"):
        assert t_got[key] == t_ref[key], key
    assert 0 < t_ref["auc"] < 1


def _expected(boxes, gt, rule: str):
    """Success and precision curves by each toolkit's rule, computed here from the boxes."""
    pred = boxes.copy()
    pred[0] = gt[0]
    present = np.ones(len(gt), bool)
    present[list(ABSENT)] = False
    ov, err = overlap_ratio(pred, gt)[present], center_error(pred, gt)[present]
    hits_s = (ov[:, None] > SUCCESS_THRESHOLDS[None, :]).sum(axis=0)
    hits_p = (err[:, None] <= PRECISION_THRESHOLDS[None, :]).sum(axis=0)
    if rule == "dropped":  # got10k ExperimentGOT10k (cover > 0), pytracking 'vot'
        return hits_s / present.sum(), hits_p / present.sum()
    if rule == "failed":  # pytracking 'lasot': overlap -1, centre error inf, all frames
        return hits_s / len(gt), hits_p / len(gt)
    # OTB's MATLAB, pysot, pytracking 'uav': overlap -1 (fails), centre error -1 (hits), all frames
    return hits_s / len(gt), (hits_p + len(ABSENT)) / len(gt)


@pytest.mark.parametrize(
    ("layout", "rule"), [("got10k", "dropped"), ("vot", "dropped"), ("lasot", "failed"), ("uav123", "otb")]
)
def test_absent_frames_are_scored_by_the_layouts_rule(runs, otb_dir, layout, rule):
    got = runs["absent", layout]
    np.testing.assert_array_equal(got["boxes"], runs["clean", "otb"]["boxes"])  # same frames, same track
    _, gt = cut(otb_dir / "Crossing", 40)
    success, precision = _expected(got["boxes"], gt, rule)
    entry = got["summary"]["trackers"][TRACKER]
    np.testing.assert_allclose(entry["success"], success, atol=1e-12)
    np.testing.assert_allclose(entry["precision"], precision, atol=1e-12)
    assert entry["auc"] == pytest.approx(success.mean(), abs=1e-12)


def test_the_rules_differ_on_these_frames(runs, otb_dir):
    """The absent frames change the score, and differently per rule (so the test above can fail)."""
    boxes = runs["clean", "otb"]["boxes"]
    _, gt = cut(otb_dir / "Crossing", 40)
    curves = {rule: _expected(boxes, gt, rule) for rule in ("dropped", "failed", "otb")}
    aucs = {rule: s.mean() for rule, (s, _) in curves.items()}
    assert len(set(aucs.values())) == 2 and aucs["dropped"] != aucs["failed"] == aucs["otb"]
    assert not np.allclose(curves["failed"][1], curves["otb"][1])
    assert aucs["dropped"] != runs["clean", "otb"]["summary"]["trackers"][TRACKER]["auc"]
