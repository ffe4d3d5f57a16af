"""A benchmark folder: one OTB sequence per sub-folder (``<root>/<Seq>/img`` + ground truth),
or a GOT-10k, LaSOT, UAV123 or VOT folder, detected by :func:`.layouts.detect_layout`."""

from __future__ import annotations

import re
from pathlib import Path

from .errors import SequenceError
from .layouts import detect_layout, layout_module
from .names import name_clashes, natural_key
from .otb import groundtruth_targets, is_otb_folder, open_otb_sequence

__all__ = ["open_dataset", "list_dataset"]


def list_dataset(root) -> list:
    """Sequences in ``root`` without opening them: ``[(name, folder, target), ...]``.

    A sub-folder counts when it has ``img/`` or a ground-truth file (hidden
    folders and others are ignored). A folder with several numbered
    ground-truth files (``groundtruth_rect.1.txt``, ``.2.txt``) gives one entry
    per target, named ``<folder>-<k>``; a single numbered file also gives
    ``<folder>-<k>`` (Human4 -> ``Human4-2``, as OTB names it). ``target`` is
    None for a plain ``groundtruth_rect.txt`` or none at all. Sorted by name,
    naturally and case-insensitively.

    A folder in another layout (:mod:`.layouts`) gives that layout's sequences, each
    ``(name, folder, None)``: GOT-10k and VOT ``<seq>``, LaSOT ``<class>-<n>``, UAV123 the
    annotation file's stem (``bird1_2``, whose folder is ``data_seq/UAV123/bird1``).
    """
    root = Path(root)
    if not root.is_dir():
        raise SequenceError(f"dataset folder not found: {root}", path=root)
    layout = layout_module(detect_layout(root))
    if layout is not None:
        return sorted(layout.entries(root), key=lambda e: natural_key(e[0]))
    entries = []
    for folder in root.iterdir():
        if folder.name.startswith(".") or not folder.is_dir():
            continue
        targets = groundtruth_targets(folder)
        if not targets and not is_otb_folder(folder):
            continue
        if not targets or None in targets:
            entries.append((folder.name, folder, None))
        else:
            entries.extend((f"{folder.name}-{k}", folder, k) for k in targets)
    return sorted(entries, key=lambda e: natural_key(e[0]))


def _select(entries, names, root):
    """Entries matching ``names`` (sequence or folder names, case-insensitive)."""
    wanted: dict[str, object] = {}
    for n in names:
        wanted.setdefault(str(n).casefold(), n)
    chosen, matched = [], set()
    for entry in entries:
        name, folder, _ = entry
        keys = {name.casefold(), folder.name.casefold()}
        hit = keys & wanted.keys()
        if hit:
            chosen.append(entry)
            matched |= hit
    unknown = [wanted[k] for k in wanted if k not in matched]
    if unknown:
        available = ", ".join(e[0] for e in entries) or "none"
        raise SequenceError(
            f"{root}: no sequence named {', '.join(map(repr, unknown))} (case-insensitive); available: {available}",
            path=root,
        )
    return chosen


def _clash_messages(names, root) -> dict[str, str]:
    """An error message for each name that differs from another only in case or separators."""
    out = {}
    for group in name_clashes(names).values():
        listed = " and ".join(repr(n) for n in group)
        for name in group:
            out[name] = (
                f"{root}: sequences {listed} differ only in case or separators ('_', '-', '.', space); "
                f"results and reports match names that way, so one would carry the other's scores: rename one"
            )
    return out


def open_dataset(root, sequences=None, *, on_error="raise") -> list:
    """Open every sequence in ``root`` (see :func:`list_dataset`), sorted by name.

    The folder's layout is detected (:func:`.layouts.detect_layout`): OTB by default, else
    GOT-10k, LaSOT, UAV123 or VOT; frames where a layout's labels say the target is absent
    have NaN ground-truth rows (see each layout module for the rule scoring applies).

    Parameters
    ----------
    root : path
        Folder of sequence folders (e.g. ``.../otb``).
    sequences : iterable of str, optional
        Keep only these; a name matches a sequence name (``Jogging-1``) or a
        folder name (``Jogging``: all its targets), case-insensitively.
        An unknown name raises SequenceError listing the available names.
    on_error : {"raise", "collect"}
        What to do with a sequence that cannot be opened (no images, no or bad
        ground truth, a name that differs from another sequence's only in case or
        separators, see :func:`~smtmvt.data.names.canonical_name`, ...):

        - ``"raise"``: raise its SequenceError (the first one, in name order);
        - ``"collect"``: put the SequenceError in the returned list, in that
          sequence's place, and go on. The error names the file (and line)
          at fault; its ``.sequence`` attribute holds the sequence name.

    Returns
    -------
    list
        ``"raise"``: ``list[Sequence]``. ``"collect"``: ``list[Sequence | SequenceError]``,
        one item per sequence, so a runner can report the broken ones and go
        on with the rest::

            for item in open_dataset(root, on_error="collect"):
                if isinstance(item, SequenceError):
                    print(f"skipped {item.sequence}: {item}")
                    continue
                ...

    Notes
    -----
    Every sequence must have a ground-truth file (it is a benchmark). Opening
    reads the ground truth and lists the images; frames are read later, and a
    bad frame raises SequenceError (naming file and frame) when read.
    """
    if on_error not in ("raise", "collect"):
        raise ValueError(f"on_error must be 'raise' or 'collect', got {on_error!r}")
    root = Path(root)
    entries = list_dataset(root)
    clashes = _clash_messages([e[0] for e in entries], root)
    if sequences is not None:
        if isinstance(sequences, str):
            sequences = re.split(r"[,\s]+", sequences.strip())
        entries = _select(entries, sequences, root)
    items: list = []
    layout = layout_module(detect_layout(root))
    for name, folder, target in entries:
        try:
            if name in clashes:
                raise SequenceError(clashes[name], path=folder)
            if layout is not None:
                items.append(layout.open_entry(root, name, folder))
                continue
            if not groundtruth_targets(folder):
                raise SequenceError(f"{folder}: no ground-truth file (groundtruth_rect.txt)", path=folder)
            items.append(open_otb_sequence(folder, name=name, target=target))
        except SequenceError as exc:
            if exc.sequence is None:
                exc.sequence = name
            if on_error == "raise":
                raise
            items.append(exc)
    return items
