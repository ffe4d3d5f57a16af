"""The runner: every tracker on every sequence, resumable, parallel; OTB's one-pass
evaluation (OPE) and its temporal and spatial robustness evaluations (TRE, SRE).

Usage::

    from smtmvt.evaluation import run_evaluation
    run = run_evaluation("../shared/data/otb", ["smtmvt", "opencv-csrt"], "runs/example",
                         workers=4)                       # or scheduler="tcp://host:8786"
    run.ok, run.failed, run.report_dir

Protocol
--------
Each tracker is initialised on frame 1 with the first ground-truth box and run over the
whole sequence without re-initialisation (OTB's OPE). Frame 1's reported box is the
initial box. ``max_frames`` cuts sequences short for quick checks; such runs are **not**
OTB-compliant. ``repeat=N`` runs each stochastic tracker N times per sequence with N seeds
(deterministic trackers once); the report gives the mean and spread over the repeats.

``protocols=["tre"]`` (or ``"sre"``, or several) runs OTB's TRE (20 runs per sequence, each
from a start frame spread over the sequence with that frame's ground-truth box, to the end)
or SRE (12 runs from the first frame with the ground-truth box shifted or scaled): where
and with which box each run starts is :mod:`.protocols` (the OTB toolkit's rules). Each run
is a unit of work of its own with its own result file (:class:`RunDir`, ``part``), resumed
like an OPE pair; the start box is frame 0's of the result file and of its record. With
``max_frames`` the segments are those of the cut sequence. A sequence where TRE or SRE has
no start (fewer than 20 frames after its last valid one) is an error of that sequence and
protocol for each tracker.

The run folder
--------------
Its layout, lock, settings (``run.json``) and errors (``errors.json``) belong to
:class:`~.rundir.RunDir`. A folder keeps one dataset and one frame limit: a command asking
for another is refused (``overwrite=True`` discards the old results first). It keeps its
repeat count too: a larger one adds repeats, a smaller one runs and reports the first ones.
While a command works on a folder it holds its lock; a second command gets a clear error.

Resuming
--------
The unit of work is one (tracker, sequence, repeat). It is skipped when its result file is
complete: as many well-formed, finite lines as frames to run (:meth:`RunDir.result_problem`),
and made from what this command would start it from: the same first ground-truth box,
frame count, seed and tracker settings (its record, :meth:`RunDir.record_problem`);
otherwise it is (re)computed, with a note saying why. A tracker's settings (options,
resolved configuration, versions: :mod:`.settings`) are kept in ``run.json``: a command with
other ones is refused (``overwrite=True`` discards that tracker's results first). Workers *return* boxes and times to
the driver, which writes the times file and then the result file, each atomically: a killed
run loses only the pairs in flight, never a finished one, and never leaves a partial result
file. A tracker folder holding imported results (``report --import``) is never taken for
computed results: evaluating a tracker of that name is an error.

Errors
------
Every pair is run inside ``try``: an exception (a missing or unreadable image, a tracker
that raises) is recorded in ``errors.json`` naming the tracker, the sequence, the frame and
the file, nothing is written for that pair, and the other pairs go on. Sequences whose
folder or ground truth cannot be read are recorded for each tracker; an unknown tracker
name is recorded once, and the known trackers run.

Parallelism and determinism
---------------------------
See :mod:`.workers`: local processes (``workers``), a Dask cluster (``scheduler``), a fresh
process per pair for the trackers that need one, and no orphan processes. Each pair gets a
seed derived from the sequence name and repeat (:func:`sequence_seed`), so it gives the same
boxes wherever it runs.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..data import detect_layout
from ..interrupts import reraise_interruption
from .pairs import PairOutcome, PairTask, describe, run_pair, sequence_seed
from .progress import Progress
from .protocols import init_omit, parse_protocols, segments, start_box
from .rundir import MAX_REPEAT, RunDir, RunInfo
from .settings import settings_digest, tracker_settings
from .trackers import TrackerSpec, UnknownTrackerError, accepts_keyword, tracker_spec
from .workers import probe_scheduler, run_tasks

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


def result_path(run_dir, tracker: str, sequence: str, repeat: int = 0) -> Path:
    """``RUN_DIR/results/<tracker>[/repeat-<r>]/<sequence>.txt`` (see :class:`RunDir`)."""
    return RunDir(run_dir).result_path(tracker, sequence, repeat)


def times_path(run_dir, tracker: str, sequence: str, repeat: int = 0) -> Path:
    """``RUN_DIR/results/<tracker>[/repeat-<r>]/times/<sequence>_time.txt``."""
    return RunDir(run_dir).times_path(tracker, sequence, repeat)


def count_lines(path) -> int | None:
    """Number of non-blank lines of ``path``; None when it does not exist or can't be read."""
    try:
        with open(path, "rb") as f:
            return sum(1 for line in f if line.strip())
    except OSError:
        return None


