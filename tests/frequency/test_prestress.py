"""Bolt and contact prestress: the static step with the friction released or stuck, then the dynamics from it.

* a 2-mass chain whose second mass is pressed on a Jenkins contact by a preload (a third DOF, its normal
  motion, on a spring): the static state in closed form with the friction released (the chain alone) and
  stuck (the chain plus the contact's stiffness), the onset of slip in the dynamic analysis at the
  tangential amplitude ``(mu N0 - |T0|) / kt`` (stuck) against ``mu N0 / kt`` (released);
* with the friction released the static state is the frictionless static equilibrium of an independent
  active-set solve (1e-10), on a structure with contacts of several elements, gaps and one on its plane;
* at small amplitude the forced response is the linear prestressed structure's, the contacts stuck with
  their closed elements' stiffness (1e-8), and the nonlinear mode starts at its linear mode (1e-8);
* time integration started at rest at the prestressed state agrees with harmonic balance at one point;
* damping fitted on the prestressed modes gives the ratios asked for.
"""

import numpy as np
import pytest
import scipy.linalg as sla

from microslip import MicroslipModel
from microslip.frequency import (HarmonicBalance, Structure, frequency_point, frequency_response, nonlinear_modes, prestress,
                                 steady_state)

# -- the chain ----------------------------------------------------------------------------------------------
K1, K2, K3 = 1e6, 1e6, 2e6          # N/m: ground-mass 1, mass 1-mass 2, the normal spring of mass 2
KT, KN, MU, PRELOAD = 1e6, 4e6, 0.5, 300.0
N0 = KN * PRELOAD / (K3 + KN)        # the contact's share of the preload (N): 200 N
BETA = 1e-4                          # s: stiffness-proportional damping of the structure


def chain() -> Structure:
    """DOFs 0, 1: the masses along the chain; DOF 2: mass 2 normal to the contact (1 kg each)."""
    K = np.array([[K1 + K2, -K2, 0.0], [-K2, K2, 0.0], [0.0, 0.0, K3]])
    s = Structure(np.eye(3), BETA * K, K)
    s.add_contact(MicroslipModel([KT], [KN], [0.0], MU), tangential=1, normal=2, preload=PRELOAD, name="joint")
    return s


def chain_static(F: float, stuck: bool) -> np.ndarray:
    """The chain's static displacement (m) under F on mass 2: K_chain (+ kt at DOF 1 when stuck) q = (0, F)."""
    Kc = np.array([[K1 + K2, -K2], [-K2, K2 + (KT if stuck else 0.0)]])
    q = np.linalg.solve(Kc, [0.0, F])
    return np.array([q[0], q[1], PRELOAD / (K3 + KN)])


@pytest.mark.parametrize("friction", ["released", "stuck"])
def test_chain_static_state_is_its_closed_form(friction):
    F = 40.0
    p = prestress(chain(), {1: F}, friction=friction)
    q = chain_static(F, friction == "stuck")
    assert np.allclose(p.displacement, q, rtol=1e-12, atol=1e-18)
    assert p.normal_force[0] == pytest.approx(N0, rel=1e-12)
    T0 = KT * q[1] if friction == "stuck" else 0.0  # stuck from the unloaded state: the contact's spring carries it
    assert p.tangential_force[0] == pytest.approx(T0, rel=1e-12, abs=1e-12)
    assert p.closed_elements.tolist() == [1]
    assert p.tangential_displacement[0] == pytest.approx(q[1], rel=1e-12)
    # released: the sliders reset at the static displacement; stuck: they stay at the unloaded state
    assert p.prestressed.contacts[0].reference == (p.tangential_displacement[0] if friction == "released" else 0.0)


def _threshold_force(p, omega: float, amplitude: float) -> np.ndarray:
    """The first-harmonic force on mass 2 (N, ``(3,)``) that moves DOF 1 by ``amplitude`` (m) in the linear
    prestressed structure."""
    M, C, K = np.eye(3), p.prestressed.C, p.stiffness()
    H = np.linalg.inv(K - omega**2 * M + 1j * omega * C)
    return np.array([0.0, amplitude / abs(H[1, 1]), 0.0])


