"""Cyclic symmetry: one sector under an engine-order excitation against the whole assembled disk."""

import numpy as np
import pytest

from microslip import Sphere, tune
from microslip.frequency import CyclicStructure, Structure, frequency_point

SPHERE = Sphere.paper()
MODEL = tune(SPHERE, 37.5, elements=4)
SECTORS = 7
# sector DOFs: 0 ring node (left boundary), 1 ring node (right boundary), 2 platform, 3 blade tip
M_SECTOR = np.diag([0.05, 0.05, 0.08, 0.03])  # the ring nodes' mass is split between the two sectors sharing them
SPRINGS = [(0, 1, 4e6), (0, 2, 3e6), (1, 2, 3e6), (2, 3, 2e6), (0, None, 1e6), (1, None, 1e6)]
F_TIP = 12.0  # N on the tip, first harmonic
# samples per period, a multiple of the sectors: sector k's signals are sector 0's shifted by k EO / N of a
# period, a whole number of samples, so the disk's AFT samples every sector at the same phases (with another
# number the sectors' sampling (aliasing) errors differ, about 1e-3 here at 64 samples)
SAMPLES = 16 * SECTORS


def springs_matrix(n, springs):
    """Stiffness (N/m) of springs ``(i, j, k)`` between DOFs ``i`` and ``j`` (``j`` None: to ground)."""
    K = np.zeros((n, n))
    for i, j, k in springs:
        K[i, i] += k
        if j is not None:
            K[j, j] += k
            K[i, j] -= k
            K[j, i] -= k
    return K


def sector_matrices():
    K = springs_matrix(4, SPRINGS)
    return M_SECTOR.copy(), 1e-6 * K + 2.0 * M_SECTOR, K


def add_contacts(s, own, nxt):
    """The two contacts of a sector: platforms rubbing (normal load held), tips joined through the platforms."""
    s.add_contact(MODEL, tangential={own(2): 1.0, nxt(2): -1.0}, approach=SPHERE.approach(20.0), name=None)
    s.add_contact(MODEL, tangential={own(3): 1.0, nxt(3): -1.0}, normal={own(2): 0.5, nxt(2): 0.5},
                  approach=SPHERE.approach(15.0))


def disk():
    M, C, K = sector_matrices()
    d = CyclicStructure(M, C, K, sectors=SECTORS, left=[0], right=[1])
    add_contacts(d, lambda i: i, d.next)
    return d


def whole_disk(engine_order):
    """The assembled disk: ring nodes 0..N-1, platforms N..2N-1, tips 2N..3N-1; travelling-wave force."""
    N = SECTORS
    g = lambda s, i: (s % N, (s + 1) % N, N + s % N, 2 * N + s % N)[i]  # noqa: E731
    M, C, K = (np.zeros((3 * N, 3 * N)) for _ in range(3))
    Ms, Cs, Ks = sector_matrices()
    for s in range(N):
        idx = [g(s, i) for i in range(4)]
        for A, a in ((M, Ms), (C, Cs), (K, Ks)):
            A[np.ix_(idx, idx)] += a
    full = Structure(M, C, K)
    for s in range(N):
        add_contacts(full, lambda i, s=s: g(s, i), lambda i, s=s: g(s + 1, i))
    f = np.zeros(3 * N, dtype=complex)
    phi = 2 * np.pi * engine_order / N
    for s in range(N):
        f[g(s, 3)] = F_TIP * np.exp(-1j * s * phi)  # sector s + 1 lags sector s by phi
    return full, f, g


@pytest.mark.parametrize("engine_order", [1, 5])  # EO = 5 of 7 sectors: h EO folds past N/2 (5, 3, 1 for h = 1..3)
@pytest.mark.parametrize("omega", [9000.0, 12000.0])
def test_a_sector_equals_the_whole_disk(engine_order, omega):
    d = disk()
    f = np.zeros(4)
    f[3] = F_TIP
    sector = frequency_point(d, f, omega, harmonics=3, engine_order=engine_order, samples=SAMPLES)
    full_s, full_f, g = whole_disk(engine_order)
    full = frequency_point(full_s, full_f, omega, harmonics=3, reduction="none", samples=SAMPLES)
    scale = np.max(np.abs(full.coefficients))
    assert sector.engine_order == engine_order and sector.reduction == "exact"
    for dof in range(4):  # every DOF of sector 0, the right boundary (next ring node) included
        np.testing.assert_allclose(sector.dof_coefficients(dof), full.dof_coefficients(g(0, dof)), rtol=0,
                                   atol=1e-8 * scale)
    for k in (1, 3, SECTORS - 1):  # expanded to other sectors
        np.testing.assert_allclose(sector.sector_coefficients(3, k), full.dof_coefficients(g(k, 3)), rtol=0,
                                   atol=1e-8 * scale)
    # per sector: the contacts' energy is one N-th of the disk's
    np.testing.assert_allclose(sector.contact_dissipation.sum(), full.contact_dissipation.sum() / SECTORS, rtol=1e-7)


