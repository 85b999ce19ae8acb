"""Masing's rule: hysteresis branches and loops built from any backbone curve.

A backbone is a callable ``T = f(t)`` for ``t >= 0`` (odd extension for
``t < 0``). After a reversal at ``(t_r, T_r)`` the branch is the backbone
scaled by two about the reversal point::

    T(t) = T_r + 2 f((t - t_r) / 2)

which holds for the continuous Cattaneo--Mindlin contact, for the MDR array
and for any parallel array of Jenkins elements (the paper's model).
"""

from __future__ import annotations

import numpy as np

from ..common import _checks


def _odd(backbone, t):
    t = np.asarray(t, dtype=float)
    return np.sign(t) * backbone(np.abs(t))


def branch(backbone, t, t_reversal, T_reversal):
    """Force on the Masing branch that starts at the reversal ``(t_reversal, T_reversal)``.

    Parameters
    ----------
    backbone : callable
        Virgin curve ``T = f(t)`` (N of m) for ``t >= 0``.
    t : array_like
        Tangential displacement (m) along the branch.
    t_reversal, T_reversal : float
        Reversal point (m, N).

    Returns
    -------
    ndarray
        Tangential force (N), same shape as ``t``.
    """
    t = _checks.real_array("t", t)
    t_reversal = _checks.real_scalar("t_reversal", t_reversal)
    T_reversal = _checks.real_scalar("T_reversal", T_reversal)
    return T_reversal + 2.0 * _odd(backbone, (t - t_reversal) / 2.0)


def loop(backbone, amplitude, points: int = 401):
    """A closed steady loop of displacement amplitude ``amplitude`` (m).

    Starts at ``(+amplitude, T_a)``, descends to ``-amplitude`` and climbs back.

    Returns
    -------
    t, T : ndarray, shape (2 * points - 1,)
        Displacement (m) and force (N) around the loop.
    """
    amplitude = _checks.positive_scalar("amplitude", amplitude)
    points = _checks.size("points", points, minimum=3)
    Ta = float(backbone(np.asarray(amplitude)))
    down = np.linspace(amplitude, -amplitude, points)
    up = down[::-1][1:]
    T_down = branch(backbone, down, amplitude, Ta)
    T_up = branch(backbone, up, -amplitude, -Ta)
    return np.concatenate([down, up]), np.concatenate([T_down, T_up])
