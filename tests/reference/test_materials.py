"""Dissimilar materials: the pair's E* and G* in Hertz, Cattaneo-Mindlin, the MDR reference and the tuning."""

import numpy as np
import pytest

from microslip import Cylinder, Sphere, mdr, tune

# a cobalt-alloy damper on a nickel-alloy platform (typical room-temperature values)
E1, NU1, E2, NU2 = 230e9, 0.30, 205e9, 0.29


def moduli_by_hand():
    G1, G2 = E1 / (2 * (1 + NU1)), E2 / (2 * (1 + NU2))
    return 1 / ((1 - NU1**2) / E1 + (1 - NU2**2) / E2), 1 / ((2 - NU1) / G1 + (2 - NU2) / G2)


def test_identical_bodies_are_the_default_and_unchanged():
    s = Sphere.paper()
    assert s.E_star == pytest.approx(200e9 / (2 * (1 - 0.3**2)), rel=1e-15)
    assert s.G_star == pytest.approx(200e9 / (2 * 1.3) / (2 * 1.7), rel=1e-15)
    assert Sphere(5e-3, 200e9, 0.3, 0.4, E2=200e9, nu2=0.3).E_star == pytest.approx(s.E_star, rel=1e-15)


def test_hertz_and_cattaneo_mindlin_with_the_pair_moduli():
    E_star, G_star = moduli_by_hand()
    s = Sphere(radius=5e-3, E=E1, nu=NU1, mu=0.4, E2=E2, nu2=NU2)
    assert s.E_star == pytest.approx(E_star, rel=1e-14) and s.G_star == pytest.approx(G_star, rel=1e-14)
    N = 30.0
    a = (3 * N * 5e-3 / (4 * E_star)) ** (1 / 3)
    assert s.contact_radius(N) == pytest.approx(a, rel=1e-14)
    assert s.approach(N) == pytest.approx(a * a / 5e-3, rel=1e-14)
    assert s.tangential_stiffness(N) == pytest.approx(8 * G_star * a, rel=1e-14)
    assert s.gross_slip_displacement(N) == pytest.approx(3 * 0.4 * N / (16 * G_star * a), rel=1e-14)


def test_the_exact_reference_and_the_tuning_follow_the_pair():
    s = Sphere(radius=5e-3, E=E1, nu=NU1, mu=0.4, E2=E2, nu2=NU2)
    ref = mdr(s, max_load=40.0, elements=1600)
    n = float(s.approach(30.0))
    # the MDR array converges like 1/elements^2 (tests/reference/test_mdr.py: 2.3e-7 of N at 1600 elements)
    assert float(ref.normal_force(n)) == pytest.approx(30.0, rel=1e-6)
    model = tune(s, 30.0, elements=6)
    assert float(model.normal_force(n)) == pytest.approx(30.0, rel=1e-12)  # tuned through the pair's Hertz law
    # closed-form tuning: kn = kt E*/G*_P with G*_P = 4 G*
    E_star, G_star = moduli_by_hand()
    np.testing.assert_allclose(model.kn, model.kt * E_star / (4 * G_star), rtol=1e-9)


def test_cylinder_uses_the_pair_in_lundberg_sjovall():
    E_star, _ = moduli_by_hand()
    c = Cylinder(length=10e-3, radius=5e-3, E=E1, nu=NU1, mu=0.4, law="lundberg", E2=E2, nu2=NU2)
    Q, l = 30.0, 10e-3
    delta = Q / (np.pi * E_star * l) * np.log(2 * np.pi * l**2 * E_star / Q)
    assert float(c.approach(Q)) == pytest.approx(delta, rel=1e-13)
    assert float(c.normal_force(c.approach(Q))) == pytest.approx(Q, rel=1e-12)


@pytest.mark.parametrize("kwargs, message", [
    ({"E2": 200e9}, "E2 and nu2 go together"),
    ({"nu2": 0.3}, "E2 and nu2 go together"),
    ({"E2": -1.0, "nu2": 0.3}, "E2"),
    ({"E2": 200e9, "nu2": 0.7}, "nu2"),
])
def test_the_second_body_is_checked(kwargs, message):
    with pytest.raises(ValueError, match=message):
        Sphere(5e-3, 200e9, 0.3, 0.4, **kwargs)
    with pytest.raises(ValueError, match=message):
        Cylinder(10e-3, 5e-3, 200e9, 0.3, 0.4, **kwargs)
