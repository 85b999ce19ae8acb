"""Cylinder on a plane: the Palmgren and Lundberg-Sjövall laws of Harris, a measured table."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import optimize

from microslip import Cylinder

GEOM = dict(length=10e-3, radius=5e-3, E=200e9, nu=0.3)


def test_palmgren_by_hand():
    # delta[mm] = 3.84e-5 Q^0.9 / l^0.8 with Q = 36.6 N, l = 10 mm, computed step by step
    delta_mm = 3.84e-5 * 36.6**0.9 / 10.0**0.8
    assert float(Cylinder(**GEOM).approach(36.6)) == pytest.approx(delta_mm * 1e-3, rel=1e-14)
    # doubling the load multiplies the approach by 2^0.9; doubling l divides it by 2^0.8
    c = Cylinder(**GEOM)
    assert float(c.approach(20.0) / c.approach(10.0)) == pytest.approx(2**0.9, rel=1e-13)
    c2 = Cylinder(**{**GEOM, "length": 20e-3})
    assert float(c.approach(10.0) / c2.approach(10.0)) == pytest.approx(2**0.8, rel=1e-13)


def test_lundberg_by_hand_and_its_inverse_against_brentq():
    Q, l, E, nu = 25.0, 10e-3, 200e9, 0.3
    delta = 2 * Q * (1 - nu**2) / (np.pi * E * l) * np.log(np.pi * l**2 * E / (Q * (1 - nu**2)))
    c = Cylinder(**GEOM, law="lundberg")
    assert float(c.approach(Q)) == pytest.approx(delta, rel=1e-14)
    # the Lambert-W inverse against a plain bracketed root of delta(Q) = n
    root = optimize.brentq(lambda q: float(c.approach(q)) - delta, 1e-3, 1e3, xtol=1e-14, rtol=1e-15)
    assert float(c.normal_force(delta)) == pytest.approx(root, rel=1e-12)


@settings(max_examples=60, deadline=None)
@given(N=st.floats(1e-3, 1e4), law=st.sampled_from(["palmgren", "lundberg"]))
def test_round_trip_and_monotone(N, law):
    c = Cylinder(**GEOM, law=law)
    n = c.approach(N)
    assert float(c.normal_force(n)) == pytest.approx(N, rel=1e-10)
    assert float(c.approach(N * 1.01)) > float(n) > 0  # increasing


@pytest.mark.parametrize("law", ["palmgren", "lundberg"])
def test_normal_stiffness_is_the_derivative(law):
    c = Cylinder(**GEOM, law=law)
    N = 30.0
    h = 1e-4
    fd = 2 * h / float(c.approach(N + h) - c.approach(N - h))
    assert float(c.normal_stiffness(N)) == pytest.approx(fd, rel=1e-6)  # central difference, O(h^2)


def test_zero_load_and_negative_approach():
    for law in ("palmgren", "lundberg"):
        c = Cylinder(**GEOM, law=law)
        assert float(c.approach(0.0)) == 0.0
        np.testing.assert_array_equal(c.normal_force([-1e-7, 0.0]), [0.0, 0.0])


def test_table_law_is_monotone_and_inverts_exactly():
    n = np.array([0.0, 0.05, 0.1, 0.2, 0.4]) * 1e-6
    N = np.array([0.0, 2.0, 6.0, 15.0, 40.0])
    c = Cylinder(**GEOM, law=np.column_stack([n, N]))
    np.testing.assert_allclose(c.normal_force(n), N, rtol=1e-12)  # passes through the rows
    grid = np.linspace(0, 0.4e-6, 400)
    assert np.all(np.diff(c.normal_force(grid)) >= 0)  # PCHIP keeps monotone data monotone
    loads = np.linspace(0.0, 40.0, 33)
    np.testing.assert_allclose(c.normal_force(c.approach(loads)), loads, atol=1e-9)
    assert c.law == "table" and "table" in c.law_name
    assert float(c.normal_stiffness(10.0)) > 0


def test_table_without_zero_row_gets_one():
    c = Cylinder(**GEOM, law=[[1e-7, 5.0], [2e-7, 12.0]])
    assert float(c.normal_force(0.0)) == 0.0 and float(c.normal_force(5e-8)) > 0


def test_table_files(tmp_path):
    path = tmp_path / "normal.csv"
    path.write_text("n [um],N [N]\n0,0\n0.1,5\n0.2,12\n0.3,21\n", encoding="utf-8")
    c = Cylinder.from_file(path, **GEOM, mu=0.4)
    assert float(c.normal_force(0.2e-6)) == pytest.approx(12.0) and c.mu == 0.4


def test_errors_name_the_problem():
    with pytest.raises(ValueError, match=r"law must be one of \['palmgren', 'lundberg'\].*got 'hertz'"):
        Cylinder(**GEOM, law="hertz")
    with pytest.raises(ValueError, match=r"not monotone: load of row 3 \(4 N\) does not exceed row 2 \(5 N\)"):
        Cylinder(**GEOM, law=[[0, 0], [1e-7, 5.0], [2e-7, 4.0]])
    with pytest.raises(ValueError, match=r"not monotone: approach of row 3"):
        Cylinder(**GEOM, law=[[0, 0], [1e-7, 5.0], [1e-7, 6.0]])
    with pytest.raises(ValueError, match=r"shape \(k, 2\)"):
        Cylinder(**GEOM, law=[1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="non-negative"):
        Cylinder(**GEOM, law=[[0, 0], [-1e-7, 5.0]])
    c = Cylinder(**GEOM, law=[[0, 0], [1e-7, 5.0]])
    with pytest.raises(ValueError, match=r"N beyond the table: up to 9 N, the table ends at 5 N"):
        c.approach(9.0)
    with pytest.raises(ValueError, match=r"n beyond the table"):
        c.normal_force(3e-7)
    with pytest.raises(ValueError, match=r"length must be positive, got -0.01"):
        Cylinder(length=-0.01, radius=5e-3, E=200e9, nu=0.3)
    with pytest.raises(ValueError, match=r"nu must lie in \(-1.0, 0.5\]"):
        Cylinder(length=0.01, radius=5e-3, E=200e9, nu=0.7)
    with pytest.raises(ValueError, match="mu must be positive"):
        Cylinder(**GEOM, mu=0.0)
    with pytest.raises(ValueError, match=r"2 l / e"):
        Cylinder(**GEOM, law="lundberg").normal_force(0.01)


def test_hertz_half_width_and_with_mu():
    c = Cylinder(**GEOM)
    E_star = 200e9 / (2 * (1 - 0.09))
    assert float(c.contact_half_width(36.6)) == pytest.approx(np.sqrt(4 * 36.6 * 5e-3 / (np.pi * 10e-3 * E_star)))
    assert c.with_mu(0.45).mu == 0.45 and c.with_mu(0.45).law == "palmgren"
