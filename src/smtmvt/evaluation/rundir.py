"""The run folder: one object owns every path in it, its lock, its settings and its files.

Layout (``RUN_DIR`` = :attr:`RunDir.root`)::

    run.json                                   settings (RunInfo): dataset, trackers, sequences,
                                               protocols, attributes, published, max_frames, repeat,
                                               tracker_settings (per tracker, see .settings)
    errors.json                                [{"tracker", "sequence", "repeat", "error"}, ...]
    .lock                                      held (flock) by the command working on the run
    results/<tracker>/<seq>.txt                repeat 0: 1-based x,y,w,h per frame (got10k/pysot)
    results/<tracker>/times/<seq>_time.txt     seconds per frame of repeat 0
    results/<tracker>/meta/<seq>.json          what the result started from: first box, frames,
                                               seed, settings digest (no meta: imported)
    results/<tracker>/repeat-<r>/<seq>.txt     repeat r = 1..N-1 (the same layout one level down)
    results/<tracker>/repeat-<r>/times/<seq>_time.txt, .../repeat-<r>/meta/<seq>.json
    results/<tracker>[/repeat-<r>]/tre/<seq>/seg-<k>.txt
                                               TRE run k = 01..20 of <seq>: one line per frame
                                               from its start frame to the end (.protocols)
    results/<tracker>[/repeat-<r>]/sre/<seq>/<shift>.txt
                                               SRE run from the shifted box (left, ..., scale_12);
                                               both with times/<k>_time.txt and meta/<k>.json beside
    results/<tracker>/import.json              only for imported trackers: provenance
    report/                                    summary.json, table.md/.csv, plots, index.html

Repeat 0 sits where got10k's ``ExperimentOTB`` and pysot look for a tracker's results, so
any tool reading that layout reads a repeated run's first repeat; each ``repeat-<r>``
folder is itself such a tracker folder.

Every write goes through :meth:`RunDir.write_bytes` (atomic, and only to paths inside the
run through real folders); names used as path components are checked first
(:func:`check_tracker_name`, :func:`check_sequence_name`), so no input, however named,
makes a file appear outside ``RUN_DIR``.
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import re
import shutil
from collections.abc import Iterable, Iterator
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from ..data import SequenceError, read_boxes, write_boxes, write_bytes_atomic
from ..data.files import read_regular_bytes
from .settings import settings_difference

__all__ = [
    "RunDir",
    "RunInfo",
    "RunDirError",
    "RunLockedError",
    "ErrorLog",
    "check_tracker_name",
    "check_sequence_name",
]

RUN_JSON = "run.json"
ERRORS_JSON = "errors.json"
LOCK = ".lock"
RESULTS = "results"
REPORT = "report"
#: files of a protocol's report folder (``report/`` for OPE, ``report/<protocol>/`` else)
REPORT_SUMMARY = "summary.json"
REPORT_TABLE = "table.md"
REPORT_TABLE_CSV = "table.csv"
REPORT_PAGE = "index.html"
IMPORT_JSON = "import.json"
META = "meta"
_TRACKER_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.+-]*")
_REPEAT_DIR = re.compile(r"repeat-([1-9][0-9]*)")
#: the protocols whose runs are segments with their own files (``part``), see :mod:`.protocols`
SEGMENTED_PROTOCOLS = ("tre", "sre")
ALL_PROTOCOLS = ("ope", *SEGMENTED_PROTOCOLS)
#: ``(protocol, segment)``: one run of TRE or SRE (``("tre", "seg-03")``, ``("sre", "left")``)
Part = tuple[str, str]
#: the most repeats a run may hold (``--repeat``): each is a whole pass over the dataset
MAX_REPEAT = 1000


class RunDirError(ValueError):
    """A run folder that cannot be used as asked (the message names it and says why)."""


class RunLockedError(RunDirError):
    """Another command holds the run folder's lock."""


def check_tracker_name(name: str) -> str:
    """``name`` if it can be a folder name in ``results/`` (letters, digits, ``_ . + -``,
    starting with a letter or digit); ``ValueError`` otherwise."""
    if not isinstance(name, str) or not _TRACKER_NAME.fullmatch(name):
        raise ValueError(
            f"invalid tracker name {name!r}: use letters, digits and _ . + - only (starting with a letter or digit)"
        )
    return name


