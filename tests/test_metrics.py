"""OTB OPE metrics: hand-computed cases, the MATLAB toolkit's rules, and got10k as a reference."""

from __future__ import annotations

import re
import warnings

# got10k is a pinned test dependency (requirements-dev.txt): imported, not skipped when missing.
# Its ExperimentOTB computes the OTB curves (the module imports six, also pinned).
import got10k.experiments.otb as got10k_otb
import got10k.utils.metrics as got10k_metrics
import numpy as np
import pytest

from smtmvt.evaluation.metrics import (
    PRECISION_THRESHOLDS,
    SUCCESS_THRESHOLDS,
    aggregate,
    center_error,
    overlap_ratio,
    precision_curve,
    prepare_predictions,
    repair_predictions,
    score_sequence,
    success_curve,
    valid_groundtruth,
)
from smtmvt.evaluation.published import read_box_file

# ----------------------------------------------------------------------------- helpers


def matlab_calc_rect_int(A, B):
    """Line-by-line transcription of the OTB toolkit's rstEval/calcRectInt.m."""
    leftA, bottomA = A[:, 0], A[:, 1]
    rightA = leftA + A[:, 2] - 1
    topA = bottomA + A[:, 3] - 1
    leftB, bottomB = B[:, 0], B[:, 1]
    rightB = leftB + B[:, 2] - 1
    topB = bottomB + B[:, 3] - 1
    tmp = np.maximum(0, np.minimum(rightA, rightB) - np.maximum(leftA, leftB) + 1) * np.maximum(
        0, np.minimum(topA, topB) - np.maximum(bottomA, bottomB) + 1
    )
    areaA = A[:, 2] * A[:, 3]
    areaB = B[:, 2] * B[:, 3]
    return tmp / (areaA + areaB - tmp)


def matlab_repair_loop(res, rect_anno):
    """Transcription of the repair loop of the OTB toolkit's util/calcSeqErrRobust.m::

        for i = 2:seq_length
            r = results.res(i,:);
            r_anno = rect_anno(i,:);
            if (isnan(r) | r(3)<=0 | r(4)<=0)&(~isnan(r_anno))
                results.res(i,:)=results.res(i-1,:);
            end
        end

    MATLAB's ``if`` on a vector is true when every element is nonzero."""
    res = np.array(res, dtype=float)
    for i in range(1, len(res)):
        r, r_anno = res[i], rect_anno[i]
        with np.errstate(invalid="ignore"):
            cond = (np.isnan(r) | (r[2] <= 0) | (r[3] <= 0)) & ~np.isnan(r_anno)
        if np.all(cond):
            res[i] = res[i - 1]
    return res


class _NoDataset(list):
    """Just enough of a dataset for ExperimentOTB._calc_curves (which needs none)."""


def got10k_scores(pred, gt):
    """got10k's OTB report for one sequence: boxes[0] = anno[0], rect_iou, center_error, curves."""
    exp = got10k_otb.ExperimentOTB.__new__(got10k_otb.ExperimentOTB)
    exp.nbins_iou, exp.nbins_ce = 21, 51
    boxes = np.array(pred, dtype=float)
    boxes[0] = gt[0]
    ious, errs = exp._calc_metrics(boxes, np.array(gt, dtype=float))
    return exp._calc_curves(ious, errs)


def random_boxes(rng, n, integer=False):
    xy = rng.uniform(1, 300, size=(n, 2))
    wh = rng.uniform(5, 120, size=(n, 2))
    b = np.hstack([xy, wh])
    return np.round(b) if integer else b


def perturb(rng, gt, shift=12.0, scale=0.25):
    p = gt.copy()
    p[:, :2] += rng.normal(0, shift, size=(len(gt), 2)) + np.cumsum(rng.normal(0, 1.0, size=(len(gt), 2)), 0)
    p[:, 2:] *= np.exp(rng.normal(0, scale, size=(len(gt), 2)))
    return p


# ----------------------------------------------------------------------------- IoU and centre error


