"""The examples run as users run them (examples that are tests)."""

import csv
import sys

import numpy as np
import pytest

from _paths import EXAMPLES
from microslip import Sphere, accuracy, mdr, paths, tune
from microslip.kernels import element as _kernels
from microslip.frequency import frequency_point

sys.path.insert(0, str(EXAMPLES))

import bladed_disk  # noqa: E402
import fe_blade  # noqa: E402
import variable_normal_load  # noqa: E402

EXACT, PAPER = "exact (MDR, 2000 elements)", "paper's array, J = 4"


def test_variable_normal_load_example(tmp_path):
    out = tmp_path / "loops.png"
    energies = variable_normal_load.main(out=out)
    assert out.stat().st_size > 20_000
    # the example's path, rebuilt from its defaults (N = 20 + 12 sin(tau + phi) N, t_a = t_gs(8 N))
    sphere = Sphere.paper()
    N_m, N_a = 20.0, 12.0
    t_a = float(sphere.gross_slip_displacement(N_m - N_a))
    paper = tune(sphere, 37.5, elements=4)
    exact, finer = mdr(sphere, max_load=37.5, elements=2000), mdr(sphere, max_load=37.5, elements=8000)
    for phase in (0.0, 90.0, 180.0):
        path = paths.variable_load_cycles(sphere, N_m, N_a, t_a, phase)
        steady = path.steady
        # the exact contact: MDR converges as J^-2 (on this path 8.4e-6 at 1000 elements, 6e-7 at 2000
        # against 16000), so 2000 elements agree with 8000 within 1e-5
        W_finer = float(path.simulate(finer).friction_work[steady][1:].sum())
        assert energies[phase, EXACT] == pytest.approx(W_finer, rel=1e-5)
        # the paper's array: the same energy from the kernel's pure-Python twin (rounding of the ~360 steps'
        # sums only)
        W = _kernels.march_reference(paper.kt, paper.kn, paper.gaps, paper.mu, path.t, path.n,
                                     np.zeros(paper.elements))[2]
        assert energies[phase, PAPER] == pytest.approx(float(np.sum(W[steady][1:])), rel=1e-12)
        # the ratio as the accuracy report measures it (the area of the steady loop, trapezoidal): both
        # energies converge to the same limit as the cycle is refined (each within 0.6 % at 360 samples,
        # in the same direction for both models), so the ratios agree to 1e-3 (measured 4.4e-4)
        rep = accuracy(paper, exact, [path])
        ratio = energies[phase, PAPER] / energies[phase, EXACT]
        assert ratio == pytest.approx(rep.energy[0] / rep.energy_reference[0], rel=1e-3)
    # phases 0 and 180 degrees are mirror images (t -> -t half a cycle later): the same energies to the
    # rounding of the two marches (measured 3e-16)
    for name in (EXACT, PAPER):
        assert energies[180.0, name] == pytest.approx(energies[0.0, name], rel=1e-12)


def test_variable_normal_load_script_writes_into_the_folder_given(tmp_path):
    """Run as a script it wrote its figure next to itself, over the tracked examples/variable_normal_load.png."""
    import os
    import subprocess

    tracked = EXAMPLES / "variable_normal_load.png"
    before = tracked.stat().st_mtime_ns
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(EXAMPLES.parent / "src"), os.environ.get("PYTHONPATH", "")])}
    script = str(EXAMPLES / "variable_normal_load.py")
    done = subprocess.run([sys.executable, script, "--out", str(tmp_path / "figs")], capture_output=True, text=True,
                          env=env, cwd=tmp_path, timeout=300)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "figs" / "variable_normal_load.png").stat().st_size > 20_000
    assert tracked.stat().st_mtime_ns == before
    a_file = tmp_path / "figs" / "variable_normal_load.png"
    bad = subprocess.run([sys.executable, script, "--out", str(a_file)], capture_output=True, text=True, env=env,
                         timeout=120)
    assert bad.returncode == 2 and "is a file, not a folder" in bad.stderr


