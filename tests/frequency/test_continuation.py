"""Continuation past corners: a curve that turns back at a kink (a fold where the Jacobian jumps)."""

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from microslip.frequency.numerics.continuation import continuation

SLOPE = 3.0  # the curve's slope in (x, omega) on each piece: it turns by 2 atan(3) = 143 degrees at a corner


def zigzag(x):
    """``omega = f(x)`` and ``f'(x)``: rising to 1 at the first knot, falling to 0 at the second, rising after."""
    knots = np.array([1.0, 2.0]) / SLOPE
    if x < knots[0]:
        return SLOPE * x, SLOPE
    if x < knots[1]:
        return 1.0 - SLOPE * (x - knots[0]), -SLOPE
    return SLOPE * (x - knots[1]), SLOPE


class Zigzag:
    """``R(x, omega) = omega - f(x)`` for ``x`` of size 1 (the continuation's problem interface)."""

    def __init__(self, sparse=False):
        self.sparse = sparse

    def _evaluate(self, x, omega, jacobian=True):
        f, slope = zigzag(float(x[0]))
        R = np.array([omega - f])
        if not jacobian:
            return R
        J = np.array([[-slope]])
        return R, (sp.csc_matrix(J) if self.sparse else J), np.array([1.0])

    def solve(self, A, b):
        try:
            return spla.splu(sp.csc_matrix(A)).solve(b) if sp.issparse(A) else np.linalg.solve(A, b)
        except (np.linalg.LinAlgError, RuntimeError):
            return np.full(np.shape(b), np.nan)

    def augmented(self, Jx, R_omega, row):
        if sp.issparse(Jx):
            return sp.vstack([sp.hstack([Jx, sp.csc_matrix(R_omega[:, None])]), sp.csc_matrix(row[None, :])],
                             format="csc")
        return np.block([[Jx, R_omega[:, None]], [row[None, :]]])


@pytest.mark.parametrize("sparse", [False, True])
def test_the_continuation_turns_back_at_a_corner_and_forward_at_the_next(sparse):
    start = -0.3
    xs, omegas, _, complete = continuation(Zigzag(sparse), np.array([start / SLOPE]), start, 1.5, x_scale=1.0,
                                           r_scale=1.0)
    assert complete and omegas[-1] == 1.5
    # every point on the curve, x never going back (the branch already followed is not retraced)
    np.testing.assert_allclose(omegas, [zigzag(x)[0] for x in xs[:, 0]], rtol=0, atol=1e-12)
    assert np.all(np.diff(xs[:, 0]) > 0)
    # both corners passed: omega falls from 1 to 0 between them
    assert omegas.max() > 1.0 - 1e-12 and np.any(np.diff(omegas) < 0)
    assert xs[-1, 0] == pytest.approx((2.0 + 1.5) / SLOPE, abs=1e-12)


def test_the_factored_bordered_system_gives_the_determinants_sign_with_any_last_row():
    """The orientation of a new point comes from the corrector's last factors with the last row replaced
    (matrix determinant lemma): the sign equals the determinant's of the replaced matrix, the solve NumPy's."""
    from microslip.frequency.numerics.continuation import _Factored

    rng = np.random.default_rng(7)
    for _ in range(50):
        A = rng.normal(size=(80, 80))
        row = rng.normal(size=80)
        A[-1] = row
        f = _Factored(A, row)
        b = rng.normal(size=80)
        np.testing.assert_allclose(f.solve(b), np.linalg.solve(A, b), rtol=1e-9, atol=1e-9 * np.abs(b).max())
        assert f.sign == np.linalg.slogdet(A)[0]
        other = rng.normal(size=80)
        B = A.copy()
        B[-1] = other
        assert f.sign_with_row(other) == np.linalg.slogdet(B)[0]
    A[:, 3] = 0.0  # singular: no sign, NaN solves (the continuation then shortens its step)
    f = _Factored(A, A[-1])
    assert f.sign_with_row(rng.normal(size=80)) == 0.0 and np.isnan(f.solve(np.ones(80))).all()


class Plateau(Zigzag):
    """``R(x, omega) = omega - g(x)``: ``g`` rises with slope 1 to 0.5 at ``x = 0``, stays there until ``end``,
    then rises again -- a straight line of solutions at ``omega = 0.5`` (unbounded with ``end`` None)."""

    def __init__(self, end=None):
        super().__init__()
        self.end = end

    def _evaluate(self, x, omega, jacobian=True):
        u = float(x[0])
        g, slope = (0.5 + u, 1.0) if u < 0 else (0.5, 0.0)
        if self.end is not None and u > self.end:
            g, slope = 0.5 + (u - self.end), 1.0
        R = np.array([omega - g])
        return R if not jacobian else (R, np.array([[-slope]]), np.array([1.0]))


