"""The under-platform damper between two blade platforms: static equilibrium, limits, time integration."""

import warnings

import numpy as np
import pytest
from scipy.optimize import root

from microslip import MicroslipModel, Sphere, tune
from microslip.kernels.element import STICK
from microslip.frequency import (CyclicStructure, Structure, UnderPlatformDamper, damper_design_curve, frequency_point,
                                 frequency_response, steady_state, time_samples)

SPHERE = Sphere.paper()
CURVED = tune(SPHERE, 37.5, elements=4)
FLAT = tune(SPHERE, 37.5, elements=4)
LOAD = 50.0  # N, centrifugal: about 35 N on each interface


def blade_pair(mass_damping=1.0, stiffness_damping=1e-6):
    """Two blades, DOFs [px0, py0, tip0, px1, py1, tip1]: platforms on springs, a tip on each platform.

    Rayleigh damping ``C = mass_damping M + stiffness_damping K`` (1/s and s).
    """
    K = np.zeros((6, 6))
    for b in (0, 3):
        K[b, b] += 5e6          # platform, circumferential
        K[b + 1, b + 1] += 2e7  # platform, radial
        for i, j in ((b, b + 2),):
            K[i, i] += 1e6
            K[j, j] += 1e6
            K[i, j] -= 1e6
            K[j, i] -= 1e6
    M = np.diag([0.1, 0.1, 0.05, 0.1, 0.1, 0.05])
    return Structure(M, stiffness_damping * K + mass_damping * M, K)


def damper(flat=FLAT, curved=CURVED, load=LOAD, damping=200.0, retention=0.0):
    d = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=load, damping=damping, retention=retention)
    a = np.radians(135.0)  # the flat face against blade 0's platform, normal up and to the left
    tau = np.array([-np.sin(a), np.cos(a)])
    centre = np.array([-3e-3, 2e-3])
    d.add_interface(flat, points=[centre - 1.5e-3 * tau, centre + 1.5e-3 * tau], angle_deg=135.0,
                    platform={"x": 0, "y": 1}, name="flat")
    d.add_interface(curved, points=[(3e-3, 2e-3)], angle_deg=45.0, platform={"x": 3, "y": 4}, name="curved")
    return d


def tip_force(s, amplitude):
    f = np.zeros(s.ndof)
    f[2] = amplitude
    return f


@pytest.mark.parametrize("retention", [0.0, 1e3])  # N/m: without, and with the springs that keep it in its pocket
@pytest.mark.parametrize("load", [5.0, LOAD, 300.0])  # N: a sliding, the usual and a stuck damper
def test_the_static_state_balances_the_damper(load, retention):
    d = damper(load=load, retention=retention)
    s = d.attach(blade_pair())
    assert s.ndof == 9 and d.dofs == (6, 7, 8) and len(s.contacts) == 3
    r = frequency_point(s, tip_force(s, 1.0), 1500.0, harmonics=3)
    # Newton's static tolerance is 1e-10 of the residual scale (the load); the retention's springs are part of the
    # balance (left out, they made it 9.5e-5 to 1.2e-4 of the load)
    assert d.static_balance(r) < 1e-10
    N0 = r.static_normal_force
    assert np.all(N0 > 0) and abs(N0[:2].sum() - N0[2]) < 0.5 * N0[2]  # both interfaces carry load


def test_the_rotation_dof_is_the_arc_of_the_farthest_contact():
    d = damper()
    s = d.attach(blade_pair())
    assert d.arm == max(np.hypot(*c.point) for c in d.contacts)
    # a rotation theta (rad) moves the damper's point p by theta (-py, px): the contact directions carry 1/arm
    theta, q = 1e-4, np.zeros(s.ndof)
    q[d.dofs[2]] = d.arm * theta
    Bt, Bn, _ = s.contact_directions()
    for c, contact in enumerate(d.contacts):
        move = theta * np.array([-contact.point[1], contact.point[0]])
        assert Bn[:, c] @ q == pytest.approx(np.dot(contact.normal, move), rel=1e-12)
        assert Bt[:, c] @ q == pytest.approx(np.dot(contact.tangent, move), rel=1e-12)
    # and its inertia is the moment of inertia over arm^2: the kinetic energy of theta' is I theta'^2 / 2
    assert s.M[d.dofs[2], d.dofs[2]] * d.arm**2 == pytest.approx(d.inertia, rel=1e-12)


