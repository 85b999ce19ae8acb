"""The kernels compiled for other processors give the host's numbers.

numba compiles for the host's processor unless ``NUMBA_CPU_NAME`` names another. This file runs its own
:func:`compute` in fresh processes compiled for a generic x86-64 (SSE2, no fused multiply-add) and for an
AVX2 processor (``haswell``: 256-bit vectors, fused multiply-adds), each with a numba cache of its own in a
temporary folder (the caches of different targets never mix), and compares them with the host's:

* the marches (``simulate`` along one direction and on the plane: every recorded quantity and the state)
  bit for bit: their arithmetic is IEEE-rounded additions, products, divisions and square roots, which
  the compiler neither fuses nor reorders (no ``fastmath``), so vectors of any width give the same bits;
* the AFTs (``aft``, ``aft_plane``: forces and Jacobians) to ``RTOL`` = 1e-14 of each array's largest entry:
  their syntheses, transforms and sample sums are compiled with ``fastmath`` (sums reordered to the vector
  width, products fused into multiply-adds where the processor has them), so the targets' numbers differ
  by rounding, a few units of the last place of the largest entries (measured: up to 4.4e-16 between the
  generic target and this file's author's AVX2 host, none between ``haswell`` and that host), carried to
  the periodic state (whose tolerance is 32 ulps of the motion, 7e-15) and to the derivatives.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

#: the AFTs' tolerance, relative to each array's largest entry (see the module's note)
RTOL = 1e-14
TARGETS = ("generic", "haswell")
MARCHES = ("march", "plane")


def _model(rng, J):
    from microslip import MicroslipModel

    return MicroslipModel(kt=10 ** rng.uniform(6, 7, J), kn=10 ** rng.uniform(6, 7, J),
                          gaps=np.sort(rng.uniform(0, 1.5e-6, J)), mu=0.3)


def compute() -> dict:
    """Every number compared, from fixed inputs: ``{name: array}``; names start with the kernel's family."""
    from microslip.frequency import aft, aft_plane

    rng = np.random.default_rng(2024)
    out = {}
    # 13 elements: vector loops of any width have a remainder; n crosses every gap, elements open and close
    model = _model(rng, 13)
    k = np.arange(1500)
    t = np.column_stack([1.5e-6 * np.cos(2 * np.pi * k / 97), 0.8e-6 * np.sin(2 * np.pi * k / 97)])
    t += np.cumsum(rng.normal(0.0, 0.1e-6, (k.size, 2)), axis=0)
    n = 0.8e-6 + 0.9e-6 * np.sin(2 * np.pi * k / 331)
    for name, path in (("march", t[:, 0]), ("plane", t)):
        r = model.simulate(path, n)
        for field in ("T", "N", "friction_work", "Ti", "condition"):
            out[f"{name}_{field}"] = np.asarray(getattr(r, field))
        out[f"{name}_sliders"] = r.state.sliders
    H = 7
    for case in range(3):
        contact = _model(rng, 8)
        x = np.zeros((2, 2 * H + 1))
        x[:, 1:] = rng.normal(0.0, 0.4e-6, (2, 2 * H)) / np.repeat(np.arange(1, H + 1), 2) ** 2
        x[0, 1], x[1, 2] = (1.0, 0.6) if case else (0.3, 0.2)  # gross slip, microslip
        x[:, 1:3] *= 1e-6
        xn = np.zeros(2 * H + 1)
        xn[0], xn[1] = 1.2e-6, 0.25e-6
        for name, r in ((f"aft{case}", aft(contact, x[0], xn)), (f"aftplane{case}", aft_plane(contact, x, xn))):
            for field in ("T", "N", "dT_dt", "dT_dn", "dN_dn"):
                out[f"{name}_{field}"] = np.asarray(getattr(r, field))
    return out


@pytest.fixture(scope="module")
def targets(tmp_path_factory):
    """``{target: compute()}`` for each of :data:`TARGETS`, computed side by side in fresh processes."""
    import microslip

    folder = tmp_path_factory.mktemp("targets")
    src = str(Path(microslip.__file__).resolve().parents[1])
    runs = {}
    for cpu in TARGETS:
        env = dict(os.environ, NUMBA_CPU_NAME=cpu, NUMBA_CACHE_DIR=str(folder / f"cache-{cpu}"),
                   PYTHONPATH=os.pathsep.join([src, os.environ.get("PYTHONPATH", "")]), OPENBLAS_NUM_THREADS="1")
        env.pop("NUMBA_CPU_FEATURES", None)
        runs[cpu] = subprocess.Popen([sys.executable, __file__, str(folder / f"{cpu}.npz")], env=env,
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    results = {}
    for cpu, proc in runs.items():
        log, _ = proc.communicate(timeout=600)
        assert proc.returncode == 0, f"NUMBA_CPU_NAME={cpu}: exit {proc.returncode}\n{log[-3000:]}"
        with np.load(folder / f"{cpu}.npz") as data:
            results[cpu] = dict(data)
    return results


@pytest.fixture(scope="module")
def host():
    return compute()


@pytest.mark.parametrize("cpu", TARGETS)
def test_the_marches_are_the_hosts_bit_for_bit(targets, host, cpu):
    names = [k for k in host if k.split("_")[0] in MARCHES]
    assert len(names) == 12
    for name in names:
        got, want = targets[cpu][name], host[name]
        assert got.dtype == want.dtype and got.shape == want.shape, name
        assert np.ascontiguousarray(got).tobytes() == np.ascontiguousarray(want).tobytes(), name


@pytest.mark.parametrize("cpu", TARGETS)
def test_the_afts_are_the_hosts_to_rounding(targets, host, cpu):
    names = [k for k in host if k.split("_")[0] not in MARCHES]
    assert len(names) == 30
    for name in names:
        got, want = targets[cpu][name], host[name]
        scale = np.abs(want).max()
        assert scale > 0, name
        np.testing.assert_allclose(got, want, rtol=0, atol=RTOL * scale, err_msg=name)


if __name__ == "__main__":
    np.savez(sys.argv[1], **compute())
