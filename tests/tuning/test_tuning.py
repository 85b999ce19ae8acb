"""The paper's tuning (eqs. 1-9): exact pass-through, the closed form for a sphere, errors."""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy import optimize

from microslip import ContactReference, MicroslipModel, Sphere, TuningError, tune, tuning_points
from microslip.tuning import model_from_points, normal_parameters, tangential_stiffnesses

N_TOT = 37.5


@pytest.fixture(scope="module")
def sphere():
    return Sphere.paper()


class NormalLawReference:
    """The paper's sphere in the tangential direction, with another normal force--approach law."""

    def __init__(self, law):
        self._sphere = Sphere.paper()
        self.mu = self._sphere.mu
        self._law = law

    def backbone(self, t, N):
        return self._sphere.backbone(t, N)

    def backbone_displacement(self, T, N):
        return self._sphere.backbone_displacement(T, N)

    def gross_slip_displacement(self, N):
        return self._sphere.gross_slip_displacement(N)

    def normal_force(self, n):
        return self._law(np.asarray(n, dtype=float))

    def approach(self, N):
        return optimize.brentq(lambda n: float(self._law(n)) - float(N), 0.0, 1e-4, xtol=1e-22, rtol=1e-15)


def hertz_then_power(frac, p):
    """Hertz up to n1 = frac * n_tot, then N1 + A (n - n1)^p through (n_tot, N_TOT): for p < 1
    the curve turns concave with an infinite slope just past n1 (a saturating contact)."""
    sphere = Sphere.paper()
    n_tot = float(sphere.approach(N_TOT))
    n1 = frac * n_tot
    N1 = float(sphere.normal_force(n1))
    A = (N_TOT - N1) / (n_tot - n1) ** p
    return NormalLawReference(
        lambda n: np.where(n <= n1, sphere.normal_force(n), N1 + A * np.maximum(n - n1, 0.0) ** p))


def choices(sphere):
    t_gs = float(sphere.gross_slip_displacement(N_TOT))
    return [
        dict(elements=4),
        dict(elements=1),
        dict(elements=12),
        dict(forces=[2.0, 6.0, 9.5, 13.0, 0.4 * N_TOT]),
        dict(displacements=[0.05 * t_gs, 0.3 * t_gs, 0.7 * t_gs, t_gs]),
    ]


def check_pass_through(reference, model, pts):
    n_tot = pts.approach
    # tangential: the array's backbone at n_tot goes through every tuning point (the element
    # slipping at s_e carries kt_e s_e = mu N_e(n_tot) by eqs. (5)-(8)); rounding only
    np.testing.assert_allclose(model.backbone(pts.t, n_tot), pts.T, rtol=1e-12)
    # normal: through (n_tot, N_tot) and, by eq. (9), through (gaps_j, N_ref(gaps_j)) for j >= 2;
    # the gaps are roots found to xtol = 1e-15 n_tot, so the force error is slope * 1e-15 n_tot,
    # below 1e-12 N_tot
    assert float(model.normal_force(n_tot)) == pytest.approx(pts.normal_load, rel=1e-12)
    g = model.gaps[1:]
    np.testing.assert_allclose(model.normal_force(g), reference.normal_force(g), rtol=0,
                               atol=1e-12 * pts.normal_load)


def test_tuned_curves_pass_through_the_chosen_points(sphere):
    for choice in choices(sphere):
        model = tune(sphere, N_TOT, **choice)
        pts = tuning_points(sphere, N_TOT, **choice)
        assert model.elements == pts.t.size
        check_pass_through(sphere, model, pts)
        assert model.gaps[0] == 0.0 and (np.diff(model.gaps) > 0).all()
        assert model.mu == sphere.mu