def test_a_line_of_solutions_at_one_parameter_value_that_does_not_end_stops_the_curve_where_it_starts():
    lines = []
    xs, omegas, _, complete = continuation(Plateau(), np.array([-0.5]), 0.0, 1.0, x_scale=1.0, r_scale=1.0,
                                           lines=lines)
    assert not complete and lines == [pytest.approx(0.5, abs=1e-12)]
    # the points up to the line's start, every one on the curve; none on the line beyond its first point
    np.testing.assert_allclose(omegas, 0.5 + np.minimum(xs[:, 0], 0.0), rtol=0, atol=1e-12)
    assert xs[-1, 0] < 0.1 and len(omegas) < 60  # the line (arclength 1e6 ds_max) took no point of the curve's


def test_a_line_of_solutions_that_ends_is_crossed_in_few_points():
    end = 2.0  # 40 steps of ds_max = 0.05 long (the range of omega, 1, is the scaled length unit)
    xs, omegas, _, complete = continuation(Plateau(end), np.array([-0.5]), 0.0, 1.0, x_scale=1.0, r_scale=1.0)
    assert complete and omegas[-1] == 1.0
    np.testing.assert_allclose(omegas, [0.5 + min(x, 0.0) + max(x - end, 0.0) for x in xs[:, 0]], rtol=0, atol=1e-12)
    on_line = np.count_nonzero((xs[:, 0] > 1e-9) & (xs[:, 0] < end - 1e-9))
    assert 0 < on_line < 12  # doubling steps from ds_max: about log2(40) + the steps shortened near its end


class Parabola(Zigzag):
    """``R(x, omega) = omega - x (2 - x)``: a smooth fold at ``(x, omega) = (1, 1)``, back to ``omega = 0`` at 2."""

    def _evaluate(self, x, omega, jacobian=True):
        u = float(x[0])
        R = np.array([omega - u * (2.0 - u)])
        return R if not jacobian else (R, np.array([[-(2.0 - 2.0 * u)]]), np.array([1.0]))


def test_a_fold_in_the_parameter_ends_the_curve_when_asked_and_is_followed_otherwise():
    folds = []
    xs, omegas, _, complete = continuation(Parabola(), np.array([0.0]), 0.0, 1.5, x_scale=1.0, r_scale=1.0,
                                           folds=folds)
    # it ends at its farthest point, before the turn: within one step (ds_max 0.05 of the range, whose scaled
    # length is 1.5) of the fold, with every point on the curve and rising
    assert not complete and folds == [omegas[-1]] and np.all(np.diff(omegas) > 0)
    assert 1.0 - 0.05 * 1.5 < omegas[-1] <= 1.0 and abs(xs[-1, 0] - 1.0) < 0.05 * 1.5
    np.testing.assert_allclose(omegas, xs[:, 0] * (2 - xs[:, 0]), rtol=0, atol=1e-12)
    # followed (the default), the same points up to there, then back down until it leaves the range at its start
    xs2, omegas2, _, complete2 = continuation(Parabola(), np.array([0.0]), 0.0, 1.5, x_scale=1.0, r_scale=1.0)
    assert complete2 and omegas2[-1] < 0.05 * 1.5 and xs2[-1, 0] > 1.9  # its last point before leaving
    np.testing.assert_array_equal(omegas2[:omegas.size], omegas)


def test_a_line_at_one_parameter_value_is_no_fold():
    """Along a line of solutions the parameter moves by rounding, either way: not a turn back."""
    folds = []
    _, omegas, _, complete = continuation(Plateau(2.0), np.array([-0.5]), 0.0, 1.0, x_scale=1.0, r_scale=1.0,
                                          folds=folds)
    assert complete and omegas[-1] == 1.0 and folds == []


# -- the chord rule: steps sized by the distance between the curve and the chords ------------------------------------

class Graph(Zigzag):
    """``R(x, omega) = x - g(omega)``: the curve ``x = g(omega)`` in closed form, ``g`` and ``g'`` given."""

    def __init__(self, g, dg):
        super().__init__()
        self.g, self.dg = g, dg

    def _evaluate(self, x, omega, jacobian=True):
        R = np.array([x[0] - self.g(omega)])
        if not jacobian:
            return R
        return R, np.array([[1.0]]), np.array([-self.dg(omega)])


#: closed-form curves over omega in [-1, 1]: an S bend (a straight line with a tanh step in it) and a circle's arc
S_BEND = (lambda w: w + 0.2 * np.tanh(5 * w), lambda w: 1 + 1 / np.cosh(5 * w) ** 2)
ARC = (lambda w: np.sqrt(1.2 - w ** 2), lambda w: -w / np.sqrt(1.2 - w ** 2))


