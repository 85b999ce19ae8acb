"""Sphere on a plane: Hertz, Cattaneo--Mindlin, Masing, Mindlin's energy, Mindlin--Deresiewicz.

Expected values are recomputed here from the textbook formulas (Johnson,
*Contact Mechanics*, ch. 4 and 7) written out independently of the code.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from microslip import Sphere
from microslip.reference import masing

R, E, NU, MU = 5e-3, 200e9, 0.3, 0.4
N_TOT = 37.5


@pytest.fixture(scope="module")
def sphere():
    return Sphere.paper()


def test_paper_parameters(sphere):
    assert (sphere.radius, sphere.E, sphere.nu, sphere.mu) == (R, E, NU, MU)


# -- Hertz -----------------------------------------------------------------------
def test_hertz_closed_forms(sphere):
    E_star = 1.0 / (2 * (1 - NU**2) / E)  # identical bodies: 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2
    N = np.array([0.0, 1.0, 10.0, 37.5, 100.0])
    a = (3 * N * R / (4 * E_star)) ** (1 / 3)
    np.testing.assert_allclose(sphere.E_star, E_star, rtol=1e-15)
    np.testing.assert_allclose(sphere.contact_radius(N), a, rtol=1e-14)
    np.testing.assert_allclose(sphere.approach(N), a**2 / R, rtol=1e-14)
    # Johnson (4.23): delta = (9 N^2 / (16 R E*^2))^(1/3), another route to the same number
    np.testing.assert_allclose(sphere.approach(N), (9 * N**2 / (16 * R * E_star**2)) ** (1 / 3), rtol=1e-14)
    # N(n) inverts the approach (and is zero out of contact)
    np.testing.assert_allclose(sphere.normal_force(sphere.approach(N)), N, rtol=1e-13, atol=1e-14)
    np.testing.assert_array_equal(sphere.normal_force([-1e-6, 0.0]), [0.0, 0.0])
    # order of magnitude at the paper's load: a ~ 0.1 mm
    assert 0.09e-3 < float(sphere.contact_radius(N_TOT)) < 0.11e-3


def test_hertz_normal_stiffness_is_the_derivative(sphere):
    """dN/dn = 2 a E*: central difference with h = 1e-6 n, whose truncation error,
    (h/n)^2 / 8 relative for N ~ n^(3/2), is 1e-13, far below rtol = 1e-8 (which
    leaves room for the rounding of the difference, ~ eps n / h = 2e-10)."""
    for N in (1.0, 37.5, 200.0):
        n = float(sphere.approach(N))
        h = 1e-6 * n
        fd = (float(sphere.normal_force(n + h)) - float(sphere.normal_force(n - h))) / (2 * h)
        assert float(sphere.normal_stiffness(N)) == pytest.approx(fd, rel=1e-8)
        assert float(sphere.normal_stiffness(N)) == pytest.approx(
            2 * float(sphere.contact_radius(N)) * sphere.E_star, rel=1e-15)


# -- Cattaneo--Mindlin -------------------------------------------------------------
def test_gross_slip_of_the_paper_sphere_is_1_145_um(sphere):
    """Johnson (7.52) for two identical bodies: delta_gs = 3 mu N (2 - nu) / (8 G a)."""
    G = E / (2 * (1 + NU))
    E_star = E / (2 * (1 - NU**2))
    a = (3 * N_TOT * R / (4 * E_star)) ** (1 / 3)
    t_gs = 3 * MU * N_TOT * (2 - NU) / (8 * G * a)
    assert round(t_gs * 1e6, 3) == 1.145  # the paper's Fig. 2a, with E = 200 GPa
    assert float(sphere.gross_slip_displacement(N_TOT)) == pytest.approx(t_gs, rel=1e-14)
    assert float(sphere.backbone(t_gs, N_TOT)) == pytest.approx(MU * N_TOT, rel=1e-15)
    assert float(sphere.gross_slip_displacement(0.0)) == 0.0


def test_backbone_closed_form_and_its_inverse(sphere):
    t_gs = float(sphere.gross_slip_displacement(N_TOT))
    t = np.linspace(-1.5, 1.5, 61) * t_gs
    x = np.minimum(np.abs(t) / t_gs, 1.0)
    expected = np.sign(t) * MU * N_TOT * (1 - (1 - x) ** 1.5)
    np.testing.assert_allclose(sphere.backbone(t, N_TOT), expected, rtol=1e-14, atol=1e-14)
    inside = np.abs(t) <= t_gs
    np.testing.assert_allclose(sphere.backbone_displacement(sphere.backbone(t[inside], N_TOT), N_TOT),
                               t[inside], rtol=1e-9, atol=1e-9 * t_gs)
    T = np.linspace(-MU * N_TOT, MU * N_TOT, 41)
    np.testing.assert_allclose(sphere.backbone(sphere.backbone_displacement(T, N_TOT), N_TOT), T,
                               rtol=1e-12, atol=1e-12 * MU * N_TOT)
    # broadcasting over loads: t of shape (5, 1) against N of shape (3,)
    assert sphere.backbone(t[:5, None], [10.0, 20.0, 37.5]).shape == (5, 3)


def test_initial_tangential_stiffness_is_8_G_star_a(sphere):
    """Forward difference T(h)/h of the backbone (odd, T(0) = 0): T = mu N (1 - (1-x)^(3/2))
    = mu N (3x/2 - 3x^2/8 + ...), so the relative truncation error is x/4 = 2.5e-7 for
    x = h/t_gs = 1e-6; rtol = 1e-6."""
    G_star = (E / (2 * (1 + NU))) / (2 * (2 - NU))
    for N in (5.0, 37.5):
        a = float(sphere.contact_radius(N))
        h = 1e-6 * float(sphere.gross_slip_displacement(N))
        assert float(sphere.backbone(h, N)) / h == pytest.approx(8 * G_star * a, rel=1e-6)
        assert float(sphere.tangential_stiffness(N)) == pytest.approx(8 * G_star * a, rel=1e-14)


# -- Masing --------------------------------------------------------------------------
def test_masing_branch_is_the_backbone_doubled_about_the_reversal(sphere):
    t_gs = float(sphere.gross_slip_displacement(N_TOT))
    tr = 0.7 * t_gs
    Tr = float(sphere.backbone(tr, N_TOT))
    t = np.linspace(tr, -tr, 50)
    branch = sphere.branch(t, N_TOT, tr, Tr)
    np.testing.assert_allclose(branch, Tr - 2 * sphere.backbone((tr - t) / 2, N_TOT), rtol=1e-14, atol=1e-14)
    assert branch[0] == Tr
    # the unloading branch from (tr, Tr) ends at (-tr, -Tr): the loop closes
    assert branch[-1] == pytest.approx(-Tr, rel=1e-14)
    # the generic Masing helper does the same with any backbone
    np.testing.assert_allclose(masing.branch(lambda x: sphere.backbone(x, N_TOT), t, tr, Tr), branch, rtol=0)


def test_masing_loop_closes_and_is_point_symmetric(sphere):
    t_gs = float(sphere.gross_slip_displacement(N_TOT))
    amp = 0.8 * t_gs
    t, T = sphere.loop(amp, N_TOT, points=101)
    assert t.shape == T.shape == (201,)
    assert (t[0], t[100], t[-1]) == (amp, -amp, amp)
    assert T[-1] == pytest.approx(T[0], rel=1e-14)
    assert T[0] == pytest.approx(float(sphere.backbone(amp, N_TOT)), rel=1e-15)
    # the reloading half is the unloading half turned by 180 degrees
    np.testing.assert_allclose(T[100:], -T[:101], rtol=1e-13, atol=1e-13 * MU * N_TOT)
    # the loop is traversed clockwise in the (t, T) plane: the work done on the contact is positive
    assert np.trapezoid(T, t) > 0


@pytest.mark.parametrize("x", [0.1, 0.5, 0.9, 0.99])
def test_mindlin_energy_equals_the_integrated_masing_loop(sphere, x):
    """Trapezoidal area of the loop vs W from Mindlin's formula, at T* = x mu N.

    Tolerance from the composite trapezoid error bound, (b - a) h^2 max|T''| / 12 per
    branch: on a branch T = T_r + 2 f((t - t_r)/2) so T'' = f''/2, and with
    f(u) = mu N (1 - (1 - u/t_gs)^(3/2)), |f''(u)| = 3 mu N / (4 t_gs^2) (1 - u/t_gs)^(-1/2),
    largest at u = amplitude.
    """
    N = N_TOT
    t_gs = float(sphere.gross_slip_displacement(N))
    T_amp = x * MU * N
    amp = float(sphere.backbone_displacement(T_amp, N))
    points = 801
    t, T = sphere.loop(amp, N, points=points)
    area = np.trapezoid(T, t)
    h = 2 * amp / (points - 1)
    T2_max = 0.5 * 3 * MU * N / (4 * t_gs**2) * (1 - amp / t_gs) ** -0.5
    bound = 2 * (2 * amp) * h**2 * T2_max / 12
    W = float(sphere.dissipation(T_amp, N))
    assert abs(area - W) <= bound
    assert bound < 1e-3 * W  # the check is sharp: the bound is a small fraction of W


def test_mindlin_energy_limits(sphere):
    """At gross slip (x = 1) the bracket is 1 - 5/6. For small amplitudes the bracket expands to
    5 x^3 / 162 + O(x^4), so W -> T*^3 / (36 mu N a G*), the small-amplitude result (Johnson 7.60
    with G* for identical bodies); at x = 1e-3 the next term is a relative O(x), rtol = 1e-2."""
    a = float(sphere.contact_radius(N_TOT))
    G_star = sphere.G_star
    pre = 9 * MU**2 * N_TOT**2 / (10 * a * G_star)
    assert float(sphere.dissipation(MU * N_TOT, N_TOT)) == pytest.approx(pre / 6, rel=1e-14)
    assert float(sphere.dissipation(0.0, N_TOT)) == 0.0
    T_small = 1e-3 * MU * N_TOT
    assert float(sphere.dissipation(T_small, N_TOT)) == pytest.approx(
        T_small**3 / (36 * MU * N_TOT * a * G_star), rel=1e-2)


@pytest.mark.parametrize("T_amp, N", [(1e-8 * MU * N_TOT, N_TOT), (5.0, 1e30)])
def test_mindlin_energy_keeps_its_digits_at_small_amplitudes(sphere, T_amp, N):
    """The bracket is 5 x^3 / 162 (1 + 2x/3 + O(x^2)) (its series: c_4 / c_3 = 2/3), so W is the
    small-amplitude limit T*^3 / (36 mu N a G*) to a relative 2x/3: 7e-9 at x = 1e-8, 1e-29 at
    N = 1e30 N. The closed form cancels to noise there (relative error ~ 1e-16 / x^2): rtol 1e-7."""
    a = float(sphere.contact_radius(N))
    limit = T_amp**3 / (36 * MU * N * a * sphere.G_star)
    assert float(sphere.dissipation(T_amp, N)) == pytest.approx(limit, rel=1e-7, abs=0.0)


def test_mindlin_energy_at_an_enormous_load_is_finite():
    """5 N at 1e300 N: x = 1e-299, W about 1e-407 J underflows to 0; it once came out as -inf
    (N^2 overflowed and multiplied the bracket's cancellation noise)."""
    W = float(Sphere.paper().dissipation(5.0, 1e300))
    assert W == 0.0


@pytest.mark.parametrize("x", [0.0999999, 0.1])
def test_mindlin_energy_is_continuous_where_series_and_closed_form_meet(sphere, x):
    """Both sides of x = 0.1 agree to the closed form's own round-off there (~1e-16 / x^2 relative)."""
    T_amp = x * MU * N_TOT
    below = float(sphere.dissipation(T_amp * (1 - 1e-9), N_TOT)) / (1 - 1e-9) ** 3
    assert float(sphere.dissipation(T_amp, N_TOT)) == pytest.approx(below, rel=1e-8, abs=0.0)


# -- Mindlin--Deresiewicz -----------------------------------------------------------------
@pytest.mark.parametrize("T_A_frac, dN", [(0.0, 5.0), (0.4, 5.0), (0.9, 12.5), (1.0, 2.0)])
def test_join_point_and_raised_load_path(sphere, T_A_frac, dN):
    N = 25.0
    T_A = T_A_frac * MU * N
    N2 = N + dN
    t_A = float(sphere.backbone_displacement(T_A, N))
    t_B, T_B = sphere.join_point(N, dN, T_A)
    assert T_B == pytest.approx(T_A + MU * dN, rel=1e-15)
    # B lies on the virgin curve at N + dN
    assert float(sphere.backbone(t_B, N2)) == pytest.approx(T_B, rel=1e-12)
    # continuity at the join: the shifted branch from A, t_A + t_virgin(T - T_A; N + dN), reaches
    # B exactly (with t = c (N^(2/3) - (N - T/mu)^(2/3)) both sides equal c ((N+dN)^(2/3) - (N - T_A/mu)^(2/3)))
    assert float(sphere.raised_load_path(T_B, N, dN, T_A)) == pytest.approx(t_B, rel=1e-12)
    assert t_A + float(sphere.backbone_displacement(MU * dN, N2)) == pytest.approx(t_B, rel=1e-12)
    # beyond the join the path is the virgin curve at N + dN, before A the virgin curve at N
    T_after = np.linspace(T_B, MU * N2, 7)
    np.testing.assert_allclose(sphere.raised_load_path(T_after, N, dN, T_A),
                               sphere.backbone_displacement(T_after, N2), rtol=1e-12)
    T_before = np.linspace(0, T_A, 7)
    np.testing.assert_allclose(sphere.raised_load_path(T_before, N, dN, T_A),
                               sphere.backbone_displacement(T_before, N), rtol=1e-12, atol=1e-20)
    # continuity at A, and the slope just after A is the initial stiffness at N + dN, 8 G* a(N + dN):
    # forward difference with dT = 1e-7 mu (N + dN); the branch's compliance changes by a relative
    # dT / (6 mu (N + dN)) ~ 2e-8 over it, so rtol = 1e-6
    assert float(sphere.raised_load_path(T_A, N, dN, T_A)) == pytest.approx(t_A, rel=1e-15, abs=1e-20)
    dT = 1e-7 * MU * N2
    slope = dT / (float(sphere.raised_load_path(T_A + dT, N, dN, T_A)) - t_A)
    assert slope == pytest.approx(8 * sphere.G_star * float(sphere.contact_radius(N2)), rel=1e-6)
    # the whole path is continuous and increasing
    T = np.linspace(0, MU * N2, 2001)
    path = sphere.raised_load_path(T, N, dN, T_A)
    assert (np.diff(path) > 0).all()
    assert np.abs(np.diff(path)).max() < 0.05 * float(sphere.gross_slip_displacement(N2))


def test_raised_load_path_without_load_step_is_the_virgin_curve(sphere):
    T = np.linspace(0, MU * 20.0, 11)
    np.testing.assert_allclose(sphere.raised_load_path(T, 20.0, 0.0, 3.0),
                               sphere.backbone_displacement(T, 20.0), rtol=1e-12, atol=1e-20)


# -- errors -----------------------------------------------------------------------------------
@pytest.mark.parametrize("change, message", [
    (dict(radius=0.0), "radius must be positive, got 0.0"),
    (dict(radius=np.inf), "radius must be finite, got inf"),
    (dict(E=-1.0), "E must be positive, got -1.0"),
    (dict(nu=0.6), "nu must lie in (-1.0, 0.5], got 0.6"),
    (dict(nu=-1.0), "nu must lie in (-1.0, 0.5], got -1.0"),
    (dict(mu=0.0), "mu must be positive, got 0.0"),
])
def test_constructor_errors(change, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        Sphere(**{**dict(radius=R, E=E, nu=NU, mu=MU), **change})


@pytest.mark.parametrize("method, args, message", [
    ("contact_radius", (-1.0,), "N must be non-negative, got -1.0 at flat index 0"),
    ("approach", ([1.0, -2.0],), "N must be non-negative, got -2.0 at flat index 1"),
    ("normal_stiffness", (np.nan,), "N must be finite, got nan at flat index 0"),
    ("tangential_stiffness", (-1.0,), "N must be non-negative, got -1.0"),
    ("gross_slip_displacement", (-1.0,), "N must be non-negative, got -1.0"),
    ("normal_force", (np.nan,), "n must be finite, got nan at flat index 0"),
    ("backbone", (np.inf, 37.5), "t must be finite, got inf"),
    ("backbone", (1e-6, -1.0), "N must be non-negative, got -1.0"),
    ("backbone_displacement", (16.0, 37.5), "T must satisfy |T| <= mu*N (gross slip); it exceeds it by up to 1 N"),
    ("backbone_displacement", (-16.0, 37.5), "T must satisfy |T| <= mu*N"),
    ("branch", (0.0, -1.0, 0.0, 0.0), "N must be positive, got -1.0"),
    ("branch", (0.0, 37.5, 0.0, np.nan), "T_reversal must be finite, got nan"),
    ("branch", (0.0, 37.5, np.nan, 0.0), "t_reversal must be finite, got nan"),
    ("branch", (0.0, 37.5, 0.0, 16.0), "T_reversal must satisfy |T_reversal| <= mu*N = 15 N (no force beyond "
                                       "gross slip), got 16 N"),
    ("branch", ("abc", 37.5, 0.0, 0.0), "t must be an array of real numbers, got 'abc'"),
    ("backbone", ([0.0, 1e-6, 2e-6], []), "t (shape (3,)) and N (shape (0,)) must have shapes that broadcast"),
    ("backbone_displacement", ([1.0, 2.0], [1.0, 2.0, 3.0]), "T (shape (2,)) and N (shape (3,)) must have"),
    ("normal_force", (1e300,), "n is too large"),
    ("loop", (0.0, 37.5), "amplitude must be positive, got 0.0"),
    ("loop", (1e-6, 0.0), "N must be positive, got 0.0"),
    ("loop", (1e-6, 37.5, 2), "points must be an integer >= 3, got 2"),
    ("loop", (1e-6, 37.5, 10.5), "points must be an integer, got 10.5"),
    ("loop", (1e-6, 37.5, 10**12), "points must be at most 10000000 (a size: larger ones would need gigabytes)"),
    ("dissipation", (16.0, 37.5), "T_amplitude must not exceed mu*N (the gross-slip force); "
                                  "got T_amplitude/(mu N) up to 1.06667"),
    ("dissipation", (-1.0, 37.5), "T_amplitude must be non-negative, got -1.0"),
    ("dissipation", (1.0, 0.0), "N must be positive, got 0.0"),
    ("raised_load_path", (1.0, 37.5, -1.0, 1.0), "dN must be non-negative, got -1.0"),
    ("raised_load_path", (1.0, 37.5, 1.0, 16.0), "T_A must not exceed mu*N = 15 N, got 16 N"),
    ("raised_load_path", (-1.0, 37.5, 5.0, 1.0), "T must lie in [0, mu*(N+dN)] = [0, 17] N, got -1 N"),
    ("raised_load_path", ([1.0, 18.0], 37.5, 5.0, 1.0), "T must lie in [0, mu*(N+dN)] = [0, 17] N, got 18 N"),
    ("join_point", (0.0, 1.0, 1.0), "N must be positive, got 0.0"),
    ("join_point", (37.5, 1.0, -1.0), "T_A must be non-negative, got -1.0"),
    ("join_point", (37.5, np.nan, 1.0), "dN must be finite, got nan"),
])
def test_method_errors(sphere, method, args, message):
    with pytest.raises((ValueError, TypeError), match=re.escape(message)):
        getattr(sphere, method)(*args)