def test_points_from_forces_displacements_and_elements(sphere):
    t_gs = float(sphere.gross_slip_displacement(N_TOT))
    by_elements = tuning_points(sphere, N_TOT, elements=4)
    np.testing.assert_allclose(by_elements.T, [3.75, 7.5, 11.25, 15.0], rtol=1e-15)  # T_j = j mu N / J
    assert by_elements.t[-1] == t_gs
    by_forces = tuning_points(sphere, N_TOT, forces=[3.75, 7.5, 11.25, 15.0])
    np.testing.assert_array_equal(by_forces.t, by_elements.t)
    by_disp = tuning_points(sphere, N_TOT, displacements=by_elements.t)
    np.testing.assert_allclose(by_disp.T, by_elements.T, rtol=1e-12)
    assert by_disp.T[-1] == 0.4 * N_TOT
    assert by_disp.approach == float(sphere.approach(N_TOT))


def test_closed_form_for_hertz_and_cattaneo_mindlin(sphere):
    """DESIGN.md section 2 (method of dimensionality reduction): kn_i = kt_i E*/G*_P with
    G*_P = 4 G*, and gaps_i = n_tot - G*_P/(mu E*) s_i, s_i the slip displacement of element i.
    The generic solver finds the gaps as roots to xtol = 1e-15 n_tot, so they agree to ~1e-14 n_tot;
    rtol 1e-10 on kn and atol 1e-12 n_tot on the gaps leave a margin for the optimiser."""
    E_star = sphere.E / (2 * (1 - sphere.nu**2))
    G_star_P = 4 * (sphere.E / (2 * (1 + sphere.nu))) / (2 * (2 - sphere.nu))
    n_tot = float(sphere.approach(N_TOT))
    for choice in choices(sphere):
        model = tune(sphere, N_TOT, **choice)
        s = tuning_points(sphere, N_TOT, **choice).t[::-1]
        np.testing.assert_allclose(model.kn, model.kt * E_star / G_star_P, rtol=1e-10)
        np.testing.assert_allclose(model.gaps, n_tot - G_star_P / (sphere.mu * E_star) * s, rtol=0,
                                   atol=1e-12 * n_tot)


def test_shares_sum_to_one(sphere):
    """Eq. (5): alpha_e = kt_e s_e / (mu N_tot); the last row of eq. (2) makes them sum to 1, and
    at n_tot each element carries alpha_e N_tot."""
    for choice in choices(sphere):
        model = tune(sphere, N_TOT, **choice)
        pts = tuning_points(sphere, N_TOT, **choice)
        alpha = model.kt * pts.t[::-1] / (sphere.mu * N_TOT)
        assert alpha.sum() == pytest.approx(1.0, rel=1e-13)
        np.testing.assert_allclose(model.element_normal_forces(pts.approach) / N_TOT, alpha, rtol=1e-12)


def test_corrected_eq2_by_hand():
    """Points (1, 3, 4 m; 4, 6, 6.5 N): slopes 4, 1, 0.5, drops 3, 0.5, 0.5. Element 1 slips last
    (at 4 m) with kt = 0.5, element 3 first (at 1 m) with kt = 3; row j of eq. (2):
    T_j = sum_e kt_e min(t_j, s_e)."""
    kt = tangential_stiffnesses([1.0, 3.0, 4.0], [4.0, 6.0, 6.5])
    np.testing.assert_allclose(kt, [0.5, 0.5, 3.0], rtol=1e-15)
    s = np.array([4.0, 3.0, 1.0])
    for tj, Tj in zip([1.0, 3.0, 4.0], [4.0, 6.0, 6.5]):
        assert np.sum(kt * np.minimum(tj, s)) == pytest.approx(Tj, rel=1e-15)


def test_sphere_is_a_contact_reference(sphere):
    assert isinstance(sphere, ContactReference)
    assert isinstance(NormalLawReference(lambda n: n), ContactReference)


def test_non_convex_normal_curve_is_solved(sphere):
    """Hertz, then a concave law from 0.65 n_tot on: the residual of eq. (9) is no longer concave
    and the bounded search for its maximum alone misses its positive part; the tuning must still
    find the root and pass through the points."""
    reference = hertz_then_power(0.65, 0.6)
    model = tune(reference, N_TOT, elements=4)
    check_pass_through(reference, model, tuning_points(reference, N_TOT, elements=4))
    # the first three elements see only the Hertz part: same as the sphere's
    hertz = tune(sphere, N_TOT, elements=4)
    np.testing.assert_allclose(model.gaps[:3], hertz.gaps[:3], rtol=1e-9)


