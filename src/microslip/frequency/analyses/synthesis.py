"""Forced responses from one nonlinear mode (single nonlinear mode synthesis): :func:`forced_response`.

Near an isolated resonance the forced response of a structure under
``Re(F exp(i Omega time))`` is taken as the nonlinear mode at some amplitude,
shifted in time: ``q = Re(A psi(a) exp(i Omega time)) + ...``, ``A = a exp(i theta)``,
``psi = z_1 / a`` the mode's first-harmonic shape (``phi^T M psi = 1``), the static
term and the higher harmonics those of the mode at ``a``. Projected onto ``psi``
(Galerkin) the equation of motion becomes, since the contact forces are rate
independent and the mode satisfies its own equation at ``(omega, xi)``,

``A [m_1 (omega^2 - Omega^2) + i (omega xi m_1 + (Omega - omega) c_1)] = psi^H F``

(``m_1 = psi^H M psi``, ``c_1 = psi^H C psi``: :attr:`NonlinearModes.modal_mass`,
:attr:`NonlinearModes.modal_damping`): the contacts' dissipation enters at the
mode's own frequency, the viscous damping at the excitation's. Its modulus is
a quartic in ``Omega`` for each ``a``: two excitation frequencies below and
above ``omega(a)`` until ``a`` reaches the peak, where they meet
(``a omega xi m_1 = |psi^H F|``, phase resonance: the peaks lie on the
backbone ``omega(a)``).

Validity. The response must keep the shape of this one mode: the mode isolated
(no other mode, nor a harmonic of the excitation, near ``Omega``: no modal
interaction), the excitation frequency near the resonance (within a few times
the half-power bandwidth ``2 D omega``), light damping, and a force whose
projection onto the mode dominates its response. Far from the resonance the
other modes' share of the response, which this leaves out, is no longer small.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import PchipInterpolator

from ...common import _checks
from ...common.errors import deprecated

#: modal amplitudes of the mode's range sampled for the curve, per point asked for
_REFINE = 60


@dataclass(frozen=True, eq=False)
class SynthesizedResponse:
    """A forced response synthesised from one nonlinear mode (from :meth:`NonlinearModes.forced_response`).

    Attributes
    ----------
    mode : NonlinearModes
        The mode it comes from.
    force : ndarray, shape (ndof,), complex
        The excitation's amplitudes ``F`` (N): ``Re(F exp(i Omega time))``.
    omega : ndarray, shape (points,)
        Excitation frequency of each point (rad/s), along the curve: up the
        branch below the backbone to the peak, then down the branch above it.
    modal_amplitude : ndarray, shape (points,)
        The response's modal amplitude ``a`` (kg^1/2 m).
    phase : ndarray, shape (points,)
        ``theta`` (rad): the phase of ``A`` relative to the force's projection
        ``psi^H F`` (``-pi/2`` at the peak).
    peak_omega, peak_modal_amplitude : float
        The peak (rad/s, kg^1/2 m), where the two branches meet.
    """

    mode: object
    force: np.ndarray
    omega: np.ndarray
    modal_amplitude: np.ndarray
    phase: np.ndarray
    peak_omega: float
    peak_modal_amplitude: float

    @property
    def points(self) -> int:
        """Number of points on the curve."""
        return self.omega.size

    def amplitude(self, dof=None, harmonic: int | None = 1) -> np.ndarray:
        """Amplitude at every point, ``(points,)``: the modal amplitude (``dof`` None, kg^1/2 m), or a DOF's (m),
        ``harmonic`` as in :meth:`FrequencyResponse.amplitude <microslip.frequency.FrequencyResponse.amplitude>`,
        the mode's at the response's modal amplitude (the time shift changes no harmonic's amplitude)."""
        if dof is None:
            return self.modal_amplitude.copy()
        return _interpolate(self.mode, self.mode.amplitude(dof, harmonic), self.modal_amplitude)

    def peak(self, dof=None, harmonic: int | None = 1) -> tuple[float, float]:
        """``(omega, amplitude)`` at the peak (rad/s; kg^1/2 m or m, as :meth:`amplitude`)."""
        if dof is None:
            return self.peak_omega, self.peak_modal_amplitude
        value = _interpolate(self.mode, self.mode.amplitude(dof, harmonic), np.array([self.peak_modal_amplitude]))
        return self.peak_omega, float(value[0])

    def plot(self, dof=None, harmonic: int | None = 1, ax=None, *, frequency_unit: str = "Hz", unit: str = "µm",
             backbone: bool = True, **kwargs):
        """The synthesised response against the excitation frequency, with the mode's backbone.

        ``dof``, ``harmonic`` as in :meth:`amplitude`; ``unit`` the length unit of
        a DOF's amplitude; ``backbone`` also draws the mode's natural frequency
        against the same amplitude (dotted). Returns the matplotlib Axes.
        """
        import matplotlib.pyplot as plt

        from ...common.units import plot_factor

        frequency_unit = _checks.one_of("frequency_unit", frequency_unit, ("Hz", "rad/s"))
        to_unit = 1.0 if frequency_unit == "rad/s" else 1 / (2 * np.pi)
        factor = 1.0 if dof is None else plot_factor(unit)
        if ax is None:
            _, ax = plt.subplots(figsize=(6.5, 4.2))
        ax.plot(self.omega * to_unit, self.amplitude(dof, harmonic) * factor, **kwargs)
        if backbone:
            ax.plot(self.mode.omega * to_unit, (self.mode.amplitude(dof, harmonic if dof is not None else None)
                                                * factor), ":", color="0.4", label="backbone")
        lo, hi = resonance_band(self, dof, harmonic)
        ax.set_xlim(lo * to_unit, hi * to_unit)
        ax.set_ylim(0, 1.15 * self.amplitude(dof, harmonic).max() * factor)
        ax.set_xlabel(f"excitation frequency ({frequency_unit})")
        ax.set_ylabel("modal amplitude (kg^1/2 m)" if dof is None else f"amplitude ({unit})")
        ax.grid(True, alpha=0.3)
        return ax


def resonance_band(response: SynthesizedResponse, dof=None, harmonic: int | None = 1) -> tuple[float, float]:
    """``(lo, hi)`` (rad/s): the half-power band of the synthesised resonance (amplitude of ``dof`` above
    ``1/sqrt(2)`` of its peak) widened by one and a half times its width on either side, within the curve: where
    the synthesis is meant to describe the forced response."""
    amplitude = response.amplitude(dof, harmonic)
    band = response.omega[amplitude >= amplitude.max() / np.sqrt(2)]
    width = max(float(np.ptp(band)), 1e-3 * response.peak_omega)
    return max(band.min() - 1.5 * width, response.omega.min()), min(band.max() + 1.5 * width, response.omega.max())


def _interpolate(mode, values, a) -> np.ndarray:
    """``values`` (one per point of ``mode``) at modal amplitudes ``a``, monotone cubic in ``ln a`` (over the
    points of :func:`rising`)."""
    n = rising(mode.modal_amplitude)
    return PchipInterpolator(np.log(mode.modal_amplitude[:n]), values[:n])(np.log(a))


def rising(modal_amplitude) -> int:
    """How many of a mode's first points have a rising modal amplitude: all of them, unless the mode turns
    back in amplitude (a fold, usually an internal resonance), where it stops being a function of the amplitude."""
    a = np.asarray(modal_amplitude, dtype=float)
    falls = np.flatnonzero(np.diff(a) <= 0)
    return int(falls[0]) + 1 if falls.size else a.size


def _turn(a_mode, n: int) -> str:
    """The clause saying where the mode turns back in amplitude, when it does (``n`` rising points of ``a_mode``)."""
    if n == a_mode.size:
        return ""
    return (f", where the mode turns back (a fold in amplitude, usually an internal resonance: the mode is no "
            f"function of its amplitude beyond, and the synthesis uses it up to there)")


def _projection(mode, force) -> np.ndarray:
    """``a psi^H F`` (N kg^1/2 m) at every point of ``mode``: ``z_1^H F``."""
    out = np.zeros(mode.points, dtype=complex)
    for part, weight in ((force.real, 1.0), (force.imag, 1j)):
        if np.any(part):
            c = mode.dof_coefficients(part)  # (points, 2H+1): sum_i F_i c_i
            out += weight * (c[:, 1] + 1j * c[:, 2])  # conj(a1 - i b1) . F
    return out


def _frequencies(m1, c1, omega, xi, R) -> np.ndarray:
    """The positive real roots ``Omega`` of ``m1^2 (omega^2 - Omega^2)^2 + (omega xi m1 + (Omega - omega) c1)^2 = R^2``.

    Solved for ``u = Omega / omega``: ``(1 - u^2)^2 + (d + (u - 1) c)^2 = r^2`` with ``d = xi / omega``,
    ``c = c1 / (m1 omega)``, ``r = R / (m1 omega^2)``; none when ``r`` is so large that the only root lies
    beyond ``sqrt(r)`` times the mode's frequency (a force far too large for the mode's range).
    """
    d, c, r = xi / omega, c1 / (m1 * omega), R / (m1 * omega * omega)
    if not r < 1e100:
        return np.empty(0)
    e = d - c
    roots = np.roots([1.0, 0.0, c * c - 2.0, 2 * c * e, 1.0 + e * e - r * r])
    real = roots[np.abs(roots.imag) <= 1e-9 * np.abs(roots)].real
    return omega * np.sort(real[real > 0])


def forced_response(mode, force, omega=None, *, points: int = 400) -> SynthesizedResponse:
    """The forced response under ``Re(F exp(i Omega time))`` near a nonlinear mode, from the mode alone.

    The single nonlinear mode approximation of the module docstring: for each
    modal amplitude ``a`` of the mode's range the excitation frequencies at which
    the forced response has that amplitude; valid where the mode is isolated and
    the excitation near its resonance (the module docstring says when).

    Parameters
    ----------
    mode : NonlinearModes
        The mode (from :func:`~microslip.frequency.nonlinear_modes`).
    force : array_like or mapping
        The excitation's amplitudes (N) on the structure's DOFs, at the excitation
        frequency: ``ndof`` values (real, or complex for a phase) or ``{dof: amplitude}``.
    omega : (float, float), optional
        Keep the points whose excitation frequency lies in this range (rad/s).
    points : int, default 400
        About how many points the curve has (its amplitudes are sampled
        ``points`` times over the mode's range; the peak is found exactly).

    Returns
    -------
    SynthesizedResponse

    Raises
    ------
    TypeError, ValueError
        A parameter of the wrong type or out of range; a force that does not
        act on the mode (``psi^H F = 0``); a peak above the mode's amplitude
        range (compute the mode to larger amplitudes); an ``omega`` range
        that holds no point of the response.

    Notes
    -----
    Where the mode turns back in amplitude (a fold, usually an internal
    resonance) it is no longer a function of its amplitude: the synthesis
    uses its points up to the turn.
    """
    F = mode.structure.force_vector(force, "force").astype(complex)
    if not np.any(F):
        raise ValueError("force must not be all zeros")
    if omega is not None:
        lo, hi = _checks.positive_pair("omega", omega, "(start, end) of excitation frequencies in rad/s")
        lo, hi = min(lo, hi), max(lo, hi)
    points = _checks.size("points", points, minimum=10, maximum=100_000)
    n = rising(mode.modal_amplitude)
    if n < 2:
        raise ValueError(f"mode: its modal amplitude does not rise from its first point "
                         f"({mode.modal_amplitude[0]:.3g} kg^1/2 m; {mode.points} points): nothing to synthesise from")
    a_mode = mode.modal_amplitude[:n]
    proj = np.abs(_projection(mode, F))[:n]
    if not np.any(proj > 1e-12 * np.max(np.abs(F)) * a_mode):
        raise ValueError("force does not act on the mode: its projection onto the mode's shape is zero")
    funcs = [PchipInterpolator(np.log(a_mode), v[:n]) for v in (mode.modal_mass, mode.modal_damping, mode.omega,
                                                                 mode.xi, proj / a_mode)]

    def roots(a):  # |psi^H F| / a = |A [...]| / a
        m1, c1, w, xi, psiF = (float(f(np.log(a))) for f in funcs)
        return _frequencies(m1, c1, w, xi, psiF / a), w

    grid = np.geomspace(a_mode[0], a_mode[-1], points)
    found = [roots(a) for a in grid]
    has = np.array([r[0].size >= 2 for r in found])
    if not has.any():
        raise ValueError(f"force: the synthesised peak lies below the mode's smallest amplitude ({a_mode[0]:.3g} "
                         f"kg^1/2 m): the force is too small to reach the mode's range; compute the mode from smaller "
                         f"amplitudes")
    last = int(np.flatnonzero(has)[-1])
    if last == points - 1:
        advice = "compute the mode to larger amplitudes" if n == mode.points else "the synthesis cannot reach its peak"
        raise ValueError(f"force: the synthesised peak lies above the mode's largest amplitude "
                         f"({a_mode[-1]:.3g} kg^1/2 m){_turn(mode.modal_amplitude, n)}; {advice}")
    a_lo, a_hi = grid[last], grid[last + 1]
    for _ in range(60):  # the peak: where the two frequencies meet, between the last amplitude with them and the next
        mid = np.sqrt(a_lo * a_hi)
        a_lo, a_hi = (mid, a_hi) if roots(mid)[0].size >= 2 else (a_lo, mid)
    a_peak = a_lo
    below, above, amps = [], [], []
    for a, (r, w) in zip(grid[:last + 1], found[:last + 1]):
        if r.size >= 2:
            below.append(r[r <= w].max() if np.any(r <= w) else r[0])
            above.append(r[r >= w].min() if np.any(r >= w) else r[-1])
            amps.append(a)
    r, w = roots(a_peak)
    w_peak = float(np.mean(r[np.argsort(np.abs(r - w))[:2]])) if r.size >= 2 else w
    Omega = np.concatenate([below, [w_peak], above[::-1]])
    a = np.concatenate([amps, [a_peak], amps[::-1]])
    m1, c1, w_mode, xi = (f(np.log(a)) for f in funcs[:4])
    theta = -np.angle(m1 * (w_mode ** 2 - Omega ** 2) + 1j * (w_mode * xi * m1 + (Omega - w_mode) * c1))
    if omega is not None:
        keep = (Omega >= lo) & (Omega <= hi)
        if not keep.any():
            raise ValueError(f"omega: the synthesised response has no point between {lo:.6g} and {hi:.6g} rad/s: it "
                             f"spans {Omega.min():.6g} to {Omega.max():.6g} rad/s (its peak at {w_peak:.6g} rad/s); "
                             f"give a range that overlaps it, or none")
        Omega, a, theta = Omega[keep], a[keep], theta[keep]
    return SynthesizedResponse(mode, F, Omega, a, theta, w_peak, float(a_peak))


def synthesize(mode, force, omega=None, *, points: int = 400) -> SynthesizedResponse:
    """Deprecated name of :func:`forced_response` (the same function; warns)."""
    deprecated("microslip.frequency.synthesis.synthesize", "microslip.frequency.synthesis.forced_response")
    return forced_response(mode, force, omega, points=points)
