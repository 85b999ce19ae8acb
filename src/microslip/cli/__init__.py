"""The ``microslip`` command line: one sub-command per module of this package.

Each module in :data:`COMMANDS` defines ``add_parser(subparsers)``, which
registers its sub-command and sets ``func(args) -> int`` as its handler.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import warnings

COMMANDS = ["reproduce", "tune", "simulate", "frf", "accuracy", "target"]


def build_parser() -> argparse.ArgumentParser:
    from ._args import Parser

    parser = Parser(
        prog="microslip",
        description="Microslip friction contacts with variable normal load (Gastaldi & Gola). "
                    "SI units unless a value carries its own unit (e.g. 10mm, 2.5um, 30N, 200GPa).")
    from ..common._version import __version__

    parser.add_argument("--version", action="version", version=f"microslip {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name in COMMANDS:
        importlib.import_module(f"{__name__}.{name}").add_parser(sub)
    return parser


def main(argv=None) -> int:
    """Entry point of the ``microslip`` console script."""
    parser = build_parser()
    args = parser.parse_args(argv)
    import matplotlib

    matplotlib.use("Agg")  # the commands write figures to files; no window is ever opened
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("default")  # each distinct warning once, wherever the filters were set
            warnings.showwarning = _show_warning(args.command)
            return int(args.func(args) or 0)
    except (ValueError, TypeError, OSError) as exc:
        print(f"microslip {args.command}: error: {exc}", file=sys.stderr)
        return 2


def _show_warning(command: str):
    """Warnings as a command's messages, ``microslip CMD: warning: ...``, without the source line."""

    def show(message, category, filename, lineno, file=None, line=None):
        print(f"microslip {command}: warning: {message}", file=sys.stderr)

    return show


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