def check_sequence_name(name: str) -> str:
    """``name`` if it is a plain file name (no folder part, not hidden, not ``..``)."""
    if (
        not isinstance(name, str)
        or not name.strip()
        or name != os.path.basename(name)
        or "/" in name
        or "\\" in name
        or name.startswith(".")
        or "\0" in name
    ):
        raise ValueError(f"invalid sequence name {name!r}: it must be a plain file name")
    return name


@dataclass
class RunInfo:
    """The settings of a run folder, as in ``run.json``.

    ``max_frames`` None means every frame; ``repeat`` is the number of repeats of the
    stochastic trackers the folder holds (1 for runs made before repeats existed).
    ``tracker_settings``: ``{tracker: settings record}`` (:mod:`.settings`) of the computed
    trackers (empty for runs made before it was recorded). ``protocols``: the protocols run
    into the folder (``"ope"``, ``"tre"``, ``"sre"``; ``["ope"]`` for runs made before TRE and
    SRE existed), which the report scores.
    Keys of ``run.json`` not listed here are kept in ``extra`` and written back.
    """

    dataset: str | None = None
    trackers: list = field(default_factory=list)
    sequences: list = field(default_factory=list)
    attributes: str | None = None
    published: str | None = None
    max_frames: int | None = None
    repeat: int = 1
    tracker_settings: dict = field(default_factory=dict)
    protocols: list = field(default_factory=lambda: ["ope"])
    extra: dict = field(default_factory=dict)

    @classmethod
    def from_json(cls, data: dict, path: Path) -> RunInfo:
        known = {k: data[k] for k in ("dataset", "attributes", "published", "max_frames") if k in data}
        info = cls(**known, extra={k: v for k, v in data.items() if k not in cls.__dataclass_fields__})
        info.trackers = list(data.get("trackers") or [])
        info.sequences = list(data.get("sequences") or [])
        info.repeat = data.get("repeat") or 1
        info.protocols = list(data.get("protocols") or ["ope"])
        if not set(info.protocols) <= set(ALL_PROTOCOLS):
            raise RunDirError(f"{path}: protocols must be among {', '.join(ALL_PROTOCOLS)}, got {info.protocols!r}")
        for key in ("max_frames", "repeat"):
            value = getattr(info, key)
            if value is not None and (not isinstance(value, int) or value < 1):
                raise RunDirError(f"{path}: {key} must be a whole number >= 1, got {value!r}")
        if info.repeat > MAX_REPEAT:
            raise RunDirError(f"{path}: repeat must be at most {MAX_REPEAT}, got {info.repeat!r}")
        settings = data.get("tracker_settings") or {}
        if not isinstance(settings, dict) or not all(isinstance(v, dict) for v in settings.values()):
            raise RunDirError(f"{path}: tracker_settings must map tracker names to objects")
        info.tracker_settings = dict(settings)
        return info

    def to_json(self) -> dict:
        data = asdict(self)
        extra = data.pop("extra")
        return {**extra, **data}


class ErrorLog:
    """``errors.json``: one message per (tracker, sequence, repeat, part), rewritten atomically
    on every change. ``sequence`` None: an error of the tracker itself (unknown name, bad
    options). ``part``: ``""`` for an OPE pair, ``"<protocol>/<segment>"`` (``"tre/seg-03"``)
    for one run of TRE or SRE (the entry has a ``"part"`` key then)."""

    def __init__(self, run: RunDir):
        self.run = run
        self.entries: dict[tuple, str] = {}
        path = run.errors_json
        if path.is_file():
            try:
                for e in json.loads(path.read_text(encoding="utf-8")):
                    key = (e.get("tracker"), e.get("sequence"), int(e.get("repeat") or 0), str(e.get("part") or ""))
                    self.entries[key] = str(e.get("error"))
            except (ValueError, TypeError, AttributeError, OSError):
                self.entries = {}  # a damaged errors.json is rebuilt from this run

    def set(self, tracker, sequence, error: str, repeat: int = 0, part: str = "") -> None:
        self.entries[(tracker, sequence, repeat, part)] = error
        self.save()

    def clear(self, tracker, sequence, repeat: int = 0, part: str = "") -> None:
        if self.entries.pop((tracker, sequence, repeat, part), None) is not None:
            self.save()

    def drop(self, keep) -> None:
        """Remove the entries for which ``keep(tracker, sequence, repeat)`` is False."""
        self.entries = {k: v for k, v in self.entries.items() if keep(*k[:3])}
        self.save()

    def as_list(self) -> list[dict]:
        out = []
        for (t, s, r, part), e in self.entries.items():
            entry = {"tracker": t, "sequence": s, "repeat": r, "error": e}
            out.append(entry | {"part": part} if part else entry)
        return out

    def save(self) -> None:
        self.run.write_text(self.run.errors_json, json.dumps(self.as_list(), indent=1) + "\n")


