"""The structured solver of a modal model's Hill problem (never formed: the linear part per harmonic, the contacts
through a capacitance system of the retained unknowns) against the formed problem, point by point along curves:
the same verdicts, leading exponents and bifurcations."""

import sys

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from microslip import MicroslipModel, Sphere, tune
from microslip.frequency import Structure, frequency_response
from microslip.frequency.analyses import stability
from microslip.frequency.analyses.response import MAX_PERIODS, _equations
from microslip.frequency.equations.hbm import harmonic_operators

from _models import plane_chain
from _paths import EXAMPLES

sys.path.insert(0, str(EXAMPLES))
from inclined_block import FORCE as BLOCK_FORCE  # noqa: E402  (the example is the test case)


def both_methods(structure, force, omega, harmonics, reduction, modes=None, samples=None):
    """``(curve, structured, full)``: a curve without stability and :func:`stability.assess` of its points by
    each method."""
    curve = frequency_response(structure, force, omega, harmonics=harmonics, samples=samples,
                               reduction=reduction, modes=modes, stability=False)
    _, hb, _ = _equations(structure, force, harmonics, samples, MAX_PERIODS, reduction, modes)
    xs = curve.coefficients.reshape(curve.points, -1)
    return curve, stability.assess(hb, xs, curve.omega), stability.assess(hb, xs, curve.omega, method="full")


def agree(curve, structured, full):
    """The same verdict at every point, the same bifurcations, the leading exponents to the Arnoldi tolerance at
    the points computed; a point skipped (NaN) is far inside the stable region by the formed problem."""
    stable, leading, found = structured
    assert stable is not None and np.array_equal(stable, full[0])
    assert [b.kind for b in found] == [b.kind for b in full[2]]
    for a, b in zip(found, full[2]):
        # interpolated between the same two points from exponents equal to the Arnoldi tolerance
        assert a.point == pytest.approx(b.point, abs=1e-6)
    skipped = np.isnan(leading) & np.isfinite(full[1])
    # a skipped point lies between computed ones below -FAR omega: its own exponent is below the boundary by far
    # (half of FAR: the leading exponent moves little over SKIP_RUN points where it is not near a fold)
    assert np.all(full[1][skipped].real < -0.5 * stability.FAR * curve.omega[skipped])
    # both from shift-invert Arnoldi with tolerance 1e-10 on the same problem: 1e-8 of omega leaves room for the
    # conditioning of the eigenvalues; a conjugate pair may come in either order
    both = np.isfinite(leading) & np.isfinite(full[1])
    assert np.array_equal(both | skipped, np.isfinite(full[1]))
    gap = np.minimum(np.abs(leading - full[1]), np.abs(leading - np.conj(full[1])))[both]
    assert np.all(gap <= 1e-8 * curve.omega[both])


def block_with_arm():
    """The inclined block (its second mode bends back on itself between two folds) with a light stiff arm of
    four masses on its x: a structure whose modal model keeps more modes than the contact has DOFs."""
    n = 6
    M = np.diag([0.1, 0.1] + [0.005] * 4)
    K = np.zeros((n, n))
    K[0, 0] = K[1, 1] = 1e7
    chain = [0, 2, 3, 4, 5]
    for a, b in zip(chain[:-1], chain[1:]):
        K[np.ix_([a, b], [a, b])] += 2e8 * np.array([[1.0, -1.0], [-1.0, 1.0]])
    C = 2 * 0.005 * np.sqrt(3e7 / 0.1) * M
    s = Structure(M, C, K)
    a = np.radians(30)
    s.add_contact(tune(Sphere.paper(), 37.5, elements=4), tangential={0: np.cos(a), 1: np.sin(a)},
                  normal={0: -np.sin(a), 1: np.cos(a)}, preload=37.5, name="sphere")
    return s, np.concatenate([BLOCK_FORCE, np.zeros(n - 2)])