# -- errors ---------------------------------------------------------------------------------
def test_points_not_strictly_increasing(sphere):
    with pytest.raises(ValueError, match=re.escape(
            "forces must be strictly increasing: point 3 (5 N) does not exceed point 2 (5 N)")):
        tune(sphere, N_TOT, forces=[2.0, 5.0, 5.0, 15.0])
    with pytest.raises(ValueError, match=re.escape(
            "displacements must be strictly increasing: point 2 (4e-07 m) does not exceed point 1 (5e-07 m)")):
        tune(sphere, N_TOT, displacements=[5e-7, 4e-7, float(sphere.gross_slip_displacement(N_TOT))])


def test_last_point_not_at_gross_slip(sphere):
    with pytest.raises(ValueError, match=re.escape(
            "forces: the last point must be at gross slip, mu*normal_load = 15 N, got 14 N")):
        tune(sphere, N_TOT, forces=[5.0, 10.0, 14.0])
    with pytest.raises(ValueError, match=re.escape(
            "displacements: the last point must be at gross slip, t_gs = 1.14502e-06 m at normal_load = 37.5 N, "
            "got 1e-06 m")):
        tune(sphere, N_TOT, displacements=[0.5e-6, 1e-6])


@pytest.mark.parametrize("call, exc, message", [
    (lambda s: tune(s, N_TOT, elements=10**12), ValueError, "elements must be at most 10000000"),
    (lambda s: model_from_points("sphere", tuning_points(s, N_TOT, elements=2)), TypeError,
     "reference must provide mu, backbone"),
    (lambda s: normal_parameters(s, [1e7, np.nan], [2e-7, 1e-7], N_TOT), ValueError, "kt must be finite"),
    (lambda s: normal_parameters(s, [1e7, 1e7], [2e-7], N_TOT), ValueError,
     r"slip_displacements must have one value per element of kt \(2\), got 1"),
    (lambda s: normal_parameters(s, [1e7, 1e7], [2e-7, 1e-7], 0.0), ValueError, "normal_load must be positive"),
    (lambda s: normal_parameters(s, [1e300, 1e300], [2e-7, 1e-7], N_TOT), TuningError,
     r"kt, slip_displacements and normal_load = 37.5 N: eq. \(9\) has no solution for element 2"),
])
def test_bad_arguments_are_named(sphere, call, exc, message):
    with pytest.raises(exc, match=message):
        call(sphere)


def test_points_not_concave_name_the_point():
    with pytest.raises(TuningError, match=re.escape(
            "the tuning points are not concave at point 2 (t = 2 m, T = 5 N): the slope before it (2 N/m) "
            "does not exceed the slope after it (3 N/m), so the element that slips there would get a "
            "stiffness of -1 N/m <= 0")):
        # slopes 3, 2, 3, 1: the drop at point 2 is 2 - 3 = -1
        tangential_stiffnesses([1.0, 2.0, 3.0, 4.0], [3.0, 5.0, 8.0, 9.0])


def test_linear_backbone_gives_zero_stiffness_through_tune():
    """A reference whose backbone is straight up to gross slip: evenly spaced force points are
    collinear, so the element slipping at the first point would get kt = 0."""

    class Linear(NormalLawReference):
        k = 1e7

        def backbone(self, t, N):
            return np.minimum(self.k * np.asarray(t, dtype=float), self.mu * np.asarray(N, dtype=float))

        def backbone_displacement(self, T, N):
            return np.asarray(T, dtype=float) / self.k

        def gross_slip_displacement(self, N):
            return self.mu * N / self.k

    reference = Linear(Sphere.paper().normal_force)
    with pytest.raises(TuningError, match=r"not concave at point 1 \(t = 3\.75e-07 m, T = 3\.75 N\).*"
                                          r"stiffness of 0 N/m <= 0"):
        tune(reference, N_TOT, elements=4)


