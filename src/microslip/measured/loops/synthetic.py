"""The synthetic cylinder-on-flat data set shipped with microslip (SYNTHETIC, not measured).

The paper's measured loops of a cylinder on a plane (Sect. 3, Fig. 6) are
not public. This module generates a stand-in with a physically grounded
model, reproducibly (fixed seed), so that the path *data file -> loop
analysis -> fit -> tuning -> validation* can be exercised and the paper's
Fig. 6 drawn from a file through the same code a user runs.

The model of the specimen
-------------------------
A steel cylinder, l = d = 10 mm (E = 200 GPa, nu = 0.3), on a steel flat,
mu = 0.4, with ground surfaces:

* **normal law**: the approach is the Lundberg--Sjövall approach of the
  smooth line contact plus the approach of the surface roughness,
  ``n(N) = n_LS(N) + n_r (N / N_r)^(1/m)`` with ``n_r = 0.25 µm`` at
  ``N_r = 36.6 N`` and ``m = 2`` (asperity layers stiffen with load, their
  load grows about as the square of their approach at light loads);
* **tangential law**: Ciavarella--Jäger superposition, exact for the
  method of dimensionality reduction (MDR) and used for rough contacts as
  well: ``T(t, n) = mu [N(n) - N(n - t G*_P / (mu E*))]`` with
  ``G*_P / E* = 2 (1 - nu) / (2 - nu)`` for identical bodies; unloading and
  reloading follow from the same element-by-element Coulomb law (Masing).

It is realised as a fine MDR-like array of 3000 macroslip elements
(:func:`specimen_model`): gaps ``g_k`` on a grid of approach, normal
stiffnesses from the jumps in slope of the normal law between grid points,
``kt_k = (G*_P / E*) kn_k``. Each record is a sinusoidal displacement
(20 Hz, 400 samples per cycle) started from rest (so the first quarter
cycle is the virgin curve), 6 cycles at a displacement amplitude of
0.35 µm (gross slip at every load), at 5 normal loads from 16.4 N to
36.6 N. Sensor effects: Gaussian noise of 2 nm on the displacement (laser
vibrometer), 0.04 N on the tangential force, 0.1 N on the normal load;
offsets of +12 nm and +0.06 N.

Run ``python scripts/make_cylinder_data.py`` to write the files again (the
output is identical for the same seed, NumPy and this module).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...common._io import atomic_write
from ...model import MicroslipModel
from ...reference.cylinder import Cylinder


@dataclass(frozen=True)
class Specimen:
    """Parameters of the synthetic specimen and test (SI units); see the module docstring."""

    length: float = 10e-3
    radius: float = 5e-3
    E: float = 200e9
    nu: float = 0.3
    mu: float = 0.4
    roughness_approach: float = 0.25e-6
    roughness_load: float = 36.6
    roughness_exponent: float = 2.0
    loads: tuple = (16.4, 21.5, 26.5, 31.6, 36.6)
    amplitude: float = 0.35e-6
    frequency: float = 20.0
    samples_per_cycle: int = 400
    cycles: int = 6
    noise_t: float = 2e-9
    noise_T: float = 0.04
    noise_N: float = 0.1
    offset_t: float = 12e-9
    offset_T: float = 0.06
    elements: int = 3000
    seed: int = 20240611

    @property
    def stiffness_ratio(self) -> float:
        """``G*_P / E* = kt / kn = 2 (1 - nu) / (2 - nu)`` for identical bodies."""
        return 2.0 * (1.0 - self.nu) / (2.0 - self.nu)

    def approach(self, N):
        """Approach of the specimen (m) at load ``N`` (N): Lundberg--Sjövall plus roughness."""
        N = np.asarray(N, dtype=float)
        smooth = Cylinder(self.length, self.radius, self.E, self.nu, law="lundberg").approach(N)
        return smooth + self.roughness_approach * (N / self.roughness_load) ** (1.0 / self.roughness_exponent)

    def gross_slip_displacement(self, N):
        """Gross-slip displacement of the specimen's backbone (m) at load ``N`` (N): ``mu n(N) / (G*_P/E*)``."""
        return self.mu * self.approach(N) / self.stiffness_ratio

    def initial_stiffness(self, N):
        """Initial tangential stiffness (N/m) at load ``N`` (N): ``(G*_P/E*) dN/dn``."""
        N = np.asarray(N, dtype=float)
        h = 1e-6 * N
        return self.stiffness_ratio * 2 * h / (self.approach(N + h) - self.approach(N - h))


