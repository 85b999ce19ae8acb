"""Mistuned bladed disks: blade stiffness scatter, the assembled disk, each blade's peak, the amplification factor."""

import numpy as np
import pytest

from microslip import MicroslipModel, Sphere, tune
from microslip.frequency import CyclicStructure, frequency_point, frequency_response
from microslip.frequency.analyses.blade_peaks import amplification_factor, blade_peaks
from microslip.frequency.structures.mistuning import MAX_STD, blade_scatter, mistuned_disk
from test_cyclic import springs_matrix  # the same spring assembly

SPHERE = Sphere.paper()
MODEL = tune(SPHERE, 37.5, elements=4)
SECTORS = 5
# samples per period, a multiple of the sectors: sector k's signals are sector 0's shifted by a whole number of
# samples, so the disk's AFT samples every blade at the same phases as the sector's (see test_cyclic.py)
SAMPLES = 16 * SECTORS


def rubbing_sector():
    """Ring DOFs 0 (left) and 1 (right), platform 2 rubbing on the next sector's, blade tip 3 (excited)."""
    M = np.diag([0.05, 0.05, 0.08, 0.03])
    K = springs_matrix(4, [(0, 1, 4e6), (0, 2, 3e6), (1, 2, 3e6), (2, 3, 2e6), (0, None, 1e6), (1, None, 1e6)])
    d = CyclicStructure(M, 1e-6 * K + 2.0 * M, K, sectors=SECTORS, left=[0], right=[1])
    d.add_contact(MODEL, tangential={2: 1.0, d.next(2): -1.0}, approach=SPHERE.approach(20.0))
    f = np.zeros(4)
    f[3] = 3.0
    return d, f


def linear_sector(sectors=6):
    """Ring DOFs 0 (left) and 1 (right) held by stiff ground springs, a blade 2 on ring node 0; no contact.

    The ring spring between sectors couples the blades weakly: the tuned family of blade modes spans 4363 to
    4373 rad/s (0.2 %), less than the 1 % frequency scatter of a 2 % stiffness scatter, which localises the
    response on a few blades.
    """
    M = np.diag([0.01, 0.01, 0.1])
    K = springs_matrix(3, [(0, 1, 1e6), (0, 2, 2e6), (0, None, 2e7), (1, None, 2e7)])
    d = CyclicStructure(M, 1e-6 * K, K, sectors=sectors, left=[0], right=[1])
    f = np.zeros(3)
    f[2] = 1.0
    return d, f


# -- the scatter ---------------------------------------------------------------------------------------
def test_the_same_seed_and_sample_give_the_same_scatter_bit_for_bit():
    a = blade_scatter(24, 0.03, seed=7, sample=4)
    assert a.shape == (24,)
    np.testing.assert_array_equal(a, blade_scatter(24, 0.03, seed=7, sample=4))
    assert not np.array_equal(a, blade_scatter(24, 0.03, seed=7, sample=5))
    assert not np.array_equal(a, blade_scatter(24, 0.03, seed=8, sample=4))
    # normal(0, std) scaled: the same draw at another std is the same pattern, scaled
    np.testing.assert_allclose(blade_scatter(24, 0.01, seed=7, sample=4) * 3.0, a, rtol=1e-15, atol=0)
    np.testing.assert_array_equal(blade_scatter(24, 0.0, seed=7, sample=4), np.zeros(24))
    # 2000 draws of 24 blades: the sample standard deviation of 48000 values is within 2 % of std (5 sigma)
    draws = np.concatenate([blade_scatter(24, 0.03, seed=1, sample=k) for k in range(2000)])
    assert abs(draws.std() / 0.03 - 1.0) < 0.02 and abs(draws.mean()) < 5 * 0.03 / np.sqrt(draws.size)