@pytest.mark.parametrize("disc", [0.5, 0.75, 1.0])
def test_a_curve_with_folds_gets_the_verdicts_of_the_formed_problem(disc, monkeypatch):
    """Two folds and an unstable branch between them, with the structured solver's disc at half of omega (its
    leading-exponent check then always widens it to omega: the widening path), the default and omega."""
    monkeypatch.setattr(stability, "DENSE_LIMIT", 10)  # 55 unknowns: the iterative solvers, formed or not
    monkeypatch.setattr(stability, "DISC", disc)
    s, f = block_with_arm()
    curve, structured, full = both_methods(s, f, (16000, 17500), 5, "modal", modes=5)
    assert [b.kind for b in full[2]] == ["fold", "fold"]
    assert not full[0].all()  # the branch between the folds is unstable
    agree(curve, structured, full)


def test_points_near_the_boundary_are_computed_and_the_folds_located_as_with_every_point(monkeypatch):
    """The fold curve (stable, two folds, an unstable branch, stable): the skipping solver leaves out points far
    inside the stable region only. Every point whose leading exponent (formed problem) is within FAR omega of the
    boundary, every point within TURN_WINDOW of a turn, and both points of each fold are computed; the verdicts and
    the folds' positions are those of every point computed, to rounding (the same exponents at the same points:
    1e-9 of a point, interpolated from exponents equal to the Arnoldi tolerance); and points are skipped (else the
    test would not test skipping)."""
    monkeypatch.setattr(stability, "DENSE_LIMIT", 10)
    s, f = block_with_arm()
    curve, skipping, full = both_methods(s, f, (16000, 17500), 5, "modal", modes=5)
    _, hb, _ = _equations(s, f, 5, None, MAX_PERIODS, "modal", 5)
    every = stability.assess(hb, curve.coefficients.reshape(curve.points, -1), curve.omega, every_point=True)
    computed = np.isfinite(skipping[1])
    assert 0 < np.count_nonzero(~computed) < curve.points
    near = full[1].real >= -stability.FAR * curve.omega
    assert near.any() and computed[near].all()
    assert computed[stability._turning(curve.omega)].all()
    assert [b.kind for b in every[2]] == [b.kind for b in skipping[2]] == ["fold", "fold"]
    for a, b in zip(skipping[2], every[2]):
        assert computed[int(np.floor(a.point))] and computed[int(np.floor(a.point)) + 1]
        assert a.point == pytest.approx(b.point, abs=1e-9)
        assert a.omega == pytest.approx(b.omega, rel=1e-12)
    assert np.array_equal(skipping[0], every[0])
    assert np.all(np.isfinite(every[1]))  # every point computed on request
    with pytest.raises(TypeError, match="every_point must be True or False"):
        stability.assess(hb, curve.coefficients.reshape(curve.points, -1), curve.omega, every_point="yes")


def test_the_receptance_is_that_of_the_linear_part_inverted(monkeypatch):
    """:meth:`_ModalParts.receptance` (built per harmonic) against ``R + Phi A^-1 Phi^T`` from ``A^-1`` applied to
    every column of ``Phi^T``, with classical and with non-classical modal damping, at a shift off 0; to rounding
    (1e-12 of the largest entry: sums of a few products of the same numbers in another order)."""
    s, f = block_with_arm()
    linear = _equations(s, f, 3, None, MAX_PERIODS, "modal", 5)[1].linear
    for damping in (None, "non-classical"):
        parts = stability._ModalParts(linear, 3, harmonic_operators(3)[0])
        if damping:
            Cm = parts.Cm + 0.3 * np.abs(parts.Cm).max() * (np.eye(5, k=1) + np.eye(5, k=-1))
            parts.Cm, parts.damping = Cm, None
        inverse = parts.inverse_linear(16500.0, 120.0)
        r = parts.nb * parts.retained
        Phi_t = np.column_stack([parts.lift(e) for e in np.eye(r)])
        expected = parts.R + parts.project(parts.apply_inverse(inverse, Phi_t))
        G = parts.receptance(inverse)
        assert np.abs(G - expected).max() <= 1e-12 * np.abs(expected).max()