def specimen_model(spec: Specimen = Specimen(), top_load: float | None = None) -> MicroslipModel:
    """The fine MDR-like array realising the specimen up to ``top_load`` (N; default 1.1 x the largest load)."""
    top = 1.1 * max(spec.loads) if top_load is None else float(top_load)
    # a grid in load, fine where the curve bends most (near zero load)
    N = top * np.linspace(0.0, 1.0, spec.elements + 1) ** 2
    n = spec.approach(N)
    slope = np.diff(N) / np.diff(n)
    kn = np.diff(np.concatenate([[0.0], slope]))
    keep = kn > 0
    kn, gaps = kn[keep], n[:-1][keep]
    return MicroslipModel(kt=spec.stiffness_ratio * kn, kn=kn, gaps=gaps, mu=spec.mu)


def record(spec: Specimen, load: float, rng: np.random.Generator, model: MicroslipModel | None = None):
    """One synthetic record at ``load`` (N): ``(time s, t m, T N, N N)``, with noise and offsets."""
    model = specimen_model(spec) if model is None else model
    steps = spec.cycles * spec.samples_per_cycle + 1
    time = np.arange(steps) / (spec.samples_per_cycle * spec.frequency)
    t = spec.amplitude * np.sin(2.0 * np.pi * spec.frequency * time)
    T = model.simulate(t, float(spec.approach(load)), per_element=False).T
    return (time,
            t + spec.offset_t + rng.normal(0.0, spec.noise_t, steps),
            T + spec.offset_T + rng.normal(0.0, spec.noise_T, steps),
            load + rng.normal(0.0, spec.noise_N, steps))


def file_name(load: float) -> str:
    """File name of the record at ``load`` (N)."""
    return f"cylinder_{load:.1f}N.csv"


def write_dataset(out_dir, spec: Specimen = Specimen()) -> list[Path]:
    """Write one CSV per load and the normal curve ``cylinder_normal.csv`` into ``out_dir``."""
    out_dir = Path(out_dir)
    rng = np.random.default_rng(spec.seed)
    model = specimen_model(spec)
    paths = []
    header = _header(spec)
    for load in spec.loads:
        time, t, T, N = record(spec, load, rng, model)
        lines = [f"# {h}" for h in header] + [f"# normal load = {load:g} N", "time [s],t [um],T [N],N [N]"]
        lines += [f"{a:.6f},{b * 1e6:.5f},{c:.4f},{d:.3f}" for a, b, c, d in zip(time, t, T, N)]
        paths.append(atomic_write(out_dir / file_name(load), "\n".join(lines) + "\n"))
    loads = np.linspace(0.0, 1.1 * max(spec.loads), 23)
    lines = [f"# {h}" for h in header] + [
        "# the specimen's normal force-approach curve (smooth: the curve fitted to a normal-load test)",
        "n [um],N [N]"]
    lines += [f"{a * 1e6:.6f},{b:.3f}" for a, b in zip(spec.approach(loads), loads)]
    paths.append(atomic_write(out_dir / "cylinder_normal.csv", "\n".join(lines) + "\n"))
    return paths


def _header(spec: Specimen) -> list[str]:
    return [
        "SYNTHETIC DATA - NOT MEASURED. Generated by microslip.loops.synthetic (scripts/make_cylinder_data.py).",
        f"Steel cylinder l = {spec.length * 1e3:g} mm, d = {2e3 * spec.radius:g} mm on a steel flat, "
        f"E = {spec.E / 1e9:g} GPa, nu = {spec.nu:g}, mu = {spec.mu:g}.",
        "Model: MDR-like array (Ciavarella-Jaeger superposition) on a normal law = Lundberg-Sjovall + "
        f"roughness ({spec.roughness_approach * 1e6:g} um at {spec.roughness_load:g} N, exponent "
        f"{spec.roughness_exponent:g}).",
        f"Test: sinusoidal displacement {spec.amplitude * 1e6:g} um, {spec.frequency:g} Hz, {spec.cycles} cycles "
        f"from rest; noise {spec.noise_t * 1e9:g} nm / {spec.noise_T:g} N / {spec.noise_N:g} N; offsets "
        f"{spec.offset_t * 1e9:g} nm / {spec.offset_T:g} N; seed {spec.seed}.",
    ]


def dataset_dir() -> Path:
    """Folder of the shipped data set (``microslip/data``)."""
    return Path(__file__).resolve().parents[2] / "data"  # microslip/data


def dataset_files() -> list[Path]:
    """The shipped loop files, lowest load first."""
    return [dataset_dir() / file_name(load) for load in Specimen().loads]


def normal_curve_file() -> Path:
    """The shipped normal force-approach table."""
    return dataset_dir() / "cylinder_normal.csv"