def test_next_dofs_and_boundaries_are_checked():
    d = disk()
    with pytest.raises(ValueError, match="tangential: DOF 1 is on the right boundary"):
        d.add_contact(MODEL, tangential={1: 1.0}, approach=1e-6)
    with pytest.raises(ValueError, match="dof: DOF 9 is out of range for a sector with 4 DOFs"):
        d.next(9)
    with pytest.raises(ValueError, match="left and right must pair the boundary DOFs one to one"):
        CyclicStructure(*sector_matrices(), sectors=6, left=[0], right=[1, 2])
    with pytest.raises(ValueError, match="a DOF cannot be on both boundaries"):
        CyclicStructure(*sector_matrices(), sectors=6, left=[0], right=[0])
    with pytest.raises(ValueError, match="sectors must be"):
        CyclicStructure(*sector_matrices(), sectors=2, left=[0], right=[1])
    with pytest.raises(ValueError, match="engine_order must be given for a CyclicStructure"):
        frequency_point(d, [0, 0, 0, 1.0], 9000.0, harmonics=3)
    with pytest.raises(ValueError, match="engine_order is only for a CyclicStructure"):
        frequency_point(whole_disk(1)[0], np.ones(3 * SECTORS), 9000.0, harmonics=3, engine_order=1)
    with pytest.raises(ValueError, match="force: DOF 1 is on the right boundary"):
        frequency_point(d, [0, 1.0, 0, 0], 9000.0, harmonics=3, engine_order=1)
    with pytest.raises(ValueError, match="a CyclicStructure is solved with reduction=.exact. or .modal."):
        frequency_point(d, [0, 0, 0, 1.0], 9000.0, harmonics=3, engine_order=1, reduction="none")
    with pytest.raises(ValueError, match="engine_order must be"):
        d.travelling_wave([0, 0, 0, 1.0], -1)
    with pytest.raises(TypeError, match="force \\(a harmonic as key\\) must be an integer"):
        d.travelling_wave({"h1": [0, 0, 0, 1.0]}, 1)
    with pytest.raises(ValueError, match="force\\[1\\] must have one entry per DOF \\(4\\)"):
        d.travelling_wave([0, 1.0], 1)


def test_a_craig_bampton_sector_keeps_its_boundaries_and_equals_the_full_sector(tmp_path):
    from microslip.frequency import CraigBampton, craig_bampton

    # a sector whose blade is a chain of 8 DOFs: ring 0 (left), ring 1 (right), blade 2..9 (2 the platform)
    n = 10
    springs = [(0, 1, 4e6), (0, 2, 3e6), (1, 2, 3e6), (0, None, 1e6), (1, None, 1e6)]
    K = springs_matrix(n, springs + [(i, i + 1, 8e6) for i in range(2, n - 1)])
    M = np.diag([0.05, 0.05] + [0.02] * (n - 2))
    d = CyclicStructure(M, 1e-6 * K + 2.0 * M, K, sectors=SECTORS, left=[0], right=[1])
    d.add_contact(MODEL, tangential={2: 1.0, d.next(2): -1.0}, approach=SPHERE.approach(20.0))
    f = np.zeros(n)
    f[n - 1] = 3.0
    keep = [0, 1, 2, n - 1]
    ref = frequency_point(d, f, 5000.0, harmonics=3, engine_order=2, samples=SAMPLES)
    cb = craig_bampton(d, keep, modes=n - len(keep))  # every interior mode: the same structure in other coordinates
    assert isinstance(cb.structure, CyclicStructure) and list(cb.structure.left) == [0] and list(cb.structure.right) == [1]
    back = CraigBampton.load(cb.save(tmp_path / "sector.npz"))
    fr = np.zeros(cb.structure.ndof)
    fr[3] = 3.0
    for model in (cb, back):
        r = frequency_point(model.structure, fr, 5000.0, harmonics=3, engine_order=2, samples=SAMPLES)
        scale = np.abs(ref.coefficients).max()
        for k, dof in enumerate(keep):
            np.testing.assert_allclose(r.dof_coefficients(k), ref.dof_coefficients(dof), rtol=0, atol=1e-8 * scale)


