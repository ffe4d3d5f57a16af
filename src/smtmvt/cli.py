"""The ``smtmvt`` command line: ``track``, ``demo``, ``evaluate``, ``report``.

Each sub-command lives in the module that owns its work; this file only wires
them into one argparse parser. A sub-command module exposes
``add_parser(subparsers)`` which registers the parser and sets ``func``.
"""

from __future__ import annotations

import argparse
import signal
import sys

from .interrupts import Terminated, interruption, signals_as_interrupts

__all__ = ["main", "build_parser", "Terminated"]


def build_parser() -> argparse.ArgumentParser:
    from . import __version__
    from .commands import demo as demo_cmd
    from .commands import track as track_cmd
    from .evaluation import cli as eval_cli

    parser = argparse.ArgumentParser(
        prog="smtmvt",
        description="SMTMVT visual tracker and OTB evaluation toolkit.",
    )
    parser.add_argument("--version", action="version", version=f"smtmvt {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    track_cmd.add_parser(sub)
    demo_cmd.add_parser(sub)
    eval_cli.add_parsers(sub)
    return parser


def main(argv=None) -> int:
    """Run one sub-command. Exit status: its own (0, or 1 for partial failures), 2 for bad
    input (one ``error:`` line), 130 after Ctrl-C, 143 after SIGTERM."""
    from .commands.args import join_negative_values

    parser = build_parser()
    args = parser.parse_args(join_negative_values(list(sys.argv[1:] if argv is None else argv)))
    with signals_as_interrupts():  # inside: a signal received is known to interruption()
        try:
            return int(args.func(args) or 0)
        except BaseException as exc:
            status = _failure_status(args.command, exc)
            if status is None:
                raise  # a bug: its traceback is wanted
            return status


def _failure_status(command: str, exc: BaseException) -> int | None:
    """Exit status of a command stopped by ``exc``, after one line on stderr: 130 / 143 for
    Ctrl-C / SIGTERM (also when compiled code wrapped them in another exception), 2 for bad
    input; None for any other exception."""
    stop = interruption(exc)
    if stop is not None:
        terminated = isinstance(stop, Terminated)
        print("terminated" if terminated else "interrupted", file=sys.stderr)
        return 128 + (signal.SIGTERM if terminated else signal.SIGINT)
    if isinstance(exc, (ValueError, OSError)):
        # Bad input: one clear line naming the file / frame / value at fault.
        print(f"smtmvt {command}: error: {exc}", file=sys.stderr)
        return 2
    return None


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
