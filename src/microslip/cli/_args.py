"""Argument types shared by the sub-commands (private).

Every value is checked when the command line is read, before any work: a
quantity's unit and sign, a fraction, the folder of an output file, an
output folder, an image format. A bad value exits with status 2 and a
message naming the option (argparse's ``argument -o/--output: ...``).
"""

from __future__ import annotations

import argparse
import math
import os
import re
from pathlib import Path

from ..common.units import parse_fraction, parse_quantity

#: a value that starts like a negative number (``-30N``, ``-2.5um``, ``-.5``, ``-7.5N,37.5N``): no option does
_NEGATIVE = re.compile(r"^-\.?\d")


class Parser(argparse.ArgumentParser):
    """The parser of every command: no abbreviated options, and ``-30N`` read as a value, not an option.

    argparse takes only plain numbers (``-30``) for negative values; a value
    with a unit (``--load -30N``) would be read as an unknown option. Here it
    reaches the option's type, which accepts it where a negative value makes
    sense and refuses it by name where not. Abbreviations are off so that
    ``--out`` (a folder) is never taken as the prefix of ``--output`` (a file).
    """

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE


def quantity(kind: str, default_unit: str | None = None, *, sign: str | None = None):
    """An argparse ``type`` that reads ``"10mm"``-style values into SI floats.

    ``sign='positive'`` or ``'non-negative'`` refuses other values, naming
    the value and its unit; ``None`` accepts any sign (e.g. an approach).
    """

    def convert(text):
        try:
            value = parse_quantity(text, kind, name="value", default_unit=default_unit)
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
        bad = {"positive": not value > 0, "non-negative": not value >= 0}.get(sign, False)
        if bad or not math.isfinite(value):
            what = f"a {sign} {kind}" if sign else f"a finite {kind}"
            raise argparse.ArgumentTypeError(f"must be {what}, got {text!r}")
        return value

    convert.__name__ = f"{kind} quantity"
    return convert


def quantity_list(kind: str, *, sign: str | None = None):
    """An argparse ``type`` for comma-separated quantities, ``"3.75N,7.5N"`` -> ``[3.75, 7.5]`` (SI)."""
    one = quantity(kind, sign=sign)

    def convert(text):
        return [one(p) for p in str(text).split(",") if p.strip()]

    convert.__name__ = f"comma-separated {kind} quantities"
    return convert


def load_range(text):
    """An argparse ``type`` for two loads ``N_lo,N_hi`` (``"7.5N,37.5N"``) -> ``(7.5, 37.5)`` (N)."""
    loads = quantity_list("force", sign="positive")(text)
    if len(loads) != 2:
        raise argparse.ArgumentTypeError(f"expected two loads N_lo,N_hi such as 7.5N,37.5N, got {text!r}")
    if not loads[0] < loads[1]:
        raise argparse.ArgumentTypeError(f"expected N_lo < N_hi such as 7.5N,37.5N, got {text!r}")
    return tuple(loads)


def fraction(text):
    """An argparse ``type`` for a fraction in ``(0, 1]``: ``0.02`` and ``2%`` both mean 2 %; ``2`` is refused."""
    try:
        value = parse_fraction(text, name="value")
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    if not 0 < value <= 1:
        raise argparse.ArgumentTypeError(f"must be a fraction in (0, 1] such as 0.02 or 2%, got {text!r}")
    return value


def positive_int(text):
    """An argparse ``type`` for an integer >= 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number such as 4, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}")
    return value


def degrees(text):
    """An argparse ``type`` for an angle in degrees: any finite number (``30``, ``-45``, ``90.5``)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an angle in degrees such as 30, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite angle in degrees, got {text!r}")
    return value


def _writable_folder(folder: Path, text: str, what: str) -> None:
    """Refuse a folder that is a file or cannot be written into (``what`` says what lives there)."""
    if not folder.is_dir():
        raise argparse.ArgumentTypeError(f"{text!r}: {str(folder)!r} is a file, not a folder")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise argparse.ArgumentTypeError(f"{text!r}: cannot write {what} into the folder {str(folder)!r} "
                                         "(permission denied)")


def output_file(example: str):
    """An argparse ``type`` for a file to write: not a folder, in an existing folder one can write into.

    ``example`` is a file name to suggest when a folder is given.
    """

    def convert(text):
        path = Path(text)
        if not str(text).strip():
            raise argparse.ArgumentTypeError(f"expected a file name such as {example}, got {text!r}")
        if path.is_dir():
            raise argparse.ArgumentTypeError(f"{text!r} is a folder; give a file to write, e.g. "
                                             f"{str(path / example)!r}")
        folder = path.parent
        if not folder.exists():
            raise argparse.ArgumentTypeError(f"{text!r}: the folder {str(folder)!r} does not exist; create it "
                                             "first (files are written only into existing folders)")
        _writable_folder(folder, text, "the file")
        return str(text)

    convert.__name__ = "output file"
    return convert