def test_the_assembled_disk_is_the_whole_disk_built_by_hand():
    d = disk()
    whole = d.assembled()
    full, f, g = whole_disk(1)
    # assembled numbering: sector s's independent DOFs (ring 0, platform 2, tip 3) at 3s, 3s + 1, 3s + 2
    perm = np.array([g(s, i) for s in range(SECTORS) for i in (0, 2, 3)])
    for A, B in ((whole.M, full.M), (whole.C, full.C), (whole.K, full.K)):
        np.testing.assert_array_equal(A, B[np.ix_(perm, perm)])
    for A, B in zip(whole.contact_directions(), full.contact_directions()):
        np.testing.assert_array_equal(A, B[perm] if A.ndim == 2 else B)
    assert [c.name for c in whole.contacts[:3]] == ["contact0@0", "contact1@0", "contact0@1"]
    force = np.zeros(4)
    force[3] = F_TIP
    wave = d.travelling_wave(force, 1)
    assert list(wave) == [1]
    np.testing.assert_allclose(wave[1], f[perm], rtol=0, atol=1e-15 * F_TIP)  # exp(-i s phi), rounding only


# -- modal reduction of a sector ---------------------------------------------------------------------
def chain_sector(n, *, sparse=False, dashpot=0.0):
    """A sector: ring DOFs 0 (left) and 1 (right), a blade chain 2..n-1 (2 the platform, rubbing on the next's).

    ``dashpot`` (N s/m) grounds the middle of the chain: damping that is not proportional to M and K.
    """
    springs = [(0, 1, 4e6), (0, 2, 3e6), (1, 2, 3e6), (0, None, 1e6), (1, None, 1e6)]
    K = springs_matrix(n, springs + [(i, i + 1, 3e7 * n / 40) for i in range(2, n - 1)])  # the same chain for any n
    M = np.diag([0.05, 0.05] + [0.2 / (n - 2)] * (n - 2))
    C = 1e-6 * K + 2.0 * M
    C[n // 2, n // 2] += dashpot
    if sparse:
        import scipy.sparse as sps

        M, C, K = sps.csr_matrix(M), sps.csr_matrix(C), sps.csr_matrix(K)
    d = CyclicStructure(M, C, K, sectors=SECTORS, left=[0], right=[1])
    d.add_contact(MODEL, tangential={2: 1.0, d.next(2): -1.0}, approach=SPHERE.approach(20.0))
    f = np.zeros(n)
    f[n - 1] = 3.0
    return d, f


def modal_error(d, f, engine_order, modes, omega=3000.0):
    """``(response error, estimate)``: a modal sector against the exact one at one point, every DOF (relative)."""
    ref = frequency_point(d, f, omega, harmonics=3, engine_order=engine_order, samples=SAMPLES)
    r = frequency_point(d, f, omega, harmonics=3, engine_order=engine_order, samples=SAMPLES, reduction="modal",
                        modes=modes)
    assert r.reduction == "modal" and r.modes == modes and ref.reduction == "exact"
    scale = np.abs(ref.coefficients).max()
    error = max(np.abs(r.dof_coefficients(k) - ref.dof_coefficients(k)).max() for k in range(d.ndof)) / scale
    return error, r.reduction_error


@pytest.mark.parametrize("engine_order", [2, 5])  # 5 of 7 sectors: harmonics 1..3 in diameters 5, 3, 1
def test_a_modal_sector_converges_to_the_exact_cyclic_condensation(engine_order):
    d, f = chain_sector(40)
    errors = [modal_error(d, f, engine_order, m) for m in (3, 6, 12, 38)]
    # measured 3.2e-3, 6.3e-5, 1.1e-6: each doubling of the modes gains at least 20x (the omitted modes'
    # inertia and damping are carried to first order, so the error falls like (omega / cutoff)^4)
    for (coarse, _), (fine, _) in zip(errors[:2], errors[1:3]):
        assert fine < coarse / 20
    # every mode but the highest (38 of the 39 independent DOFs): the residual carries the last one, to
    # (omega / its frequency)^4 -- measured 1.9e-10
    assert errors[-1][0] < 1e-9
    # the estimate (the first harmonic's condensed stiffness at the point) follows the error within 50x
    # (measured: 3 to 28 times below it; the higher harmonics, nearer the cutoff, carry the rest)
    for error, estimate in errors:
        assert error / 50 < estimate < error * 50


def test_non_proportional_damping_couples_the_modes_and_still_converges():
    from microslip.frequency.reduction.choice import cyclic_linear_part
    from microslip.frequency.equations.hbm import excitation

    # a dashpot halfway up the chain: 20 % damping of the highest mode, coupling every mode to the others
    d, f = chain_sector(40, dashpot=300.0)
    linear = cyclic_linear_part(d, excitation(d, f, 3), 2, "modal", 6, 3)
    assert not any(m.diagonal for m in linear.diameters.values())  # the modal damping matrix is full
    errors = [modal_error(d, f, 2, m)[0] for m in (6, 12, 38)]
    # the kept-omitted coupling through C is carried to second order: measured 6.9e-4, 1.2e-4, 2.0e-6 (without
    # it 3e-2, 1e-2, 6e-4)
    assert errors[1] < errors[0] / 4 and errors[2] < 1e-5


def test_the_frequency_derivative_of_the_modal_stiffness_is_exact():
    from microslip.frequency.reduction.cyclic_modal import DiameterModes, ModalStack

    for dashpot in (0.0, 300.0):  # the diagonal and the coupled evaluation
        d, f = chain_sector(40, dashpot=dashpot)
        retained = np.array([1, 38])  # the platform and the tip, numbered among the independent DOFs
        stack = ModalStack([DiameterModes(*d.matrices(d.phase(h, 2)), retained, 10) for h in (1, 2, 3)], [1, 2, 3])
        assert stack.diagonal == (dashpot == 0.0)
        S, dS = stack(3000.0, True)
        step = 1e-3  # rad/s: central differences, truncation (1e-3 / 3000)^2 and rounding 1e-16 / 3e-7
        fd = (stack(3000.0 + step, False)[0] - stack(3000.0 - step, False)[0]) / (2 * step)
        np.testing.assert_allclose(dS, fd, rtol=0, atol=1e-8 * np.abs(dS).max())  # measured 5e-10


def test_a_large_modal_sector_uses_the_sparse_eigensolver_and_its_modes_are_exact():
    from microslip.frequency.reduction.choice import cyclic_linear_part
    from microslip.frequency.equations.hbm import excitation
    from microslip.frequency.reduction.modal import DENSE_EIGEN
    import scipy.linalg as sla

    d, f = chain_sector(DENSE_EIGEN + 100, sparse=True)
    linear = cyclic_linear_part(d, excitation(d, f, 3), 2, "modal", 10, 3)
    assert len(linear.diameters) == 3  # diameters 2, 3 (4 folded) and 1 (6 folded)
    for phi, modes in linear.diameters.items():
        M, _, K = d.matrices(phi)
        lam = sla.eigh(K.toarray(), M.toarray(), eigvals_only=True, subset_by_index=[0, 9])
        np.testing.assert_allclose(modes.eigenvalues, lam, rtol=1e-9)  # ARPACK's tolerance is machine precision
        Mm = modes.phi.conj().T @ (M @ modes.phi)
        np.testing.assert_allclose(Mm, np.eye(10), rtol=0, atol=1e-12)  # mass-normalised after Rayleigh-Ritz
    error, estimate = modal_error(d, f, 2, 10)
    assert error < 3e-5 and estimate < 3e-5  # measured 3.2e-6 and 1.6e-6


def test_a_modal_sector_with_a_damper_equals_the_exact_one():
    from microslip.frequency import UnderPlatformDamper

    d, f = chain_sector(30)
    upd = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=40.0, damping=200.0)
    a = np.radians(135.0)
    upd.add_interface(MODEL, points=[(-3e-3, 1e-3), (-2e-3, 2e-3)], angle=a, platform={"x": 2, "y": 3})
    upd.add_interface(MODEL, points=[(3e-3, 2e-3)], angle=np.radians(45.0), platform={"x": d.next(2), "y": d.next(3)})
    s = upd.attach(d)
    fs = np.zeros(s.ndof)
    fs[:f.size] = f
    # the damper body has no stiffness of its own: three zero eigenvalues in every diameter, kept as modes
    error, estimate = modal_error(s, fs, 2, s.independent.size - 1, omega=2500.0)
    assert error < 1e-8 and estimate < 1e-7  # every mode but the highest: measured 1.3e-9 and 6.7e-9
    r = frequency_point(s, fs, 2500.0, harmonics=3, engine_order=2, samples=SAMPLES, reduction="modal", modes=8)
    assert upd.static_balance(r) < 1e-10  # the static term is condensed exactly


