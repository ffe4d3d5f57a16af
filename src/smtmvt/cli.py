"""The ``smtmvt`` command line: ``track``, ``demo``, ``evaluate``, ``report``.

Each sub-command lives in the module that owns its work; this file only wires
them into one argparse parser. A sub-command module exposes
``add_parser(subparsers)`` which registers the parser and sets ``func``.
"""

from __future__ import annotations

import argparse
import sys

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


def main(argv=None) -> int:
    from .commands.args import join_negative_values

    parser = build_parser()
    args = parser.parse_args(join_negative_values(list(sys.argv[1:] if argv is None else argv)))
    try:
        return int(args.func(args) or 0)
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except (ValueError, FileNotFoundError, OSError) as exc:
        # Bad input: one clear line naming the file / frame / value at fault.
        print(f"smtmvt {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