def test_overlap_hand_computed_inclusive_extents():
    # pixels 1..10 x 1..10 and 6..15 x 6..15: 5x5 = 25 shared pixels, union 100 + 100 - 25
    a = np.array([[1, 1, 10, 10]], float)
    b = np.array([[6, 6, 10, 10]], float)
    assert overlap_ratio(a, b)[0] == pytest.approx(25 / 175, abs=1e-15)
    # touching edges: pixels 1..10 and 11..20 share nothing
    assert overlap_ratio(a, np.array([[11, 1, 10, 10]], float))[0] == 0.0
    # one shared column: pixels 1..10 and 10..19
    assert overlap_ratio(a, np.array([[10, 1, 10, 10]], float))[0] == pytest.approx(10 / 190, abs=1e-15)
    # identical boxes
    assert overlap_ratio(a, a)[0] == 1.0
    # containment: 4x4 inside 10x10
    assert overlap_ratio(a, np.array([[3, 3, 4, 4]], float))[0] == pytest.approx(16 / 100)
    # a shift of both boxes changes nothing (0- vs 1-based)
    assert overlap_ratio(a - [1, 1, 0, 0], b - [1, 1, 0, 0])[0] == overlap_ratio(a, b)[0]


def test_center_error_hand_computed():
    a = np.array([[1, 1, 10, 10]], float)  # centre (5.5, 5.5)
    b = np.array([[6, 6, 10, 10]], float)  # centre (10.5, 10.5)
    assert center_error(a, b)[0] == pytest.approx(np.sqrt(50))
    # centre x + (w - 1) / 2: a 1-px box at x=7 has centre 7; a 3-px box at x=6 also
    assert center_error(np.array([[7, 7, 1, 1]], float), np.array([[6, 6, 3, 3]], float))[0] == 0.0


@pytest.mark.parametrize("integer", [True, False])
def test_overlap_equals_matlab_transcription_and_got10k(integer):
    rng = np.random.default_rng(3 + integer)
    a, b = random_boxes(rng, 4000, integer), random_boxes(rng, 4000, integer)
    b[::3] = a[::3] + rng.normal(0, 8, size=a[::3].shape)  # many overlapping pairs
    b[:, 2:] = np.abs(b[:, 2:]) + 1
    ours = overlap_ratio(a, b)
    # bit-exact MATLAB (capped at 1: see test_equal_float_boxes_overlap_is_exactly_one)
    np.testing.assert_array_equal(ours, np.minimum(matlab_calc_rect_int(a, b), 1.0))
    # got10k: min(x1+w1, x2+w2) - max(x1, x2), union + eps, clip: same up to rounding
    np.testing.assert_allclose(ours, got10k_metrics.rect_iou(a.copy(), b.copy()), rtol=0, atol=1e-12)
    assert (ours > 0).sum() > 500
    np.testing.assert_allclose(center_error(a, b), got10k_metrics.center_error(a, b), rtol=0, atol=1e-12)


def test_equal_float_boxes_overlap_is_exactly_one():
    # MATLAB's formula rounds (x + w - 1) - x + 1 to w + 1 ulp for some non-integer boxes and
    # gives an IoU above 1, a success at threshold 1; we cap at 1 like got10k.
    rng = np.random.default_rng(11)
    a = random_boxes(rng, 2000)
    assert (matlab_calc_rect_int(a, a) > 1).any()  # the quirk exists
    ov = overlap_ratio(a, a)
    assert ov.max() == 1.0 and ov.min() > 1 - 1e-12
    assert success_curve(overlap_ratio(a, a))[-1] == 0.0


def test_overlap_nan_rows_are_nan_not_zero():
    a = np.array([[1, 1, 10, 10], [np.nan, np.nan, np.nan, np.nan]], float)
    b = np.array([[1, 1, 10, 10], [1, 1, 10, 10]], float)
    ov = overlap_ratio(a, b)
    assert ov[0] == 1.0 and np.isnan(ov[1])


def test_curves_strictly_greater_and_less_equal():
    ov = np.array([0.0, 0.5, 0.5000001, 1.0])
    s = success_curve(ov)
    assert s.shape == (21,)
    assert s[0] == 0.75  # 0.0 is not > 0
    assert s[10] == 0.5  # threshold 0.5: 0.5 fails, 0.5000001 passes
    assert s[20] == 0.0  # nothing is > 1
    err = np.array([0.0, 20.0, 20.5, 60.0])
    p = precision_curve(err)
    assert p.shape == (51,)
    assert p[0] == 0.25 and p[20] == 0.5 and p[21] == 0.75 and p[50] == 0.75
    np.testing.assert_array_equal(SUCCESS_THRESHOLDS, np.linspace(0, 1, 21))
    np.testing.assert_array_equal(PRECISION_THRESHOLDS, np.arange(51))


