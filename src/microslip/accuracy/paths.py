"""Load paths: histories of tangential displacement ``t`` and normal approach ``n`` to drive a contact.

A :class:`Path` holds the samples ``t`` (along one tangential direction, or
its two components on the contact plane), ``n`` (m), the normal load ``N`` (N)
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
:func:`circle`, :func:`ellipse`, :func:`figure_eight`, :func:`line`
    orbits on the contact plane (``t`` of shape ``(steps, 2)``), each with a
    normal load ``N = N_m + N_a sin(tau + phi)`` along the orbit;
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
from ..model import PLANE_LIMIT, MicroslipModel, frozen, tangential_history

__all__ = ["Path", "circle", "default_family", "ellipse", "figure_eight", "from_arrays", "line", "loop", "paper_fig4",
           "variable_load_cycles"]


@dataclass(frozen=True, eq=False)
class Path:
    """A history of tangential displacement and normal approach.

    Parameters
    ----------
    t : array_like, shape (steps,) or (steps, 2)
        Tangential displacement (m), finite: along one direction, or its two
        components on the contact plane (an orbit).
    n : array_like, shape (steps,)
        Normal approach (m), finite.
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
        t = tangential_history("t", self.t, min_steps=2)
        n = _checks.real_array("n", self.n, ndim=1, min_size=2)
        if n.shape != t.shape[:1]:
            raise ValueError(_not_per_sample("n", t, n))
        if not isinstance(self.steady, slice):
            raise TypeError(f"steady must be a slice of the samples, got {type(self.steady).__name__}")
        start, stop, step = self.steady.indices(t.shape[0])
        if step != 1 or stop - start < 2:
            raise ValueError(f"steady must select at least 2 consecutive samples of the {t.shape[0]}, "
                             f"got {self.steady}")
        object.__setattr__(self, "steady", slice(start, stop))
        object.__setattr__(self, "t", frozen(t))
        object.__setattr__(self, "n", frozen(n))
        if self.N is not None:
            N = _checks.real_array("N", self.N, ndim=1)
            if N.shape != t.shape[:1]:
                raise ValueError(_not_per_sample("N", t, N))
            object.__setattr__(self, "N", frozen(N))
        object.__setattr__(self, "params", _checks.mapping("params", self.params))
        object.__setattr__(self, "periodic", _checks.flag("periodic", self.periodic))
        object.__setattr__(self, "label", _checks.text("label", self.label, allow_empty=True))
        if self.periodic:
            k0, k1 = self.steady.start, self.steady.stop - 1
            for name, x in (("t", t), ("n", n)):
                if np.abs(x[k1] - x[k0]).max() > 1e-9 * max(float(np.abs(x).max()), 1e-300):
                    raise ValueError(f"periodic: the steady part must close, but {name} goes from {_point(x[k0])} m "
                                     f"at sample {k0} to {_point(x[k1])} m at sample {k1}; give periodic=False "
                                     f"or a steady slice over whole cycles")

    def __len__(self) -> int:
        return self.t.shape[0]

    @property
    def plane(self) -> bool:
        """True for a path on the contact plane (``t`` of shape ``(steps, 2)``)."""
        return self.t.ndim == 2

    @cached_property
    def steady_span(self) -> float:
        """``max t - min t`` over the steady part (m); along one direction only (it scales the accuracy metrics)."""
        if self.plane:
            raise ValueError("steady_span is defined along one tangential direction; this path is on the contact "
                             "plane (measure its orbit from t directly)")
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
            (:meth:`MicroslipModel.simulate`); on the plane ``(steps, 2)``
            and ``(steps, J, 2)``.
        """
        if not isinstance(model, MicroslipModel):
            raise TypeError(f"model must be a MicroslipModel (e.g. from tune() or mdr()), got {type(model).__name__}")
        return model.simulate(self.t, self.n, per_element=_checks.flag("per_element", per_element))

    def plot(self, ax=None):
        """Plot ``t`` (µm; both components on the plane) and ``N`` (N, or ``n`` in µm) against the sample index.

        Returns
        -------
        matplotlib.axes.Axes
            The axes of ``t``; the normal quantity is on a twin axis.
        """
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 3.5))
        k = np.arange(len(self))
        if self.plane:
            ax.plot(k, self.t[:, 0] * 1e6, color="tab:blue", label="x component")
            ax.plot(k, self.t[:, 1] * 1e6, color="tab:blue", ls="--", label="y component")
            ax.legend(fontsize="small", loc="upper left")
        else:
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


def _not_per_sample(name, t, values) -> str:
    if t.ndim == 1:
        return f"{name} must have the same shape as t {t.shape}, got {values.shape}"
    return f"{name} must have one value per sample of t {t.shape[:1]}, got {values.shape}"


def _point(x) -> str:
    """A sample of ``t`` or ``n`` for a message: a number, or ``(x, y)`` on the plane."""
    return f"{float(x):.6g}" if np.ndim(x) == 0 else "(" + ", ".join(f"{float(v):.6g}" for v in x) + ")"


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
    t : array_like, shape (steps,) or (steps, 2)
        Tangential displacement (m): along one direction, or its two
        components on the contact plane.
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
    t = tangential_history("t", t, min_steps=2)
    steps = t.shape[:1]
    if (n is None) == (N is None):
        raise ValueError("give exactly one of n= (approaches, m) or N= (loads, N)")
    if N is not None:
        if reference is None:
            raise ValueError("N= needs reference= (its normal law turns loads into approaches)")
        N = np.broadcast_to(_like_t("N", N, t), steps)
        n = _approach(reference, N)
    else:
        n = np.broadcast_to(_like_t("n", n, t), steps)
    return Path(t=t, n=n, N=None if N is None else N, steady=slice(0, steps[0]) if steady is None else steady,
                periodic=periodic, label=label)


def _like_t(name, values, t):
    """``values`` checked finite and either a scalar or one value per sample of ``t``."""
    v = _checks.real_array(name, values)
    if v.ndim and v.shape != t.shape[:1]:
        raise ValueError(f"{name} must be a scalar or have the shape of t {t.shape}, got shape {v.shape}" if t.ndim == 1
                         else f"{name} must be a scalar or have one value per sample of t {t.shape[:1]}, got shape "
                              f"{v.shape}")
    return v


# -- orbits on the contact plane -------------------------------------------------------------------------
def _orbit(reference, shape, mean_load, load_amplitude, phase_deg, angle_deg, cycles, steps_per_cycle,
           lead_in, label, params):
    """An orbit ``R(angle) @ shape(tau)`` (m) with ``N = N_m + N_a sin(tau + phi)``, the last cycle steady.

    ``shape`` maps ``tau`` (rad, array) to the unrotated orbit, shape ``(samples, 2)``. With ``lead_in``
    the first turn is the orbit scaled by ``tau / 2 pi`` (a spiral out of the centre, where the path
    starts unloaded).
    """
    Nm = _checks.positive_scalar("mean_load", mean_load)
    Na = _checks.positive_scalar("load_amplitude", load_amplitude, allow_zero=True)
    phi_deg = _checks.real_scalar("phase_deg", phase_deg)
    angle = _checks.real_scalar("angle_deg", angle_deg)
    if Na > Nm:
        raise ValueError(f"load_amplitude must not exceed mean_load = {Nm:.6g} N (the normal load "
                         f"N_m - N_a would be negative), got {Na:.6g} N")
    _require(reference, "approach")
    tau, steady = _cycles_grid(_checks.size("cycles", cycles) + lead_in, steps_per_cycle)
    xy = shape(tau)
    if lead_in:
        xy *= np.minimum(tau / (2.0 * np.pi), 1.0)[:, None]
    c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
    t = xy @ np.array([[c, s], [-s, c]])  # each row rotated by the angle
    N = np.maximum(Nm + Na * np.sin(tau + np.radians(phi_deg)), 0.0)  # clip round-off below 0 when N_a = N_m
    load = f"N = {Nm:.4g} N" if Na == 0 else f"N = {Nm:.4g} + {Na:.4g} sin(tau + {phi_deg:.0f}°) N"
    return Path(t=t, n=_approach(reference, N), N=N, steady=steady, periodic=True,
                label=f"{label}, {load}" + (f", at {angle:g}°" if angle else ""),
                params={**params, "N_m": Nm, "N_a": Na, "phase": float(np.radians(phi_deg)), "phase_deg": phi_deg,
                        "angle_deg": angle})


def _orbit_size(name, value) -> float:
    """A positive size of an orbit (m), below the plane's limit of 1e100 m."""
    size = _checks.positive_scalar(name, value)
    if size >= PLANE_LIMIT:
        raise ValueError(f"{name} must be below {PLANE_LIMIT:g} m on the contact plane, got {size:.6g} m")
    return size