def test_a_stuck_damper_is_the_linear_structure_with_its_stick_stiffnesses():
    sticky = MicroslipModel(FLAT.kt, FLAT.kn, FLAT.gaps, 1e3)  # friction that never slips
    d = damper(sticky, MicroslipModel(CURVED.kt, CURVED.kn, CURVED.gaps, 1e3))
    s = d.attach(blade_pair())
    omega, F = 1500.0, 0.5
    r = frequency_point(s, tip_force(s, F), omega, harmonics=3, reduction="none")
    # the linear structure: every element closed at the static state adds kt and kn along its directions
    Bt, Bn, n0 = s.contact_directions()
    K = s.K.copy()
    q0 = r.coefficients[0, 0]
    for c, contact in enumerate(s.contacts):
        closed = Bn[:, c] @ q0 + n0[c] > contact.model.gaps
        K += contact.model.kt[closed].sum() * np.outer(Bt[:, c], Bt[:, c])
        K += contact.model.kn[closed].sum() * np.outer(Bn[:, c], Bn[:, c])
    z = np.linalg.solve(K - omega**2 * s.M + 1j * omega * s.C, tip_force(s, F))
    # the solver's tolerance, 1e-9 of the residual, bounds the difference
    np.testing.assert_allclose(r.coefficients[0, 1] - 1j * r.coefficients[0, 2], z, rtol=0,
                               atol=1e-8 * np.abs(z).max())
    assert np.abs(r.coefficients[0, 3:]).max() < 1e-8 * np.abs(z).max()  # no higher harmonics


@pytest.mark.parametrize("omega", [3500.0, 3700.0, 3850.0])  # rad/s, below the first resonance, the damper slipping
def test_the_energy_balances_on_a_sliding_damper(omega):
    s = damper().attach(blade_pair())
    r = frequency_point(s, tip_force(s, 5.0), omega, harmonics=5, reduction="none")
    assert r.contact_dissipation.sum() > 1e-3 * r.excitation_work[0]  # the damper dissipates
    # harmonic balance conserves the energy of the harmonics kept: to the solver's tolerance
    assert abs(r.viscous_dissipation[0] + r.contact_harmonic_work.sum() - r.excitation_work[0]) \
        < 1e-6 * r.excitation_work[0]
    # the physical dissipation (friction work) differs from it by the AFT's sampling error: measured
    # below 1.3e-4 of the excitation's work at these points
    assert abs(r.contact_dissipation.sum() - r.contact_harmonic_work.sum()) < 3e-4 * r.excitation_work[0]


def test_a_retention_holds_the_damper_where_a_contact_stays_open_over_the_cycle():
    F = tip_force(damper().attach(blade_pair()), 0.5)
    d = damper(load=10.0)
    d.retention = 1e3  # N/m: 4e-5 of the flat contacts' normal stiffness (2.3e7 N/m)
    s = d.attach(blade_pair())
    assert np.allclose(np.diag(s.K)[6:], 1e3)
    r = frequency_response(s, F, (3000.0, 5000.0), harmonics=5, stability=False)
    # past the peak a flat contact stays open over the whole cycle while the others slide: without the
    # retention nothing but friction holds the damper's mean position there, and the continuation crept
    # through 5000 points (3000 folds) within 10 rad/s; with it the curve ends in 570 points
    assert r.complete and r.points < 1000 and r.contact_N[:, :2, 0].min() == 0.0
    # the peak is the one without retention (reached before that region; 1e-4 apart measured, the
    # parabola through the highest points)
    free = frequency_response(damper(load=10.0).attach(blade_pair()), F, (3000.0, 3921.0), harmonics=5,
                              stability=False)
    assert r.peak(2)[1] == pytest.approx(free.peak(2)[1], rel=1e-3)


