"""A study's results on disk: one file per finished case, then the summary table and the curves' Zarr store.

``OUT/cases/<key>.npz`` holds one case's curves and, as JSON, its values,
summary row, error and time. It is written atomically when the case ends, so a
killed run loses only the cases in flight, and a rerun finds the finished ones
by their key (a hash of the base configuration and the case's values); a file
that cannot be read, or does not hold its key's case, is not trusted
(:func:`read_case` says why) and its case is solved again.
``OUT/summary.csv``, ``OUT/summary.parquet`` and ``OUT/curves.zarr`` are
rebuilt from the case files at the end of every run, each written whole to a
temporary name and renamed.
"""

from __future__ import annotations

import io
import json
import os
import shutil
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from ..common._io import atomic_write
from ..common._optional import require
from ..common.units import unit_factor
from .solve import CURVES
from .spec import Case, Study

CASES = "cases"


def case_file(out: Path, case: Case) -> Path:
    """Where a case's results are kept."""
    return Path(out) / CASES / f"{case.key}.npz"


def save_case(out: Path, case: Case, outcome: dict) -> dict:
    """Write a case's outcome (from :func:`~microslip.study.solve.solve_case`) atomically; returns it as stored.

    The record returned is what :func:`load_case` reads back from the file.
    """
    meta = {"key": case.key, "values": case.values, "mistuning_sample": case.mistuning_sample,
            "row": outcome["row"], "error": outcome["error"], "warnings": outcome["warnings"],
            "time": outcome["time"]}
    curves = {k: np.asarray(v) for k, v in outcome["curves"].items()}
    buf = io.BytesIO()
    np.savez(buf, meta=np.array(json.dumps(meta, default=str)), **{f"curve_{k}": v for k, v in curves.items()})
    atomic_write(case_file(out, case), buf.getvalue())
    return {**json.loads(json.dumps(meta, default=str)), "curves": curves}


def load_case(out: Path, case: Case) -> dict | None:
    """A finished case's outcome, or None when it has not finished (or its file is not trusted: :func:`read_case`)."""
    return read_case(out, case)[0]


def read_case(out: Path, case: Case, solve: str | None = None, dofs: int | None = None) -> tuple[dict | None, str]:
    """A case's stored outcome, and why its file cannot be trusted when it cannot.

    Parameters
    ----------
    out : Path
        The results folder.
    case : Case
        The case (its key names the file).
    solve : {"frf", "modes"}, optional
        The study's solve: a solved case must then hold its curves
        (:data:`~microslip.study.solve.CURVES`).
    dofs : int, optional
        The output DOFs: the columns of its amplitude curve.

    Returns
    -------
    record : dict or None
        What :func:`save_case` wrote; None when there is no file or it cannot
        be trusted.
    problem : str
        Empty, or what is wrong with the file (truncated, emptied, damaged,
        metadata missing or of the wrong type, values not those of its key):
        its case is to be solved again.
    """
    path = case_file(out, case)
    if not path.exists() and not path.is_symlink():
        return None, ""
    if not path.is_file():
        return None, "is not a file"
    if path.stat().st_size == 0:
        return None, "is empty"
    try:
        with open(path, "rb") as fh:
            if fh.read(4) != b"PK\x03\x04":
                return None, "is not a NumPy .npz archive"
            fh.seek(0)
            with np.load(fh, allow_pickle=False) as f:
                meta = f["meta"]
                curves = {k[6:]: np.array(f[k]) for k in f.files if k.startswith("curve_")}
    except zipfile.BadZipFile as exc:
        return None, f"is damaged or truncated ({exc})"
    except Exception as exc:  # noqa: BLE001 - whatever stops the file being read, the case is solved again
        return None, f"cannot be read ({type(exc).__name__}: {exc})"
    if meta.dtype.kind != "U" or meta.ndim != 0:
        return None, f"holds no metadata text (its 'meta' is an array of {meta.dtype} and shape {meta.shape})"
    try:
        meta = json.loads(str(meta))
    except ValueError as exc:
        return None, f"holds metadata that is not JSON ({exc})"
    problem = _meta_problem(meta, case) or _curves_problem(curves, meta, solve, dofs)
    if problem:
        return None, problem
    meta["curves"] = curves
    return meta, ""


