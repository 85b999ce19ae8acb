"""A mistuning Monte Carlo: each mistuned disk solved as the assembled disk, its amplification over the tuned sector."""

import numpy as np
import pytest

from microslip import Sphere, tune
from microslip.frequency import frequency_response
from microslip.frequency.analyses.blade_peaks import blade_peaks
from microslip.frequency.structures.mistuning import blade_scatter, mistuned_disk
from microslip.study import load_study, sweep

distributed = pytest.importorskip("dask.distributed")

SPHERE = Sphere.paper()
# tests/frequency/test_mistuning.py's rubbing sector: ring DOFs 0 (left) and 1 (right), a platform 2 rubbing on
# the next sector's, a blade tip 3 (excited); 80 samples per period, a multiple of the 5 sectors
SECTOR = """
title = "Five blades rubbing at their platforms"
[structure]
M = [[0.05, 0, 0, 0], [0, 0.05, 0, 0], [0, 0, 0.08, 0], [0, 0, 0, 0.03]]
K = [[8e6, -4e6, -3e6, 0], [-4e6, 8e6, -3e6, 0], [-3e6, -3e6, 8e6, -2e6], [0, 0, -2e6, 2e6]]
rayleigh = [2.0, 1e-6]
dofs = ["ring left", "ring right", "platform", "tip"]
[cyclic]
sectors = 5
left = [0]
right = [1]
engine_order = 1
[[contact]]
model = "sphere.json"
tangential = {{"2" = 1.0, "next:2" = -1.0}}
approach = {approach!r}
name = "platform"
[excitation]
h1 = [0, 0, 0, 3.0]
[sweep]
omega = [6300, 7100]
harmonics = 1
samples = 80
[output]
plot = ["tip"]
harmonic = 1
"""


@pytest.fixture
def mistuning_study(tmp_path):
    tune(SPHERE, 37.5, elements=4).save(tmp_path / "sphere.json")
    (tmp_path / "sector.toml").write_text(SECTOR.format(approach=float(SPHERE.approach(20.0))))
    study = tmp_path / "study.toml"
    study.write_text('base = "sector.toml"\n[mistuning]\nstd = 0.03\nsamples = 3\nseed = 4\n')
    return study


def test_each_mistuned_disk_is_the_assembled_disk_and_its_amplification_the_tuned_sectors(mistuning_study, tmp_path):
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0") as c, \
            distributed.Client(c) as client:
        result = sweep(mistuning_study, client, out=tmp_path / "out")
    study = load_study(mistuning_study)
    assert [c.mistuning_sample for c in result.cases] == [None, 0, 1, 2] and not result.failed
    cfg = study.configuration(result.cases[0])
    tuned = frequency_response(cfg.structure, cfg.force, cfg.omega, harmonics=1, samples=80, engine_order=1)
    assert result.rows[0]["peak tip (m)"] == tuned.peak(3, 1)[1]
    factors = result.amplification("tip")
    for k in (1, 2, 3):
        scatter = blade_scatter(5, 0.03, seed=4, sample=k - 1)
        disk = mistuned_disk(cfg.structure, scatter)
        whole = frequency_response(disk, cfg.structure.travelling_wave(cfg.force, 1), cfg.omega, harmonics=1,
                                   samples=80, reduction="exact", stability=False)
        peaks = blade_peaks(whole, cfg.structure, 3, harmonic=1)
        row = result.rows[k]
        assert row["peak tip (m)"] == peaks.max() and row["largest blade tip"] == int(np.argmax(peaks))
        assert factors[k - 1] == row["amplification tip"] == peaks.max() / tuned.peak(3, 1)[1]
    # mistuning localises the travelling wave: the largest blade exceeds the tuned peak, below Whitehead's limit
    assert np.all(factors > 1.0) and np.all(factors < (1 + np.sqrt(5)) / 2)
    report = (tmp_path / "out" / "report.md").read_text()
    assert "Distribution of the amplification factor" in report and "3 mistuned disks" in report


def test_the_engine_order_can_be_varied_from_the_sweep_table(mistuning_study):
    mistuning_study.write_text('base = "sector.toml"\n[vary]\n"sweep.engine_order" = [0, 2]\n')
    study = load_study(mistuning_study)
    assert [study.configuration(c).engine_order for c in study.cases()] == [0, 2]
    mistuning_study.write_text('base = "sector.toml"\n[vary]\n"sweep.engine_order" = [-1]\n')
    with pytest.raises(ValueError, match=r"\[sweep\] engine_order must be an integer >= 0, got -1"):
        load_study(mistuning_study)