# ----------------------------------------------------------------------------- against got10k


def _assert_same_as_got10k(pred, gt):
    ours = score_sequence(pred, gt)
    succ, prec = got10k_scores(pred, gt)
    np.testing.assert_allclose(ours.success, succ, rtol=0, atol=1e-12)
    np.testing.assert_allclose(ours.precision, prec, rtol=0, atol=1e-12)
    assert ours.auc == pytest.approx(np.mean(succ), abs=1e-9)
    assert ours.precision20 == pytest.approx(prec[20], abs=1e-9)
    return ours


def test_random_sequences_match_got10k():
    rng = np.random.default_rng(0)
    ours_all, succ_all, prec_all = [], [], []
    for k in range(12):
        gt = random_boxes(rng, 150, integer=k % 2 == 0)
        gt = np.cumsum(np.vstack([gt[:1], rng.normal(0, 2, size=(149, 4)) * [1, 1, 0.1, 0.1]]), axis=0)
        gt[:, 2:] = np.maximum(gt[:, 2:], 4)
        pred = perturb(rng, gt)
        ours_all.append(_assert_same_as_got10k(pred, gt))
        s, p = got10k_scores(pred, gt)
        succ_all.append(s)
        prec_all.append(p)
    agg = aggregate(ours_all)
    # got10k averages the curves over sequences, then AUC = mean, precision = value at 20 px
    assert agg.auc == pytest.approx(np.mean(np.mean(succ_all, axis=0)), abs=1e-9)
    assert agg.precision20 == pytest.approx(np.mean(prec_all, axis=0)[20], abs=1e-9)
    assert 0.05 < agg.auc < 0.95  # a non-trivial case


def test_real_crossing_groundtruth_matches_got10k(otb_dir):
    gt = read_box_file(otb_dir / "Crossing" / "groundtruth_rect.txt")
    assert gt.shape == (120, 4)
    rng = np.random.default_rng(7)
    for shift in (2.0, 6.0, 15.0):
        pred = perturb(rng, gt, shift=shift, scale=0.15)
        ours = _assert_same_as_got10k(pred, gt)
        assert 0 < ours.auc < 1


def test_frame_one_is_replaced_by_groundtruth():
    gt = np.array([[10, 10, 20, 20]] * 5, float)
    pred = np.array([[200, 200, 5, 5]] * 5, float)
    s = score_sequence(pred, gt)
    assert s.overlaps[0] == 1.0 and np.all(s.overlaps[1:] == 0)
    assert s.success[0] == pytest.approx(1 / 5)
    assert score_sequence(pred, gt, replace_first=False).success[0] == 0.0


# ----------------------------------------------------------------------------- MATLAB rules


def test_nan_and_zero_size_predictions_take_previous_box():
    gt = np.array([[10, 10, 20, 20]] * 5, float)
    pred = np.array(
        [
            [10, 10, 20, 20],
            [12, 10, 20, 20],
            [np.nan, np.nan, np.nan, np.nan],  # -> frame 2's box
            [50, 50, 0, 20],  # zero width -> frame 3's (repaired) box
            [10, 10, 20, 20],
        ]
    )
    fixed = repair_predictions(pred, gt)
    np.testing.assert_array_equal(fixed[2], pred[1])
    np.testing.assert_array_equal(fixed[3], pred[1])
    s = score_sequence(pred, gt)
    expected = overlap_ratio(pred[1:2], gt[1:2])[0]
    np.testing.assert_allclose(s.overlaps, [1, expected, expected, expected, 1])
    # got10k, without the repair, fails frames 3 and 4
    succ, _ = got10k_scores(pred, gt)
    assert succ[0] == pytest.approx(3 / 5) and s.success[0] == 1.0