def test_fe_blade_example(tmp_path):
    rows = fe_blade.main(out=tmp_path)
    assert (tmp_path / "fe_blade_response.png").stat().st_size > 20_000
    with open(tmp_path / "fe_blade_response.csv") as f:
        written = list(csv.DictReader(f))
    assert [float(r["omega [rad/s]"]) for r in written] == [r["omega [rad/s]"] for r in rows]
    assert [float(r["harmonic balance [m]"]) for r in written] == [r["harmonic balance [m]"] for r in rows]
    omega = np.array([r["omega [rad/s]"] for r in rows])
    hb = np.array([r["harmonic balance [m]"] for r in rows])
    # five frequencies, sorted, the peak of the curve in the middle: the largest response of the five
    assert np.all(np.diff(omega) > 0) and int(np.argmax(hb)) == 2
    # started on the harmonic balance solution, time integration differs by the truncation of the
    # 11 harmonics (falling slowly and not monotonically: the contact forces have kinks; measured up
    # to 2.5e-4, at the peak) and the time step (2e-5 at 1024 steps per period)
    assert max(abs(r["difference from it [-]"]) for r in rows) < 4e-4
    # from rest: the same steady state at the peak, where the response builds up without overshoot
    # (measured 1.8e-6 apart, within the convergence of the two runs); off it the start-up transient
    # beats (its first peaks 1.6 times the steady amplitude at 12500 rad/s) and makes contact elements
    # slip that then stick through the steady cycle with another force: 0.26 % to 1.2 % apart
    on, rest = (np.array([r[k] for r in rows]) for k in ("time integration from it [m]",
                                                          "time integration from rest [m]"))
    assert abs(rest[2] / on[2] - 1) < 1e-5
    assert np.all(np.abs(np.delete(rest / on - 1, 2)) > 1e-3)
    # the Craig-Bampton model (10 fixed-interface modes) against the whole blade at the peak, solved
    # here with the modal condensation onto the contact DOFs (40 modes): measured 8e-6 apart
    b, structure, tip = fe_blade.blade_with_contacts()
    force = np.zeros(structure.ndof)
    force[tip] = fe_blade.FORCE
    whole = frequency_point(structure, force, omega[2], harmonics=11, reduction="modal", modes=40)
    assert whole.amplitude(tip, 1)[0] == pytest.approx(hb[2], rel=1e-4)


def test_bladed_disk_example(tmp_path):
    result = bladed_disk.main(out=tmp_path, quick=True)  # 40 N and 320 N: the full run adds 3 to 160 N
    for name in ("bladed_disk.png", "bladed_disk_contacts.png"):
        assert (tmp_path / name).stat().st_size > 50_000
    curve, limits, s = result["curve"], result["limits"], result["sector"]
    assert list(curve.loads) == bladed_disk.QUICK_LOADS and s.sectors == 24
    for load, r in zip(curve.loads, curve.responses):
        d = bladed_disk.damper(s, result["laws"], load)
        d.attach(s)  # names the damper's contacts as in the response
        assert d.static_balance(r) < 1e-10  # Newton's static tolerance, relative to the load
        assert r.engine_order == 3 and r.complete
    free, stuck = (limits[k].peak(bladed_disk.TIP) for k in ("no damper", "damper stuck"))
    # the blade alone resonates at its first natural frequency (a linear response: to the continuation's
    # resolution of the peak, 1e-4)
    assert free[0] == pytest.approx(result["free"], rel=1e-4)
    # at 320 N the damper sticks along the whole curve: the response is the linear one with friction that never
    # slips (their static states differ, the one sliding into place, hence 1e-2; measured 5e-4)
    w, a = curve.peak_frequency[-1], curve.peak_amplitude[-1]
    assert w == pytest.approx(stuck[0], rel=1e-3) and a == pytest.approx(stuck[1], rel=1e-2)
    assert curve.responses[-1].contact_dissipation.max() < 1e-3 * curve.responses[-1].excitation_work.max()
    # at 40 N the damper slips and dissipates: the peak falls far below both limits, between their frequencies
    assert curve.peak_amplitude[0] < 0.5 * min(free[1], stuck[1]) and free[0] < curve.peak_frequency[0] < stuck[0]
    # the contacts at that peak: the flat face rocks (one contact lifts off part of the cycle), the curved face's
    # holds; every sample in one state
    cycles = {cy.name: cy for cy in result["cycles"]}
    assert cycles["flat1"].fractions()["lift-off"] > 0.1 and cycles["curved2"].fractions()["lift-off"] == 0
    for cy in cycles.values():
        assert sum(cy.fractions().values()) == pytest.approx(1.0, abs=1e-12)
