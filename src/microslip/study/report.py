"""A design study's plots and HTML report: results against each varied parameter, curves overlaid, mistuning."""

from __future__ import annotations

import json

import numpy as np

#: response curves drawn in one overlay at most (the rest are in the Zarr store)
MAX_CURVES = 60
#: summary rows printed in the report's table at most (the whole table is summary.csv)
MAX_ROWS = 40


def _values(result, parameter: str) -> tuple[np.ndarray, list | None]:
    """A parameter's value per case as numbers; for text values their order of appearance and the labels."""
    from .store import parameter_value

    raw = [parameter_value(c.values[parameter]) if parameter in c.values else None for c in result.cases]
    if all(isinstance(v, float) for v in raw):
        return np.array(raw), None
    labels = list(dict.fromkeys(str(v) for v in raw))
    return np.array([labels.index(str(v)) for v in raw], dtype=float), labels


def plot_against(result, parameter: str, dof=None, ax=None):
    """The study's main result against ``parameter``, one line per combination of the other parameters."""
    import matplotlib.pyplot as plt

    if parameter not in result.study.parameters:
        raise ValueError(f"parameter: the study does not vary {parameter!r} (it varies "
                         f"{', '.join(result.study.parameters)})")
    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 4.2))
    y, label, scale = result.measure(dof)
    x, labels = _values(result, parameter)
    tuned = np.array([c.mistuning_sample is None for c in result.cases])
    others = [p for p in result.study.parameters if p != parameter]
    groups: dict = {}
    for i, c in enumerate(result.cases):
        if tuned[i]:
            key = json.dumps({p: c.values.get(p) for p in others}, default=str)
            groups.setdefault(key, []).append(i)
    for key, idx in groups.items():
        idx = np.array(idx)[np.argsort(x[idx], kind="stable")]
        name = ", ".join(f"{p} = {v}" for p, v in json.loads(key).items() if v is not None)
        if result.study.mistuning is not None:
            name = ("tuned disk, " + name) if name else "tuned disk"
        ax.plot(x[idx], y[idx] * scale, "o-", ms=4, label=name or None)
    if result.study.mistuning is not None:
        ax.plot(x[~tuned], y[~tuned] * scale, ".", color="0.45", ms=4, label="mistuned disks: largest blade")
    if labels is not None:
        ax.set_xticks(range(len(labels)), labels, rotation=20, ha="right", fontsize=8)
    elif np.nanmin(x) > 0 and np.nanmax(x) / np.nanmin(x) > 20:
        ax.set_xscale("log")
    ax.set_xlabel(parameter + ("" if labels is not None else " (SI units)"))
    ax.set_ylabel(label)
    ax.grid(True, alpha=0.3)
    if 1 < len(groups) <= 10 or result.study.mistuning is not None:
        ax.legend(fontsize=7)
    return ax


def _design_curve(parameter: str) -> bool:
    return parameter.startswith("damper.") and parameter.endswith(("centrifugal_load", "speed"))