def test_auto_chooses_modal_for_a_large_sector(monkeypatch):
    import microslip.frequency.reduction.choice as cb

    d, f = chain_sector(40)
    monkeypatch.setattr(cb, "EXACT_LIMIT", 30)
    r = frequency_point(d, f, 3000.0, harmonics=2, engine_order=2)
    assert r.reduction == "modal" and r.modes == 38  # min(60, independent DOFs - 1)
    monkeypatch.setattr(cb, "EXACT_LIMIT", 39)
    assert frequency_point(d, f, 3000.0, harmonics=2, engine_order=2).reduction == "exact"


@pytest.mark.parametrize("kwargs, message", [
    ({"reduction": "none"}, "a CyclicStructure is solved with reduction='exact' or 'modal'"),
    ({"reduction": "exact", "modes": 5}, "modes is used only with reduction='modal'"),
    ({"modes": 39}, "modes must be below the sector's 39 independent DOFs"),
    ({"modes": 0}, "modes"),
])
def test_modal_arguments_of_a_sector_are_checked(kwargs, message):
    d, f = chain_sector(40)
    with pytest.raises(ValueError, match=message):
        frequency_point(d, f, 3000.0, harmonics=2, engine_order=2, **kwargs)


def test_dofs_by_name_and_from_files(tmp_path):
    """With a DOF map a sector's boundaries, next-sector DOFs and scaled DOFs may be named as the configuration
    names them, and ``CyclicStructure.from_files`` reads a sector as ``Structure.from_files`` reads a structure
    (issue 24, item 18: both were a TypeError)."""
    from microslip.fe import DofMap

    M, C, K = sector_matrices()
    names = DofMap([1014, 2014, 3000, 4000], ["x"] * 4)
    by_name = CyclicStructure(M, C, K, sectors=SECTORS, left=["1014:x"], right="2014:1", dof_map=names)
    np.testing.assert_array_equal(by_name.left, [0])
    np.testing.assert_array_equal(by_name.right, [1])
    assert by_name.next("3000:x") == disk().next(2)
    add_contacts(by_name, lambda i: i, by_name.next)
    whole = by_name.assembled(np.linspace(0.9, 1.1, SECTORS), scaled_dofs=["4000:x"])
    np.testing.assert_array_equal(whole.K, disk().assembled(np.linspace(0.9, 1.1, SECTORS), scaled_dofs=[3]).K)
    with pytest.raises(ValueError, match="left\\[1\\]: DOF '1015:x': node 1015 is not in the DOF map"):
        CyclicStructure(M, C, K, sectors=SECTORS, left=["1014:x", "1015:x"], right=[1, 2], dof_map=names)
    with pytest.raises(TypeError, match="left must be a list of DOF indices, got \\['1014:x'\\] \\(DOF names such as "
                                        "'1204:x' need a DOF map"):
        CyclicStructure(M, C, K, sectors=SECTORS, left=["1014:x"], right=[1])
    with pytest.raises(ValueError, match="right must not repeat a DOF: DOF 1 appears 2 times"):
        CyclicStructure(M, C, K, sectors=SECTORS, left=[0, 2], right=["2014:x", 1], dof_map=names)

    np.savez(tmp_path / "sector.npz", M=M, C=C, K=K)
    names.to_csv(tmp_path / "sector_dofs.csv")
    read = CyclicStructure.from_files(tmp_path / "sector.npz", sectors=SECTORS, dof_map=tmp_path / "sector_dofs.csv",
                                      left=["1014:x"], right=["2014:x"])
    assert isinstance(read, CyclicStructure) and read.sectors == SECTORS and read.dof_map == names
    np.testing.assert_array_equal(read.K, K)
    np.testing.assert_array_equal(read.right, [1])