@pytest.mark.parametrize("kwargs, error, message", [
    ({"centrifugal_load": -1.0}, ValueError, "centrifugal_load"),
    ({"centrifugal_load": 1.0, "retention": -1.0}, ValueError, "retention"),
    ({}, ValueError, "the damper needs its static load"),
    ({"centrifugal_load": 10.0, "speed": 100.0, "radius": 0.2}, ValueError, "not both"),
    # unloaded, nothing presses the damper against its platforms: refused here, not by the solver's ConvergenceError
    ({"centrifugal_load": 0.0}, ValueError, r"centrifugal_load must be > 0 N, got 0: only the "
     r"centrifugal load presses the damper against its platforms"),
    ({"speed": 0.0, "radius": 0.2}, ValueError, "speed must be positive, got 0.0"),
])
def test_damper_arguments_are_checked(kwargs, error, message):
    with pytest.raises(error, match=message):
        UnderPlatformDamper(0.02, 1e-6, **kwargs)


def test_interface_arguments_are_checked():
    d = UnderPlatformDamper(0.02, 1e-6, speed=1000.0, radius=0.3)
    assert d.centrifugal_load == pytest.approx(0.02 * 0.3 * 1000.0**2)
    with pytest.raises(ValueError, match=r"points must have shape \(k, 2\)"):
        d.add_interface(FLAT, points=[[1.0, 2.0, 3.0]], angle=0.0, platform={"x": 0, "y": 1})
    with pytest.raises(ValueError, match=r"platform\[0\] must be a mapping with keys 'x' and 'y'"):
        d.add_interface(FLAT, points=[(0, 0)], angle=0.0, platform={"x": 0})
    with pytest.raises(TypeError, match="models must be a MicroslipModel or a list of 2"):
        d.add_interface([FLAT], points=[(0, 0), (1e-3, 0)], angle=0.0, platform={"x": 0, "y": 1})
    with pytest.raises(ValueError, match="the damper has no interface"):
        d.attach(blade_pair())
    d.add_interface(FLAT, points=[(0, 0)], angle=0.0, platform={"x": 99, "y": 1}, name="side")
    with pytest.raises(ValueError, match="platform DOF 99 is out of range"):
        d.attach(blade_pair())


def test_a_load_set_to_zero_after_construction_is_refused_when_attached():
    d = damper()
    d.centrifugal_load = 0.0
    with pytest.raises(ValueError, match=r"centrifugal_load must be > 0 N, got 0"):
        d.attach(blade_pair())


def test_the_balance_reads_the_load_each_result_was_solved_at():
    d = damper()  # 50 N, never attached: the design curve attaches a copy of it at each load
    f = np.zeros(6)
    f[2], f[5] = 0.5, -0.5
    curve = damper_design_curve(blade_pair(), d, [20.0, 300.0], f, (3000.0, 3200.0), dof=2, harmonics=1)
    for r in curve.responses:  # it raised AttributeError ('names') here
        assert d.static_balance(r) < 1e-10
    d.attach(blade_pair())  # attached at its own 50 N, it read its own load: 0.6 and 5.0 of the load here
    assert [d.static_balance(r) < 1e-10 for r in curve.responses] == [True, True]
    # a new damper with the same interfaces is the same damper (the examples rebuild theirs)
    assert damper(load=7.0).static_balance(curve.responses[1]) < 1e-10


def test_the_balance_of_a_result_of_another_structure_is_refused():
    s = damper().attach(blade_pair())
    r = frequency_point(s, tip_force(s, 1.0), 1500.0, harmonics=1, stability=False)
    other = damper(curved=MicroslipModel(CURVED.kt, CURVED.kn, CURVED.gaps, 0.3))  # another law on its curved face
    other.attach(blade_pair())
    with pytest.raises(ValueError, match=r"result: its structure \(Structure\(ndof=9, dense, contacts=3\)\) carries "
                                         r"no damper with this damper's interfaces \(flat, curved\)"):
        other.static_balance(r)
    with pytest.raises(TypeError, match="result must be a FrequencyResponse solved on a structure this damper was "
                                        "attached to, got str"):
        other.static_balance("result")


