"""Argument types shared by the sub-commands (private)."""

from __future__ import annotations

import argparse

from ..common.units import parse_quantity


def quantity(kind: str, default_unit: str | None = None):
    """An argparse ``type`` that reads ``"10mm"``-style values into SI floats."""

    def convert(text):
        try:
            return parse_quantity(text, kind, name="value", default_unit=default_unit)
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None

    convert.__name__ = f"{kind} quantity"
    return convert


def quantity_list(kind: str):
    """An argparse ``type`` for comma-separated quantities, ``"3.75N,7.5N"`` -> ``[3.75, 7.5]`` (SI)."""
    one = quantity(kind)

    def convert(text):
        return [one(p) for p in str(text).split(",") if p.strip()]

    convert.__name__ = f"comma-separated {kind} quantities"
    return convert


def load_range(text):
    """An argparse ``type`` for two loads ``N_lo,N_hi`` (``"7.5N,37.5N"``) -> ``(7.5, 37.5)`` (N)."""
    loads = quantity_list("force")(text)
    if len(loads) != 2:
        raise argparse.ArgumentTypeError(f"expected two loads N_lo,N_hi such as 7.5N,37.5N, got {text!r}")
    return tuple(loads)


def add_output_folder(parser, default: str, *names: str) -> None:
    """``--out DIR`` (and any extra ``names``) for a command that writes a folder, plus ``--quiet``."""
    parser.add_argument(*names, "--out", dest="out", default=default,
                        help=f"folder to write into, created if needed (default ./{default})")
    parser.add_argument("--quiet", action="store_true", help="do not show progress on standard error")


def add_sphere_options(parser) -> None:
    """Options that describe a sphere on a plane (defaults: the paper's benchmark)."""
    g = parser.add_argument_group("sphere on a plane (defaults: the paper's benchmark)")
    g.add_argument("--radius", type=quantity("length"), default=5e-3,
                   help="sphere radius, e.g. 5mm (default 5mm: d = 10 mm)")
    g.add_argument("--E", dest="E", type=quantity("pressure"), default=200e9,
                   help="Young's modulus of both bodies, e.g. 200GPa (default 200GPa; "
                        "the paper's '200 MPa' is a typo)")
    g.add_argument("--nu", type=float, default=0.3, help="Poisson's ratio (default 0.3)")
    g.add_argument("--mu", type=float, default=0.4, help="friction coefficient (default 0.4)")


def sphere_from(args):
    from ..reference import Sphere

    return Sphere(radius=args.radius, E=args.E, nu=args.nu, mu=args.mu)
