"""One-pass-evaluation (OPE) metrics exactly as the OTB benchmark toolkit computes them.

Reference: the OTB MATLAB toolkit (``rstEval/calcRectInt.m``, ``util/calcSeqErrRobust.m``,
``perfPlot.m``), checked against got10k 0.1.3 (``got10k.utils.metrics``,
``got10k.experiments.otb.ExperimentOTB``) and pytracking's ``extract_results``.

Box convention
--------------
Boxes are ``(x, y, w, h)`` rows. Every function here is invariant to a common shift of both
arrays, so 0-based and 1-based boxes give the same numbers **as long as the prediction and the
ground truth use the same convention** (the OTB files, the got10k/pysot result files and
``RUN_DIR/results`` are all 1-based).

What the OTB toolkit does, and what we do
-----------------------------------------
* IoU (``calcRectInt``): pixel extents are inclusive, ``right = x + w - 1``; the intersection
  width is ``max(0, min(right1, right2) - max(x1, x2) + 1)``, which is algebraically
  ``max(0, min(x1 + w1, x2 + w2) - max(x1, x2))``; areas are ``w * h``. got10k's ``rect_iou``
  uses the second form and divides by ``union + eps`` then clips to [0, 1]: for boxes with
  positive sizes the two agree to ~1e-16. We compute the MATLAB expression literally, then
  cap it at 1 (as got10k): for two *equal non-integer* boxes rounding can make MATLAB's value
  1 + 1e-16, which would count as a success at threshold 1 (found by the got10k comparison
  test); integer boxes, such as all of OTB's ground truth, are unaffected.
* Centre: ``x + (w - 1) / 2`` (MATLAB, got10k, pysot, pytracking all agree).
* Frame 1's prediction is replaced by the ground truth before scoring (MATLAB and got10k).
* Predictions that are all NaN or have ``w <= 0`` or ``h <= 0`` take the previous frame's
  (already repaired) box, when that frame's ground truth has no NaN (MATLAB's loop, applied
  sequentially from frame 2). got10k does no such repair. Deviations from MATLAB, both only
  for pathological files: we replace frame 1 by the ground truth *before* the repair loop
  (MATLAB does it after, so an invalid frame-1 box would propagate), and we repair for every
  result type (MATLAB only for ``rect``; ``ivtAff`` boxes never have non-positive sizes in
  practice). A frame still non-finite after the repair (a partly-NaN box, MATLAB keeps it and
  gets NaN) counts as a failure: overlap 0, centre error +inf.
* Invalid ground truth (``invalid=``):

  - ``"otb"`` (default, MATLAB and pysot): a ground-truth row is valid only when all four
    numbers are ``> 0`` (MATLAB's ``sum(rect_anno > 0, 2) == 4``; note this also rejects
    boxes with ``x <= 0`` or ``y <= 0``, e.g. 7 frames of Biker, 1 of Crowds). Invalid frames
    get overlap -1 (a failure at every success threshold) and centre error -1 (a hit at
    every precision threshold); the denominator is the number of frames of the sequence.
  - ``"pytracking"``: pytracking with ``exclude_invalid_frames=True``: a row is valid when
    ``w > 0`` and ``h > 0``; invalid frames are dropped from numerators and denominators.
  - ``"fail"``: pytracking's default (``exclude_invalid_frames=False``): same validity test,
    invalid frames count as failures for both curves, denominator = all frames.

  got10k has no special case: an all-zero row scores IoU 0 and a (usually large) centre
  error, a NaN row fails both curves.
* Success curve: fraction of frames with overlap **strictly greater** than each of the 21
  thresholds ``0:0.05:1``; AUC = mean of the curve. Precision curve: fraction of frames with
  centre error ``<=`` each of ``0..50`` px; the precision score is the value at 20 px.
* Averaging: curves are computed per sequence and averaged over sequences
  (``aggregate``). Like MATLAB's ``plotDrawSave`` (``aa = aa(sum(aa,2) > eps, :)``) a
  sequence whose curve is identically zero is left out of that curve's mean; with frame 1
  set to the ground truth this cannot happen unless frame 1's ground truth is invalid.
* ``avg_overlap`` (the paper's table): the mean overlap over the frames with valid ground
  truth. This is the published ``overlapScores`` of the benchmark's score files (checked: it
  reproduces them on Biker and Crowds, which have invalid frames). MATLAB's
  ``aveErrCoverage`` instead divides the same sum by all frames; the two differ only on
  sequences with invalid ground truth (Biker, Board, Crowds, Twinnings in OTB-100).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

__all__ = [
    "SUCCESS_THRESHOLDS",
    "PRECISION_THRESHOLDS",
    "INVALID_MODES",
    "overlap_ratio",
    "center_error",
    "success_curve",
    "precision_curve",
    "valid_groundtruth",
    "repair_predictions",
    "prepare_predictions",
    "SequenceScore",
    "score_sequence",
    "Aggregate",
    "aggregate",
]

#: 21 overlap thresholds 0, 0.05, ..., 1 (MATLAB ``0:0.05:1``; got10k ``linspace(0, 1, 21)``).
SUCCESS_THRESHOLDS = np.linspace(0.0, 1.0, 21)
#: 51 location-error thresholds 0..50 px.
PRECISION_THRESHOLDS = np.arange(51, dtype=np.float64)
#: index of the 20 px threshold in ``PRECISION_THRESHOLDS``.
PRECISION_INDEX = 20
INVALID_MODES = ("otb", "pytracking", "fail")


def _as_boxes(a, name: str) -> np.ndarray:
    arr = np.asarray(a, dtype=np.float64)
    if arr.ndim == 1 and arr.shape[0] == 4:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != 4:
        raise ValueError(f"{name}: expected an (n, 4) array of x, y, w, h boxes, got shape {arr.shape}")
    return arr


def overlap_ratio(a, b) -> np.ndarray:
    """Per-row IoU of two ``(m, 4)`` box arrays, as the OTB toolkit's ``calcRectInt``.

    Inclusive pixel extents: ``right = x + w - 1``, ``inter_w = max(0, min(right_a, right_b)
    - max(x_a, x_b) + 1)`` (the same number as ``min(x_a + w_a, x_b + w_b) - max(x_a, x_b)``),
    ``IoU = inter / (w_a h_a + w_b h_b - inter)``. No clipping and no epsilon, as MATLAB (got10k
    adds ``eps`` to the union and clips to [0, 1]; identical to ~1e-16 for positive sizes),
    except that the result is capped at 1 (rounding can exceed it for equal non-integer
    boxes). Both arrays must use the same origin (0- or 1-based); rows with NaN give NaN.
    """
    a = _as_boxes(a, "overlap_ratio(a)")
    b = _as_boxes(b, "overlap_ratio(b)")
    if a.shape != b.shape:
        raise ValueError(f"overlap_ratio: shapes differ, {a.shape} vs {b.shape}")
    right_a = a[:, 0] + a[:, 2] - 1
    top_a = a[:, 1] + a[:, 3] - 1
    right_b = b[:, 0] + b[:, 2] - 1
    top_b = b[:, 1] + b[:, 3] - 1
    with np.errstate(invalid="ignore", divide="ignore"):
        iw = np.maximum(0.0, np.minimum(right_a, right_b) - np.maximum(a[:, 0], b[:, 0]) + 1)
        ih = np.maximum(0.0, np.minimum(top_a, top_b) - np.maximum(a[:, 1], b[:, 1]) + 1)
        # MATLAB's min/max skip NaN but the NaN area still makes the IoU NaN; mark it
        # explicitly so that a NaN box never reads as a zero-overlap box.
        nan = np.isnan(a).any(axis=1) | np.isnan(b).any(axis=1)
        inter = iw * ih
        union = a[:, 2] * a[:, 3] + b[:, 2] * b[:, 3] - inter
        iou = np.minimum(inter / union, 1.0)
    iou[nan] = np.nan
    return iou


def center_error(a, b) -> np.ndarray:
    """Euclidean distance between box centres ``(x + (w - 1) / 2, y + (h - 1) / 2)``.

    Same formula as the OTB toolkit, got10k and pytracking. Invariant to a common shift, so both
    arrays only need the same origin.
    """
    a = _as_boxes(a, "center_error(a)")
    b = _as_boxes(b, "center_error(b)")
    if a.shape != b.shape:
        raise ValueError(f"center_error: shapes differ, {a.shape} vs {b.shape}")
    ca = a[:, :2] + (a[:, 2:] - 1) / 2
    cb = b[:, :2] + (b[:, 2:] - 1) / 2
    return np.sqrt(np.sum((ca - cb) ** 2, axis=1))


def success_curve(overlaps, thresholds=SUCCESS_THRESHOLDS, n_frames: int | None = None) -> np.ndarray:
    """Fraction of frames whose overlap is **strictly greater** than each threshold.

    ``n_frames`` is the denominator (default ``len(overlaps)``); NaN overlaps never succeed.
    """
    ov = np.asarray(overlaps, dtype=np.float64).ravel()
    thr = np.asarray(thresholds, dtype=np.float64).ravel()
    n = ov.size if n_frames is None else int(n_frames)
    if n <= 0:
        return np.zeros(thr.size)
    with np.errstate(invalid="ignore"):
        hits = np.sum(ov[:, None] > thr[None, :], axis=0)
    return hits / n


def precision_curve(errors, thresholds=PRECISION_THRESHOLDS, n_frames: int | None = None) -> np.ndarray:
    """Fraction of frames whose centre error is ``<=`` each threshold (NaN never hits)."""
    err = np.asarray(errors, dtype=np.float64).ravel()
    thr = np.asarray(thresholds, dtype=np.float64).ravel()
    n = err.size if n_frames is None else int(n_frames)
    if n <= 0:
        return np.zeros(thr.size)
    with np.errstate(invalid="ignore"):
        hits = np.sum(err[:, None] <= thr[None, :], axis=0)
    return hits / n


def valid_groundtruth(gt, invalid: str = "otb") -> np.ndarray:
    """Boolean mask of ground-truth rows that are scored (see the module docstring).

    ``"otb"``: all four numbers ``> 0`` (MATLAB); ``"pytracking"`` / ``"fail"``: ``w > 0``
    and ``h > 0`` and no NaN.
    """
    gt = _as_boxes(gt, "groundtruth")
    _check_mode(invalid)
    with np.errstate(invalid="ignore"):
        if invalid == "otb":
            return np.all(gt > 0, axis=1)
        return np.all(np.isfinite(gt), axis=1) & (gt[:, 2] > 0) & (gt[:, 3] > 0)


def repair_predictions(pred, gt) -> np.ndarray:
    """MATLAB's repair loop: from frame 2 on, a prediction that is all NaN or has ``w <= 0``
    or ``h <= 0`` takes the previous (repaired) frame's box, when that frame's ground truth has
    no NaN. Returns a new array."""
    pred = _as_boxes(pred, "prediction").copy()
    gt = _as_boxes(gt, "groundtruth")
    gt_ok = ~np.isnan(gt).any(axis=1)
    with np.errstate(invalid="ignore"):
        bad = np.isnan(pred).all(axis=1) | (pred[:, 2] <= 0) | (pred[:, 3] <= 0)
    for i in np.flatnonzero(bad):
        if i >= 1 and gt_ok[i]:
            pred[i] = pred[i - 1]
    return pred


@dataclass
class SequenceScore:
    """Scores of one tracker on one sequence (see ``score_sequence``)."""

    overlaps: np.ndarray  #: per frame; -1 marks an invalid ground-truth frame ("otb"/"fail")
    errors: np.ndarray  #: per frame centre error; -1 ("otb") / +inf ("fail") on invalid frames
    success: np.ndarray  #: (21,) success curve
    precision: np.ndarray  #: (51,) precision curve
    auc: float
    precision20: float
    avg_overlap: float
    n_frames: int  #: frames of the sequence
    n_valid: int = 0  #: frames with valid ground truth
    valid: np.ndarray = field(default_factory=lambda: np.zeros(0, bool), repr=False)

    def to_dict(self) -> dict:
        return {
            "auc": float(self.auc),
            "precision20": float(self.precision20),
            "avg_overlap": float(self.avg_overlap),
            "n_frames": int(self.n_frames),
            "n_valid": int(self.n_valid),
        }


def _check_mode(invalid: str) -> None:
    if invalid not in INVALID_MODES:
        raise ValueError(f"invalid={invalid!r}: expected one of {', '.join(INVALID_MODES)}")


def prepare_predictions(
    pred, gt, invalid: str = "otb", replace_first: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The boxes as ``score_sequence`` scores them: ``(pred, gt, valid)``.

    ``pred`` and ``gt`` are ``(n, 4)`` boxes of the same length (a mismatch or an empty
    sequence raises ``ValueError``). Returns new ``(n, 4)`` float64 predictions with frame 1
    := ground truth (``replace_first``) and failed boxes repaired (``repair_predictions``),
    the ``(n, 4)`` float64 ground truth, and the ``(n,)`` bool mask of its scored frames
    (``valid_groundtruth``).
    """
    _check_mode(invalid)
    pred = _as_boxes(pred, "prediction")
    gt = _as_boxes(gt, "groundtruth")
    if pred.shape[0] != gt.shape[0]:
        raise ValueError(f"prediction has {pred.shape[0]} boxes but the ground truth has {gt.shape[0]}")
    if gt.shape[0] == 0:
        raise ValueError("empty sequence")
    pred = pred.copy()
    if replace_first:
        pred[0] = gt[0]
    return repair_predictions(pred, gt), gt, valid_groundtruth(gt, invalid)


