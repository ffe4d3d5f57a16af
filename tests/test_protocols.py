"""TRE segment starts, SRE start boxes and segment pooling, checked by hand against the OTB
MATLAB toolkit's formulas (``util/splitSeqTRE.m``, ``util/shiftInitBB.m``, ``genPerfMat.m``).

Every expected value below was worked out on paper from the toolkit's code, not computed by
the function under test; the working is in the comments.
"""

from __future__ import annotations

import numpy as np
import pytest

from smtmvt.evaluation.metrics import score_sequence
from smtmvt.evaluation.protocols import (
    SRE_SHIFTS,
    Segment,
    init_omit,
    parse_protocols,
    pool_scores,
    segments,
    shift_box,
    start_box,
    tre_starts,
)


def test_tre_starts_of_a_clean_40_frame_sequence():
    # len = 40, all valid: candidates 1..40; the last f with 40 - f + 1 >= 20 is f = 21, so E = 21.
    # floor(1 : 21/19 : 21) = floor(1, 2.105, 3.211, 4.316, 5.421, 6.526, 7.632, 8.737, 9.842,
    # 10.947, 12.053, 13.158, 14.263, 15.368, 16.474, 17.579, 18.684, 19.789, 20.895)
    # = 1..10, 12..20 (11 is stepped over), then E = 21: twenty 1-based starts.
    gt = np.tile([10.0, 19.0, 31.0, 45.0], (40, 1))
    expected_1based = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21]
    assert tre_starts(gt) == [f - 1 for f in expected_1based]


def test_tre_starts_skip_invalid_and_omitted_frames_and_repeat_like_the_toolkit():
    # len = 30; frame 1 has x = 0 (invalid: r(1) <= 0); frames 5..7 are in initOmit.
    # Candidates (1-based): 2, 3, 4, 8, 9, ..., 30. Usable (30 - f + 1 >= 20): f <= 11, i.e.
    # 2, 3, 4, 8, 9, 10, 11 -> E = 7. Colon 1 : 7/19 : 7 has floor(6 / 0.3684) + 1 = 17 elements
    # 1, 1.37, 1.74, 2.11, 2.47, 2.84, 3.21, 3.58, 3.95, 4.32, 4.68, 5.05, 5.42, 5.79, 6.16,
    # 6.53, 6.89 -> floored 1,1,1,2,2,2,3,3,3,4,4,5,5,5,6,6,6, then 7: 18 positions.
    # Positions -> candidates: 1->2, 2->3, 3->4, 4->8, 5->9, 6->10, 7->11.
    gt = np.tile([10.0, 19.0, 31.0, 45.0], (30, 1))
    gt[0, 0] = 0
    expected_1based = [2, 2, 2, 3, 3, 3, 4, 4, 4, 8, 8, 9, 9, 9, 10, 10, 10, 11]
    assert [s + 1 for s in tre_starts(gt, omit=[(5, 7)])] == expected_1based


def test_tre_starts_nan_rows_are_invalid_and_a_short_sequence_is_a_clear_error():
    gt = np.tile([10.0, 19.0, 31.0, 45.0], (25, 1))
    gt[:6] = np.nan  # 25 - f + 1 >= 20 needs f <= 6: frames 1..6 are all invalid
    with pytest.raises(ValueError, match="no TRE segment.*20 or more frames from the end.*25 frames"):
        tre_starts(gt)
    gt[5] = [10.0, 19.0, 31.0, 45.0]  # frame 6 valid: E = 1, colon 1:1/19:1 = [1], then 1
    assert tre_starts(gt) == [5, 5]


# 1-based box [x y w h] = [10 19 31 45]: br = (40, 63), 0.1 w = 3.1, 0.1 h = 4.5, centre (25.5, 41.5).
# MATLAB's round takes halves away from zero (14.5 -> 15, 40.5 -> 41, 67.5 -> 68).
HAND_SHIFTS = {
    "left": [6, 19, 31, 45],  # x - ceil(3.1) = 10 - 4
    "right": [14, 19, 31, 45],  # x + 4
    "up": [10, 14, 31, 45],  # y - ceil(4.5) = 19 - 5
    "down": [10, 24, 31, 45],  # y + 5
    "topLeft": [7, 15, 34, 49],  # x = round(6.9), y = round(14.5); w = 40 - 7 + 1, h = 63 - 15 + 1
    "topRight": [10, 15, 34, 49],  # br_x = round(43.1) = 43: w = 43 - 10 + 1; y = 15
    "bottomLeft": [7, 19, 34, 50],  # x = 7; br_y = round(67.5) = 68: h = 68 - 19 + 1
    "bottomRight": [10, 19, 34, 50],  # br_x = 43, br_y = 68
    "scale_8": [13, 24, 25, 36],  # round([25.5 - 12.4, 41.5 - 18, 24.8, 36]) = round([13.1 23.5 24.8 36])
    "scale_9": [12, 21, 28, 41],  # round([11.55 21.25 27.9 40.5])
    "scale_11": [8, 17, 34, 50],  # round([8.45 16.75 34.1 49.5])
    "scale_12": [7, 15, 37, 54],  # round([6.9 14.5 37.2 54])
}


@pytest.mark.parametrize("shift", SRE_SHIFTS)
def test_sre_boxes_inside_the_image(shift):
    got = shift_box([10, 19, 31, 45], shift, image_size=(200, 300))
    assert got.tolist() == HAND_SHIFTS[shift]