def _follow(curve, control):
    g, dg = curve
    xs, omegas, _, complete = continuation(Graph(g, dg), np.array([g(-1.0)]), -1.0, 1.0, x_scale=1.0, r_scale=1.0,
                                           control=control)
    assert complete
    return xs[:, 0], omegas


def chord_errors(curve, xs, omegas):
    """Largest distance between the curve and each chord (scaled units: x / 1, omega / 2), from the closed form
    sampled at 401 parameter values per step (the distance is smooth: sampling misses a fraction of 1e-5 of it)."""
    g = curve[0]
    out = []
    for k in range(omegas.size - 1):
        w = np.linspace(omegas[k], omegas[k + 1], 401)
        points = np.stack([g(w), w / 2.0], axis=1)
        a, b = np.array([xs[k], omegas[k] / 2.0]), np.array([xs[k + 1], omegas[k + 1] / 2.0])
        normal = np.array([a[1] - b[1], b[0] - a[0]]) / np.linalg.norm(b - a)
        out.append(np.max(np.abs((points - a) @ normal)))
    return np.array(out)


@pytest.mark.parametrize("curve", [S_BEND, ARC], ids=["s-bend", "arc"])
def test_the_chord_rule_keeps_every_chord_near_its_target(curve):
    from microslip.frequency.numerics.continuation import CHORD_REFUSE, StepControl

    target = 1e-4
    xs, omegas = _follow(curve, StepControl(chord_error=target, ds_max=0.5))
    np.testing.assert_allclose(xs, curve[0](omegas), rtol=0, atol=1e-8)  # every point on the curve
    errors = chord_errors(curve, xs, omegas)
    # a step is refused above CHORD_REFUSE times the estimate, which is exact to third order in the step (a
    # cubic through both ends with the curve's tangents there): a quarter more covers its error on these curves
    assert errors.max() <= 1.25 * CHORD_REFUSE * target
    # and the steps aim at the target rather than far below it (the last step ends on the range's edge: shorter)
    assert np.median(errors[:-1]) >= 0.4 * target


def test_the_chord_rule_follows_a_curve_with_fewer_points_at_a_smaller_error_than_the_turn_rule():
    from microslip.frequency.numerics.continuation import StepControl

    xs, omegas = _follow(S_BEND, StepControl())  # the turn rule: max_angle, iterations, ds_max
    xs_c, omegas_c = _follow(S_BEND, StepControl(chord_error=7e-5, ds_max=0.5))
    # the turn rule spends its points on the straight ends (ds_max) and its largest error in the bend
    assert omegas_c.size <= 0.9 * omegas.size
    assert chord_errors(S_BEND, xs_c, omegas_c).max() <= chord_errors(S_BEND, xs, omegas).max()


class Pair(Zigzag):
    """``R(x, omega) = x - (g(omega), h(omega))``: two unknowns, the curve in closed form; ``watched`` names the
    first (a nonlinear mode's frequency and damping against its amplitude, the second its shape)."""

    def __init__(self, g, h, watched=(0,)):
        super().__init__()
        self.g, self.h, self.watched = g, h, watched

    def _evaluate(self, x, omega, jacobian=True):
        R = x - np.array([self.g[0](omega), self.h[0](omega)])
        if not jacobian:
            return R
        return R, np.eye(2), -np.array([self.g[1](omega), self.h[1](omega)])


def test_the_chord_rule_on_watched_quantities_holds_their_error_against_the_parameter_and_ignores_the_rest():
    from microslip.frequency.numerics.continuation import CHORD_REFUSE, StepControl

    wave = (lambda w: 0.1 * np.sin(8 * w), lambda w: 0.8 * np.cos(8 * w))  # bends, in the unwatched unknown
    target = 1e-4
    control = StepControl(chord_error=target, ds_max=0.5, max_angle=0.3)  # as a nonlinear mode's default
    runs = {}
    for watched in ((0,), None):
        xs, omegas, _, complete = continuation(Pair(S_BEND, wave, watched), np.array([S_BEND[0](-1.0), wave[0](-1.0)]),
                                               -1.0, 1.0, x_scale=1.0, r_scale=1.0, control=control)
        assert complete
        np.testing.assert_allclose(xs, np.stack([S_BEND[0](omegas), wave[0](omegas)], axis=1), atol=1e-8)
        runs[watched] = xs[:, 0], omegas
    xs, omegas = runs[(0,)]
    # the watched quantity's difference from the straight lines joining the points at the same parameter value
    # (the scaled units are x / 1 and omega / 2: this is its difference in x), sampled at 40001 values: within
    # the refusal's bound, as for the distance from the chords above
    w = np.linspace(-1.0, 1.0, 40001)
    assert np.max(np.abs(np.interp(w, omegas, xs) - S_BEND[0](w))) <= 1.25 * CHORD_REFUSE * target
    # the unwatched wave sets no step: measured 67 points against 137 with the whole curve's chords
    assert runs[(0,)][1].size <= 0.6 * runs[None][1].size


