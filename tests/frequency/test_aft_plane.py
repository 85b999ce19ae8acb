"""AFT of a contact moving on its plane: twin, exact Jacobians, the one-direction case, closed forms, checks."""

import numpy as np
import pytest

from _plane_twin import aft_plane_reference
from _strategies import random_contact
from microslip import MicroslipModel, Sphere, tune
from microslip.frequency import aft, aft_plane, cycle_work
from microslip.frequency.aft import NotPeriodicError

JENKINS = MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0)  # slip force 1 N at n = 1 µm, r = 1e-4 m


def _random_case(seed, H=3, J=4):
    """Random contact and motion: ellipses of random size and tilt, some elements opening, varying n."""
    rng = np.random.default_rng(seed)
    model = random_contact(rng, J)
    nb = 2 * H + 1
    t = rng.normal(size=(2, nb)) * 1e-6
    t[0] *= 10 ** rng.uniform(-2, 1)
    t[1] *= 10 ** rng.uniform(-3, 1)
    n = rng.normal(size=nb) * 0.5e-6
    n[0] = rng.uniform(0.5, 2.5) * 1e-6
    return model, t, n


# seeds checked to cover stick, slip and opening, elements stuck after a slipping transient (history
# derivative), slowly contracting ones (Newton steps), while the twin converges within seconds
SEEDS = [0, 1, 2, 3, 5, 7, 11, 31, 42, 207, 242]


@pytest.mark.parametrize("seed", SEEDS)
def test_kernel_matches_pure_python_twin(seed):
    rng = np.random.default_rng(seed)
    model, t, n = _random_case(seed, H=int(rng.integers(1, 5)), J=int(rng.integers(1, 7)))
    Ns = int(rng.choice([16, 33, 64]))
    r = aft_plane(model, t, n, samples=Ns)
    F, Jac, periods = aft_plane_reference(model.kt, model.kn, model.gaps, model.mu, t[0], t[1], n, Ns)
    assert periods > 0
    # the same return mapping and history; the state is periodic to 32 ulps of the motion in both (the
    # twin by plain periods, the kernel with Newton steps on the period map): forces to 1e-12, and the
    # derivatives, which the twin carries forward until they repeat, to 1e-9 of the stiffness
    scale_F = model.kt.sum() * np.abs(t).max()
    np.testing.assert_allclose(r.T, F[:2], atol=1e-12 * scale_F)
    np.testing.assert_allclose(r.N, F[2], atol=1e-12 * model.kn.sum() * 1e-6)
    k = max(model.kt.sum(), model.kn.sum())
    np.testing.assert_allclose(r.dT_dt, Jac[:2, :2], atol=1e-9 * k)
    np.testing.assert_allclose(r.dT_dn, Jac[:2, 2], atol=1e-9 * k)
    np.testing.assert_allclose(r.dN_dn, Jac[2, 2], atol=1e-9 * k)


def _finite_difference(model, t, n, Ns, h=1e-13):
    nb = n.size
    dT_dt = np.empty((2, 2, nb, nb))
    dT_dn = np.empty((2, nb, nb))
    dN_dn = np.empty((nb, nb))
    for q in range(nb):
        e = np.zeros(nb)
        e[q] = h
        for b in range(2):
            E = np.zeros((2, nb))
            E[b] = e
            plus, minus = aft_plane(model, t + E, n, samples=Ns), aft_plane(model, t - E, n, samples=Ns)
            dT_dt[:, b, :, q] = (plus.T - minus.T) / (2 * h)
        plus, minus = aft_plane(model, t, n + e, samples=Ns), aft_plane(model, t, n - e, samples=Ns)
        dT_dn[:, :, q] = (plus.T - minus.T) / (2 * h)
        dN_dn[:, q] = (plus.N - minus.N) / (2 * h)
    return dT_dt, dT_dn, dN_dn


