"""Nonlinear modes (extended periodic motion concept) against closed forms, linear limits and forced responses.

* a 1-DOF oscillator with a Jenkins element: with one harmonic the mode is the describing-function result,
  in closed form (derived below), to 1e-8; with seven harmonics the difference is measured;
* the small-amplitude limit is the linear mode of the structure with its contacts stuck (an exact
  eigenvalue, 1e-8), the large-amplitude one the mode of the structure with its contacts sliding;
* forced responses of the same structures at light damping peak on the mode's backbone (phase resonance)
  within 1e-3 in frequency, and the single-mode synthesis matches their peak within 2 %: a 2-DOF chain, the
  block on an inclined plane with springs that make its normal load vary along the mode;
* the reduction onto the contact DOFs: exact equals every DOF solved (1e-8), modal within its estimate, and
  a scikit-fem blade's small-amplitude limit is its stuck linear mode.
"""

import sys

import numpy as np
import pytest
import scipy.linalg as sla

from microslip import MicroslipModel, Sphere, Structure, tune
from microslip.frequency import StepControl, frequency_response
from microslip.frequency.analyses.nonlinear_modes import nonlinear_modes

from _paths import EXAMPLES

sys.path.insert(0, str(EXAMPLES))
from inclined_block import inclined_block  # noqa: E402  (the example is the test case)

# -- a 1-DOF oscillator with a Jenkins element -------------------------------------------------------
MASS, STIFFNESS, KT, MU, LOAD, DAMPING = 0.5, 1e6, 4e6, 0.5, 10.0, 20.0  # kg, N/m, N/m, -, N, N s/m
SLIP = MU * LOAD  # the Jenkins element's slip force (N)


def jenkins(damping: float = DAMPING) -> Structure:
    """``m q'' + c q' + k q + T(q) = 0``, ``T`` a Jenkins element (stiffness KT, slip force mu N, N imposed)."""
    s = Structure([[MASS]], [[damping]], [[STIFFNESS]])
    s.add_contact(MicroslipModel([KT], [1e9], [0.0], MU), tangential=0, approach=LOAD / 1e9)
    return s


def describing_function(A):
    """``(omega, D, D_viscous)`` of the mode at displacement amplitude ``A`` (m), first harmonic, closed form.

    With ``q = A cos(tau)`` the Jenkins force sticks while ``A <= A_s = mu N / k_t`` (``T = k_t q``). Above,
    starting from ``tau = 0`` (``q = A``, ``T = mu N``, sliding back) the element sticks on the way down until
    ``k_t (A - q) = 2 mu N``, i.e. ``cos(tau) = 1 - 2 A_s / A = cos(beta)``, then slides at ``-mu N`` until
    ``tau = pi``; the second half repeats with opposite signs. Its first harmonic ``T ~ a_1 cos + b_1 sin``:

    ``a_1 = (1/pi) int_0^2pi T cos = (k_t A / pi) (beta - sin(2 beta) / 2)``,
    ``b_1 = (1/pi) int_0^2pi T sin = -(4 mu N / pi) (1 - A_s / A)``

    (``-pi A b_1 = 4 mu N (A - A_s)``, the area of the loop). Harmonic balance of
    ``m q'' + (c - xi m) q' + k q + T = 0`` with ``q' = -A omega sin``: the cosines give
    ``omega^2 = (k + a_1 / A) / m``, the sines ``(c - xi m) A omega = b_1``, so
    ``xi = c / m - b_1 / (m A omega)`` and ``D = xi / (2 omega)``, of which ``c / (2 m omega)`` is viscous.
    The modal amplitude of the mass-normalised mode ``1 / sqrt(m)`` is ``a = sqrt(m) A``.
    """
    A = np.asarray(A, dtype=float)
    As = SLIP / KT
    beta = np.arccos(np.clip(1 - 2 * As / A, -1.0, 1.0))
    a1 = np.where(A > As, KT * A / np.pi * (beta - np.sin(2 * beta) / 2), KT * A)
    b1 = np.where(A > As, -(4 * SLIP / np.pi) * (1 - As / A), 0.0)
    omega = np.sqrt((STIFFNESS + a1 / A) / MASS)
    xi = DAMPING / MASS - b1 / (MASS * A * omega)
    return omega, xi / (2 * omega), DAMPING / (2 * MASS * omega)


