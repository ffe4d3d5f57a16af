"""OTB attribute tables: which of the 11 challenge attributes each sequence has.

Two file layouts are read:

- the OTB toolkit's ``anno/att/<Seq>.txt``: one file per sequence, 11 flags
  ``0``/``1`` (comma or space separated) in the toolkit's order
  :data:`OTB_FLAG_ORDER` = IV, OPR, SV, OCC, DEF, MB, FM, IPR, OV, BC, LR
  (note: not the order of :data:`ATTRIBUTES`);
- a table file, one sequence per line: ``<name><TAB><codes>``, codes separated
  by commas and/or spaces, e.g. ``Basketball\tIV, OCC, DEF, OPR, BC``
  (``attributes-tb100.txt``).

The OTB results folder holding both (``attributes-tb100.txt`` and
``anno/att/``) is accepted too: its table file is read (see below).

Either way the codes come back in the display order :data:`ATTRIBUTES`, so
tables from both layouts compare equal.

The two published sources do not fully agree: in the OTB-100 data the toolkit's
``anno/att`` files differ from ``attributes-tb100.txt`` for Box, Car1, Car2,
Coke, Crossing and Jump (the flag files lack some attributes, e.g. Crossing's
FM and OPR), and ``anno/att/Human4.txt`` is all zeros while the table has
``Human4-2: IV, SV, OCC, DEF``. The published per-attribute scores
(``scores_tb100/<ATTR>.json``) follow the table file: prefer it.
"""

from __future__ import annotations

import re
from pathlib import Path

from .errors import SequenceError
from .files import read_regular_bytes
from .names import lookup, natural_key

__all__ = ["ATTRIBUTES", "OTB_FLAG_ORDER", "ATTRIBUTE_NAMES", "load_attributes", "attributes_of"]

#: The 11 OTB attribute codes in the order the papers and plots use.
ATTRIBUTES = ("IV", "SV", "OCC", "DEF", "MB", "FM", "IPR", "OPR", "OV", "BC", "LR")

#: Order of the 11 flags in the OTB toolkit's ``anno/att/<Seq>.txt`` files.
OTB_FLAG_ORDER = ("IV", "OPR", "SV", "OCC", "DEF", "MB", "FM", "IPR", "OV", "BC", "LR")

#: Code -> short description.
ATTRIBUTE_NAMES = {
    "IV": "Illumination Variation",
    "SV": "Scale Variation",
    "OCC": "Occlusion",
    "DEF": "Deformation",
    "MB": "Motion Blur",
    "FM": "Fast Motion",
    "IPR": "In-Plane Rotation",
    "OPR": "Out-of-Plane Rotation",
    "OV": "Out-of-View",
    "BC": "Background Clutters",
    "LR": "Low Resolution",
}

# The table file of the OTB results folder, preferred to its ``anno/att`` flags.
_TABLE_FILE = "attributes-tb100.txt"

_RANK = {code: i for i, code in enumerate(ATTRIBUTES)}
_SPLIT = re.compile(r"[,\s]+")


def load_attributes(path) -> dict:
    """Read an attribute table: sequence name -> attribute codes.

    Parameters
    ----------
    path : path
        An ``att`` folder of per-sequence flag files (a folder that holds
        ``att/`` or ``anno/att/`` is accepted too), a table file (see module
        notes), or a folder holding the table file ``attributes-tb100.txt``
        (the OTB results folder), which is then preferred to its ``anno/att``.

    Returns
    -------
    dict[str, tuple[str, ...]]
        Keys are the sequence names **as given** (file stem or first column,
        case kept: ``basketball`` from ``anno/att``, ``Basketball`` from the
        table), in natural order; values are codes from :data:`ATTRIBUTES`,
        in that order. Look names up case-insensitively with
        :func:`attributes_of`.

    Raises
    ------
    SequenceError
        Missing path, a file that is not UTF-8 text or not a regular file, a
        flag file without exactly 11 flags 0/1, an unknown attribute code, a
        duplicate name; naming the file (and line).
    """
    path = Path(path)
    if path.is_dir() and (path / _TABLE_FILE).is_file():
        table = _read_table_file(path / _TABLE_FILE)
    elif path.is_dir():
        for sub in (path / "anno" / "att", path / "att"):
            if sub.is_dir():
                path = sub
                break
        table = _read_flag_folder(path)
    elif path.exists():  # a file (a FIFO or device is refused by _read_text, never waited on)
        table = _read_table_file(path)
    else:
        raise SequenceError(f"attribute file or folder not found: {path}", path=path)
    return dict(sorted(table.items(), key=lambda kv: natural_key(kv[0])))


def attributes_of(table: dict, name: str) -> tuple:
    """``table[name]`` matching the name case-insensitively (``BasketBall`` finds ``basketball``).

    Raises ``KeyError`` listing the known names when there is no match.
    """
    return lookup(table, name)


def _ordered(codes) -> tuple:
    return tuple(sorted(set(codes), key=_RANK.__getitem__))


def _read_flag_folder(folder: Path) -> dict:
    files = sorted((p for p in folder.glob("*.txt") if not p.name.startswith(".")), key=lambda p: natural_key(p.name))
    if not files:
        raise SequenceError(f"no attribute files (<Seq>.txt) in {folder}", path=folder)
    table: dict[str, tuple] = {}
    for f in files:
        text = _read_text(f).strip()
        flags = _SPLIT.split(text) if text else []
        if len(flags) != len(OTB_FLAG_ORDER) or any(v not in ("0", "1") for v in flags):
            raise SequenceError(
                f"{f}: expected {len(OTB_FLAG_ORDER)} flags 0/1 in the order {', '.join(OTB_FLAG_ORDER)}, "
                f"got {text[:80]!r}",
                path=f,
                line=1,
            )
        _add(table, f.stem, _ordered(c for c, v in zip(OTB_FLAG_ORDER, flags) if v == "1"), f, 1)
    return table


def _read_table_file(path: Path) -> dict:
    table: dict[str, tuple] = {}
    for i, line in enumerate(_read_text(path).splitlines(), start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        name, sep, rest = stripped.partition("\t")
        if not sep:
            name, _, rest = stripped.partition(" ")
        name = name.strip()
        codes = [c.upper() for c in _SPLIT.split(rest.strip()) if c]
        unknown = [c for c in codes if c not in _RANK]
        if unknown:
            raise SequenceError(
                f"{path}, line {i}: unknown attribute code {unknown[0]!r} (known: {', '.join(ATTRIBUTES)}): {line!r}",
                path=path,
                line=i,
            )
        _add(table, name, _ordered(codes), path, i)
    if not table:
        raise SequenceError(f"attribute table is empty: {path}", path=path)
    return table


def _read_text(path: Path) -> str:
    """The UTF-8 text of ``path`` (a byte-order mark dropped); SequenceError naming the file
    when it cannot be read, is not a regular file, or is not UTF-8 text."""
    try:
        raw = read_regular_bytes(path)
    except OSError as exc:
        raise SequenceError(f"cannot read attribute file {path}: {exc.strerror or exc}", path=path) from None
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise SequenceError(f"{path}, line {line}: not a text file (undecodable byte)", path=path, line=line) from None


def _add(table: dict, name: str, codes: tuple, path: Path, line: int) -> None:
    if name in table:
        raise SequenceError(f"{path}, line {line}: sequence {name!r} listed twice", path=path, line=line)
    table[name] = codes