def test_no_repair_where_the_groundtruth_has_nan():
    """MATLAB repairs a frame only when its ground truth has no NaN; an unrepaired NaN box
    is then what the next bad frame copies, so that frame fails too."""
    gt = np.array([[10, 10, 20, 20]] * 5, float)
    gt[2, 1] = np.nan  # one NaN number is enough to block the repair
    pred = np.array(
        [
            [10, 10, 20, 20],
            [12, 10, 20, 20],
            [np.nan] * 4,  # gt has NaN: stays NaN
            [50, 50, 0, 20],  # zero width, gt fine: takes frame 2's box, which is NaN
            [10, 10, 20, 20],
        ]
    )
    fixed = repair_predictions(pred, gt)
    assert np.isnan(fixed[2]).all() and np.isnan(fixed[3]).all()
    np.testing.assert_array_equal(fixed, matlab_repair_loop(pred, gt))
    s = score_sequence(pred, gt)
    np.testing.assert_array_equal(s.overlaps[2:4], [-1, 0])  # invalid gt; NaN box = failure
    assert s.errors[3] == np.inf


def test_prepare_predictions_is_what_score_sequence_scores():
    """Frame 1 := truth, the repair, the valid mask; the inputs untouched; the scored
    overlap is the mean over the mask of the prepared boxes' overlaps."""
    rng = np.random.default_rng(11)
    gt = random_boxes(rng, 30)
    gt[[4, 9], 2] = 0.0  # unscored frames ("otb")
    pred = perturb(rng, gt)
    pred[[0, 6, 7]] = np.nan
    before = pred.copy()
    b, g, valid = prepare_predictions(pred, gt)
    np.testing.assert_array_equal(pred, before)  # a new array
    np.testing.assert_array_equal(b[0], gt[0])
    np.testing.assert_array_equal(b[6], pred[5])
    np.testing.assert_array_equal(b[7], pred[5])
    np.testing.assert_array_equal(valid, valid_groundtruth(gt))
    assert valid.sum() == 28
    s = score_sequence(pred, gt)
    assert s.avg_overlap == pytest.approx(float(np.mean(overlap_ratio(b, g)[valid])))
    kept, _, _ = prepare_predictions(pred, gt, replace_first=False)
    assert np.isnan(kept[0]).all()
    with pytest.raises(ValueError, match="prediction has 29 boxes but the ground truth has 30"):
        prepare_predictions(pred[1:], gt)


def test_repair_equals_matlab_loop_on_random_sequences():
    rng = np.random.default_rng(5)
    changed = left_nan = 0
    for _ in range(30):
        gt = random_boxes(rng, 40)
        pred = perturb(rng, gt)
        pred[rng.random(40) < 0.2] = np.nan
        pred[rng.random(40) < 0.1, 2] = 0.0
        pred[rng.random(40) < 0.1, 3] = -rng.uniform(0, 5)
        pred[rng.random(40) < 0.05, 0] = np.nan  # partly NaN: MATLAB does not repair it
        pred[rng.random(40) < 0.05, 3] = 0.0
        pred[rng.random(40) < 0.05, 2:] = 0.5  # small but positive: kept
        if rng.random() < 0.3:
            pred[0] = np.nan  # frame 1 is never repaired (score_sequence replaces it first)
        gt[rng.random(40) < 0.2, rng.integers(0, 4)] = np.nan
        ours = repair_predictions(pred, gt)
        np.testing.assert_array_equal(ours, matlab_repair_loop(pred, gt))
        same = (ours == pred) | (np.isnan(ours) & np.isnan(pred))
        changed += int(np.sum(~same.all(axis=1)))
        left_nan += int(np.sum(np.isnan(ours).all(axis=1)[1:]))
    assert changed > 200 and left_nan > 40  # both branches are exercised (measured 323 and 69)