def score_sequence(pred, gt, invalid: str = "otb", replace_first: bool = True) -> SequenceScore:
    """Score one result against its ground truth, as the OTB toolkit does.

    ``pred`` and ``gt`` are ``(n, 4)`` boxes in the same convention and of the same length
    (a length mismatch raises ``ValueError``; the caller names the file). Steps: frame 1's
    prediction := ground truth (``replace_first``), repair NaN / non-positive-size
    predictions (``repair_predictions``), IoU and centre error per frame, invalid ground-truth
    frames handled per ``invalid`` (module docstring), curves and scores
    (``prepare_predictions`` does the first three steps).
    """
    pred, gt, valid = prepare_predictions(pred, gt, invalid, replace_first)
    n = gt.shape[0]
    ov = overlap_ratio(pred, gt)
    err = center_error(pred, gt)
    # leftover non-finite predictions are failures
    ov = np.where(np.isfinite(ov), ov, 0.0)
    err = np.where(np.isfinite(err), err, np.inf)
    n_valid = int(valid.sum())

    avg = float(np.mean(ov[valid])) if n_valid else 0.0
    if invalid == "pytracking":
        ov_s, err_s = ov[valid], err[valid]
        denom = n_valid
        ov = np.where(valid, ov, -1.0)
        err = np.where(valid, err, np.inf)
    else:
        ov = np.where(valid, ov, -1.0)
        err = np.where(valid, err, -1.0 if invalid == "otb" else np.inf)
        ov_s, err_s = ov, err
        denom = n

    succ = success_curve(ov_s, n_frames=denom)
    prec = precision_curve(err_s, n_frames=denom)
    return SequenceScore(
        overlaps=ov,
        errors=err,
        success=succ,
        precision=prec,
        auc=float(np.mean(succ)),
        precision20=float(prec[PRECISION_INDEX]),
        avg_overlap=avg,
        n_frames=n,
        n_valid=n_valid,
        valid=valid,
    )


