"""Contacts moving on their planes in structures: directions, harmonic balance against time integration,
the one-direction case, reductions, the contact's cycle and the configuration file."""

import numpy as np
import pytest

from microslip.frequency import (CyclicStructure, Structure, contact_cycle, craig_bampton, frequency_point,
                                 frequency_response, steady_state)
from microslip.kernels import aft as _aft

from _models import PLANE_APPROACH, PLANE_CONTACT, PLANE_FORCE, plane_chain


def puck(kx=1e5, ky=1.2e5, zeta=0.01) -> Structure:
    """One mass (1 kg) moving in x and y on springs, with a contact on its plane to the ground, the normal load
    imposed. Its two modes differ, so a force at an angle to the axes drives an elliptical orbit."""
    s = Structure(np.eye(2), np.diag([2 * zeta * np.sqrt(kx), 2 * zeta * np.sqrt(ky)]), np.diag([kx, ky]))
    s.add_contact(PLANE_CONTACT, tangential=[{0: 1.0}, {1: 1.0}], approach=PLANE_APPROACH, name="puck")
    return s


# -- directions ------------------------------------------------------------------------------------------

@pytest.mark.parametrize("tangential", [[0, 2], [{0: 1.0}, {2: 1.0}], [[1.0, 0, 0], [0, 0, 1.0]],
                                        np.array([[1.0, 0, 0], [0, 0, 1.0]]), ([1.0, 0, 0], 2)])
def test_two_tangential_directions_in_any_form(tangential):
    s = Structure(np.eye(3), None, np.eye(3))
    c = s.add_contact(PLANE_CONTACT, tangential=tangential, approach=1e-6)
    assert c.planar
    np.testing.assert_array_equal(c.tangential, [1, 0, 0])
    np.testing.assert_array_equal(c.tangential2, [0, 0, 1])
    np.testing.assert_array_equal(s.second_tangential_directions(), [[0], [0], [1]])
    # the stuck stiffness holds both directions
    np.testing.assert_array_equal(np.diag(s.stuck_stiffness()), [1 + 6e4, 1, 1 + 6e4])


def test_a_flat_list_of_numbers_is_one_direction():
    s = Structure(np.eye(2), None, np.eye(2))
    c = s.add_contact(PLANE_CONTACT, tangential=[0.6, 0.8], approach=1e-6)
    assert not c.planar and c.tangential2 is None
    np.testing.assert_array_equal(s.second_tangential_directions(), [[0.0], [0.0]])


def test_dof_names_give_two_directions():
    from microslip.fe import DofMap

    s = Structure(np.eye(3), None, np.eye(3), dof_map=DofMap.from_names(["12:x", "12:y", "12:z"]))
    c = s.add_contact(PLANE_CONTACT, tangential=["12:x", "12:y"], normal="12:z", preload=1.0)
    np.testing.assert_array_equal([c.tangential, c.tangential2], [[1, 0, 0], [0, 1, 0]])


@pytest.mark.parametrize("tangential, message", [
    ([0, 1], "tangential = \\[0, 1\\] is ambiguous on a structure of 2 DOFs.*\\[\\{0: 1.0\\}, \\{1: 1.0\\}\\].*"
             "\\[0.0, 1.0\\]"),
    ([{0: 1.0}, {0: 2.0}], "tangential\\[1\\] must not be parallel to tangential\\[0\\]"),
    ([{0: 1.0}, {5: 1.0}], "tangential\\[1\\]: DOF 5 is out of range"),
    ([{0: 1.0}, [1.0]], "tangential\\[1\\] must have one coefficient per DOF \\(2\\), got 1"),
    ([{0: 1.0}, {1: 0.0}], "tangential\\[1\\] must not be all zeros"),
])
def test_direction_errors_name_the_item(tangential, message):
    s = Structure(np.eye(2), None, np.eye(2))
    with pytest.raises(ValueError, match=message):
        s.add_contact(PLANE_CONTACT, tangential=tangential, approach=1e-6)


def test_a_cyclic_sector_refuses_two_directions():
    disk = CyclicStructure(np.eye(3), None, np.eye(3) * 1e4, sectors=6, left=[0], right=[2])
    with pytest.raises(ValueError, match="two tangential directions .* are for a Structure"):
        disk.add_contact(PLANE_CONTACT, tangential=[{1: 1.0}, {0: 1.0}], approach=1e-6)


# -- harmonic balance --------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def curve():
    """The curve at the default samples, to locate the peak (single-valued over this range)."""
    return frequency_response(puck(), PLANE_FORCE, (330.0, 440.0), harmonics=5, stability=False)


