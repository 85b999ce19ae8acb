"""A scikit-fem blade with microslip contacts under its platform, solved like a finite-element model.

The blade of :func:`microslip.fe.blade` at 384 free DOFs (plane stress, 9-node quadrilaterals,
clamped at the root), damped in proportion to its stiffness (0.5 % at its first mode). Two nodes
under each platform overhang touch a fixed counterpart through the paper's sphere (4 elements
tuned at 37.5 N): tangential along the chord (x), normal along the span (pressing the platform
down, -y), each pressed by a static force of 25 N that the platform shares with the contact. A
1 N force along x at the tip excites the first bending mode; the platform rocks, so the normal
loads of the two sides breathe in opposition. Checked:

* harmonic balance on the contact DOFs (``reduction="exact"``, ``"modal"``) against every DOF an
  unknown (``"none"``);
* a Craig-Bampton model (the contact and tip DOFs plus 10 fixed-interface modes) against the
  blade;
* harmonic balance on that model against its time integration, at five frequencies including the
  peak of the microslip resonance.
"""

import numpy as np
import pytest

from microslip import Sphere, Structure, tune
from microslip.fe import blade, natural_frequencies
from microslip.frequency import craig_bampton, frequency_point, frequency_response, steady_state

PRELOAD = 25.0  # N on each contact node
FORCE = 1.0  # N along x at the tip
H = 11  # harmonics of the comparison with time integration (see there)


@pytest.fixture(scope="module")
def model():
    """``(structure, tip row, kept rows)``: the blade with its four contacts."""
    b = blade(300, contact_nodes=2)
    w1 = 2 * np.pi * natural_frequencies(b.M, b.K, 1)[0]
    s = Structure(b.M, (2 * 0.005 / w1) * b.K, b.K, dof_map=b.dof_map)
    sphere = tune(Sphere.paper(), 37.5, elements=4)
    for node in b.platform_nodes:
        s.add_contact(sphere, tangential=f"{node}:x", normal={f"{node}:y": -1.0}, preload=PRELOAD)
    tip = s.dof_index(f"{b.tip_node}:x")
    contact_rows = [s.dof_index(f"{node}:{c}") for node in b.platform_nodes for c in "xy"]
    return s, tip, np.array(contact_rows + [tip])


def tip_force(s, tip):
    f = np.zeros(s.ndof)
    f[tip] = FORCE
    return f


@pytest.fixture(scope="module")
def reduced(model):
    """The Craig-Bampton model: the 9 kept rows (the tip last) and 10 fixed-interface modes."""
    s, tip, keep = model
    return craig_bampton(s, keep, modes=10)


@pytest.fixture(scope="module")
def frequencies(reduced):
    """Two below the microslip resonance, its peak, two above (the stuck blade resonates at 14450 rad/s).

    The peak of the tip's first harmonic, from a curve with 5 harmonics (the one with 11 peaks
    within 0.5 rad/s of it, where the amplitude is flat).
    """
    cb, tip = reduced.structure, reduced.keep.size - 1
    curve = frequency_response(cb, tip_force(cb, tip), (12900.0, 13700.0), harmonics=5, reduction="exact",
                               stability=False)
    peak, _ = curve.peak(tip, 1)
    return (11500.0, 12500.0, peak, 13800.0, 14500.0)


def test_the_blade_and_its_contacts(model, frequencies):
    """384 DOFs; each contact carries part of its preload statically and its load breathes with the motion."""
    s, tip, keep = model
    assert s.ndof == 384 and len(s.contacts) == 4 and s.sparse
    r = frequency_point(s, tip_force(s, tip), frequencies[2], harmonics=5, reduction="exact")
    N0 = r.static_normal_force
    assert np.all((N0 > 5.0) & (N0 < PRELOAD))  # the platform's own stiffness takes the rest
    np.testing.assert_allclose(N0[:2], N0[2:], rtol=1e-9)  # the blade is symmetric about its mid-chord
    N1 = np.hypot(r.contact_N[0, :, 1], r.contact_N[0, :, 2])
    assert np.all(N1 > 0.25 * r.contact_N[0, :, 0])  # at the peak the loads vary by 32 % and 75 % (measured)
    # the two sides breathe in opposition: the platform rocks
    np.testing.assert_allclose(r.contact_N[0, :2, 1:3], -r.contact_N[0, 2:, 1:3], rtol=1e-6)