def test_invalid_groundtruth_otb_rule():
    gt = np.array(
        [
            [10, 10, 20, 20],
            [10, 10, 20, 20],
            [0, 0, 0, 0],  # unannotated (Board, Twinnings)
            [np.nan] * 4,
            [-3, 10, 20, 20],  # y <= 0: MATLAB's sum(rect_anno > 0, 2) == 4 rejects it too (Biker)
            [10, 10, 20, 20],
        ],
        float,
    )
    pred = np.array([[10, 10, 20, 20]] * 6, float)
    pred[1] = [200, 200, 20, 20]  # a miss on a valid frame
    np.testing.assert_array_equal(valid_groundtruth(gt, "otb"), [1, 1, 0, 0, 0, 1])
    np.testing.assert_array_equal(valid_groundtruth(gt, "pytracking"), [1, 1, 0, 0, 1, 1])

    s = score_sequence(pred, gt, invalid="otb")
    # success: invalid frames fail (overlap -1), denominator = all 6 frames
    assert s.success[0] == pytest.approx(2 / 6)
    # precision: invalid frames are hits (error -1)
    assert s.precision[20] == pytest.approx(5 / 6)
    assert s.precision[0] == pytest.approx(5 / 6)  # -1 is a hit even at threshold 0
    np.testing.assert_array_equal(s.overlaps[2:5], -1)
    np.testing.assert_array_equal(s.errors[2:5], -1)
    np.testing.assert_array_equal(s.valid, [1, 1, 0, 0, 0, 1])
    assert s.avg_overlap == pytest.approx(2 / 3)  # mean over the 3 valid frames

    d = score_sequence(pred, gt, invalid="pytracking")  # dropped: 4 valid frames of 6
    assert d.n_valid == 4 and d.n_frames == 6
    assert d.success[0] == pytest.approx(3 / 4)
    assert d.precision[20] == pytest.approx(3 / 4)
    # the per-frame arrays keep all frames, the dropped ones marked
    ov4, err4 = overlap_ratio(pred[4], gt[4])[0], center_error(pred[4], gt[4])[0]
    np.testing.assert_allclose(d.overlaps, [1, 0, -1, -1, ov4, 1], rtol=0, atol=1e-15)
    np.testing.assert_allclose(
        d.errors, [0, center_error(pred[1], gt[1])[0], np.inf, np.inf, err4, 0], rtol=0, atol=1e-12
    )

    f = score_sequence(pred, gt, invalid="fail")  # pytracking's default: failures for both
    assert f.success[0] == pytest.approx(3 / 6)
    assert f.precision[20] == pytest.approx(3 / 6)
    np.testing.assert_array_equal(f.errors[[2, 3]], np.inf)

    with pytest.raises(ValueError, match="^invalid='nope': expected one of otb, pytracking, fail$"):
        score_sequence(pred, gt, invalid="nope")


def test_valid_groundtruth_size_and_position_rules():
    gt = np.array(
        [
            [1, 1, 1, 1],  # the smallest valid 1-based box: x, y = 1 pass "all > 0"
            [10, 10, 0.5, 0.5],  # sub-pixel sizes are still positive
            [10, 10, 0, 20],  # zero width
            [10, 10, 20, 0],  # zero height
            [10, np.nan, 20, 20],  # one NaN
        ],
        float,
    )
    np.testing.assert_array_equal(valid_groundtruth(gt, "otb"), [1, 1, 0, 0, 0])
    np.testing.assert_array_equal(valid_groundtruth(gt, "pytracking"), [1, 1, 0, 0, 0])
    np.testing.assert_array_equal(valid_groundtruth(gt, "fail"), [1, 1, 0, 0, 0])


def test_leftover_non_finite_prediction_is_a_failure():
    """A partly-NaN box is not repaired (MATLAB repairs all-NaN rows only); it scores
    overlap 0 and centre error +inf, not NaN."""
    gt = np.array([[10, 10, 20, 20]] * 4, float)
    pred = gt.copy()
    pred[1] = [np.nan, 10, 20, 20]
    s = score_sequence(pred, gt)
    np.testing.assert_array_equal(s.overlaps, [1, 0, 1, 1])
    np.testing.assert_array_equal(s.errors, [0, np.inf, 0, 0])
    assert s.n_frames == 4 and s.n_valid == 4 and s.valid.all()
    assert s.success[0] == 0.75 and s.precision[50] == 0.75


def test_sequence_of_one_frame_and_of_no_valid_frame():
    gt = np.array([[10, 10, 20, 20]], float)
    one = score_sequence(gt + [50, 0, 0, 0], gt)  # frame 1 := ground truth
    assert one.auc == pytest.approx(20 / 21) and one.precision20 == 1.0 and one.avg_overlap == 1.0
    unannotated = np.zeros((3, 4))
    none = score_sequence(np.array([[1, 1, 5, 5]] * 3, float), unannotated)
    assert none.n_valid == 0 and none.avg_overlap == 0.0 and none.auc == 0.0
    with pytest.raises(ValueError, match="^empty sequence$"):
        score_sequence(np.zeros((0, 4)), np.zeros((0, 4)))


