"""The microslip contact model of Gastaldi & Gola: a parallel array of macroslip elements.

Element ``i`` has a tangential stiffness ``kt[i]`` (N/m), a normal stiffness
``kn[i]`` (N/m) and a normal gap ``gaps[i]`` (m). At normal approach ``n``
(m) it carries ``N_i = kn_i * max(n - gaps_i, 0)`` and, through a Coulomb
slider with friction coefficient ``mu``, a tangential force ``|T_i| <= mu N_i``.
The state is the position of each slider (m).

On the contact plane (``t`` with two tangential components) each element is
an isotropic Jenkins slider: its trial force is returned radially onto the
disc ``|T_i| <= mu N_i``; a path along a straight line gives the
one-direction result along that line.

The public objects are

* :class:`MicroslipModel` -- immutable parameters, :meth:`~MicroslipModel.simulate`
  for whole histories and :meth:`~MicroslipModel.trial` for one step at a time,
  along one tangential direction or on the contact plane;
* :class:`State` -- the committed slider positions;
* :class:`Response` and :class:`Step` -- what a march or a trial step returns;
* :class:`Provenance` -- how a tuned model was tuned (kept in its JSON file);
* :class:`BeyondTuningWarning` -- a model driven beyond the load it was tuned for.
"""

from __future__ import annotations

import json
import mmap
import warnings
from dataclasses import dataclass, field, replace
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from .common import _checks
from .kernels import element as _kernels
from .common._io import atomic_write
from .common._version import __version__
from .common.units import unit_factor
from .common.errors import BeyondTuningWarning

OPEN, STICK, SLIP = _kernels.OPEN, _kernels.STICK, _kernels.SLIP

_FORMAT = "microslip.MicroslipModel"
_FORMAT_VERSION = 1
#: the keys of a model file (``provenance`` is optional: hand-built models and older files have none)
_KEYS = ("format", "version", "units", "kt", "kn", "gaps", "mu", "provenance")
#: the kind of unit each parameter of a model file may be given in (its ``units`` entry)
_UNIT_KINDS = {"kt": "stiffness", "kn": "stiffness", "gaps": "length", "mu": "dimensionless"}
_SI = {"kt": "N/m", "kn": "N/m", "gaps": "m", "mu": "-"}
#: relative margin above the tuning approach before a model counts as driven beyond its tuning load
_BEYOND_RTOL = 1e-9
#: largest displacement (m) accepted on the contact plane: the element squares the stretch (1e200 m^2 at most)
PLANE_LIMIT = 1e100


def frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=np.float64, copy=True)
    a.setflags(write=False)
    return a


def _below_plane_limit(name: str, a: np.ndarray) -> None:
    """Refuse displacements (m) on the contact plane at or beyond :data:`PLANE_LIMIT`, naming ``name``."""
    if a.size and float(np.abs(a).max()) >= PLANE_LIMIT:
        k = int(np.argmax(np.abs(a)))
        raise ValueError(f"{name} must stay below {PLANE_LIMIT:g} m in magnitude on the contact plane (the element "
                         f"squares the stretch), got {float(a.ravel()[k]):.6g} m at flat index {k}")


#: bytes in a huge page (x86-64 and aarch64 with 4 KiB pages), which NumPy asks for large arrays
_HUGE_PAGE = 2**21


