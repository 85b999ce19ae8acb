"""Contact moduli of a pair of elastic bodies (identical or dissimilar materials).

``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2`` and ``1/G* = (2 - nu1)/G1 + (2 - nu2)/G2``
with ``G = E / (2 (1 + nu))``; for identical bodies ``E* = E / (2 (1 - nu^2))`` and
``G* = G / (2 (2 - nu))`` (Johnson, *Contact Mechanics*, Sects. 4.2 and 7.2; the
Cattaneo--Mindlin solution with ``G*`` holds exactly when the two bodies have the
same ``(1 - 2 nu)/G``, and is the usual engineering approximation otherwise).
"""

from __future__ import annotations

from ..common import _checks


def check_second_body(E, nu, E2, nu2) -> tuple[float, float]:
    """``(E2, nu2)`` checked (Pa, -): the second body's, or the first's when both are None."""
    if (E2 is None) != (nu2 is None):
        raise ValueError("E2 and nu2 go together: give both for a second body of another material, or neither "
                         "for identical bodies")
    if E2 is None:
        return E, nu
    return (_checks.positive_scalar("E2", E2), _checks.in_range("nu2", nu2, -1.0, 0.5, lo_open=True))


def contact_moduli(E: float, nu: float, E2: float, nu2: float) -> tuple[float, float]:
    """``(E*, G*)`` (Pa) of two bodies with Young's moduli ``E``, ``E2`` (Pa) and Poisson's ratios ``nu``, ``nu2``."""
    G, G2 = E / (2.0 * (1.0 + nu)), E2 / (2.0 * (1.0 + nu2))
    E_star = 1.0 / ((1.0 - nu**2) / E + (1.0 - nu2**2) / E2)
    G_star = 1.0 / ((2.0 - nu) / G + (2.0 - nu2) / G2)
    return E_star, G_star
