"""Steady loops of the tuned array and of the continuous sphere, shared by Figs. 3a and 3b (private)."""

from __future__ import annotations

import numpy as np


def array_loop(model, amplitude: float, n: float, points: int = 401):
    """Steady loop of ``model`` at constant approach ``n`` (m) and displacement amplitude (m).

    The array is loaded from rest to ``+amplitude`` first; a parallel array of
    Jenkins elements is steady from the first reversal on (Masing), so the
    loop recorded is ``+amplitude -> -amplitude -> +amplitude``.

    Returns
    -------
    t, T : ndarray, shape (2 * points - 1,)
        Displacement (m) and force (N), in the same order as :func:`microslip.reference.masing.loop`.
    energy : float
        Energy dissipated by friction over the loop (J), exact for the array.
    """
    up = np.linspace(0.0, amplitude, points)
    down = np.linspace(amplitude, -amplitude, points)
    back = down[::-1][1:]
    t = np.concatenate([up, down[1:], back])
    r = model.simulate(t, n, per_element=False)
    return t[points - 1:], r.T[points - 1:], float(r.friction_work[points:].sum())


def loop_energy(t, T) -> float:
    """Area of a closed loop given as samples around it (J), by the trapezoidal rule."""
    return float(abs(np.trapezoid(T, t)))