_ORBIT_PARAMETERS = """    mean_load : float
        ``N_m`` (N), positive.
    load_amplitude : float, default 0
        ``N_a`` (N), ``0 <= N_a <= N_m``: the normal load along the orbit is
        ``N = N_m + N_a sin(tau + phi)``, ``tau`` the orbit's phase (rad).
    phase_deg : float, default 0
        ``phi`` (degrees): the lead of the normal load on the orbit."""

_ORBIT_GRID = """    cycles : int, default 3
        Number of whole orbits; the last is the steady one.
    steps_per_cycle : int, default 360
        Samples per orbit (at least 8)."""


def circle(reference, radius, mean_load, load_amplitude=0.0, phase_deg=0.0, *, cycles: int = 3,
           steps_per_cycle: int = 360) -> Path:
    """A circular orbit ``t = radius (cos tau, sin tau)`` on the contact plane.

    Parameters
    ----------
    reference : object with ``approach(N)``
        Normal law turning ``N`` into the approach ``n`` (e.g. a
        :class:`~microslip.Sphere`, or a model's own normal curve).
    radius : float
        Radius of the orbit (m), positive.
    {load}
    {grid}

    Returns
    -------
    Path
        ``t`` of shape ``(steps, 2)``: one lead-in turn spiralling out from
        the centre (the path starts at ``t = 0``, the contact unloaded), then
        ``cycles`` circles; periodic, the last circle steady. ``params``:
        ``radius`` (m), ``N_m``, ``N_a`` (N), ``phase``, ``phase_deg``,
        ``angle_deg`` (0).
    """
    R = _orbit_size("radius", radius)
    return _orbit(reference, lambda tau: R * np.column_stack([np.cos(tau), np.sin(tau)]), mean_load,
                  load_amplitude, phase_deg, 0.0, cycles, steps_per_cycle, True,
                  f"circle of radius {R * 1e6:.4g} µm", {"radius": R, "t_a": R})


