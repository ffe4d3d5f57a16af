"""Ground truth of a dataset folder for scoring, looked up by any spelling of a name."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from ..data import ABSENT_RULES, SequenceError, canonical_name, detect_layout, name_clashes, open_dataset
from .published import read_box_file

__all__ = ["GroundTruth", "load_groundtruth_source"]


class GroundTruth:
    """Ground truth (1-based, as in the files) of a dataset folder, looked up by any spelling.

    OTB folders (``<Seq>/img`` + ``groundtruth_rect*.txt``) are opened with
    :mod:`smtmvt.data` (which knows the OTB quirks: David's frame range, numbered targets);
    anything else (an ``anno/`` folder of ``<Seq>.txt``, folders without images) is read
    directly (other people's files: the lenient reader). Names that differ only in case or
    separators (``Seq_1``, ``seq-1``) are refused, never mixed up.

    A GOT-10k, LaSOT, UAV123 or VOT folder (:func:`smtmvt.data.detect_layout`) is read by
    its layout's reader only; ``layout`` names it and ``absent_rule`` is how its toolkit
    scores frames without a box (``invalid=`` of :mod:`.metrics`; ``"otb"`` for OTB).
    """

    def __init__(self, root) -> None:
        self.root = Path(root)
        if not self.root.exists():
            raise FileNotFoundError(f"dataset not found: {self.root}")
        self._boxes: dict[str, np.ndarray] = {}
        self._names: dict[str, str] = {}
        self._errors: dict[str, str] = {}
        self._files: dict[str, Path] = {}
        self.layout = detect_layout(self.root)
        self.absent_rule = ABSENT_RULES[self.layout]
        self._scan_sequences()
        if self.layout == "otb":
            self._scan_files()

    def _scan_sequences(self) -> None:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                items = open_dataset(self.root, on_error="collect")
        except SequenceError:  # not an OTB folder of folders; read it as files
            items = []
        for item in items:
            if isinstance(item, SequenceError):
                if _annotations_only(item):
                    continue  # a folder of ground truth without img/: read as a file below
                name = item.sequence or "?"
                self._names.setdefault(canonical_name(name), name)
                self._errors[canonical_name(name)] = str(item)
                continue
            key = canonical_name(item.name)
            self._names.setdefault(key, item.name)
            if item.groundtruth is None:
                self._errors[key] = f"sequence {item.name}: no ground truth"
                continue
            self._boxes[key] = np.asarray(item.groundtruth, dtype=np.float64) + np.array([1.0, 1.0, 0.0, 0.0])

    def _scan_files(self) -> None:
        """``anno/<Seq>.txt`` files, or sequence folders the data layer did not take."""
        found: list[tuple[str, Path]] = []
        for p in sorted(self.root.iterdir()) if self.root.is_dir() else []:
            if p.is_file() and p.suffix.lower() == ".txt":
                found.append((p.stem, p))
            elif p.is_dir():
                if (p / "groundtruth_rect.txt").is_file():
                    found.append((p.name, p / "groundtruth_rect.txt"))
                for f in sorted(p.glob("groundtruth_rect.*.txt")):
                    k = f.name.split(".")[1]
                    if k.isdigit():
                        found.append((f"{p.name}-{k}", f))
        for name, path in found:
            self._files.setdefault(canonical_name(name), path)
            self._names.setdefault(canonical_name(name), name)
        for key, names in name_clashes(dict.fromkeys(n for n, _ in found)).items():
            self._errors[key] = (
                f"{self.root}: name collision: sequences {' and '.join(map(repr, names))} differ only in case "
                "or separators, so neither is scored (one would carry the other's scores): rename one"
            )
            self._boxes.pop(key, None)
            self._files.pop(key, None)

    def names(self) -> list[str]:
        return list(self._names.values())

    def display_name(self, seq: str) -> str:
        return self._names.get(canonical_name(seq), seq)

    def load(self, seq: str) -> np.ndarray:
        """``(n, 4)`` 1-based boxes of ``seq``; ValueError naming the problem."""
        key = canonical_name(seq)
        if key in self._boxes:
            return self._boxes[key]
        if key in self._errors:
            raise ValueError(self._errors[key])
        if key in self._files:
            boxes = read_box_file(self._files[key])
            self._boxes[key] = boxes
            return boxes
        raise ValueError(f"no ground truth for sequence {seq!r} in {self.root}")


def _annotations_only(error: SequenceError) -> bool:
    """True for the data layer's error about a sequence folder that has no ``img/``."""
    path = Path(error.path) if error.path else None
    return path is not None and path.name == "img" and not path.exists()


def load_groundtruth_source(dataset) -> GroundTruth:
    """Ground-truth look-up of a dataset folder (OTB sequence folders or an ``anno`` folder)."""
    return GroundTruth(dataset)
