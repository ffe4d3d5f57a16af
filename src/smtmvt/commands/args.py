"""Argument types and checks shared by the sub-commands (one clear message per bad value)."""

from __future__ import annotations

import os
import re
from pathlib import Path

from ..argtypes import bounded_int, positive_int

__all__ = ["positive_int", "bounded_int", "check_writable", "same_file", "join_negative_values"]

# an option value that starts with '-' but is numbers: "-5,10,20,20", "-5 10 20 20"
_NEGATIVE_LIST = re.compile(r"-\d[\d.eE+-]*(?:[,\s]+[+-]?[\d.][\d.eE+-]*)+")
#: options whose value may start with a minus sign (argparse would take it for an option)
NUMBER_LIST_OPTIONS = ("--box",)


def join_negative_values(argv: list[str], options=NUMBER_LIST_OPTIONS) -> list[str]:
    """``["--box", "-5,10,20,20"]`` -> ``["--box=-5,10,20,20"]``, so that argparse reads a
    value that starts with a minus sign as the option's value, not as an unknown option."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        if argv[i] in options and i + 1 < len(argv) and _NEGATIVE_LIST.fullmatch(argv[i + 1]):
            out.append(f"{argv[i]}={argv[i + 1]}")
            i += 2
            continue
        out.append(argv[i])
        i += 1
    return out


def check_writable(path, what: str) -> Path:
    """Raise ``OSError`` naming ``path`` unless a file can be created there.

    The nearest existing folder above ``path`` must be a folder we may write in (missing
    folders below it are created on writing); ``path`` itself must not be a folder.
    """
    path = Path(path)
    if path.is_dir():
        raise IsADirectoryError(f"{what} {path}: is a folder")
    parent = path.parent
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if not parent.is_dir():
        raise NotADirectoryError(f"{what} {path}: {parent} is not a folder")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise PermissionError(f"{what} {path}: no permission to write in {parent}")
    return path


def same_file(a, b) -> bool:
    """True when ``a`` and ``b`` name one file (through links, ``..`` and case-folding
    file systems when both exist; by resolved path otherwise)."""
    a, b = Path(a), Path(b)
    try:
        return os.path.samefile(a, b)
    except OSError:
        return a.resolve() == b.resolve()