def _circle(H, A, phase_x=0.0, B=None):
    """``t`` coefficients of x = A cos, y = B sin (an ellipse; a circle with B = A)."""
    t = np.zeros((2, 2 * H + 1))
    t[0, 1] = A
    t[1, 2] = A if B is None else B
    t[0, 0] = phase_x
    return t


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4, 5])
def test_jacobian_matches_finite_differences(seed):
    model, t, n = _random_case(seed, H=3)
    r = aft_plane(model, t, n, samples=64)
    fd = _finite_difference(model, t, n, 64)
    # piecewise smooth in the coefficients; a 1e-13 m step of 1e-6 m motions stays on one piece, so central
    # differences match to their rounding: ~1 N forces / 1e-13 m carry about 1e-3 N/m of noise on 1e7 N/m
    k = max(model.kt.sum(), model.kn.sum())
    for exact, approx in zip((r.dT_dt, r.dT_dn, r.dN_dn), fd):
        np.testing.assert_allclose(exact, approx, atol=1e-6 * k)


@pytest.mark.parametrize("shape", ["circle", "ellipse", "offset ellipse", "figure eight"])
def test_jacobian_matches_finite_differences_on_orbits(shape):
    """Orbits a damper sees: gross slip on a circle, microslip on ellipses, a figure eight; n varying."""
    model = tune(Sphere.paper(), 37.5, elements=8)
    n0 = float(Sphere.paper().approach(37.5))
    H = 3
    t = {"circle": _circle(H, 3e-6), "ellipse": _circle(H, 0.6e-6, B=0.3e-6),
         "offset ellipse": _circle(H, 0.6e-6, 0.4e-6, B=0.1e-6), "figure eight": _circle(H, 0.8e-6, B=0.0)}[shape]
    if shape == "figure eight":
        t[1, 4] = 0.4e-6  # y = 0.4 sin 2 tau
    n = np.zeros(2 * H + 1)
    n[0], n[1] = n0, 0.2 * n0
    r = aft_plane(model, t, n, samples=64)
    fd = _finite_difference(model, t, n, 64, h=1e-14)
    k = model.kn.sum()
    for exact, approx in zip((r.dT_dt, r.dT_dn, r.dN_dn), fd):
        np.testing.assert_allclose(exact, approx, atol=1e-6 * k)


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4, 5, 6, 7])
def test_a_motion_along_one_direction_is_the_one_direction_contact(seed):
    model, t, n = _random_case(seed, H=3, J=5)
    one = aft(model, t[0], n, samples=64)
    on_x = aft_plane(model, np.array([t[0], np.zeros_like(t[0])]), n, samples=64)
    # the same return mapping, the slip written as s = t - (r / |d|) d on the plane and s = t -+ r on a line:
    # the forces to rounding
    np.testing.assert_allclose(on_x.T[0], one.T, rtol=0, atol=1e-14 * model.kt.sum() * np.abs(t[0]).max())
    np.testing.assert_array_equal(on_x.N, one.N)
    assert not on_x.T[1].any()
    # the derivatives by another route (the fixed point of the period map, not the last slip): to rounding
    k = model.kt.sum() + model.kn.sum()
    np.testing.assert_allclose(on_x.dT_dt[0, 0], one.dT_dt, atol=1e-10 * k)
    np.testing.assert_allclose(on_x.dT_dn[0], one.dT_dn, atol=1e-10 * k)
    np.testing.assert_allclose(on_x.dN_dn, one.dN_dn, atol=1e-10 * k)
    # by symmetry (y -> -y) nothing couples the two directions on the line
    for block in (on_x.dT_dt[0, 1], on_x.dT_dt[1, 0], on_x.dT_dn[1]):
        assert np.abs(block).max() <= 1e-10 * k