@dataclass
class RunResult:
    """Summary of :func:`run_evaluation`.

    Attributes
    ----------
    run_dir : Path
    trackers, sequences : names that were run (known trackers, readable sequences).
    done : pairs computed in this call; skipped : pairs already complete. A pair is
        ``(tracker, sequence)`` for repeat 0 and ``(tracker, sequence, repeat)`` after.
    errors : this call's errors, ``{"tracker", "sequence", "repeat", "error"}`` dicts (also
        in ``errors.json``, which keeps errors of pairs not part of this call).
    notes : remarks (result files recomputed and why, settings).
    cut_short : the sequences longer than ``max_frames``, run on their first frames only.
    repeat : repeats used by this call.
    report : what ``build_report`` returned, or None; report_error : why it failed.
    """

    run_dir: Path
    trackers: list = field(default_factory=list)
    sequences: list = field(default_factory=list)
    done: list = field(default_factory=list)
    skipped: list = field(default_factory=list)
    errors: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    cut_short: list = field(default_factory=list)
    frames: int = 0
    seconds: float = 0.0
    repeat: int = 1
    report: dict | None = None
    report_error: str | None = None

    @property
    def ok(self) -> bool:
        """True when every requested pair is complete and no error occurred."""
        return not self.errors

    @property
    def report_gaps(self) -> list:
        """The report's errors (run errors and unusable results); empty without a report."""
        return list((self.report or {}).get("errors", []))

    @property
    def failed(self) -> list:
        """``(tracker, sequence)`` of the pairs that failed in this call."""
        return [(e["tracker"], e["sequence"]) for e in self.errors]

    @property
    def report_dir(self) -> Path:
        return RunDir(self.run_dir).report_dir


def _pair_id(tracker: str, sequence: str, repeat: int, part: tuple[str, str] | None = None) -> tuple:
    """``(tracker, sequence)`` for OPE repeat 0, ``(tracker, sequence, repeat)`` for later
    repeats, ``(tracker, sequence, repeat, protocol, segment)`` for a TRE or SRE run."""
    if part is not None:
        return (tracker, sequence, repeat, *part)
    return (tracker, sequence) if repeat == 0 else (tracker, sequence, repeat)


def _on(task: PairTask) -> str:
    """``"tracker on sequence"`` (`` (tre seg-03)`` for a segment), for messages."""
    text = f"{task.tracker} on {task.sequence.name}"
    return text if task.part is None else f"{text} ({task.part[0]} {task.part[1]})"


def _part_text(part: tuple[str, str] | None) -> str:
    """The ``part`` of an ``errors.json`` entry: ``""`` (OPE) or ``"tre/seg-03"``."""
    return "" if part is None else "/".join(part)


@dataclass(frozen=True)
class _Start:
    """One run to make on a sequence: ``part`` (None for OPE), 0-based first frame, 0-based
    start box (None: frame 0's ground truth), frames to run."""

    part: tuple[str, str] | None
    start: int
    init_box: tuple | None
    n_frames: int