@pytest.mark.parametrize("where", ["peak", 370.0, 395.0, 415.0, 432.0])
def test_harmonic_balance_equals_time_integration_on_an_elliptical_orbit(curve, where):
    omega = curve.peak(0)[0] if where == "peak" else where
    # 2048 AFT samples: on a curved orbit the sampled radial return errs to first order in the step; the
    # difference below is 1.8e-2 with the default 128 samples (H = 7), 4e-3 with 512, 1.7e-4 to 6.6e-4 with 2048
    point = frequency_point(puck(), PLANE_FORCE, omega, harmonics=7, samples=2048, stability=False)
    # an ellipse, not a line: the first harmonics of x and y enclose an area (a1 b2 - b1 a2 = 0 on a line)
    (a1, b1), (a2, b2) = point.contact_t[0, 0, 1:3], point.contact_t2[0, 0, 1:3]
    assert abs(a1 * b2 - b1 * a2) > 0.3 * np.hypot(a1, b1) * np.hypot(a2, b2)
    cycle = contact_cycle(point, 0, 0)
    assert cycle.fractions()["gross slip"] > 0.2  # elements slip: the friction is not a linear spring
    ti = steady_state(puck(), PLANE_FORCE, omega, harmonics=7, steps_per_period=4096, tolerance=1e-9, start=point)
    assert ti.converged
    # every DOF and harmonic, to the largest dynamic coefficient (the time integration's own step changes it by
    # less than 1e-4: 4096 against 16384 steps)
    scale = np.abs(ti.coefficients[1:]).max()
    assert np.abs(point.coefficients[0] - ti.coefficients).max() < 1e-3 * scale, omega
    # harmonic balance conserves the energy of the harmonics kept; the friction work agrees with it to the
    # sampling and is never negative
    balance = point.viscous_dissipation[0] + point.contact_harmonic_work[0].sum() - point.excitation_work[0]
    assert abs(balance) < 1e-6 * point.excitation_work[0]
    assert 0 < point.contact_dissipation[0, 0] == pytest.approx(point.contact_harmonic_work[0, 0], rel=1e-2)


def test_the_curve_has_its_peak_inside_the_range(curve):
    assert np.all(np.diff(curve.omega) > 0)  # single-valued: one steady state per frequency
    assert 345.0 < curve.peak(0)[0] < 370.0


def test_a_contact_on_its_plane_moving_along_a_line_is_the_one_direction_contact():
    """Excited along x only, with nothing coupling y, the plane contact's y stays at rest: it is the x contact."""
    plane = Structure(np.eye(2), 0.02 * np.sqrt(1e5) * np.eye(2), np.diag([1e5, 1.2e5]))
    plane.add_contact(PLANE_CONTACT, tangential=[{0: 1.0}, {1: 1.0}], approach=PLANE_APPROACH)
    line = Structure(np.eye(2), 0.02 * np.sqrt(1e5) * np.eye(2), np.diag([1e5, 1.2e5]))
    line.add_contact(PLANE_CONTACT, tangential={0: 1.0}, approach=PLANE_APPROACH)
    a = frequency_response(plane, [1.5, 0.0], (300.0, 420.0), harmonics=5, stability=False)
    b = frequency_response(line, [1.5, 0.0], (300.0, 420.0), harmonics=5, stability=False)
    assert not a.contact_t2.any() and not a.contact_T2.any()
    # the same equations, the same forces (the AFT on the plane equals the line's to the bit there) and the same
    # Jacobian to rounding: the same curve to the continuation's tolerance
    np.testing.assert_array_equal(a.omega.size, b.omega.size)
    np.testing.assert_allclose(a.coefficients, b.coefficients, atol=1e-9 * np.abs(b.coefficients).max())
    np.testing.assert_allclose(a.contact_dissipation, b.contact_dissipation, rtol=1e-8)


@pytest.mark.parametrize("reduction", ["exact", "modal"])
def test_reductions_keep_both_directions(reduction):
    """A chain of masses with the plane contact on the last one's x and y: reduced to the contact DOFs."""
    n = 6
    s, force = plane_chain(n)
    full = frequency_point(s, force, 80.0, harmonics=3, reduction="none", stability=False)
    red = frequency_point(s, force, 80.0, harmonics=3, reduction=reduction, stability=False,
                          modes=2 * n - 1 if reduction == "modal" else None)
    assert set(red.dofs) == {2 * n - 2, 2 * n - 1}
    # exact: the same equations to solver tolerance; modal with every mode but one plus the residual flexibility
    # of the one omitted (a static correction of the highest mode, 1400 rad/s against 80): 2e-5 measured
    tol = 1e-9 if reduction == "exact" else 1e-4
    for dof in (2 * n - 2, 2 * n - 1, 0, 1):
        assert red.amplitude(dof)[0] == pytest.approx(full.amplitude(dof)[0], rel=tol)
    np.testing.assert_allclose(red.contact_T2, full.contact_T2, atol=tol * np.abs(full.contact_T2).max())