@pytest.mark.parametrize("angle", [0.3, 2.0, -1.2])
def test_a_straight_line_at_an_angle_gives_the_one_direction_result_rotated(angle):
    model, t, n = _random_case(3, H=3, J=5)
    c, s = np.cos(angle), np.sin(angle)
    one = aft(model, t[0], n, samples=64)
    r = aft_plane(model, np.array([c * t[0], s * t[0]]), n, samples=64)
    scale = model.kt.sum() * np.abs(t[0]).max()
    np.testing.assert_allclose(r.T, np.array([c * one.T, s * one.T]), atol=1e-12 * scale)
    R = np.array([[c, -s], [s, c]])
    # dT/dt in the rotated frame: R diag(dT1/dt1, dT2/dt2) R^T with the line's own stiffnesses
    local = np.einsum("ai,ijpq,bj->abpq", R.T, r.dT_dt, R.T)
    k = model.kt.sum()
    np.testing.assert_allclose(local[0, 0], one.dT_dt, atol=1e-9 * k)
    np.testing.assert_allclose(local[0, 1], 0.0, atol=1e-9 * k)
    np.testing.assert_allclose(c * r.dT_dn[0] + s * r.dT_dn[1], one.dT_dn, atol=1e-9 * k)


def _sampled_circle(A, r, Ns):
    """The steady state of one Jenkins element on a circle sampled ``Ns`` times, in closed form.

    By symmetry the slider runs on a circle too, ``rho`` behind by the angle ``phi``: in the frame turning
    with ``t = A``, ``s_k = rho exp(-i phi)`` and ``s_(k-1) = rho exp(-i (phi + 2 pi / Ns))``. The return
    mapping puts ``s_k`` on the segment from ``t`` to ``s_(k-1)`` at ``r`` from ``t``: two equations.
    Returns ``u``, the unit force direction in that frame (complex).
    """
    from scipy.optimize import brentq

    step = 2 * np.pi / Ns

    def radius(phi):  # |A - rho exp(-i phi)| = r, the root inside
        return A * np.cos(phi) - np.sqrt(r**2 - (A * np.sin(phi)) ** 2)

    def collinear(phi):
        rho = radius(phi)
        return ((A - rho * np.exp(-1j * (phi + step))) * np.conj(A - rho * np.exp(-1j * phi))).imag / A**2

    phi = brentq(collinear, 0.0, np.arcsin(r / A), xtol=1e-16, rtol=4 * np.finfo(float).eps)
    rho = radius(phi)
    return (A - rho * np.exp(-1j * phi)) / r


@pytest.mark.parametrize("A, Ns", [(2e-4, 16), (5e-4, 64), (2e-3, 33), (1.2e-4, 128)])
def test_circle_in_gross_slip_matches_the_closed_form_of_its_sampled_orbit(A, Ns):
    """t = A (cos, sin) beyond the stick radius: the force, of magnitude mu N, turns with t at a fixed lag."""
    r = aft_plane(JENKINS, _circle(1, A), [1e-6, 0, 0], samples=Ns)
    u = _sampled_circle(A, 1e-4, Ns) * 1.0  # mu N = 1 N
    # T1 + i T2 = mu N u exp(i tau): exact samples of one harmonic, so exact coefficients (to rounding)
    np.testing.assert_allclose(r.T[:, 1:], [[u.real, -u.imag], [u.imag, u.real]], atol=1e-12)
    np.testing.assert_allclose(r.T[:, 0], 0.0, atol=1e-12)


def test_energy_on_a_circle_converges_to_the_continuous_closed_form():
    """Continuous motion: the slider runs on a concentric circle of radius ``rho = sqrt(A^2 - r^2)``, ``t - s``
    of length r tangent to it (the slider moves along the force), so the energy per cycle is ``mu N 2 pi rho``.

    The sampled return mapping follows a curved path to first order in the step (on a straight path it is
    exact between samples): the error halves with each doubling of the samples.
    """
    A = 3e-4
    rho = np.sqrt(A**2 - 1e-8)
    errors = np.array([aft_plane(JENKINS, _circle(1, A), [1e-6, 0, 0], samples=Ns).dissipation(_circle(1, A))
                       / (2 * np.pi * rho) - 1 for Ns in (64, 128, 256, 512, 1024)])
    rates = np.log2(errors[:-1] / errors[1:])
    assert np.all(np.abs(rates - 1) < 0.1)  # first order, from one side
    assert abs(errors[1]) < 1e-2 and abs(errors[-1]) < 1.2e-3  # 128 samples: 0.9 %; 1024: 0.11 %