def _fresh(shape: tuple, dtype=np.float64) -> np.ndarray:
    """An uninitialised array for a march's records; a large one starts on a huge-page boundary, its pages
    faulted in.

    NumPy asks the kernel for huge pages for arrays of 4 MiB and more, but
    the parts of an allocation before its first and after its last 2 MiB
    boundary get 4 KiB pages, each faulted in on its own: 355 faults for the
    77 MB of element forces of 3e5 steps at J = 16, against 38 when the data
    start on a boundary (about 1 ms less). The pages are then faulted in (the
    kernel clears them) in one pass, writing a zero into each: 3.4 ms for
    those 77 MB, where the march's own stores faulting them in one by one,
    between its arithmetic, cost 7 ms more than into memory touched before.
    The array is a view of an allocation up to 4 MiB longer, whose extra
    pages are never touched (no memory behind them).
    """
    dtype = np.dtype(dtype)
    size = int(np.prod(shape)) * dtype.itemsize
    if size < 2 * _HUGE_PAGE:
        return np.empty(shape, dtype)
    raw = np.empty(-(-size // _HUGE_PAGE) * _HUGE_PAGE + _HUGE_PAGE, np.uint8)
    start = -raw.ctypes.data % _HUGE_PAGE
    raw[start:start + size:mmap.PAGESIZE] = 0
    return raw[start:start + size].view(dtype).reshape(shape)


def tangential_history(name: str, value, *, min_steps: int = 1) -> np.ndarray:
    """A tangential history (m): shape ``(steps,)``, or ``(steps, 2)`` on the contact plane; finite."""
    if (type(value) is np.ndarray and value.dtype == np.float64 and value.ndim == 2 and value.shape[1] == 2
            and value.shape[0] >= max(min_steps, 1) and -PLANE_LIMIT < value.min() and value.max() < PLANE_LIMIT):
        return value  # what the checks below accept, in two passes without temporaries (NaN fails both bounds)
    t = _checks.real_array(name, value, min_size=min_steps)
    if not (t.ndim == 1 or (t.ndim == 2 and t.shape[1] == 2)):
        raise ValueError(f"{name} must have shape (steps,) (one tangential direction) or (steps, 2) (its two "
                         f"components on the contact plane), got shape {t.shape}")
    if t.shape[0] < min_steps:
        raise ValueError(f"{name} must have at least {min_steps} samples, got {t.shape[0]}")
    if t.ndim == 2:
        _below_plane_limit(name, t)
    return t


def _plane_point(name: str, value) -> np.ndarray:
    """A point of the contact plane ``(x, y)`` (m), shape (2,)."""
    p = _checks.real_array(name, value)
    if p.shape != (2,):
        raise ValueError(f"{name} must be a number (one tangential direction) or a pair (x, y) on the contact "
                         f"plane (m), got shape {p.shape}")
    _below_plane_limit(name, p)
    return p


@dataclass(frozen=True, eq=False)
class State:
    """Committed state of a microslip array.

    Attributes
    ----------
    sliders : ndarray, shape (J,) or (J, 2)
        Slider position of each element (m): one value per element along
        one tangential direction, a point of the contact plane per element
        (its two components) on the plane. Read-only.
    """

    sliders: np.ndarray

    def __post_init__(self):
        sliders = _checks.real_array("sliders", self.sliders, min_size=1)
        if not (sliders.ndim == 1 or (sliders.ndim == 2 and sliders.shape[1] == 2)):
            raise ValueError(f"sliders must have shape (J,) (one tangential direction) or (J, 2) (the contact "
                             f"plane), got shape {sliders.shape}")
        object.__setattr__(self, "sliders", frozen(sliders))

    @property
    def plane(self) -> bool:
        """True for the state of an array on the contact plane (sliders of shape ``(J, 2)``)."""
        return self.sliders.ndim == 2

    def __repr__(self) -> str:
        return f"State(sliders={np.array2string(self.sliders, precision=4)})"


@dataclass(frozen=True, eq=False)
class Step:
    """Result of one trial step (:meth:`MicroslipModel.trial`).

    Nothing is committed: pass ``step.state`` to the next call to commit it,
    or keep the previous state to discard the trial.

    Attributes
    ----------
    T : float, or ndarray of shape (2,) on the contact plane
        Total tangential force (N).
    N : float
        Total normal force (N).
    Ti : ndarray, shape (J,), or (J, 2) on the plane
        Tangential force of each element (N).
    Ni : ndarray, shape (J,)
        Normal force of each element (N).
    condition : ndarray of int8, shape (J,)
        0 open, 1 stick, 2 slip.
    dT_dt : float, or ndarray of shape (2, 2) on the plane
        Consistent tangent ``dT/dt`` (N/m): the sum of ``kt`` over sticking
        elements; on the plane ``kt I`` per sticking element plus, per
        slipping one, ``(mu N_i / |d_i|) (I - u_i u_i^T)`` with ``d_i`` the
        element's stretch ``t - s_i`` before the step and ``u_i = d_i / |d_i|``
        (sliding along a circle, an element still resists a change of
        direction).
    dT_dn : float, or ndarray of shape (2,) on the plane
        ``dT/dn`` (N/m): the sum of ``sign(T_i) mu kn_i`` over slipping
        elements (``mu kn_i u_i`` on the plane).
    dN_dn : float
        ``dN/dn`` (N/m): the sum of ``kn`` over closed elements.
    state : State
        The state after the step, to commit.
    """

    T: float | np.ndarray
    N: float
    Ti: np.ndarray
    Ni: np.ndarray
    condition: np.ndarray
    dT_dt: float | np.ndarray
    dT_dn: float | np.ndarray
    dN_dn: float
    state: State


@dataclass(frozen=True, eq=False)
class Response:
    """Result of :meth:`MicroslipModel.simulate` over a history of ``steps`` samples.

    On the contact plane every tangential quantity has a trailing axis of
    two components: ``t``, ``T`` of shape ``(steps, 2)``, ``Ti`` of shape
    ``(steps, J, 2)``, the state's sliders ``(J, 2)``.

    Attributes
    ----------
    model : MicroslipModel
        The model that produced it.
    t : ndarray, shape (steps,) or (steps, 2)
        The imposed tangential displacement (m).
    n : ndarray, shape (steps,)
        The imposed normal approach (m).
    T : ndarray, shape (steps,) or (steps, 2)
        Total tangential force (N).
    N : ndarray, shape (steps,)
        Total normal force (N).
    friction_work : ndarray, shape (steps,), or None
        Energy dissipated by friction in each step (J): each element's
        force times its slider's travel (a dot product on the plane),
        summed. Never negative. ``None`` when the march was run with
        ``work=False``.
    Ti : ndarray, shape (steps, J) or (steps, J, 2), or None
        Tangential force of each element (N); ``None`` when the march was
        run with ``per_element=False``.
    condition : ndarray of int8, shape (steps, J), or None
        Condition of each element at each step: 0 open, 1 stick, 2 slip.
    state : State
        The state after the last step; pass it to ``simulate`` to continue.
    """

    model: "MicroslipModel"
    t: np.ndarray
    n: np.ndarray
    T: np.ndarray
    N: np.ndarray
    friction_work: np.ndarray | None
    Ti: np.ndarray | None
    condition: np.ndarray | None
    state: State

    @property
    def Ni(self) -> np.ndarray:
        """Normal force of each element (N), shape ``(steps, J)``."""
        return self.model.element_normal_forces(self.n)

    @property
    def plane(self) -> bool:
        """True when the march ran on the contact plane (``t`` of shape ``(steps, 2)``)."""
        return self.t.ndim == 2

    @property
    def dissipation(self) -> float:
        """Energy dissipated by friction along the record (J), ``sum(friction_work)``.

        Never negative, on any path. Over a closed path that brings the state
        back (a steady cycle) it equals the work ``∮ T dt`` done on the
        contact, up to the discretisation of the path: exactly at constant
        normal approach for a displacement linear between samples, and in
        the limit of fine steps when ``n`` varies too (see :attr:`work`).
        """
        if self.friction_work is None:
            raise ValueError("this response was computed with work=False: run simulate(..., work=True) "
                             "to record the friction work")
        return float(self.friction_work.sum())

    @property
    def work(self) -> float:
        """Work done on the contact along the record, ``∫ T · dt`` (J), by the trapezoidal rule.

        It includes the elastic energy stored at the end; over a steady cycle
        it converges to :attr:`dissipation` as the path is refined. On the
        plane it is the sum of the work of the two components.
        """
        if self.t.shape[0] < 2:
            return 0.0
        return float(np.sum(np.trapezoid(self.T, self.t, axis=0)))

    def plot(self, ax=None, *, label: str | None = None, **kwargs):
        """Plot the tangential force against the tangential displacement.

        On the contact plane: the displacement orbit (``t_y`` against
        ``t_x``, µm) and, next to it, the force orbit (``T_y`` against
        ``T_x``, N) with the friction limit ``mu N`` at the largest normal
        load as a dashed circle; both with equal scales on their two axes
        and the first sample marked.

        Parameters
        ----------
        ax : matplotlib Axes, or a pair of Axes on the plane, optional
            Where to draw; a new figure is made if omitted.
        label : str, optional
            Legend label.
        **kwargs
            Passed to ``Axes.plot``.

        Returns
        -------
        matplotlib.axes.Axes, or ndarray of two Axes on the plane
        """
        import matplotlib.pyplot as plt

        if self.plane:
            return self._plot_orbits(ax, label, **kwargs)
        if ax is None:
            _, ax = plt.subplots(figsize=(5.5, 4))
        ax.plot(self.t * 1e6, self.T, label=label, **kwargs)
        ax.set_xlabel("tangential displacement t (µm)")
        ax.set_ylabel("tangential force T (N)")
        ax.grid(True, alpha=0.3)
        if label:
            ax.legend()
        return ax

    def _plot_orbits(self, axes, label, **kwargs):
        import matplotlib.pyplot as plt

        if axes is None:
            _, axes = plt.subplots(1, 2, figsize=(10, 4.5))
        axes = np.asarray(axes, dtype=object).ravel()
        if axes.size != 2:
            raise ValueError(f"ax must be a pair of Axes on the contact plane (displacement, force), got {axes.size}")
        limit = self.model.mu * float(self.N.max())
        circle = np.linspace(0.0, 2.0 * np.pi, 361)
        axes[1].plot(limit * np.cos(circle), limit * np.sin(circle), color="0.6", ls="--", lw=1,
                     label=f"mu N at the largest load ({limit:.3g} N)")
        for ax, xy, scale, what in ((axes[0], self.t, 1e6, "displacement t (µm)"), (axes[1], self.T, 1.0,
                                                                                     "force T (N)")):
            line, = ax.plot(xy[:, 0] * scale, xy[:, 1] * scale, label=label, **kwargs)
            ax.plot(xy[0, 0] * scale, xy[0, 1] * scale, "o", color=line.get_color(), ms=4)
            name, unit = what.split(" (")
            ax.set_xlabel(f"tangential {name}, x component ({unit}")
            ax.set_ylabel(f"tangential {name}, y component ({unit}")
            ax.set_aspect("equal", adjustable="datalim")
            ax.grid(True, alpha=0.3)
        axes[0].set_title("displacement orbit")
        axes[1].set_title("force orbit")
        axes[1].legend(fontsize="small")
        if label:
            axes[0].legend(fontsize="small")
        return axes


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="seconds")


#: units of the parameters of the usual references, for :meth:`Provenance.describe`
_PARAMETER_UNITS = {"radius": " m", "length": " m", "flat_radius": " m", "edge_radius": " m", "E": " Pa",
                    "normal_load": " N", "max_load": " N"}

_PROVENANCE_KEYS = ("reference", "normal_load", "approach", "points", "mu_source", "load_range", "loops", "notes",
                    "version", "date")


@dataclass(frozen=True)
class Provenance:
    """How a model was tuned, kept with it in its JSON file (SI units).

    :func:`microslip.tune`, :func:`microslip.tune_on_loops` and the command
    line fill it; a model built by hand from its parameters has none.
    ``microslip accuracy`` takes its reference and load from it, and the
    model warns (:class:`BeyondTuningWarning`) when driven beyond
    ``approach``.

    Parameters
    ----------
    reference : dict
        The reference contact: ``{"kind": class name, parameter: value}``
        (e.g. ``{"kind": "Sphere", "radius": 0.005, "E": 2e11, "nu": 0.3,
        "mu": 0.4}``, SI units; nested for a reference built on another).
    normal_load : float
        Tuning load ``N_tot`` (N).
    approach : float
        The reference's normal approach at ``normal_load`` (m): the model
        carries ``normal_load`` there, with every element closed.
    points_t, points_T : sequence of float, shape (J,)
        The tuning points on the reference backbone (m, N).
    mu_source : str
        Where ``mu`` came from (e.g. ``"given with the reference"``,
        ``"fitted from the slip forces"``).
    load_range : (float, float), optional
        ``(N_lo, N_hi)`` (N) when the points were chosen for accuracy over
        that range.
    loops : sequence of str, optional
        The measured loop files tuned on (names as given).
    notes : dict, optional
        Anything else worth keeping, name -> number or text.
    version : str
        Package version that tuned it (default: this one).
    date : str
        When (ISO 8601, UTC; default: now).
    """

    reference: dict
    normal_load: float
    approach: float
    points_t: tuple
    points_T: tuple
    mu_source: str
    load_range: tuple | None = None
    loops: tuple = ()
    notes: dict = field(default_factory=dict)
    version: str = __version__
    date: str = field(default_factory=_now)

    def __post_init__(self):
        if not isinstance(self.reference, dict) or not isinstance(self.reference.get("kind"), str):
            raise TypeError(f"reference must be a dict with a 'kind' (the reference's class name), "
                            f"got {_checks._show(self.reference)}")
        set_ = lambda name, value: object.__setattr__(self, name, value)  # noqa: E731
        set_("reference", json.loads(json.dumps(self.reference)))  # a plain-JSON copy (refuses what is not)
        set_("normal_load", _checks.positive_scalar("normal_load", self.normal_load))
        set_("approach", _checks.positive_scalar("approach", self.approach))
        t = _checks.positive_array("points_t", self.points_t, ndim=1, min_size=1)
        T = _checks.positive_array("points_T", self.points_T, ndim=1, min_size=1)
        if t.size != T.size:
            raise ValueError(f"points_t and points_T must have the same length, got {t.size} and {T.size}")
        set_("points_t", tuple(float(x) for x in t))
        set_("points_T", tuple(float(x) for x in T))
        for name in ("mu_source", "version", "date"):
            if not isinstance(getattr(self, name), str):
                raise TypeError(f"{name} must be a str, got {_checks._show(getattr(self, name))}")
        if self.load_range is not None:
            set_("load_range", _checks.positive_pair("load_range", self.load_range, "(N_lo, N_hi) in N"))
        if isinstance(self.loops, str) or not all(isinstance(x, str) for x in self.loops):
            raise TypeError(f"loops must be a sequence of file names, got {_checks._show(self.loops)}")
        set_("loops", tuple(self.loops))
        if not isinstance(self.notes, dict) or not all(
                isinstance(k, str) and isinstance(v, (str, int, float, bool)) for k, v in self.notes.items()):
            raise TypeError(f"notes must be a dict of name -> number or text, got {_checks._show(self.notes)}")
        set_("notes", dict(self.notes))

    @property
    def kind(self) -> str:
        """Class name of the reference tuned on (e.g. ``'Sphere'``, ``'MeasuredContact'``)."""
        return self.reference["kind"]

    def describe(self) -> str:
        """One sentence: the reference, the load, the points, mu, the version and the date."""
        params = []
        for k, v in self.reference.items():
            if isinstance(v, float):
                params.append(f"{k} = {v:.6g}{_PARAMETER_UNITS.get(k, '')}")
            elif isinstance(v, dict) and "kind" in v and "mu" in v:  # a contact it was built on
                params.append(f"{k}: {v['kind']}" + (f" ({v['law']} law)" if isinstance(v.get("law"), str) else ""))
            elif isinstance(v, str) and k != "kind":
                params.append(f"{k} = {v}")
        text = f"tuned on a {self.kind}" + (f" ({', '.join(params)})" if params else "")
        text += f" at {self.normal_load:.6g} N with {len(self.points_t)} point{'s' * (len(self.points_t) > 1)}"
        if self.load_range is not None:
            text += f" chosen for {self.load_range[0]:.6g}-{self.load_range[1]:.6g} N"
        if self.loops:
            names = [x.replace("\\", "/").rsplit("/", 1)[-1] for x in self.loops]
            text += f", on {len(names)} loop file{'s' * (len(names) > 1)} ({', '.join(names)})"
        return text + f"; mu {self.mu_source}; microslip {self.version}, {self.date}"

    def to_dict(self) -> dict:
        """Plain-JSON form (the ``"provenance"`` block of a model file)."""
        d = {"reference": self.reference, "normal_load": self.normal_load, "approach": self.approach,
             "points": {"t": list(self.points_t), "T": list(self.points_T)}, "mu_source": self.mu_source}
        if self.load_range is not None:
            d["load_range"] = list(self.load_range)
        if self.loops:
            d["loops"] = list(self.loops)
        if self.notes:
            d["notes"] = dict(self.notes)
        d["version"], d["date"] = self.version, self.date
        return d

    @classmethod
    def from_dict(cls, data, where: str = "provenance") -> "Provenance":
        """Rebuild from :meth:`to_dict` output; unknown or missing keys are refused, naming ``where``."""
        if not isinstance(data, dict):
            raise TypeError(f"{where} must be a JSON object, got {_checks._show(data)}")
        _checks.known_keys(where, data, _PROVENANCE_KEYS)
        required = ("reference", "normal_load", "approach", "points", "mu_source", "version", "date")
        missing = [k for k in required if k not in data]
        if missing:
            raise ValueError(f"{where} is missing the key(s) {missing}; it needs {', '.join(required)}")
        points = data["points"]
        if not isinstance(points, dict):
            raise TypeError(f"{where}['points'] must be an object with the lists t (m) and T (N), got "
                            f"{_checks._show(points)}")
        _checks.known_keys(f"{where}['points']", points, ("t", "T"))
        try:
            return cls(reference=data["reference"], normal_load=data["normal_load"], approach=data["approach"],
                       points_t=points.get("t", []), points_T=points.get("T", []), mu_source=data["mu_source"],
                       load_range=data.get("load_range"), loops=data.get("loops", ()),
                       notes=data.get("notes", {}), version=data["version"], date=data["date"])
        except (TypeError, ValueError) as exc:
            raise type(exc)(f"{where}: {exc}") from None


@dataclass(frozen=True, eq=False, repr=False)
class MicroslipModel:
    """A parallel array of ``J`` macroslip elements with normal stiffness and gaps.

    Parameters
    ----------
    kt : array_like, shape (J,)
        Tangential stiffness of each element (N/m), positive.
    kn : array_like, shape (J,)
        Normal stiffness of each element (N/m), positive.
    gaps : array_like, shape (J,)
        Normal approach at which each element comes into contact (m).
    mu : float
        Friction coefficient, positive.
    provenance : Provenance, optional
        How it was tuned (filled by :func:`microslip.tune` and the other
        tunings, kept in its JSON file); ``None`` for a model built by hand.
        Equality ignores it: two models with the same parameters behave
        identically whatever their history (and the same tuning run twice
        differs in its date). When it is known, :meth:`simulate` and
        :meth:`trial` warn (:class:`BeyondTuningWarning`) when the model is
        driven beyond the load it was tuned for.

    Examples
    --------
    >>> import numpy as np
    >>> from microslip import MicroslipModel
    >>> m = MicroslipModel(kt=[1e7, 2e7], kn=[1e8, 1e8], gaps=[0.0, 1e-7], mu=0.4)
    >>> r = m.simulate(t=np.linspace(0, 2e-6, 5), n=np.full(5, 1e-6))
    >>> r.T.round(3).tolist()
    [0.0, 15.0, 30.0, 36.0, 36.0]
    """

    kt: np.ndarray
    kn: np.ndarray
    gaps: np.ndarray
    mu: float
    provenance: Provenance | None = None

    def __post_init__(self):
        kt = _checks.positive_array("kt", self.kt, ndim=1, min_size=1)
        J = kt.size
        kn = _checks.positive_array("kn", self.kn, ndim=1, min_size=1)
        gaps = _checks.real_array("gaps", self.gaps, ndim=1, min_size=1)
        for name, arr in (("kn", kn), ("gaps", gaps)):
            if arr.size != J:
                raise ValueError(f"{name} must have the same length as kt ({J}), got {arr.size}")
        mu = _checks.positive_scalar("mu", self.mu)
        object.__setattr__(self, "kt", frozen(kt))
        object.__setattr__(self, "kn", frozen(kn))
        object.__setattr__(self, "gaps", frozen(gaps))
        object.__setattr__(self, "mu", mu)
        if self.provenance is not None and not isinstance(self.provenance, Provenance):
            raise TypeError(f"provenance must be a microslip Provenance or None, got {type(self.provenance).__name__}")
        # the approach beyond which the model is driven past its tuning load (None: not known)
        object.__setattr__(self, "_beyond", None if self.provenance is None
                           else self.provenance.approach * (1.0 + _BEYOND_RTOL))
        object.__setattr__(self, "_warned", False)

    def with_provenance(self, provenance: Provenance | None) -> "MicroslipModel":
        """The same model with another :class:`Provenance` (or none)."""
        return replace(self, provenance=provenance)

    def _warn_beyond(self, n_max: float, stacklevel: int) -> None:
        p = self.provenance
        warnings.warn(
            f"the normal approach reaches {n_max:.4g} m, where this model carries {float(self.normal_force(n_max)):.4g} N: "
            f"beyond the load it was tuned for ({p.normal_load:.4g} N, approach {p.approach:.4g} m), every element "
            f"is closed and the array only extrapolates linearly; tune it at the highest load it is to meet",
            BeyondTuningWarning, stacklevel=stacklevel + 1)

    # -- description -------------------------------------------------------
    @property
    def elements(self) -> int:
        """Number of elements ``J``."""
        return self.kt.size

    def __repr__(self) -> str:
        return (f"MicroslipModel(J={self.elements}, mu={self.mu:g}, "
                f"kt_total={self.kt.sum():.4g} N/m, kn_total={self.kn.sum():.4g} N/m, "
                f"gaps=[{self.gaps.min():.4g} .. {self.gaps.max():.4g}] m)")

    def __eq__(self, other) -> bool:
        """Same parameters ``kt``, ``kn``, ``gaps``, ``mu``; the provenance is not compared (see the class)."""
        if not isinstance(other, MicroslipModel):
            return NotImplemented
        return (self.mu == other.mu and np.array_equal(self.kt, other.kt)
                and np.array_equal(self.kn, other.kn) and np.array_equal(self.gaps, other.gaps))

    __hash__ = None

    # -- static curves -----------------------------------------------------
    def element_normal_forces(self, n) -> np.ndarray:
        """Normal force of each element at approach ``n``.

        Parameters
        ----------
        n : array_like, shape (...)
            Normal approach (m).

        Returns
        -------
        ndarray, shape (..., J)
            ``kn_i * max(n - gaps_i, 0)`` (N).
        """
        n = _checks.real_array("n", n)
        return self.kn * np.maximum(n[..., None] - self.gaps, 0.0)

    def normal_force(self, n) -> np.ndarray:
        """Total normal force (N) at approach ``n`` (m), same shape as ``n``."""
        return self.element_normal_forces(n).sum(axis=-1)

    def slip_force(self, n) -> np.ndarray:
        """Gross-slip tangential force ``mu * N(n)`` (N) at approach ``n`` (m)."""
        return self.mu * self.normal_force(n)

    def approach(self, N) -> np.ndarray:
        """Normal approach (m) at which the array carries the normal force ``N`` (N).

        Inverts the piecewise-linear, increasing curve :meth:`normal_force`.
        ``N = 0`` returns the first gap.
        """
        N = _checks.positive_array("N", N, allow_zero=True)
        order = np.argsort(self.gaps)
        g, k = self.gaps[order], self.kn[order]
        slope = np.cumsum(k)  # slope of the curve beyond each gap
        Nk = np.concatenate([[0.0], np.cumsum(slope[:-1] * np.diff(g))])  # force at each gap
        j = np.searchsorted(Nk, N, side="right") - 1
        return g[j] + (N - Nk[j]) / slope[j]

    def backbone(self, t, n) -> np.ndarray:
        """Virgin tangential force (N) at displacement ``t`` (m) and constant approach ``n`` (m).

        ``sum_i sign(t) min(kt_i |t|, mu N_i)``; ``t`` and ``n`` broadcast.
        """
        t = _checks.real_array("t", t)
        _checks.broadcast(t=t, n=_checks.real_array("n", n))
        Ni = self.element_normal_forces(n)
        t = np.asarray(t)[..., None]
        return (np.sign(t) * np.minimum(self.kt * np.abs(t), self.mu * Ni)).sum(axis=-1)

    # -- marching ----------------------------------------------------------
    def initial_state(self, t0=0.0) -> State:
        """State with every slider at ``t0``: all elements unloaded at ``t = t0``.

        Parameters
        ----------
        t0 : float, or array_like of shape (2,)
            Tangential displacement (m); a pair ``(tx, ty)`` gives the state
            of the array on the contact plane (sliders of shape ``(J, 2)``).
        """
        if np.ndim(t0) == 0:
            return State(np.full(self.elements, _checks.real_scalar("t0", t0)))
        t0 = _plane_point("t0", t0)
        return State(np.tile(t0, (self.elements, 1)))

    def _check_state(self, state, plane: bool = False) -> np.ndarray:
        shape = (self.elements, 2) if plane else (self.elements,)
        if state is None:
            return np.zeros(shape)
        if not isinstance(state, State):
            raise TypeError(f"state must be a microslip State (from a Response or Step), got {type(state).__name__}")
        if state.sliders.shape[0] != self.elements:
            raise ValueError(f"state has {state.sliders.shape[0]} sliders, this model has J = {self.elements}")
        if state.plane != plane:
            raise ValueError(
                f"state has sliders of shape {state.sliders.shape}, " + (
                    f"one tangential direction; t on the contact plane needs a state of shape {shape} (from a "
                    f"march on the plane, or initial_state((tx, ty)))" if plane else
                    f"on the contact plane; t along one direction needs a state of shape {shape}"))
        if plane:
            _below_plane_limit("state", state.sliders)
        return np.array(state.sliders)

    def simulate(self, t, n, state: State | None = None, *, per_element: bool = True,
                 work: bool = True) -> Response:
        """March the array through a history of displacements.

        Parameters
        ----------
        t : array_like, shape (steps,) or (steps, 2)
            Tangential relative displacement (m): along one direction, or its
            two components in the contact plane. On the plane each element
            is an isotropic Jenkins slider (its trial force returned radially
            onto the disc ``|T_i| <= mu N_i``, an open element's slider
            following ``t``), and ``|t|`` must stay below 1e100 m.
        n : array_like, shape (steps,) or scalar
            Normal approach (m); a scalar is held constant.
        state : State, optional
            State to start from (``Response.state`` of an earlier call to
            continue it exactly; sliders of shape ``(J, 2)`` on the plane).
            Default: every slider at ``t = 0``, so an element in contact at
            the first sample carries ``kt_i * t[0]`` (capped by friction).
        per_element : bool, default True
            Record each element's force and condition. ``False`` records only
            the totals, which is faster for long histories of large arrays.
        work : bool, default True
            Record the friction work of each step (``Response.friction_work``,
            ``Response.dissipation``). ``False`` saves about a third of the
            time of a march that records only totals (along one direction;
            on the plane the work is computed anyway and only its sum is
            saved).

        Returns
        -------
        Response
            Forces in N, shapes ``(steps,)`` and ``(steps, J)``; on the plane
            ``T`` of shape ``(steps, 2)`` and ``Ti`` of shape ``(steps, J, 2)``.

        Warns
        -----
        BeyondTuningWarning
            Once per call, when a model with a :class:`Provenance` is driven
            beyond the approach of the load it was tuned for.
        """
        t = tangential_history("t", t)
        plane = t.ndim == 2
        n = _checks.real_array("n", n)
        per_element, work = _checks.flag("per_element", per_element), _checks.flag("work", work)
        if n.ndim == 0:
            top = float(n)
            n = np.full(t.shape[:1], top)
        elif n.shape != t.shape[:1]:
            raise ValueError(f"n must be a scalar or have the same shape as t {t.shape}, got {n.shape}"
                             if not plane else
                             f"n must be a scalar or have one value per sample of t ({t.shape[0]},), got {n.shape}")
        else:
            top = None  # its largest approach, only when there is a tuning load to compare it with
        s = self._check_state(state, plane)
        if self._beyond is not None:
            top = float(n.max()) if top is None else top
            if top > self._beyond:
                self._warn_beyond(top, 2)
        steps = t.shape[0]
        T = _fresh(t.shape)
        N = _fresh((steps,))
        W = _fresh((steps,)) if work else _kernels.NO_WORK
        if per_element:
            Ti = _fresh((steps, self.elements) + t.shape[1:])
            cond = _fresh((steps, self.elements), np.int8)
        else:
            Ti = _kernels.NO_PLANE_ELEMENTS if plane else _kernels.NO_ELEMENTS
            cond = _kernels.NO_CONDITIONS
        march = _kernels.march_plane if plane else _kernels.march
        march(self.kt, self.kn, self.gaps, self.mu, t, n, s, T, N, W, Ti, cond)
        return Response(self, t, n, T, N, W if work else None, Ti if per_element else None,
                        cond if per_element else None, State(s))

    def trial(self, state: State | None, t, n: float) -> Step:
        """One trial step from a committed state; nothing is changed.

        Parameters
        ----------
        state : State or None
            Committed state (None: every slider at ``t = 0``).
        t : float, or array_like of shape (2,)
            Tangential displacement at the end of the step (m); a pair
            ``(tx, ty)`` on the contact plane (then ``state`` is a state on
            the plane).
        n : float
            Normal approach at the end of the step (m).

        Returns
        -------
        Step
            Forces (N), consistent tangent (N/m; on the plane ``dT_dt`` of
            shape ``(2, 2)`` and ``dT_dn`` of shape ``(2,)``) and the trial
            state.

        Warns
        -----
        BeyondTuningWarning
            The first time a model with a :class:`Provenance` is stepped
            beyond its tuning approach (once per model object).
        """
        plane = np.ndim(t) != 0
        t = _plane_point("t", t) if plane else _checks.real_scalar("t", t)
        n = _checks.real_scalar("n", n)
        s = self._check_state(state, plane)
        if self._beyond is not None and n > self._beyond and not self._warned:
            object.__setattr__(self, "_warned", True)  # called per step inside solvers: once per model
            self._warn_beyond(n, 2)
        if plane:
            return self._trial_plane(s, t, n)
        T, N = np.empty(1), np.empty(1)
        Ti = np.empty((1, self.elements))
        cond = np.empty((1, self.elements), dtype=np.int8)
        _kernels.march(self.kt, self.kn, self.gaps, self.mu, np.array([t]), np.array([n]), s, T, N,
                       _kernels.NO_WORK, Ti, cond)  # the one return mapping, on one sample
        Ti, cond = Ti[0], cond[0]
        stick, slipping = cond == STICK, cond == SLIP
        return Step(
            T=float(T[0]), N=float(N[0]), Ti=Ti, Ni=self.kn * np.maximum(n - self.gaps, 0.0), condition=cond,
            dT_dt=float(self.kt[stick].sum()),
            dT_dn=float((np.sign(Ti) * self.mu * self.kn)[slipping].sum()),
            dN_dn=float(self.kn[cond != OPEN].sum()),
            state=State(s),
        )

    def _trial_plane(self, s: np.ndarray, t: np.ndarray, n: float) -> Step:
        tangent = np.empty(5)  # Kxx, Kxy, Kyy, Dx, Dy at the committed state, before the step moves it
        _kernels.plane_tangents(self.kt, self.kn, self.gaps, self.mu, t[0], t[1], n, s, tangent)
        T, N = np.empty((1, 2)), np.empty(1)
        Ti = np.empty((1, self.elements, 2))
        cond = np.empty((1, self.elements), dtype=np.int8)
        _kernels.march_plane(self.kt, self.kn, self.gaps, self.mu, t[None, :], np.array([n]), s, T, N,
                             _kernels.NO_WORK, Ti, cond)
        cond = cond[0]
        return Step(
            T=T[0], N=float(N[0]), Ti=Ti[0], Ni=self.kn * np.maximum(n - self.gaps, 0.0), condition=cond,
            dT_dt=np.array([[tangent[0], tangent[1]], [tangent[1], tangent[2]]]), dT_dn=tangent[3:].copy(),
            dN_dn=float(self.kn[cond != OPEN].sum()), state=State(s))

    # -- persistence -------------------------------------------------------
    def to_dict(self) -> dict:
        """Plain-JSON form: ``{"format", "version", "units", "kt", "kn", "gaps", "mu"}`` and ``"provenance"`` if known."""
        d = {
            "format": _FORMAT,
            "version": _FORMAT_VERSION,
            "units": dict(_SI),
            "kt": self.kt.tolist(),
            "kn": self.kn.tolist(),
            "gaps": self.gaps.tolist(),
            "mu": self.mu,
        }
        if self.provenance is not None:
            d["provenance"] = self.provenance.to_dict()
        return d

    @classmethod
    def from_dict(cls, data: dict, *, where: str = "data") -> "MicroslipModel":
        """Rebuild a model from :meth:`to_dict` output.

        Every key is checked: an unknown one is refused (naming it, a close
        spelling and the accepted keys), never ignored. ``units`` may give
        other units for ``kt``, ``kn`` (e.g. ``"N/um"``) and ``gaps`` (e.g.
        ``"um"``); the values are converted to SI. ``where`` names the data
        in messages (:meth:`load` passes the file).
        """
        if not isinstance(data, dict):
            raise TypeError(f"{where} must be a dict from MicroslipModel.to_dict(), got {type(data).__name__}")
        _checks.known_keys(where, data, _KEYS)
        fmt = data.get("format", _FORMAT)
        if fmt != _FORMAT:
            raise ValueError(f"{where}['format'] must be {_FORMAT!r}, got {fmt!r}")
        version = data.get("version", _FORMAT_VERSION)
        if version != _FORMAT_VERSION:
            raise ValueError(f"{where}['version'] must be {_FORMAT_VERSION}, got {version!r}")
        missing = [k for k in ("kt", "kn", "gaps", "mu") if k not in data]
        if missing:
            raise ValueError(f"{where} is missing the key(s) {missing}; expected kt, kn, gaps, mu")
        factors = _unit_factors(data.get("units", {}), where)
        values = {}
        for key in ("kt", "kn", "gaps", "mu"):
            name = key if where == "data" else f"{where}: {key}"
            values[key] = (_checks.real_array(name, data[key]) if key != "mu" else _checks.real_scalar(name, data[key]))
            values[key] = values[key] * factors[key]
        provenance = data.get("provenance")
        if provenance is not None:
            provenance = Provenance.from_dict(provenance, where=f"{where}['provenance']")
        try:
            return cls(**values, provenance=provenance)
        except (TypeError, ValueError) as exc:
            if where == "data":
                raise
            raise type(exc)(f"{where}: {exc}") from None

    def save(self, path) -> Path:
        """Write the model as JSON to ``path`` (atomically). Returns the path."""
        path = _checks.file_path("path", path)
        return atomic_write(path, json.dumps(self.to_dict(), indent=2) + "\n")

    @classmethod
    def load(cls, path) -> "MicroslipModel":
        """Read a model written by :meth:`save` (messages name the file)."""
        path = _checks.file_path("path", path)
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except FileNotFoundError:
            raise FileNotFoundError(f"model file {str(path)!r} does not exist") from None
        except IsADirectoryError:
            raise IsADirectoryError(f"model file {str(path)!r} is a folder, not a file") from None
        except (json.JSONDecodeError, UnicodeDecodeError) as exc:
            raise ValueError(f"model file {str(path)!r} is not valid JSON: {exc}") from None
        return cls.from_dict(data, where=f"model file {str(path)!r}")


def _unit_factors(units, where: str) -> dict:
    """SI factor of each parameter from a model file's ``units`` entry (absent: SI)."""
    if not isinstance(units, dict):
        raise TypeError(f"{where}['units'] must be an object such as {_SI}, got {_checks._show(units)}")
    _checks.known_keys(f"{where}['units']", units, _UNIT_KINDS)
    factors = {}
    for key, kind in _UNIT_KINDS.items():
        unit = units.get(key, _SI[key])
        if not isinstance(unit, str):
            raise TypeError(f"{where}['units']['{key}'] must be a unit symbol such as {_SI[key]!r}, got {unit!r}")
        try:
            factors[key] = unit_factor(unit, kind)
        except ValueError as exc:
            raise ValueError(f"{where}['units']['{key}']: {exc}") from None
    return factors
