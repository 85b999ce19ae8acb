"""Alternating frequency--time (AFT) contact forces with exact Jacobians.

A periodic history of the contact's tangential displacement ``t`` and normal
approach ``n`` is given by its Fourier coefficients (static term plus ``H``
harmonics, layout ``[c0, a1, b1, ..., aH, bH]`` of
``c0 + sum_h a_h cos(h tau) + b_h sin(h tau)``, ``tau = omega time``). The
contact is marched over ``samples`` points per period, period after period,
until its state repeats exactly, and the periodic forces ``T`` and ``N`` are
returned as Fourier coefficients, with their derivatives with respect to the
coefficients of ``t`` and ``n``, carried through the march (see
:mod:`microslip.kernels.aft` for the algorithm).

History convention: the contact is taken closed at ``t = 0`` with no
tangential force (every slider at 0). The static part of the motion is
applied first, as one monotonic step from that virgin state at the static
normal approach; the periodic motion follows. An element that never slips
keeps the force it took in that static step, as a real contact does.

Number of samples. At least ``2H + 1`` samples are needed for the kept
harmonics to be distinguishable. The contact force has kinks (stick--slip
transitions), so its harmonics decay like ``1/j^2``, and harmonic ``Ns - h``
folds onto ``h``; each kink is also located only to within one sample. Both
errors fall like ``1/Ns^2``. :func:`default_samples` takes ``16 H`` rounded
up to a power of two (and at least 32; one sample for a constant, H = 0): the aliased part of the highest kept
harmonic is then about ``(1/15)^2`` of its neighbour beyond ``Ns``, and the
first harmonic of a Jenkins element is within about 1e-3 of its closed form
(the test suite checks the ``1/Ns^2`` convergence).
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import accumulate
from typing import Sequence

import numpy as np

from ..common import _checks
from ..common.errors import NotPeriodicError, UnderResolvedWarning, deprecated
from ..model import PLANE_LIMIT, MicroslipModel
from ..kernels import aft as _aft, aft_plane as _aft_plane

MAX_PERIODS = 1000
#: harmonics kept at most (each adds two unknowns per DOF; a response with kinks needs tens, not hundreds)
MAX_HARMONICS = 256
#: samples x (2H + 1) at most: the AFT's tables and work arrays hold about seven arrays of that many
#: numbers (235 MB at the limit), so a slip such as samples = 10**7 is refused before any allocation
MAX_TABLE = 2**22


def default_samples(harmonics: int) -> int:
    """Default number of time samples per period for ``harmonics`` harmonics.

    ``16 H`` rounded up to a power of two, at least 32 (128 for ``H = 7``);
    1 for ``H = 0`` (a constant needs one sample). See the module docstring for why.
    """
    H = check_harmonics(harmonics, minimum=0)
    if H == 0:
        return 1
    return max(32, 1 << (16 * H - 1).bit_length())  # bit_length: ceil(log2) in integers


def check_harmonics(harmonics, *, name: str = "harmonics", minimum: int = 1) -> int:
    """``harmonics`` checked: an integer from ``minimum`` to :data:`MAX_HARMONICS`."""
    return _checks.size(name, harmonics, minimum=minimum, maximum=MAX_HARMONICS)


def check_table(name: str, samples: int, harmonics: int) -> None:
    """Refuse ``samples`` per period whose tables for ``harmonics`` would exceed :data:`MAX_TABLE` numbers."""
    limit = MAX_TABLE // (2 * harmonics + 1)
    if samples > limit:
        raise ValueError(f"{name} must be at most {limit} with harmonics = {harmonics} (the tables of a period "
                         f"hold {name} x (2 harmonics + 1) numbers, at most {MAX_TABLE}), got {samples}")


def check_samples(samples, harmonics: int) -> int:
    """``samples`` checked against ``harmonics`` (``None``: :func:`default_samples`).

    At least ``2 harmonics + 1``, and small enough for :func:`check_table`.
    """
    if samples is None:
        return default_samples(harmonics)
    Ns = _checks.size("samples", samples, minimum=1)
    if Ns < 2 * harmonics + 1:
        raise ValueError(f"samples must be at least 2 * harmonics + 1 = {2 * harmonics + 1} "
                         f"to resolve {harmonics} harmonics, got {Ns}")
    check_table("samples", Ns, harmonics)
    return Ns


def harmonics_of(name: str, coefficients) -> tuple[np.ndarray, int]:
    """Check a Fourier coefficient array ``(..., 2H+1)``; returns it and ``H``."""
    c = _checks.real_array(name, coefficients)
    if c.ndim == 0 or c.shape[-1] % 2 == 0:
        raise ValueError(f"{name} must hold 2H + 1 Fourier coefficients [c0, a1, b1, ..., aH, bH] "
                         f"along its last axis, got shape {c.shape}")
    return c, check_harmonics((c.shape[-1] - 1) // 2, name=f"{name}: the number of harmonics H", minimum=0)


def time_samples(coefficients, samples: int) -> np.ndarray:
    """Values at ``tau_k = 2 pi k / samples`` of the Fourier series with these coefficients.

    Parameters
    ----------
    coefficients : array_like, shape (..., 2H+1)
        ``[c0, a1, b1, ..., aH, bH]``.
    samples : int
        Number of samples per period.

    Returns
    -------
    ndarray, shape (..., samples)
    """
    c, H = harmonics_of("coefficients", coefficients)
    Ns = check_samples(samples, H)
    E = _aft.tables(H, Ns)[0]
    return c @ E.T


def synthesise(coefficients, samples: int) -> np.ndarray:
    """Deprecated name of :func:`time_samples` (the same function; warns)."""
    deprecated("microslip.frequency.synthesise", "microslip.frequency.time_samples")
    return time_samples(coefficients, samples)


@dataclass(frozen=True, eq=False)
class AFTResult:
    """Periodic contact forces and their derivatives (from :func:`aft`).

    With ``nb = 2H + 1`` coefficients and, for :func:`aft_batch`, a leading
    axis of length ``nc`` (one row per contact).

    Attributes
    ----------
    T, N : ndarray, shape ([nc,] nb)
        Fourier coefficients of the tangential and normal force (N).
    dT_dt, dT_dn, dN_dn : ndarray, shape ([nc,] nb, nb)
        Derivatives of the coefficients of ``T`` (resp. ``N``) with respect
        to those of ``t`` (resp. ``n``) (N/m). ``dN/dt`` is zero.
    periods : int or ndarray of int
        Periods marched until the state repeated (the last one is periodic).
    samples : int
        Time samples per period.
    """

    T: np.ndarray
    N: np.ndarray
    dT_dt: np.ndarray
    dT_dn: np.ndarray
    dN_dn: np.ndarray
    periods: int | np.ndarray
    samples: int

    @property
    def harmonics(self) -> int:
        """Number of harmonics ``H``."""
        return (self.T.shape[-1] - 1) // 2

    def dissipation(self, t) -> np.ndarray:
        """Energy dissipated per cycle by the tangential force along ``t`` (J).

        ``W = pi sum_h h (A_h b_h - B_h a_h)`` with ``T = A cos + B sin`` and
        ``t = a cos + b sin``: the work of the harmonics kept (the normal
        force is elastic and does no net work).

        Parameters
        ----------
        t : array_like, shape ([nc,] nb)
            The tangential displacement coefficients (m) given to :func:`aft`.
        """
        t, _ = harmonics_of("t", t)
        return cycle_work(self.T, t)


def cycle_work(force, displacement) -> np.ndarray:
    """Work per cycle of a periodic force along a periodic displacement (J).

    Parameters
    ----------
    force, displacement : array_like, shape (..., 2H+1)
        Fourier coefficients (N and m).

    Returns
    -------
    ndarray, shape (...)
        ``pi sum_h h (F_a,h x_b,h - F_b,h x_a,h)``.
    """
    F = _checks.real_array("force", force)
    x = _checks.real_array("displacement", displacement)
    try:
        np.broadcast_shapes(F.shape, x.shape)
        same = F.shape[-1:] == x.shape[-1:]
    except ValueError:
        same = False
    if not same:
        raise ValueError(f"force and displacement must have the same shape (..., 2H+1) (or shapes that "
                         f"broadcast), got {F.shape} and {x.shape}")
    if F.ndim == 0 or F.shape[-1] % 2 == 0:
        raise ValueError(f"force and displacement must hold 2H+1 coefficients [c0, a1, b1, ...] in their last axis "
                         f"(an odd number), got shape {F.shape}")
    H = (F.shape[-1] - 1) // 2
    h = np.arange(1, H + 1)
    return np.pi * np.sum(h * (F[..., 1::2] * x[..., 2::2] - F[..., 2::2] * x[..., 1::2]), axis=-1)


def _check_model(name: str, model) -> MicroslipModel:
    if not isinstance(model, MicroslipModel):
        raise TypeError(f"{name} must be a microslip MicroslipModel, got {type(model).__name__}")
    return model


def check_periodic(periods, max_periods: int) -> None:
    """Raise :class:`NotPeriodicError` if a kernel's period count (int or array) is negative."""
    if periods >= 0 if isinstance(periods, int) else not np.count_nonzero(periods < 0):
        return  # periodic: the fast path of every call
    bad = np.flatnonzero(np.atleast_1d(periods) < 0)
    if bad.size:
        raise NotPeriodicError(
            f"the state of contact {int(bad[0])} was still changing after max_periods = {max_periods} "
            "periods; raise max_periods")


