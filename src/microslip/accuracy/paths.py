"""Load paths: histories of tangential displacement ``t`` and normal approach ``n`` to drive a contact.

A :class:`Path` holds the samples ``t``, ``n`` (m), the normal load ``N`` (N)
they were built from (when built from loads), and ``steady``: the slice that
is the steady cycle, over which accuracy metrics are measured. Every path
starts at ``t = 0`` from the virgin state (sliders at 0): pressing the
contact at ``t = 0`` to any approach leaves every slider at 0, so the first
sample may sit at any load.

Builders
--------
:func:`loop`
    cycles at constant normal load;
:func:`paper_fig4`
    the Mindlin--Deresiewicz path of the paper's Fig. 4 (raise ``N`` at
    constant ``T``, then raise ``T``);
:func:`variable_load_cycles`
    ``t = t_a sin(tau)``, ``N = N_m + N_a sin(tau + phi)`` (``phi`` in degrees,
    as everywhere in this module);
:func:`from_arrays`
    any user history, given as approaches or as loads;
:func:`default_family`
    the family of variable-normal-load cycles used by :func:`microslip.accuracy`.

Normal loads are turned into approaches through the reference's normal law
(``reference.approach(N)``, e.g. Hertz for a :class:`~microslip.Sphere`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from ..common import _checks
from ..model import MicroslipModel, _frozen

__all__ = ["AMPLITUDES", "LEVELS", "PHASES_DEG", "Path", "RATIOS", "default_family", "from_arrays", "loop",
           "paper_fig4", "variable_load_cycles"]


@dataclass(frozen=True, eq=False)
class Path:
    """A history of tangential displacement and normal approach.

    Parameters
    ----------
    t, n : array_like, shape (steps,)
        Tangential displacement and normal approach (m), finite.
    steady : slice
        The steady cycle (the part the metrics use); for a periodic path it
        starts and ends at the same ``t`` and ``n``.
    N : array_like, shape (steps,), optional
        Normal load (N) the approaches were computed from.
    periodic : bool
        True when ``steady`` is a closed cycle (then ``∮ T dt`` is the
        energy dissipated per cycle).
    label : str
        Short description.
    params : dict
        The parameters it was built from (used as columns by the accuracy report).
    """

    t: np.ndarray
    n: np.ndarray
    steady: slice
    N: np.ndarray | None = None
    periodic: bool = False
    label: str = "path"
    params: dict = field(default_factory=dict)

    def __post_init__(self):
        t = _checks.real_array("t", self.t, ndim=1, min_size=2)
        n = _checks.real_array("n", self.n, ndim=1, min_size=2)
        if n.shape != t.shape:
            raise ValueError(f"n must have the same shape as t {t.shape}, got {n.shape}")
        if not isinstance(self.steady, slice):
            raise TypeError(f"steady must be a slice of the samples, got {type(self.steady).__name__}")
        start, stop, step = self.steady.indices(t.size)
        if step != 1 or stop - start < 2:
            raise ValueError(f"steady must select at least 2 consecutive samples of the {t.size}, "
                             f"got {self.steady}")
        object.__setattr__(self, "steady", slice(start, stop))
        object.__setattr__(self, "t", _frozen(t))
        object.__setattr__(self, "n", _frozen(n))
        if self.N is not None:
            N = _checks.real_array("N", self.N, ndim=1)
            if N.shape != t.shape:
                raise ValueError(f"N must have the same shape as t {t.shape}, got {N.shape}")
            object.__setattr__(self, "N", _frozen(N))
        object.__setattr__(self, "params", _checks.mapping("params", self.params))
        object.__setattr__(self, "periodic", _checks.flag("periodic", self.periodic))
        object.__setattr__(self, "label", _checks.text("label", self.label, allow_empty=True))
        if self.periodic:
            k0, k1 = self.steady.start, self.steady.stop - 1
            for name, x in (("t", t), ("n", n)):
                if abs(x[k1] - x[k0]) > 1e-9 * max(float(np.abs(x).max()), 1e-300):
                    raise ValueError(f"periodic: the steady part must close, but {name} goes from {x[k0]:.6g} m "
                                     f"at sample {k0} to {x[k1]:.6g} m at sample {k1}; give periodic=False "
                                     f"or a steady slice over whole cycles")

    def __len__(self) -> int:
        return self.t.size

    @cached_property
    def steady_span(self) -> float:
        """``max t - min t`` over the steady part (m)."""
        return float(np.ptp(self.t[self.steady]))

    def simulate(self, model, *, per_element: bool = False):
        """Run ``model`` along the path from the virgin state.

        Parameters
        ----------
        model : MicroslipModel
            The contact model to drive with ``t`` and ``n`` (m).
        per_element : bool, default False
            Record each element's force and condition too.

        Returns
        -------
        Response
            Forces in N, shapes ``(steps,)`` and, per element, ``(steps, J)``
            (:meth:`MicroslipModel.simulate`).
        """
        if not isinstance(model, MicroslipModel):
            raise TypeError(f"model must be a MicroslipModel (e.g. from tune() or mdr()), got {type(model).__name__}")
        return model.simulate(self.t, self.n, per_element=_checks.flag("per_element", per_element))

    def plot(self, ax=None):
        """Plot ``t`` (µm) and ``N`` (N, or ``n`` in µm) against the sample index, steady cycle shaded.

        Returns
        -------
        matplotlib.axes.Axes
            The axes of ``t``; the normal quantity is on a twin axis.
        """
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 3.5))
        k = np.arange(self.t.size)
        ax.plot(k, self.t * 1e6, color="tab:blue")
        ax.set_xlabel("sample")
        ax.set_ylabel("tangential displacement t (µm)", color="tab:blue")
        ax.axvspan(self.steady.start, self.steady.stop - 1, color="0.9", zorder=0, label="steady cycle")
        twin = ax.twinx()
        if self.N is not None:
            twin.plot(k, self.N, color="tab:red")
            twin.set_ylabel("normal load N (N)", color="tab:red")
        else:
            twin.plot(k, self.n * 1e6, color="tab:red")
            twin.set_ylabel("normal approach n (µm)", color="tab:red")
        ax.set_title(self.label)
        return ax


def _require(reference, *names):
    """Refuse a reference lacking any of the methods ``names``, naming them."""
    missing = [m for m in names if not callable(getattr(reference, m, None))]
    if missing:
        raise TypeError(f"reference must provide {', '.join(m + '()' for m in missing)} (e.g. a microslip.Sphere), "
                        f"got {type(reference).__name__}")


def _approach(reference, N, name="N"):
    """Approaches (m) of loads ``N`` (N) through ``reference.approach``; negative loads refused."""
    N = _checks.real_array(name, N)
    if N.size and float(N.min()) < 0.0:
        k = int(np.argmin(N))
        raise ValueError(f"{name} must be non-negative for the normal law (a contact cannot pull), "
                         f"got {float(N.ravel()[k]):.6g} N at sample {k}")
    _require(reference, "approach")
    return np.asarray(reference.approach(N), dtype=float)


def _cycles_grid(cycles, steps_per_cycle):
    cycles = _checks.size("cycles", cycles)
    spc = _checks.size("steps_per_cycle", steps_per_cycle, minimum=8)
    if cycles * spc >= _checks.MAX_SIZE:
        raise ValueError(f"cycles * steps_per_cycle must be below {_checks.MAX_SIZE} samples, got {cycles} * {spc}")
    tau = 2.0 * np.pi * np.arange(cycles * spc + 1) / spc
    return tau, slice((cycles - 1) * spc, cycles * spc + 1)


def loop(reference, normal_load, amplitude, *, cycles: int = 2, steps_per_cycle: int = 400) -> Path:
    """Cycles ``t = amplitude sin(tau)`` at constant normal load.

    Parameters
    ----------
    reference : object with ``approach(N)``
        Normal law (e.g. :class:`~microslip.Sphere`).
    normal_load : float
        Normal load (N), positive.
    amplitude : float
        Tangential displacement amplitude (m), positive.
    cycles : int, default 2
        Number of cycles; the last is the steady one.
    steps_per_cycle : int, default 400
        Samples per cycle (at least 8).

    Returns
    -------
    Path
        ``cycles * steps_per_cycle + 1`` samples, periodic.
    """
    N = _checks.positive_scalar("normal_load", normal_load)
    ta = _checks.positive_scalar("amplitude", amplitude)
    tau, steady = _cycles_grid(cycles, steps_per_cycle)
    n = float(_approach(reference, N, "normal_load"))
    return Path(t=ta * np.sin(tau), n=np.full(tau.shape, n), N=np.full(tau.shape, N), steady=steady,
                periodic=True, label=f"loop at N = {N:.4g} N, t_a = {ta * 1e6:.4g} µm",
                params={"N_m": N, "N_a": 0.0, "phase": 0.0, "t_a": ta})


def variable_load_cycles(reference, mean_load, load_amplitude, amplitude, phase_deg=0.0, *, cycles: int = 3,
                         steps_per_cycle: int = 360) -> Path:
    """Periodic cycles ``t = t_a sin(tau)``, ``N = N_m + N_a sin(tau + phi)``.

    Parameters
    ----------
    reference : object with ``approach(N)``
        Normal law turning ``N`` into the approach ``n``.
    mean_load : float
        ``N_m`` (N), positive.
    load_amplitude : float
        ``N_a`` (N), ``0 <= N_a <= N_m`` (the contact must stay closed).
    amplitude : float
        ``t_a`` (m), positive.
    phase_deg : float, default 0
        ``phi`` (degrees, as in :func:`default_family` and the path labels):
        the lead of the normal load on the tangential motion.
    cycles : int, default 3
        Number of cycles; the last is the steady one.
    steps_per_cycle : int, default 360
        Samples per cycle.

    Returns
    -------
    Path
        Periodic; starts at ``t = 0`` with ``N = N_m + N_a sin(phi)``;
        ``params`` ``N_m``, ``N_a`` (N), ``phase_deg`` (degrees), ``phase``
        (the same in rad) and ``t_a`` (m).
    """
    Nm = _checks.positive_scalar("mean_load", mean_load)
    Na = _checks.positive_scalar("load_amplitude", load_amplitude, allow_zero=True)
    ta = _checks.positive_scalar("amplitude", amplitude)
    phi_deg = _checks.real_scalar("phase_deg", phase_deg)
    phi = np.radians(phi_deg)
    if Na > Nm:
        raise ValueError(f"load_amplitude must not exceed mean_load = {Nm:.6g} N (the normal load "
                         f"N_m - N_a would be negative), got {Na:.6g} N")
    _require(reference, "approach")
    tau, steady = _cycles_grid(cycles, steps_per_cycle)
    N = np.maximum(Nm + Na * np.sin(tau + phi), 0.0)  # clip round-off below 0 when N_a = N_m
    return Path(t=ta * np.sin(tau), n=_approach(reference, N), N=N, steady=steady, periodic=True,
                label=f"N = {Nm:.4g} + {Na:.4g} sin(tau + {phi_deg:.0f}°) N, t_a = {ta * 1e6:.4g} µm",
                params={"N_m": Nm, "N_a": Na, "phase": phi, "phase_deg": phi_deg, "t_a": ta})


def paper_fig4(reference, normal_load: float = 25.0, load_step: float = 12.5, raised_at: float = 0.5, *,
               beyond: float = 1.3, steps: int = 200) -> Path:
    """The path of the paper's Fig. 4: T to ``T_A`` at ``N``, N raised by ``dN`` at constant t, then t raised.

    Parameters
    ----------
    reference : Sphere or similar
        Provides ``mu``, ``approach``, ``backbone_displacement`` and
        ``gross_slip_displacement``.
    normal_load : float, default 25
        ``N`` (N) before the step.
    load_step : float, default 12.5
        ``dN`` (N), non-negative.
    raised_at : float, default 0.5
        ``T_A / (mu N)``, in ``[0, 1]``.
    beyond : float, default 1.3
        The last leg ends at ``beyond`` times the gross-slip displacement at
        ``N + dN``.
    steps : int, default 200
        Samples of each of the three legs.

    Returns
    -------
    Path
        Not periodic; ``steady`` is the whole path. At constant ``t`` raising
        ``n`` leaves ``T`` unchanged (new contact enters unloaded, slipping
        elements stick under the higher limit), so the second leg is
        Mindlin--Deresiewicz's step at constant ``T``.
    """
    N = _checks.positive_scalar("normal_load", normal_load)
    dN = _checks.positive_scalar("load_step", load_step, allow_zero=True)
    x = _checks.in_range("raised_at", raised_at, 0.0, 1.0)
    beyond = _checks.positive_scalar("beyond", beyond)
    steps = _checks.size("steps", steps, minimum=2, maximum=_checks.MAX_SIZE // 3)
    _require(reference, "approach", "backbone_displacement", "gross_slip_displacement")
    if not hasattr(reference, "mu"):
        raise TypeError(f"reference must provide mu (its friction coefficient), got {type(reference).__name__}")
    tA = float(reference.backbone_displacement(x * reference.mu * N, N))
    t_end = max(beyond * float(reference.gross_slip_displacement(N + dN)), tA)
    leg1 = np.linspace(0.0, tA, steps)
    leg3 = np.linspace(tA, t_end, steps)[1:]
    loads = np.concatenate([np.full(steps, N), np.linspace(N, N + dN, steps)[1:], np.full(steps - 1, N + dN)])
    t = np.concatenate([leg1, np.full(steps - 1, tA), leg3])
    return Path(t=t, n=_approach(reference, loads), N=loads, steady=slice(0, t.size), periodic=False,
                label=f"Fig. 4: N = {N:g} N, T_A = {x:g} mu N, dN = {dN:g} N",
                params={"N_m": N, "N_a": dN, "phase": 0.0, "t_a": t_end})


def from_arrays(t, n=None, *, N=None, reference=None, steady=None, periodic: bool = False,
                label: str = "user path") -> Path:
    """A path from user arrays: ``t`` with either approaches ``n`` or loads ``N``.

    Parameters
    ----------
    t : array_like, shape (steps,)
        Tangential displacement (m).
    n : array_like, shape (steps,) or scalar, optional
        Normal approach (m).
    N : array_like, shape (steps,) or scalar, optional
        Normal load (N), non-negative; needs ``reference`` (its normal law).
    reference : object with ``approach(N)``, optional
        Normal law for ``N``.
    steady : slice, optional
        The steady part; default the whole path.
    periodic : bool, default False
        Whether ``steady`` is a closed cycle.
    label : str
        Description.
    """
    t = _checks.real_array("t", t, ndim=1, min_size=2)
    if (n is None) == (N is None):
        raise ValueError("give exactly one of n= (approaches, m) or N= (loads, N)")
    if N is not None:
        if reference is None:
            raise ValueError("N= needs reference= (its normal law turns loads into approaches)")
        N = np.broadcast_to(_like_t("N", N, t), t.shape)
        n = _approach(reference, N)
    else:
        n = np.broadcast_to(_like_t("n", n, t), t.shape)
    return Path(t=t, n=n, N=None if N is None else N, steady=slice(0, t.size) if steady is None else steady,
                periodic=periodic, label=label)


def _like_t(name, values, t):
    """``values`` checked finite and either a scalar or of the shape of ``t``."""
    v = _checks.real_array(name, values)
    if v.ndim and v.shape != t.shape:
        raise ValueError(f"{name} must be a scalar or have the shape of t {t.shape}, got shape {v.shape}")
    return v


#: defaults of :func:`default_family`
RATIOS = (0.0, 0.3, 0.6, 0.9)
PHASES_DEG = (0.0, 90.0, 180.0)
AMPLITUDES = (0.1, 0.2, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0)
LEVELS = (0.1, 0.325, 0.55, 0.775, 1.0)


def default_family(reference, normal_load, *, ratios=RATIOS, phases_deg=PHASES_DEG, amplitudes=AMPLITUDES,
                   levels=LEVELS, cycles: int = 2, steps_per_cycle: int = 360) -> list[Path]:
    """The family of variable-normal-load cycles the accuracy report runs.

    One path per combination of

    * ``ratio = N_a / N_m`` in ``ratios`` (0 to 0.9); at ratio 0 only one phase;
    * ``phi`` in ``phases_deg`` (0°, 90°, 180°);
    * ``level`` in ``levels`` (0.1 to 1): the peak load ``N_m + N_a`` is
      ``level * normal_load``, so at ratio 0 the mean load runs from 0.1 to 1
      times the tuning load and no path exceeds it (beyond its tuning load
      the paper's array extrapolates linearly, with every gap closed);
    * amplitude factor in ``amplitudes`` (0.1 to 3): ``t_a`` is that
      multiple of the gross-slip displacement at the path's lowest load
      ``N_m - N_a``.

    Parameters
    ----------
    reference : Sphere or similar
        Normal law and gross-slip displacement.
    normal_load : float
        The tuning load ``N_tot`` (N).
    ratios : array_like, shape (R,), default (0, 0.3, 0.6, 0.9)
        Load ratios ``N_a / N_m`` (-), each in ``[0, 1)``.
    phases_deg : array_like, shape (F,), default (0, 90, 180)
        Phases ``phi`` (degrees) of the normal load on the tangential motion.
    amplitudes : array_like, shape (A,), default (0.1, 0.2, 0.35, 0.5, 0.75, 1, 1.5, 2, 3)
        Tangential amplitude factors (-), positive: multiples of the
        gross-slip displacement at the path's lowest load.
    levels : array_like, shape (L,), default (0.1, 0.325, 0.55, 0.775, 1)
        Peak loads ``N_m + N_a`` (-) as fractions of ``normal_load``, in ``(0, 1]``.
    cycles : int, default 2
        Cycles per path; the last is measured. The first cycle already
        brings both the exact contact and the paper's array to their
        periodic state (a third cycle repeats the second to round-off,
        checked in ``tests/test_paths.py``).
    steps_per_cycle : int, default 360
        Samples per cycle.

    Returns
    -------
    list of Path
        ``(R - 1) F L A + L A`` paths when ``ratios`` holds one 0 (one phase
        at ratio 0), each with ``params`` ``ratio``, ``phase_deg``, ``level``,
        ``amplitude`` (the factor), ``N_m``, ``N_a`` (N), ``t_a`` (m).

    Notes
    -----
    For a unidirectional ``t``, the phases ``phi`` and ``phi + 180°`` give
    mirror-image steady cycles (``t -> -t`` half a cycle later), so their
    metrics coincide.
    """
    _require(reference, "approach", "gross_slip_displacement")
    N_tot = _checks.positive_scalar("normal_load", normal_load)
    ratios = _checks.positive_array("ratios", ratios, ndim=1, min_size=1, allow_zero=True)
    if float(ratios.max()) >= 1.0:
        raise ValueError(f"ratios must be below 1 (the load N_m - N_a must stay positive), got {ratios.max():g}")
    phases = _checks.real_array("phases_deg", phases_deg, ndim=1, min_size=1)
    amps = _checks.positive_array("amplitudes", amplitudes, ndim=1, min_size=1)
    levels = _checks.positive_array("levels", levels, ndim=1, min_size=1)
    if float(levels.max()) > 1.0:
        raise ValueError(f"levels must not exceed 1 (peak load at most the tuning load), got {levels.max():g}")
    paths = []
    for r in ratios:
        for phi in (phases[:1] if r == 0 else phases):
            for lev in levels:
                Nm = lev * N_tot / (1.0 + r)
                Na = r * Nm
                t_gs = float(reference.gross_slip_displacement(Nm - Na))
                for a in amps:
                    p = variable_load_cycles(reference, Nm, Na, a * t_gs, phi, cycles=cycles,
                                             steps_per_cycle=steps_per_cycle)
                    paths.append(replace(p, params={**p.params, "ratio": float(r), "level": float(lev),
                                                    "phase_deg": float(phi) if r else 0.0,
                                                    "amplitude": float(a)}))
    return paths