def test_one_harmonic_equals_the_describing_function_at_every_amplitude():
    # 2^15 samples: the AFT's sampling error (1/samples^2, 1e-3 at 32 samples) falls below 1e-9
    mode = nonlinear_modes(jenkins(), 1, (1e-7, 1e-2), harmonics=1, samples=2 ** 15)
    A = mode.modal_amplitude / np.sqrt(MASS)
    omega, D, viscous = describing_function(A)
    assert mode.complete and A.min() < 0.5 * SLIP / KT and A.max() > 1000 * SLIP / KT  # stuck to gross slip
    assert np.max(np.abs(mode.omega / omega - 1)) < 1e-8
    assert np.max(np.abs(mode.damping_ratio - D)) < 1e-8
    assert np.max(np.abs(mode.viscous_damping_ratio - viscous)) < 1e-8
    assert np.max(np.abs(mode.contact_damping_ratio - (D - viscous))) < 1e-8
    # the first harmonic is the modal amplitude, in phase: a1 = A, b1 = 0
    c = mode.dof_coefficients(0)
    assert np.allclose(c[:, 1], A, rtol=1e-12) and np.all(np.abs(c[:, 2]) < 1e-12 * A)


def test_seven_harmonics_differ_from_the_describing_function_by_less_than_one_percent():
    """The higher harmonics of the stick-slip motion: the README states the difference (0.73 % in frequency,
    0.0085 in damping ratio, 3.4 % of it, between 6 and 8 times the slip displacement)."""
    mode = nonlinear_modes(jenkins(0.0), 1, (1e-7, 1e-2), harmonics=7, samples=2 ** 12)
    A = mode.modal_amplitude / np.sqrt(MASS)
    omega, D, _ = describing_function(A)
    # with c = 0 in the closed form's D (DAMPING is in it): rescale to the undamped oscillator
    D = D - DAMPING / (2 * MASS * omega)
    d_omega, d_D = mode.omega / omega - 1, mode.damping_ratio - D
    assert 1e-3 < np.max(np.abs(d_omega)) < 1e-2
    assert 1e-3 < np.max(np.abs(d_D)) < 0.1 * D.max()
    assert np.max(np.abs(d_omega[A < SLIP / KT])) < 1e-10  # stuck: linear, every harmonic but the first is zero


# -- a 2-DOF chain, the contact on the first mass ------------------------------------------------------
M2 = np.diag([1.0, 0.5])
K2 = np.array([[2e6, -1e6], [-1e6, 1e6]])
KT2, SLIP2 = 2e5, 10.0


def chain(C=None) -> Structure:
    s = Structure(M2, 1e-6 * K2 + 0.5 * M2 if C is None else C, K2)
    s.add_contact(MicroslipModel([KT2], [1e9], [0.0], 0.5), tangential=0, approach=SLIP2 / 0.5 / 1e9)
    return s


def test_small_amplitude_is_the_linear_mode_with_the_contacts_stuck():
    K_stuck = K2 + np.diag([KT2, 0.0])
    C = 3.0 * M2 + 2e-5 * K_stuck  # classical for the stuck structure: its mode is real, xi = 3 + 2e-5 lambda
    lam, vec = sla.eigh(K_stuck, M2)
    for k in (1, 2):
        mode = nonlinear_modes(chain(C), k, (1e-8, 1e-7), harmonics=3)  # below the slip displacement
        assert np.max(np.abs(mode.omega / np.sqrt(lam[k - 1]) - 1)) < 1e-8
        assert np.max(np.abs(mode.xi / (3.0 + 2e-5 * lam[k - 1]) - 1)) < 1e-8
        assert np.max(np.abs(mode.contact_damping_ratio)) < 1e-10
        phi = vec[:, k - 1] * np.sign(vec[np.argmax(np.abs(vec[:, k - 1])), k - 1])
        assert np.allclose(mode.linear_mode, phi, rtol=1e-10)
        shape = mode.coefficients[:, 1] / mode.modal_amplitude[:, None]  # a1 / a = phi
        assert np.max(np.abs(shape - phi)) < 1e-8 * np.max(np.abs(phi))


