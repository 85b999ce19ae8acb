"""Accuracy of a contact model against an exact reference model on a family of load paths.

:func:`accuracy` runs a model and a reference model (normally the exact
continuous contact, :func:`microslip.mdr`) along the same paths and measures,
over each path's steady cycle,

``energy_error``
    ``W / W_ref - 1``, with ``W`` the energy dissipated over the steady
    part: on a periodic path ``W = ∮ T dt`` per cycle by the trapezoidal
    rule (over a closed cycle the normal work ``∮ N dn`` vanishes, ``N``
    being a function of ``n``); on an open path, where ``∫ T dt`` would
    also count the elastic energy stored, the friction work of its steps
    (``Response.friction_work``);
``peak_error``
    ``max|T| / max|T_ref| - 1``;
``force_difference``
    ``max|T - T_ref| / max|T_ref|``, the largest force difference over the
    cycle relative to the reference's peak;
``normal_difference``
    ``mean(N - N_ref) / mean(N_ref)``, the mean normal-force difference
    relative to the reference's mean normal force.

All are fractions (the report shows them in %).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..common import _checks
from ..common._io import write_csv
from ..common._progress import Progress
from ..common.report import plural
from .paths import Path
from ..reference.mdr import LoadLimitError

#: the metrics and their labels (no '|', which would break Markdown tables)
METRICS = {
    "energy_error": "energy per cycle: W/W_ref - 1",
    "peak_error": "peak force: max abs T / max abs T_ref - 1",
    "force_difference": "force: max abs(T - T_ref) / max abs T_ref",
    "normal_difference": "normal force: mean(N - N_ref) / mean N_ref",
}

#: reference dissipation below this fraction of the elastic work scale counts as none (round-off is ~1e-15)
SHAKEDOWN_RTOL = 1e-9

#: parameter columns of the default family, in table order
PARAMS = ("ratio", "phase_deg", "level", "amplitude", "N_m", "N_a", "phase", "t_a")


def restriction_mask(paths, min_load: float = 0.0, min_amplitude: float = 0.0) -> np.ndarray:
    """Which paths have their lowest load and their amplitude factor at least the given ones.

    Parameters
    ----------
    paths : sequence of Path, length P
        Paths with the default family's ``params`` (``N_m``, ``N_a`` in N,
        ``amplitude``); a path lacking them is not kept.
    min_load : float, default 0
        Smallest lowest load ``N_m - N_a`` kept (N).
    min_amplitude : float, default 0
        Smallest amplitude factor kept (multiple of the gross-slip
        displacement at the path's lowest load).

    Returns
    -------
    ndarray of bool, shape (P,)
        Both bounds met, with a relative tolerance of 1e-12 (round-off of the
        loads computed from the levels).
    """
    paths = _check_paths(paths)
    lo = _checks.positive_scalar("min_load", min_load, allow_zero=True)
    amin = _checks.positive_scalar("min_amplitude", min_amplitude, allow_zero=True)
    get = lambda name: np.array([float(p.params.get(name, np.nan)) for p in paths])  # noqa: E731
    with np.errstate(invalid="ignore"):
        return (get("N_m") - get("N_a") >= lo * (1 - 1e-12)) & (get("amplitude") >= amin * (1 - 1e-12))


class PathBatch:
    """Paths laid end to end for one kernel call, with the weights that turn forces into metrics.

    The paths are concatenated with one separator sample between them at
    ``t = 0`` and an approach below every gap: every element opens there, and
    an open element's slider sits at the current ``t``, so the state after
    the separator is exactly the virgin state (every slider at 0) and each
    path runs as if alone.

    Parameters
    ----------
    paths : Path or sequence of Path
        The histories (m).
    """

    def __init__(self, paths):
        self.paths = _check_paths(paths)
        sizes = np.array([len(p) for p in self.paths])
        self.starts = np.concatenate([[0], np.cumsum(sizes + 1)[:-1]])  # first sample of each path
        self.t = np.concatenate([np.append(p.t, 0.0) for p in self.paths])
        self._n = np.concatenate([np.append(p.n, 0.0) for p in self.paths])
        self._sep = self.starts + sizes  # separator samples
        # the steady samples, gathered: index into the batch, first of each path, and the weights of
        # the energy: trapezoid weights on T for a periodic path, ones on the friction work of the steps
        # (but the one ending at its first steady sample) for an open one
        index, weight, work, first = [], [], [], [0]
        for p, k0 in zip(self.paths, self.starts):
            t = p.t[p.steady]
            w = np.zeros(t.size)
            if p.periodic:
                w[:-1] += 0.5 * np.diff(t)
                w[1:] += 0.5 * np.diff(t)
            index.append(k0 + np.arange(p.steady.start, p.steady.stop))
            weight.append(w)
            work.append(np.zeros(t.size) if p.periodic else np.r_[0.0, np.ones(t.size - 1)])
            first.append(first[-1] + t.size)
        self.steady_index = np.concatenate(index)
        self.steady_weight = np.concatenate(weight)
        self.steady_work_weight = np.concatenate(work)
        self.steady_starts = np.array(first[:-1])

    def __len__(self) -> int:
        return len(self.paths)

    def n_for(self, model) -> np.ndarray:
        """Approaches with the separators set below every gap of ``model`` (m)."""
        _check_model("model", model)
        n = self._n.copy()
        low = min(float(model.gaps.min()), float(n.min()))
        n[self._sep] = low - max(1.0, abs(low))
        return n

    def run(self, model, *, chunks: int = 1, progress: Progress | None = None):
        """Total forces ``(T, N)`` (N) and friction work ``W`` (J) of each step of ``model`` over the batch.

        Returns
        -------
        T, N, W : ndarray, shape (samples,)
        """
        n = self.n_for(model)
        chunks = _checks.size("chunks", chunks)
        T = np.empty_like(self.t)
        N = np.empty_like(self.t)
        W = np.empty_like(self.t)
        cuts = self.starts[np.linspace(0, len(self), max(1, min(chunks, len(self))) + 1)[:-1].astype(int)]
        cuts = np.append(cuts, self.t.size)
        for c, (lo, hi) in enumerate(zip(cuts[:-1], cuts[1:])):
            if progress is not None:
                progress.step(f"{type(model).__name__} J = {model.elements}: part {c + 1} of {cuts.size - 1}")
            r = model.simulate(self.t[lo:hi], n[lo:hi], per_element=False)
            T[lo:hi], N[lo:hi], W[lo:hi] = r.T, r.N, r.friction_work
        return T, N, W

    def per_path(self, values, how: str = "sum") -> np.ndarray:
        """Sum (``how='sum'``) or maximum (``'max'``) per path of ``values`` on the steady samples.

        ``values`` has shape ``(steady samples,)``: a batch array indexed with ``steady_index``.
        """
        values = self._samples("values", values, self.steady_index.size)
        op = np.add if _checks.one_of("how", how, ("sum", "max")) == "sum" else np.maximum
        return op.reduceat(values, self.steady_starts)

    def _samples(self, name: str, values, size: int) -> np.ndarray:
        """``values`` checked finite, 1-D, of ``size`` samples."""
        values = _checks.real_array(name, values, ndim=1)
        if values.size != size:
            raise ValueError(f"{name} must have {size} samples, one per sample of the batch, got {values.size}")
        return values

    def steady_metrics(self, T, N, W):
        """``(energy, peak |T|, sum N)`` per path over the steady parts of batch arrays from :meth:`run`."""
        T, N, W = (self._samples(name, v, self.t.size) for name, v in (("T", T), ("N", N), ("W", W)))
        k = self.steady_index
        Ts = T[k]
        energy = self.per_path(self.steady_weight * Ts + self.steady_work_weight * W[k])
        return energy, self.per_path(np.abs(Ts), "max"), self.per_path(N[k])

    def split(self, values) -> list:
        """``values`` (shape ``(samples,)``) over the batch cut back into one array per path."""
        values = self._samples("values", values, self.t.size)
        return [values[k0:k0 + len(p)] for p, k0 in zip(self.paths, self.starts)]


@dataclass(frozen=True, eq=False)
class ReferenceRun:
    """Forces of a reference model along a batch of paths, computed once and reused.

    Attributes
    ----------
    reference_model : MicroslipModel
        The model that produced them.
    batch : PathBatch
    T, N : ndarray, shape (samples,)
        Forces (N) over the batch.
    W : ndarray, shape (samples,)
        Friction work of each step (J).
    """

    reference_model: object
    batch: PathBatch
    T: np.ndarray
    N: np.ndarray
    W: np.ndarray

    @property
    def paths(self) -> tuple:
        """The paths run: tuple of :class:`~microslip.paths.Path`, length P, in batch order (m)."""
        return self.batch.paths

    @cached_property
    def metrics(self):
        """``(energy, peak |T|, sum N)`` per path over the steady parts (J, N, N)."""
        return self.batch.steady_metrics(self.T, self.N, self.W)


def reference_run(reference_model, paths, *, progress: Progress | None = None, chunks: int = 1) -> ReferenceRun:
    """Run the reference model once on ``paths``; pass the result to :func:`accuracy` to reuse it.

    Parameters
    ----------
    reference_model : MicroslipModel
        Normally ``mdr(...)``.
    paths : Path, sequence of Path, or PathBatch
    progress : Progress, optional
    chunks : int
        Number of kernel calls (progress is stepped once per call).
    """
    _check_model("reference_model", reference_model)
    chunks = _checks.size("chunks", chunks)
    batch = paths if isinstance(paths, PathBatch) else PathBatch(paths)
    limit = getattr(reference_model, "max_approach", np.inf)
    for k, p in enumerate(batch.paths):
        if float(p.n.max()) > limit * (1.0 + 1e-9):
            raise LoadLimitError(f"paths[{k}] ({p.label}) reaches the approach {float(p.n.max()):.6g} m, beyond "
                                 f"the {limit:.6g} m of max_load = {reference_model.max_load:.6g} N the reference "
                                 f"was built for; build it with a larger max_load (mdr(..., max_load=...))")
    return ReferenceRun(reference_model, batch, *batch.run(reference_model, chunks=chunks, progress=progress))


def _check_paths(paths) -> tuple:
    if isinstance(paths, Path):
        return (paths,)
    try:
        paths = tuple(paths)
    except TypeError:
        raise TypeError(f"paths must be a Path or a sequence of Path, got {type(paths).__name__}") from None
    if not paths:
        raise ValueError("paths must hold at least one Path, got an empty sequence")
    for k, p in enumerate(paths):
        if not isinstance(p, Path):
            raise TypeError(f"paths[{k}] must be a microslip.paths.Path, got {type(p).__name__}")
        if p.plane:
            raise ValueError(f"paths[{k}] ({p.label}) is an orbit on the contact plane: the accuracy metrics are "
                             f"defined along one tangential direction; compare models on it with simulate")
    return paths


def _check_model(name, model):
    if not (hasattr(model, "simulate") and hasattr(model, "gaps")):
        raise TypeError(f"{name} must be a MicroslipModel (e.g. from tune() or mdr()), got {type(model).__name__}")


def accuracy(model, reference_model, paths=None, *, progress: bool = False) -> "AccuracyReport":
    """Measure a model against a reference model along load paths.

    Parameters
    ----------
    model : MicroslipModel
        The model to judge (e.g. the paper's tuned array).
    reference_model : MicroslipModel or ReferenceRun
        The exact answer, normally ``mdr(sphere, max_load=...)``; or a
        :class:`ReferenceRun` of it (then ``paths`` may be omitted), to run
        the reference once for several models.
    paths : Path or sequence of Path
        The histories (m), e.g. :func:`microslip.paths.default_family`.
    progress : bool, default False
        Show progress on standard error.

    Returns
    -------
    AccuracyReport
        One row per path; see :data:`METRICS`.
    """
    _check_model("model", model)
    bar = Progress(8, enabled=progress) if _checks.flag("progress", progress) else None
    if isinstance(reference_model, ReferenceRun):
        ref = reference_model
        if paths is not None and _check_paths(paths) != ref.paths:
            raise ValueError("reference_model is a ReferenceRun of other paths; run reference_run() on these")
    else:
        if paths is None:
            raise ValueError("paths is required unless reference_model is a ReferenceRun")
        ref = reference_run(reference_model, paths, progress=bar, chunks=4)
    b = ref.batch
    T, N, W = b.run(model, chunks=4 if progress else 1, progress=bar)
    energy, peak, sum_N = b.steady_metrics(T, N, W)
    energy_ref, peak_ref, sum_N_ref = ref.metrics
    k = b.steady_index
    with np.errstate(invalid="ignore", divide="ignore"):
        force = b.per_path(np.abs(T[k] - ref.T[k]), "max") / peak_ref
        normal = (sum_N - sum_N_ref) / sum_N_ref
    if bar is not None:
        bar.done("accuracy measured")
    return AccuracyReport(paths=b.paths, energy=energy, energy_reference=energy_ref, peak=peak,
                          peak_reference=peak_ref, force_difference=force, normal_difference=normal)


@dataclass(frozen=True, eq=False)
class AccuracyReport:
    """Per-path accuracy of a model against a reference (from :func:`accuracy`).

    Attributes
    ----------
    paths : tuple of Path, length P
    energy, energy_reference : ndarray, shape (P,)
        Energy dissipated over the steady part of the model and of the
        reference (J): ``∮ T dt`` per cycle for a periodic path, the friction
        work for an open one.
    peak, peak_reference : ndarray, shape (P,)
        ``max |T|`` over the steady cycle (N).
    force_difference : ndarray, shape (P,)
        ``max|T - T_ref| / max|T_ref|`` (fraction).
    normal_difference : ndarray, shape (P,)
        ``mean(N - N_ref) / mean(N_ref)`` (fraction).
    """

    paths: tuple
    energy: np.ndarray
    energy_reference: np.ndarray
    peak: np.ndarray
    peak_reference: np.ndarray
    force_difference: np.ndarray
    normal_difference: np.ndarray

    def __len__(self) -> int:
        return len(self.paths)

    @property
    def work_scale(self) -> np.ndarray:
        """``max|T_ref| * (max t - min t)`` over the steady part of each path (J): the elastic work's scale."""
        return self.peak_reference * np.array([p.steady_span for p in self.paths])

    @property
    def shakedown(self) -> np.ndarray:
        """Paths where the reference stops dissipating (``W_ref <= 1e-9 * work_scale``), bool shape (P,).

        At small tangential amplitudes under a varying normal load the
        continuous contact shakes down: after the first cycle nothing slips
        and ``W_ref`` is zero up to round-off, so a relative energy error
        means nothing there.
        """
        return self.energy_reference <= SHAKEDOWN_RTOL * self.work_scale

    @property
    def energy_error(self) -> np.ndarray:
        """``W / W_ref - 1`` per path (fraction); NaN where the reference shakes down (:attr:`shakedown`)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(self.shakedown, np.nan, self.energy / self.energy_reference - 1.0)

    @property
    def peak_error(self) -> np.ndarray:
        """``max|T| / max|T_ref| - 1`` per path (fraction)."""
        return self.peak / self.peak_reference - 1.0

    def metric(self, name: str) -> np.ndarray:
        """The values of metric ``name`` (one of :data:`METRICS`), shape (P,)."""
        _checks.one_of("name", name, tuple(METRICS))
        return np.asarray(getattr(self, name), dtype=float)

    def param(self, name: str) -> np.ndarray:
        """Path parameter ``name`` (e.g. ``amplitude``, ``ratio``) per path; NaN where a path lacks it.

        ``name`` is one of the default family's parameters (:data:`PARAMS`) or
        a parameter of at least one of the paths.
        """
        known = set(PARAMS).union(*(p.params for p in self.paths))
        if not isinstance(name, str) or name not in known:
            raise ValueError(f"name must be a path parameter, one of {', '.join(sorted(known))}, got {name!r}")
        return np.array([float(p.params.get(name, np.nan)) for p in self.paths])

    def where(self, mask) -> "AccuracyReport":
        """The report restricted to the paths where ``mask`` (bool array, shape (P,)) is true."""
        mask = np.asarray(mask)
        if mask.dtype != bool or mask.shape != (len(self),):
            raise ValueError(f"mask must be a boolean array of shape ({len(self)},), got {mask.shape}")
        if not mask.any():
            raise ValueError("mask selects no path")
        idx = np.flatnonzero(mask)
        return AccuracyReport(paths=tuple(self.paths[i] for i in idx), energy=self.energy[idx],
                              energy_reference=self.energy_reference[idx], peak=self.peak[idx],
                              peak_reference=self.peak_reference[idx],
                              force_difference=self.force_difference[idx],
                              normal_difference=self.normal_difference[idx])

    def restrict(self, min_load: float, min_amplitude: float = 0.0) -> "AccuracyReport":
        """The report on the paths with lowest load ``N_m - N_a >= min_load`` (N) and amplitude factor
        ``>= min_amplitude`` (:func:`restriction_mask`)."""
        mask = restriction_mask(self.paths, min_load, min_amplitude)
        if not mask.any():
            raise ValueError(f"min_load {min_load:g} N and min_amplitude {min_amplitude:g} leave no path of the "
                             "report")
        return self.where(mask)

    def worst_by_amplitude(self) -> tuple[np.ndarray, np.ndarray]:
        """Worst ``|energy_error|`` (fraction) over the paths of each amplitude factor.

        Returns
        -------
        amplitudes, worst : ndarray, shape (A,)
            The distinct amplitude factors (increasing) and their worst error;
            NaN where every path of that amplitude shakes down.
        """
        amp = self.param("amplitude")
        if np.all(np.isnan(amp)):
            raise ValueError("needs paths with an 'amplitude' parameter (default_family)")
        levels = np.unique(amp[~np.isnan(amp)])
        err = np.abs(self.energy_error)
        worst = [np.nanmax(err[amp == a]) if np.any(~np.isnan(err[amp == a])) else np.nan for a in levels]
        return levels, np.array(worst, dtype=float)

    def worst(self, name: str) -> tuple[float, int]:
        """Worst value of metric ``name`` (largest magnitude, sign kept) and the index of its path."""
        v = self.metric(name)
        if np.all(np.isnan(v)):
            return float("nan"), -1
        k = int(np.nanargmax(np.abs(v)))
        return float(v[k]), k

    def summary(self) -> list[tuple]:
        """Rows ``(metric, worst, median of the magnitudes, path of the worst)``; values as fractions."""
        rows = []
        for name, label in METRICS.items():
            w, k = self.worst(name)
            v = np.abs(self.metric(name))
            rows.append((label, w, float(np.median(v[~np.isnan(v)])) if np.any(~np.isnan(v)) else float("nan"),
                         self.paths[k].label if k >= 0 else ""))
        return rows

    def summary_text(self) -> str:
        """The summary as a plain-text table (values in %)."""
        lines = [f"{'metric':<44} {'worst %':>9} {'median abs %':>13}  where the worst occurs"]
        for label, w, med, where in self.summary():
            lines.append(f"{label:<44} {100 * w:>9.3f} {100 * med:>13.3f}  {where}")
        lines.append(plural(len(self), "path"))
        sd = self.shakedown
        if sd.any():
            own = np.max(np.abs(self.energy[sd]) / self.work_scale[sd])
            down = int(sd.sum())
            lines.append(f"{down} of them {'shakes' if down == 1 else 'shake'} down in the reference (no "
                         f"dissipation after the first cycle): energy error undefined there; the model's W there is "
                         f"at most "
                         f"{own:.2g} of max|T_ref| * (max t - min t)")
        return "\n".join(lines)

    def columns(self) -> dict:
        """The table as ``{'name [unit]': column}``: path parameters then metrics."""
        cols = {"path": [p.label.replace(",", ";") for p in self.paths]}
        units = {"ratio": "-", "phase_deg": "deg", "level": "-", "amplitude": "-", "N_m": "N", "N_a": "N",
                 "phase": "rad", "t_a": "m"}
        for name in PARAMS:
            v = self.param(name)
            if not np.all(np.isnan(v)):
                cols[f"{name} [{units[name]}]"] = v
        cols["W [J]"] = self.energy
        cols["W_ref [J]"] = self.energy_reference
        cols["peak |T| [N]"] = self.peak
        cols["peak |T_ref| [N]"] = self.peak_reference
        for name in METRICS:
            cols[f"{name} [%]"] = 100 * self.metric(name)
        return cols

    def to_csv(self, path):
        """Write :meth:`columns` as CSV (atomically). Returns the path."""
        path = _checks.file_path("path", path)
        return write_csv(path, self.columns())

    def threshold_amplitude(self, limit: float = 0.10) -> float:
        """Smallest amplitude factor at and above which every path has ``|energy_error| <= limit``.

        Paths that shake down in the reference (no energy error defined) are
        ignored. ``nan`` when even the largest amplitude exceeds the limit.
        Uses the ``amplitude`` parameter of the paths (the default family's
        multiple of the gross-slip displacement at the path's lowest load).
        """
        limit = _checks.positive_scalar("limit", limit)
        amp = self.param("amplitude")
        err = np.abs(self.energy_error)
        answer = float("nan")
        for a in np.unique(amp[~np.isnan(amp)])[::-1]:
            e = err[(amp == a) & ~np.isnan(err)]
            if e.size and e.max() > limit:
                break
            answer = float(a)
        return answer

    # -- figures ------------------------------------------------------------
    def error_maps(self, metrics=("energy_error", "force_difference")):
        """The data of :meth:`plot`: worst ``|metric|`` (%) over the load levels per amplitude and ``N_a/N_m``.

        Phases whose maps are equal for every metric (to round-off: relative 1e-9) share one panel: for a
        tangential motion symmetric in sign, phi = 0° and 180° give mirror-image cycles (t -> -t half a
        cycle later) and the same errors.

        Returns
        -------
        amplitudes : ndarray, shape (A,)
            Amplitude factors (multiples of the gross-slip displacement at the path's lowest load).
        ratios : ndarray, shape (R,)
            Load ratios ``N_a / N_m``.
        panels : list of (tuple of float, dict)
            Per group of phases (degrees): ``{metric: grid}``, each grid of shape (R, A) in %, NaN where no
            path has a value (the reference shakes down).
        """
        if isinstance(metrics, str) or not hasattr(metrics, "__iter__") or not metrics or \
                not all(isinstance(m, str) and m in METRICS for m in metrics):
            raise ValueError(f"metrics must be a non-empty sequence of names among {', '.join(METRICS)}, "
                             f"got {metrics!r}")
        amp, ratio, phase = self.param("amplitude"), self.param("ratio"), self.param("phase_deg")
        if np.any(np.isnan(amp)) or np.any(np.isnan(ratio)):
            raise ValueError("plot() needs paths from default_family (with amplitude and ratio parameters); "
                             "use plot_amplitude() or the table for other paths")
        amps, ratios = np.unique(amp), np.unique(ratio)
        phases = np.unique(phase[ratio > 0]) if np.any(ratio > 0) else np.array([0.0])
        values = {name: np.abs(self.metric(name)) * 100 for name in metrics}
        panels = []
        for ph in phases:
            grids = {}
            for name, v in values.items():
                grid = np.full((ratios.size, amps.size), np.nan)
                for a_i, a in enumerate(amps):
                    for r_i, r in enumerate(ratios):
                        sel = (amp == a) & (ratio == r) & ((phase == ph) | (r == 0)) & ~np.isnan(v)
                        if np.any(sel):
                            grid[r_i, a_i] = np.max(v[sel])
                grids[name] = grid
            same = next((p for p in panels if all(np.allclose(p[1][n], grids[n], rtol=1e-9, atol=1e-12,
                                                              equal_nan=True) for n in metrics)), None)
            if same is None:
                panels.append(((float(ph),), grids))
            else:
                panels[panels.index(same)] = (same[0] + (float(ph),), same[1])
        return amps, ratios, panels

    def plot(self, metrics=("energy_error", "force_difference")):
        """Error maps: for each metric and group of phases (one panel each, stacked), the worst ``|metric|`` (%)
        over the load levels against the amplitude factor (x) and ``N_a/N_m`` (y); phases with equal maps
        share a panel (:meth:`error_maps`). Sized to be read at the width of a report page; the panels of
        one metric share a colour scale. Needs the default family.

        Returns
        -------
        matplotlib.figure.Figure
        """
        import matplotlib.pyplot as plt
        from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

        amps, ratios, panels = self.error_maps(metrics)
        rows = [(name, phases, grids[name]) for name in metrics for phases, grids in panels]
        fig, axes = plt.subplots(len(rows), 1, figsize=(MAP_WIDTH, 0.5 + MAP_PANEL_HEIGHT * len(rows)),
                                 squeeze=False, constrained_layout=True)
        for name in metrics:
            mine = [k for k, row in enumerate(rows) if row[0] == name]
            norm = _log_norm(np.concatenate([rows[k][2].ravel() for k in mine]))
            for k in mine:
                _, phases, grid = rows[k]
                ax = axes[k, 0]
                im = ax.imshow(grid, origin="lower", aspect="auto", cmap="magma_r", norm=norm)
                for (r_i, a_i), val in np.ndenumerate(grid):
                    if np.isfinite(val):
                        ax.text(a_i, r_i, _cell_text(val), ha="center", va="center", fontsize=MAP_FONT,
                                color=_text_colour(im.cmap(im.norm(val))))
                ax.set_xticks(range(amps.size), [f"{a:g}" for a in amps], fontsize=MAP_FONT)
                ax.set_yticks(range(ratios.size), [f"{r:g}" for r in ratios], fontsize=MAP_FONT)
                ax.set_xlabel("tangential amplitude / gross-slip displacement at the lowest load, t_a / t_gs(N_min)",
                              fontsize=MAP_FONT)
                ax.set_ylabel("load amplitude\nratio N_a / N_m", fontsize=MAP_FONT)
                ax.set_title(f"{MAP_TITLES.get(name, name)} (%), φ = {_phases_text(phases)}", fontsize=MAP_FONT + 1)
            bar = fig.colorbar(im, ax=[axes[k, 0] for k in mine], shrink=0.9, aspect=25, pad=0.02)
            bar.set_label(f"{MAP_TITLES.get(name, name)} (%)", fontsize=MAP_FONT)
            if norm is not None:  # 1, 2, 5 x 10^k written plainly, not as 2 x 10^1
                bar.ax.yaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
            bar.ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
            bar.ax.yaxis.set_minor_formatter(NullFormatter())
            bar.ax.tick_params(labelsize=MAP_FONT)
        fig.suptitle("worst over the load levels; blank: the reference shakes down (no energy error defined)",
                     fontsize=MAP_FONT + 1)
        return fig

    def plot_amplitude(self, ax=None, *, label: str | None = None, **kwargs):
        """Worst ``|energy_error|`` (%) over all paths of each amplitude factor, against the factor.

        Returns
        -------
        matplotlib.axes.Axes
        """
        import matplotlib.pyplot as plt

        try:
            levels, worst = self.worst_by_amplitude()
        except ValueError as exc:
            raise ValueError(f"plot_amplitude() {exc}") from None
        if ax is None:
            _, ax = plt.subplots(figsize=(5.5, 4))
        ax.loglog(levels, 100 * worst, "o-", label=label, **kwargs)
        ax.axhline(10, color="0.5", ls=":", lw=1)
        ax.set_xlabel("tangential amplitude t_a / t_gs(N_min) (-)")
        ax.set_ylabel("worst |energy error| (%)")
        ax.grid(True, which="both", alpha=0.3)
        if label:
            ax.legend(fontsize=8)
        return ax


#: width of the error maps (in): the width of a report page (:data:`microslip.common.report.REPORT_WIDTH`)
MAP_WIDTH = 6.4
#: height of one panel of the error maps (in)
MAP_PANEL_HEIGHT = 2.1
#: font size of the maps' numbers and labels (pt), as printed at the report's width
MAP_FONT = 8.0
#: panel titles of the metrics, in words
MAP_TITLES = {"energy_error": "worst energy error", "force_difference": "worst force difference",
              "peak_error": "worst peak-force error", "normal_difference": "worst mean normal-force difference"}


def _cell_text(val: float) -> str:
    """A percentage in at most three significant characters: 364, 48, 7.2, 0.5."""
    return f"{val:.0f}" if val >= 9.5 else f"{val:.1f}" if val >= 0.95 else f"{val:.1g}"


def _text_colour(rgba) -> str:
    """Black or white, whichever contrasts more with the cell's colour (WCAG contrast ratio; on magma at
    least 4.6, above the 4.5 asked of body text)."""
    r, g, b = (c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in rgba[:3])
    luminance = 0.2126 * r + 0.7152 * g + 0.0722 * b
    return "black" if (luminance + 0.05) / 0.05 >= 1.05 / (luminance + 0.05) else "white"


def _phases_text(phases) -> str:
    """``0°``, ``0° and 180°``, ``0°, 90° and 180°``."""
    names = [f"{p:g}°" for p in phases]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def _log_norm(grid):
    from matplotlib.colors import LogNorm

    finite = grid[np.isfinite(grid) & (grid > 0)]
    if finite.size == 0:
        return None
    lo, hi = float(finite.min()), float(finite.max())
    return LogNorm(vmin=lo, vmax=hi if hi > lo else lo * 10)
