"""Harmonic balance: input checks, step control settings, incomplete curves, the static state of the contacts."""

import sys
import warnings

import numpy as np
import pytest

from microslip import MicroslipModel, Sphere, tune
from microslip.frequency import (HarmonicBalance, IncompleteCurveWarning, StepControl, Structure, frequency_point,
                                 frequency_response, static_solution)

from _paths import EXAMPLES

sys.path.insert(0, str(EXAMPLES))
from blade_damper import NORMAL_LOAD, blade_with_damper  # noqa: E402  (the example is the test case)

JENKINS = MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0)  # slip force 1 N at an approach of 1 µm
SPHERE = tune(Sphere.paper(), 37.5, elements=4)


def jenkins_oscillator():
    s = Structure(M=[[1.0]], C=[[1.0]], K=[[1e4]])
    s.add_contact(JENKINS, tangential=0, approach=1e-6)
    return s


# -- HarmonicBalance.evaluate -----------------------------------------------------------------------

@pytest.mark.parametrize("x, omega, error, message", [
    (np.zeros(3), 100.0, ValueError, "x must be a vector of the n = \\(2H\\+1\\) ndof = 7 unknowns .* got shape \\(3,\\)"),
    (np.zeros((7, 1)), 100.0, ValueError, "got shape \\(7, 1\\)"),
    (np.full(7, np.nan), 100.0, ValueError, "x must be finite"),
    (np.zeros(7), -1.0, ValueError, "omega must be positive, got -1.0"),
    (np.zeros(7), np.inf, ValueError, "omega must be finite"),
    (np.zeros(7), "fast", TypeError, "omega must be a real number, got 'fast'"),
])
def test_evaluate_checks_x_and_omega(x, omega, error, message):
    # a length-3 x for n = 7 used to reach the compiled kernel unchecked and return garbage
    hb = HarmonicBalance(jenkins_oscillator(), [2.0], 3, samples=32)
    for evaluate in (hb.evaluate, hb.evaluate_reference):
        with pytest.raises(error, match=message):
            evaluate(x, omega)


