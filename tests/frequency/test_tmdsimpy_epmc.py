"""Side by side with a peer: tmdsimpy's extended periodic motion concept (MIT licence; not on PyPI).

tmdsimpy (Porter et al., https://github.com/tmd-lab/tmdsimpy) solves the same EPMC equations as
``nonlinear_modes``: harmonic balance of the unforced structure with the damping ``C - xi M``, its
documented ``VibrationSystem.epmc_res`` with a ``VectorJenkins`` per contact (a Jenkins element of
stiffness ``kt`` and slip force ``Fs``: our array with one element at a held normal load). Run it when a
local copy is given (its dependency jax installed)::

    TMDSIMPY_PATH=/path/to/tmdsimpy python -m pytest tests/frequency/test_tmdsimpy_epmc.py

Amplitudes: tmdsimpy's ``10**la`` is the mass norm of the first harmonic, ``sqrt(c1' M c1 + s1' M s1)``;
ours, ``a = phi' M z_1``, is its projection onto the stuck linear mode, so ``10**la = a sqrt(modal_mass)``.
Its phase condition is ``Fl . (harmonics >= 1) = 0``; with ``Fl`` the sine part ``M phi`` it is ours
(``phi' M b_1 = 0``), so our point, rescaled, is a solution of its equations: its solver is started there.
"""

from __future__ import annotations

import numpy as np
import pytest

from microslip import MicroslipModel, Structure, nonlinear_modes

from _tmdsimpy import import_tmdsimpy

H, SAMPLES = 3, 64
KT, SLIP, KN, MU = 4e5, 5.0, 1e9, 0.5  # N/m, N, N/m, -: each contact a Jenkins element (slip force MU N)


@pytest.fixture(scope="module")
def peer():
    return import_tmdsimpy(["tmdsimpy.vibration_system", "tmdsimpy.nlforces.vector_jenkins", "tmdsimpy.solvers"],
                           "tmdsimpy's EPMC")


def chain():
    """Two masses on springs, a Jenkins contact to the ground on each (modes far from 3:1, so no internal
    resonance of the third harmonic along the mode: 1873 to 1573 rad/s against 4073 to 4505 rad/s)."""
    M = np.diag([0.5, 0.1])
    K = 1e6 * np.array([[2.0, -1.0], [-1.0, 1.5]])
    C = 4.0 * M + 1e-6 * K
    s = Structure(M, C, K)
    for dof in (0, 1):
        s.add_contact(MicroslipModel([KT], [KN], [0.0], MU), tangential=dof, approach=SLIP / (MU * KN))
    return s


def test_frequency_and_damping_equal_tmdsimpys_epmc_at_the_same_amplitudes(peer):
    s = chain()
    mode = nonlinear_modes(s, 1, (1e-6, 1e-4), harmonics=H, samples=SAMPLES)
    slip_amplitude = SLIP / KT  # the contacts slide from here on (m)
    assert mode.complete and mode.amplitude(0, 1)[-1] > 10 * slip_amplitude  # stuck to well into slip

    n = s.ndof
    system = peer["vibration_system"].VibrationSystem(s.M, s.K, C=s.C)
    for dof in (0, 1):
        Q = np.zeros((1, n))
        Q[0, dof] = 1.0
        system.add_nl_force(peer["vector_jenkins"].VectorJenkins(Q, Q.T.copy(), KT, SLIP))
    h = np.arange(H + 1)
    Fl = np.zeros((2 * H + 1) * n)
    Fl[2 * n:3 * n] = s.M @ mode.linear_mode  # phase: phi' M s1 = 0, as ours
    solver = peer["solvers"].NonlinearSolver()

    checked = 0
    for k in np.linspace(0, mode.points - 1, 6).round().astype(int):
        amplitude = mode.modal_amplitude[k] * np.sqrt(mode.modal_mass[k])  # tmdsimpy's normalisation
        la = np.log10(amplitude)
        shape = mode.shape(k)  # (2H+1, ndof), our coefficients
        guess = np.concatenate([shape[0], shape[1:].ravel() / amplitude, [mode.omega[k], mode.xi[k]]])
        fun = lambda Uwx: system.epmc_res(np.append(Uwx, la), Fl, h, Nt=SAMPLES)[0:2]  # noqa: E731
        X, R, _, sol = solver.nsolve(fun, guess, verbose=False, xtol=1e-12)
        assert sol["success"], sol["message"]
        omega, zeta = X[-2], X[-1] / (2 * X[-2])
        # the same equations (same harmonics, samples and return mapping) solved by two solvers: what
        # separates the answers is their tolerances (ours 1e-9 of the scaled Newton step); 1e-6 is 100x
        # that margin, well inside the 1e-4 asked of the comparison, and a wrong amplitude normalisation
        # (modal_mass differs from 1 by up to 1e-3 here) or a different contact law moves them by far more
        assert abs(omega / mode.omega[k] - 1) < 1e-6
        assert abs(zeta / mode.damping_ratio[k] - 1) < 1e-6
        checked += 1
    assert checked == 6
    assert np.ptp(mode.omega) > 0.05 * mode.omega[0]  # the frequency drops by more than 5 %: slip was compared
