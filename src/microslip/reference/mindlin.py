"""Mindlin--Deresiewicz: the normal load raised at constant tangential force, on any reference.

The rule (Mindlin and Deresiewicz; DESIGN.md §2) needs only the reference's
backbone at constant load: the tangential force ``T`` rises to ``T_A`` at
load ``N`` (point A); the load is raised to ``N + dN`` at constant ``T`` (the
point does not move in the T--t plane); when ``T`` rises again the curve is
the virgin curve at ``N + dN`` shifted to start at A, until the tangential
increment reaches ``mu dN`` (point B, ``T_B = T_A + mu dN``), and from there
on the virgin curve at ``N + dN`` itself.

Both functions take any :class:`~microslip.tuning.ContactReference` (they use
its ``mu`` and ``backbone_displacement(T, N)``): :class:`microslip.Sphere`
(whose methods of the same names call these), a
:class:`microslip.MeasuredContact`, ... All quantities SI: N, m.
"""

from __future__ import annotations

import numpy as np

from ..common import _checks


def raised_load_path(reference, T, N, dN, T_A):
    """Displacement (m) along the Mindlin--Deresiewicz path of the paper's Fig. 4a.

    Parameters
    ----------
    reference : ContactReference
        Gives ``mu`` and ``backbone_displacement(T, N)`` (m of N, N).
    T : array_like
        Tangential force (N), ``0 <= T <= mu (N + dN)``.
    N, dN : float
        Initial load and its increment (N).
    T_A : float
        Tangential force at which the load is raised (N), ``0 <= T_A <= mu N``.

    Returns
    -------
    ndarray
        Tangential displacement (m), same shape as ``T``.

    Raises
    ------
    ValueError
        ``N`` not positive, ``dN`` or ``T_A`` negative or not finite,
        ``T_A > mu N``, or ``T`` outside ``[0, mu (N + dN)]``.
    """
    N, dN, T_A = _arguments(reference, N, dN, T_A)
    T = _checks.real_array("T", T)
    mu = reference.mu
    N2 = N + dN
    outside = (T < 0) | (T > mu * N2 * (1 + 1e-12))
    if outside.any():
        raise ValueError(f"T must lie in [0, mu*(N+dN)] = [0, {mu * N2:g}] N, "
                         f"got {float(T[outside].flat[0]):g} N")
    before = reference.backbone_displacement(np.clip(T, 0, mu * N), N)
    tA = reference.backbone_displacement(T_A, N)
    shifted = tA + reference.backbone_displacement(np.clip(T - T_A, 0, mu * N2), N2)
    joined = reference.backbone_displacement(np.clip(T, 0, mu * N2), N2)
    return np.where(T <= T_A, before, np.where(T <= T_A + mu * dN, shifted, joined))


def join_point(reference, N, dN, T_A):
    """Point B where the raised-load path joins the virgin curve at ``N + dN``.

    Parameters
    ----------
    reference : ContactReference
        Gives ``mu`` and ``backbone_displacement(T, N)``.
    N, dN, T_A : float
        As in :func:`raised_load_path` (N).

    Returns
    -------
    t_B, T_B : float
        Its displacement (m) and ``T_B = T_A + mu dN`` (N).
    """
    N, dN, T_A = _arguments(reference, N, dN, T_A)
    T_B = T_A + reference.mu * dN
    return float(reference.backbone_displacement(T_B, N + dN)), float(T_B)


def _arguments(reference, N, dN, T_A):
    N = _checks.positive_scalar("N", N)
    dN = _checks.positive_scalar("dN", dN, allow_zero=True)
    T_A = _checks.positive_scalar("T_A", T_A, allow_zero=True)
    if T_A > reference.mu * N:
        raise ValueError(f"T_A must not exceed mu*N = {reference.mu * N:g} N, got {T_A:g} N")
    return N, dN, T_A