# -- the assembled disk ----------------------------------------------------------------------------------
def test_one_scaled_blade_equals_the_disk_assembled_by_hand_and_its_linear_solution():
    # 3 sectors of ring node 0 (left), ring node 1 (right) and a blade 2 on node 0; the blade's stiffness is
    # K[i, j] with i, j in blade_dofs = (0, 2): the ring's spring to ground on node 0 and the blade spring scale
    N = 3
    M = np.diag([0.02, 0.02, 0.1])
    K = springs_matrix(3, [(0, 1, 3e6), (0, 2, 2e6), (0, None, 5e6)])
    C = 2e-6 * K + 1.0 * M
    d = CyclicStructure(M, C, K, sectors=N, left=[0], right=[1])
    delta = np.array([0.0, 0.1, -0.05])
    disk = mistuned_disk(d, delta, blade_dofs=[0, 2])
    # by hand: whole-disk DOFs ring 0..2, blades 3..5; sector s is (ring s, ring s+1, blade s)
    Mh, Ch, Kh = (np.zeros((2 * N, 2 * N)) for _ in range(3))
    for s in range(N):
        idx = [s, (s + 1) % N, N + s]
        Ks = K.copy()
        Ks[np.ix_([0, 2], [0, 2])] *= 1.0 + delta[s]
        Mh[np.ix_(idx, idx)] += M
        Ch[np.ix_(idx, idx)] += C
        Kh[np.ix_(idx, idx)] += Ks
    perm = [0, 3, 1, 4, 2, 5]  # assembled numbering: (ring s, blade s) of sector s at 2s, 2s + 1
    for A, B in ((disk.M, Mh), (disk.C, Ch), (disk.K, Kh)):
        np.testing.assert_allclose(A, B[np.ix_(perm, perm)], rtol=1e-15, atol=0)  # sums in another order
    np.testing.assert_array_equal(mistuned_disk(d, np.zeros(N)).K, d.assembled().K)
    # its linear response to a force on blade 1 alone, solved directly: (K - w^2 M + i w C) z = F, |z| per blade
    omega = 4000.0
    F = np.zeros(2 * N, dtype=complex)
    F[N + 1] = 5.0
    z = np.linalg.solve(Kh - omega**2 * Mh + 1j * omega * Ch, F)
    force = np.zeros(2 * N, dtype=complex)
    force[perm.index(N + 1)] = 5.0
    r = frequency_point(disk, force, omega, harmonics=1, reduction="exact")
    # Newton on a linear problem: one step from the start, the rest is the condensation's rounding
    np.testing.assert_allclose(blade_peaks(r, d, 2, harmonic=1), np.abs(z[N:]), rtol=1e-10)
    # the ring nodes are not retained (only blade 1's force is): recovered from the condensation, as exact
    assert not np.isin([0, 2, 4], r.dofs).any()
    np.testing.assert_allclose(blade_peaks(r, d, 0, harmonic=1), np.abs(z[:N]), rtol=1e-10)
    # one harmonic: max |q - q0| = |z| cos(theta), theta the phase of the nearest of 256 samples, |theta| <= pi/256
    sampled = blade_peaks(r, d, 2)
    assert np.all(sampled <= np.abs(z[N:]) * (1 + 1e-10)) and np.all(sampled >= np.abs(z[N:]) * np.cos(np.pi / 256))


def test_the_damper_dofs_can_be_kept_out_of_the_blade():
    from microslip.frequency import UnderPlatformDamper
    from microslip.frequency.structures.structure import Structure

    d, f = rubbing_sector()
    damper = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=300.0, retention=1e3)
    law = MicroslipModel([1e6], [1e8], [0.0], 0.5)
    damper.add_interface(law, points=[[-4e-3, 2e-3]], angle=2.356, platform={"x": 2, "y": 0})
    damper.add_interface(law, points=[[4e-3, 2e-3]], angle=0.785, platform={"x": d.next(2), "y": d.next(0)})
    with_damper = damper.attach(d)
    delta = np.linspace(-0.04, 0.04, SECTORS)
    disk = mistuned_disk(with_damper, delta, blade_dofs=range(d.ndof))
    tuned = with_damper.assembled()
    n = with_damper.independent.size
    assert isinstance(disk, Structure) and disk.ndof == tuned.ndof == SECTORS * n
    for s in range(SECTORS):
        blade = with_damper._whole_index(s, [0, 2, 3])  # the blade's own DOFs (ring 0, platform, tip)
        extra = with_damper._whole_index(s, damper.dofs)
        # the damper's retention springs (only on its own DOFs) are untouched, the blade's tip spring scaled
        np.testing.assert_array_equal(disk.K[np.ix_(extra, extra)], tuned.K[np.ix_(extra, extra)])
        assert disk.K[blade[2], blade[2]] == pytest.approx(tuned.K[blade[2], blade[2]] * (1 + delta[s]), rel=1e-15)
    np.testing.assert_array_equal(disk.M, tuned.M)
    np.testing.assert_array_equal(disk.static_force, tuned.static_force)
    assert [c.name for c in disk.contacts] == [c.name for c in tuned.contacts]


