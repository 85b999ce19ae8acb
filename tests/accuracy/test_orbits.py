"""Orbits on the contact plane: circles, ellipses, figure-eights, straight lines at an angle."""

import matplotlib

matplotlib.use("Agg")

import re  # noqa: E402

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from microslip import Sphere, accuracy, mdr, paths, tune  # noqa: E402
from microslip.paths import Path  # noqa: E402

SPHERE = Sphere.paper()


def test_circle_spirals_out_then_orbits_with_the_load_along_it():
    p = paths.circle(SPHERE, 1e-6, 20.0, 8.0, 90.0, cycles=2, steps_per_cycle=64)
    tau = 2 * np.pi * np.arange(3 * 64 + 1) / 64
    assert p.t.shape == (3 * 64 + 1, 2) and p.plane and p.periodic
    np.testing.assert_array_equal(p.t[0], [0.0, 0.0])  # starts unloaded at the centre
    radius = np.hypot(*p.t.T)
    np.testing.assert_allclose(radius[:65], 1e-6 * tau[:65] / (2 * np.pi), rtol=1e-14)  # the lead-in spiral
    np.testing.assert_allclose(radius[64:], 1e-6, rtol=1e-14)
    np.testing.assert_allclose(p.t[64:], 1e-6 * np.column_stack([np.cos(tau), np.sin(tau)])[64:], atol=1e-21)
    np.testing.assert_allclose(p.N, 20.0 + 8.0 * np.sin(tau + np.pi / 2), rtol=1e-14)
    np.testing.assert_allclose(p.n, SPHERE.approach(p.N), rtol=1e-15)
    assert p.steady == slice(128, 193)
    np.testing.assert_allclose(p.t[128], p.t[192], atol=1e-21)
    assert p.params["radius"] == 1e-6 and p.params["N_a"] == 8.0 and p.params["phase_deg"] == 90.0
    assert "circle of radius 1 µm" in p.label and "90°" in p.label


def test_ellipse_at_an_angle_lies_on_its_ellipse():
    a, b, angle = 2e-6, 0.5e-6, 30.0
    p = paths.ellipse(SPHERE, a, b, 25.0, angle_deg=angle, cycles=1, steps_per_cycle=90)
    c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
    steady = p.t[p.steady]
    major, minor = steady @ [c, s], steady @ [-s, c]  # coordinates along and across the major axis
    np.testing.assert_allclose((major / a) ** 2 + (minor / b) ** 2, 1.0, rtol=1e-13)
    np.testing.assert_allclose(steady[0], a * np.array([c, s]), rtol=1e-14)
    assert np.all(p.N == 25.0) and "at 30°" in p.label


def test_figure_eight_starts_at_the_centre_and_crosses_itself_there():
    p = paths.figure_eight(SPHERE, 2e-6, 1e-6, 25.0, 5.0, angle_deg=90.0, cycles=2, steps_per_cycle=80)
    assert len(p) == 161 and p.steady == slice(80, 161)
    np.testing.assert_allclose(p.t[[0, 40, 80, 120, 160]], 0.0, atol=1e-20)
    # turned by 90°: the long axis (2 µm) along y, the short one (1 µm) along x
    assert np.abs(p.t[:, 1]).max() == pytest.approx(2e-6) and np.abs(p.t[:, 0]).max() == pytest.approx(1e-6, rel=1e-3)


@pytest.mark.parametrize("angle", [0.0, 37.0, 90.0, 200.0])
def test_a_line_at_an_angle_gives_the_variable_load_cycles_along_it(angle):
    model = tune(SPHERE, 37.5, elements=4)
    p = paths.line(SPHERE, 1.2e-6, 20.0, 15.0, 45.0, angle_deg=angle, cycles=2, steps_per_cycle=90)
    q = paths.variable_load_cycles(SPHERE, 20.0, 15.0, 1.2e-6, 45.0, cycles=2, steps_per_cycle=90)
    e = np.array([np.cos(np.radians(angle)), np.sin(np.radians(angle))])
    np.testing.assert_allclose(p.t, q.t[:, None] * e, rtol=0, atol=1e-20)
    np.testing.assert_array_equal(p.n, q.n)
    plane, one = p.simulate(model), q.simulate(model)
    np.testing.assert_allclose(plane.T @ e, one.T, rtol=0, atol=1e-12 * 15.0)  # 1e-12 of mu N: rounding
    np.testing.assert_allclose(plane.T @ [-e[1], e[0]], 0.0, rtol=0, atol=1e-12 * 15.0)