def test_the_static_state_closes_each_contact_then_moves_it_tangentially():
    """The harmonic balance's static step, as the module says; a damper spun up from rest differs where gapped
    elements stick."""

    def solved(mu, load):
        laws = (MicroslipModel(law.kt, law.kn, law.gaps, mu) for law in (FLAT, CURVED))
        d = damper(*laws, load=load)
        s = d.attach(blade_pair())
        return s, frequency_point(s, tip_force(s, 1e-3), 100.0, harmonics=1, reduction="none", stability=False)

    def spun_up(s, steps=50):
        """``(T, N)`` of each contact (N) after raising the load from zero in ``steps`` equilibria."""
        Bt, Bn, approach = s.contact_directions()
        q, states = np.linalg.solve(s.stuck_stiffness(), s.static_force / steps), [None] * len(s.contacts)

        def steps_to(q):
            return [c.model.simulate([Bt[:, k] @ q], [Bn[:, k] @ q + approach[k]], states[k], work=False)
                    for k, c in enumerate(s.contacts)]

        for fraction in np.linspace(0.0, 1.0, steps + 1)[1:]:
            def residual(q):
                out = steps_to(q)
                return s.K @ q + Bt @ [o.T[-1] for o in out] + Bn @ [o.N[-1] for o in out] - fraction * s.static_force

            # Levenberg-Marquardt: where every contact slides, Powell's hybrid method stalls
            q = root(residual, q, method="lm", options={"xtol": 1e-14, "ftol": 1e-14}).x
            assert np.abs(residual(q)).max() < 1e-9 * s.static_force.max()
            states = [o.state for o in steps_to(q)]
        out = steps_to(q)
        return np.array([o.T[-1] for o in out]), np.array([o.N[-1] for o in out])

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # beyond the tuned load at mu = 3
        for mu, load in ((0.4, LOAD), (3.0, LOAD)):
            s, r = solved(mu, load)
            Bt, Bn, approach = s.contact_directions()
            q0 = r.static_coefficients
            for k, c in enumerate(s.contacts):  # one step from the virgin contact to its static (t0, n0)
                step = c.model.simulate([Bt[:, k] @ q0], [Bn[:, k] @ q0 + approach[k]])
                assert abs(step.T[-1] - r.static_tangential_force[k]) < 1e-10 * load
                assert abs(step.N[-1] - r.static_normal_force[k]) < 1e-10 * load
            T, N = spun_up(s)
            dT = np.abs(T - r.static_tangential_force).max() / load
            dN = np.abs(N - r.static_normal_force).max() / load
            if mu == 0.4:  # every contact slides at its static state: the same forces
                assert np.all(np.abs(r.static_tangential_force) >= mu * r.static_normal_force * (1 - 1e-9))
                assert dT < 1e-8 and dN < 1e-8  # measured 1e-12
            else:  # gapped elements stick: measured 1.5 % and 2.4 % of the load (the module's docstring)
                assert 0.01 < dT < 0.02 and 0.02 < dN < 0.03


def cylinder(retention=0.0, radius=3e-3):
    """A cylindrical damper: one contact on each face, both normals through its centre of mass."""
    d = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=LOAD, damping=200.0, retention=retention)
    for name, degrees, platform, law in (("left", 135.0, {"x": 0, "y": 1}, FLAT), ("right", 45.0, {"x": 3, "y": 4},
                                                                                     CURVED)):
        a = np.radians(degrees)
        d.add_interface(law, points=[(radius * np.cos(a), radius * np.sin(a))], angle_deg=degrees, platform=platform,
                        name=name)
    return d


def test_a_cylindrical_damper_rolls_without_a_retention_and_is_solved_with_one():
    # one contact per face: the rotation about the centre changes no normal approach, only friction holds it (it
    # met a singular Jacobian at the static solve, omega = 1 rad/s)
    with pytest.raises(ValueError, match=r"the damper's contacts hold only 2 of its 3 motions by their normal "
                                         r"stiffness: the rotation about the point \(0, 0\) mm of the damper changes "
                                         r"no contact's normal approach .* give the damper a retention \(N/m; e.g. "
                                         r"retention=2.3e\+03"):
        cylinder().attach(blade_pair())
    d = cylinder(retention=1e3)
    s = d.attach(blade_pair())
    f = np.zeros(s.ndof)
    f[2], f[5] = 0.5, -0.5
    r = frequency_response(s, f, (3000.0, 5000.0), harmonics=3, stability=False)
    assert r.complete and d.static_balance(r) < 1e-10
    assert r.contact_dissipation.max() > 0  # the contacts slide: a damper, not a spring


