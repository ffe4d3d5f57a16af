"""OTB one-pass evaluation: run trackers over a benchmark, score them, report.

Running (:mod:`.runner`, :mod:`.trackers`; where pairs run: :mod:`.workers`)::

    from smtmvt.evaluation import run_evaluation, available_trackers, register_tracker
    run = run_evaluation("../shared/data/otb", ["smtmvt", "opencv-csrt"], "runs/example", workers=4)

The run folder, every path in it, its lock and its settings: :class:`RunDir`
(:mod:`.rundir`). Scoring (:mod:`.scoring`, :mod:`.metrics`), writing the report
(:mod:`.report`, :mod:`.tables`, :mod:`.page`, :mod:`.plots`), published results
(:mod:`.published`) and imports (:mod:`.imports`) are re-exported here too; they are
imported on first use, so ``import smtmvt.evaluation`` stays light (no matplotlib).

Command line: ``smtmvt evaluate`` and ``smtmvt report`` (:mod:`.cli`).
"""

from __future__ import annotations

import importlib

from . import metrics as _metrics
from .rundir import RunDir, RunDirError, RunInfo, RunLockedError
from .runner import (
    PairOutcome,
    PairTask,
    RunResult,
    count_lines,
    result_path,
    run_evaluation,
    run_pair,
    sequence_seed,
    times_path,
)
from .trackers import (
    EvalTracker,
    OpenCVTracker,
    SmtmvtAdapter,
    TrackerSpec,
    UnknownTrackerError,
    available_trackers,
    get_factory,
    make_tracker,
    register_tracker,
    to_bgr8,
    tracker_spec,
    unregister_tracker,
)

#: Names re-exported lazily from the scoring/report modules: ``name -> module``.
_LAZY = {
    **dict.fromkeys(_metrics.__all__, "metrics"),  # numpy only: its name list is read, not copied
    **dict.fromkeys(
        (
            "load_published_scores",
            "published_trackers",
            "import_results",
            "load_attribute_table",
            "read_otb_mat",
            "read_otb_json",
            "ImportedResult",
        ),
        "published",
    ),
    **dict.fromkeys(("import_into_run",), "imports"),
    **dict.fromkeys(("build_report", "load_groundtruth_source"), "report"),
    **dict.fromkeys(("score_run", "Summary"), "scoring"),
    **dict.fromkeys(("plot_curves", "render_curves", "select_curves", "Curve"), "plots"),
}

__all__ = [
    "EvalTracker",
    "OpenCVTracker",
    "PairOutcome",
    "PairTask",
    "RunDir",
    "RunDirError",
    "RunInfo",
    "RunLockedError",
    "RunResult",
    "SmtmvtAdapter",
    "TrackerSpec",
    "UnknownTrackerError",
    "available_trackers",
    "count_lines",
    "get_factory",
    "make_tracker",
    "register_tracker",
    "result_path",
    "run_evaluation",
    "run_pair",
    "sequence_seed",
    "times_path",
    "to_bgr8",
    "tracker_spec",
    "unregister_tracker",
    *_LAZY,
]


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    try:
        mod = importlib.import_module(f"{__name__}.{module}")
    except ImportError as exc:
        raise AttributeError(
            f"smtmvt.evaluation.{name} needs smtmvt.evaluation.{module}, which cannot be imported: {exc}"
        ) from exc
    try:
        value = getattr(mod, name)
    except AttributeError:
        raise AttributeError(f"smtmvt.evaluation.{module} has no attribute {name!r}") from None
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
