"""The MDR array against the closed forms of the continuous sphere contact.

Measured errors (paper's sphere, built for 50 N; ``python -m pytest tests/test_mdr.py``
checks them), for J = 100 / 400 / 1600 elements:

====================================================  =========  =========  =========
quantity                                               J = 100    J = 400    J = 1600
====================================================  =========  =========  =========
Hertz: max |N/N_Hertz - 1| over 2..50 N                6.5e-5     3.4e-6     2.3e-7
backbone: max |T - T_CM| / (mu N), 10 and 37.5 N       1.0e-4     6.4e-6     2.4e-7
Masing loop at 30 N, t_a = 0.8 t_gs: max |dT|/(mu N)   6.0e-5     4.0e-6     3.3e-7
Mindlin's energy at T*/(mu N) = 0.1, relative          5.0e-2     1.1e-3     1.2e-4
Mindlin's energy at T*/(mu N) = 0.5, relative          2.9e-4     2.2e-5     4.7e-6
Fig. 4 path (M-D join): max |dT| / (mu (N + dN))       2.9e-5     5.9e-6     5.7e-6
====================================================  =========  =========  =========

The errors fall as about J^-2 until the floor set by the time steps of the
path (4000 per cycle for the energy, 400 per leg for Fig. 4).
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import Sphere, mdr, paths
from microslip.reference.mdr import LoadLimitError, MDRModel, contact_radius
from microslip.reference.profiles import AxisymmetricProfile, RoundedPunch, SphereProfile

SPHERE = Sphere.paper()
SIZES = (100, 400, 1600)


@pytest.fixture(scope="module")
def arrays():
    return {J: mdr(SPHERE, max_load=50.0, elements=J) for J in SIZES}


def _hertz_error(m):
    loads = np.array([2.0, 10.0, 37.5, 50.0])
    return float(np.max(np.abs(m.normal_force(SPHERE.approach(loads)) / loads - 1)))


def _backbone_error(m):
    worst = 0.0
    for N in (10.0, 37.5):
        t = np.linspace(0.0, 1.2 * SPHERE.gross_slip_displacement(N), 300)
        worst = max(worst, float(np.max(np.abs(m.backbone(t, SPHERE.approach(N)) - SPHERE.backbone(t, N))))
                    / (SPHERE.mu * N))
    return worst


def _masing_error(m, N=30.0):
    ta = 0.8 * float(SPHERE.gross_slip_displacement(N))
    tau = np.linspace(0.0, 2.5 * np.pi, 2001)
    t = ta * np.sin(tau)
    T = m.simulate(t, SPHERE.approach(N), per_element=False).T
    k1, k2 = np.searchsorted(tau, [np.pi / 2, 1.5 * np.pi])
    Ta = float(SPHERE.backbone(ta, N))
    down = SPHERE.branch(t[k1:k2 + 1], N, ta, Ta)
    up = SPHERE.branch(t[k2:], N, -ta, -Ta)
    return max(np.max(np.abs(T[k1:k2 + 1] - down)), np.max(np.abs(T[k2:] - up))) / (SPHERE.mu * N)


def _energy_error(m, x, N=30.0):
    Ta = x * SPHERE.mu * N
    ta = float(SPHERE.backbone_displacement(Ta, N))
    t = ta * np.sin(np.linspace(0.0, 4 * np.pi, 8001))
    T = m.simulate(t, SPHERE.approach(N), per_element=False).T
    return abs(np.trapezoid(T[4000:], t[4000:]) / SPHERE.dissipation(Ta, N) - 1)


def _converges(errors, tol, rate=8.0):
    """The finest error is below ``tol`` and each 4x refinement cuts the error ``rate`` times (order > 1.5)."""
    assert errors[-1] < tol, errors
    for coarse, fine in zip(errors[:-1], errors[1:]):
        assert fine < coarse / rate, errors


def test_hertz_normal_law_converges(arrays):
    # measured 6.5e-5, 3.4e-6, 2.3e-7: midpoint quadrature of a kinked integrand, O(J^-2)
    _converges([_hertz_error(arrays[J]) for J in SIZES], 5e-7)


def test_cattaneo_mindlin_backbone_converges(arrays):
    # measured 1.0e-4, 6.4e-6, 2.4e-7 of mu N
    _converges([_backbone_error(arrays[J]) for J in SIZES], 5e-7)


def test_masing_loop_converges(arrays):
    # measured 6.0e-5, 4.0e-6, 3.3e-7 of mu N
    _converges([_masing_error(arrays[J]) for J in SIZES], 1e-6)


@pytest.mark.parametrize("x, tol", [(0.1, 3e-4), (0.5, 2e-5), (0.9, 1e-5)])
def test_mindlin_energy(arrays, x, tol):
    # finest measured 1.2e-4, 4.7e-6, 1.9e-6: at x = 0.1 the slip annulus is thin (few elements slip)
    errors = [_energy_error(arrays[J], x) for J in SIZES]
    assert errors[-1] < tol, errors
    assert errors[-1] < errors[0], errors


def test_mindlin_deresiewicz_join_after_a_normal_step(arrays):
    """Raise N at constant T (point A), then T: the path of Sphere.raised_load_path, joining at B."""
    N, dN, x = 25.0, 12.5, 0.5
    p = paths.paper_fig4(SPHERE, N, dN, x, steps=400)
    Tg = np.linspace(0.0, SPHERE.mu * (N + dN), 20001)
    tg = SPHERE.raised_load_path(Tg, N, dN, x * SPHERE.mu * N)
    leg2, leg3 = slice(399, 2 * 399), slice(2 * 399, None)
    errors = []
    for J in SIZES:
        T = p.simulate(arrays[J]).T
        # raising n at constant t leaves T unchanged: new contact enters unloaded, slipping elements stick
        assert np.ptp(T[leg2]) <= 1e-12 * T[leg2][0]
        errors.append(np.max(np.abs(T[leg3] - np.interp(p.t[leg3], tg, Tg))) / (SPHERE.mu * (N + dN)))
    # measured 2.9e-5, 5.9e-6, 5.7e-6: the floor is the 400 samples per leg (a kink at B between samples)
    assert errors[-1] < 1e-5 and errors[1] < errors[0], errors
    # at and beyond the join point B the path is the virgin curve at N + dN
    tB, TB = SPHERE.join_point(N, dN, x * SPHERE.mu * N)
    T = p.simulate(arrays[1600]).T
    beyond = p.t[leg3] >= tB
    assert np.allclose(T[leg3][beyond], SPHERE.backbone(p.t[leg3][beyond], N + dN), atol=1e-5 * SPHERE.mu * N)
    # ... and not before: between A and B it runs distinctly below that curve
    gap = SPHERE.backbone(p.t[leg3][~beyond], N + dN) - T[leg3][~beyond]
    assert gap.max() > 0.05 * SPHERE.mu * N and gap.min() > -1e-5 * SPHERE.mu * N
    assert float(SPHERE.backbone(tB, N + dN)) == pytest.approx(TB, rel=1e-12)


def test_lowering_n_at_constant_T_erases_memory(arrays):
    """Load to T_A at N, lower N to N2 keeping T = T_A: the state lands on the virgin curve at N2."""
    m = arrays[1600]
    N, N2, TA = 37.5, 20.0, 0.6 * SPHERE.mu * 20.0
    n1, n2 = SPHERE.approach(N), SPHERE.approach(N2)
    tA = float(SPHERE.backbone_displacement(TA, N))
    state = m.simulate(np.linspace(0.0, tA, 200), n1, per_element=False).state
    t = tA
    for n in np.linspace(n1, n2, 60)[1:]:
        lo, hi = t, 2 * float(SPHERE.gross_slip_displacement(N2))  # T rises with t: bisect for T = T_A
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if m.trial(state, mid, n).T < TA else (lo, mid)
        t = 0.5 * (lo + hi)
        state = m.trial(state, t, n).state
    # the displacement is the virgin one at N2 (memory of N erased); measured error 2.6e-7 of it
    assert t == pytest.approx(float(SPHERE.backbone_displacement(TA, N2)), rel=2e-6)
    # and raising t from there follows the virgin curve at N2
    more = np.linspace(t, 1.2 * float(SPHERE.gross_slip_displacement(N2)), 200)
    T = m.simulate(more, n2, state, per_element=False).T
    assert np.max(np.abs(T - SPHERE.backbone(more, N2))) < 2e-6 * SPHERE.mu * N2  # measured 2.0e-7


@settings(max_examples=25, deadline=None)
@given(load=st.floats(0.5, 50.0), x=st.floats(0.0, 1.0))
def test_any_load_and_point_on_the_backbone(load, x):
    m = _fine()
    n = SPHERE.approach(load)
    assert float(m.normal_force(n)) == pytest.approx(load, rel=2e-5)  # J = 800: measured <= 1e-6
    t = x * float(SPHERE.gross_slip_displacement(load))
    assert float(m.backbone(t, n)) == pytest.approx(float(SPHERE.backbone(t, load)), abs=1e-4 * SPHERE.mu * load)


_FINE = {}


def _fine():
    if not _FINE:
        _FINE["m"] = mdr(SPHERE, max_load=50.0, elements=800)
    return _FINE["m"]


def test_it_is_a_microslip_model_with_the_mdr_stiffnesses():
    m = mdr(SPHERE, max_load=37.5, elements=10)
    assert isinstance(m, MDRModel) and m.elements == 10
    a = float(SPHERE.contact_radius(37.5))
    assert m.contact_radius == pytest.approx(a)
    assert m.kt.sum() == pytest.approx(8 * SPHERE.G_star * a)  # Mindlin's initial stiffness
    assert m.kn.sum() == pytest.approx(2 * SPHERE.E_star * a)  # Hertz stiffness
    assert m.max_approach == pytest.approx(float(SPHERE.approach(37.5)))
    assert "max_load=37.5 N" in repr(m)


def test_loads_beyond_max_load_are_refused():
    m = mdr(SPHERE, max_load=20.0, elements=50)
    n = SPHERE.approach(np.array([10.0, 25.0]))
    with pytest.raises(LoadLimitError, match=r"max_load = 20 N this MDR model was built for"):
        m.simulate([0.0, 1e-7], n)
    with pytest.raises(LoadLimitError, match="beyond the approach"):
        m.normal_force(n[1])
    with pytest.raises(LoadLimitError):
        m.trial(None, 0.0, float(n[1]))
    m.simulate([0.0, 1e-7], SPHERE.approach(np.array([10.0, 20.0])))  # exactly at the limit is fine


@pytest.mark.parametrize("kwargs, message", [
    ({"max_load": -1.0}, "max_load must be positive, got -1.0"),
    ({"max_load": np.nan}, "max_load must be finite"),
    ({"max_load": 10.0, "elements": 0}, "elements must be an integer >= 1, got 0"),
    ({"max_load": 10.0, "elements": 2.5}, "elements must be an integer"),
    ({"max_load": 10.0, "profile": 3.0}, "profile must be a SphereProfile"),
])
def test_bad_arguments(kwargs, message):
    with pytest.raises((ValueError, TypeError), match=message):
        mdr(SPHERE, **kwargs)


def test_reference_without_elastic_constants():
    with pytest.raises(TypeError, match="reference must provide E_star, G_star and mu"):
        mdr(object(), max_load=1.0)


def test_decreasing_profile_is_refused():
    """A spherical cap on a cylinder (flat beyond r = c): g(x) falls beyond c."""
    R, c = 5e-3, 2e-5
    cap = AxisymmetricProfile(lambda r: np.minimum(r, c) ** 2 / (2 * R), scale=c,
                              slope=lambda r: np.where(r < c, r / R, 0.0), breaks=[c])
    with pytest.raises(ValueError, match="g\\(x\\) decreases"):
        mdr(SPHERE, max_load=1.0, elements=20, profile=cap)


# -- profiles ---------------------------------------------------------------------

def test_quadrature_reproduces_the_sphere_profile():
    R = 5e-3
    x = np.linspace(0, 2e-4, 7)
    p = AxisymmetricProfile(lambda r: r**2 / (2 * R), scale=R)
    assert np.allclose(p.mdr(x), SphereProfile(R).mdr(x), rtol=1e-8, atol=0)


@pytest.mark.parametrize("with_slope", [True, False])
def test_quadrature_reproduces_the_rounded_punch(with_slope):
    b, rho = 1e-4, 2e-3
    exact = RoundedPunch(b, rho)
    slope = (lambda r: np.maximum(r - b, 0.0) / rho) if with_slope else None
    p = AxisymmetricProfile(exact.height, scale=rho, slope=slope)
    x = np.linspace(0, 3e-4, 13)
    # the slope has a kink at b; measured relative errors <= 1e-9 (finite-difference slope included)
    # and 1e-13 m absolute at x = b, where the finite difference straddles the kink
    assert np.allclose(p.mdr(x), exact.mdr(x), rtol=1e-8, atol=1e-12)


def test_contact_radius_by_quadrature_matches_hertz():
    R = 5e-3
    p = AxisymmetricProfile(lambda r: r**2 / (2 * R), scale=R)
    assert contact_radius(p, SPHERE.E_star, 30.0) == pytest.approx(float(SPHERE.contact_radius(30.0)), rel=1e-8)


def test_sharp_punch_has_the_boussinesq_stiffness():
    """A flat punch of radius b with a nearly sharp edge: N = 2 E* b n (Boussinesq)."""
    b = 1e-4
    m = mdr(SPHERE, max_load=200.0, elements=2000, profile=RoundedPunch(b, 1e-7))
    n = 0.5 * m.max_approach
    # the rounded edge adds a contact ring of width ~sqrt(2 rho n): measured +0.3 %
    assert float(m.normal_force(n)) == pytest.approx(2 * SPHERE.E_star * b * n, rel=1e-2)


def test_profile_argument_errors():
    with pytest.raises(TypeError, match="shape must be a callable"):
        AxisymmetricProfile(3.0, scale=1.0)
    with pytest.raises(ValueError, match="breaks must be positive"):
        AxisymmetricProfile(lambda r: r, scale=1.0, breaks=[-1.0])
    with pytest.raises(ValueError, match="scale must be positive"):
        AxisymmetricProfile(lambda r: r, scale=0.0)
    with pytest.raises(ValueError, match="edge_radius must be positive"):
        RoundedPunch(1e-4, 0.0)
    with pytest.raises(ValueError, match="x must be finite"):
        SphereProfile(1.0).mdr([np.nan])