def test_large_amplitude_tends_to_the_sliding_mode():
    """Far in gross slip the contact force ``mu N sign(t')`` is bounded: the mode becomes that of the structure
    without the contact's tangential stiffness, and the contact dissipates ``4 mu N (|t| - mu N / k_t)`` per
    cycle, so its damping ratio falls like ``2 mu N |t| / (pi omega^2 a_s^2)`` with ``a_s`` the sliding mode's
    amplitude (``|t| = |phi_s,t| a_s``)."""
    mode = nonlinear_modes(chain(np.zeros((2, 2))), 1, (1e-3, 1e0), harmonics=3)
    lam, vec = sla.eigh(K2, M2)
    phi_s = vec[:, 0]
    a_s = mode.modal_amplitude[-1] / abs(mode.linear_mode @ M2 @ phi_s)  # a = phi^T M z_1, z_1 = a_s phi_s
    t = abs(phi_s[0]) * a_s
    assert t > 1e4 * SLIP2 / KT2
    assert abs(mode.omega[-1] / np.sqrt(lam[0]) - 1) < 1e-6  # the stick phases' stiffness: O((slip / t)^1.5)
    expected = 2 * SLIP2 * (t - SLIP2 / KT2) / (np.pi * lam[0] * a_s ** 2)
    assert abs(mode.contact_damping_ratio[-1] / expected - 1) < 1e-3  # higher harmonics of the motion: O(1e-4)
    assert np.all(np.diff(mode.omega) <= 1e-9 * mode.omega[0])  # softening all along


def test_the_damping_shares_add_up_and_the_contacts_dissipate():
    mode = nonlinear_modes(chain(), 1, (1e-6, 1e-2), harmonics=5)
    # the harmonics' energy balance: the work of -xi M q' equals the viscous and the contacts' (solver tolerance)
    total = mode.viscous_damping_ratio + mode.contact_damping_ratio
    assert np.max(np.abs(total - mode.damping_ratio)) < 1e-9  # measured 9e-11 (Newton's tolerance 1e-9)
    assert np.all(mode.contact_dissipation >= 0)
    # the friction work of the sampled period and the harmonics' agree where the contact slides (AFT: 1/Ns^2)
    slides = mode.contact_dissipation[:, 0] > 1e-3 * mode.contact_dissipation.max()
    assert np.allclose(mode.contact_dissipation[slides, 0], mode.contact_harmonic_work[slides, 0], rtol=0.02)


def modal_amplitude_of(curve, mode):
    """The forced response's modal amplitude ``|phi^T M z_1|`` at every point: the same measure as the mode's."""
    return curve.amplitude(curve.structure.M @ mode.linear_mode, 1)


def check_forced(structure, mode, force, window, *, dof, **kwargs):
    """The forced response's peak against the backbone and the synthesis; returns the three relative errors."""
    curve = frequency_response(structure, force, window, stability=False, control=StepControl(ds_max=0.01),
                               **kwargs)
    w_peak, a_peak = curve.peak(structure.M @ mode.linear_mode, 1)
    backbone = np.interp(np.log(a_peak), np.log(mode.modal_amplitude), mode.omega)
    synthesis = mode.forced_response(force)
    return (backbone / w_peak - 1, synthesis.peak()[1] / a_peak - 1,
            synthesis.peak(dof)[1] / curve.peak(dof, 1)[1] - 1)


@pytest.mark.parametrize("force", [3.0, 10.0])  # microslip (peak damping 0.9 %) and near gross slip (2.5 %)
def test_forced_peaks_lie_on_the_backbone_and_the_synthesis_matches_them(force):
    s = chain()
    mode = nonlinear_modes(s, 1, (1e-6, 1e-2), harmonics=5)
    w1 = mode.linear_frequency
    on_backbone, modal, dof = check_forced(s, mode, [0.0, force], (0.85 * w1, 1.05 * w1), dof=1, harmonics=5)
    assert abs(on_backbone) < 1e-3  # measured 6e-5 and 2e-5
    assert abs(modal) < 0.02 and abs(dof) < 0.02  # measured 0.04 % and 0.5 %