def aft(model: MicroslipModel, t, n, *, samples: int | None = None,
        max_periods: int = MAX_PERIODS) -> AFTResult:
    """Periodic forces of one contact and their exact derivatives.

    Parameters
    ----------
    model : MicroslipModel
        The contact.
    t, n : array_like, shape (2H+1,)
        Fourier coefficients of the tangential displacement and of the normal
        approach (m), ``[c0, a1, b1, ..., aH, bH]``.
    samples : int, optional
        Time samples per period (default :func:`default_samples`).
    max_periods : int, default 1000
        Periods allowed for the state to become periodic.

    Returns
    -------
    AFTResult
        Coefficients of ``T`` and ``N`` (N), shape ``(2H+1,)``, and the
        Jacobians (N/m), shape ``(2H+1, 2H+1)``.

    Raises
    ------
    NotPeriodicError
        If the state is still changing after ``max_periods`` periods.

    Examples
    --------
    >>> import numpy as np
    >>> from microslip import MicroslipModel
    >>> from microslip.frequency import aft
    >>> jenkins = MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0)  # slip force 1 N at n = 1 µm
    >>> r = aft(jenkins, t=[0, 3e-4, 0], n=[1e-6, 0, 0])
    >>> r.T.shape, r.dT_dt.shape
    ((3,), (3, 3))
    """
    model = _check_model("model", model)
    t, H = harmonics_of("t", t)
    n, _ = harmonics_of("n", n)
    if t.ndim != 1:
        raise ValueError(f"t must be 1-D (2H+1 coefficients), got shape {t.shape}")
    if n.shape != t.shape:
        raise ValueError(f"n must have the same shape as t {t.shape}, got {n.shape}")
    Ns = check_samples(samples, H)
    max_periods = _checks.positive_int("max_periods", max_periods)
    nb = t.size
    T, N = np.empty(nb), np.empty(nb)
    dT_dt, dT_dn, dN_dn = np.empty((nb, nb)), np.empty((nb, nb)), np.empty((nb, nb))
    periods = _aft._aft_contact(model.kt, model.kn, model.gaps, model.mu, t, n, *_aft.tables(H, Ns), max_periods,
                                T, N, dT_dt, dT_dn, dN_dn)
    check_periodic(periods, max_periods)
    return AFTResult(T, N, dT_dt, dT_dn, dN_dn, int(periods), Ns)


