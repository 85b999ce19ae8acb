"""Harmonic balance against time integration: a block pressed on an inclined plane.

A 0.1 kg block on two springs (x and y, 10 N/µm each) is pushed by a static force of
37.5 N (the contact's ``preload``) against a plane inclined at 30 degrees; the contact is
the paper's steel sphere tuned with 4 elements at 37.5 N. The preload is a force on the
block, so the springs take part of it: at the static equilibrium the contact carries
21.4 N, with 3 of its 4 elements closed and no tangential force (the springs are alike
in x and y, so the block moves straight along the normal). Both the tangential
displacement and the normal approach move with x and y, so the normal load -- and its
share among the elements -- varies along the cycle. The block is shaken along x with
0.6 N.

The script computes the forced response (H = 7) and compares it with explicit time
integration of the same structure and contact to the periodic steady state at five
frequencies including the resonance peak, then shows the harmonic truncation error
at the peak as H grows. Run ``python examples/inclined_block.py`` (about 10 s).
The same structure is the configuration ``inclined_block.toml`` of ``microslip frf``.
"""

from __future__ import annotations

import numpy as np

from microslip import Sphere, Structure, frequency_response, tune
from microslip.frequency import frequency_point
from microslip.frequency.analyses.transient import steady_state

FORCE = [0.6, 0.0]  # N along x: partial slip, varying normal load, the contact never opens
RANGE = (12000.0, 16500.0)  # rad/s, around the first resonance


def inclined_block(sparse: bool = False) -> Structure:
    """The block and its contact (SI units); ``sparse`` stores the matrices as scipy.sparse."""
    M = 0.1 * np.eye(2)
    K = np.diag([1e7, 1e7])
    C = 2 * 0.005 * np.sqrt(3e7 / 0.1) * M
    if sparse:
        import scipy.sparse as sp

        M, C, K = sp.csr_matrix(M), sp.csr_matrix(C), sp.csr_matrix(K)
    block = Structure(M, C, K)
    a = np.radians(30)
    block.add_contact(tune(Sphere.paper(), 37.5, elements=4), tangential=[np.cos(a), np.sin(a)],
                      normal=[-np.sin(a), np.cos(a)], preload=37.5, name="sphere")
    return block


def compare(curve, omegas, steps_per_period=2048):
    """Rows ``(omega, HB amplitude, time-integration amplitude, relative difference)`` (x, first harmonic).

    The curve must be single-valued at ``omegas`` (one steady state per frequency).
    """
    rows = []
    for w in omegas:
        a = frequency_point(curve.structure, FORCE, w, harmonics=curve.harmonics).amplitude(0, 1)[0]
        ss = steady_state(curve.structure, FORCE, w, steps_per_period=steps_per_period, tolerance=1e-8)
        rows.append((w, a, ss.amplitude(0, 1), a / ss.amplitude(0, 1) - 1))
    return rows


def truncation(structure, omega, harmonics=(1, 2, 3, 5, 7, 11, 15)):
    """Rows ``(H, relative error of max |x - x0|)`` against time integration at ``omega``."""
    ss = steady_state(structure, FORCE, omega, steps_per_period=2048, tolerance=1e-8)
    rows = []
    for H in harmonics:
        r = frequency_point(structure, FORCE, omega, harmonics=H)
        rows.append((H, r.amplitude(0)[0] / ss.amplitude(0) - 1))
    return rows


def main():
    block = inclined_block()
    curve = frequency_response(block, FORCE, RANGE, harmonics=7)
    w_peak, _ = curve.peak(0, 1)
    print(f"curve: {curve.points} points in {curve.elapsed:.3f} s; peak at {w_peak:.1f} rad/s")
    print("omega (rad/s)   HB x1 (um)   time integration x1 (um)   difference")
    for w, a, b, d in compare(curve, [12500.0, 14500.0, w_peak, 15900.0, 16400.0]):
        print(f"{w:12.1f}   {a * 1e6:10.5f}   {b * 1e6:12.5f}              {d:+.2e}")
    print("H    error of max |x - x0| at the peak")
    for H, e in truncation(block, w_peak):
        print(f"{H:2d}   {e:+.2e}")


if __name__ == "__main__":
    main()