def anisotropic_block() -> Structure:
    """The example's block with springs of 10 and 30 N/µm along x and y: its stuck mode moves the contact along
    its normal too, so the normal load varies along the mode (the example's equal springs keep it constant)."""
    block = inclined_block()
    s = Structure(block.M, 0.4 * block.C, np.diag([1e7, 3e7]))
    c = block.contacts[0]
    s.add_contact(c.model, tangential=c.tangential, normal=c.normal, preload=c.preload, name=c.name)
    return s


def stuck_stiffness(s: Structure, mode) -> np.ndarray:
    """``K`` plus the stiffness of every contact element closed at the static state (the smallest gaps close
    first: as many as the result counts), along the contact's tangential and normal directions."""
    K = s.K.toarray() if hasattr(s.K, "toarray") else np.array(s.K)
    for c, contact in enumerate(s.contacts):
        model = contact.model
        closed = np.argsort(model.gaps)[:mode.static_closed_elements[c]]
        K += model.kt[closed].sum() * np.outer(contact.tangential, contact.tangential)
        K += model.kn[closed].sum() * np.outer(contact.normal, contact.normal)
    return K


def test_inclined_block_with_a_varying_normal_load():
    s = anisotropic_block()
    mode = nonlinear_modes(s, 1, (1e-9, 1e-6), harmonics=5, samples=512)
    normal = mode.contact_N[:, 0, 0]
    assert normal.max() - normal.min() > 1.0  # N: the mean normal load changes along the mode
    assert np.abs(mode.contact_n[-1, 0, 1:]).max() > 0.2 * np.abs(mode.contact_t[-1, 0, 1:]).max()
    # the first point is the stuck linear mode: the closed elements' stiffness along t and n
    lam = sla.eigh(stuck_stiffness(s, mode), s.M, eigvals_only=True)[0]
    assert abs(mode.omega[0] / np.sqrt(lam) - 1) < 1e-8
    w1 = mode.linear_frequency
    for force in (0.3, 0.6):  # N along x; damping at the peaks 3.5 % and 2.4 %
        on_backbone, modal, dof = check_forced(s, mode, [force, 0.0], (0.7 * w1, 1.05 * w1), dof=0, harmonics=5,
                                               samples=512)
        assert abs(on_backbone) < 1e-3  # measured 1.1e-4 and 1.9e-4
        assert abs(modal) < 0.02 and abs(dof) < 0.02  # measured below 0.3 %


def test_the_example_block_peaks_on_its_backbone():
    block = inclined_block()
    mode = nonlinear_modes(block, 1, (1e-9, 1e-5), harmonics=5, samples=512)
    for force in (0.6, 1.2):
        on_backbone, modal, _ = check_forced(block, mode, [force, 0.0], (12000, 16500), dof=0, harmonics=5,
                                             samples=512)
        assert abs(on_backbone) < 1e-3 and abs(modal) < 0.02  # measured 2e-4 and 0.2 %


# -- reductions -------------------------------------------------------------------------------------------
def long_chain() -> Structure:
    """A grounded chain of 6 masses with Rayleigh damping, contacts at its ends (the 4 inner DOFs condensed).

    Its stuck and sliding modes keep away from 3 and 5 times the first one's frequency: no internal
    resonance with the harmonics (a 10-mass chain has one, and its first mode folds back in amplitude)."""
    n = 6
    K = (np.diag(np.full(n, 2e6)) - np.diag(np.full(n - 1, 1e6), 1) - np.diag(np.full(n - 1, 1e6), -1))
    M = np.diag(np.linspace(0.1, 0.2, n))
    s = Structure(M, 2e-6 * K + 2.0 * M, K)
    for dof in (0, n - 1):
        s.add_contact(MicroslipModel([2e5, 1e5], [1e9, 1e9], [0.0, 0.0], 0.5), tangential=dof, approach=1e-8)
    return s