def test_eq9_without_solution_names_the_element_and_the_condition():
    # a saturating contact, N ~ sqrt(n): infinitely stiff at first touch, so element 2 never
    # meets the reference again
    n_tot = float(Sphere.paper().approach(N_TOT))
    root = NormalLawReference(lambda n: N_TOT * np.sqrt(np.maximum(n, 0.0) / n_tot))
    with pytest.raises(TuningError, match=r"eq\. \(9\) has no solution for element 2: the normal stiffness "
                                          r"of elements 1\.\.1 \(sum [0-9.e+]+ N/m\) must exceed the slope of "
                                          r"the reference normal curve where element 1 touches"):
        tune(root, N_TOT, elements=4)
    # Hertz, then saturating from 0.45 n_tot: elements 1..3 are found, element 4 is not
    with pytest.raises(TuningError, match=r"no solution for element 4: the normal stiffness of elements "
                                          r"1\.\.3 .* where element 3 touches \(about [0-9.e+]+ N/m at "
                                          r"n = 1\.06\d*e-06 m\)"):
        tune(hertz_then_power(0.45, 0.6), N_TOT, elements=4)


def test_reference_lacking_methods():
    with pytest.raises(TypeError, match=re.escape(
            "reference must provide mu, backbone, backbone_displacement, gross_slip_displacement, approach, "
            "normal_force (see microslip.tuning.ContactReference); got object")):
        tune(object(), N_TOT, elements=4)

    class HalfReference:
        mu = 0.4

        def backbone(self, t, N):
            return t

    with pytest.raises(TypeError, match=re.escape(
            "reference must provide backbone_displacement, gross_slip_displacement, approach, normal_force")):
        tune(HalfReference(), N_TOT, elements=4)


@pytest.mark.parametrize("kwargs, got", [
    (dict(), "none"),
    (dict(elements=4, forces=[15.0]), "forces, elements"),
    (dict(forces=[15.0], displacements=[1e-6]), "forces, displacements"),
])
def test_exactly_one_of_forces_displacements_elements(sphere, kwargs, got):
    with pytest.raises(ValueError, match=re.escape(
            f"give exactly one of forces=, displacements= or elements= (got {got})")):
        tune(sphere, N_TOT, **kwargs)


@pytest.mark.parametrize("args, kwargs, error, message", [
    ((0.0,), dict(elements=4), ValueError, "normal_load must be positive, got 0.0"),
    ((N_TOT,), dict(elements=0), ValueError, "elements must be an integer >= 1, got 0"),
    ((N_TOT,), dict(elements=2.5), TypeError, "elements must be an integer, got 2.5"),
    ((N_TOT,), dict(forces=[-1.0, 15.0]), ValueError, "forces must be positive, got -1.0 at flat index 0"),
    ((N_TOT,), dict(forces=[[15.0]]), ValueError, "forces must be 1-D, got shape (1, 1)"),
    ((N_TOT,), dict(displacements=[np.nan]), ValueError, "displacements must be finite, got nan"),
])
def test_other_argument_errors(sphere, args, kwargs, error, message):
    with pytest.raises(error, match=re.escape(message)):
        tune(sphere, *args, **kwargs)


def test_tangential_stiffnesses_length_mismatch():
    with pytest.raises(ValueError, match=re.escape("t and T must have the same length, got 2 and 3")):
        tangential_stiffnesses([1.0, 2.0], [1.0, 2.0, 3.0])


def test_normal_parameters_reproduce_tune(sphere):
    pts = tuning_points(sphere, N_TOT, elements=5)
    kt = tangential_stiffnesses(pts.t, pts.T)
    kn, gaps = normal_parameters(sphere, kt, pts.t[::-1], N_TOT)
    assert MicroslipModel(kt, kn, gaps, sphere.mu) == tune(sphere, N_TOT, elements=5)
