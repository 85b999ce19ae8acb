"""The record a tuning leaves in its model: the reference, the load, the points, where mu came from (private)."""

from __future__ import annotations

import dataclasses
import numbers

from ..model import Provenance

#: a second body's material, left out when it is the first body's (None)
_SAME_AS_FIRST = ("E2", "nu2")
_DEPTH = 3  # references built on references (loops on a cylinder, MDR on a profile): enough levels to name them


def describe_reference(reference, depth: int = 0) -> dict:
    """``{"kind": class name, parameter: value}`` of a reference contact, in SI units.

    The public scalar fields of a dataclass (numbers, text, ``None``) are
    kept, nested references described in turn, a ``notes`` dict keeps its
    numbers and text; arrays are left out (the model file keeps the points,
    not the data). Anything else records its class name and ``mu``.
    """
    out = {"kind": type(reference).__name__}
    if not dataclasses.is_dataclass(reference) or isinstance(reference, type):
        mu = getattr(reference, "mu", None)
        return out if mu is None else {**out, "mu": float(mu)}
    for f in dataclasses.fields(reference):
        if f.name.startswith("_"):
            continue
        value = getattr(reference, f.name)
        if value is None and f.name in _SAME_AS_FIRST:  # identical bodies: nothing to record
            continue
        if value is None or isinstance(value, (str, bool)):
            out[f.name] = value
        elif isinstance(value, numbers.Real):
            out[f.name] = float(value)
        elif dataclasses.is_dataclass(value) and depth < _DEPTH:
            out[f.name] = describe_reference(value, depth + 1)
        elif isinstance(value, dict):
            kept = {str(k): (float(v) if isinstance(v, numbers.Real) and not isinstance(v, bool) else v)
                    for k, v in value.items() if isinstance(v, (str, bool, numbers.Real))}
            if kept:
                out[f.name] = kept
    return out


def record(reference, points) -> Provenance:
    """The :class:`~microslip.model.Provenance` of a model tuned on ``reference`` at ``points`` (TuningPoints)."""
    notes = getattr(reference, "notes", None)
    mu_source = notes.get("mu_source") if isinstance(notes, dict) else None
    return Provenance(reference=describe_reference(reference), normal_load=points.normal_load,
                      approach=points.approach, points_t=points.t, points_T=points.T,
                      mu_source=mu_source or "given with the reference")