def _starts(seq, protocols: list[str], max_frames: int | None, layout: str) -> dict[str, list[_Start] | str]:
    """``{protocol: runs}`` of ``seq`` (:mod:`.protocols`; ``layout``: the dataset's, for
    :func:`.protocols.init_omit`), or ``{protocol: message}`` when the protocol has no run
    there (no ground truth, too short, frame 0 unreadable for SRE)."""
    from ..data.boxes import ONE_BASED_OFFSET

    n_seq = len(seq) if max_frames is None else min(len(seq), max_frames)
    out: dict[str, list[_Start] | str] = {}
    for protocol in protocols:
        if protocol == "ope":
            out[protocol] = [_Start(None, 0, None, n_seq)]
            continue
        try:
            if seq.groundtruth is None:
                raise ValueError("no ground truth")
            gt = np.asarray(seq.groundtruth, dtype=np.float64)[:n_seq] + ONE_BASED_OFFSET
            size = tuple(seq[0].shape[:2]) if protocol == "sre" else None
            out[protocol] = [
                _Start(
                    (protocol, s.name),
                    s.start,
                    tuple((start_box(s, gt, size) - ONE_BASED_OFFSET).tolist()),
                    n_seq - s.start,
                )
                for s in segments(protocol, gt, init_omit(seq.name, layout))
            ]
        except Exception as exc:  # noqa: BLE001 - bad data of one sequence: an error of its pairs
            reraise_interruption(exc)
            out[protocol] = f"{seq.name}: no {protocol.upper()} run: {describe(exc)}"
    return out


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
    repeat: int | None = None,
    overwrite: bool = False,
    protocols="ope",
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
    max_frames : run at most this many frames per sequence (quick checks, not OTB-compliant);
        must match the folder's (see the module notes) unless ``overwrite``.
    report : call :func:`smtmvt.evaluation.report.build_report` at the end.
    attributes, published : paths stored in ``run.json`` and passed to the report.
    repeat : runs of each stochastic tracker per sequence (default: the folder's count, 1 for
        a new folder).
    protocols : ``"ope"``, ``"tre"``, ``"sre"``, a comma-separated string or a list of them
        (module notes); they are added to the folder's ``run.json`` for the report.
    overwrite : discard the folder's results when its frame limit or dataset differs, and a
        tracker's results when its settings differ.

    Returns
    -------
    RunResult

    Raises
    ------
    ValueError, OSError
        Only for problems with the whole run (no dataset folder, a run folder made for another
        dataset or frame limit, a folder in use, no tracker given, unreachable scheduler, an
        attribute table that cannot be read); everything per pair is recorded.
    """
    t_run = time.perf_counter()
    dataset_dir = Path(dataset_dir).expanduser().resolve()
    sequences = _check_arguments(dataset_dir, sequences, max_frames, workers, repeat)
    request = _Request(
        max_frames, repeat, attributes, published, overwrite, parse_protocols(protocols), workers, scheduler, progress
    )
    run = RunDir(out_dir)
    run.check_can_hold_run()  # a folder that is not a run: refused before anything else
    _check_attributes(attributes)
    tracker_options = dict(tracker_options or {})
    known, unknown = _resolve_trackers(trackers, tracker_options)
    if isinstance(scheduler, str):
        probe_scheduler(scheduler)  # a wrong address fails in seconds, before the run folder is touched
    with run.locked("smtmvt evaluate", create=True):
        result = _run_locked(run, dataset_dir, sequences, known, unknown, tracker_options, request)
        result.seconds = time.perf_counter() - t_run
        if report:
            _make_report(result, run, attributes, published)
    return result


@dataclass(frozen=True)
class _Request:
    """What :func:`run_evaluation` was asked for besides the dataset, trackers and sequences
    (checked; ``protocols`` parsed)."""

    max_frames: int | None
    repeat: int | None
    attributes: object
    published: object
    overwrite: bool
    protocols: list[str]
    workers: int
    scheduler: object
    progress: bool


def _run_locked(run: RunDir, dataset_dir: Path, sequences, known, unknown, tracker_options: dict, req: _Request):
    """The body of :func:`run_evaluation`, under the run folder's lock: open the sequences,
    settle ``run.json`` (the settings check), record the unknown names and unreadable
    sequences, then run the pairs left to do. Returns the :class:`RunResult` (no report yet)."""
    seqs, seq_errors, unknown_seqs = _open_sequences(dataset_dir, sequences)
    if not seqs and not seq_errors and not unknown_seqs:
        raise ValueError(
            f"no sequence in {dataset_dir} (OTB: sub-folders with img/ and groundtruth_rect.txt; "
            "or a GOT-10k, LaSOT, UAV123 or VOT folder)"
        )
    names = [s.name for s in seqs] + [n for n, _ in seq_errors if n]
    probes = {spec.name: _tracker_problem(run, spec, tracker_options.get(spec.name, {})) for spec in known}
    info, notes = run.settle(
        dataset_dir,
        trackers=[s.name for s in known],
        sequences=names,
        max_frames=req.max_frames,
        repeat=req.repeat,
        attributes=req.attributes,
        published=req.published,
        overwrite=req.overwrite,
        tracker_settings={name: settings for name, (_, settings) in probes.items() if settings is not None},
        protocols=req.protocols,
    )
    result = RunResult(run.root, [s.name for s in known], [s.name for s in seqs], notes=notes, repeat=info.repeat)
    if info.max_frames is not None:
        result.cut_short = [s.name for s in seqs if len(s) > info.max_frames]
    book = _Book(run, result, info)
    for name, message in unknown:
        book.record(name, None, message)
    for sname, message in unknown_seqs + seq_errors:
        for spec in known:
            book.record(spec.name, sname, message)
    layout = detect_layout(dataset_dir)
    starts = {seq.name: _starts(seq, req.protocols, info.max_frames, layout) for seq in seqs}
    parallel = req.scheduler is not None or req.workers > 1
    tasks = _plan(book, known, seqs, tracker_options, probes, starts, parallel=parallel)
    with Progress(len(tasks), sum(t.n_frames for t in tasks), req.progress) as bars:

        def finish(task: PairTask, outcome: PairOutcome | None, failure: str | None) -> None:
            book.finish(task, outcome, failure)
            bars.pair_done(task)

        run_tasks(tasks, finish, bars, workers=req.workers, scheduler=req.scheduler)
    return result


def _check_arguments(dataset_dir: Path, sequences, max_frames, workers, repeat) -> list | None:
    if not dataset_dir.is_dir():
        raise FileNotFoundError(f"dataset folder not found: {dataset_dir}")
    if isinstance(sequences, str):
        sequences = [s.strip() for s in sequences.split(",") if s.strip()]
    for name, value in (("max_frames", max_frames), ("repeat", repeat)):
        if value is not None and (not isinstance(value, int) or value < 1):
            raise ValueError(f"{name} must be a whole number >= 1, got {value!r}")
    if repeat is not None and repeat > MAX_REPEAT:
        raise ValueError(f"repeat must be at most {MAX_REPEAT}, got {repeat!r}")
    if not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers must be >= 1, got {workers!r}")
    return sequences


def _check_attributes(attributes) -> None:
    """Read the attribute table before anything runs: a bad one is an error of the whole
    command (nothing is run, nothing stored in ``run.json`` for later reports to trip on)."""
    if not attributes:
        return
    from .published import load_attribute_table

    try:
        load_attribute_table(attributes)
    except (OSError, ValueError) as exc:
        raise ValueError(f"attribute table {attributes} cannot be used (nothing was run): {exc}") from None


class _Book:
    """The driver's bookkeeping: ``errors.json`` and the :class:`RunResult` of this call."""

    def __init__(self, run: RunDir, result: RunResult, info: RunInfo):
        self.run, self.result, self.info = run, result, info
        self.records: dict[tuple, dict] = {}  # task.key -> what its result starts from
        self.log = run.errors()
        # Errors about names given on a previous command line (unknown tracker or sequence) are
        # properties of that command, not of the run's data: drop them, this call re-adds its own.
        self.log.drop(lambda t, s, r: s is not None and s in info.sequences)

    def record(self, tracker: str, sequence: str | None, message: str, repeat: int = 0, part: str = "") -> None:
        """Enter an error of a pair (``part``: ``""`` for OPE, ``"tre/seg-03"``, or ``"tre"``
        for the whole protocol on that sequence)."""
        self.log.set(tracker, sequence, message, repeat, part)
        entry = {"tracker": tracker, "sequence": sequence, "repeat": repeat, "error": message}
        self.result.errors.append(entry | {"part": part} if part else entry)

    def finish(self, task: PairTask, outcome: PairOutcome | None, failure: str | None) -> None:
        name = task.sequence.name
        if outcome is not None and outcome.ok:
            record = self.records.get(task.key)
            try:
                run, part = self.run, task.part
                run.write_result(task.tracker, name, outcome.boxes, outcome.times, task.repeat, record, part=part)
            except OSError as exc:  # this pair's files only (a name too long, ...): the rest go on
                why = f"{_on(task)}: cannot write its result: {describe(exc)}"
                self.record(task.tracker, name, why, task.repeat, _part_text(task.part))
                return
            self.log.clear(task.tracker, name, task.repeat, _part_text(task.part))
            self.result.done.append(_pair_id(task.tracker, name, task.repeat, task.part))
            self.result.frames += task.n_frames
        else:
            message = failure if outcome is None else outcome.error
            self.record(task.tracker, name, str(message), task.repeat, _part_text(task.part))