# -- zero scatter: the sector solution ---------------------------------------------------------------------
# EO 3 of 5 sectors: h EO folds past N/2 (diameters 2, 1, 2 for h = 1..3). The peak near the frequency given lies
# between the first family's frequencies with the contacts free (5.3e3 rad/s in diameter 1, 6.2e3 in 2) and
# stuck (7.8e3, 8.0e3): the contacts slip there
@pytest.mark.parametrize("engine_order, peak", [(1, 6700.0), (3, 7500.0)])
def test_zero_scatter_gives_the_cyclic_sector_solution_in_every_blade(engine_order, peak):
    d, f = rubbing_sector()
    disk = mistuned_disk(d, np.zeros(SECTORS))
    wave = d.travelling_wave(f, engine_order)
    for omega in (peak - 700.0, peak):  # below and at the peak (the contact slides there)
        sector = frequency_point(d, f, omega, harmonics=3, engine_order=engine_order, samples=SAMPLES)
        whole = frequency_point(disk, wave, omega, harmonics=3, reduction="exact", samples=SAMPLES)
        for harmonic in (None, 1, 3):
            # a travelling wave: every blade has sector 0's amplitude. Newton's tolerance (1e-9 on the scaled step
            # and residual) on both problems: 1e-8 of the amplitude; over a period (None), each blade's maximum
            # is sampled at its own phase: within 1 - cos(pi / 256) = 7.5e-5 (the nearest of 256 samples)
            rtol = 1e-8 if harmonic else 1 - np.cos(np.pi / 256)
            np.testing.assert_allclose(blade_peaks(whole, d, 3, harmonic=harmonic), sector.amplitude(3, harmonic)[0],
                                       rtol=rtol)
    # along a curve: every blade has the same curve, so the same refined peak; the tuned sector's own curve,
    # on other frequencies, has the same peak to the parabola's refinement of the discrete maximum
    window = (peak - 400.0, peak + 400.0)
    tuned = frequency_response(d, f, window, harmonics=1, engine_order=engine_order, samples=SAMPLES)
    curve = frequency_response(disk, wave, window, harmonics=1, reduction="exact", samples=SAMPLES, stability=False)
    peaks = blade_peaks(curve, d, 3, harmonic=1)
    np.testing.assert_allclose(peaks, peaks[0], rtol=1e-8)  # solver tolerance, as above
    assert amplification_factor(curve, tuned, d, 3, harmonic=1) == pytest.approx(1.0, abs=2e-3)  # measured 2e-4


# -- a linear disk with scatter ------------------------------------------------------------------------
def test_a_mistuned_linear_disk_amplifies_below_whiteheads_limit():
    d, f = linear_sector()
    N = d.sectors
    eo, window = 2, (4100.0, 4650.0)  # around the blade family, 4.37e3 rad/s, +-1 % scattered
    tuned = frequency_response(d, f, window, harmonics=1, engine_order=eo)
    whitehead = (1.0 + np.sqrt(N)) / 2.0
    wave = d.travelling_wave(f, eo)
    for sample in range(3):
        disk = mistuned_disk(d, blade_scatter(N, 0.02, seed=3, sample=sample))
        r = frequency_response(disk, wave, window, harmonics=1, reduction="exact", stability=False)
        peaks = blade_peaks(r, d, 2)
        factor = amplification_factor(r, tuned, d, 2)
        assert factor == peaks.max() / tuned.peak(2)[1]
        # measured 1.14, 1.14, 1.13 (20 samples: 1.02 to 1.19): the largest blade above the tuned peak, and
        # far below Whitehead's limit of 1.72 for 6 blades
        assert 1.0 < factor < whitehead
        assert peaks.min() < 0.95 * peaks.max()  # the blades no longer respond alike (measured 0.66 to 0.71)