class RunDir:
    """A run folder (see the module docstring for its layout).

    ``RunDir(path)`` does no I/O. The folder is a run once it has ``run.json``
    (:meth:`settle` writes it); the report and imports refuse a folder that is not
    (:meth:`info`), and ``evaluate`` makes a run only of a new or empty folder
    (:meth:`check_can_hold_run`).
    """

    def __init__(self, root) -> None:
        self.root = Path(root).expanduser().resolve()
        self._lock_fd: int | None = None
        self._lock_depth = 0

    def __repr__(self) -> str:
        return f"RunDir({str(self.root)!r})"

    # ------------------------------------------------------------------ paths
    @property
    def run_json(self) -> Path:
        return self.root / RUN_JSON

    @property
    def errors_json(self) -> Path:
        return self.root / ERRORS_JSON

    @property
    def results_dir(self) -> Path:
        return self.root / RESULTS

    @property
    def report_dir(self) -> Path:
        return self.root / REPORT

    def protocol_report_dir(self, protocol: str = "ope") -> Path:
        """``report/`` for OPE, ``report/<protocol>/`` for TRE and SRE."""
        if protocol == "ope":
            return self.report_dir
        if protocol not in SEGMENTED_PROTOCOLS:
            raise ValueError(f"protocol {protocol!r}: expected one of {', '.join(ALL_PROTOCOLS)}")
        return self.report_dir / protocol

    def report_summary(self, protocol: str = "ope") -> Path:
        """The protocol's ``summary.json`` (what :func:`.report.build_report` returned for it)."""
        return self.protocol_report_dir(protocol) / REPORT_SUMMARY

    def report_table(self, protocol: str = "ope") -> Path:
        """The protocol's ``table.md``."""
        return self.protocol_report_dir(protocol) / REPORT_TABLE

    def report_page(self, protocol: str = "ope") -> Path:
        """The protocol's ``index.html``."""
        return self.protocol_report_dir(protocol) / REPORT_PAGE

    def tracker_dir(self, tracker: str, repeat: int = 0) -> Path:
        """``results/<tracker>`` for repeat 0, ``results/<tracker>/repeat-<r>`` after."""
        base = self.results_dir / check_tracker_name(tracker)
        if repeat == 0:
            return base
        if not isinstance(repeat, int) or repeat < 0:
            raise ValueError(f"repeat must be a whole number >= 0, got {repeat!r}")
        return base / f"repeat-{repeat}"

    def _place(self, tracker: str, sequence: str, repeat: int, part: Part | None) -> tuple[Path, str]:
        """``(folder, stem)`` of a pair's files: ``results/<tracker>[/repeat-<r>]`` and the
        sequence for OPE (``part`` None); ``.../<protocol>/<sequence>`` and the segment for one
        run of TRE or SRE (``part = (protocol, segment)``)."""
        base, name = self.tracker_dir(tracker, repeat), check_sequence_name(sequence)
        if part is None:
            return base, name
        protocol, segment = part
        if protocol not in SEGMENTED_PROTOCOLS:
            raise ValueError(f"protocol {protocol!r} has no segments: expected one of {', '.join(SEGMENTED_PROTOCOLS)}")
        return base / protocol / name, check_sequence_name(segment)

    def result_path(self, tracker: str, sequence: str, repeat: int = 0, *, part: Part | None = None) -> Path:
        """``results/<tracker>[/repeat-<r>]/<sequence>.txt``; for a segment (``part``)
        ``results/<tracker>[/repeat-<r>]/<protocol>/<sequence>/<segment>.txt``."""
        folder, stem = self._place(tracker, sequence, repeat, part)
        return folder / f"{stem}.txt"

    def times_path(self, tracker: str, sequence: str, repeat: int = 0, *, part: Part | None = None) -> Path:
        """``times/<stem>_time.txt`` beside :meth:`result_path`'s file."""
        folder, stem = self._place(tracker, sequence, repeat, part)
        return folder / "times" / f"{stem}_time.txt"

    def record_path(self, tracker: str, sequence: str, repeat: int = 0, *, part: Part | None = None) -> Path:
        """``meta/<stem>.json`` beside :meth:`result_path`'s file: what the result started from."""
        folder, stem = self._place(tracker, sequence, repeat, part)
        return folder / META / f"{stem}.json"

    def import_json(self, tracker: str) -> Path:
        return self.tracker_dir(tracker) / IMPORT_JSON

    def import_meta(self, tracker: str) -> dict:
        """``import.json`` of an imported tracker (``{"imported": True, "sequences": {seq:
        provenance}}``); an empty dict when there is none or it cannot be read."""
        try:
            meta = json.loads(read_regular_bytes(self.import_json(tracker)).decode("utf-8"))
        except (OSError, ValueError):
            return {}
        return meta if isinstance(meta, dict) else {}

    def is_imported(self, tracker: str) -> bool:
        """True when ``results/<tracker>`` holds imported results (``import.json``)."""
        return self.import_json(tracker).is_file()

    def tracker_folders(self) -> list[str]:
        """Names of the tracker folders under ``results/`` (valid names only), sorted."""
        if not self.results_dir.is_dir():
            return []
        names = [p.name for p in self.results_dir.iterdir() if p.is_dir() and _TRACKER_NAME.fullmatch(p.name)]
        return sorted(names, key=str.lower)

    def repeats_on_disk(self, tracker: str) -> int:
        """1 + the highest ``repeat-<r>`` folder of ``tracker`` (1 when there is none)."""
        base = self.tracker_dir(tracker)
        found = [int(m.group(1)) for p in base.glob("repeat-*") if (m := _REPEAT_DIR.fullmatch(p.name)) and p.is_dir()]
        return 1 + max(found, default=0)

    # ------------------------------------------------------------------ writing
    def _checked(self, path) -> Path:
        """``path`` (absolute or relative to the root) if it lies inside the run and every
        existing folder on the way is a real folder, not a link; RunDirError otherwise."""
        path = Path(path)
        path = path if path.is_absolute() else self.root / path
        norm = Path(os.path.normpath(path))
        if norm == self.root or self.root not in norm.parents:
            raise RunDirError(f"refusing to write {path}: outside the run folder {self.root}")
        for folder in reversed(norm.parents):
            if folder == self.root or self.root in folder.parents:
                if folder.is_symlink():
                    raise RunDirError(f"refusing to write {norm}: {folder} is a symbolic link")
        return norm

    def write_bytes(self, path, data: bytes) -> Path:
        """Write ``data`` atomically at ``path`` inside the run (a link there is replaced)."""
        return write_bytes_atomic(self._checked(path), data)

    def write_text(self, path, text: str) -> Path:
        return self.write_bytes(path, text.encode("utf-8"))

    def write_result(
        self,
        tracker: str,
        sequence: str,
        boxes,
        times=None,
        repeat: int = 0,
        record: dict | None = None,
        *,
        part: Part | None = None,
    ) -> Path:
        """Write one pair's times file (when given), then its result file (the completion
        marker), then its record (when given: what it started from, see
        :meth:`record_problem`), each atomically. ``boxes``: ``(n, 4)`` 0-based; ``times``:
        ``(n,)`` s. The old record goes first, so a record never describes another result."""
        self._checked(self.record_path(tracker, sequence, repeat, part=part)).unlink(missing_ok=True)
        if times is not None:
            text = "".join(f"{float(t):.9f}\n" for t in np.asarray(times, dtype=np.float64).ravel())
            self.write_text(self.times_path(tracker, sequence, repeat, part=part), text)
        path = write_boxes(self._checked(self.result_path(tracker, sequence, repeat, part=part)), boxes)
        if record is not None:
            self.write_record(tracker, sequence, record, repeat, part=part)
        return path

    def write_record(
        self, tracker: str, sequence: str, record: dict, repeat: int = 0, *, part: Part | None = None
    ) -> Path:
        """Write the pair's record (what its result started from), atomically."""
        path = self.record_path(tracker, sequence, repeat, part=part)
        return self.write_text(path, json.dumps(record, indent=1) + "\n")

    # ------------------------------------------------------------------ reading our own files
    def read_result(
        self, tracker: str, sequence: str, repeat: int = 0, n_frames: int | None = None, *, part: Part | None = None
    ) -> np.ndarray:
        """Boxes ``(n, 4)`` as written (1-based) of one result file, read strictly
        (:func:`smtmvt.data.read_boxes`); with ``n_frames``, exactly that many rows.
        ``SequenceError`` naming the file (and line) otherwise."""
        path = self.result_path(tracker, sequence, repeat, part=part)
        boxes = read_boxes(path, one_based=True)
        if n_frames is not None and len(boxes) != n_frames:
            rel = path.relative_to(self.root)
            of = sequence if part is None else f"{sequence} {part[0]} {part[1]}"
            raise SequenceError(f"{rel}: {len(boxes)} lines for {n_frames} frames of {of}", path=path)
        return boxes

    def result_problem(
        self, tracker: str, sequence: str, n_frames: int, repeat: int = 0, *, part: Part | None = None
    ) -> str | None:
        """None when the pair's result file is complete: ``n_frames`` well-formed lines of
        finite numbers. Otherwise why not (``"missing"`` when there is no file)."""
        path = self.result_path(tracker, sequence, repeat, part=part)
        if not path.exists():
            return "missing"
        try:
            boxes = self.read_result(tracker, sequence, repeat, n_frames, part=part)
        except SequenceError as exc:
            return str(exc)
        bad = ~np.isfinite(boxes).all(axis=1)
        if bad.any():
            return f"{path.relative_to(self.root)}, line {int(np.argmax(bad)) + 1}: not a finite box"
        return None

    def read_record(self, tracker: str, sequence: str, repeat: int = 0, *, part: Part | None = None) -> dict | None:
        """The pair's record (:meth:`write_result`), or None when there is none or it cannot
        be read as a JSON object."""
        try:
            record = json.loads(self.record_path(tracker, sequence, repeat, part=part).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        return record if isinstance(record, dict) else None

    def record_problem(
        self, tracker: str, sequence: str, expected: dict, repeat: int = 0, *, part: Part | None = None
    ) -> str | None:
        """None when the pair's complete result was made from ``expected`` (the record this
        command would write: ``first_box`` 1-based, ``n_frames``, ``sequence_frames``,
        ``seed``, ``settings``); otherwise what differs, naming the file and the sequence.

        A result without a record (a command killed between the two writes) is checked by
        its first line, which is the first box it started from (the rest is checked for the
        whole tracker by :meth:`settle`); when it passes, the caller writes its record."""
        rel = self.result_path(tracker, sequence, repeat, part=part).relative_to(self.root)
        record = self.read_record(tracker, sequence, repeat, part=part)
        if record is None:
            first = self.read_result(tracker, sequence, repeat, part=part)[0].tolist()
            record = {**expected, "first_box": first}
        for key, new in expected.items():
            old = record.get(key)
            if old != new:
                return f"{rel}: {_record_change(sequence, key, old, new)}"
        return None

    def read_times(
        self, tracker: str, sequence: str, repeat: int = 0, *, part: Part | None = None
    ) -> np.ndarray | None:
        """Seconds per frame ``(n,)`` of one pair, or None when the file is missing or not
        one finite non-negative number per line (or not a regular file: a FIFO is not read)."""
        path = self.times_path(tracker, sequence, repeat, part=part)
        try:
            lines = [line for line in read_regular_bytes(path).decode("utf-8").splitlines() if line.strip()]
            times = np.array([float(v) for v in lines], dtype=np.float64)
        except (OSError, ValueError):
            return None
        if not times.size or not np.all(np.isfinite(times)) or np.any(times < 0):
            return None
        return times

    # ------------------------------------------------------------------ run.json
    def info(self) -> RunInfo:
        """The settings in ``run.json``; RunDirError when the folder is not a run."""
        if not self.root.is_dir():
            raise FileNotFoundError(f"run folder not found: {self.root}")
        if not self.run_json.is_file():
            raise RunDirError(
                f"{self.root} is not a run folder (no {RUN_JSON}); make one with smtmvt evaluate --out {self.root}"
            )
        return self._read_info()

    def _read_info(self) -> RunInfo:
        try:
            data = json.loads(self.run_json.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise RunDirError(f"{self.run_json}: not valid JSON ({exc}); remove it or choose another --out") from None
        if not isinstance(data, dict):
            raise RunDirError(f"{self.run_json}: expected a JSON object; remove it or choose another --out")
        return RunInfo.from_json(data, self.run_json)

    def save_info(self, info: RunInfo) -> None:
        self.write_text(self.run_json, json.dumps(info.to_json(), indent=1) + "\n")

    def errors(self) -> ErrorLog:
        return ErrorLog(self)

    # ------------------------------------------------------------------ lock
    @contextlib.contextmanager
    def locked(self, command: str = "smtmvt", *, create: bool = False) -> Iterator[RunDir]:
        """Hold the run's lock (an exclusive ``flock`` on ``.lock``) for the block.

        ``create``: make the folder if needed (``evaluate``); otherwise the folder must
        already be a run (:meth:`info`), and nothing is created in one that is not.
        Re-entrant for this object. A second command on the same folder gets a
        :class:`RunLockedError` naming the holder at once (no waiting). The lock dies with
        its process, so a killed run never leaves the folder locked.
        """
        if self._lock_depth:
            self._lock_depth += 1
            try:
                yield self
            finally:
                self._lock_depth -= 1
            return
        if create:
            self.check_can_hold_run()
            self.root.mkdir(parents=True, exist_ok=True)
        else:
            self.info()
        fd = _acquire(self.root / LOCK, command)
        self._lock_fd, self._lock_depth = fd, 1
        try:
            yield self
        finally:
            self._lock_fd, self._lock_depth = None, 0
            os.close(fd)

    # ------------------------------------------------------------------ starting a run
    def settle(
        self,
        dataset: Path,
        *,
        trackers: Iterable[str],
        sequences: Iterable[str],
        max_frames: int | None,
        repeat: int | None,
        attributes=None,
        published=None,
        overwrite: bool = False,
        tracker_settings: dict | None = None,
        protocols: Iterable[str] = ("ope",),
    ) -> tuple[RunInfo, list[str]]:
        """Check this command's settings against the folder's and write ``run.json``.

        A folder keeps one dataset and one frame limit: a different one is a RunDirError
        naming both, unless ``overwrite`` (then results, errors and report are removed
        first). It keeps each tracker's settings (``tracker_settings``: ``{tracker: record}``
        of :mod:`.settings`): different ones, or results of a tracker with no record (made
        before records existed: their settings are unknown), are a RunDirError naming what
        differs, unless ``overwrite`` (then that tracker's results, its errors and the report
        are removed first). ``repeat`` None takes the folder's count; a larger one is stored
        (later repeats are added), a smaller one is used for this command only. Tracker and
        sequence lists are merged (first-seen order), and so are ``protocols`` (kept in
        ``ope, tre, sre`` order; a new folder holds this command's only). Returns ``(info, notes)``; the
        returned ``info.repeat`` is this command's count. Call under :meth:`locked`.
        """
        notes: list[str] = []
        self.check_can_hold_run()
        self._remove_stale_temporaries(notes)
        old = self._read_info() if self.run_json.is_file() else None
        if old is not None:
            clash = _settings_clash(self, old, dataset, max_frames)
            if clash and not overwrite:
                raise RunDirError(clash)
            if clash:
                notes.append(self._wipe())
                old = None
        info = old or RunInfo()
        notes += self._settle_trackers(info, tracker_settings or {}, overwrite)
        stored = info.repeat
        info.dataset = str(dataset)
        info.trackers = _merge(info.trackers, trackers)
        info.sequences = _merge(info.sequences, sequences)
        held = set(info.protocols if old is not None else ()) | set(protocols)
        info.protocols = [p for p in ALL_PROTOCOLS if p in held]
        info.attributes = str(Path(attributes).resolve()) if attributes else info.attributes
        info.published = str(Path(published).resolve()) if published else info.published
        info.max_frames = max_frames
        wanted = stored if repeat is None else repeat
        info.repeat = max(stored, wanted) if old is not None else wanted
        self.save_info(info)
        if wanted < info.repeat:
            notes.append(f"{self.root} holds {info.repeat} repeats; this command uses the first {wanted}")
        return RunInfo(**{**asdict(info), "repeat": wanted}), notes

    def check_can_hold_run(self) -> None:
        """RunDirError unless the folder is missing, empty, a run (``run.json``), or holds only
        what a command stopped before writing ``run.json`` leaves (``.lock``, the temporary
        file of ``run.json``). Reads only: a folder that is refused is left as it is."""
        if not self.root.exists():
            return
        if not self.root.is_dir():
            raise RunDirError(f"{self.root} is not a folder; choose another --out")
        if self.run_json.is_file():
            return
        foreign = sorted(p.name for p in self.root.iterdir() if not _is_left_before_run_json(p))
        if foreign:
            shown = ", ".join(foreign[:3]) + (", ..." if len(foreign) > 3 else "")
            raise RunDirError(
                f"{self.root} is not a run folder (no {RUN_JSON}) and is not empty ({shown}); "
                f"nothing in it was changed. Choose a new or empty folder for --out"
            )

    def _remove_stale_temporaries(self, notes: list[str]) -> None:
        """Delete the temporary files of atomic writes that a killed command left (hidden
        ``.<name>.<random>.tmp`` beside their target; no reader ever takes them for results),
        only where the run writes: beside ``run.json`` and ``errors.json``, and in its own
        ``results/`` and ``report/`` trees (real folders only, no link followed). Safe under
        the lock: no other command is writing."""
        stale = [p for p in self.root.glob(".*.tmp") if _is_temporary_of(p, (RUN_JSON, ERRORS_JSON))]
        for top in (self.results_dir, self.report_dir):
            stale += [p for p in _real_files(top) if _is_temporary_of(p)]
        for p in stale:
            p.unlink(missing_ok=True)
        if stale:
            notes.append(f"removed {len(stale)} temporary file(s) left by an interrupted command")

    def _settle_trackers(self, info: RunInfo, settings: dict, overwrite: bool) -> list[str]:
        """Check each tracker's settings against ``info``'s record (see :meth:`settle`) and
        enter them there; RunDirError naming the first clash, unless ``overwrite``."""
        clashes = {name: why for name, record in settings.items() if (why := self._tracker_clash(info, name, record))}
        if clashes and not overwrite:
            name, why = next(iter(clashes.items()))
            steps = ["choose another --out", f"pass --overwrite to discard the results of {name}"]
            if name in info.tracker_settings:  # known settings: the same ones resume it
                steps.insert(0, "repeat the settings it was made with to resume it")
            raise RunDirError(f"{self.root}: {why}. Either {', '.join(steps[:-1])}, or {steps[-1]}")
        notes = [self._wipe_tracker(name) for name in clashes]
        # a record the same as the stored one (settings_difference) stays as stored: the results'
        # records hold its digest
        info.tracker_settings.update(
            {name: r for name, r in settings.items() if name in clashes or name not in info.tracker_settings}
        )
        return notes

    def _tracker_clash(self, info: RunInfo, name: str, record: dict) -> str | None:
        """Why ``name``'s results in this folder cannot be resumed with ``record``, or None."""
        old = info.tracker_settings.get(name)
        if old is None:
            base = self.tracker_dir(name)
            if any(base.glob("*.txt")) or any(base.glob("repeat-*/*.txt")):
                return (
                    f"results/{name} holds results made before run folders recorded tracker settings "
                    f"(run.json has none for {name}), so they cannot be checked against this command's"
                )
            return None
        why = settings_difference(old, record)
        return None if why is None else f"results/{name} was made with other settings than this command's ({why})"

    def _wipe_tracker(self, name: str) -> str:
        """Remove ``results/<name>``, its errors and report/ (for ``--overwrite``); say so."""
        base = self.tracker_dir(name)
        n = sum(1 for p in base.rglob("*.txt")) if base.is_dir() and not base.is_symlink() else 0
        for folder in (base, self.report_dir):
            if folder.is_symlink():
                folder.unlink()
            elif folder.exists():
                shutil.rmtree(folder)
        self.errors().drop(lambda t, s, r: t != name)
        return f"--overwrite: removed {n} result/times file(s) of {name}, its errors and report/ of {self.root}"

    def _wipe(self) -> str:
        """Remove results/, errors.json and report/ (for ``--overwrite``); say what went."""
        n = sum(1 for p in self.results_dir.rglob("*.txt")) if self.results_dir.is_dir() else 0
        for folder in (self.results_dir, self.report_dir):
            if folder.is_symlink():
                folder.unlink()
            elif folder.exists():
                shutil.rmtree(folder)
        self.errors_json.unlink(missing_ok=True)
        return f"--overwrite: removed {n} result/times file(s), errors.json and report/ of {self.root}"


def _settings_clash(run: RunDir, old: RunInfo, dataset: Path, max_frames: int | None) -> str | None:
    if old.dataset and Path(old.dataset).resolve() != dataset:
        return (
            f"{run.root} holds results for dataset {old.dataset}, not {dataset}; "
            f"choose another --out (results of different datasets must not mix)"
        )
    if old.max_frames != max_frames:

        def limit(v):
            return "all frames" if v is None else f"--max-frames {v}"

        return (
            f"{run.root} was run with {limit(old.max_frames)} (run.json); this command asks for "
            f"{limit(max_frames)}. Repeat the same setting to resume it, choose another --out, or pass "
            f"--overwrite to discard its results"
        )
    return None


#: ``.<target>.<8 random characters>.tmp``: the temporary file of an atomic write
#: (:func:`smtmvt.data.write_bytes_atomic`, ``tempfile.mkstemp``'s names)
_TEMPORARY = re.compile(r"\.(.+)\.[a-z0-9_]{8}\.tmp")


def _is_temporary_of(path: Path, targets: Iterable[str] | None = None) -> bool:
    """Whether ``path`` is a regular file named as the temporary of an atomic write (of one
    of ``targets``, when given)."""
    m = _TEMPORARY.fullmatch(path.name)
    ok = m is not None and (targets is None or m.group(1) in targets)
    return ok and path.is_file() and not path.is_symlink()


def _is_left_before_run_json(path: Path) -> bool:
    """``.lock`` or a temporary of ``run.json``: all a command leaves before ``run.json``."""
    return (path.name == LOCK and path.is_file()) or _is_temporary_of(path, (RUN_JSON,))


def _real_files(top: Path) -> Iterator[Path]:
    """Files under ``top`` through real folders only (nothing when ``top`` is a link)."""
    if top.is_symlink() or not top.is_dir():
        return
    for folder, _, files in os.walk(top, followlinks=False):
        for name in files:
            yield Path(folder) / name


def _record_change(sequence: str, key: str, old, new) -> str:
    """What changed between a result's record and this command's, in words."""

    def box(b) -> str:
        try:
            return ",".join(f"{float(v):.10g}" for v in b)
        except (TypeError, ValueError):
            return repr(b)

    if key == "first_box":
        return f"{sequence}'s first ground-truth box is now {box(new)}; the result started from {box(old)}"
    if key == "sequence_frames":
        return f"{sequence} now has {new} frames; the result was made when it had {old}"
    if key == "n_frames":
        return f"{new} frames of {sequence} to run; the result was made for {old}"
    if key == "settings":
        return f"made with other tracker settings than this command's (digest {old}, now {new})"
    return f"made with {key} {old!r}; this command uses {new!r}"


def _merge(old: Iterable, new: Iterable) -> list:
    out: list = []
    for x in [*old, *new]:
        if x not in out:
            out.append(x)
    return out


def _acquire(path: Path, command: str) -> int:
    import fcntl

    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError as exc:
        holder = os.pread(fd, 200, 0).decode("utf-8", "replace").strip() or "another process"
        os.close(fd)
        if exc.errno in (errno.EAGAIN, errno.EACCES, errno.EWOULDBLOCK):
            raise RunLockedError(
                f"{path.parent} is in use by {holder}; wait for it to finish or choose another run folder"
            ) from None
        raise
    os.ftruncate(fd, 0)
    os.pwrite(fd, f"{command} (pid {os.getpid()})\n".encode(), 0)
    return fd