def test_paths_on_the_plane_in_from_arrays_plot_and_where_they_are_refused():
    t = np.array([[0.0, 0.0], [1e-6, 0.0], [0.0, 1e-6], [0.0, 0.0]])
    p = paths.from_arrays(t, N=[10.0, 12.0, 14.0, 10.0], reference=SPHERE, periodic=True)
    assert p.plane and p.t.shape == (4, 2) and len(p) == 4
    assert p.simulate(tune(SPHERE, 37.5, elements=2)).T.shape == (4, 2)
    p.plot()
    with pytest.raises(ValueError, match="steady_span is defined along one tangential direction"):
        p.steady_span
    with pytest.raises(ValueError, match=re.escape("paths[0] (user path) is an orbit on the contact plane: the "
                                                   "accuracy metrics are defined along one tangential direction")):
        accuracy(tune(SPHERE, 37.5, elements=2), mdr(SPHERE, max_load=40.0, elements=20), [p])


@pytest.mark.parametrize("call, error, message", [
    (lambda: paths.circle(SPHERE, 0.0, 20.0), ValueError, "radius must be positive, got 0.0"),
    (lambda: paths.circle(SPHERE, 1e-6, 20.0, 25.0), ValueError,
     "load_amplitude must not exceed mean_load = 20 N (the normal load N_m - N_a would be negative), got 25 N"),
    (lambda: paths.circle(SPHERE, 1e-6, -1.0), ValueError, "mean_load must be positive, got -1.0"),
    (lambda: paths.circle("sphere", 1e-6, 20.0), TypeError, "reference must provide approach()"),
    (lambda: paths.circle(SPHERE, 1e-6, 20.0, cycles=0), ValueError, "cycles"),
    (lambda: paths.circle(SPHERE, 1e-6, 20.0, steps_per_cycle=4), ValueError, "steps_per_cycle"),
    (lambda: paths.ellipse(SPHERE, 1e-6, 2e-6, 20.0), ValueError,
     "semi_minor must not exceed semi_major = 1e-06 m, got 2e-06 m"),
    (lambda: paths.ellipse(SPHERE, 1e-6, 0.5e-6, 20.0, angle_deg=np.nan), ValueError, "angle_deg must be finite"),
    (lambda: paths.figure_eight(SPHERE, 1e-6, -1.0, 20.0), ValueError, "half_height must be positive"),
    (lambda: paths.line(SPHERE, 1e-6, 20.0, phase_deg="90"), TypeError, "phase_deg must be a real number, got '90'"),
    (lambda: paths.from_arrays(np.zeros((3, 2)), n=[1e-6, 1e-6]), ValueError,
     "n must be a scalar or have one value per sample of t (3,), got shape (2,)"),
    (lambda: Path(t=np.zeros((3, 2)), n=np.zeros(2), steady=slice(0, 3)), ValueError,
     "n must have one value per sample of t (3,), got (2,)"),
    (lambda: Path(t=np.zeros((3, 3)), n=np.zeros(3), steady=slice(0, 3)), ValueError,
     "t must have shape (steps,) (one tangential direction) or (steps, 2)"),
    (lambda: Path(t=np.zeros((1, 2)), n=np.zeros(1), steady=slice(0, 1)), ValueError,
     "t must have at least 2 samples, got 1"),
    (lambda: paths.from_arrays([[0.0, 0.0], [1e-6, 0.0]], n=1e-6, periodic=True), ValueError,
     "periodic: the steady part must close, but t goes from (0, 0) m at sample 0 to (1e-06, 0) m at sample 1"),
])
def test_orbit_builders_refuse_bad_input_by_name(call, error, message):
    with pytest.raises(error) as info:
        call()
    assert message in str(info.value)
