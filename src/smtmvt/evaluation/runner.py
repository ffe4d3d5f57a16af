"""One-pass evaluation (OPE) runner: every tracker on every sequence, resumable, parallel.

Usage::

    from smtmvt.evaluation import run_evaluation
    run = run_evaluation("../shared/data/otb", ["smtmvt", "opencv-csrt"], "/tmp/run",
                         workers=4)                       # or scheduler="tcp://host:8786"
    run.ok, run.failed, run.report_dir

Protocol
--------
Each tracker is initialised on frame 1 with the first ground-truth box and run over the
whole sequence without re-initialisation (OTB's OPE). Frame 1's reported box is the
initial box. ``max_frames`` cuts sequences short for quick checks; such runs are **not**
OTB-compliant (the report engineer's code reads ``max_frames`` from ``run.json``).

Run folder (shared with :mod:`smtmvt.evaluation.report`)
--------------------------------------------------------
``RUN_DIR/results/<tracker>/<sequence>.txt``
    1-based ``x,y,w,h``, one line per frame (got10k / pysot layout).
``RUN_DIR/results/<tracker>/times/<sequence>_time.txt``
    Seconds per frame: ``init`` for frame 1, ``update`` for the others, measured with
    ``time.perf_counter`` around the adapter's call only (includes the adapter's colour
    conversion, excludes reading the image).
``RUN_DIR/run.json``
    ``{"dataset", "trackers", "sequences", "attributes", "published", "max_frames"}``;
    on restart the lists are merged (union, first-seen order).
``RUN_DIR/errors.json``
    ``[{"tracker", "sequence", "error"}, ...]``, rewritten atomically after every change. An
    entry is removed when its pair later succeeds (or is found complete). ``sequence`` is
    null for an unknown tracker name.

Resuming
--------
The unit of work is one (tracker, sequence) pair. A pair is skipped when its result file
exists with exactly as many lines as frames to run; otherwise it is (re)computed. Workers
*return* boxes and times to the driver, which writes the times file and then the result
file, each atomically (temporary file + ``os.replace``), as soon as the pair completes: a
killed run loses only the pairs in flight, never a finished one, and never leaves a partial
result file (the result file is the completion marker). Only the driver needs write access
to ``RUN_DIR``; workers only read the dataset, so a Dask cluster needs the dataset at the
same path on every worker, nothing more.

Errors
------
Every pair is run inside ``try``: an exception (a missing or unreadable image, a tracker
that raises) is recorded in ``errors.json`` naming the tracker, the sequence, the frame and
the file, nothing is written for that pair, and the other pairs go on. A pair is stopped at
its first bad frame: a box sequence with a hole cannot be scored under OPE. Sequences whose
folder or ground truth cannot be read are recorded for each tracker; an unknown tracker
name is recorded once, and the known trackers run.

Parallelism and determinism
---------------------------
``workers > 1`` runs pairs in a ``ProcessPoolExecutor`` with the ``spawn`` start method (safe
with OpenCV's threads); ``scheduler`` (an address or a ``distributed.Client``) runs them
on a Dask cluster, one ``client.submit`` per pair with picklable arguments only (tracker
name and factory, the :class:`~smtmvt.data.Sequence` object, which holds file paths and
ground truth but no pixels). Worker processes use one OpenCV/BLAS thread each, like
Dask's workers. Each tracker gets a seed derived from the sequence name
(:func:`sequence_seed`), so the same pair gives the same boxes wherever it runs (for the
trackers that are deterministic given a seed; see :mod:`.trackers` about OpenCV's MIL/TLD).
"""

from __future__ import annotations

import contextlib
import json
import multiprocessing
import os
import sys
import time
import traceback
import uuid
import zlib
from collections.abc import Callable, Iterable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..data import write_boxes, write_text_atomic
from .trackers import UnknownTrackerError, accepts_keyword, get_factory

__all__ = [
    "run_evaluation",
    "run_pair",
    "RunResult",
    "PairTask",
    "PairOutcome",
    "sequence_seed",
    "result_path",
    "times_path",
    "count_lines",
]