def test_exact_reduction_equals_every_dof_solved_and_modal_lies_within_its_estimate():
    s = long_chain()
    control = StepControl(ds_initial=0.2, ds_max=0.2)  # a few points: only the ends are compared
    full = nonlinear_modes(s, 1, (1e-5, 1e-2), harmonics=3, reduction="none", control=control)
    exact = nonlinear_modes(s, 1, (1e-5, 1e-2), harmonics=3, reduction="exact", control=control)
    modal = nonlinear_modes(s, 1, (1e-5, 1e-2), harmonics=3, reduction="modal", modes=3, control=control)
    assert exact.reduction == "exact" and exact.dofs.size == 2
    for end in (0, -1):  # both curves start and end exactly at the range's amplitudes
        assert abs(exact.omega[end] / full.omega[end] - 1) < 1e-8
        assert abs(exact.xi[end] / full.xi[end] - 1) < 1e-8
        assert abs(exact.contact_damping_ratio[end] - full.contact_damping_ratio[end]) < 1e-8
        # every DOF recovered from the contact DOFs, with the damping C - xi M
        assert np.allclose(exact.shape(end if end == 0 else exact.points - 1), full.coefficients[end],
                           atol=1e-8 * np.abs(full.coefficients[end]).max())
        # the modal reduction: its error in the first harmonic's stiffness bounds the frequency's
        assert abs(modal.omega[end] / full.omega[end] - 1) < max(modal.reduction_error, 1e-8)
    assert full.contact_damping_ratio.max() > 0.01 and full.omega[-1] < 0.95 * full.omega[0]  # through slip


def test_a_reduced_blade_starts_from_its_stuck_linear_mode():
    """A scikit-fem blade (384 DOFs) with four preloaded contacts under its platform, mass-proportional damping
    (classical whatever the contacts add): at small amplitude the mode on the contact DOFs is the whole stuck
    blade's eigenvalue, exactly with the exact reduction."""
    from microslip.fe import blade

    b = blade(300, contact_nodes=2)
    s = Structure(b.M, 200.0 * b.M, b.K, dof_map=b.dof_map)
    sphere = tune(Sphere.paper(), 37.5, elements=4)
    for node in b.platform_nodes:
        s.add_contact(sphere, tangential=f"{node}:x", normal={f"{node}:y": -1.0}, preload=25.0)
    exact = nonlinear_modes(s, 1, (1e-9, 1e-6), harmonics=3, reduction="exact")
    modal = nonlinear_modes(s, 1, (1e-9, 1e-6), harmonics=3, reduction="modal")
    assert exact.dofs.size == 8 and exact.complete and modal.complete
    lam = sla.eigh(stuck_stiffness(s, exact), s.M.toarray(), eigvals_only=True, subset_by_index=[0, 0])[0]
    assert abs(exact.omega[0] / np.sqrt(lam) - 1) < 1e-8 and abs(exact.xi[0] / 200.0 - 1) < 1e-8
    assert abs(modal.omega[0] / np.sqrt(lam) - 1) < modal.reduction_error
    assert exact.omega[-1] < 0.97 * exact.omega[0]  # the contacts slip by the end of the range
    assert abs(modal.omega[-1] / exact.omega[-1] - 1) < modal.reduction_error


def test_the_stuck_mode_of_a_large_sparse_structure_is_found_by_the_sparse_eigensolver():
    """Above 500 sparse DOFs the linear mode comes from shift-invert Lanczos: the same mode as a dense solution."""
    import scipy.sparse as sp

    from microslip.frequency.equations.epmc import SPARSE_EIGEN, stuck_mode

    n = SPARSE_EIGEN + 100
    K = sp.diags([np.full(n, 2e6), np.full(n - 1, -1e6), np.full(n - 1, -1e6)], [0, 1, -1], format="csr")
    M = sp.diags(np.linspace(0.1, 0.2, n), format="csr")
    s = Structure(M, None, K)
    s.add_contact(MicroslipModel([2e5, 1e5], [1e9, 1e9], [0.0, 1e-6], 0.5), tangential=3, normal=None,
                  approach=5e-7)  # the second element is open: only the first one's stiffness counts
    lam, phi, _, _ = stuck_mode(s, np.zeros(n), 2)
    K_stuck = K.toarray()
    K_stuck[3, 3] += 2e5
    lam_dense, vec = sla.eigh(K_stuck, M.toarray(), subset_by_index=[1, 1])
    assert abs(lam / lam_dense[0] - 1) < 1e-10
    assert abs(abs(phi @ M @ vec[:, 0]) - 1) < 1e-8 and phi[np.argmax(np.abs(phi))] > 0