def test_angles_are_degrees_with_angle_deg_and_radians_with_angle():
    a, b = (UnderPlatformDamper(0.02, 1e-6, centrifugal_load=LOAD) for _ in range(2))
    a.add_interface(FLAT, points=[(0.0, 1e-3)], angle_deg=135.0, platform={"x": 0, "y": 1})
    b.add_interface(FLAT, points=[(0.0, 1e-3)], angle=np.radians(135.0), platform={"x": 0, "y": 1})  # as before
    np.testing.assert_allclose(a.contacts[0].normal, b.contacts[0].normal, rtol=0, atol=1e-15)
    d = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=LOAD)
    with pytest.raises(ValueError, match=r"angle is in radians, got 130.0 \(beyond 2 pi\): for an angle in degrees "
                                         r"give angle_deg=130.0"):
        d.add_interface(FLAT, points=[(0.0, 1e-3)], angle=130, platform={"x": 0, "y": 1})
    with pytest.raises(TypeError, match="angle_deg: give the interface normal's angle from x, either angle_deg"):
        d.add_interface(FLAT, points=[(0.0, 1e-3)], platform={"x": 0, "y": 1})
    with pytest.raises(TypeError, match="got angle_deg=135 and angle=2.3"):
        d.add_interface(FLAT, points=[(0.0, 1e-3)], angle_deg=135, angle=2.3, platform={"x": 0, "y": 1})
    # 2.1 rad (120 degrees) where 45 degrees was meant: a normal no platform can push the load back along
    wrong = damper()
    wrong.contacts = [c for c in wrong.contacts if c.interface == "flat"]
    wrong.add_interface(CURVED, points=[(3e-3, 2e-3)], angle=2.1, platform={"x": 3, "y": 4}, name="curved")
    with pytest.raises(ValueError, match=r"the damper cannot be held against its platforms: .* \(normals 'flat' at "
                                         r"135°, 'curved' at 120.3° from x, .*the angles' unit: add_interface takes "
                                         r"angle_deg in degrees"):
        wrong.attach(blade_pair())


def test_a_platform_with_x_and_y_on_one_dof_is_refused():
    d = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=LOAD)
    with pytest.raises(ValueError, match=r"platform\[1\]: 'x' and 'y' name the same DOF \(4\)"):
        d.add_interface(FLAT, points=[(0.0, 1e-3), (1e-3, 1e-3)], angle_deg=135,
                        platform=[{"x": 0, "y": 1}, {"x": 4, "y": 4}])
    from test_cyclic import springs_matrix

    disk = CyclicStructure(np.eye(5), None, springs_matrix(5, [(0, 1, 4e6), (0, None, 1e6), (1, None, 1e6)]) +
                           np.eye(5), sectors=6, left=[0], right=[1])
    with pytest.raises(ValueError, match=r"platform\[0\]: 'x' and 'y' name the same DOF \(NextDof\(dof=2\)\)"):
        d.add_interface(FLAT, points=[(0.0, 1e-3)], angle_deg=45, platform={"x": disk.next(2), "y": disk.next(2)})


def test_a_damper_with_both_faces_on_one_sector_of_a_disk_is_warned():
    from test_cyclic import springs_matrix

    K = springs_matrix(5, [(0, 1, 4e6), (0, 2, 3e6), (1, 2, 3e6), (2, 4, 1e6), (0, None, 1e6), (1, None, 1e6),
                           (3, None, 2e7)])
    disk = CyclicStructure(np.diag([0.05, 0.05, 0.1, 0.1, 0.05]), None, K, sectors=6, left=[0], right=[1])

    def on(right):
        d = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=LOAD)
        d.add_interface(FLAT, points=[(-3e-3, 1e-3), (-3e-3, 3e-3)], angle_deg=135, platform={"x": 2, "y": 3},
                        name="flat")
        d.add_interface(CURVED, points=[(3e-3, 2e-3)], angle_deg=45, platform=right, name="curved")
        return d

    with pytest.warns(UserWarning, match=r"every face of the damper \('flat', 'curved'\) touches this sector's "
                                         r"platform: the damper joins a blade to itself"):
        on({"x": 2, "y": 3}).attach(disk)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        on({"x": disk.next(2), "y": disk.next(3)}).attach(disk)  # between blades: no warning