def test_an_element_that_barely_slips_is_periodic_in_a_few_periods():
    """Slipping 1 % of its stick radius per cycle, the slider contracts by about exp(-0.01) per period.

    Plain periods would take thousands to repeat to rounding; the Newton steps on the period map take a
    handful, and the twin, marching plainly, agrees with the result.
    """
    t = _circle(1, 1.005e-4, B=0.5e-4)  # just beyond r = 1e-4 along x, well inside along y
    n = np.array([1e-6, 0.0, 0.0])
    r = aft_plane(JENKINS, t, n, samples=32)
    assert r.periods <= 10
    F, Jac, periods = aft_plane_reference(JENKINS.kt, JENKINS.kn, JENKINS.gaps, JENKINS.mu, t[0], t[1], n, 32)
    assert periods > 100
    np.testing.assert_allclose(r.T, F[:2], atol=1e-10)
    np.testing.assert_allclose(r.dT_dt, Jac[:2, :2], atol=1e-6 * 1e4)


def test_a_newton_step_that_overshoots_is_shortened():
    """A motion met on a harmonic balance curve (the 8-element sphere under a 3-DOF structure), where one
    element's fixed point lies just across a change of its slip pattern: a full Newton step from one side
    overshoots. Shortened steps converge; starting the element again from the static step would leave it to
    thousands of plain periods (the slider creeps by a factor 0.997 per period)."""
    model = tune(Sphere.paper(), 37.5, elements=8)
    t = np.array([[-1.4281600127283143e-08, 3.316156156115378e-07, 2.0815998960129506e-08, -3.778051744516878e-09,
                   1.6263739072811408e-10, -1.1136066812832282e-09, -4.212444957215849e-09, -4.463730483436133e-09,
                   3.829519338763516e-10, -5.24339784937063e-11, -2.651019892543301e-11],
                  [4.658914561721157e-10, 1.760193966568407e-08, -1.8910973820509768e-07, 5.287259898294274e-10,
                   2.5325287896504892e-09, -3.537727925328244e-09, 7.16211608316541e-10, 3.5169805500303176e-09,
                   1.8487809413979257e-09, 2.164820931504973e-12, 4.2874365710598445e-11]])
    n = np.zeros(11)
    n[:3] = [1.616451152150991e-06, 8.759388532241335e-08, 1.472366374462887e-09]
    r = aft_plane(model, t, n, samples=128)
    assert r.periods < 400


def test_an_element_on_a_corner_of_its_stick_region_takes_its_derivative_from_that_corner():
    """A motion met on a harmonic balance curve (a puck on its plane with a static push): the third element
    creeps onto a corner of its stick region, where the circles of two samples meet, contracting by 1.3 % per
    period. Newton steps reach it in a few periods; the corner, fixed by those two samples and not by the
    element's history, gives the derivative (taking it from the history instead was off by 100 %)."""
    model = MicroslipModel(kt=[3e4, 2e4, 1e4], kn=[2e6, 2e6, 2e6], gaps=[0.0, 0.3e-6, 0.6e-6], mu=0.5)
    t = np.zeros((2, 11))
    t[0, [0, 1, 2, 5, 6, 9, 10]] = [1.026264169071451e-05, 3.612656221146175e-05, 1.0236958498141291e-05,
                                    -7.837399704048127e-08, -7.387460973786496e-08, -1.499696969485441e-08,
                                    -2.473172828743903e-09]
    t[1, [0, 1, 2, 5, 6, 9, 10]] = [1.6180259733182164e-05, 1.376620486634661e-05, 2.697312294576065e-06,
                                    -3.1600467436319924e-08, -2.9034236851201593e-08, -5.92959775585675e-09,
                                    -8.468215146626199e-10]
    n = np.zeros(11)
    n[0] = 1e-6
    r = aft_plane(model, t, n, samples=128)
    assert r.periods < 20
    fd = _finite_difference(model, t, n, 128)
    k = model.kn.sum()
    for exact, approx in zip((r.dT_dt, r.dT_dn, r.dN_dn), fd):
        np.testing.assert_allclose(exact, approx, atol=1e-6 * k)


