"""Harmonic balance on the contact DOFs (reduction='exact' / 'modal') and Craig-Bampton, against the full solve."""

import numpy as np
import pytest
import scipy.sparse as sp

from microslip import MicroslipModel, Sphere, tune
from microslip.frequency import (CraigBampton, Structure, craig_bampton, frequency_point, frequency_response,
                                 static_solution)

SPHERE = Sphere.paper()
MODEL = tune(SPHERE, 37.5, elements=4)
N = 30  # DOFs per chain


def two_chains(grounded_normal: bool = True, sparse: bool = True) -> Structure:
    """A tangential chain (DOFs 0..N-1, grounded at DOF 0) and a normal chain (N..2N-1) pressed into a contact.

    Contact 0 joins the ends: tangential DOF N-1, normal DOF 2N-1, preloaded with 40 N. Contact 1 sits
    between two DOFs of the tangential chain with an imposed approach (normal load 20 N). With
    ``grounded_normal=False`` the normal chain is a free body held only by the contact's normal stiffness.
    """
    k, m = 2e6, 0.02
    n = 2 * N
    K = sp.lil_matrix((n, n))
    for a in (0, N):
        for i in range(N - 1):
            K[a + i, a + i] += k
            K[a + i + 1, a + i + 1] += k
            K[a + i, a + i + 1] -= k
            K[a + i + 1, a + i] -= k
    K[0, 0] += k
    if grounded_normal:
        K[N, N] += k
    K = K.tocsr()
    M = sp.identity(n, format="csr") * m
    C = 2e-6 * K + 5.0 * M
    if not sparse:
        M, C, K = M.toarray(), C.toarray(), K.toarray()
    s = Structure(M, C, K)
    s.add_contact(MODEL, tangential=N - 1, normal=2 * N - 1, preload=40.0)
    s.add_contact(MODEL, tangential={N // 2: 1.0, N // 2 - 1: -1.0}, approach=SPHERE.approach(20.0))
    return s


def forcing(amplitude=20.0):
    f = np.zeros(2 * N)
    f[N - 1] = amplitude
    f[2 * N - 1] = 0.3 * amplitude  # the normal load breathes too
    return f


FREQUENCIES = (600.0, 900.0, 1100.0, 1300.0, 1700.0)  # rad/s, across the first stuck and sliding resonances


@pytest.fixture(scope="module")
def full_points():
    s = two_chains()
    return {w: frequency_point(s, forcing(), w, harmonics=3, reduction="none") for w in FREQUENCIES}


@pytest.mark.parametrize("omega", FREQUENCIES)
def test_exact_condensation_equals_the_full_solve(full_points, omega):
    full = full_points[omega]
    red = frequency_point(two_chains(), forcing(), omega, harmonics=3, reduction="exact")
    assert red.reduction == "exact" and red.dofs.size < 2 * N
    scale = np.max(np.abs(full.coefficients))
    # Newton stops at a relative residual of 1e-9 on both: the solutions agree to that order
    assert np.max(np.abs(full.coefficients[0][:, red.dofs] - red.coefficients[0])) < 1e-7 * scale
    for dof in (3, N + 5, 2 * N - 1):  # interior DOFs recovered on demand, and a retained one
        np.testing.assert_allclose(red.dof_coefficients(dof), full.dof_coefficients(dof), rtol=0, atol=1e-7 * scale)
    np.testing.assert_allclose(red.contact_dissipation, full.contact_dissipation, rtol=1e-6)
    np.testing.assert_allclose(red.viscous_dissipation, full.viscous_dissipation, rtol=1e-6)


def test_static_solution_on_the_retained_dofs_equals_the_full_one():
    s = two_chains()
    full = static_solution(s, reduction="none")
    for reduction in ("exact", "modal"):
        np.testing.assert_allclose(static_solution(s, reduction=reduction), full, rtol=0,
                                   atol=1e-9 * np.max(np.abs(full)))


def test_modal_error_falls_with_the_modes_and_the_estimate_follows_it(full_points):
    full = full_points[1100.0]
    s = two_chains()
    errors, estimates = [], []
    for modes in (2, 6, 12, 24):
        r = frequency_point(s, forcing(), 1100.0, harmonics=3, reduction="modal", modes=modes)
        assert r.reduction == "modal" and r.modes == modes
        errors.append(np.max(np.abs(r.coefficients[0] - full.coefficients[0][:, r.dofs]))
                      / np.max(np.abs(full.coefficients[0])))
        estimates.append(r.reduction_error)
    assert all(b < a for a, b in zip(errors, errors[1:])), errors
    assert all(b < a for a, b in zip(estimates, estimates[1:])), estimates
    assert errors[-1] < 1e-3  # measured 6.7e-4 with 24 of 60 modes (those above 3 x 1100 rad/s enter quasi-statically)


def test_a_free_body_held_by_its_contact_works_with_every_reduction():
    s = two_chains(grounded_normal=False)
    f = forcing()
    ref = frequency_point(s, f, 1100.0, harmonics=3, reduction="none")
    scale = np.max(np.abs(ref.coefficients))
    # modal: measured 6.1e-4 with 24 of 60 modes (as on the grounded chains)
    for reduction, modes, tol in (("exact", None, 1e-7), ("modal", 24, 1e-3)):
        r = frequency_point(s, f, 1100.0, harmonics=3, reduction=reduction, modes=modes)
        assert np.max(np.abs(r.coefficients[0] - ref.coefficients[0][:, r.dofs])) < tol * scale


def test_every_point_of_a_curve_with_exact_condensation_is_a_point_of_the_full_solve():
    s = two_chains()
    red = frequency_response(s, forcing(), (700.0, 1500.0), harmonics=3, reduction="exact")
    assert red.complete and red.reduction == "exact"
    # the curves' points fall at other frequencies (the step control sees other unknowns), so each
    # sampled point of the reduced curve is compared with the full solve at its own frequency
    for k in np.linspace(0, red.points - 1, 6).astype(int):
        full = frequency_point(s, forcing(), float(red.omega[k]), harmonics=3, reduction="none")
        scale = np.max(np.abs(full.coefficients))
        assert np.max(np.abs(red.coefficients[k] - full.coefficients[0][:, red.dofs])) < 1e-7 * scale
        np.testing.assert_allclose(red.dof_coefficients(N // 3)[k], full.dof_coefficients(N // 3)[0], rtol=0,
                                   atol=1e-7 * scale)


def test_auto_chooses_by_size_and_says_so():
    small = Structure(np.eye(2), 0.1 * np.eye(2), [[2e4, -1e4], [-1e4, 1e4]])
    small.add_contact(MicroslipModel([1e4], [1e6], [0.0], 0.5), tangential=1, approach=2e-6)
    assert frequency_point(small, [0.0, 1.0], 100.0, harmonics=3).reduction == "none"
    assert frequency_point(two_chains(), forcing(), 1100.0, harmonics=7).reduction == "exact"
    assert frequency_point(two_chains(), forcing(), 1100.0, harmonics=3, modes=10).reduction == "modal"


@pytest.mark.parametrize("kwargs, message", [
    ({"reduction": "fast"}, "reduction must be one of 'auto', 'none', 'exact', 'modal', got 'fast'"),
    ({"reduction": "exact", "modes": 5}, "modes is used only with reduction='modal'"),
    ({"reduction": "modal", "modes": 60}, "modes must be below the number of DOFs (60), got 60"),
    ({"reduction": "modal", "modes": 0}, "modes must be"),
])
def test_reduction_arguments_are_checked(kwargs, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        frequency_point(two_chains(), forcing(), 1100.0, harmonics=3, **kwargs)


def test_craig_bampton_keeps_the_response_and_round_trips_through_a_file(tmp_path, full_points):
    s = two_chains()
    keep = [N - 1, N // 2, N // 2 - 1, 2 * N - 1]
    cb = craig_bampton(s, keep, modes=2 * N - len(keep) - 1)  # all but one mode: close to exact
    assert cb.structure.ndof == 2 * N - 1 and len(cb.structure.contacts) == 2
    f = np.zeros(cb.structure.ndof)
    f[0], f[3] = 20.0, 6.0  # the same excitation on the kept DOFs N-1 and 2N-1
    r = frequency_point(cb.structure, f, 1100.0, harmonics=3, reduction="none")
    q = cb.expand(r.coefficients[0])
    full = full_points[1100.0].coefficients[0]
    assert np.max(np.abs(q - full)) < 1e-3 * np.max(np.abs(full))
    path = cb.save(tmp_path / "blade.npz")
    back = CraigBampton.load(path)
    for a, b in ((back.structure.M, cb.structure.M), (back.structure.K, cb.structure.K), (back.recovery, cb.recovery)):
        np.testing.assert_array_equal(a, b)
    again = frequency_point(back.structure, f, 1100.0, harmonics=3, reduction="none")
    np.testing.assert_array_equal(again.coefficients, r.coefficients)


def test_craig_bampton_converges_with_the_modes(full_points):
    s = two_chains()
    keep = [N - 1, N // 2, N // 2 - 1, 2 * N - 1]
    full = full_points[900.0].coefficients[0]
    errors = []
    for modes in (1, 4, 16):
        cb = craig_bampton(s, keep, modes=modes)
        f = np.zeros(cb.structure.ndof)
        f[0], f[3] = 20.0, 6.0
        r = frequency_point(cb.structure, f, 900.0, harmonics=3, reduction="none")
        errors.append(np.max(np.abs(cb.expand(r.coefficients[0]) - full)) / np.max(np.abs(full)))
    assert errors[0] > errors[1] > errors[2]


@pytest.mark.parametrize("keep, modes, error, message", [
    ([N - 1], 2, ValueError, "keep must include every DOF a contact or a static force uses"),
    ([N - 1, N // 2, N // 2 - 1, 2 * N - 1, 999], 2, ValueError, "keep: DOF indices must lie in 0..59"),
    ([N - 1, N - 1], 2, ValueError, "keep must not repeat a DOF"),
    ("abc", 2, TypeError, "keep must be a list of DOF indices, got 'abc' \\(DOF names such as '1204:x' need a DOF map"),
    ([], 2, TypeError, "keep must be a non-empty list of DOF indices, got \\[\\]"),
    ([0, 99], 2, ValueError, "keep: DOF indices must lie in 0..59, got 0..99"),
    ([0.5], 2, TypeError, "keep must be a list of DOF indices, got \\[0.5\\]"),
    ([N - 1, 2.0], 2, TypeError, "keep must be a list of DOF indices, got \\[29, 2.0\\]"),
    ([N - 1, N // 2, N // 2 - 1, 2 * N - 1, N - 1], 2, ValueError,
     "keep must not repeat a DOF: DOF 29 appears 2 times"),
    ([N - 1, N // 2, N // 2 - 1, 2 * N - 1], 100, ValueError, "modes must be at most 56"),
])
def test_craig_bampton_checks_its_arguments(keep, modes, error, message):
    with pytest.raises(error, match=message):
        craig_bampton(two_chains(), keep, modes)


@pytest.mark.parametrize("reduction, modes", [("exact", None), ("modal", 24)])
def test_the_reduced_jacobians_match_finite_differences(reduction, modes):
    """Along a curve the exact condensation switches to the held structure's modes and the modal one evaluates
    every harmonic at once: the Jacobian and the frequency derivative of the reduced equations stay exact."""
    from microslip.frequency.equations.reduced import ReducedHarmonicBalance
    from microslip.frequency.reduction.choice import linear_part, retained_dofs
    from microslip.frequency.equations.hbm import excitation

    s = two_chains()
    loads = excitation(s, forcing(), 3)
    loads[0] += s.preload_force()
    linear = linear_part(s, retained_dofs(s, loads), reduction, modes)
    hb = ReducedHarmonicBalance(s, forcing(), 3, linear, samples=64)
    for omega in (900.0, 1000.0, 1100.0, 1200.0):  # from the fourth frequency on: the spectral interior
        hb.dynamic_stiffness(omega)
    if reduction == "exact":
        assert linear._spectral[0] is not None
    x = np.random.default_rng(3).normal(size=hb.n) * 2e-6
    omega = 1150.0
    R, J, Rw = hb.evaluate(x, omega)
    h = 1e-12  # m: the contact forces are piecewise smooth, so a small step keeps both sides on one piece
    fd = np.array([(hb.evaluate(x + h * e, omega, jacobian=False) - hb.evaluate(x - h * e, omega, jacobian=False))
                   / (2 * h) for e in np.eye(hb.n)]).T
    # stiffnesses up to ~1e7 N/m; central differences of forces ~1e2 N at h = 1e-12 m carry ~1e-2 N/m of rounding
    np.testing.assert_allclose(J, fd, rtol=0, atol=1e-6 * np.abs(J).max())
    dw = 1e-3  # rad/s
    fdw = (hb.evaluate(x, omega + dw, jacobian=False) - hb.evaluate(x, omega - dw, jacobian=False)) / (2 * dw)
    np.testing.assert_allclose(Rw, fdw, rtol=0, atol=1e-7 * np.abs(Rw).max())


def test_a_finer_mesh_of_the_same_blade_needs_about_as_many_continuation_points():
    """The continuation measures arclength in the reduced unknowns (contact and excitation DOFs), which a
    finer mesh does not multiply: 420 and 5968 DOFs give 82 and 113 points (1452 DOFs: 109; the exact
    reduction 80, 92 and 109), where arclength in every DOF took 4-8 times more points at 1000-2000 DOFs."""
    from microslip.fe import blade

    points = []
    for dofs in (400, 6000):
        b = blade(dofs, contact_nodes=1)
        s = Structure(b.M, 2e-7 * b.K, b.K, dof_map=b.dof_map)
        for node in b.platform_nodes:
            s.add_contact(MODEL, tangential=f"{node}:x", approach=float(MODEL.approach(37.5)))
        f = np.zeros(s.ndof)
        f[s.dof_index(f"{b.tip_node}:x")] = 2.0
        r = frequency_response(s, f, (2 * np.pi * 1200, 2 * np.pi * 1800), harmonics=3, reduction="modal", modes=20)
        assert r.complete
        points.append(r.points)
    # the curve itself changes with the mesh (its peak by 8 %; the exact reduction's counts differ by 1.36
    # too), so the counts differ a little; growth with the DOFs would be several times
    assert max(points) <= 1.5 * min(points), points


def _jenkins_chain(n: int, contacts: int) -> Structure:
    """A fixed-free chain of ``n`` 0.1 kg masses and 1e6 N/m springs, Jenkins contacts spread along it."""
    K = 1e6 * (2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1))
    s = Structure(0.1 * np.eye(n), 1e-6 * K, K)
    for d in np.linspace(0, n - 1, contacts).astype(int):
        s.add_contact(MicroslipModel([4e5], [1e9], [0.0], 0.5), tangential=int(d), approach=1e-8)
    return s


def test_auto_condenses_a_small_structure_that_keeps_few_of_its_dofs():
    """A 40-DOF chain with 4 contacts, forced at one of them: small enough for dense equations on every
    DOF, but they keep only 4 DOFs, so "auto" condenses exactly (2.5x faster); the same point as on
    every DOF to solver tolerance (1e-8 of the largest coefficient). A 10-DOF chain stays on every DOF."""
    chain = _jenkins_chain(40, 4)
    force = np.zeros(40)
    force[13] = 2.0  # a contact DOF (np.linspace(0, 39, 4) -> 0, 13, 26, 39)
    auto = frequency_point(chain, force, 2500.0, harmonics=3)
    full = frequency_point(chain, force, 2500.0, harmonics=3, reduction="none")
    assert auto.reduction == "exact"
    for dof in (0, 13, 20, 39):
        np.testing.assert_allclose(auto.dof_coefficients(dof), full.dof_coefficients(dof), rtol=0,
                                   atol=1e-8 * np.abs(full.dof_coefficients(13)).max())
    small = _jenkins_chain(10, 2)
    assert frequency_point(small, np.eye(10)[0], 2500.0, harmonics=3).reduction == "none"


def test_craig_bampton_keeps_dofs_given_by_name():
    """With a DOF map the kept DOFs may be named as everywhere else (issue 24, item 18)."""
    from microslip.fe import DofMap

    s = two_chains()
    named = Structure(s.M, s.C, s.K, dof_map=DofMap(np.arange(100, 100 + s.ndof), ["x"] * s.ndof))
    for c in s.contacts:
        named.add_contact(c.model, tangential=c.tangential, normal=c.normal, preload=c.preload or None,
                          approach=c.approach, name=c.name)
    keep = [N - 1, N // 2, N // 2 - 1, 2 * N - 1]
    by_index = craig_bampton(s, keep, 4)
    by_name = craig_bampton(named, [f"{100 + k}:x" for k in keep[:2]] + keep[2:], 4)
    np.testing.assert_array_equal(by_name.keep, keep)
    np.testing.assert_array_equal(by_name.recovery, by_index.recovery)
    with pytest.raises(ValueError, match="keep\\[1\\]: DOF '999:x': node 999 is not in the DOF map"):
        craig_bampton(named, [f"{100 + N - 1}:x", "999:x"], 4)
