"""The condensations with a mass-proportional damping ``-xi M`` (the extended periodic motion concept's term).

Every path (dense and sparse factorisation, the spectral interior with all its modes, the series of the omitted
modes, the modal condensation with diagonal and general damping) is checked against the same class built on the
matrices ``M, C - xi M, K`` -- the definition of what ``xi`` means -- and its ``xi``-derivatives against central
differences; the projection of every DOF's first harmonic onto the retained ones against the recovered interior.
"""

import numpy as np
import pytest
import scipy.sparse as sp

from microslip.frequency.reduction.condensation import Condensation
from microslip.frequency.reduction.modal import ModalCondensation

RETAINED = np.array([3, 10, 20])
XI = 40.0  # 1/s: a damping ratio of 2 % at 1000 rad/s
H = 3


def chain(ndof: int, stiffness: float = 1e6, damping: str = "rayleigh", seed: int = 0):
    """``(M, C, K)`` of a grounded chain, sparse; ``damping`` "rayleigh", "none" or "general" (a local damper)."""
    rng = np.random.default_rng(seed)
    K = sp.diags([2 * np.ones(ndof), -np.ones(ndof - 1), -np.ones(ndof - 1)], [0, 1, -1]).tocsr() * stiffness
    M = sp.diags(0.1 * (1 + 0.1 * rng.random(ndof))).tocsr()
    C = {"rayleigh": 2e-5 * K + 3.0 * M, "none": 0 * M,
         "general": 2e-5 * K + 3.0 * M + sp.diags(np.r_[np.zeros(ndof - 1), 50.0])}[damping]
    return M, sp.csr_matrix(C), K


def relative(a, b) -> float:
    return float(np.abs(a - b).max() / np.abs(b).max())


def spectral_state(condensation):
    """Which path the last evaluation took: "factorised", "spectral" (every mode) or "series"."""
    spectral = condensation._spectral.get(0)
    return "factorised" if spectral is None else ("series" if spectral.tail is not None else "spectral")


def derivative(f, x: float, step: float):
    """Five-point central difference of ``f`` at ``x`` (truncation ``step^4``): the chains' dense spectra near
    ``omega`` make ``S`` vary quickly with ``xi``, too quickly for the three-point one."""
    return (8 * (f(x + step) - f(x - step)) - (f(x + 2 * step) - f(x - 2 * step))) / (12 * step)


def check(linear, reference, omega, ndof, seed=1):
    """``linear`` with ``xi`` against ``reference`` built on ``C - xi M``; derivatives; the projection."""
    Z, dZ, dX = linear.operator(omega, H, XI)
    Zr, dZr = reference.operator(omega, H)
    # rounding of the same algebra in another order (measured up to 1.1e-10: conditioning times 1e-16)
    assert relative(Z, Zr) < 1e-9 and relative(dZ, dZr) < 1e-9
    fd = derivative(lambda xi: linear.operator(omega, H, xi)[0], XI, 1e-3 * XI)
    assert relative(dX, fd) < 1e-6  # five-point difference: truncation and rounding, measured below 1e-8
    rng = np.random.default_rng(seed)
    w = rng.random(ndof)
    g, g_omega, g_xi = linear.projection(w, omega, XI)
    z = rng.random(RETAINED.size) + 1j * rng.random(RETAINED.size)
    X = np.zeros((3, RETAINED.size))
    X[1], X[2] = z.real, -z.imag
    full = linear.recover(X, omega, 1, XI)
    assert abs(w @ (full[1] - 1j * full[2]) - g @ z) < 1e-8 * abs(g @ z)  # rounding of sums that cancel (measured 1e-9)
    fd_omega = derivative(lambda o: linear.projection(w, o, XI)[0], omega, 1e-4 * omega)
    fd_xi = derivative(lambda xi: linear.projection(w, omega, xi)[0], XI, 1e-3 * XI)
    assert relative(g_omega, fd_omega) < 1e-6 and relative(g_xi, fd_xi) < 1e-6  # as above


@pytest.mark.parametrize("ndof, stiffness, frequencies, path", [
    (30, 1e6, [900.0], "factorised"),  # a dense interior, one frequency: factorised
    (30, 1e6, [900.0, 1000.0, 1100.0, 1200.0], "spectral"),  # from the fourth frequency: every mode
    (2500, 1e6, [900.0], "factorised"),  # sparse, one frequency: factorised
    (2500, 1e9, [300.0, 400.0], "series"),  # sparse, stiff: the lowest modes and the series of the others
])
def test_exact_condensation_with_xi_equals_the_condensation_of_c_minus_xi_m(ndof, stiffness, frequencies, path):
    M, C, K = chain(ndof, stiffness)
    linear = Condensation(M, C, K, RETAINED)
    for omega in frequencies:
        linear.operator(omega, H, XI)
    assert spectral_state(linear) == path
    check(linear, Condensation(M, C - XI * M, K, RETAINED), frequencies[-1], ndof)


@pytest.mark.parametrize("damping", ["rayleigh", "general", "none"])
@pytest.mark.parametrize("ndof", [40, 700])
def test_modal_condensation_with_xi_equals_the_modal_condensation_of_c_minus_xi_m(damping, ndof):
    M, C, K = chain(ndof, damping=damping)
    linear = ModalCondensation(M, C, K, RETAINED, 10)
    assert (linear._damping is None) == (damping == "general")
    check(linear, ModalCondensation(M, C - XI * M, K, RETAINED, 10), 1000.0, ndof)


def test_xi_zero_is_the_plain_operator():
    M, C, K = chain(30)
    linear = Condensation(M, C, K, RETAINED)
    Z, dZ = linear.operator(1000.0, H)
    Zx, dZx, _ = linear.operator(1000.0, H, 0.0)
    assert np.array_equal(Z, Zx) and np.array_equal(dZ, dZx)