@pytest.mark.parametrize("k", [2, 4])
def test_reductions_equal_the_full_solve(model, frequencies, k):
    """At the peak and above the stuck resonance.

    ``exact``: the same solution to Newton's tolerance (1e-9 on the residual: 1e-7 of the largest
    coefficient, as on the chains of test_reduction). ``modal``: within the estimate each result
    states (measured 4.4e-6 and 1.6e-6 with 40 modes, estimates 1.5e-5 and 1.7e-5), and ten times
    better with 40 modes than with 10 (measured 33 and 45 times; before the omitted modes' damping
    was carried, 1.5 and 2.4 times, the error stuck near 3e-3).
    """
    s, tip, _ = model
    f, omega = tip_force(s, tip), frequencies[k]
    full = frequency_point(s, f, omega, harmonics=5, reduction="none")
    scale = np.max(np.abs(full.coefficients[0]))
    exact = frequency_point(s, f, omega, harmonics=5, reduction="exact")
    assert exact.reduction == "exact" and exact.dofs.size == 9
    assert np.max(np.abs(exact.coefficients[0] - full.coefficients[0][:, exact.dofs])) < 1e-7 * scale
    errors = {}
    for modes in (10, 40):
        modal = frequency_point(s, f, omega, harmonics=5, reduction="modal", modes=modes)
        errors[modes] = np.max(np.abs(modal.coefficients[0] - full.coefficients[0][:, modal.dofs])) / scale
    assert errors[40] < modal.reduction_error, (errors, modal.reduction_error)
    assert errors[40] < errors[10] / 10, errors


def test_the_craig_bampton_model_equals_the_blade(model, reduced, frequencies):
    """10 fixed-interface modes (of 375): the tip's first harmonic within 1e-4 at the five frequencies.

    Measured 3.4e-6 to 3.8e-5: the first mode omitted lies at 6.0e5 rad/s, eight times the highest
    frequency of the fifth harmonic (7.3e4 rad/s).
    """
    s, tip, _ = model
    cb, cb_tip = reduced.structure, reduced.keep.size - 1
    for omega in frequencies:
        a = frequency_point(s, tip_force(s, tip), omega, harmonics=5, reduction="exact").amplitude(tip, 1)[0]
        b = frequency_point(cb, tip_force(cb, cb_tip), omega, harmonics=5, reduction="exact").amplitude(cb_tip, 1)[0]
        assert b == pytest.approx(a, rel=1e-4), omega


def test_harmonic_balance_agrees_with_time_integration(reduced, frequencies):
    """Harmonic balance (H = 11, reduced to the contact and tip DOFs) against central differences.

    Time integration of the Craig-Bampton model, 1024 steps per period, started on the harmonic
    balance solution (so that the elements sticking through the cycle keep the force harmonic
    balance gives them; from rest they differ off the resonance: see ``steady_state``) and run
    until the first harmonic changes by less than 1e-8 per period. What separates the two:

    * the harmonics: the contact elements open and close and stick and slip within the cycle, so
      the contact forces have kinks and the truncation falls slowly and not monotonically with H
      (against time integration at 4096 steps, largest over the five frequencies: 6e-3 for H = 3,
      8.5e-4 for H = 5, 1.8e-3 for H = 7, 1.6e-4 for H = 11; at 13800 rad/s with 1024 samples
      1.8e-4 for H = 11, 3.2e-4 for H = 15, 2.3e-4 for H = 21 and 9e-6 for H = 31, where time
      integration from each of these solutions lands on the same motion within 2e-6);
    * the time step: 2.4e-5 at 1024 steps (the difference to 4096 steps falls like dt^2).

    Measured at H = 11 and 1024 steps: 2.3e-5, 4.4e-5, 1.3e-4 (the peak), 1.8e-4 and 1.6e-5; held
    at 3e-4, the truncation's 1.6e-4 plus the step's 2.4e-5 with a margin of 1.6.
    """
    cb, tip = reduced.structure, reduced.keep.size - 1
    f = tip_force(cb, tip)
    for omega in frequencies:
        hb = frequency_point(cb, f, omega, harmonics=H, reduction="exact")
        ti = steady_state(cb, f, omega, steps_per_period=1024, harmonics=1, tolerance=1e-8, start=hb)
        assert ti.converged
        assert hb.amplitude(tip, 1)[0] == pytest.approx(ti.amplitude(tip, 1), rel=3e-4), omega