def ellipse(reference, semi_major, semi_minor, mean_load, load_amplitude=0.0, phase_deg=0.0, *,
            angle_deg: float = 0.0, cycles: int = 3, steps_per_cycle: int = 360) -> Path:
    """An elliptical orbit ``(a cos tau, b sin tau)``, its major axis at ``angle_deg`` on the contact plane.

    Parameters
    ----------
    reference : object with ``approach(N)``
        Normal law turning ``N`` into the approach ``n``.
    semi_major, semi_minor : float
        Semi-axes ``a`` and ``b`` (m), positive, ``b <= a``.
    {load}
    angle_deg : float, default 0
        Direction of the major axis (degrees from the first tangential axis).
    {grid}

    Returns
    -------
    Path
        As :func:`circle`: a lead-in turn spiralling out from the centre,
        then ``cycles`` ellipses, the last steady. ``params``: ``semi_major``,
        ``semi_minor`` (m), the load's and ``angle_deg``.
    """
    a = _orbit_size("semi_major", semi_major)
    b = _orbit_size("semi_minor", semi_minor)
    if b > a:
        raise ValueError(f"semi_minor must not exceed semi_major = {a:.6g} m, got {b:.6g} m")
    return _orbit(reference, lambda tau: np.column_stack([a * np.cos(tau), b * np.sin(tau)]), mean_load,
                  load_amplitude, phase_deg, angle_deg, cycles, steps_per_cycle, True,
                  f"ellipse {a * 1e6:.4g} x {b * 1e6:.4g} µm", {"semi_major": a, "semi_minor": b, "t_a": a})


