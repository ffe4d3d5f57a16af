"""argparse value types shared by every command line of the project (``smtmvt track``,
``smtmvt evaluate``, the bench scripts): one clear message per bad value.

Neutral ground: the library's own command modules (:mod:`smtmvt.evaluation.cli`) and the
command layer (:mod:`smtmvt.commands`) both import from here, so that the library never
imports its command line.
"""

from __future__ import annotations

import argparse

__all__ = ["positive_int", "bounded_int"]


def positive_int(text: str) -> int:
    """argparse type: a whole number >= 1 (``--max-frames``, ``--workers``, ...)."""
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 1, got {text!r}")
    return value


def bounded_int(low: int, high: int):
    """argparse type: a whole number from ``low`` to ``high`` (``--repeat``: 1 to 1000)."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            value = low - 1
        if value < low:  # the message of positive_int for low = 1
            raise argparse.ArgumentTypeError(f"expected a whole number >= {low}, got {text!r}")
        if value > high:
            raise argparse.ArgumentTypeError(f"expected a whole number from {low} to {high}, got {text!r}")
        return value

    parse.__name__ = f"whole number from {low} to {high}"
    return parse
