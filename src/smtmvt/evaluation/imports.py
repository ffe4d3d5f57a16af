"""Importing other trackers' per-frame results into a run folder, safely.

``import_into_run(RUN_DIR, SOURCE)`` reads foreign results (OTB toolkit ``.mat``, the
benchmark's per-frame JSON, got10k/pysot text; :func:`.published.import_results`, the lenient
readers meant for other people's files) and stores them as ``results/<tracker>/<seq>.txt``
so the report scores them with our metrics on our sequences.

What can never happen
---------------------
* A file outside the run: every sequence name is matched against the run's sequences (the
  dataset's spelling is used; a name from inside a file, such as a JSON ``seqName`` of
  ``"../../x"``, that matches none is skipped and said so), and tracker names must be folder
  names (:func:`~.rundir.check_tracker_name`: no ``..``).
* Our own results replaced: a tracker name that this run computed (in ``run.json`` or a
  folder without ``import.json``) is imported as ``<name>-imported`` instead, with a note.
* A folder that is not a run: refused (it has no dataset to check names against).
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable
from pathlib import Path

import numpy as np

from ..data import canonical_name, list_dataset
from ..data.boxes import ONE_BASED_OFFSET
from .published import ImportedResult, import_results
from .rundir import RunDir, RunInfo, check_tracker_name

__all__ = ["import_into_run", "IMPORTED_SUFFIX"]

#: appended to an imported tracker's name when the run computed a tracker of that name
IMPORTED_SUFFIX = "-imported"


def import_into_run(
    run_dir,
    source,
    tracker_name: str | None = None,
    fmt: str = "auto",
    trackers: Iterable[str] | None = None,
    sequences: Iterable[str] | None = None,
    notes: list | None = None,
) -> dict[str, list[str]]:
    """Import foreign results into ``RUN_DIR/results/<tracker>/<seq>.txt``.

    Only the run's sequences are imported (``sequences`` narrows them further; names match
    by :func:`~smtmvt.data.canonical_name` and take the run's spelling). Per-frame times go to
    ``times/<seq>_time.txt`` when the source has them (text) or an fps (``1/fps`` per
    frame); without either, no times (those of an earlier import of that sequence are removed).
    Provenance and the annotation offset of each sequence (Tiger1 starts at frame 6
    in the toolkit's files) go to ``results/<tracker>/import.json``. ``notes`` (a list)
    receives the remarks (skipped results, renamed trackers). Returns ``{tracker:
    [sequences written]}``; ValueError when nothing could be imported.
    """
    run = RunDir(run_dir)
    if tracker_name is not None:
        check_tracker_name(tracker_name)
    notes = notes if notes is not None else []
    with run.locked("smtmvt report --import"):
        info = run.info()
        allowed = _run_sequences(info, sequences)
        found = import_results(
            source, fmt=fmt, tracker_name=tracker_name, trackers=trackers, sequences=allowed.values()
        )
        written: dict[str, list[str]] = {}
        for trk, items in found.items():
            name = _target_name(run, info, trk, notes)
            accepted = {}
            for res in items.values():
                seq = allowed.get(canonical_name(res.sequence))
                if seq is None:
                    notes.append(
                        f"skipped {res.source}: it names sequence {res.sequence!r}, not a sequence of this run"
                    )
                else:
                    accepted[seq] = res
            if accepted:
                written[name] = _store(run, name, accepted)
    if not written:
        why = "; ".join(notes) if notes else f"trackers={trackers}"
        raise ValueError(f"{source}: no results matched this run's sequences ({why})")
    return written


def _run_sequences(info: RunInfo, sequences: Iterable[str] | None) -> dict[str, str]:
    """``{canonical name: the run's spelling}`` of the sequences an import may write."""
    names = list(info.sequences)
    if info.dataset and Path(info.dataset).is_dir():
        known = {canonical_name(n): n for n, _folder, _target in list_dataset(info.dataset)}
        names = [known.get(canonical_name(n), n) for n in names] or list(known.values())
    allowed = {canonical_name(n): n for n in names}
    if sequences is not None:
        wanted = {canonical_name(s) for s in sequences}
        allowed = {k: v for k, v in allowed.items() if k in wanted}
    return allowed


def _target_name(run: RunDir, info: RunInfo, tracker: str, notes: list) -> str:
    """``tracker``, or ``tracker-imported`` when the run computed a tracker of that name."""
    check_tracker_name(tracker)

    def computed(name: str) -> bool:
        return name in info.trackers or (run.tracker_dir(name).is_dir() and not run.is_imported(name))

    if not computed(tracker):
        return tracker
    other = tracker + IMPORTED_SUFFIX
    if computed(other):
        raise ValueError(f"this run computed both {tracker!r} and {other!r}: import under another name (PATH:NAME)")
    notes.append(
        f"{tracker}: this run computed results of that name; imported as {other!r} (its own results are untouched)"
    )
    return other


def _store(run: RunDir, tracker: str, items: dict[str, ImportedResult]) -> list[str]:
    """Write boxes, times and ``import.json`` of one imported tracker; the names written."""
    meta = run.import_meta(tracker)
    meta.setdefault("sequences", {})
    for seq, res in sorted(items.items()):
        meta["sequences"][seq] = {
            "source": os.path.abspath(res.source),
            "format": res.format,
            "source_name": res.sequence,
            "result_type": res.result_type,
            "start_frame": res.start_frame,
            "anno_begin": res.anno_begin,
            "anno_offset": res.anno_offset,
            "fps": res.fps,
            "frames": int(len(res.boxes)),
        }
    meta["imported"] = True
    # the marker first: a folder with results is never taken for computed ones, even if
    # this is interrupted half-way
    run.write_text(run.import_json(tracker), json.dumps(meta, indent=2, sort_keys=True))
    for seq, res in sorted(items.items()):
        times = None
        if res.times is not None and len(res.times) == len(res.boxes):
            times = np.asarray(res.times, dtype=np.float64)
        elif res.fps and res.fps > 0:
            times = np.full(len(res.boxes), 1.0 / res.fps)
        else:  # no speed known: an earlier import's times must not give this one its FPS
            run._checked(run.times_path(tracker, seq)).unlink(missing_ok=True)
        run.write_result(tracker, seq, np.asarray(res.boxes, dtype=np.float64) - ONE_BASED_OFFSET, times)
    return sorted(items)