#: the metadata of a case file: each key and the JSON types its value may have
_META = {"key": (str,), "values": (dict,), "mistuning_sample": (int, type(None)), "row": (dict,), "error": (str,),
         "warnings": (str,), "time": (int, float)}


def _meta_problem(meta, case: Case) -> str:
    """What makes a case file's metadata unfit for ``case``, or ''."""
    if not isinstance(meta, dict):
        return f"holds metadata that is a JSON {type(meta).__name__}, not an object"
    for name, types in _META.items():
        if name not in meta:
            return f"has metadata without {name!r}"
        if not isinstance(meta[name], types) or (isinstance(meta[name], bool) and bool not in types):
            return f"has metadata whose {name!r} is {meta[name]!r}"
    if meta["key"] != case.key:
        return f"holds case {meta['key']!r}, not {case.key!r}"
    values = json.loads(json.dumps(case.values, default=str))
    if meta["values"] != values or meta["mistuning_sample"] != case.mistuning_sample:
        def show(v, sample):
            return json.dumps(v) + ("" if sample is None else f", mistuned disk {sample}")

        return (f"holds the values {show(meta['values'], meta['mistuning_sample'])}, not those of its key "
                f"{show(values, case.mistuning_sample)}: not trusted")
    bad = next((k for k, v in meta["row"].items() if not isinstance(v, (int, float, type(None)))), None)
    if bad is not None:
        return f"has a summary value {bad!r} that is not a number: {meta['row'][bad]!r}"
    if not meta["error"] and not isinstance(meta["row"].get("complete"), bool):
        return "has a solved case's summary without 'complete'"
    return ""


def _curves_problem(curves: dict, meta: dict, solve: str | None, dofs: int | None) -> str:
    """What makes a solved case's curves unfit for a study solving ``solve`` with ``dofs`` output DOFs, or ''."""
    if meta["error"] or solve is None:
        return ""
    specs = CURVES[solve]
    if set(curves) != set(specs):
        return f"holds the curves {sorted(curves)}, not {sorted(specs)}"
    length = curves[next(iter(specs))].shape[:1]
    for name, (dims, _, _) in specs.items():
        c = curves[name]
        shape = length + (() if not dims else (dofs,) if dofs is not None else c.shape[1:2])
        if c.dtype.kind not in "biuf" or c.shape != shape:
            return f"holds a curve {name!r} of {c.dtype} and shape {c.shape}, not numbers of shape {shape}"
    return ""


def parameter_value(value):
    """A varied value as the summary shows it: a number in SI units when it is one (``"25N"`` -> 25.0), else text."""
    if isinstance(value, bool):
        return value
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        from .spec import _WITH_UNIT

        m = _WITH_UNIT.match(value)
        if m is not None:
            try:
                return float(m.group(1)) * unit_factor((m.group(2) or "").strip())
            except ValueError:
                pass
        return value
    return json.dumps(value)


def summary_rows(study: Study, cases: list[Case], outcomes: list[dict | None]) -> list[dict]:
    """One row per case: its key, each varied key path's value, the results, then complete, time and error."""
    params = study.parameters
    peaks = _tuned_peaks(study, cases, outcomes) if study.mistuning is not None else {}
    rows = []
    for case, o in zip(cases, outcomes):
        row = {"case": case.key}
        row.update({p: parameter_value(case.values[p]) if p in case.values else None for p in params})
        if study.mistuning is not None:
            row["mistuned disk"] = -1 if case.mistuning_sample is None else case.mistuning_sample
        if o is None:
            row.update({"complete": False, "time (s)": None, "error": "not run", "warnings": ""})
            rows.append(row)
            continue
        result = dict(o["row"])
        complete = bool(result.pop("complete", False)) and not o["error"]
        row.update(result)
        if study.mistuning is not None:
            tuned = peaks.get(_group(case))
            for name in [k[5:-4] for k in result if k.startswith("peak ") and k.endswith(" (m)")]:
                ok = tuned is not None and tuned.get(name) and f"peak {name} (m)" in result
                row[f"amplification {name}"] = result[f"peak {name} (m)"] / tuned[name] if ok else None
        row.update({"complete": complete, "time (s)": o["time"], "error": o["error"], "warnings": o["warnings"]})
        rows.append(row)
    return rows