def test_the_period_is_plane_step_to_the_bit():
    """The AFT's period against ``plane_step`` marched sample by sample (the contact cycles' march) from the
    same sliders, on 11 elements that open, stick and slip: the conditions, each element's force and the
    sliders equal to the bit (the same element update)."""
    from microslip.kernels import aft_plane as _aft_plane, plane_march as _plane_march

    rng = np.random.default_rng(5)
    J, Ns = 11, 64
    kt, kn = rng.uniform(1e6, 1e7, J), rng.uniform(1e6, 1e7, J)
    gaps, mu = np.linspace(0.0, 2e-7, J), 0.3
    tau = 2 * np.pi * np.arange(Ns) / Ns
    t1, t2, n = 1e-7 * np.cos(tau), 0.4e-7 * np.sin(2 * tau), 1.5e-7 + 1e-7 * np.cos(tau)
    s = rng.normal(scale=1e-7, size=(2, J))
    st, rec = _aft_plane.march_work(J, Ns)
    st[:2] = s
    _aft_plane._period(kt, kn, gaps, mu, mu * kn / kt, t1, t2, n, st, rec)
    Ti, cond = np.empty((Ns, J, 2)), np.empty((Ns, J), dtype=np.int8)
    _plane_march.march_plane(kt, kn, gaps, mu, t1, t2, n, s, np.empty((Ns, 2)), np.empty(Ns), Ti, cond)
    assert set(np.unique(cond)) == {0, 1, 2}  # open, stick and slip all occur
    np.testing.assert_array_equal(rec[0], cond)
    np.testing.assert_array_equal(rec[4], Ti[:, :, 0])
    np.testing.assert_array_equal(rec[5], Ti[:, :, 1])
    np.testing.assert_array_equal(st[:2], s)


@pytest.mark.parametrize("planar", [[True, False, True], [True, True, True]])
def test_a_batch_of_contacts_gives_each_contact_alone(planar):
    """The harmonic balance's batch (contacts on their planes, with contacts along one direction or without
    them) equals each contact's ``aft_plane`` and ``aft``, bit for bit."""
    from microslip.kernels import aft as _aft, aft_plane as _aft_plane
    from microslip.frequency.aft import aft as aft_line
    from microslip.frequency.aft import pack_models

    cases = [_random_case(seed, H=3, J=seed + 2) for seed in (0, 1, 2)]
    models = [model for model, _, _ in cases]
    nc, nb = len(cases), 7
    XT, XT2, XN = (np.array([c[1][0] if a == 0 else c[1][1] if a == 1 else c[2] for c in cases]) for a in range(3))
    for c, p in enumerate(planar):
        if not p:
            XT2[c] = 0.0
    FT, FN, FT2 = (np.zeros((nc, nb)) for _ in range(3))
    JTt, JTn, JNn, JT12, JT21, JT22, JT2n = (np.zeros((nc, nb, nb)) for _ in range(7))
    periods = np.empty(nc, dtype=np.int64)
    _aft_plane.aft_mixed_batch(*pack_models(models), np.array(planar), XT, XT2, XN, *_aft.tables(3, 64),
                               _aft_plane.sweep_tables(3, 64), 1000, FT, FN, JTt, JTn, JNn, FT2, JT12, JT21, JT22,
                               JT2n, periods)
    for c, (model, t, n) in enumerate(cases):
        if planar[c]:
            r = aft_plane(model, np.array([XT[c], XT2[c]]), n, samples=64)
            got = (FT[c], FT2[c], FN[c], JTt[c], JT12[c], JT21[c], JT22[c], JTn[c], JT2n[c], JNn[c])
            want = (r.T[0], r.T[1], r.N, r.dT_dt[0, 0], r.dT_dt[0, 1], r.dT_dt[1, 0], r.dT_dt[1, 1], r.dT_dn[0],
                    r.dT_dn[1], r.dN_dn)
        else:
            r = aft_line(model, XT[c], n, samples=64)
            got, want = (FT[c], FN[c], JTt[c], JTn[c], JNn[c]), (r.T, r.N, r.dT_dt, r.dT_dn, r.dN_dn)
        for a, b in zip(got, want):
            np.testing.assert_array_equal(a, b)