def _plan(
    book: _Book,
    known: list[TrackerSpec],
    seqs,
    tracker_options: dict,
    probes: dict,
    starts: dict[str, dict[str, list[_Start] | str]],
    parallel: bool,
) -> list[PairTask]:
    """The pairs left to do (skipped ones and problems are entered in ``book``, and what
    each task's result starts from in ``book.records``). ``probes``: ``{tracker:
    (problem, settings)}`` of :func:`_tracker_problem`; ``starts``: ``{sequence:
    {protocol: runs or message}}`` of :func:`_starts`."""
    tasks: list[PairTask] = []
    for spec in known:
        options = dict(tracker_options.get(spec.name, {}))
        base_seed = options.pop("seed", 0) or 0
        problem, settings = probes[spec.name]
        if problem:
            book.record(spec.name, None, problem)
            continue
        # the digest of the record run.json keeps (the same settings, perhaps written before
        # an experimental option was added: RunDir.settle)
        digest = settings_digest(book.info.tracker_settings.get(spec.name, settings))
        for seq in seqs:
            for r in range(1 if spec.deterministic else book.info.repeat):
                for protocol, runs in starts[seq.name].items():
                    if isinstance(runs, str):
                        book.record(spec.name, seq.name, runs, r, protocol)
                        continue
                    if protocol != "ope":
                        book.log.clear(spec.name, seq.name, r, protocol)
                    for start in runs:
                        seed = sequence_seed(_seed_name(seq.name, start.part), base_seed, r)
                        task = PairTask(
                            spec.name, spec.factory, options, seq, start.n_frames, seed, parallel, r,
                            spec.fresh_process, start.part, start.start, start.init_box,
                        )  # fmt: skip
                        if _needs_running(book, task, _start_record(seq, start, seed, digest)):
                            tasks.append(task)
    return tasks