def test_curves_with_a_denominator_and_degenerate_lengths():
    # n_frames is the denominator, not the number of values given
    assert success_curve([0.6, 0.7], n_frames=4)[10] == 0.5
    assert precision_curve([3.0, 30.0], n_frames=4)[20] == 0.25
    np.testing.assert_array_equal(success_curve([]), np.zeros(21))
    np.testing.assert_array_equal(precision_curve([]), np.zeros(51))
    assert success_curve([0.9])[0] == 1.0 and precision_curve([0.0])[0] == 1.0


def test_single_boxes_and_box_arrays():
    a, b = [1, 1, 10, 10], [6, 6, 10, 10]
    ov = overlap_ratio(a, b)  # one box as a 1-D row
    assert ov.shape == (1,) and ov[0] == pytest.approx(25 / 175)
    assert center_error(a, b).shape == (1,) and center_error(a, b)[0] == pytest.approx(np.sqrt(50))
    four = np.array([a, b, a, b], float)  # (4, 4): four boxes, not one row to wrap
    np.testing.assert_array_equal(overlap_ratio(four, four), np.ones(4))
    np.testing.assert_array_equal(center_error(four, four[::-1]), [np.sqrt(50)] * 4)


_BAD = np.zeros((3, 5))
_OK = np.zeros((3, 4)) + [1, 1, 5, 5]


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: overlap_ratio(_BAD, _OK), "overlap_ratio(a)"),
        (lambda: overlap_ratio(_OK, _BAD), "overlap_ratio(b)"),
        (lambda: center_error(_BAD, _OK), "center_error(a)"),
        (lambda: center_error(_OK, _BAD), "center_error(b)"),
        (lambda: valid_groundtruth(_BAD), "groundtruth"),
        (lambda: repair_predictions(_BAD, _OK), "prediction"),
        (lambda: repair_predictions(_OK, _BAD), "groundtruth"),
        (lambda: score_sequence(_BAD, _OK), "prediction"),
        (lambda: score_sequence(_OK, _BAD), "groundtruth"),
        (lambda: overlap_ratio(np.zeros((2, 3, 4)), _OK), "overlap_ratio(a)"),
    ],
)
def test_bad_box_arrays_are_named(call, name):
    with pytest.raises(ValueError, match="^" + re.escape(name) + r": expected an \(n, 4\) array"):
        call()


def test_shape_mismatch_and_empty_aggregate_are_errors():
    with pytest.raises(ValueError, match=r"^overlap_ratio: shapes differ, \(3, 4\) vs \(2, 4\)$"):
        overlap_ratio(_OK, _OK[:2])
    with pytest.raises(ValueError, match=r"^center_error: shapes differ, \(3, 4\) vs \(2, 4\)$"):
        center_error(_OK, _OK[:2])
    with pytest.raises(ValueError, match="^aggregate: no sequences to average$"):
        aggregate([])