def figure_eight(reference, half_width, half_height, mean_load, load_amplitude=0.0, phase_deg=0.0, *,
                 angle_deg: float = 0.0, cycles: int = 3, steps_per_cycle: int = 360) -> Path:
    """A figure-eight ``(w sin tau, h sin 2 tau)`` (a Lissajous curve 1:2) on the contact plane.

    It passes through the centre twice per orbit, crossing itself there, so
    it needs no lead-in.

    Parameters
    ----------
    reference : object with ``approach(N)``
        Normal law turning ``N`` into the approach ``n``.
    half_width : float
        ``w`` (m), positive: the extent along the figure's long axis.
    half_height : float
        ``h`` (m), positive: the extent across it.
    {load}
    angle_deg : float, default 0
        Direction of the long axis (degrees from the first tangential axis).
    {grid}

    Returns
    -------
    Path
        ``cycles`` figure-eights from ``t = 0``, the last steady.
        ``params``: ``half_width``, ``half_height`` (m), the load's and
        ``angle_deg``.
    """
    w = _orbit_size("half_width", half_width)
    h = _orbit_size("half_height", half_height)
    return _orbit(reference, lambda tau: np.column_stack([w * np.sin(tau), h * np.sin(2.0 * tau)]), mean_load,
                  load_amplitude, phase_deg, angle_deg, cycles, steps_per_cycle, False,
                  f"figure-eight {w * 1e6:.4g} x {h * 1e6:.4g} µm", {"half_width": w, "half_height": h, "t_a": w})


def line(reference, amplitude, mean_load, load_amplitude=0.0, phase_deg=0.0, *, angle_deg: float = 0.0,
         cycles: int = 3, steps_per_cycle: int = 360) -> Path:
    """A straight back-and-forth ``t = amplitude sin(tau) (cos angle, sin angle)`` on the contact plane.

    Every increment is parallel to the line, so the contact responds as along
    one direction: the forces of :func:`variable_load_cycles` (with
    ``cycles``), along the line (to rounding).

    Parameters
    ----------
    reference : object with ``approach(N)``
        Normal law turning ``N`` into the approach ``n``.
    amplitude : float
        ``t_a`` (m), positive.
    {load}
    angle_deg : float, default 0
        Direction of the line (degrees from the first tangential axis).
    {grid}

    Returns
    -------
    Path
        ``cycles`` back-and-forth strokes from ``t = 0``, the last steady.
        ``params``: ``t_a`` (m), the load's and ``angle_deg``.
    """
    ta = _orbit_size("amplitude", amplitude)
    return _orbit(reference, lambda tau: np.column_stack([ta * np.sin(tau), np.zeros_like(tau)]), mean_load,
                  load_amplitude, phase_deg, angle_deg, cycles, steps_per_cycle, False,
                  f"line of amplitude {ta * 1e6:.4g} µm", {"t_a": ta})


for _builder in (circle, ellipse, figure_eight, line):
    if _builder.__doc__:  # not under python -OO
        _builder.__doc__ = _builder.__doc__.format(load=_ORBIT_PARAMETERS.strip(), grid=_ORBIT_GRID.strip())
del _builder


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