def _seed_name(sequence: str, part: tuple[str, str] | None) -> str:
    """What a run's seed derives from (:func:`sequence_seed`): the sequence name for OPE (the
    seeds of before TRE and SRE), ``"<sequence>/<protocol>/<segment>"`` for their runs."""
    return sequence if part is None else f"{sequence}/{part[0]}/{part[1]}"


def _needs_running(book: _Book, task: PairTask, record: dict) -> bool:
    """Whether ``task``'s result must be (re)computed; when it must, its ``record`` goes to
    ``book.records``; when not, the pair is entered as skipped (and a missing record written)."""
    run, result, name, r, part = book.run, book.result, task.sequence.name, task.repeat, task.part
    try:
        why = run.result_problem(task.tracker, name, task.n_frames, r, part=part)
        why = why or run.record_problem(task.tracker, name, record, r, part=part)
    except OSError as exc:  # its result file cannot even be looked at (a name too long)
        message = f"{_on(task)}: cannot check its result file: {describe(exc)}"
        book.record(task.tracker, name, message, r, _part_text(part))
        return False
    if why is None:
        if run.read_record(task.tracker, name, r, part=part) is None:  # killed between the writes
            run.write_record(task.tracker, name, record, r, part=part)
        result.skipped.append(_pair_id(task.tracker, name, r, part))
        book.log.clear(task.tracker, name, r, _part_text(part))
        return False
    if why != "missing":
        result.notes.append(f"{why}; recomputing")
    book.records[task.key] = record
    return True