def test_non_classical_damping(monkeypatch):
    """A dashpot at one end of a chain: modal damping with off-diagonal terms (the linear part's harmonic blocks
    are inverted as matrices); a Jenkins contact that slips; 5 modes, H = 5: 55 unknowns."""
    monkeypatch.setattr(stability, "DENSE_LIMIT", 10)
    n = 6
    K = 2e7 * (np.eye(n) * 2 - np.eye(n, k=1) - np.eye(n, k=-1))
    K[-1, -1] = 2e7
    C = 1e-6 * K
    C[0, 0] += 40.0
    s = Structure(0.01 * np.eye(n), C, K)
    s.add_contact(MicroslipModel(kt=[1e6], kn=[1e8], gaps=[0.0], mu=1.0), tangential=n - 1, approach=1e-8)
    f = np.zeros(n)
    f[-1] = 5.0
    curve, structured, full = both_methods(s, f, (8000, 13000), 5, "modal", modes=5)
    linear = _equations(s, f, 5, None, MAX_PERIODS, "modal", 5)[1].linear
    assert stability._ModalParts(linear, 5, np.eye(11)).damping is None  # the matrix path
    agree(curve, structured, full)


def test_a_plane_contact(monkeypatch):
    """A chain of masses in x and y with a contact on its plane at the free end (two tangential directions);
    7 modes, H = 3: 49 unknowns."""
    monkeypatch.setattr(stability, "DENSE_LIMIT", 10)
    s, force = plane_chain(4)
    curve, structured, full = both_methods(s, force, (150.0, 350.0), 3, "modal", modes=7)
    assert curve.contact_dissipation.max() > 0  # the contact slips
    agree(curve, structured, full)


def test_a_finite_element_blade_behind_an_exact_reduction(monkeypatch):
    """The scikit-fem blade of about 400 DOFs (classical damping): with WHOLE_LIMIT lowered, the exact
    reduction's stability comes from a 60-mode modal model, 420 unknowns at H = 3."""
    pytest.importorskip("skfem")
    from microslip.fe import blade

    monkeypatch.setattr(stability, "WHOLE_LIMIT", 0)
    b = blade(300, contact_nodes=1)
    s = Structure(b.M, 2e-7 * b.K, b.K, dof_map=b.dof_map)
    for node in b.platform_nodes:
        s.add_contact(MicroslipModel(kt=[2e6], kn=[2e8], gaps=[0.0], mu=0.1), tangential={f"{node}:x": 1.0},
                      normal={f"{node}:y": 1.0}, preload=50.0)
    f = s.force_vector({f"{b.tip_node}:x": 12.0})
    curve, structured, full = both_methods(s, f, (9000.0, 9800.0), 3, "exact")
    agree(curve, structured, full)


def test_the_method_is_checked():
    s, f = block_with_arm()
    _, hb, _ = _equations(s, f, 3, None, MAX_PERIODS, "modal", 5)
    with pytest.raises(ValueError, match="method must be one of"):
        stability.assess(hb, np.zeros((1, hb.n)), [16000.0], method="dense")


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2 ** 32 - 1), level=st.floats(-2.0, 1.0), skew=st.floats(0.0, 0.3),
       omega=st.floats(15000.0, 18000.0))