# Clipping (image W = 25, H = 30) of [3 2 20 30]: br = (22, 31), 0.1 w = 2, 0.1 h = 3.
# x < 1 -> 1 and y < 1 -> 1 without changing w, h; then w = W - x + 1 if x + w - 1 > W,
# h = H - y + 1 if y + h - 1 > H (the box already overruns the bottom: 2 + 30 - 1 = 31 > 30).
HAND_CLIPPED = {
    "left": [1, 2, 20, 29],  # x = 3 - 2 = 1; h = 30 - 2 + 1
    "up": [3, 1, 20, 30],  # y = 2 - 3 = -1 -> 1 (h stays 30); 1 + 30 - 1 = 30 fits
    "down": [3, 5, 20, 26],  # y = 5; h = 30 - 5 + 1
    "topLeft": [1, 1, 22, 30],  # x = round(1) = 1, y = round(-1) = -1: w = 22, h = 33; y -> 1, h -> 30
    "scale_12": [1, 1, 24, 30],  # centre (13, 17): round([1 -1 24 36]); y -> 1; h -> 30
}


@pytest.mark.parametrize("shift", sorted(HAND_CLIPPED))
def test_sre_boxes_are_clipped_to_the_image_as_the_toolkit_does(shift):
    assert shift_box([3, 2, 20, 30], shift, image_size=(30, 25)).tolist() == HAND_CLIPPED[shift]


def test_segments_of_each_protocol():
    gt = np.tile([10.0, 19.0, 31.0, 45.0], (40, 1))
    assert segments("ope", gt) == [Segment("ope", "", 0)]
    tre = segments("tre", gt)
    assert [s.name for s in tre][:3] == ["seg-01", "seg-02", "seg-03"] and len(tre) == 20
    assert tre[10].start == 11 and tre[10].label == "tre seg-11 (from frame 12)"
    sre = segments("sre", gt)
    assert [s.shift for s in sre] == list(SRE_SHIFTS) and {s.start for s in sre} == {0}
    assert start_box(sre[0], gt, (200, 300)).tolist() == HAND_SHIFTS["left"]
    assert start_box(tre[10], gt).tolist() == gt[11].tolist()
    with pytest.raises(ValueError, match="image size"):
        start_box(sre[0], gt)
    with pytest.raises(ValueError, match="protocol 'xyz'"):
        segments("xyz", gt)


def test_parse_protocols():
    assert parse_protocols("sre,OPE") == ["ope", "sre"]
    assert parse_protocols(["tre"]) == ["tre"]
    with pytest.raises(ValueError, match="protocol abc: expected one or more of ope, tre, sre"):
        parse_protocols("ope,abc")


def test_pooling_sums_hits_over_summed_lengths():
    # Segment A: 5 frames, IoU 1 (frame 1 := ground truth), 1, 0, 0, 0 -> 2/5 at t = 0.5.
    # Segment B: 2 frames, IoU 1, 0 -> 1/2. genPerfMat pools: (2 + 1) / (5 + 2) = 3/7,
    # not the mean of the two rates (0.45).
    gt_a = np.tile([1.0, 1.0, 10.0, 10.0], (5, 1))
    pred_a = gt_a.copy()
    pred_a[2:] = [50.0, 50.0, 10.0, 10.0]
    gt_b = np.tile([1.0, 1.0, 10.0, 10.0], (2, 1))
    pred_b = gt_b.copy()
    pred_b[1] = [50.0, 50.0, 10.0, 10.0]
    a, b = score_sequence(pred_a, gt_a), score_sequence(pred_b, gt_b)
    pooled = pool_scores([a, b])
    i_half = 10  # threshold 0.5
    assert a.success[i_half] == pytest.approx(2 / 5) and b.success[i_half] == pytest.approx(1 / 2)
    assert pooled.success[i_half] == pytest.approx(3 / 7)
    assert pooled.precision[20] == pytest.approx(3 / 7)  # centre errors 0 or ~69 px
    assert pooled.auc == pytest.approx(np.mean(pooled.success))
    assert pooled.n_frames == 7 and pooled.overlaps.shape == (7,)
    assert pooled.avg_overlap == pytest.approx(3 / 7)


def test_the_toolkits_omitted_start_frames_are_applied_to_otb_sequences_only():
    # initOmit/matrix.txt is "36 40". len = 60: candidates 1..35, 41..60; usable (60 - f + 1 >= 20)
    # f <= 41: 1..35, 41 -> E = 36. floor(1 : 36/19 : 36) = floor(1, 2.89, 4.79, 6.68, 8.58,
    # 10.47, 12.37, 14.26, 16.16, 18.05, 19.95, 21.84, 23.74, 25.63, 27.53, 29.42, 31.32, 33.21,
    # 35.11), then 36; positions 1..35 are frames 1..35, position 36 is frame 41.
    assert init_omit("Matrix") == ((36, 40),) and init_omit("matrix", layout="vot") == ()
    assert init_omit("Jogging-1") == ((61, 83),) and init_omit("Crossing") == ()
    gt = np.tile([10.0, 19.0, 31.0, 45.0], (60, 1))
    expected_1based = [1, 2, 4, 6, 8, 10, 12, 14, 16, 18, 19, 21, 23, 25, 27, 29, 31, 33, 35, 41]
    assert [s + 1 for s in tre_starts(gt, init_omit("Matrix"))] == expected_1based
    assert [s.start + 1 for s in segments("tre", gt, init_omit("Matrix"))] == expected_1based