def _start_record(seq, start: _Start, seed: int, digest: str) -> dict:
    """What a result of ``seq`` starts from (:meth:`RunDir.record_problem`): the start box
    (1-based, as the result's first line), the frames run and the sequence's, the seed and
    the tracker settings' digest; for a TRE or SRE run also its 0-based start frame."""
    from ..data.boxes import ONE_BASED_OFFSET

    box = seq.first_box if start.init_box is None else start.init_box
    first = (np.asarray(box, dtype=np.float64) + ONE_BASED_OFFSET).tolist()
    record = {
        "first_box": first,
        "n_frames": start.n_frames,
        "sequence_frames": len(seq),
        "seed": seed,
        "settings": digest,
    }
    return record if start.part is None else record | {"start": start.start}


def _tracker_problem(run: RunDir, spec: TrackerSpec, options: dict) -> tuple[str | None, dict | None]:
    """``(problem, settings)``: why ``spec`` cannot run into ``run`` (its folder holds
    imported results, or the options are refused: checked once here, not once per sequence
    in the workers), or None and the settings record of its results (:mod:`.settings`)."""
    if run.is_imported(spec.name):
        rel = run.tracker_dir(spec.name).relative_to(run.root)
        return (
            f"{rel} holds imported results ({rel}/import.json), not results of this run; "
            f"evaluate will not add to them: remove that folder or import under another name"
        ), None
    given = {k: v for k, v in options.items() if k != "seed" or v}  # no seed, seed 0: the same runs
    options = {k: v for k, v in given.items() if k != "seed"}
    try:
        probe = {**options, "seed": 0} if accepts_keyword(spec.factory, "seed") else options
        tracker = spec.factory(**probe)
    except Exception as exc:  # noqa: BLE001 - any failure of the factory is the user's to see
        reraise_interruption(exc)
        return f"{spec.name}: cannot be created with options {options}: {describe(exc)}", None
    return None, tracker_settings(tracker, given)


def _open_sequences(dataset_dir: Path, sequences):
    """``(sequences, errors, unknown)``: the opened sequences, ``(name, message)`` for each
    sequence that could not be opened (missing image, malformed ground truth, ...), and
    ``(name, message)`` for each requested name the dataset does not have."""
    from ..data import SequenceError, open_dataset

    items = []
    unknown = []
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
    seqs, errors, seen = [], [], set()
    for item in items:
        name = item.sequence if isinstance(item, SequenceError) else item.name
        if name in seen:
            continue
        seen.add(name)
        if isinstance(item, SequenceError):
            errors.append((name, str(item)))
        else:
            seqs.append(item)
    return seqs, errors, unknown


def _resolve_trackers(trackers, tracker_options: dict) -> tuple[list[TrackerSpec], list[tuple[str, str]]]:
    names = [t.strip() for t in (trackers.split(",") if isinstance(trackers, str) else trackers)]
    names = list(dict.fromkeys(t for t in names if t))
    if not names:
        raise ValueError("no tracker given")
    known, unknown = [], []
    for name in names:
        try:
            known.append(tracker_spec(name))
        except UnknownTrackerError as exc:
            unknown.append((name, str(exc)))
    for name in tracker_options:
        if name not in names:
            raise ValueError(f"tracker options given for {name!r}, which is not among the trackers run")
    return known, unknown


def _make_report(result: RunResult, run: RunDir, attributes, published) -> None:
    from .report import build_report

    try:
        result.report = build_report(
            run, attributes=attributes or None, published=published or None, repeat=result.repeat
        )
    except Exception as exc:  # noqa: BLE001 - the results are safe; say why the report failed
        reraise_interruption(exc)
        result.report_error = describe(exc)