def test_stability_and_the_static_state_with_a_plane_contact():
    s = puck()
    s.add_static_force([0.5, 1.0])  # a static push at an angle: a static tangential force in both directions
    r = frequency_response(s, {0: [0.5, 1.0], 1: PLANE_FORCE}, (300.0, 420.0), harmonics=5)
    assert r.stable is not None and r.stable.all()  # a single-valued curve of a damped structure
    # statically stuck (|T0| = 0.76 N < mu N = 2.1 N): each direction shares its load [1, 2] N between its
    # spring and the contact's stuck stiffness sum(kt) = 6e4 N/m
    slip_force = PLANE_CONTACT.mu * r.static_normal_force[0]
    assert np.hypot(r.static_tangential_force, r.static_tangential_force2)[0] < slip_force
    assert r.static_tangential_force[0] == pytest.approx(6e4 / 1.6e5 * 1.0, rel=1e-9)
    assert r.static_tangential_force2[0] == pytest.approx(6e4 / 1.8e5 * 2.0, rel=1e-9)


def test_the_cycle_at_a_point_carries_the_harmonic_balance_forces():
    point = frequency_point(puck(), PLANE_FORCE, 360.0, harmonics=7, stability=False)
    cy = contact_cycle(point, "puck", 0)
    # the harmonic balance's own march (same samples, same periodic state to 32 ulps): its forces to rounding
    P = _aft.tables(7, point.samples)[1]
    np.testing.assert_allclose(P @ cy.T, point.contact_T[0, 0], atol=1e-12)
    np.testing.assert_allclose(P @ cy.T2, point.contact_T2[0, 0], atol=1e-12)
    # the friction law on the plane: |T| <= mu N. In gross slip every element's force has its full length
    # mu N_i, but along its own slider's lag, so the sum falls just short of mu N (here by 1.1e-4)
    size = np.hypot(cy.T, cy.T2)
    assert np.all(size <= PLANE_CONTACT.mu * cy.N * (1 + 1e-12))
    gross = cy.state == 2
    assert gross.any()
    np.testing.assert_allclose(size[gross], PLANE_CONTACT.mu * cy.N[gross], rtol=1e-3)


def test_craig_bampton_keeps_the_contact_on_its_plane(tmp_path):
    from microslip.frequency import CraigBampton

    s = Structure(np.eye(3), None, np.array([[2e5, -1e5, 0], [-1e5, 2e5, -1e5], [0, -1e5, 1e5]]))
    s.add_contact(PLANE_CONTACT, tangential=[{1: 1.0}, {2: 1.0}], approach=PLANE_APPROACH)
    cb = craig_bampton(s, keep=[1, 2], modes=1)
    c = cb.structure.contacts[0]
    assert c.planar
    path = cb.save(tmp_path / "cb.npz")
    again = CraigBampton.load(path).structure.contacts[0]
    np.testing.assert_array_equal(again.tangential2, c.tangential2)


def test_the_configuration_file_takes_two_tangential_directions(tmp_path):
    from microslip.config import ConfigError, load_config

    PLANE_CONTACT.save(tmp_path / "contact.json")
    text = """
[structure]
M = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
K = [[1e5, 0.0, 0.0], [0.0, 1.2e5, 0.0], [0.0, 0.0, 1e5]]
[[contact]]
model = "contact.json"
tangential = TANGENTIAL
approach = "1um"
[excitation]
h1 = [1.0, 0.5, 0.0]
[sweep]
omega = [300, 420]
harmonics = 3
"""
    for tangential, second in (('[{"0" = 1.0}, {"1" = 1.0}]', [0, 1, 0]), ("[0, 2]", [0, 0, 1]),
                               ("[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]", [0, 1, 0])):
        (tmp_path / "frf.toml").write_text(text.replace("TANGENTIAL", tangential))
        contact = load_config(tmp_path / "frf.toml").structure.contacts[0]
        np.testing.assert_array_equal(contact.tangential2, second)
    (tmp_path / "frf.toml").write_text(text.replace("TANGENTIAL", '[{"0" = 1.0}, {"0" = -1.0}]'))
    with pytest.raises(ConfigError, match="\\[\\[contact\\]\\] 1: tangential\\[1\\] must not be parallel"):
        load_config(tmp_path / "frf.toml")


def test_the_frf_command_reports_a_contact_on_its_plane(tmp_path, capsys):
    from microslip.cli import main

    PLANE_CONTACT.save(tmp_path / "contact.json")
    (tmp_path / "frf.toml").write_text(f"""
[structure]
M = [[1.0, 0.0], [0.0, 1.0]]
K = [[1e5, 0.0], [0.0, 1.2e5]]
[[contact]]
model = "contact.json"
tangential = [{{"0" = 1.0}}, {{"1" = 1.0}}]
approach = "1um"
name = "puck"
[excitation]
h1 = {[float(f) for f in PLANE_FORCE]}
[sweep]
omega = [330, 440]
harmonics = 3
""")
    assert main(["frf", str(tmp_path / "frf.toml"), "--out", str(tmp_path / "out")]) == 0
    header = (tmp_path / "out" / "contact_cycle.csv").read_text().splitlines()[0]
    assert "puck T [N]" in header and "puck T2 [N]" in header
    line = next(x for x in capsys.readouterr().out.splitlines() if x.startswith("Contact puck at the peak"))
    # the size of the force on the plane, within mu N = 2.1 N
    assert 1.0 < float(line.split("|T| up to ")[1].split(" N")[0]) <= 2.1