def _group(case: Case) -> str:
    return json.dumps(case.values, sort_keys=True, default=str)


def _tuned_peaks(study, cases, outcomes) -> dict:
    """The tuned sector's peak of each output DOF, by the values of the other parameters."""
    out = {}
    for case, o in zip(cases, outcomes):
        if case.mistuning_sample is None and o is not None and not o["error"]:
            out[_group(case)] = {k[5:-4]: v for k, v in o["row"].items() if k.startswith("peak ") and k.endswith(" (m)")}
    return out


def write_summary(out: Path, rows: list[dict]) -> tuple[Path, Path]:
    """``summary.csv`` and ``summary.parquet`` (the same table), each written atomically."""
    pd = require("pandas", "the study's summary table", "sweep")
    require("pyarrow", "the study's Parquet summary", "sweep")
    table = pd.DataFrame(rows)
    csv = atomic_write(Path(out) / "summary.csv", table.to_csv(index=False))
    buf = io.BytesIO()
    table.to_parquet(buf, index=False)
    return csv, atomic_write(Path(out) / "summary.parquet", buf.getvalue())


def write_curves(out: Path, study: Study, cases: list[Case], outcomes: list[dict | None], dof_names: list[str]) -> Path:
    """Every case's curve in ``OUT/curves.zarr`` through xarray (dims ``case``, ``point``; ``dof`` for amplitudes).

    Curves shorter than the longest are padded with NaN; ``points`` gives each
    case's length. Written to a temporary folder and renamed over the old store.
    """
    xr = require("xarray", "the study's curves", "sweep")
    require("zarr", "the study's curves", "sweep")
    specs = CURVES[study.solve]
    length = max([o["curves"][next(iter(specs))].size for o in outcomes if o and o["curves"]] or [0])
    n = len(cases)
    data = {}
    for name, (dims, unit, description) in specs.items():
        shape = (n, length) + ((len(dof_names),) if dims else ())
        values = np.full(shape, np.nan)
        for i, o in enumerate(outcomes):
            if o and name in o["curves"]:
                c = np.asarray(o["curves"][name], float)
                values[i, :c.shape[0]] = c
        data[name] = (("case", "point") + dims, values, {"units": unit, "long_name": description})
    points = [o["curves"][next(iter(specs))].size if o and o["curves"] else 0 for o in outcomes]
    coords = {"case": [c.key for c in cases], "dof": list(dof_names), "points": ("case", np.array(points))}
    for p in study.parameters:
        values = [parameter_value(c.values[p]) if p in c.values else None for c in cases]
        numeric = all(isinstance(v, float) for v in values)
        coords[p] = ("case", np.array(values, dtype=float if numeric else str))
    if study.mistuning is not None:
        coords["mistuned_disk"] = ("case", np.array([-1 if c.mistuning_sample is None else c.mistuning_sample
                                                     for c in cases]))
    ds = xr.Dataset(data, coords=coords, attrs={"title": study.title, "solve": study.solve,
                                                "base": str(study.base.name)})
    target = Path(out) / "curves.zarr"
    tmp = Path(tempfile.mkdtemp(prefix=".curves.", suffix=".tmp", dir=out))
    try:
        ds.to_zarr(tmp / "store.zarr", mode="w", consolidated=True, zarr_format=2)
        _replace_folder(tmp / "store.zarr", target)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return target


def _replace_folder(new: Path, target: Path) -> None:
    """Put the folder ``new`` at ``target``: the old one is moved aside first and removed after."""
    old = None
    if target.exists():
        old = target.with_name(f".{target.name}.old.{os.getpid()}")
        os.replace(target, old)
    os.replace(new, target)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