# -- a cyclic sector in a nodal diameter ----------------------------------------------------------------
SECTORS = 6


def bladed_disk(C=None):
    """A 6-sector disk: each sector a blade (DOF 1) between its left and right disk DOFs (0, 2), a contact from
    the blade to the ground and an under-platform-like contact from the blade to the next sector's blade."""
    from microslip.frequency import CyclicStructure

    M = np.diag([0.1, 0.2, 0.1])
    K = np.array([[3e6, -1e6, -0.5e6], [-1e6, 2e6, -1e6], [-0.5e6, -1e6, 3e6]])
    d = CyclicStructure(M, 1e-6 * K + 2.0 * M if C is None else C, K, sectors=SECTORS, left=[0], right=[2])
    d.add_contact(MicroslipModel([3e5, 1e5], [1e9, 1e9], [0.0, 0.0], 0.5), tangential=1, approach=1e-8)
    d.add_contact(MicroslipModel([2e5], [1e9], [0.0], 0.5), tangential={1: 1.0, d.next(1): -1.0}, approach=1e-8)
    return d


@pytest.mark.parametrize("diameter", [0, SECTORS // 2])  # standing waves: one mode of the whole disk each
def test_a_sector_mode_equals_the_assembled_disks(diameter):
    """In diameters 0 and N/2 the sector's mode is a mode of the whole disk (every sector in phase, or in
    opposition); the disk's mass-normalised mode is the sector's over sqrt(N), so its modal amplitude is
    sqrt(N) times the sector's."""
    from microslip.frequency.equations.epmc import stuck_mode

    disk = bladed_disk()
    whole = disk.assembled()
    lam = stuck_mode(disk, np.zeros(disk.ndof), 1, diameter)[0]
    everyone = np.array([stuck_mode(whole, np.zeros(whole.ndof), j)[0] for j in range(1, whole.ndof + 1)])
    j = int(np.argmin(np.abs(everyone / lam - 1))) + 1
    assert abs(everyone[j - 1] / lam - 1) < 1e-12 and np.sum(np.abs(everyone / lam - 1) < 1e-6) == 1
    control = StepControl(ds_initial=0.2, ds_max=0.2)
    sector = nonlinear_modes(disk, 1, (1e-6, 1e-3), harmonics=3, nodal_diameter=diameter, control=control)
    full = nonlinear_modes(whole, j, (np.sqrt(SECTORS) * 1e-6, np.sqrt(SECTORS) * 1e-3), harmonics=3,
                           reduction="none", control=control)
    assert sector.engine_order == diameter and sector.contact_damping_ratio.max() > 0.03  # through slip
    for end in (0, -1):
        assert abs(sector.omega[end] / full.omega[end] - 1) < 1e-8
        assert abs(sector.xi[end] / full.xi[end] - 1) < 1e-8  # measured up to 1.7e-9
        assert abs(sector.contact_damping_ratio[end] - full.contact_damping_ratio[end]) < 1e-8


def test_a_travelling_wave_mode_peaks_under_its_engine_order():
    """Diameter 1: the sector's mode is a travelling wave (its stuck mode complex); at small amplitude its
    frequency is the disk's double eigenvalue of that diameter, and the sector's forced responses under engine
    order 1 peak on its backbone, the synthesis matching their peaks."""
    from microslip.frequency.equations.epmc import stuck_mode

    disk = bladed_disk(C=2.0 * np.diag([0.1, 0.2, 0.1]))  # mass-proportional: the linear mode stays undamped
    whole = disk.assembled()
    everyone = np.array([stuck_mode(whole, np.zeros(whole.ndof), j)[0] for j in range(1, 4)])
    mode = nonlinear_modes(disk, 1, (1e-6, 1e-2), harmonics=3, nodal_diameter=1)
    assert np.iscomplexobj(mode.linear_mode) and np.abs(mode.linear_mode.imag).max() > 0.1
    assert abs(mode.omega[0] / np.sqrt(everyone[1]) - 1) < 1e-8 and abs(everyone[2] / everyone[1] - 1) < 1e-12
    w = np.conj(disk.M @ mode.linear_mode)  # a = phi^H M z_1 over the sector's DOFs
    # N on the blade: microslip (damping ratio 1.2 % at the peak), gross slip (0.11 %); windows around the peaks
    for force, window in ((1.0, (0.97, 1.01)), (30.0, (0.8, 1.0))):
        curve = frequency_response(disk, [0.0, force, 0.0], tuple(np.multiply(window, mode.omega[0])), harmonics=3,
                                   engine_order=1, control=StepControl(ds_max=0.01))
        eta = [(c[:, 1] - 1j * c[:, 2]) for c in (curve.dof_coefficients(w.real), curve.dof_coefficients(w.imag))]
        a = np.abs(eta[0] + 1j * eta[1])
        k = int(np.argmax(a))  # the peak: a parabola through the highest point and its neighbours
        p = np.polyfit(curve.omega[k - 1:k + 2] - curve.omega[k], a[k - 1:k + 2], 2)
        w_peak = curve.omega[k] - p[1] / (2 * p[0])
        a_peak = np.polyval(p, w_peak - curve.omega[k])
        backbone = np.interp(np.log(a_peak), np.log(mode.modal_amplitude), mode.omega)
        assert abs(backbone / w_peak - 1) < 1e-3  # measured 6.7e-4 and 5e-6
        synthesis = mode.forced_response([0.0, force, 0.0])
        assert abs(synthesis.peak()[1] / a_peak - 1) < 0.02  # measured 0.09 % and 3e-5
        assert abs(synthesis.peak(1)[1] / curve.peak(1, 1)[1] - 1) < 0.02


def test_a_contact_on_its_plane_sticks_along_both_directions_in_the_linear_mode():
    """The stuck mode adds the closed elements' kt along the second tangential direction too: with x alone
    stiffened the second mode would be y's 5e4 N/m instead of 5e4 + 2e4."""
    from microslip import MicroslipModel, Structure
    from microslip.frequency.equations.epmc import stuck_mode

    s = Structure(np.eye(2), np.zeros((2, 2)), np.diag([1e4, 5e4]))
    s.add_contact(MicroslipModel(kt=[2e4], kn=[1e6], gaps=[0.0], mu=0.3), tangential=[{0: 1.0}, {1: 1.0}], normal=None,
                  approach=1e-6)
    lam1, phi1, _, _ = stuck_mode(s, np.zeros(2), 1)
    lam2, _, _, _ = stuck_mode(s, np.zeros(2), 2)
    assert lam1 == pytest.approx(3e4, rel=1e-12) and lam2 == pytest.approx(7e4, rel=1e-12)
    assert abs(phi1[0]) == pytest.approx(1.0, rel=1e-12)


def test_the_compiled_damped_balance_equals_the_reference_with_its_damping_subtracted():
    """The compiled evaluation adds ``-xi M`` to the damping inside the kernel; the reference evaluation
    of the same equations and the subtraction of ``omega xi M D x`` agree to rounding (1e-12 of the
    largest entry: a few operations per entry)."""
    from microslip.frequency.equations.epmc import DampedBalance

    hb = DampedBalance(chain(), 3, samples=64)
    assert hb.compiled
    x = np.random.default_rng(3).normal(size=hb.n) * 2e-6
    omega, hb.xi = 9000.0, 37.0
    R, J, Rw = hb._evaluate(x, omega)
    R0, J0, Rw0 = hb.evaluate_reference(x, omega)
    MDx = hb.MD @ x
    for got, want in ((R, R0 - omega * hb.xi * MDx), (J, J0 - omega * hb.xi * hb.MD), (Rw, Rw0 - hb.xi * MDx),
                      (hb._evaluate(x, omega, jacobian=False), R0 - omega * hb.xi * MDx)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * np.abs(want).max())
    hb.xi = 0.0
    np.testing.assert_array_equal(hb._evaluate(x, omega)[1], J0)


def test_a_branch_point_is_passed_on_the_same_branch_and_reported():
    """A 3-DOF chain whose mode meets a branch point at a modal amplitude near 3.0e-5 kg^1/2 m: the
    orientation of the curve changes sign there on a smooth stretch. Refusing every step across it
    (as past a corner) made the steps fall to the smallest and the curve creep to max_points (5000
    points, stuck at 3.01e-5); the mode now passes it and warns. Along the same branch: the step
    across it changes the frequency and the damping ratio by no more than the curve's steps
    elsewhere (a jump to another branch would), and the frequency keeps falling."""
    from microslip.frequency import BranchPointWarning

    M = np.diag([0.3, 0.5, 0.4])
    K = 1e6 * np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 2.0]])
    s = Structure(M, 1e-6 * K, K)
    for d in (0, 2):
        s.add_contact(MicroslipModel([4e5], [1e9], [0.0], 0.5), tangential=d, approach=5 / 0.5 / 1e9)
    with pytest.warns(BranchPointWarning, match=r"branch point at modal amplitude 3\.0") as caught:
        mode = nonlinear_modes(s, 1, (1e-6, 1e-4), harmonics=3)
    assert mode.complete and mode.points < 200
    a = mode.modal_amplitude
    assert np.all(np.diff(a) > 0)
    where = float(str(caught[0].message).split("modal amplitude ")[1].split()[0])
    k = int(np.searchsorted(a, where))  # the step from k - 1 to k crosses the branch point
    dw, dz = np.abs(np.diff(mode.omega)), np.abs(np.diff(mode.damping_ratio))
    assert dw[k - 1] <= dw.max() and dz[k - 1] <= dz.max()
    assert dw[k - 1] <= 2 * max(dw[k - 2], dw[k]) and dz[k - 1] <= 2 * max(dz[k - 2], dz[k])
    assert np.all(np.diff(mode.omega[k - 5:]) < 0)