@pytest.mark.parametrize("watched, same_as", [(0, (0,)), (-2, (0,)), ((), None)], ids=["scalar", "negative", "empty"])
def test_watched_takes_one_index_negative_indices_and_none(watched, same_as):
    from microslip.frequency.numerics.continuation import StepControl

    wave = (lambda w: 0.1 * np.sin(8 * w), lambda w: 0.8 * np.cos(8 * w))
    x0 = np.array([S_BEND[0](-1.0), wave[0](-1.0)])
    control = StepControl(chord_error=1e-4, ds_max=0.5, max_angle=0.3)
    _, omegas, _, _ = continuation(Pair(S_BEND, wave, watched), x0, -1.0, 1.0, x_scale=1.0, r_scale=1.0,
                                   control=control)
    _, expected, _, _ = continuation(Pair(S_BEND, wave, same_as), x0, -1.0, 1.0, x_scale=1.0, r_scale=1.0,
                                     control=control)
    np.testing.assert_array_equal(omegas, expected)


def test_the_chord_rule_keeps_a_corner_as_a_point_of_the_curve():
    from microslip.frequency.numerics.continuation import StepControl

    corner = (lambda w: np.abs(w - 0.1), lambda w: np.sign(w - 0.1))
    xs, omegas = _follow(corner, StepControl(chord_error=1e-4, ds_max=0.5))
    np.testing.assert_allclose(xs, corner[0](omegas), rtol=0, atol=1e-12)
    # the corner found on the straight line from the last point (bisection to 1e-6 of the step) is a point: the
    # chords on both sides lie on the curve's two straight pieces
    assert np.min(np.abs(omegas - 0.1)) < 1e-6
    assert chord_errors(corner, xs, omegas).max() < 1e-6
    assert omegas.size <= 15  # the straight pieces in long steps, not halved towards the corner


@pytest.mark.parametrize("value, error, message", [
    (0.0, ValueError, "chord_error must be positive, got 0.0"),
    (-1e-4, ValueError, "chord_error must be positive, got -0.0001"),
    ("small", TypeError, "chord_error must be a real number, got 'small'"),
    (float("nan"), ValueError, "chord_error must be finite"),
])
def test_a_chord_error_that_is_not_a_positive_number_is_refused_by_name(value, error, message):
    from microslip.frequency.numerics.continuation import StepControl

    with pytest.raises(error, match=message):
        StepControl(chord_error=value)


class Walled(Graph):
    """The straight line ``x = omega / 2`` whose residual is not finite for ``0.2 < omega < 0.35``: the corrector
    fails from any predictor there, as Newton's method can just across a point where the contact forces are not
    smooth; the band is longer than the longest step, so halved steps only creep towards it."""

    def __init__(self):
        super().__init__(lambda w: 0.5 * w, lambda w: 0.5)

    def _evaluate(self, x, omega, jacobian=True):
        if 0.2 < omega < 0.35:
            R = np.array([np.nan])
            return R if not jacobian else (R, np.array([[1.0]]), np.array([np.nan]))
        return super()._evaluate(x, omega, jacobian)


def test_steps_that_creep_to_a_wall_leap_over_it_with_a_warning_or_stall_beyond_reach():
    from microslip.common.errors import ConvergenceError, IncompleteCurveWarning

    with pytest.warns(IncompleteCurveWarning, match=r"stepped over the stretch from 0\.2\d* to 0\.(3[5-9]|[4-9])"):
        xs, omegas, _, complete = continuation(Walled(), np.array([-0.5]), -1.0, 1.0, x_scale=1.0, r_scale=1.0)
    assert complete and omegas[-1] == 1.0
    np.testing.assert_allclose(xs[:, 0], 0.5 * omegas, rtol=0, atol=1e-12)
    assert not np.any((omegas > 0.2) & (omegas < 0.35))
    # a band wider than four times the step that first failed (at most ds_max = 0.05 of the scaled length 2):
    # no leap reaches beyond it, and the continuation stops by name
    wide = Walled()
    wide._evaluate = lambda x, omega, jacobian=True: (Walled._evaluate(wide, x, 0.3, jacobian) if 0.2 < omega < 0.9
                                                      else Walled._evaluate(wide, x, omega, jacobian))
    with pytest.raises(ConvergenceError, match="stalled at omega = 0.2"):
        continuation(wide, np.array([-0.5]), -1.0, 1.0, x_scale=1.0, r_scale=1.0)