@dataclass(frozen=True, eq=False)
class PlaneAFTResult(AFTResult):
    """Periodic forces of a contact on its plane and their derivatives (from :func:`aft_plane`).

    With ``nb = 2H + 1`` coefficients; component 0 and 1 are the two
    tangential directions of the contact plane.

    Attributes
    ----------
    T : ndarray, shape (2, nb)
        Fourier coefficients of the two tangential force components (N).
    N : ndarray, shape (nb,)
        Fourier coefficients of the normal force (N).
    dT_dt : ndarray, shape (2, 2, nb, nb)
        ``dT_dt[a, b]``: derivative of the coefficients of ``T[a]`` with
        respect to those of ``t[b]`` (N/m).
    dT_dn : ndarray, shape (2, nb, nb)
        ``dT_dn[a]``: derivative of the coefficients of ``T[a]`` with respect
        to those of ``n`` (N/m).
    dN_dn : ndarray, shape (nb, nb)
        Derivative of the coefficients of ``N`` with respect to those of ``n``
        (N/m); ``N`` does not depend on ``t``.
    periods : int
        Periods marched until every element's slider repeated (to rounding).
    samples : int
        Time samples per period.
    """

    def dissipation(self, t) -> float:
        """Energy dissipated per cycle by the tangential force along ``t`` (J), both components.

        Parameters
        ----------
        t : array_like, shape (2, nb)
            The tangential displacement coefficients (m) given to :func:`aft_plane`.
        """
        t, _ = harmonics_of("t", t)
        if t.shape != self.T.shape:
            raise ValueError(f"t must have the shape of T {self.T.shape}, got {t.shape}")
        return float(cycle_work(self.T, t).sum())