def test_a_damper_between_sectors_of_a_disk_equals_the_whole_disk_with_its_dampers():
    from microslip.frequency import CyclicStructure

    N, EO, omega = 6, 2, 3300.0
    samples = 16 * N  # a whole number of samples per sector's phase lag (see test_cyclic.py)
    # sector DOFs: 0 ring (left), 1 ring (right), 2 platform x, 3 platform y, 4 tip x
    from test_cyclic import springs_matrix

    Ks = springs_matrix(5, [(0, 1, 4e6), (0, 2, 3e6), (1, 2, 3e6), (2, 4, 1e6), (0, None, 1e6), (1, None, 1e6),
                            (3, None, 2e7)])
    Ms = np.diag([0.05, 0.05, 0.1, 0.1, 0.05])
    Cs = 1e-6 * Ks + 1.0 * Ms

    def upd(own, nxt):
        d = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=LOAD)
        a = np.radians(135.0)
        tau = np.array([-np.sin(a), np.cos(a)])
        c = np.array([-3e-3, 2e-3])
        d.add_interface(FLAT, points=[c - 1.5e-3 * tau, c + 1.5e-3 * tau], angle=a,
                        platform={"x": own(2), "y": own(3)})
        d.add_interface(CURVED, points=[(3e-3, 2e-3)], angle=np.radians(45.0), platform={"x": nxt(2), "y": nxt(3)})
        return d

    disk = CyclicStructure(Ms, Cs, Ks, sectors=N, left=[0], right=[1])
    mine = upd(lambda i: i, disk.next)
    disk = mine.attach(disk)
    f = np.zeros(disk.ndof)
    f[4] = 3.0
    sector = frequency_point(disk, f, omega, harmonics=3, engine_order=EO, samples=samples)

    g = lambda s, i: (s % N, (s + 1) % N, N + s % N, 2 * N + s % N, 3 * N + s % N)[i]  # noqa: E731
    M, C, K = (np.zeros((4 * N, 4 * N)) for _ in range(3))
    for s in range(N):
        idx = [g(s, i) for i in range(5)]
        for A, a in ((M, Ms), (C, Cs), (K, Ks)):
            A[np.ix_(idx, idx)] += a
    whole = Structure(M, C, K)
    for s in range(N):
        whole = upd(lambda i, s=s: g(s, i), lambda i, s=s: g(s + 1, i)).attach(whole)
    F = np.zeros(whole.ndof, dtype=complex)
    for s in range(N):
        F[g(s, 4)] = 3.0 * np.exp(-2j * np.pi * EO * s / N)
    full = frequency_point(whole, F, omega, harmonics=3, reduction="none", samples=samples)
    # the static state of the sector's damper balances, as on a plain structure (1e-10 of the load)
    assert mine.static_balance(sector) < 1e-10
    scale = np.abs(full.coefficients).max()
    # sector 0's DOFs, and its damper (the first damper attached to the whole disk: DOFs 4N, 4N+1, 4N+2)
    for mine, theirs in [(i, g(0, i)) for i in range(5)] + [(5 + k, 4 * N + k) for k in range(3)]:
        np.testing.assert_allclose(sector.dof_coefficients(mine), full.dof_coefficients(theirs), rtol=0,
                                   atol=1e-8 * scale)


# -- harmonic balance against time integration, the flat face lifting off during part of the cycle ---------

def lifting_pair():
    """The blade pair and damper, 50 N, more damped: 2.5 % at the blades' mode, 2000 1/s on the damper.

    With that damping the steady state is reached in about 110 periods and the response to 20 N at
    blade 0's tip is single-valued in frequency, while the flat face's contacts lift off over part of
    every cycle from 3.8 to 4.2 krad/s (at the peak, one of them for 61 % of the period).
    """
    return damper(load=50.0, damping=2000.0).attach(blade_pair(mass_damping=40.0, stiffness_damping=1e-5))