def output_folder(text):
    """An argparse ``type`` for a folder to write into: created if needed, so it or its first existing parent
    must be a folder one can write into."""
    path = Path(text)
    if not str(text).strip():
        raise argparse.ArgumentTypeError(f"expected a folder name, got {text!r}")
    if path.exists() and not path.is_dir():
        raise argparse.ArgumentTypeError(f"{text!r} is a file, not a folder")
    existing = path.absolute()
    while not existing.exists():
        existing = existing.parent
    _writable_folder(existing, text, "the results")
    return str(text)


def image_file(text):
    """An argparse ``type`` for an image to write: an output file whose extension Matplotlib can save."""
    from matplotlib.backend_bases import FigureCanvasBase

    name = output_file("plot.png")(text)
    formats = FigureCanvasBase.get_supported_filetypes()
    suffix = Path(name).suffix.lstrip(".").lower()
    if suffix not in formats:
        raise argparse.ArgumentTypeError(f"{text!r}: cannot write an image of type {suffix or '(no extension)'!r}; "
                                         f"use one of {', '.join('.' + s for s in sorted(formats))}")
    return name


def checked(option: str, convert, value):
    """``convert(value)`` for a value not read by argparse (a default filled in later); errors name ``option``."""
    try:
        return convert(value)
    except argparse.ArgumentTypeError as exc:
        raise ValueError(f"{option}: {exc}") from None


def percent(fraction: float) -> float:
    """A fraction printed as a percentage with three significant digits (``0.005520259824970775`` -> ``0.552``)."""
    return float(f"{100 * fraction:.3g}")


def add_output_folder(parser, default: str, *names: str) -> None:
    """``--out DIR`` (and any extra ``names``) for a command that writes a folder, plus ``--quiet``."""
    parser.add_argument(*names, "--out", dest="out", default=default, type=output_folder,
                        help=f"folder to write into, created if needed (default ./{default})")
    parser.add_argument("--quiet", action="store_true", help="do not show progress on standard error")


def add_sphere_options(parser, *, defaults: bool = True) -> None:
    """Options that describe a sphere on a plane (defaults: the paper's benchmark).

    With ``defaults=False`` they default to None, for a command that takes
    them from elsewhere (the model file's provenance) unless they are given.
    """
    g = parser.add_argument_group("sphere on a plane (defaults: the paper's benchmark)" if defaults else
                                  "sphere on a plane (defaults: the sphere the model was tuned on, from its file; "
                                  "for a model that records none, the paper's benchmark below)")
    pick = (lambda value: value) if defaults else (lambda value: None)
    g.add_argument("--radius", type=quantity("length", sign="positive"), default=pick(5e-3),
                   help="sphere radius, e.g. 5mm (default 5mm: d = 10 mm)")
    g.add_argument("--E", dest="E", type=quantity("pressure", sign="positive"), default=pick(200e9),
                   help="Young's modulus of both bodies, e.g. 200GPa (default 200GPa; "
                        "the paper's '200 MPa' is a typo)")
    g.add_argument("--nu", type=float, default=pick(0.3), help="Poisson's ratio (default 0.3)")
    g.add_argument("--mu", type=float, default=pick(0.4), help="friction coefficient (default 0.4)")


def sphere_from(args):
    from ..reference import Sphere

    return Sphere(radius=args.radius, E=args.E, nu=args.nu, mu=args.mu)


def poisson_ratio(text):
    """An argparse ``type`` for a Poisson's ratio in ``(-1, 0.5]`` (``0.3``)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a Poisson's ratio such as 0.3, got {text!r}") from None
    if not -1.0 < value <= 0.5:
        raise argparse.ArgumentTypeError(f"must be a Poisson's ratio in (-1, 0.5] such as 0.3, got {text!r}")
    return value


def add_second_body_options(parser) -> None:
    """``--E2``, ``--nu2``: the second body (the plane, the flat) when it is of another material (both or neither)."""
    g = parser.add_argument_group("second body of another material (both or neither; default: the same material "
                                  "as the first, --E and --nu)")
    g.add_argument("--E2", dest="E2", type=quantity("pressure", sign="positive"), default=None,
                   help="Young's modulus of the second body (the plane or flat the reference presses on), "
                        "e.g. 210GPa; give --nu2 with it")
    g.add_argument("--nu2", dest="nu2", type=poisson_ratio, default=None,
                   help="Poisson's ratio of the second body, in (-1, 0.5], e.g. 0.29; give --E2 with it")


def second_body_from(args) -> dict:
    """``{"E2": ..., "nu2": ...}`` of the command line (empty for identical bodies); one without the other is
    refused naming the missing option."""
    if args.E2 is None and args.nu2 is None:
        return {}
    if args.nu2 is None:
        raise ValueError("--E2 needs --nu2: give the second body's Poisson's ratio too (e.g. --nu2 0.3)")
    if args.E2 is None:
        raise ValueError("--nu2 needs --E2: give the second body's Young's modulus too (e.g. --E2 210GPa)")
    return {"E2": args.E2, "nu2": args.nu2}