def test_zero_size_boxes_give_nan_overlap_without_warnings():
    """Two empty boxes: 0/0 (NaN, as MATLAB), silently."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ov = overlap_ratio([[5, 5, 0, 0]], [[5, 5, 0, 0]])
    assert np.isnan(ov[0])


def test_length_mismatch_is_an_error():
    gt = np.zeros((10, 4)) + [1, 1, 5, 5]
    with pytest.raises(ValueError, match="9 boxes but the ground truth has 10"):
        score_sequence(gt[:9], gt)


def test_aggregate_averages_curves_over_sequences_not_frames():
    gt_long = np.array([[10, 10, 20, 20]] * 100, float)
    gt_short = np.array([[10, 10, 20, 20]] * 2, float)
    perfect = score_sequence(gt_long, gt_long)  # AUC 20/21 (nothing is > 1)
    miss = gt_short.copy()
    miss[1] = [500, 500, 20, 20]
    half = score_sequence(miss, gt_short)
    agg = aggregate([perfect, half])
    np.testing.assert_allclose(agg.success, (perfect.success + half.success) / 2)
    assert agg.auc == pytest.approx((perfect.auc + half.auc) / 2)
    assert agg.precision20 == pytest.approx((1.0 + 0.5) / 2)
    # dicts work too (what summary.json stores)
    agg2 = aggregate(
        [
            {"success": perfect.success, "precision": perfect.precision},
            {"success": half.success, "precision": half.precision},
        ]
    )
    assert agg2.auc == agg.auc


def test_aggregate_leaves_out_all_zero_curves_like_plotdrawsave():
    """MATLAB's plotDrawSave: ``aa = aa(sum(aa,2) > eps, :)`` before the mean, per curve."""
    gt = np.array([[10, 10, 20, 20]] * 4, float)
    perfect = score_sequence(gt, gt)
    # frame 1 unannotated (so not replaced by a valid box), the rest missed: the success
    # curve is all zero; precision is not (invalid frames are hits under "otb")
    gt_bad = gt.copy()
    gt_bad[0] = 0
    empty = score_sequence(np.array([[500, 500, 20, 20]] * 4, float), gt_bad)
    assert not empty.success.any() and empty.precision[20] == pytest.approx(1 / 4)

    agg = aggregate([perfect, empty])
    np.testing.assert_array_equal(agg.success, perfect.success)  # the empty curve is left out
    np.testing.assert_allclose(agg.precision, (perfect.precision + empty.precision) / 2)
    assert agg.auc == pytest.approx(20 / 21)
    assert agg.precision20 == pytest.approx((1 + 1 / 4) / 2)

    kept = aggregate([perfect, empty], drop_empty=False)
    np.testing.assert_allclose(kept.success, perfect.success / 2)
    assert kept.auc == pytest.approx(10 / 21)
    # all curves empty: nothing to leave out, the mean is zero
    assert aggregate([empty, empty]).auc == 0.0
    # precision curves are left out on their own (here as the dicts of summary.json)
    no_hits = {"success": perfect.success, "precision": np.zeros(51)}
    agg = aggregate([perfect, no_hits])
    np.testing.assert_array_equal(agg.precision, perfect.precision)
    np.testing.assert_array_equal(agg.success, perfect.success)
    assert aggregate([perfect, no_hits], drop_empty=False).precision20 == 0.5


def test_sequence_score_to_dict_holds_the_scores_as_plain_numbers():
    gt = np.array([[10, 10, 20, 20]] * 3 + [[0, 0, 0, 0]], float)
    pred = gt.copy()
    pred[2] = [14, 10, 20, 20]  # 16 of 20 columns: IoU 320 / 480
    s = score_sequence(pred, gt)
    d = s.to_dict()
    assert d == {"auc": s.auc, "precision20": s.precision20, "avg_overlap": s.avg_overlap, "n_frames": 4, "n_valid": 3}
    assert d["avg_overlap"] == pytest.approx((2 + 2 / 3) / 3)
    assert all(type(v) is float for k, v in d.items() if k not in ("n_frames", "n_valid"))
    assert type(d["n_frames"]) is int and type(d["n_valid"]) is int


def test_valid_groundtruth_default_rule_is_otb():
    """x = 0 is a valid size but fails MATLAB's "all four > 0": the default is the OTB rule."""
    gt = np.array([[0, 5, 10, 10], [3, 5, 10, 10]], float)
    np.testing.assert_array_equal(valid_groundtruth(gt), valid_groundtruth(gt, "otb"))
    np.testing.assert_array_equal(valid_groundtruth(gt), [False, True])
    np.testing.assert_array_equal(valid_groundtruth(gt, "pytracking"), [True, True])


def test_float32_boxes_are_scored_in_float64():
    """A float32 result file gives the same numbers as its float64 copy (computed in double, as MATLAB)."""
    rng = np.random.default_rng(7)
    a = (rng.uniform(0, 50, (30, 4)) + [0, 0, 5, 5]).astype(np.float32)
    b = (a + rng.normal(0, 3, a.shape)).astype(np.float32)
    a64, b64 = a.astype(np.float64), b.astype(np.float64)
    np.testing.assert_array_equal(overlap_ratio(a, b), overlap_ratio(a64, b64))
    np.testing.assert_array_equal(center_error(a, b), center_error(a64, b64))


def test_aggregate_with_empty_curves_warns_nothing():
    gt = np.array([[10, 10, 20, 20]] * 4, float)
    gt_bad = gt.copy()
    gt_bad[0] = 0
    empty = score_sequence(np.array([[500, 500, 20, 20]] * 4, float), gt_bad)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        agg = aggregate([score_sequence(gt, gt), empty])
    assert agg.auc == pytest.approx(20 / 21)