# -- input checks ---------------------------------------------------------------------------------------
def test_inputs_are_checked_by_name():
    d, f = rubbing_sector()
    with pytest.raises(ValueError, match=f"std must lie in \\[0.0, {MAX_STD}\\], got -0.01"):
        blade_scatter(5, -0.01, seed=1, sample=0)
    with pytest.raises(ValueError, match="std must lie in .* got 0.5"):
        blade_scatter(5, 0.5, seed=1, sample=0)
    with pytest.raises(ValueError, match="sectors must be an integer >= 3, got 2"):
        blade_scatter(2, 0.01, seed=1, sample=0)
    # 1e6 blades at the largest std: a draw below -4 std (3.2e-5 per blade) about 32 times
    with pytest.raises(ValueError, match="std: blade [0-9]+ of 1000000 would have 1 \\+ delta = -[0-9.e-]+ <= 0 with "
                                         "std = 0.25 \\(a blade stiffness scatter is a few percent\\)"):
        blade_scatter(1_000_000, MAX_STD, seed=1, sample=0)
    with pytest.raises(TypeError, match="sample must be an integer, got 1.5"):
        blade_scatter(5, 0.01, seed=1, sample=1.5)
    with pytest.raises(ValueError, match="scatter must have shape \\(5,\\), one value per sector, got shape \\(4,\\)"):
        mistuned_disk(d, np.zeros(4))
    with pytest.raises(ValueError, match="scatter must be finite, got nan at flat index 2"):
        mistuned_disk(d, [0, 0, np.nan, 0, 0])
    with pytest.raises(ValueError, match="scatter: blade 1 of 5 would have 1 \\+ delta = -0.5 <= 0"):
        mistuned_disk(d, [0, -1.5, 0, 0, 0])
    with pytest.raises(ValueError, match="blade_dofs: DOF indices must lie in 0..3, got 0..7"):
        mistuned_disk(d, np.zeros(5), blade_dofs=[0, 7])
    with pytest.raises(ValueError, match="blade_dofs must name at least one DOF"):
        mistuned_disk(d, np.zeros(5), blade_dofs=[])
    with pytest.raises(TypeError, match="sector must be a microslip CyclicStructure, got Structure"):
        mistuned_disk(d.assembled(), np.zeros(5))
    with pytest.raises(ValueError, match="stiffness_scale must have one factor per sector \\(5\\), got 2"):
        d.assembled([1.0, 1.0])
    with pytest.raises(ValueError, match="stiffness_scale must be positive, got 0.0 at flat index 1"):
        d.assembled([1.0, 0.0, 1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="scaled_dofs is only used with stiffness_scale"):
        d.assembled(scaled_dofs=[0])
    disk = mistuned_disk(d, np.zeros(5))
    r = frequency_point(disk, d.travelling_wave(f, 1), 6000.0, harmonics=1, reduction="exact", samples=SAMPLES)
    with pytest.raises(ValueError, match="dof: DOF 4 is out of range"):
        blade_peaks(r, d, 4)
    with pytest.raises(ValueError, match="harmonic must be at most harmonics = 1, got 2"):
        blade_peaks(r, d, 3, harmonic=2)
    sector_point = frequency_point(d, f, 6000.0, harmonics=1, engine_order=1, samples=SAMPLES)
    with pytest.raises(ValueError, match="result must be a response of the whole disk assembled from sector "
                                         "\\(5 sectors, 15 DOFs\\), got one of 4 DOFs solved as a sector"):
        blade_peaks(sector_point, d, 3)
    with pytest.raises(ValueError, match="tuned must be the response of the cyclic sector \\(solved with "
                                         "engine_order\\), got one of a structure of 15 DOFs"):
        amplification_factor(r, r, d, 3)
    with pytest.raises(TypeError, match="tuned must be the FrequencyResponse of the cyclic sector, got float"):
        amplification_factor(r, 1.0, d, 3)