def steady_contacts(result, k, samples=512):
    """Each contact's element conditions ``(samples, J)`` and normal force over the steady period at point ``k``.

    The contact is marched as harmonic balance marches it: loaded once from the virgin state to its
    mean, then along its periodic motion, period after period, until its sliders repeat.
    """
    out = []
    for c, contact in enumerate(result.structure.contacts):
        law = contact.model
        t, n = time_samples(result.contact_t[k, c], samples), time_samples(result.contact_n[k, c], samples)
        state = law.simulate([result.contact_t[k, c, 0]], [result.contact_n[k, c, 0]]).state
        for _ in range(1000):
            r = law.simulate(t, n, state, work=False)
            if np.array_equal(r.state.sliders, state.sliders):
                break
            state = r.state
        out.append((r.condition, r.N))
    return out


def test_harmonic_balance_equals_time_integration_while_the_flat_face_lifts_off():
    s = lifting_pair()
    F = tip_force(s, 20.0)
    # lift-off puts kinks in the contact forces whose harmonics decay slowly: the difference from time
    # integration is 2.4e-2 with H = 5, 7.4e-3 with H = 9, 5.9e-4 with H = 15, 6.2e-5 with H = 25; neither
    # the AFT samples nor the time step change it (python scripts/damper_time_integration.py)
    r = frequency_response(s, F, (3700.0, 4300.0), harmonics=15, stability=False)
    assert np.all(np.diff(r.omega) > 0)  # single-valued: one steady state per frequency
    peak = int(np.argmax(r.amplitude(2)))
    points = sorted({int(np.argmin(np.abs(r.omega - w))) for w in (3800.0, 3880.0, 4000.0, 4200.0)} | {peak})
    assert len(points) == 5
    for k in points:
        contacts = steady_contacts(r, k)
        # a contact of the flat face lifts off over part of the cycle: its normal force is zero at some samples only
        assert any(np.any(N == 0.0) and np.any(N > 0.0) for _, N in contacts[:2])
        # every element slips or opens during the cycle: none keeps a force from its history, so the steady
        # state does not depend on how it was reached (harmonic balance's static step, time integration's start)
        assert not any(np.all(cond == STICK, axis=0).any() for cond, _ in contacts)
        hb = r.coefficients[k]
        ti = steady_state(s, F, float(r.omega[k]), harmonics=15, steps_per_period=2048, tolerance=1e-9)
        assert ti.converged
        # every DOF and harmonic: measured at most 5.9e-4 of the largest dynamic coefficient; the time
        # integration's own error is below 2e-5 (2048 against 8192 steps per period)
        scale = np.abs(ti.coefficients[1:]).max()
        assert np.abs(hb - ti.coefficients).max() < 1e-3 * scale, r.omega[k]
        # harmonic balance conserves the energy of the harmonics kept, also where the contacts lift off
        balance = r.viscous_dissipation[k] + r.contact_harmonic_work[k].sum() - r.excitation_work[k]
        assert abs(balance) < 1e-6 * r.excitation_work[k]
    assert r.omega[peak] == pytest.approx(r.peak(2)[0], rel=1e-3)


def test_time_integration_started_on_the_harmonic_balance_solution_stays_there_where_elements_stick():
    """The lightly damped pair (50 N, 5 N at the tip) at 3.7 krad/s: elements stick through the whole cycle.

    Their force is the one they took when they last slipped, so the steady state depends on how it was
    reached: from rest, time integration ends 3.5e-2 from harmonic balance (the damper's mean position;
    python scripts/damper_time_integration.py sticking). Started on the harmonic balance solution, its
    contacts in the state harmonic balance assumes, it stays there.
    """
    s = damper(load=50.0).attach(blade_pair())
    F = tip_force(s, 5.0)
    hb = frequency_point(s, F, 3700.0, harmonics=5, stability=False)
    assert any(np.all(cond == STICK, axis=0).any() for cond, _ in steady_contacts(hb, 0))
    ti = steady_state(s, F, 3700.0, harmonics=5, steps_per_period=512, tolerance=1e-7, start=hb)
    assert ti.converged
    # measured 3.9e-4 (4.2e-4 with 1024 steps, 4.3e-4 with 2048 and 8192: not the time step), in the damper's
    # mean radial position: the first periods, on an orbit that H = 5 leaves slightly off the exact one, move
    # the stuck elements a little before they settle (H = 15 leaves 1.5e-5); 1e-3 holds it 2.5 times above
    scale = np.abs(ti.coefficients[1:]).max()
    assert np.abs(hb.coefficients[0] - ti.coefficients).max() < 1e-3 * scale