@pytest.mark.parametrize("friction", ["released", "stuck"])
def test_slip_starts_where_the_prestressed_state_leaves_room(friction):
    """The contact's force swings by ``kt a`` about its static value ``T0`` at a tangential amplitude ``a``.

    Released (``T0 = 0``): it sticks while ``kt a <= mu N0`` and slips every cycle beyond. Stuck with ``T0 =
    0.7 mu N0``: once ``kt a > mu N0 - T0`` the first swing slips and moves the slider until the force reaches
    ``mu N0``; the swing (``2 kt a < 2 mu N0``) then fits in the stick band, so the periodic motion sticks
    (shakedown: no friction work) about the mean force ``mu N0 - kt a`` instead of ``T0``.
    """
    s = chain()
    F = 0.7 * MU * N0 / KT * ((K1 + K2) * (K2 + KT) - K2**2) / (K1 + K2)  # q1 = F (K1 + K2) / det, T0 = kt q1
    p = prestress(s, {1: F}, friction=friction)
    T0 = p.tangential_force[0]
    room = MU * N0 - abs(T0)
    assert room == pytest.approx(MU * N0 * (0.3 if friction == "stuck" else 1.0), rel=1e-10)
    omega = 200.0  # rad/s: well below the first mode (about 1000 rad/s)
    for share in (0.9, 1.1):
        a = share * room / KT
        r = frequency_point(s, _threshold_force(p, omega, a), omega, harmonics=5, prestress=p, stability=False)
        loss = r.contact_dissipation[0, 0] / r.excitation_work[0]
        if friction == "released" and share > 1:  # slips every cycle
            assert loss > 1e-3
            continue
        assert loss == 0.0  # sticks through the periodic motion: the linear prestressed structure's amplitude
        assert r.amplitude(1, 1)[0] == pytest.approx(a, rel=1e-8)
        if share < 1:
            assert r.contact_T[0, 0, 0] == pytest.approx(T0, rel=1e-8, abs=1e-8 * MU * N0)
        else:  # shaken down to the band's edge, at the largest *sampled* displacement: the AFT's samples miss the
            # crest by at most 1 - cos(pi / samples) of the swing
            sampling = KT * a * (1 - np.cos(np.pi / r.samples))
            assert abs(r.contact_T[0, 0, 0] - (MU * N0 - KT * a)) <= sampling


# -- a structure with contacts of several elements, gaps, one on its plane -----------------------------------
def jointed(damped: bool = True) -> Structure:
    """7 DOFs: a spring-mass structure (random stiffness, grounded), two contacts with bolt preloads and gaps."""
    rng = np.random.default_rng(3)
    n = 7
    A = rng.normal(size=(n, n))
    K = 1e6 * (A @ A.T / n + np.eye(n))
    M = np.diag(rng.uniform(0.5, 1.5, n))
    s = Structure(M, 2e-5 * K + 5.0 * M if damped else None, K)
    one = MicroslipModel([3e5, 5e5, 7e5], [2e6, 3e6, 4e6], [0.0, 2e-6, 1.5e-5], 0.4)
    plane = MicroslipModel([4e5, 6e5], [3e6, 3e6], [0.0, 2e-6], 0.3)
    s.add_contact(one, tangential={0: 1.0, 1: -1.0}, normal={2: 1.0}, preload=80.0, name="bolt1")
    s.add_contact(plane, tangential=[{3: 1.0}, {4: 1.0}], normal={5: 1.0, 6: -0.5}, preload=60.0, name="bolt2")
    s.add_static_force(np.array([5.0, 0.0, 0.0, -3.0, 2.0, 0.0, 0.0]))  # e.g. a centrifugal load
    return s


def frictionless_static(s: Structure, load) -> np.ndarray:
    """Independent frictionless static solve: K q + sum_c b_n N_c(b_n . q + n0) = f by active sets (m)."""
    f = s.preload_force() + load
    Bt, Bn, n0 = s.contact_directions()
    q = np.zeros(s.ndof)
    for _ in range(50):
        K, rhs = s.K.copy(), f.copy()
        for c, contact in enumerate(s.contacts):
            n = Bn[:, c] @ q + n0[c]
            closed = n > contact.model.gaps
            kn = contact.model.kn[closed]
            K += kn.sum() * np.outer(Bn[:, c], Bn[:, c])
            rhs += (kn @ contact.model.gaps[closed] - kn.sum() * n0[c]) * Bn[:, c]
        q_new = np.linalg.solve(K, rhs)
        if np.array_equal(q_new, q):
            break
        q = q_new
    return q