class Aggregate(NamedTuple):
    success: np.ndarray  #: (21,) mean success curve over sequences
    precision: np.ndarray  #: (51,) mean precision curve
    auc: float  #: mean of ``success``
    precision20: float  #: ``precision[20]``


def _mean_curves(curves: np.ndarray, drop_empty: bool) -> np.ndarray:
    if drop_empty:
        keep = curves.sum(axis=1) > np.finfo(float).eps
        if keep.any():
            curves = curves[keep]
    return curves.mean(axis=0)


def aggregate(scores: Iterable[SequenceScore | dict], drop_empty: bool = True) -> Aggregate:
    """Average the per-sequence curves over sequences (OTB OPE), then AUC and precision@20.

    Accepts ``SequenceScore`` objects or dicts with ``success`` and ``precision`` arrays.
    ``drop_empty`` leaves out sequences whose curve is all zero, as MATLAB's ``plotDrawSave``.
    """
    succ, prec = [], []
    for s in scores:
        if isinstance(s, dict):
            succ.append(np.asarray(s["success"], float))
            prec.append(np.asarray(s["precision"], float))
        else:
            succ.append(np.asarray(s.success, float))
            prec.append(np.asarray(s.precision, float))
    if not succ:
        raise ValueError("aggregate: no sequences to average")
    s_mean = _mean_curves(np.vstack(succ), drop_empty)
    p_mean = _mean_curves(np.vstack(prec), drop_empty)
    return Aggregate(s_mean, p_mean, float(np.mean(s_mean)), float(p_mean[PRECISION_INDEX]))