RESULTS = "results"
RUN_JSON = "run.json"
ERRORS_JSON = "errors.json"
# Thread caps for worker processes (the same as Dask's nanny sets for its workers).
_WORKER_ENV = {"OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}


# --------------------------------------------------------------------------- paths


def result_path(run_dir, tracker: str, sequence: str) -> Path:
    """``RUN_DIR/results/<tracker>/<sequence>.txt``."""
    return Path(run_dir) / RESULTS / tracker / f"{sequence}.txt"


def times_path(run_dir, tracker: str, sequence: str) -> Path:
    """``RUN_DIR/results/<tracker>/times/<sequence>_time.txt``."""
    return Path(run_dir) / RESULTS / tracker / "times" / f"{sequence}_time.txt"


def count_lines(path) -> int | None:
    """Number of non-blank lines of ``path``; None when it does not exist or can't be read."""
    try:
        with open(path, "rb") as f:
            return sum(1 for line in f if line.strip())
    except OSError:
        return None


def sequence_seed(sequence: str, base: int = 0) -> int:
    """Deterministic per-sequence seed: ``crc32(name) xor base``, 31 bits."""
    return (zlib.crc32(sequence.encode("utf-8")) ^ int(base)) & 0x7FFFFFFF


def write_times(path, times) -> Path:
    """Seconds per frame, one per line, atomically."""
    return write_text_atomic(path, "".join(f"{float(t):.9f}\n" for t in times))


# --------------------------------------------------------------------------- one pair


@dataclass(frozen=True)
class PairTask:
    """Everything a worker needs for one (tracker, sequence) pair; picklable.

    ``factory`` is the registry's factory (a module-level function or partial), resolved
    in the driver so that trackers registered at run time work in worker processes too.
    """

    tracker: str
    factory: Callable
    options: dict
    sequence: object  # smtmvt.data.Sequence (paths + ground truth, no pixels)
    n_frames: int
    seed: int
    single_thread: bool = False


@dataclass
class PairOutcome:
    """What a worker sends back: boxes and times, or an error message."""

    tracker: str
    sequence: str
    n_frames: int
    boxes: np.ndarray | None = None  # (n, 4) 0-based
    times: np.ndarray | None = None  # (n,) seconds
    error: str | None = None
    lost_frames: int | None = None
    wall: float = 0.0

    @property
    def ok(self) -> bool:
        return self.error is None


def _describe(exc: BaseException) -> str:
    text = str(exc).strip()
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def run_pair(task: PairTask, on_frame: Callable[[int], None] | None = None) -> PairOutcome:
    """Run one tracker over one sequence (OPE). Never raises for bad data or a bad tracker:
    the failure is returned in ``PairOutcome.error``, naming tracker, sequence, frame and file.

    ``on_frame(k)`` (in-process runs only) is called with the number of frames just done.
    """
    from ..data import SequenceError

    seq = task.sequence
    name = seq.name
    t_start = time.perf_counter()
    out = PairOutcome(task.tracker, name, task.n_frames)
    if task.single_thread:
        with contextlib.suppress(Exception):
            import cv2

            cv2.setNumThreads(1)
    where = "creating the tracker"
    frame_index = None
    try:
        options = dict(task.options)
        if accepts_keyword(task.factory, "seed"):
            options["seed"] = task.seed
        else:
            options.pop("seed", None)
        tracker = task.factory(**options)
        where = "reading the first ground-truth box"
        first = tuple(float(v) for v in seq.first_box)
        n = task.n_frames
        boxes = np.empty((n, 4), dtype=np.float64)
        times = np.empty(n, dtype=np.float64)
        for i in range(n):
            frame_index = i
            where = "reading"
            frame = seq[i]
            where = "tracking"
            if i == 0:
                t0 = time.perf_counter()
                tracker.init(frame, first)
                times[0] = time.perf_counter() - t0
                boxes[0] = first
            else:
                t0 = time.perf_counter()
                box = tracker.update(frame)
                times[i] = time.perf_counter() - t0
                box = np.asarray(box, dtype=np.float64).reshape(-1)
                if box.shape != (4,):
                    raise ValueError(f"update() returned {box.size} numbers, expected x, y, w, h")
                boxes[i] = box
            if on_frame is not None:
                on_frame(1)
        bad = ~np.isfinite(boxes).all(axis=1)
        if bad.any():
            k = int(np.argmax(bad))
            frame_index = k
            where = "checking the boxes"
            raise ValueError(f"non-finite box {boxes[k].tolist()} returned")
        out.boxes, out.times = boxes, times
        out.lost_frames = getattr(tracker, "lost_frames", None)
    except SequenceError as exc:  # names the file and the frame/line itself
        out.error = f"{task.tracker} on {name}: {exc}"
    except Exception as exc:  # noqa: BLE001 - one bad pair must never stop the run
        if frame_index is None:
            out.error = f"{task.tracker} on {name}: {where}: {_describe(exc)}"
        else:
            frame_name = seq.frame_names[frame_index] if frame_index < len(seq.frame_names) else "?"
            source = getattr(seq, "files", None)
            file_txt = str(source[frame_index]) if source is not None else frame_name
            out.error = f"{task.tracker} on {name}: frame {frame_index} ({file_txt}): {where}: {_describe(exc)}"
        tb = traceback.extract_tb(exc.__traceback__)
        if tb:  # where in the code, for the tracker's author
            last = tb[-1]
            out.error += f" [at {Path(last.filename).name}:{last.lineno}]"
    out.wall = time.perf_counter() - t_start
    return out


# --------------------------------------------------------------------------- bookkeeping


class _ErrorLog:
    """``errors.json``: one entry per (tracker, sequence); rewritten atomically."""

    def __init__(self, path: Path):
        self.path = path
        self.entries: dict[tuple, str] = {}
        if path.exists():
            try:
                data = json.loads(path.read_text(encoding="utf-8"))
                for e in data:
                    self.entries[(e.get("tracker"), e.get("sequence"))] = str(e.get("error"))
            except (ValueError, TypeError, AttributeError, OSError):
                # a damaged errors.json is rebuilt from this run
                self.entries = {}

    def set(self, tracker, sequence, error: str) -> None:
        self.entries[(tracker, sequence)] = error
        self.save()

    def clear(self, tracker, sequence) -> None:
        if self.entries.pop((tracker, sequence), None) is not None:
            self.save()

    def as_list(self) -> list:
        return [{"tracker": t, "sequence": s, "error": e} for (t, s), e in self.entries.items()]

    def save(self) -> None:
        write_text_atomic(self.path, json.dumps(self.as_list(), indent=1) + "\n")


def _merge_unique(old: Iterable, new: Iterable) -> list:
    out = []
    for x in list(old or []) + list(new or []):
        if x not in out:
            out.append(x)
    return out


def _update_run_json(run_dir: Path, dataset: Path, trackers, sequences, attributes, published, max_frames):
    path = run_dir / RUN_JSON
    old = {}
    if path.exists():
        try:
            old = json.loads(path.read_text(encoding="utf-8"))
        except ValueError as exc:
            raise ValueError(f"{path}: not valid JSON ({exc}); remove it or choose another --out") from None
        if not isinstance(old, dict):
            raise ValueError(f"{path}: expected a JSON object; remove it or choose another --out")
        old_ds = old.get("dataset")
        if old_ds and Path(old_ds).resolve() != dataset:
            raise ValueError(
                f"{run_dir} holds results for dataset {old_ds}, not {dataset}; "
                f"choose another --out (results of different datasets must not mix)"
            )
    info = dict(old)
    info.update(
        {
            "dataset": str(dataset),
            "trackers": _merge_unique(old.get("trackers"), trackers),
            "sequences": _merge_unique(old.get("sequences"), sequences),
            "attributes": str(Path(attributes).resolve()) if attributes else old.get("attributes"),
            "published": str(Path(published).resolve()) if published else old.get("published"),
            "max_frames": max_frames,
        }
    )
    write_text_atomic(path, json.dumps(info, indent=1) + "\n")
    return info


# --------------------------------------------------------------------------- result


@dataclass
class RunResult:
    """Summary of :func:`run_evaluation`.

    Attributes
    ----------
    run_dir : Path
    trackers, sequences : names that were run (known trackers, readable sequences).
    done : pairs computed in this call; skipped : pairs already complete.
    errors : this call's errors, ``{"tracker", "sequence", "error"}`` dicts (also in
        ``errors.json``, which keeps errors of pairs not part of this call).
    notes : remarks (e.g. result files recomputed because their length was wrong).
    report : what ``build_report`` returned, or None; report_error : why it failed.
    """

    run_dir: Path
    trackers: list = field(default_factory=list)
    sequences: list = field(default_factory=list)
    done: list = field(default_factory=list)
    skipped: list = field(default_factory=list)
    errors: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    frames: int = 0
    seconds: float = 0.0
    report: dict | None = None
    report_error: str | None = None

    @property
    def ok(self) -> bool:
        """True when every requested pair is complete and no error occurred."""
        return not self.errors

    @property
    def failed(self) -> list:
        """``(tracker, sequence)`` of the pairs that failed in this call."""
        return [(e["tracker"], e["sequence"]) for e in self.errors]

    @property
    def report_dir(self) -> Path:
        return self.run_dir / "report"


# --------------------------------------------------------------------------- the run


def _open_sequences(dataset_dir: Path, sequences):
    """``(sequences, errors, unknown)``: the opened sequences, ``(name, message)`` for each
    sequence that could not be opened (missing image, malformed ground truth, ...), and
    ``(name, message)`` for each requested name the dataset does not have."""
    from ..data import SequenceError, open_dataset

    items = []
    errors, unknown = [], []
    try:
        items = open_dataset(dataset_dir, sequences=sequences, on_error="collect")
    except SequenceError:
        if sequences is None:  # the dataset itself is unusable
            raise
        # some requested names are unknown: open the others one by one
        for name in sequences:
            try:
                items.extend(open_dataset(dataset_dir, sequences=[name], on_error="collect"))
            except SequenceError as exc_one:
                unknown.append((name, str(exc_one)))
    seqs, seen = [], set()
    for item in items:
        if isinstance(item, SequenceError):
            if item.sequence not in seen:
                seen.add(item.sequence)
                errors.append((item.sequence, str(item)))
        elif item.name not in seen:
            seen.add(item.name)
            seqs.append(item)
    return seqs, errors, unknown


def _check_options(factory, options: dict) -> None:
    """Build one tracker with ``options`` (and a seed when accepted) and drop it."""
    if accepts_keyword(factory, "seed"):
        options = {**options, "seed": 0}
    factory(**options)


def _resolve_trackers(trackers) -> tuple[list, list]:
    names = [t.strip() for t in (trackers.split(",") if isinstance(trackers, str) else trackers)]
    names = [t for t in _merge_unique([], names) if t]
    if not names:
        raise ValueError("no tracker given")
    known, unknown = [], []
    for name in names:
        try:
            known.append((name, get_factory(name)))
        except UnknownTrackerError as exc:
            unknown.append((name, str(exc)))
    return known, unknown


@contextlib.contextmanager
def _worker_environ():
    saved = {k: os.environ.get(k) for k in _WORKER_ENV}
    os.environ.update(_WORKER_ENV)
    try:
        yield
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


def _client_for(scheduler):
    try:
        import distributed
    except ImportError as exc:  # pragma: no cover - optional dependency
        raise ValueError("--scheduler needs dask.distributed (pip install 'smtmvt[distributed]')") from exc
    if isinstance(scheduler, distributed.Client):
        return scheduler, False
    try:
        # connect timeout: dask's distributed.comm.timeouts.connect (30 s by default)
        return distributed.Client(scheduler), True
    except (OSError, TimeoutError) as exc:
        raise OSError(f"cannot connect to the Dask scheduler at {scheduler}: {exc}") from None


def run_evaluation(
    dataset_dir,
    trackers,
    out_dir,
    sequences=None,
    workers: int = 1,
    scheduler=None,
    tracker_options: dict | None = None,
    progress: bool = True,
    max_frames: int | None = None,
    report: bool = True,
    attributes=None,
    published=None,
) -> RunResult:
    """Run each tracker on each sequence of an OTB-format dataset into ``out_dir``.

    Parameters
    ----------
    dataset_dir : path of a folder of OTB sequences (see :func:`smtmvt.data.open_dataset`).
    trackers : names (list or comma-separated string) from
        :func:`~smtmvt.evaluation.trackers.available_trackers`. Unknown names are recorded as
        errors and the known ones still run.
    out_dir : the run folder (created; reused to resume).
    sequences : names to run (list or comma-separated); default all of the dataset.
    workers : processes for local parallel runs (1: in this process).
    scheduler : a Dask scheduler address (``"tcp://host:8786"``) or a ``distributed.Client``;
        when given, pairs run on the cluster and ``workers`` is ignored.
    tracker_options : ``{tracker name: {option: value}}`` passed to the tracker factories
        (``{"smtmvt": {"n_particles": 200}}``). A ``seed`` there is the base of the
        per-sequence seeds.
    progress : show tqdm bars (pairs done, frames done) on stderr.
    max_frames : run at most this many frames per sequence (quick checks, not OTB-compliant).
    report : call :func:`smtmvt.evaluation.report.build_report` at the end when available.
    attributes, published : paths stored in ``run.json`` and passed to the report.

    Returns
    -------
    RunResult

    Raises
    ------
    ValueError, OSError
        Only for problems with the whole run (no dataset folder, a run folder made for another
        dataset, no tracker given, unreachable scheduler); everything per pair is recorded.
    """
    t_run = time.perf_counter()
    dataset_dir = Path(dataset_dir).expanduser().resolve()
    if not dataset_dir.is_dir():
        raise FileNotFoundError(f"dataset folder not found: {dataset_dir}")
    run_dir = Path(out_dir).expanduser().resolve()
    if isinstance(sequences, str):
        sequences = [s.strip() for s in sequences.split(",") if s.strip()]
    if max_frames is not None and int(max_frames) < 1:
        raise ValueError(f"max_frames must be >= 1, got {max_frames}")
    workers = int(workers)
    if workers < 1:
        raise ValueError(f"workers must be >= 1, got {workers}")
    tracker_options = dict(tracker_options or {})

    known, unknown = _resolve_trackers(trackers)
    for name in tracker_options:
        if name not in {k for k, _ in known} and name not in {u for u, _ in unknown}:
            raise ValueError(f"tracker options given for {name!r}, which is not among the trackers run")
    seqs, seq_errors, unknown_seqs = _open_sequences(dataset_dir, sequences)
    if not seqs and not seq_errors and not unknown_seqs:
        raise ValueError(f"no OTB sequence (sub-folder with img/ and groundtruth_rect.txt) in {dataset_dir}")

    run_dir.mkdir(parents=True, exist_ok=True)
    tracker_names = [k for k, _ in known]
    seq_names = [s.name for s in seqs] + [n for n, _ in seq_errors if n]
    info = _update_run_json(run_dir, dataset_dir, tracker_names, seq_names, attributes, published, max_frames)
    log = _ErrorLog(run_dir / ERRORS_JSON)
    # Errors about names given on a previous command line (unknown tracker or sequence) are
    # properties of that command, not of the run's data: drop them, this call re-adds its own.
    for key in [k for k in log.entries if k[1] is None or k[1] not in info["sequences"]]:
        log.entries.pop(key)
    log.save()
    result = RunResult(run_dir, tracker_names, [s.name for s in seqs])

    def record(tracker, sequence, message):
        log.set(tracker, sequence, message)
        result.errors.append({"tracker": tracker, "sequence": sequence, "error": message})

    for name, message in unknown:
        record(name, None, message)
    for sname, message in unknown_seqs:
        for tname in tracker_names:
            record(tname, sname, message)
    for sname, message in seq_errors:
        for tname in tracker_names:
            record(tname, sname, message)

    # what is left to do
    tasks: list[PairTask] = []
    parallel = scheduler is not None or workers > 1
    for tname, factory in known:
        options = dict(tracker_options.get(tname, {}))
        base_seed = options.pop("seed", 0) or 0
        try:  # bad options fail here once, not once per sequence in the workers
            _check_options(factory, options)
        except Exception as exc:  # noqa: BLE001
            record(tname, None, f"{tname}: cannot be created with options {options}: {_describe(exc)}")
            continue
        for seq in seqs:
            n = len(seq) if max_frames is None else min(len(seq), int(max_frames))
            rpath = result_path(run_dir, tname, seq.name)
            lines = count_lines(rpath)
            if lines == n:
                result.skipped.append((tname, seq.name))
                log.clear(tname, seq.name)
                continue
            if lines is not None:
                result.notes.append(f"{rpath}: {lines} lines for {n} frames; recomputing")
            tasks.append(PairTask(tname, factory, options, seq, n, sequence_seed(seq.name, base_seed), parallel))

    total_frames = sum(t.n_frames for t in tasks)
    bars = _Progress(len(tasks), total_frames, progress)

    def finish(task: PairTask, outcome: PairOutcome | None, failure: str | None = None):
        if outcome is not None and outcome.ok:
            write_times(times_path(run_dir, task.tracker, task.sequence.name), outcome.times)
            write_boxes(result_path(run_dir, task.tracker, task.sequence.name), outcome.boxes)
            log.clear(task.tracker, task.sequence.name)
            result.done.append((task.tracker, task.sequence.name))
            result.frames += task.n_frames
        else:
            message = failure if outcome is None else outcome.error
            record(task.tracker, task.sequence.name, message)
        bars.pair_done(task, outcome)

    try:
        if not tasks:
            pass
        elif scheduler is not None:
            _run_dask(tasks, scheduler, finish)
        elif workers > 1:
            _run_pool(tasks, workers, finish, bars)
        else:
            for task in tasks:
                bars.start(task)
                finish(task, run_pair(task, on_frame=bars.frame_counter(task)))
    finally:
        bars.close()

    result.seconds = time.perf_counter() - t_run
    if report:
        _make_report(result, dataset_dir, attributes, published, progress)
    return result


_PROGRESS_QUEUE = None  # set in pool worker processes by _init_pool_worker


def _init_pool_worker(queue) -> None:
    global _PROGRESS_QUEUE
    _PROGRESS_QUEUE = queue


def _run_pair_reporting(task: PairTask) -> PairOutcome:
    """:func:`run_pair` in a pool worker, sending ``(pair key, frames)`` to the driver at
    most every 0.5 s (and once at the end) for the frames progress bar."""
    queue = _PROGRESS_QUEUE
    if queue is None:
        return run_pair(task)
    key = (task.tracker, task.sequence.name)
    state = {"n": 0, "t": time.monotonic()}

    def on_frame(k: int) -> None:
        state["n"] += k
        now = time.monotonic()
        if now - state["t"] >= 0.5:
            queue.put((key, state["n"]))
            state["n"], state["t"] = 0, now

    try:
        return run_pair(task, on_frame=on_frame)
    finally:
        if state["n"]:
            queue.put((key, state["n"]))


def _run_pool(tasks, workers, finish, bars):
    import queue as _queue
    from concurrent.futures import FIRST_COMPLETED, wait

    ctx = multiprocessing.get_context("spawn")
    progress_queue = ctx.Queue() if bars.enabled else None
    with _worker_environ():
        pool = ProcessPoolExecutor(
            max_workers=min(workers, len(tasks)),
            mp_context=ctx,
            initializer=_init_pool_worker,
            initargs=(progress_queue,),
        )
        futures = {pool.submit(_run_pair_reporting, t): t for t in tasks}

    def drain():
        if progress_queue is None:
            return
        while True:
            try:
                key, k = progress_queue.get_nowait()
            except (_queue.Empty, OSError, ValueError):
                return
            bars.frames(k, key)

    try:
        pending = set(futures)
        while pending:
            done, pending = wait(pending, timeout=0.25, return_when=FIRST_COMPLETED)
            drain()
            for fut in done:
                task = futures[fut]
                try:
                    outcome = fut.result()
                except Exception as exc:  # noqa: BLE001 - a worker died (crash, killed, unpicklable)
                    finish(task, None, f"{task.tracker} on {task.sequence.name}: worker failed: {_describe(exc)}")
                else:
                    finish(task, outcome)
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    finally:
        if progress_queue is not None:
            progress_queue.close()
    pool.shutdown(wait=True)


def _run_dask(tasks, scheduler, finish):
    import distributed

    client, owned = _client_for(scheduler)
    try:
        futures = {}
        for t in tasks:
            fut = client.submit(run_pair, t, pure=False, key=f"smtmvt-{t.tracker}-{t.sequence.name}-{uuid.uuid4().hex}")
            futures[fut] = t
        try:
            for fut in distributed.as_completed(list(futures)):
                task = futures[fut]
                try:
                    outcome = fut.result()
                except Exception as exc:  # noqa: BLE001 - KilledWorker, unpicklable, ...
                    finish(task, None, f"{task.tracker} on {task.sequence.name}: worker failed: {_describe(exc)}")
                else:
                    finish(task, outcome)
                fut.release()
        except BaseException:
            client.cancel(list(futures))
            raise
    finally:
        if owned:
            client.close()


class _Progress:
    """Two tqdm bars on stderr: pairs done, and frames done. Frames arrive per frame in this
    process, every 0.5 s from pool workers, and per finished pair from a Dask cluster."""

    def __init__(self, n_pairs: int, n_frames: int, enabled: bool):
        self.enabled = enabled and n_pairs > 0
        self._counted: dict = {}  # pair key -> frames already shown
        self._finished: set = set()
        if not self.enabled:
            return
        from tqdm.auto import tqdm

        self.pairs = tqdm(total=n_pairs, desc="pairs ", unit="pair", position=0, file=sys.stderr, dynamic_ncols=True)
        self.fbar = tqdm(
            total=n_frames, desc="frames", unit="fr", position=1, file=sys.stderr, dynamic_ncols=True, smoothing=0.05
        )

    def start(self, task: PairTask) -> None:
        if self.enabled:
            self.pairs.set_postfix_str(f"{task.tracker} / {task.sequence.name}", refresh=True)

    def frames(self, k: int, key=None) -> None:
        if not self.enabled or key in self._finished:
            return
        self._counted[key] = self._counted.get(key, 0) + k
        self.fbar.update(k)

    def frame_counter(self, task: PairTask):
        key = (task.tracker, task.sequence.name)
        return lambda k: self.frames(k, key)

    def pair_done(self, task: PairTask, outcome) -> None:
        key = (task.tracker, task.sequence.name)
        self._finished.add(key)
        if not self.enabled:
            return
        # a failed or remote pair adds what it did not report frame by frame
        remaining = task.n_frames - self._counted.pop(key, 0)
        if remaining > 0:
            self.fbar.update(remaining)
        self.pairs.set_postfix_str(f"{task.tracker} / {task.sequence.name}", refresh=False)
        self.pairs.update(1)

    def close(self) -> None:
        if self.enabled:
            self.fbar.close()
            self.pairs.close()


def _make_report(result: RunResult, dataset_dir: Path, attributes, published, progress: bool) -> None:
    try:
        from .report import build_report
    except ImportError as exc:
        result.report_error = f"report module not available ({exc})"
        return
    kwargs = {"dataset": dataset_dir}
    if attributes:
        kwargs["attributes"] = attributes
    if published:
        kwargs["published"] = published
    try:
        result.report = build_report(result.run_dir, **kwargs)
    except Exception as exc:  # noqa: BLE001 - the results are safe; say why the report failed
        result.report_error = _describe(exc)