def test_released_static_state_is_the_frictionless_static_solve():
    s = jointed()
    load = np.array([0.0, 12.0, 0.0, 4.0, -6.0, 0.0, 0.0])
    p = prestress(s, load, friction="released", reduction="none")
    q = frictionless_static(s, load)
    assert np.max(np.abs(p.displacement - q)) <= 1e-10 * np.max(np.abs(q))
    assert np.all(p.tangential_force == 0.0) and np.all(p.tangential_force2 == 0.0)
    _, Bn, n0 = s.contact_directions()
    closed = [int(np.sum(q @ Bn[:, c] + n0[c] > contact.model.gaps)) for c, contact in enumerate(s.contacts)]
    assert p.closed_elements.tolist() == closed and sum(closed) < 5  # the element with the widest gap stays open
    # the same with the linear structure condensed onto the contact DOFs
    exact = prestress(s, load, friction="released", reduction="exact")
    assert np.max(np.abs(exact.displacement - q)) <= 1e-10 * np.max(np.abs(q))


@pytest.mark.parametrize("friction", ["released", "stuck"])
def test_small_amplitude_response_is_the_linear_prestressed_structure(friction):
    s = jointed()
    load = np.array([0.0, 3.0, 0.0, 1.0, -1.5, 0.0, 0.0])  # stuck: every element well inside its stick band
    p = prestress(s, load, friction=friction)
    K = p.stiffness()
    assert p.closed_elements.sum() < sum(c.model.elements for c in s.contacts)  # open elements are absent from K
    force = 1e-3 * np.array([1.0, 0.0, 0.5, 0.0, 1.0, 0.0, 0.0])
    for omega in (0.6 * p.modes(1).omega[0], 1.1 * p.modes(2).omega[1]):
        r = frequency_point(s, force, omega, harmonics=3, prestress=p, stability=False)
        Z = K - omega**2 * s.M + 1j * omega * s.C
        z = np.linalg.solve(Z, force)
        z_hb = r.coefficients[0, 1] - 1j * r.coefficients[0, 2]
        assert np.max(np.abs(z_hb - z)) <= 1e-8 * np.max(np.abs(z))
        assert np.max(np.abs(r.coefficients[0, 0] - p.displacement)) <= 1e-8 * np.max(np.abs(p.displacement))
        assert np.max(np.abs(r.coefficients[0, 3:])) <= 1e-8 * np.max(np.abs(z))  # no higher harmonics: linear


def test_nonlinear_mode_starts_at_the_prestressed_linear_mode():
    s = jointed(damped=False)  # the undamped mode: a damping not proportional to the stuck K_p would move it
    p = prestress(s, np.array([0.0, 3.0, 0.0, 1.0, -1.5, 0.0, 0.0]), friction="released")
    mode = nonlinear_modes(s, 1, (1e-9, 1.2e-9), harmonics=1, prestress=p)
    assert mode.omega[0] == pytest.approx(p.modes(1).omega[0], rel=1e-8)