def aft_plane(model: MicroslipModel, t, n, *, samples: int | None = None,
              max_periods: int = MAX_PERIODS) -> PlaneAFTResult:
    """Periodic forces of one contact moving on its plane, and their exact derivatives.

    Each element is an isotropic Jenkins slider on the contact plane: its
    trial force ``kt_i (t - s_i)`` (2-vectors) is returned radially onto the
    disc of radius ``mu N_i`` when it leaves it. Along a straight line the
    result is :func:`aft`'s, rotated (see :mod:`microslip.kernels.aft_plane`
    for the algorithm). Unlike one direction, the periodic state is in general
    reached only asymptotically (a circular orbit in gross slip): an element is
    periodic when its slider repeats to rounding (32 ulps of the motion).

    Parameters
    ----------
    model : MicroslipModel
        The contact (isotropic: the same ``kt`` in both directions).
    t : array_like, shape (2, 2H+1)
        Fourier coefficients of the two tangential displacement components (m),
        one row per direction, ``[c0, a1, b1, ..., aH, bH]``; the magnitudes of
        a row must add up to less than 1e100 m (the element squares the stretch).
    n : array_like, shape (2H+1,)
        Fourier coefficients of the normal approach (m).
    samples, max_periods
        As in :func:`aft` (curved orbits need more samples than lines: the
        sampled radial return is first order in the step there).

    Returns
    -------
    PlaneAFTResult
        Coefficients and Jacobians, with the number of periods marched.

    Raises
    ------
    NotPeriodicError
        When some element's slider still moves by more than 32 ulps of the
        motion after ``max_periods`` periods.

    Examples
    --------
    A circle in gross slip: the force, of magnitude ``mu N``, turns with it.

    >>> from math import hypot
    >>> from microslip import MicroslipModel
    >>> from microslip.frequency import aft_plane
    >>> jenkins = MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0)  # slip force 1 N at n = 1 µm
    >>> r = aft_plane(jenkins, t=[[0, 3e-4, 0], [0, 0, 3e-4]], n=[1e-6, 0, 0])
    >>> r.T.shape, r.dT_dt.shape, round(hypot(r.T[0, 1], r.T[0, 2]), 3)
    ((2, 3), (2, 2, 3, 3), 1.0)
    """
    model = _check_model("model", model)
    t, H = harmonics_of("t", t)
    n, _ = harmonics_of("n", n)
    if t.ndim != 2 or t.shape[0] != 2:
        raise ValueError(f"t must have shape (2, 2H+1): the coefficients of the two tangential directions, "
                         f"got shape {t.shape}")
    if n.shape != t.shape[1:]:
        raise ValueError(f"n must have shape {t.shape[1:]} (the coefficients of the normal approach), got {n.shape}")
    reach = float(np.abs(t).sum(axis=1).max())  # the largest |t_a| the coefficients can give over the period
    if reach >= PLANE_LIMIT:
        raise ValueError(f"t must stay below {PLANE_LIMIT:g} m in magnitude on the contact plane (the element squares "
                         f"the stretch): its coefficients add up to {reach:.6g} m")
    Ns = check_samples(samples, H)
    max_periods = _checks.positive_int("max_periods", max_periods)
    nb = n.size
    F = np.empty((3, nb))
    Jac = np.empty((3, 3, nb, nb))
    periods = _aft_plane._aft_plane(model.kt, model.kn, model.gaps, model.mu, np.ascontiguousarray(t[0]),
                                    np.ascontiguousarray(t[1]), np.ascontiguousarray(n), *_aft.tables(H, Ns),
                                    _aft_plane.sweep_tables(H, Ns), max_periods, F, Jac)
    check_periodic(int(periods), max_periods)
    return PlaneAFTResult(F[:2].copy(), F[2].copy(), Jac[:2, :2].copy(), Jac[:2, 2].copy(), Jac[2, 2].copy(),
                          int(periods), Ns)