def plot_curves(result, dof=None, ax=None):
    """Every case's response curve (or each mode's damping curve) overlaid."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 4.2))
    j = 0 if dof is None else result.dof_names.index(dof)
    shown = [i for i, o in enumerate(result.outcomes) if o and o["curves"]][:MAX_CURVES]
    for i in shown:
        c = result.outcomes[i]["curves"]
        if result.study.solve == "frf":
            ax.plot(c["omega"] / (2 * np.pi), c["amplitude"][:, j] * 1e6, lw=0.9)
        else:
            ax.semilogx(c["modal_amplitude"], c["damping_ratio"] * 100, lw=0.9)
    if result.study.solve == "frf":
        ax.set_xlabel("excitation frequency f (Hz)")
        ax.set_ylabel(f"amplitude of {result.dof_names[j]} (µm)")
    else:
        ax.set_xlabel("modal amplitude (kg^1/2 m)")
        ax.set_ylabel("modal damping ratio (%)")
    ax.grid(True, alpha=0.3)
    return ax


def plot_amplification(result, dof=None, ax=None):
    """The mistuned disks' amplification factors: their distribution, with Whitehead's limit."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 4.2))
    af = result.amplification(dof)
    af = af[np.isfinite(af)]
    ax.hist(af, bins=max(5, min(30, af.size // 3)), color="C0", alpha=0.8)
    n = result.study.configuration(result.cases[0]).structure.sectors
    ax.axvline((1 + np.sqrt(n)) / 2, color="C3", ls="--", label=f"Whitehead's limit (1 + √N)/2, N = {n}")
    ax.axvline(1.0, color="k", lw=0.8)
    ax.set_xlabel(f"amplification factor of {dof or result.dof_names[0]} (largest blade / tuned)")
    ax.set_ylabel("mistuned disks")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    return ax


def write_report(result) -> None:
    """``report.html`` and ``report.md`` in the results folder, with their figures."""
    import matplotlib.pyplot as plt

    from ..common.report import Report, plural

    study, out = result.study, result.out
    report = Report(f"microslip sweep: {study.title}", parameters={
        "study": str(study.path), "base configuration": str(study.base), "solve": study.solve,
        "cases": len(result.cases), "solved by this run": result.computed, "output": str(out)})
    failed = result.failed
    report.text(f"{plural(len(result.cases), 'case')} of `{study.base.name}` "
                f"({'forced responses' if study.solve == 'frf' else 'nonlinear modes'}), varying "
                f"{', '.join(f'`{p}`' for p in study.parameters) or 'the blades stiffness only'}"
                + (f", with {plural(study.mistuning.samples, 'mistuned disk')} per combination (blade stiffness "
                   f"scatter {study.mistuning.std:.3g}, seed {study.mistuning.seed})" if study.mistuning else "")
                + f". {len(result.cases) - len(failed)} solved, {len(failed)} failed; "
                  f"{result.computed} solved in this run ({result.elapsed:.1f} s). Every case's values and results: "
                  f"`summary.csv` (and `summary.parquet`); every curve: `curves.zarr` "
                  f"(`xarray.open_zarr`).")
    if len(failed) == len(result.cases):
        report.text("**Every case failed**: there is no result to plot. Each case's error is in the table below "
                    "and in the column `error` of `summary.csv`.")
        report.table(["case", "values", "error"], [[c.key, c.label, e] for c, e in failed], caption="Failed cases")
        report.write(out)
        return
    for parameter in study.parameters:
        for dof in result.dof_names[:3] if study.solve == "frf" else result.dof_names[:1]:
            fig, ax = plt.subplots(figsize=(6.5, 4.2))
            plot_against(result, parameter, dof, ax=ax)
            what = "Damper design curve: the" if _design_curve(parameter) else "The"
            measure = f"peak response of {dof}" if study.solve == "frf" else "largest modal damping ratio"
            report.figure(fig, _file_name(f"against {parameter} {dof}"), f"{what} {measure} against `{parameter}`"
                          f"{', one line per combination of the other parameters' if len(study.parameters) > 1 else ''}.",
                          out)
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    plot_curves(result, ax=ax)
    shown = min(MAX_CURVES, len(result.cases) - len(failed))
    report.figure(fig, "curves", ("Response curves" if study.solve == "frf" else "Damping curves")
                  + f" of {shown} case{'s' if shown != 1 else ''}, overlaid.", out)
    if study.mistuning is not None:
        af = result.amplification()
        finite = af[np.isfinite(af)]
        if finite.size:
            fig, ax = plt.subplots(figsize=(6.5, 4.2))
            plot_amplification(result, ax=ax)
            report.figure(fig, "amplification", "Distribution of the amplification factor: the largest blade "
                          "amplitude of each mistuned disk over the tuned disk's peak.", out)
            report.text(f"Amplification factor of {result.dof_names[0]} over {finite.size} mistuned disks: mean "
                        f"{finite.mean():.4g}, 95th percentile {np.percentile(finite, 95):.4g}, largest "
                        f"{finite.max():.4g}.")
    columns = _report_columns(result)
    report.table(columns, [[_cell(r.get(c)) for c in columns] for r in result.rows[:MAX_ROWS]],
                 caption="Summary" + (f" (first {MAX_ROWS} of {len(result.rows)} cases; all in summary.csv)"
                                      if len(result.rows) > MAX_ROWS else ""))
    if failed:
        report.table(["case", "values", "error"], [[c.key, c.label, e] for c, e in failed],
                     caption="Failed cases")
    report.write(out)


def _report_columns(result) -> list:
    keys = list(dict.fromkeys(k for r in result.rows for k in r))
    skip = ("static ", "warnings", "case")
    return [k for k in keys if not k.startswith(skip)][:12]


def _cell(value) -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.5g}"
    return str(value)


def _file_name(text: str) -> str:
    return "".join(ch if ch.isalnum() else "_" for ch in text).strip("_")
