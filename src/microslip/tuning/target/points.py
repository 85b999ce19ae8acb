"""The optimised tuning points stored with the package (paper's sphere, 7.5-37.5 N) and their problem."""

from __future__ import annotations

import json
from importlib import resources

import numpy as np

from .problem import TargetProblem, _load_range

_DATA = "optimal_points.json"


def load_optimal_points() -> dict:
    """The optimised points stored with the package (paper's sphere, load range 7.5-37.5 N).

    Returns
    -------
    dict
        ``{"problem": {...}, "fractions": {J: ndarray}}``; the fractions are of
        ``t_gs(N_hi)``. Written by ``microslip target --sweep --save-points``.
    """
    text = resources.files("microslip").joinpath("data", _DATA).read_text(encoding="utf-8")
    data = json.loads(text)
    data["fractions"] = {int(k): np.asarray(v, dtype=float) for k, v in data["fractions"].items()}
    return data


def stored_mismatch(reference, load_range, *, min_amplitude=0.5, energy_target=0.02, force_target=0.02,
                    data=None) -> str | None:
    """Why the stored optimised points do not solve a problem, or None when they do.

    The points solve the problem they were optimised on: the same reference
    (type, ``radius`` (m), ``E`` (Pa), ``nu``, ``mu``), load range (N) and
    ``min_amplitude``, and the same ratio ``energy_target / force_target``
    (the minimax objective is unchanged when both targets scale together).

    Parameters
    ----------
    reference : Sphere or similar
    load_range : (float, float)
        ``(N_lo, N_hi)`` (N).
    min_amplitude, energy_target, force_target : float
        As in :class:`TargetProblem`.
    data : dict, optional
        A record as :func:`load_optimal_points` returns (default: the stored one).

    Returns
    -------
    str or None
        The first difference, in words, or None.
    """
    p = (data or load_optimal_points())["problem"]
    lo, hi = _load_range(load_range)
    name = type(reference).__name__
    if name != p["reference"]:
        return f"they are for a {p['reference']}, not a {name}"
    for key, unit in (("radius", "m"), ("E", "Pa"), ("nu", ""), ("mu", "")):
        mine = getattr(reference, key, None)
        if mine is None or p[key] is None or not np.isclose(float(mine), p[key], rtol=1e-9, atol=0.0):
            return f"they are for {key} = {p[key]:g}{unit and ' ' + unit}, not {mine}{unit and ' ' + unit}"
    if not np.allclose([lo, hi], p["load_range"], rtol=1e-9, atol=0.0):
        return f"they are for the load range {p['load_range'][0]:g}-{p['load_range'][1]:g} N, not {lo:g}-{hi:g} N"
    if not np.isclose(min_amplitude, p["min_amplitude"], rtol=1e-9, atol=0.0):
        return f"they are for min_amplitude {p['min_amplitude']:g}, not {min_amplitude:g}"
    if not np.isclose(energy_target / force_target, p["energy_target"] / p["force_target"], rtol=1e-9, atol=0.0):
        return (f"they are for energy_target / force_target = {p['energy_target'] / p['force_target']:g}, "
                f"not {energy_target / force_target:g}")
    return None


def stored_fractions(reference, load_range, **problem) -> dict | None:
    """The stored optimised points ``{J: fractions of t_gs(N_hi)}`` when they solve this problem, else None.

    Parameters are those of :func:`stored_mismatch`.
    """
    data = load_optimal_points()
    return None if stored_mismatch(reference, load_range, data=data, **problem) else data["fractions"]