def aft_batch(models: Sequence[MicroslipModel], t, n, *, samples: int | None = None,
              max_periods: int = MAX_PERIODS) -> AFTResult:
    """Periodic forces of ``nc`` contacts at once (one compiled call).

    Parameters
    ----------
    models : sequence of MicroslipModel, length nc
        The contacts (their numbers of elements may differ).
    t, n : array_like, shape (nc, 2H+1)
        Fourier coefficients of each contact's tangential displacement and
        normal approach (m).
    samples, max_periods
        As in :func:`aft`.

    Returns
    -------
    AFTResult
        Arrays with a leading axis of length ``nc``; ``periods`` per contact.
    """
    if isinstance(models, MicroslipModel) or not isinstance(models, Sequence) or len(models) == 0:
        raise TypeError(f"models must be a non-empty sequence of MicroslipModel, got {type(models).__name__}")
    models = [_check_model(f"models[{i}]", m) for i, m in enumerate(models)]
    t, H = harmonics_of("t", t)
    n, _ = harmonics_of("n", n)
    shape = (len(models), 2 * H + 1)
    if t.shape != shape:
        raise ValueError(f"t must have shape (len(models), 2H+1) = {shape}, got {t.shape}")
    if n.shape != shape:
        raise ValueError(f"n must have the same shape as t {shape}, got {n.shape}")
    return _run(models, t, n, H, samples, max_periods)


def _run(models, t, n, H, samples, max_periods) -> AFTResult:
    Ns = check_samples(samples, H)
    max_periods = _checks.positive_int("max_periods", max_periods)
    nc, nb = t.shape
    FT = np.empty((nc, nb))
    FN = np.empty((nc, nb))
    JTt = np.empty((nc, nb, nb))
    JTn = np.empty((nc, nb, nb))
    JNn = np.empty((nc, nb, nb))
    periods = np.empty(nc, dtype=np.int64)
    _aft.aft_batch(*pack_models(models), np.ascontiguousarray(t), np.ascontiguousarray(n),
                   *_aft.tables(H, Ns), max_periods, FT, FN, JTt, JTn, JNn, periods)
    check_periodic(periods, max_periods)
    return AFTResult(FT, FN, JTt, JTn, JNn, periods, Ns)


def pack_models(models: Sequence[MicroslipModel]) -> tuple[np.ndarray, ...]:
    """Concatenated ``kt, kn, gaps``, the ``offsets`` (nc+1) and ``mu`` (nc) for the kernel."""
    offsets = np.fromiter(accumulate((m.elements for m in models), initial=0), np.int64, len(models) + 1)
    if not models:  # no contacts: empty arrays of the kernel's types
        return np.ones(0), np.ones(0), np.zeros(0), offsets, np.ones(0)
    return (np.concatenate([m.kt for m in models]), np.concatenate([m.kn for m in models]),
            np.concatenate([m.gaps for m in models]), offsets, np.array([m.mu for m in models]))


def friction_work(packed, xt, xn, synthesis, max_periods: int = MAX_PERIODS) -> tuple[np.ndarray, np.ndarray]:
    """Energy each contact dissipates per cycle by friction (J), never negative, and whether it opens.

    Every element is marched over the sampled period (the convention of the
    AFT: closed at ``t = 0`` with no force, loaded statically to the mean, then
    period after period until its state repeats) and the work of its force on
    its slider's travel is summed over the last period, step by step with the
    trapezoidal rule ``(T_k-1 + T_k) (s_k - s_k-1) / 2`` on the steps where the
    slider moves (slip, or the release of the stored force when the element
    opens), each step's work floored at zero so that the sum is never negative.
    For a displacement and a normal approach linear between the samples this is
    exact up to the instant slip starts inside a step, so it converges like
    ``1/samples^2`` even where the normal load varies during slip (the work
    ``T_k (s_k - s_k-1)`` of :func:`microslip.kernels.element.friction_work` there
    converges like ``1/samples``: 10 % low at 128 samples on the inclined block
    of ``examples/inclined_block.py`` where its contact slides and opens).

    Parameters
    ----------
    packed : tuple
        The contacts' laws, :func:`pack_models`.
    xt, xn : ndarray, shape (nc, 2H+1)
        Fourier coefficients of each contact's ``t`` and ``n`` (m).
    synthesis : ndarray, shape (Ns, 2H+1)
        The AFT's synthesis table (samples of the basis over a period).
    max_periods : int
        Periods marched at most.

    Returns
    -------
    work : ndarray, shape (nc,)
        J per cycle.
    opens : ndarray of bool, shape (nc,)
        Whether some element opens and closes during the cycle.
    """
    from ..kernels.friction_work import friction_work_batch

    kt, kn, gaps, offsets, mu = packed
    nc = offsets.size - 1
    work, opens = np.zeros(nc), np.zeros(nc, dtype=bool)
    if nc == 0:
        return work, opens
    xt, xn = np.asarray(xt, dtype=float).reshape(nc, -1), np.asarray(xn, dtype=float).reshape(nc, -1)
    t = np.ascontiguousarray(xt @ synthesis.T)  # (nc, Ns)
    n = np.ascontiguousarray(xn @ synthesis.T)
    friction_work_batch(kt, kn, gaps, offsets, mu, t, n, np.ascontiguousarray(xt[:, 0]),
                        np.ascontiguousarray(xn[:, 0]), int(max_periods), work, opens)
    return work, opens