def test_random_contact_jacobians_get_the_exponents_of_the_formed_problem(seed, level, skew, omega):
    """Property: for a contact Jacobian of the retained unknowns drawn at random (stiffening or softening,
    symmetric or not: stable and unstable points), the structured solver's verdict and leading exponent are those
    of the formed problem. Leading real parts within 1e-8 of omega, as in :func:`agree` (both shift-invert Arnoldi
    to 1e-10 on the same problem). Points whose leading exponent has a real part above 0.5 omega are left out:
    the structured solver's disc does not see them (the documented limit)."""
    s, f = block_with_arm()
    _, hb, _ = _equations(s, f, 5, None, MAX_PERIODS, "modal", 5)
    limit = stability.DENSE_LIMIT
    stability.DENSE_LIMIT = 10  # 55 unknowns: the iterative solvers, formed or not
    try:
        formed, structured = stability._Builder(hb, "full"), stability._Builder(hb)
        rng = np.random.default_rng(seed)
        r = formed.Phi.shape[0]
        B = rng.standard_normal((r, r)) / np.sqrt(r)
        Jc = 10.0 ** level * 1e7 * (B @ B.T * np.sign(level + 0.5) + skew * (B - B.T))
        X = np.linalg.solve(np.eye(r) + formed.R @ Jc, formed.Phi)
        J0 = formed.Lam + omega * formed.DC - omega ** 2 * formed.WI + formed.Phi.T @ (Jc @ X)
        full = stability.HillProblem(J0, formed.C1 + 2 * omega * formed.M1, formed.D2, formed.m, omega).exponents()
        new = stability._ModalHill(structured.parts, Jc, omega, stability.NEAREST_START).exponents()
    except np.linalg.LinAlgError:  # a draw singular at and near 0 (both solvers refuse it)
        return
    finally:
        stability.DENSE_LIMIT = limit
    assume(full.size and full[0].real < 0.5 * omega)
    assert new.size and np.any(new.real > stability.TOLERANCE * omega) == np.any(full.real > stability.TOLERANCE
                                                                                  * omega)
    # the leading real part (mass-proportional damping gives several exponents one real part: which of them leads
    # is a tie), and every exponent of the formed problem in the smaller disc found
    assert abs(new[0].real - full[0].real) <= 1e-8 * omega
    for lam in full[np.abs(full) < 0.7 * omega]:
        assert np.min(np.minimum(np.abs(new - lam), np.abs(new - np.conj(lam)))) <= 1e-8 * omega


class _Scripted:
    """A stand-in for the solver of :func:`stability._skipping`: point ``k``'s exponents are ``script[k]`` (the
    points are indices), and the points it was asked for are recorded."""

    def __init__(self, script):
        self.script, self.asked = script, []

    def exponents(self, x, omega):
        k = int(x[0])
        self.asked.append(k)
        return self.script[k]


def skipped(script, omegas=None):
    """The points :func:`stability._skipping` leaves out of ``script`` (leading real parts over omega per point, None:
    no exponent resolved), omega 1 rad/s rising unless given."""
    omegas = np.arange(1.0, len(script) + 1) if omegas is None else np.asarray(omegas, dtype=float)
    lams = [np.empty(0, complex) if r is None else np.array([complex(r * w, 0.3 * w)]) for r, w in zip(script, omegas)]
    solver = _Scripted(lams)
    out = stability._skipping(solver, np.arange(len(script), dtype=float)[:, None], omegas)
    assert sorted(solver.asked) == sorted(set(solver.asked))  # no point computed twice
    return [k for k, lam in enumerate(out) if lam is None]


def test_the_skipping_rule():
    """The rule of :func:`stability._skipping` on scripted leading exponents (real part over omega): far inside
    everywhere, SKIP_RUN points of each SKIP_RUN + 1 after the first are skipped, never the last; a leading exponent
    that approaches the boundary (the line through the last two computed points reaches -FAR) stops the skipping;
    a run whose right neighbour is near the boundary, unstable or unresolved is computed after all; near a turn of
    the curve nothing is skipped."""
    far, F = -10 * stability.FAR, stability.FAR
    assert stability.SKIP_RUN == 3 and stability.TURN_WINDOW == 2  # the patterns below are written for these
    assert skipped([far] * 8) == [1, 2, 3, 5, 6]
    # approaching: the line through points 0 and 4 (-10 F, -4 F) is at -2.5 F at point 5 (skipped) and at -F at
    # point 6: computed from there on, each next line reaching -F
    assert skipped([far, far, far, far, -4 * F, -3 * F, -2 * F, -1.5 * F, -0.5 * F, far, far]) == [1, 2, 3, 5]
    # an unstable point right of a skipped run: the run is computed after all, the verdict changes between
    # computed points
    assert skipped([far, far, far, far, 0.01, far, far, far, far, far]) == [6, 7, 8]
    # nothing known of point 4 (no exponent resolved): the run before it computed, and no trend through it
    assert skipped([far, far, far, far, None, far, far, far, far, far]) == [7, 8]
    # the curve turns back at point 4: points 2..6 are computed
    assert skipped([far] * 10, [1, 2, 3, 4, 5, 4.5, 4, 3.5, 3, 2.5]) == [1, 7, 8]