def test_evaluate_accepts_lists_and_matches_the_reference():
    hb = HarmonicBalance(jenkins_oscillator(), [2.0], 3, samples=32)
    x = [0.0, 1e-4, 0.0, 0.0, 0.0, 0.0, 0.0]
    R, J, Rw = hb.evaluate(x, 100.0)
    R2, J2, Rw2 = hb.evaluate_reference(np.array(x), 100.0)
    np.testing.assert_allclose(R, R2, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(J, J2, rtol=1e-12, atol=1e-9)


# -- StepControl ------------------------------------------------------------------------------------

@pytest.mark.parametrize("kwargs, error, message", [
    (dict(max_angle="big"), TypeError, "max_angle must be a real number, got 'big'"),
    (dict(ds_initial=-0.01), ValueError, "ds_initial must be positive, got -0.01"),
    (dict(ds_min=0.0), ValueError, "ds_min must be positive, got 0.0"),
    (dict(ds_max=np.nan), ValueError, "ds_max must be finite"),
    (dict(tolerance=-1e-9), ValueError, "tolerance must be positive, got -1e-09"),
    (dict(tolerance=2.0), ValueError, "tolerance must be below 1 \\(a relative residual\\), got 2.0"),
    (dict(max_angle=4.0), ValueError, "max_angle must be below pi \\(rad\\), got 4.0"),
    (dict(target_iterations=0), ValueError, "target_iterations must be an integer >= 1, got 0"),
    (dict(max_iterations=2.5), TypeError, "max_iterations must be an integer, got 2.5"),
    (dict(max_points=1), ValueError, "max_points must be an integer >= 2, got 1"),
    (dict(ds_min=0.1, ds_max=0.01), ValueError, "ds_min must not exceed ds_max, got ds_min = 0.1 > ds_max = 0.01"),
])
def test_step_control_checks_each_field(kwargs, error, message):
    with pytest.raises(error, match=message):
        StepControl(**kwargs)


def test_first_step_is_clipped_to_ds_max():
    lo, hi = 60.0, 160.0
    r = frequency_response(jenkins_oscillator(), [2.0], (lo, hi), harmonics=1,
                           control=StepControl(ds_initial=0.5, ds_max=0.01))
    # the scaled step (frequency over the range, displacement over its scale) is at most ds_max,
    # so its frequency part is too (up to the corrector moving along the hyperplane: 1 %)
    assert (r.omega[1] - r.omega[0]) / (hi - lo) <= 0.01 * 1.01


# -- incomplete curves ------------------------------------------------------------------------------

def test_curve_stopped_by_max_points_is_flagged_and_warned():
    with pytest.warns(IncompleteCurveWarning, match="the continuation stopped at max_points = 6 points at omega = "
                                                    "[0-9.]+ rad/s, before the end of the range \\(160 rad/s\\)"):
        r = frequency_response(jenkins_oscillator(), [2.0], (60.0, 160.0), harmonics=1,
                               control=StepControl(max_points=6))
    assert r.points == 6 and not r.complete and r.omega[-1] < 160.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a complete curve does not warn
        full = frequency_response(jenkins_oscillator(), [2.0], (60.0, 160.0), harmonics=1)
    assert full.complete and full.omega[-1] == 160.0
    assert frequency_point(jenkins_oscillator(), [2.0], 100.0, harmonics=1).complete


# -- the static state of the contacts -----------------------------------------------------------------

def test_static_normal_force_of_a_preload_shared_with_the_structure():
    """A preload is a force on the structure: a spring along the normal takes ``k n0`` of it."""
    k = 1e7
    s = Structure(np.eye(2), None, np.diag([1e6, k]))
    s.add_contact(SPHERE, tangential=0, normal=1, preload=37.5)
    r = frequency_point(s, [1.0, 0.0], 900.0, harmonics=1)
    N0, T0 = r.static_normal_force[0], r.static_tangential_force[0]
    n0 = float(SPHERE.approach(N0))  # approach at which the tuned contact carries N0
    assert N0 + k * n0 == pytest.approx(37.5, rel=1e-9)  # statics of the normal DOF
    assert 15.0 < N0 < 25.0  # well below the preload: the spring takes the rest
    assert T0 == 0.0  # nothing pushes tangentially
    assert r.static_closed_elements[0] == int(np.count_nonzero(SPHERE.gaps < n0)) == 3
    # the same contact on a normal DOF with no spring carries the whole preload, every element closed
    free = Structure(np.eye(2), None, np.diag([1e6, 0.0]))
    free.add_contact(SPHERE, tangential=0, normal=1, preload=37.5)
    r = frequency_point(free, [1.0, 0.0], 900.0, harmonics=1)
    assert r.static_normal_force[0] == pytest.approx(37.5, rel=1e-9)
    assert r.static_closed_elements[0] == 4


def test_static_tangential_force_of_an_inclined_preload():
    """A preload along a direction that also moves ``t``: the static tangential force is ``kt t0`` while stuck."""
    s = Structure([[1.0]], None, [[1e8]])  # stiff: the contact stays stuck
    s.add_contact(JENKINS, tangential=[0.2], normal=[1.0], preload=50.0)
    r = frequency_point(s, [0.1], 500.0, harmonics=1)
    q0 = r.coefficients[0, 0, 0]
    # statics: K q0 + 0.2 T0 + N0 = 50 with T0 = kt 0.2 q0 and N0 = kn (q0 - 0) (stuck, closed)
    assert q0 == pytest.approx(50.0 / (1e8 + 1e4 * 0.04 + 1e6), rel=1e-9)
    assert r.static_tangential_force[0] == pytest.approx(1e4 * 0.2 * q0, rel=1e-9)
    assert r.static_normal_force[0] == pytest.approx(1e6 * q0, rel=1e-9)


def test_blade_example_damper_carries_its_load_stuck_with_every_element_closed():
    blade = blade_with_damper()
    r = frequency_point(blade, [0.0, 1.0], 8000.0, harmonics=1)
    assert r.static_normal_force[0] == pytest.approx(NORMAL_LOAD, rel=1e-12)
    assert r.static_tangential_force[0] == 0.0
    assert r.static_closed_elements[0] == 4
    assert blade_with_damper(elements=16).contacts[0].model.elements == 16


def test_static_solution_takes_a_force_vector():
    s = Structure([[1.0]], None, [[2e4]])
    np.testing.assert_allclose(static_solution(s, [0.5]), [0.5 / 2e4], rtol=1e-12)  # was 0: the vector ignored
    np.testing.assert_allclose(static_solution(s, {0: [0.5], 1: [3.0]}), [0.5 / 2e4], rtol=1e-12)
    with pytest.raises(ValueError, match="force"):
        static_solution(s, [np.nan])
    with pytest.raises((ValueError, TypeError), match="force"):
        static_solution(s, "abc")


@pytest.mark.parametrize("force, error, message", [
    ("abc", TypeError, "^force must be an array of real numbers, got 'abc'$"),  # was force[0] and an array repr
    ([1j], TypeError, "force \\(a static force\\) must be real, got \\[1j\\]"),
    ({"a": [1.0]}, TypeError, "force: harmonic keys must be integers, got 'a'"),  # was ignored: zero displacement
    ({1: "x"}, TypeError, "force\\[1\\] must be an array of real numbers, got 'x'"),  # an unused harmonic, checked
    ({-1: [1.0]}, ValueError, "force: harmonic -1 is outside"),
    ({0: [1.0, 2.0]}, ValueError, "force\\[0\\] must have one entry per DOF \\(1\\), got 2"),
])
def test_static_solution_names_a_bad_force(force, error, message):
    s = Structure([[1.0]], None, [[2e4]])
    with pytest.raises(error, match=message):
        static_solution(s, force)


def test_a_dof_held_only_by_friction_is_named_with_the_fix():
    # a free mass on a Jenkins contact: its mean position is undetermined (it used to end in "did not converge
    # (relative residual 1.3e-11 after 50 iterations)" or "continuation stalled")
    s = Structure([[1.0]], [[1.0]], [[0.0]])
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential=0, approach=1e-6)
    message = ("structure: the motion of DOF\\(s\\) \\[0\\] has no stiffness from K or from the contacts' normal "
               "springs, so it is held only by the friction of a contact: its mean position is undetermined")
    with pytest.raises(ValueError, match=message):
        frequency_response(s, [2.0], (60.0, 160.0), harmonics=3)
    with pytest.raises(ValueError, match="Ground it with a spring"):
        static_solution(s)
    grounded = Structure([[1.0]], [[1.0]], [[1e-3]])  # a spring 1e7 times softer than the contact is enough
    grounded.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential=0, approach=1e-6)
    assert frequency_point(grounded, [2.0], 100.0, harmonics=3).points == 1


