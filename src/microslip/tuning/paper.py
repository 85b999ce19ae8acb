"""The paper's tuning procedure (Gastaldi & Gola, eqs. 1--9).

Given a *reference* contact (anything that provides a tangential backbone
at constant normal load and a normal force--approach curve) and the load
``N_tot`` to tune at, the procedure

1. picks ``J`` points ``(t_j, T_j)`` on the backbone, the last at gross slip
   (``T_J = mu N_tot``);
2. solves eqs. (1)--(3) for the tangential stiffnesses. With the index slip
   of the printed eq. (2) corrected, row ``j`` reads
   ``T_j = sum_e kt_e min(t_j, s_e)`` with element ``e`` slipping at
   ``s_e = t_{J+1-e}``; equivalently ``kt`` of the element slipping at ``t_j``
   is ``sigma_j - sigma_{j+1}``, the drop in slope of the piecewise-linear
   interpolant of the points (``sigma_{J+1} = 0``). All stiffnesses are
   positive exactly when the points describe a concave curve;
3. shares the load (eq. 5): ``alpha_e = kt_e s_e / (mu N_tot)``;
4. solves eqs. (6)--(9) element by element for ``kn`` and ``gaps`` on the
   reference's normal curve. At step ``j`` the previous gap is always a
   trivial root of eq. (9); the wanted root is bracketed from the maximiser
   of the residual instead.

Element 1 slips last, touches first (``gaps[0] = 0``) and is the contact
centre; element ``J`` slips first.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np
from scipy import optimize

from ..common import _checks
from ..common.errors import TuningError
from ..model import MicroslipModel
from ._record import record


@runtime_checkable
class ContactReference(Protocol):
    """What :func:`tune` needs of a reference contact (SI units).

    Attributes
    ----------
    mu : float
        Friction coefficient.

    Methods
    -------
    backbone(t, N) -> T
        Virgin tangential force (N) at displacement ``t`` (m) and load ``N`` (N).
    backbone_displacement(T, N) -> t
        Its inverse for ``0 <= T <= mu N``.
    gross_slip_displacement(N) -> t
        Displacement (m) at which the backbone reaches ``mu N``.
    approach(N) -> n
        Normal approach (m) at load ``N`` (N).
    normal_force(n) -> N
        Normal force (N) at approach ``n`` (m), increasing.
    """

    mu: float

    def backbone(self, t, N):
        """Virgin tangential force (N) at displacement ``t`` (m) under the constant load ``N`` (N).

        Parameters
        ----------
        t : array_like
            Tangential displacement from the unloaded state (m).
        N : float or array_like
            Normal load (N), positive; broadcast against ``t``.

        Returns
        -------
        ndarray
            Tangential force (N), shape of ``t``; odd in ``t``, increasing,
            concave for ``t >= 0``, equal to ``mu N`` from the gross-slip
            displacement on.
        """

    def backbone_displacement(self, T, N):
        """Inverse of :meth:`backbone`: displacement (m) at tangential force ``T`` (N), load ``N`` (N).

        Parameters
        ----------
        T : array_like
            Tangential force (N), ``|T| <= mu N``.
        N : float or array_like
            Normal load (N), positive.

        Returns
        -------
        ndarray
            Tangential displacement (m), shape of ``T``, odd in ``T``.
        """

    def gross_slip_displacement(self, N):
        """Displacement (m) at which the backbone at load ``N`` (N) reaches ``mu N``.

        Parameters
        ----------
        N : float or array_like
            Normal load (N), positive.

        Returns
        -------
        float or ndarray
            Gross-slip displacement (m), shape of ``N``.
        """

    def approach(self, N):
        """Normal approach (m) at normal load ``N`` (N).

        Parameters
        ----------
        N : float or array_like
            Normal load (N), non-negative.

        Returns
        -------
        float or ndarray
            Normal approach (m), shape of ``N``, increasing in ``N``.
        """

    def normal_force(self, n):
        """Normal force (N) at normal approach ``n`` (m); the inverse of :meth:`approach`.

        Parameters
        ----------
        n : float or array_like
            Normal approach (m).

        Returns
        -------
        float or ndarray
            Normal force (N), shape of ``n``, increasing, 0 for ``n <= 0``.
        """


@dataclass(frozen=True)
class TuningPoints:
    """The points a model was tuned on.

    Attributes
    ----------
    t : ndarray, shape (J,)
        Tangential displacement of each point (m), increasing, last at gross slip.
    T : ndarray, shape (J,)
        Tangential force of each point (N), last equal to ``mu * normal_load``.
    normal_load : float
        Tuning load ``N_tot`` (N).
    approach : float
        Reference approach ``n_tot`` at ``N_tot`` (m).
    """

    t: np.ndarray
    T: np.ndarray
    normal_load: float
    approach: float


_GROSS_SLIP_RTOL = 1e-6  # how close the last point must be to gross slip (relative)


def tuning_points(reference, normal_load, *, forces=None, displacements=None,
                  elements=None) -> TuningPoints:
    """Choose the tuning points on the reference backbone (step 1 of :func:`tune`).

    Give exactly one of ``forces``, ``displacements`` or ``elements``.

    Parameters
    ----------
    reference : ContactReference
        The contact to imitate (e.g. :class:`microslip.Sphere`): its ``mu``,
        backbone at constant load, inverse, gross-slip displacement and
        ``approach(N)``.
    normal_load : float
        The load ``N_tot`` to tune at (N), positive.
    forces : array_like, shape (J,), optional
        Tangential forces of the points (N), strictly increasing, the last
        equal to ``mu * normal_load`` (to a relative 1e-6; it is then set
        exactly); their displacements come from the inverse backbone.
    displacements : array_like, shape (J,), optional
        Tangential displacements of the points (m), strictly increasing, the
        last at the gross-slip displacement (to a relative 1e-6); their
        forces come from the backbone.
    elements : int, optional
        Number of points ``J``, evenly spaced in force:
        ``T_j = j mu N_tot / J`` (the paper's choice).

    Returns
    -------
    TuningPoints
        ``t`` (m) and ``T`` (N), each shape ``(J,)``, the last at gross slip;
        ``normal_load`` (N) and ``approach``, the reference's normal approach
        at it (m).

    Raises
    ------
    TypeError
        ``reference`` lacks a method of :class:`ContactReference`.
    ValueError
        Not exactly one of ``forces``, ``displacements``, ``elements``; a
        value not finite or not positive; points not strictly increasing;
        the last point not at gross slip.
    """
    _check_reference(reference)
    N_tot = _checks.positive_scalar("normal_load", normal_load)
    given = [name for name, v in (("forces", forces), ("displacements", displacements),
                                  ("elements", elements)) if v is not None]
    if len(given) != 1:
        raise ValueError("give exactly one of forces=, displacements= or elements= "
                         f"(got {', '.join(given) if given else 'none'})")
    limit = reference.mu * N_tot
    t_gs = float(reference.gross_slip_displacement(N_tot))
    if elements is not None:
        J = _checks.size("elements", elements)
        forces = limit * np.arange(1, J + 1) / J
    if forces is not None:
        T = _ends_at_gross_slip("forces", forces, limit, "N", f"mu*normal_load = {limit:.6g} N")
        t = np.asarray(reference.backbone_displacement(T, N_tot), dtype=float)
        t[-1] = t_gs
    else:
        t = _ends_at_gross_slip("displacements", displacements, t_gs, "m",
                                f"t_gs = {t_gs:.6g} m at normal_load = {N_tot:g} N")
        T = np.asarray(reference.backbone(t, N_tot), dtype=float)
        T[-1] = limit
    return TuningPoints(t=t, T=T, normal_load=N_tot, approach=float(reference.approach(N_tot)))


def tangential_stiffnesses(t, T) -> np.ndarray:
    """Solve eqs. (1)--(3): the tangential stiffness of each element (N/m).

    Parameters
    ----------
    t, T : array_like, shape (J,)
        Tuning points (m, N), strictly increasing, last at gross slip.

    Returns
    -------
    kt : ndarray, shape (J,)
        ``kt[e-1]`` belongs to element ``e``, which slips at ``t[J-e]``.

    Raises
    ------
    TuningError
        If the points are not concave (a stiffness would be <= 0); the
        message names the point.
    """
    t = _checks.positive_array("t", t, ndim=1, min_size=1)
    T = _checks.positive_array("T", T, ndim=1, min_size=1)
    if t.size != T.size:
        raise ValueError(f"t and T must have the same length, got {t.size} and {T.size}")
    sigma = np.diff(np.concatenate([[0.0], T])) / np.diff(np.concatenate([[0.0], t]))
    drop = sigma - np.concatenate([sigma[1:], [0.0]])  # stiffness of the element slipping at t_j
    bad = np.flatnonzero(drop <= 0)
    if bad.size:
        j = int(bad[0])
        raise TuningError(
            f"the tuning points are not concave at point {j + 1} (t = {t[j]:.6g} m, T = {T[j]:.6g} N): "
            f"the slope before it ({sigma[j]:.6g} N/m) does not exceed the slope after it "
            f"({(sigma[j + 1] if j + 1 < sigma.size else 0.0):.6g} N/m), so the element that slips there "
            f"would get a stiffness of {drop[j]:.6g} N/m <= 0")
    return drop[::-1].copy()


def normal_parameters(reference, kt, slip_displacements, normal_load):
    """Solve eqs. (5)--(9): normal stiffness and gap of each element.

    Parameters
    ----------
    reference : ContactReference
        Provides ``mu``, ``approach(N)`` and ``normal_force(n)``.
    kt : array_like, shape (J,)
        Tangential stiffnesses (N/m), element 1 first.
    slip_displacements : array_like, shape (J,)
        Displacement at which each element slips (m), element 1 first
        (decreasing).
    normal_load : float
        Tuning load ``N_tot`` (N).

    Returns
    -------
    kn : ndarray, shape (J,)
        Normal stiffnesses (N/m).
    gaps : ndarray, shape (J,)
        Gaps (m), ``gaps[0] = 0``, increasing.

    Raises
    ------
    TuningError
        Eq. (9) has no solution for some element with these arguments
        (the message names the element and the condition that fails).
    """
    _check_reference(reference)
    kt = _checks.positive_array("kt", kt, ndim=1, min_size=1)
    s = _checks.positive_array("slip_displacements", slip_displacements, ndim=1, min_size=1)
    if s.size != kt.size:
        raise ValueError(f"slip_displacements must have one value per element of kt ({kt.size}), got {s.size}")
    N_tot = _checks.positive_scalar("normal_load", normal_load)
    try:
        return _normal_parameters(reference, kt, s, N_tot)
    except TuningError as exc:
        raise TuningError(f"kt, slip_displacements and normal_load = {N_tot:g} N: {exc}") from None


def _normal_parameters(reference, kt, s, N_tot):
    """:func:`normal_parameters` on checked arguments."""
    alpha = kt * s / (reference.mu * N_tot)  # eq. (5)
    n_tot = float(reference.approach(N_tot))
    J = kt.size
    gaps = np.zeros(J)
    kn = np.zeros(J)
    kn[0] = alpha[0] * N_tot / n_tot  # eq. (8) with gaps[0] = 0
    for j in range(1, J):
        gaps[j] = _next_gap(reference, kn[:j], gaps[:j], n_tot, j + 1)
        kn[j] = alpha[j] * N_tot / (n_tot - gaps[j])
    return kn, gaps


def _next_gap(reference, kn, gaps, n_tot, element):
    """Root of eq. (9) for element ``element`` (1-based) beyond the trivial root ``gaps[-1]``."""
    k_sum = float(kn.sum())

    def residual(x):
        return float(np.sum(kn * (x - gaps)) - reference.normal_force(x))

    lo = float(gaps[-1])
    # The residual is concave for a convex reference curve and vanishes at lo:
    # find its maximiser and bracket the wanted root between it and n_tot.
    res = optimize.minimize_scalar(lambda x: -residual(x), bounds=(lo, n_tot), method="bounded",
                                   options={"xatol": 1e-12 * n_tot})
    x_max = float(res.x)
    r_max = residual(x_max)
    r_hi = residual(n_tot)
    if not r_max > 0.0:
        # A reference curve that is not convex can leave the residual non-concave, and the
        # bounded search may then miss its positive part: scan a grid for it.
        for x in np.linspace(lo, n_tot, 513)[1:-1]:
            if residual(x) > 0.0:
                x_max, r_max = float(x), residual(x)
                break
    if not (r_max > 0.0 and r_hi < 0.0):
        h = 1e-6 * n_tot
        slope = (float(reference.normal_force(lo + h)) - float(reference.normal_force(max(lo - h, 0.0)))) / (
            lo + h - max(lo - h, 0.0))
        raise TuningError(
            f"eq. (9) has no solution for element {element}: the normal stiffness of elements "
            f"1..{element - 1} (sum {k_sum:.6g} N/m) must exceed the slope of the reference normal curve "
            f"where element {element - 1} touches (about {slope:.6g} N/m at n = {lo:.6g} m) for the "
            f"array's normal curve to meet the reference again before n_tot = {n_tot:.6g} m")
    return optimize.brentq(residual, x_max, n_tot, xtol=1e-15 * n_tot, rtol=4 * np.finfo(float).eps)


def model_from_points(reference, points: TuningPoints) -> MicroslipModel:
    """Steps 2--4 of :func:`tune` on points already chosen by :func:`tuning_points`.

    Parameters
    ----------
    reference : ContactReference
        The reference the points were chosen on (its ``mu`` and normal curve).
    points : TuningPoints
        The tuning points (m, N) and the tuning load and approach.

    Returns
    -------
    MicroslipModel
        As :func:`tune` returns it, with its :class:`~microslip.model.Provenance`
        (the reference, the tuning load and approach, the points, where ``mu``
        came from).
    """
    _check_reference(reference)
    if not isinstance(points, TuningPoints):
        raise TypeError(f"points must be TuningPoints (from tuning_points), got {type(points).__name__}")
    kt = tangential_stiffnesses(points.t, points.T)
    s = points.t[::-1]  # element e slips at t_{J+1-e}
    kn, gaps = _normal_parameters(reference, kt, s, points.normal_load)
    return MicroslipModel(kt=kt, kn=kn, gaps=gaps, mu=reference.mu, provenance=record(reference, points))


def _ends_at_gross_slip(name, values, target, unit, target_text):
    """Checked tuning points: positive, strictly increasing, the last at ``target`` (snapped to it)."""
    values = _checks.positive_array(name, values, ndim=1, min_size=1)
    _strictly_increasing(name, values, unit)
    if abs(values[-1] - target) > _GROSS_SLIP_RTOL * target:
        raise ValueError(f"{name}: the last point must be at gross slip, {target_text}, "
                         f"got {values[-1]:.6g} {unit}")
    values = values.copy()
    values[-1] = target
    return values


def _strictly_increasing(name, values, unit):
    steps = np.diff(values)
    bad = np.flatnonzero(steps <= 0)
    if bad.size:
        i = int(bad[0])
        raise ValueError(f"{name} must be strictly increasing: point {i + 2} ({values[i + 1]:.6g} {unit}) "
                         f"does not exceed point {i + 1} ({values[i]:.6g} {unit})")


def _check_reference(reference):
    missing = [name for name in ("mu", "backbone", "backbone_displacement", "gross_slip_displacement",
                                 "approach", "normal_force") if not hasattr(reference, name)]
    if missing:
        raise TypeError(f"reference must provide {', '.join(missing)} (see microslip.tuning.ContactReference); "
                        f"got {type(reference).__name__}")
