"""bench/fit_confidence.py: the logistic fit of ConfidenceModel recovers known constants."""

import csv
import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from smtmvt.confidence import ConfidenceModel, Evidence, confidence

_BENCH = Path(__file__).resolve().parents[1] / "bench"
sys.path.insert(0, str(_BENCH))
_spec = importlib.util.spec_from_file_location("fit_confidence", _BENCH / "fit_confidence.py")
assert _spec is not None and _spec.loader is not None
fit_confidence = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(fit_confidence)


def _frames(model: ConfidenceModel, n: int, rng) -> tuple[np.ndarray, np.ndarray]:
    """n frames of random evidence, each tracked with the probability ``model`` gives it."""
    x = np.column_stack(
        [
            rng.normal(0, 0.4, n),
            rng.normal(0, 0.5, n),
            rng.normal(0, 0.5, n),
            rng.integers(0, 6, n).astype(float),
            rng.uniform(0, 2, n),
        ]
    )
    p = np.array(
        [
            confidence(Evidence(np.exp(a), np.exp(b), np.exp(c), int(s), d), model)
            for a, b, c, s, d in x  # the package's own mapping, not the fit's
        ]
    )
    return x, rng.random(n) < p


def test_the_fit_recovers_the_constants_that_made_the_frames():
    truth = ConfidenceModel(bias=2.0, peak=3.0, apce=0.5, cost=1.0, streak=0.4, drift=1.2)
    x, tracked = _frames(truth, 40000, np.random.default_rng(0))
    got = fit_confidence.fit(x, tracked)
    for name in ("bias", "peak", "apce", "cost", "streak", "drift"):
        assert getattr(got, name) == pytest.approx(getattr(truth, name), abs=0.15), name


def test_a_slope_the_data_contradict_is_held_at_zero():
    # frames made with a confidence that rises with the APCE, the APCE feature then negated:
    # the unconstrained maximum has apce near -0.8; the model's sign keeps it at 0
    truth = ConfidenceModel(bias=2.0, peak=3.0, apce=0.8, cost=1.0, streak=0.4)
    x, tracked = _frames(truth, 20000, np.random.default_rng(1))
    x[:, 1] = -x[:, 1]
    got = fit_confidence.fit(x, tracked)
    assert got.apce == pytest.approx(0.0, abs=1e-6)
    assert got.peak == pytest.approx(truth.peak, abs=0.3)


def test_read_frames_reads_the_calibration_csv(tmp_path):
    path = tmp_path / "frames.csv"
    with open(path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["sequence", "seed", "frame", "overlap", "confidence", "lost", *fit_confidence.FEATURES])
        out.writerow(["A", 0, 2, 0.8, 0.9, False, 0.1, 0.2, -0.3, 0, 0.4])
        out.writerow(["A", 0, 3, 0.05, 0.2, True, -1.0, -0.5, 0.7, 2, 1.6])
        out.writerow(["A", 0, 4, "nan", 0.2, True, -1.0, -0.5, 0.7, 3, 1.7])
    x, tracked = fit_confidence.read_frames(path)
    assert x.shape == (2, 5) and list(tracked) == [True, False]
    assert x[1].tolist() == [-1.0, -0.5, 0.7, 2.0, 1.6]