def test_time_integration_from_the_prestress_agrees_with_harmonic_balance():
    # two elements: the stiff one slips every cycle, the soft one (stick band 2.5e-4 m) sticks throughout, so
    # the steady state remembers where its slider was reset: at the static displacement (2e-4 m), not at 0
    K = np.array([[K1 + K2, -K2, 0.0], [-K2, K2, 0.0], [0.0, 0.0, K3]])
    s = Structure(np.eye(3), BETA * K, K)
    s.add_contact(MicroslipModel([1e6, 0.2e6], [2e6, 2e6], [0.0, 0.0], MU), tangential=1, normal=2, preload=PRELOAD)
    p = prestress(s, {1: 100.0}, friction="released")
    omega = 0.9 * p.modes(1).omega[0]
    force = np.array([0.0, 40.0, 0.0])
    hb = frequency_point(s, force, omega, harmonics=9, prestress=p, stability=False)
    assert hb.contact_dissipation[0, 0] > 0.1 * hb.excitation_work[0]
    ts = steady_state(s, force, omega, prestress=p, harmonics=9, steps_per_period=2048)  # from rest at the prestress
    assert ts.converged
    a = hb.amplitude(1, 1)[0]
    # H = 9 and 2048 steps per period: measured 6e-5 in amplitude, 3e-9 of it in the mean; a slider left at 0
    # (no reset) moves the mean by half the amplitude
    assert ts.amplitude(1, 1) == pytest.approx(a, rel=1e-3)
    assert abs(ts.coefficients[0, 1] - hb.coefficients[0, 0, 1]) <= 1e-3 * a
    # started on the harmonic balance solution, its contacts in the state harmonic balance assumes (reset sliders)
    on = steady_state(s, force, omega, prestress=p, harmonics=9, steps_per_period=2048, start=hb)
    assert on.amplitude(1, 1) == pytest.approx(a, rel=1e-3)
    assert abs(on.coefficients[0, 1] - hb.coefficients[0, 0, 1]) <= 1e-3 * a


def test_damping_fitted_on_the_prestressed_modes():
    s = jointed()
    p = prestress(s, friction="released")
    m = p.modes(4)
    zeta = np.array([0.01, 0.02, 0.005, 0.03])
    C = p.modal_damping(zeta)
    D = m.shapes.T @ C @ m.shapes
    assert np.allclose(D, np.diag(2 * zeta * m.omega), rtol=0, atol=1e-10 * np.max(np.abs(D)))
    R = p.rayleigh_damping((0.01, 0.03), modes=(1, 3))
    ratios = np.diag(m.shapes.T @ R @ m.shapes) / (2 * m.omega)
    assert ratios[[0, 2]] == pytest.approx([0.01, 0.03], rel=1e-10)
    # the damped prestress solves with that damping: small amplitude = linear with C
    q = p.with_damping(C)
    omega = m.omega[0]
    force = 1e-3 * np.eye(7)[0]
    r = frequency_point(s, force, omega, harmonics=1, prestress=q, stability=False)
    z = np.linalg.solve(p.stiffness() - omega**2 * s.M + 1j * omega * C, force)
    assert np.max(np.abs(r.coefficients[0, 1] - 1j * r.coefficients[0, 2] - z)) <= 1e-8 * np.max(np.abs(z))


def test_prestress_refuses_bad_input_by_name():
    s = chain()
    with pytest.raises(ValueError, match="friction"):
        prestress(s, friction="slipping")
    with pytest.raises(TypeError, match="load"):
        prestress(s, {1: 1j})
    with pytest.raises(ValueError, match="load"):
        prestress(s, [1.0, 2.0])
    p = prestress(s, {1: 10.0})
    with pytest.raises(ValueError, match="another structure"):
        frequency_point(chain(), [0.0, 1.0, 0.0], 500.0, prestress=p)
    with pytest.raises(ValueError, match=r"force\[0\]"):
        frequency_point(s, {0: [0.0, 1.0, 0.0], 1: [0.0, 1.0, 0.0]}, 500.0, prestress=p)
    with pytest.raises(TypeError, match="prestress"):
        frequency_response(s, [0.0, 1.0, 0.0], (400.0, 600.0), prestress="released")
    with pytest.raises(ValueError, match="ratios"):
        p.modal_damping([0.01, 0.02], modes=3)
    with pytest.raises(ValueError, match="modes"):
        p.rayleigh_damping((0.01, 0.02), modes=(2, 2))
    with pytest.raises(ValueError, match="n must be"):
        p.modes(4)


def test_summary_and_table(tmp_path):
    p = prestress(chain(), {1: 40.0}, friction="stuck")
    text = p.summary()
    assert "joint" in text and "N0 = 200 N" in text and "stuck" in text
    path = p.to_csv(tmp_path / "prestress.csv")
    rows = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")
    assert float(rows["N0_N"]) == pytest.approx(N0, rel=1e-12)


