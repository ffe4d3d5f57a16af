"""The ``smtmvt`` command line: ``track``, ``demo``, ``evaluate``, ``report``.

Each sub-command lives in the module that owns its work; this file only wires
them into one argparse parser. A sub-command module exposes
``add_parser(subparsers)`` which registers the parser and sets ``func``.
"""

from __future__ import annotations

import argparse
import contextlib
import signal
import sys
import threading

__all__ = ["main", "build_parser"]


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


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread so that a command stops as it does on Ctrl-C:
    ``finally`` blocks run, worker processes are ended, nothing partial is written."""

    signum = signal.SIGTERM


@contextlib.contextmanager
def _sigterm_as_interrupt():
    def handler(signum, frame):
        raise Terminated()

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def main(argv=None) -> int:
    """Run one sub-command. Exit status: its own (0, or 1 for partial failures), 2 for bad
    input (one ``error:`` line), 130 after Ctrl-C, 143 after SIGTERM."""
    from .commands.args import join_negative_values

    parser = build_parser()
    args = parser.parse_args(join_negative_values(list(sys.argv[1:] if argv is None else argv)))
    try:
        with _sigterm_as_interrupt():
            return int(args.func(args) or 0)
    except KeyboardInterrupt as exc:
        terminated = isinstance(exc, Terminated)
        print("terminated" if terminated else "interrupted", file=sys.stderr)
        return 128 + (signal.SIGTERM if terminated else signal.SIGINT)
    except (ValueError, FileNotFoundError, OSError) as exc:
        # Bad input: one clear line naming the file / frame / value at fault.
        print(f"smtmvt {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