def _plain_periods(model, t, n, Ns, periods):
    """The tangential force coefficients (N, (2, 2H+1)) after ``periods`` plain periods from the static step."""
    from microslip.kernels import aft as _aft, aft_plane as _aft_plane

    H = (n.size - 1) // 2
    E, P = _aft.tables(H, Ns)[:2]
    t1, t2, nn = E @ t[0], E @ t[1], E @ n
    rk = model.mu * model.kn / model.kt
    _, a1, a2, _, _ = _aft_plane._static(rk[0], n[0] - model.gaps[0], t[0, 0], t[1, 0])
    st, rec = _aft_plane.march_work(1, Ns)
    st[0, 0], st[1, 0] = a1, a2
    for _ in range(periods):
        _aft_plane._period(model.kt, model.kn, model.gaps, model.mu, rk, t1, t2, nn, st, rec)
    return np.array([P @ rec[4][:, 0], P @ rec[5][:, 0]])


def test_an_element_slipping_between_two_nearly_touching_discs_is_periodic():
    """A nearly straight orbit a little longer than the stick diameter: the element slips at its two ends only,
    where the stick discs of the two end samples miss each other by 4e-12 m (their radii 5.2e-7 m). Its slider
    goes back and forth between their nearest points, which the plain march nears sublinearly and Newton
    steps miss (each crosses a change of the slip pattern): it was
    not periodic after 20000 periods. The fixed point is taken from the two samples, checked by one more
    period; the Jacobian equals finite differences and the plain march closes in on the forces."""
    model = MicroslipModel(kt=[7980811.235245448], kn=[17411407.649864003], gaps=[0.0], mu=0.2355663597857711)
    t = np.array([[-1.3195062315792844e-07, -2.6521411937108767e-07, 5.4606989256273365e-08],
                  [2.2724949121736333e-07, 4.4745955604701455e-07, 4.5794487877842572e-08]])
    n = np.array([1.0121856628128561e-06, -1.3147021233017030e-08, -5.4396686213659632e-09])
    r = aft_plane(model, t, n, samples=128)
    assert r.periods < 100
    # finite differences of 1e-13 m: rounding of the forces (1e-16 of 1 N) over h, 1e-3 N/m, far below 1e-7 kt
    fd = _finite_difference(model, t, n, 128)
    for exact, approx in zip((r.dT_dt, r.dT_dn, r.dN_dn), fd):
        np.testing.assert_allclose(exact, approx, atol=1e-7 * model.kt[0])
    # the plain march closes in on it, sublinearly: 0.6 %, 0.35 %, 0.055 % of the force after 1e3, 1e4, 1e5 periods
    errors = [np.abs(_plain_periods(model, t, n, 128, p) - r.T).max() for p in (1000, 10000, 100000)]
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 1e-3 * np.abs(r.T).max()


