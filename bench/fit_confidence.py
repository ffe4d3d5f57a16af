"""Fit :class:`smtmvt.confidence.ConfidenceModel` on one half's frames, check it on the other's.

Usage::

    python bench/fit_confidence.py --fit tune.csv [--check check.csv]

The CSV files are ``bench/lost_calibration.py --frames-out`` files (one line
per frame: its overlap with the ground truth and the evidence's five features,
:meth:`smtmvt.confidence.Evidence.features`). A frame is *tracked* when its
overlap is at least ``lost_calibration.LOST_OVERLAP``. The fit is a logistic
regression of "tracked" on the features (Platt scaling), by maximum likelihood
with the model's signs (``peak``, ``apce``, ``cost``, ``streak``, ``drift`` >= 0:
:class:`ConfidenceModel`'s linear score), by ``scipy.optimize.minimize``
(L-BFGS-B with those bounds). Prints the fitted constants, then for the fit
file and the check file the precision and recall of ``lost`` (confidence below
:data:`smtmvt.confidence.LOST_BELOW`), the expected calibration error and the
reliability table, for the current constants and the fitted ones. Fit on the
tuning half, judged on the checking half (``docs/split.md``).
Not a test: it measures.
"""

from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

from smtmvt.confidence import CONFIDENCE, LOST_BELOW, ConfidenceModel, Evidence, confidence

sys.path.insert(0, str(Path(__file__).resolve().parent))
from lost_calibration import FEATURES, LOST_OVERLAP, calibration_error, precision_recall, reliability

#: Signs of the features in the linear score (ConfidenceModel: + peak, + apce, - cost, - streak, - drift).
SIGNS = np.array([1.0, 1.0, -1.0, -1.0, -1.0])


def read_frames(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """``(features (m, 5), tracked (m,) bool)`` of the frames of a ``--frames-out`` CSV
    that have a ground-truth overlap."""
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["overlap"] not in ("", "nan")]
    if not rows:
        raise SystemExit(f"{path}: no frame with a ground-truth overlap")
    x = np.array([[float(r[k]) for k in FEATURES] for r in rows])
    tracked = np.array([float(r["overlap"]) >= LOST_OVERLAP for r in rows])
    return x, tracked


def confidences(model: ConfidenceModel, x: np.ndarray) -> np.ndarray:
    """Each frame's confidence ``(m,)`` under ``model``, by the package's own mapping
    (:func:`smtmvt.confidence.confidence`) of the features ``x`` ``(m, 5)``."""
    return np.array([confidence(Evidence(*np.exp(f[:3]), int(f[3]), float(f[4])), model) for f in x])


def fit(x: np.ndarray, tracked: np.ndarray) -> ConfidenceModel:
    """The :class:`ConfidenceModel` of largest likelihood of ``tracked`` given ``x``."""
    y = tracked.astype(np.float64)
    z = x * SIGNS  # slopes >= 0 on these columns

    def loss(theta):
        s = theta[0] + z @ theta[1:]
        # -log-likelihood of a logistic model and its gradient, stable for large |s|
        nll = np.sum(np.logaddexp(0.0, s) - y * s)
        g = 1.0 / (1.0 + np.exp(-s)) - y
        return nll, np.concatenate([[g.sum()], z.T @ g])

    names = ("bias", "peak", "apce", "cost", "streak", "drift")
    start = np.array([getattr(CONFIDENCE, name) for name in names])
    bounds = [(None, None)] + [(0.0, None)] * (len(names) - 1)
    res = minimize(loss, start, jac=True, method="L-BFGS-B", bounds=bounds)
    return ConfidenceModel(**{name: float(v) for name, v in zip(names, res.x)})


def report(label: str, model: ConfidenceModel, x: np.ndarray, tracked: np.ndarray) -> None:
    c = confidences(model, x)
    p, r = precision_recall(c < LOST_BELOW, tracked)
    table = reliability(c, tracked)
    print(f"{label}: {len(c)} frames, {np.mean(~tracked):.1%} truly lost, {np.mean(c < LOST_BELOW):.1%} called lost")
    print(f"  lost: precision {p:.3f}, recall {r:.3f}; expected calibration error {calibration_error(table):.3f}")
    for k, (mean, share, count) in enumerate(table):
        print(f"  [{k / len(table):.1f}, {(k + 1) / len(table):.1f})  {mean:6.3f}  {share:6.3f}  {int(count):6d}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fit", required=True, type=Path, help="frames to fit on (the tuning half)")
    ap.add_argument("--check", type=Path, default=None, help="frames to check on (the checking half)")
    args = ap.parse_args()
    x, tracked = read_frames(args.fit)
    fitted = fit(x, tracked)
    print(f"fitted: {fitted}")
    for path in [args.fit] + ([args.check] if args.check else []):
        xs, ts = (x, tracked) if path == args.fit else read_frames(path)
        report(f"{path.name}, current constants", CONFIDENCE, xs, ts)
        report(f"{path.name}, fitted constants", fitted, xs, ts)


if __name__ == "__main__":
    main()
