"""The MDR reference on the contact plane: exact along straight lines, element by element on curved orbits."""

from __future__ import annotations

import runpy
import sys

import numpy as np
import pytest

from _paths import REPO
from microslip import Sphere, mdr, paths

SPHERE = Sphere.paper()


@pytest.fixture(scope="module")
def reference():
    return mdr(SPHERE, max_load=37.5, elements=1600)


@pytest.mark.parametrize("angle", [0.0, 30.0, 135.0])
def test_a_straight_line_at_any_angle_is_mindlins_loop(reference, angle):
    """Along a line every increment is parallel: the MDR on the plane is the 1D MDR along the line, whose
    energy per cycle at constant load is Mindlin's formula (1600 elements: within 4.7e-6 of it at
    T*/(mu N) = 0.5, tests/reference/test_mdr.py; here T* = 0.65 mu N, measured 2e-8). At constant load
    the stepped energy does not depend on the step."""
    N = 30.0
    amplitude = 0.5 * float(SPHERE.gross_slip_displacement(N))
    line = paths.line(SPHERE, amplitude, N, angle_deg=angle, cycles=2, steps_per_cycle=720)
    loop = paths.loop(SPHERE, N, amplitude, cycles=2, steps_per_cycle=720)
    plane, one = line.simulate(reference), loop.simulate(reference)
    e = np.array([np.cos(np.radians(angle)), np.sin(np.radians(angle))])
    np.testing.assert_allclose(plane.T @ e, one.T, rtol=0, atol=1e-12 * 0.4 * N)  # rounding of the plane's step
    W = plane.friction_work[line.steady][1:].sum()
    T_star = float(np.abs(one.T[loop.steady]).max())
    assert W == pytest.approx(float(SPHERE.dissipation(T_star, N)), rel=5e-6)


def test_a_circle_in_gross_slip_dissipates_each_elements_closed_form(reference):
    """On a circle of radius R beyond every element's stick radius delta_i = mu N_i / kt_i, each element
    slides round its own circle (test_plane.py derives it): with h = 2 pi / M per step, the slider runs
    on rho_i = sqrt(R^2 - delta_i^2 cos^2(h/2)) - delta_i sin(h/2) and each step dissipates
    mu N_i 2 rho_i sin(h/2). The march settles on it from the lead-in spiral (checked at 1e-9; the
    orbit is attracting), and as h -> 0 the energy tends to 2 pi sum_i mu N_i sqrt(R^2 - delta_i^2)."""
    N = 25.0
    n = float(SPHERE.approach(N))
    Ni = reference.element_normal_forces(n)
    closed = Ni > 0
    delta = reference.mu * Ni[closed] / reference.kt[closed]
    R = 2.0 * delta.max()
    M = 1440
    h = 2 * np.pi / M
    path = paths.circle(SPHERE, R, N, cycles=6, steps_per_cycle=M)
    W = path.simulate(reference).friction_work[path.steady][1:].sum()
    rho = np.sqrt(R**2 - delta**2 * np.cos(h / 2) ** 2) - delta * np.sin(h / 2)
    assert W == pytest.approx(float(np.sum(M * reference.mu * Ni[closed] * 2 * rho * np.sin(h / 2))), rel=1e-9)
    continuous = 2 * np.pi * float(np.sum(reference.mu * Ni[closed] * np.sqrt(R**2 - delta**2)))
    assert W == pytest.approx(continuous, rel=np.pi * 0.5 / M)  # first order: about pi delta / (M rho) <= pi/(M sqrt 3)


def test_the_energy_script_runs_its_quick_table(capsys, monkeypatch):
    """scripts/plane_energy.py (its numbers are in the README) in its quick form: a table of energies per
    cycle on a circle and an ellipse, the tuned arrays' errors against the MDR reference."""
    monkeypatch.setattr(sys, "argv", ["plane_energy.py", "--quick"])
    with pytest.raises(SystemExit) as done:
        runpy.run_path(str(REPO / "scripts" / "plane_energy.py"), run_name="__main__")
    assert done.value.code == 0
    out = capsys.readouterr().out
    assert "circle" in out and "ellipse" in out and "J = 11 (optimised)" in out
    assert "largest |energy error| against the MDR reference (%)" in out