def test_an_element_a_newton_step_leaves_inside_its_stick_region_goes_onto_the_corner_it_creeps_to():
    """A Newton step that takes an element from outside its stick region to inside it, off the corner the
    plain march creeps to (the circles of samples 0 and 95): the element used to start again from the static
    step and march plainly, 2170 periods (beyond the default 1000). It goes onto that corner, the state the
    plain march reaches (forces to 1e-12), with the corner's derivative (finite differences)."""
    model = MicroslipModel(kt=[59985381.71883892], kn=[1.0770052201192036e+09], gaps=[0.0], mu=0.10537073041704365)
    t = np.array([[-8.1397424947921962e-07, 1.2035286380259509e-06, 6.3034614969894981e-07, 4.7730448698584528e-07,
                   0.0],
                  [6.9596887123879056e-08, 2.8903362777212640e-07, -7.7998176712417744e-08, 1.7543830490653678e-08,
                   0.0]])
    n = np.array([8.7074413334147666e-07, -2.0632646206460357e-07, 4.8459163127284144e-08, 1.5619222489861807e-07,
                  1.4491275298470830e-07])
    r = aft_plane(model, t, n, samples=128)
    assert r.periods < 100
    np.testing.assert_allclose(r.T, _plain_periods(model, t, n, 128, 3000), rtol=0, atol=1e-12 * np.abs(r.T).max())
    fd = _finite_difference(model, t, n, 128)
    for exact, approx in zip((r.dT_dt, r.dT_dn, r.dN_dn), fd):
        np.testing.assert_allclose(exact, approx, atol=1e-7 * model.kn[0])


def test_not_periodic_within_max_periods_is_reported():
    with pytest.raises(NotPeriodicError, match="max_periods = 1"):
        aft_plane(JENKINS, _circle(1, 3e-4), [1e-6, 0, 0], samples=32, max_periods=1)


def test_the_normal_force_does_no_work_and_friction_dissipates():
    model = tune(Sphere.paper(), 37.5, elements=8)
    n0 = float(Sphere.paper().approach(37.5))
    t = _circle(7, 1e-6, B=0.4e-6)
    n = np.zeros(15)
    n[0], n[1] = n0, 0.2 * n0
    r = aft_plane(model, t, n)
    assert r.samples == 128
    assert r.dissipation(t) > 0
    assert cycle_work(r.N, n) == pytest.approx(0.0, abs=1e-3 * r.dissipation(t))


@pytest.mark.parametrize("call, message", [
    (lambda: aft_plane("model", [[0, 1e-6, 0]] * 2, [1e-6, 0, 0]), "model must be a microslip MicroslipModel"),
    (lambda: aft_plane(JENKINS, [0, 1e-6, 0], [1e-6, 0, 0]), "t must have shape \\(2, 2H\\+1\\)"),
    (lambda: aft_plane(JENKINS, [[0, 1e-6, 0]] * 3, [1e-6, 0, 0]), "t must have shape \\(2, 2H\\+1\\)"),
    (lambda: aft_plane(JENKINS, [[0, 1e-6]] * 2, [1e-6, 0]), "t must hold 2H \\+ 1 Fourier coefficients"),
    (lambda: aft_plane(JENKINS, [[0, 1e-6, 0]] * 2, [1e-6, 0, 0, 0, 0]), "n must have shape \\(3,\\)"),
    (lambda: aft_plane(JENKINS, [[0, np.inf, 0]] * 2, [1e-6, 0, 0]), "t must be finite"),
    (lambda: aft_plane(JENKINS, [[0, 6e99, 6e99], [0, 0, 0]], [1e-6, 0, 0]), "t must stay below 1e\\+100 m"),
    (lambda: aft_plane(JENKINS, [[0, 1e-6, 0]] * 2, [1e-6, 0, 0], samples=2), "samples must be at least"),
    (lambda: aft_plane(JENKINS, [[0, 1e-6, 0]] * 2, [1e-6, 0, 0], max_periods=0), "max_periods must be"),
    (lambda: aft_plane(JENKINS, [[0, 1e-6, 0]] * 2, [1e-6, 0, 0]).dissipation([0, 1e-6, 0]),
     "t must have the shape of T \\(2, 3\\)"),
])
def test_input_errors_name_the_parameter(call, message):
    with pytest.raises((ValueError, TypeError), match=message):
        call()