def test_compiled_equations_with_reset_sliders_equal_their_twin():
    # the compiled residual and Jacobian subtract the reference as the NumPy form does
    s = chain()
    p = prestress(s, {1: 100.0}, friction="released")
    hb = HarmonicBalance(p.prestressed, np.array([0.0, 40.0, 0.0]), 3, samples=64)
    assert hb.compiled and hb.t_ref[0] == p.tangential_displacement[0] != 0.0
    rng = np.random.default_rng(0)
    x = 1e-5 * rng.normal(size=hb.n)  # sticks about the reference; slips about 0
    x[:3] = p.displacement
    R, J, Rw = hb.evaluate(x, 900.0)
    R2, J2, Rw2 = hb.evaluate_reference(x, 900.0)
    assert np.max(np.abs(R - R2)) <= 1e-12 * np.max(np.abs(R2))
    assert np.max(np.abs(J - J2)) <= 1e-12 * np.max(np.abs(J2))
    assert np.max(np.abs(Rw - Rw2)) <= 1e-12 * np.max(np.abs(Rw2))
    hb.t_ref = np.zeros(1)  # the reference matters here: without it the contact's force differs
    assert np.max(np.abs(hb.evaluate(x, 900.0, jacobian=False) - R)) > 1e-3 * np.max(np.abs(R))


# -- a cyclic sector against its assembled disk ----------------------------------------------------------------
def test_a_prestressed_sector_equals_the_prestressed_assembled_disk():
    from microslip.frequency import CyclicStructure

    sectors = 5
    K = np.array([[3e6, -1e6, -1e6, 0.0], [-1e6, 3e6, -1e6, 0.0], [-1e6, -1e6, 3e6, -1e6], [0.0, 0.0, -1e6, 1e6]])
    M = np.diag([0.05, 0.05, 0.08, 0.03])
    d = CyclicStructure(M, 1e-6 * K + 2.0 * M, K, sectors=sectors, left=[0], right=[1])
    model = MicroslipModel([2e5, 3e5], [1e6, 2e6], [0.0, 1e-6], 0.4)
    # a joint inside the sector (tip on platform), pressed by a preload, and one between the sectors' platforms
    d.add_contact(model, tangential={3: 1.0, 2: -1.0}, normal={0: 1.0}, preload=30.0, name="root")
    d.add_contact(model, tangential={2: 1.0, d.next(2): -1.0}, approach=5e-6, name="platforms")
    d.add_static_force([0.0, 0.0, 0.0, 8.0])  # e.g. a centrifugal load on the tip
    whole = d.assembled()
    p_sector = prestress(d, friction="released")
    p_whole = prestress(whole, friction="released", reduction="none")
    assert p_sector.tangential_displacement[0] != 0.0  # the reset matters
    # every sector of the disk stands as the sector does (its independent DOFs: the disk's first sector)
    ind = d.independent
    k = ind.size
    for s in range(sectors):
        assert np.allclose(p_whole.displacement[s * k:(s + 1) * k], p_sector.displacement[ind], rtol=0,
                           atol=1e-10 * np.max(np.abs(p_sector.displacement)))
    assert np.allclose(np.tile(p_sector.normal_force, sectors), p_whole.normal_force, rtol=1e-10)
    # the forced response of engine order 1 at an amplitude where the joints slip
    f = np.array([0.0, 0.0, 0.0, 3.0])
    omega = 0.95 * p_sector.modes(1, nodal_diameter=1).omega[0]
    r_sector = frequency_point(d, f, omega, harmonics=3, engine_order=1, prestress=p_sector, samples=16 * sectors,
                               stability=False)
    r_whole = frequency_point(whole, d.travelling_wave(f, 1)[1], omega, harmonics=3, prestress=p_whole,
                              samples=16 * sectors, stability=False)
    assert r_sector.contact_dissipation[0].sum() > 1e-2 * r_sector.excitation_work[0]
    tip = r_sector.dof_coefficients(3)[0]
    tip_whole = r_whole.dof_coefficients(k - 1)[0]  # sector 0's tip (independent DOFs 0, 2, 3)
    assert np.max(np.abs(tip - tip_whole)) <= 1e-8 * np.max(np.abs(tip))