def test_the_default_chord_rule_is_closer_to_the_curve_than_the_turn_rule_with_more_points():
    """The default step control (the chord rule on frequency and damping, ``CHORD_ERROR``) against the former
    default, the turn rule (``chord_error=None``: steps of 1/20 decade, turns of 0.1 rad) and the turn rule at
    steps of 1/40 decade, on a two-mass chain with one contact from stuck to gross slip; all against the turn rule
    at 4x shorter steps and turns, their points joined by straight lines in log amplitude (what a plot of the
    backbone shows). The chord rule takes fewer points than the turn rule needs for its error. Measured: 112
    points, errors 3.2e-4 (frequency) and 9.1e-4 (damping ratio) of their ranges; the turn rule 93 points at
    1.4e-3 and 1.1e-2, at 1/40 decade 169 points at the same errors (its largest is in the bend, where the
    turn, not the step's length, bounds the steps)."""
    from dataclasses import replace

    from microslip.frequency.analyses.nonlinear_modes import CHORD_ERROR, default_control

    s = Structure(np.diag([1.0, 0.5]), 0.5 * np.diag([1.0, 0.5]), np.array([[2e6, -1e6], [-1e6, 1e6]]))
    s.add_contact(MicroslipModel([2e5], [1e9], [0.0], 0.5), tangential=0, approach=2e-8)
    amplitude = (1e-6, 1e-2)
    assert default_control(*amplitude).chord_error == CHORD_ERROR  # the default
    turn = default_control(*amplitude, chord_error=None)
    finer = replace(turn, ds_initial=turn.ds_max / 2, ds_max=turn.ds_max / 2)
    fine = replace(turn, ds_initial=turn.ds_max / 4, ds_max=turn.ds_max / 4, max_angle=turn.max_angle / 4)
    ref, old, denser, new = (nonlinear_modes(s, 1, amplitude, harmonics=3, control=c)
                             for c in (fine, turn, finer, None))

    def error(m, q):
        between = np.interp(np.log(ref.modal_amplitude), np.log(m.modal_amplitude), getattr(m, q))
        return np.max(np.abs(between - getattr(ref, q))) / np.ptp(getattr(ref, q))

    assert new.points < denser.points
    for q in ("omega", "damping_ratio"):
        assert error(new, q) <= 0.5 * error(denser, q)