def test_a_large_sparse_structure_is_checked_by_a_sparse_factorisation_and_still_named():
    import scipy.sparse as sp

    from microslip.frequency.analyses import response

    n = 400  # above SPARSE_CHECK: the shift-invert check runs first
    chain = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1], format="lil") * 1e6
    model = MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0)
    grounded = Structure(sp.identity(n, format="csr") * 0.01, None, chain.tocsr())
    grounded.add_contact(model, tangential=n - 1, approach=1e-6)
    assert response._surely_determined(grounded)  # no dense eigensolution for a well-held structure
    chain[n - 1, :] = 0.0  # the last DOF loses its springs: only the contact's friction holds it
    chain[:, n - 1] = 0.0
    loose = Structure(sp.identity(n, format="csr") * 0.01, None, chain.tocsr())
    loose.add_contact(model, tangential=n - 1, approach=1e-6)
    assert not response._surely_determined(loose)
    with pytest.raises(ValueError, match=r"the motion of DOF\(s\) \[399\] has no stiffness .* held only by the "
                                         r"friction of a contact"):
        static_solution(loose)


def test_cycle_work_checks_its_coefficients():
    from microslip.frequency import cycle_work

    with pytest.raises(ValueError, match="force and displacement must have the same shape"):
        cycle_work(np.ones(5), np.ones(3))
    with pytest.raises(ValueError, match="2H\\+1"):
        cycle_work(np.ones(4), np.ones(4))
    with pytest.raises(ValueError, match="force"):
        cycle_work([np.nan, 0, 0], [0, 0, 0])
