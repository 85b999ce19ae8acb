"""The ``microslip`` command line: one sub-command per module of this package.

Each sub-command of :data:`COMMANDS` is a module (its name with ``_`` for ``-``) that defines
``add_parser(subparsers)``, which registers it and sets ``func(args) -> int`` as its handler.
"""

from __future__ import annotations

import argparse
import importlib
import re
import sys
import warnings

COMMANDS = ["reproduce", "tune", "simulate", "frf", "design", "modes", "campbell", "sweep", "accuracy", "target",
            "config-reference"]


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
        importlib.import_module(f"{__name__}.{name.replace('-', '_')}").add_parser(sub)
    return parser


#: a value with a sign and a unit, such as -30N or -2.5um, which argparse would take for an option
_NEGATIVE_VALUE = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*[^\d\s-][^\s]*$")


def _joined_negatives(argv: list) -> list:
    """``--load -30N`` as ``--load=-30N``: a negative value with a unit stays the option's value."""
    out = []
    for token in argv:
        if out and _NEGATIVE_VALUE.match(token) and out[-1].startswith("--") and "=" not in out[-1]:
            out[-1] = f"{out[-1]}={token}"
        else:
            out.append(token)
    return out


def main(argv=None) -> int:
    """Entry point of the ``microslip`` console script."""
    parser = build_parser()
    args = parser.parse_args(_joined_negatives(list(sys.argv[1:] if argv is None else argv)))
    import matplotlib

    matplotlib.use("Agg")  # the commands write figures to files; no window is ever opened
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("default")  # each distinct warning once, wherever the filters were set
            warnings.showwarning = _show_warning(args.command)
            return int(args.func(args) or 0)
    except (ValueError, TypeError, OSError, ImportError) as exc:
        print(f"microslip {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:  # the commands that can keep something (frf, modes, design) wrote it already
        said = f" ({exc})" if str(exc) else ""
        print(f"microslip {args.command}: interrupted{said}", file=sys.stderr)
        return 130


#: the commands that read an frf configuration: their warnings name its keys, not the API's arguments
_CONFIGURED = ("frf", "modes", "design", "campbell")


def _show_warning(command: str):
    """Warnings as a command's messages, ``microslip CMD: warning: ...``, without the source line; a command that
    reads a configuration names its keys (``[sweep] samples = 128``) where the message names the API's argument."""

    def show(message, category, filename, lineno, file=None, line=None):
        from ._words import in_config_words

        text = in_config_words(str(message)) if command in _CONFIGURED else str(message)
        print(f"microslip {command}: warning: {text}", file=sys.stderr)

    return show


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