def friction_work_plane(packed, planar, xt, xt2, xn, synthesis, max_periods: int, work, opens) -> None:
    """:func:`friction_work` of the contacts on their planes (``planar``), written into ``work`` and ``opens``.

    The same definition on the plane: from the AFT's periodic state, one
    period marched, the work ``(T_k-1 + T_k) . (s_k - s_k-1) / 2`` of each
    element's force on its slider's travel summed over the steps where the
    slider moves, each step's work floored at zero.

    Parameters
    ----------
    packed : tuple
        The contacts' laws, :func:`pack_models`.
    planar : ndarray of bool, shape (nc,)
        Which contacts move on their planes.
    xt, xt2, xn : ndarray, shape (nc, 2H+1)
        Fourier coefficients of each contact's two tangential displacements and normal approach (m).
    synthesis : ndarray, shape (Ns, 2H+1)
        The AFT's synthesis table.
    max_periods : int
        Periods marched at most.
    work : ndarray, shape (nc,)
        J per cycle, overwritten for the contacts on their planes.
    opens : ndarray of bool, shape (nc,)
        Whether some element opens and closes during the cycle, likewise.
    """
    from ..kernels.friction_work import friction_work_plane_batch

    kt, kn, gaps, offsets, mu = packed
    periods = np.zeros(offsets.size - 1, dtype=np.int64)
    friction_work_plane_batch(kt, kn, gaps, offsets, mu, np.ascontiguousarray(planar, dtype=np.bool_),
                              *(np.ascontiguousarray(x, dtype=float) for x in (xt, xt2, xn)),
                              np.ascontiguousarray(synthesis, dtype=float), int(max_periods), work, opens, periods)
    check_periodic(periods, max_periods)


def friction_work_plane_reference(packed, planar, xt, xt2, xn, synthesis, max_periods: int, work, opens) -> None:
    """:func:`friction_work_plane` contact by contact in NumPy (the compiled batch's slow twin, for the tests)."""
    from ..kernels.element import STICK
    from ..kernels.plane_march import march_plane, periodic_state

    kt, kn, gaps, offsets, mu = packed
    Ns = synthesis.shape[0]
    for c in np.flatnonzero(planar):
        lo, hi = offsets[c], offsets[c + 1]
        k, g = kt[lo:hi], gaps[lo:hi]
        s = np.empty((2, hi - lo))
        periods = periodic_state(k, kn[lo:hi], g, mu[c], xt[c], xt2[c], xn[c], synthesis, max_periods, s)
        check_periodic(int(periods), max_periods)
        t = np.stack([synthesis @ xt[c], synthesis @ xt2[c]], axis=1)  # (Ns, 2)
        n = np.ascontiguousarray(synthesis @ xn[c])
        opens[c] = bool(np.any((n.min() <= g) & (n.max() > g)))
        Ti, cond = np.empty((Ns, hi - lo, 2)), np.empty((Ns, hi - lo), dtype=np.int8)
        march_plane(k, kn[lo:hi], g, mu[c], np.ascontiguousarray(t[:, 0]), np.ascontiguousarray(t[:, 1]), n, s,
                    np.empty((Ns, 2)), np.empty(Ns), Ti, cond)
        slider = t[:, None, :] - Ti / k[None, :, None]  # T = kt (t - s) in every condition
        steps = 0.5 * np.sum((Ti + np.roll(Ti, 1, axis=0)) * (slider - np.roll(slider, 1, axis=0)), axis=-1)
        work[c] = np.maximum(steps, 0.0)[cond != STICK].sum()
