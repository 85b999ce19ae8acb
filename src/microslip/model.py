"""The microslip contact model of Gastaldi & Gola: a parallel array of macroslip elements.

Element ``i`` has a tangential stiffness ``kt[i]`` (N/m), a normal stiffness
``kn[i]`` (N/m) and a normal gap ``gaps[i]`` (m). At normal approach ``n``
(m) it carries ``N_i = kn_i * max(n - gaps_i, 0)`` and, through a Coulomb
slider with friction coefficient ``mu``, a tangential force ``|T_i| <= mu N_i``.
The state is the position of each slider (m).

The public objects are

* :class:`MicroslipModel` -- immutable parameters, :meth:`~MicroslipModel.simulate`
  for whole histories and :meth:`~MicroslipModel.trial` for one step at a time;
* :class:`State` -- the committed slider positions;
* :class:`Response` and :class:`Step` -- what a march or a trial step returns.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .common import _checks
from . import _kernels
from .common._io import atomic_write

OPEN, STICK, SLIP = _kernels.OPEN, _kernels.STICK, _kernels.SLIP

_FORMAT = "microslip.MicroslipModel"
_FORMAT_VERSION = 1


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=np.float64, copy=True)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class State:
    """Committed state of a microslip array.

    Attributes
    ----------
    sliders : ndarray, shape (J,)
        Slider position of each element (m). Read-only.
    """

    sliders: np.ndarray

    def __post_init__(self):
        object.__setattr__(self, "sliders", _frozen(_checks.real_array("sliders", self.sliders, ndim=1,
                                                                       min_size=1)))

    def __repr__(self) -> str:
        return f"State(sliders={np.array2string(self.sliders, precision=4)})"


@dataclass(frozen=True, eq=False)
class Step:
    """Result of one trial step (:meth:`MicroslipModel.trial`).

    Nothing is committed: pass ``step.state`` to the next call to commit it,
    or keep the previous state to discard the trial.

    Attributes
    ----------
    T, N : float
        Total tangential and normal force (N).
    Ti, Ni : ndarray, shape (J,)
        Force of each element (N).
    condition : ndarray of int8, shape (J,)
        0 open, 1 stick, 2 slip.
    dT_dt, dT_dn, dN_dn : float
        Consistent tangent of the step (N/m): ``dT/dt`` is the sum of ``kt``
        over sticking elements, ``dT/dn`` the sum of ``sign(T_i) mu kn_i`` over
        slipping elements, ``dN/dn`` the sum of ``kn`` over closed elements.
    state : State
        The state after the step, to commit.
    """

    T: float
    N: float
    Ti: np.ndarray
    Ni: np.ndarray
    condition: np.ndarray
    dT_dt: float
    dT_dn: float
    dN_dn: float
    state: State


@dataclass(frozen=True, eq=False)
class Response:
    """Result of :meth:`MicroslipModel.simulate` over a history of ``steps`` samples.

    Attributes
    ----------
    model : MicroslipModel
        The model that produced it.
    t, n : ndarray, shape (steps,)
        The imposed tangential displacement and normal approach (m).
    T, N : ndarray, shape (steps,)
        Total tangential and normal force (N).
    friction_work : ndarray, shape (steps,), or None
        Energy dissipated by friction in each step (J): each element's
        force times its slider's travel, summed. Never negative. ``None``
        when the march was run with ``work=False``.
    Ti : ndarray, shape (steps, J), or None
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
        """Work done on the contact along the record, ``∫ T dt`` (J), by the trapezoidal rule.

        It includes the elastic energy stored at the end; over a steady cycle
        it converges to :attr:`dissipation` as the path is refined.
        """
        return float(np.trapezoid(self.T, self.t)) if self.t.size > 1 else 0.0

    def plot(self, ax=None, *, label: str | None = None, **kwargs):
        """Plot the tangential force against the tangential displacement.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw; a new figure is made if omitted.
        label : str, optional
            Legend label.
        **kwargs
            Passed to ``Axes.plot``.

        Returns
        -------
        matplotlib.axes.Axes
        """
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(5.5, 4))
        ax.plot(self.t * 1e6, self.T, label=label, **kwargs)
        ax.set_xlabel("tangential displacement t (µm)")
        ax.set_ylabel("tangential force T (N)")
        ax.grid(True, alpha=0.3)
        if label:
            ax.legend()
        return ax


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

    def __post_init__(self):
        kt = _checks.positive_array("kt", self.kt, ndim=1, min_size=1)
        J = kt.size
        kn = _checks.positive_array("kn", self.kn, ndim=1, min_size=1)
        gaps = _checks.real_array("gaps", self.gaps, ndim=1, min_size=1)
        for name, arr in (("kn", kn), ("gaps", gaps)):
            if arr.size != J:
                raise ValueError(f"{name} must have the same length as kt ({J}), got {arr.size}")
        mu = _checks.positive_scalar("mu", self.mu)
        object.__setattr__(self, "kt", _frozen(kt))
        object.__setattr__(self, "kn", _frozen(kn))
        object.__setattr__(self, "gaps", _frozen(gaps))
        object.__setattr__(self, "mu", mu)

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
    def initial_state(self, t0: float = 0.0) -> State:
        """State with every slider at ``t0`` (m): all elements unloaded at ``t = t0``."""
        t0 = _checks.real_scalar("t0", t0)
        return State(np.full(self.elements, t0))

    def _check_state(self, state) -> np.ndarray:
        if state is None:
            return np.zeros(self.elements)
        if not isinstance(state, State):
            raise TypeError(f"state must be a microslip State (from a Response or Step), got {type(state).__name__}")
        if state.sliders.shape != (self.elements,):
            raise ValueError(f"state has {state.sliders.size} sliders, this model has J = {self.elements}")
        return np.array(state.sliders)

    def simulate(self, t, n, state: State | None = None, *, per_element: bool = True,
                 work: bool = True) -> Response:
        """March the array through a history of displacements.

        Parameters
        ----------
        t : array_like, shape (steps,)
            Tangential relative displacement (m).
        n : array_like, shape (steps,) or scalar
            Normal approach (m); a scalar is held constant.
        state : State, optional
            State to start from (``Response.state`` of an earlier call to
            continue it exactly). Default: every slider at ``t = 0``, so an
            element in contact at the first sample carries ``kt_i * t[0]``
            (capped by friction).
        per_element : bool, default True
            Record each element's force and condition. ``False`` records only
            the totals, which is faster for long histories of large arrays.
        work : bool, default True
            Record the friction work of each step (``Response.friction_work``,
            ``Response.dissipation``). ``False`` saves about a third of the
            time of a march that records only totals.

        Returns
        -------
        Response
            Forces in N, shapes ``(steps,)`` and ``(steps, J)``.
        """
        t = _checks.real_array("t", t, ndim=1, min_size=1)
        n = _checks.real_array("n", n)
        per_element, work = _checks.flag("per_element", per_element), _checks.flag("work", work)
        if n.ndim == 0:
            n = np.full(t.shape, float(n))
        elif n.shape != t.shape:
            raise ValueError(f"n must be a scalar or have the same shape as t {t.shape}, got {n.shape}")
        s = self._check_state(state)
        steps = t.size
        T = np.empty(steps)
        N = np.empty(steps)
        W = np.empty(steps) if work else _kernels.NO_WORK
        if per_element:
            Ti = np.empty((steps, self.elements))
            cond = np.empty((steps, self.elements), dtype=np.int8)
        else:
            Ti, cond = _kernels.NO_ELEMENTS, _kernels.NO_CONDITIONS
        _kernels.march(self.kt, self.kn, self.gaps, self.mu, t, n, s, T, N, W, Ti, cond)
        return Response(self, t, n, T, N, W if work else None, Ti if per_element else None,
                        cond if per_element else None, State(s))

    def trial(self, state: State | None, t: float, n: float) -> Step:
        """One trial step from a committed state; nothing is changed.

        Parameters
        ----------
        state : State or None
            Committed state (None: every slider at ``t = 0``).
        t, n : float
            Tangential displacement and normal approach at the end of the step (m).

        Returns
        -------
        Step
            Forces (N), consistent tangent (N/m) and the trial state.
        """
        t = _checks.real_scalar("t", t)
        n = _checks.real_scalar("n", n)
        s = self._check_state(state)
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

    # -- persistence -------------------------------------------------------
    def to_dict(self) -> dict:
        """Plain-JSON form: ``{"format", "version", "units", "kt", "kn", "gaps", "mu"}``."""
        return {
            "format": _FORMAT,
            "version": _FORMAT_VERSION,
            "units": {"kt": "N/m", "kn": "N/m", "gaps": "m", "mu": "-"},
            "kt": self.kt.tolist(),
            "kn": self.kn.tolist(),
            "gaps": self.gaps.tolist(),
            "mu": self.mu,
        }

    @classmethod
    def from_dict(cls, data: dict) -> "MicroslipModel":
        """Rebuild a model from :meth:`to_dict` output (checks format and keys)."""
        if not isinstance(data, dict):
            raise TypeError(f"data must be a dict from MicroslipModel.to_dict(), got {type(data).__name__}")
        fmt = data.get("format", _FORMAT)
        if fmt != _FORMAT:
            raise ValueError(f"data['format'] must be {_FORMAT!r}, got {fmt!r}")
        version = data.get("version", _FORMAT_VERSION)
        if version != _FORMAT_VERSION:
            raise ValueError(f"data['version'] must be {_FORMAT_VERSION}, got {version!r}")
        missing = [k for k in ("kt", "kn", "gaps", "mu") if k not in data]
        if missing:
            raise ValueError(f"data is missing the key(s) {missing}; expected kt, kn, gaps, mu")
        return cls(kt=data["kt"], kn=data["kn"], gaps=data["gaps"], mu=data["mu"])

    def save(self, path) -> Path:
        """Write the model as JSON to ``path`` (atomically). Returns the path."""
        path = _checks.file_path("path", path)
        return atomic_write(path, json.dumps(self.to_dict(), indent=2) + "\n")

    @classmethod
    def load(cls, path) -> "MicroslipModel":
        """Read a model written by :meth:`save`."""
        path = _checks.file_path("path", path)
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except FileNotFoundError:
            raise FileNotFoundError(f"model file {str(path)!r} does not exist") from None
        except json.JSONDecodeError as exc:
            raise ValueError(f"model file {str(path)!r} is not valid JSON: {exc}") from None
        return cls.from_dict(data)
