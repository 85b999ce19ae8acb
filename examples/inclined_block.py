"""Harmonic balance against time integration: a block pressed on an inclined plane.
================================================================================

A 0.1 kg block on two springs (x and y, 10 N/µm each) is pushed by a static force of
37.5 N (the contact's ``preload``) against a plane inclined at 30 degrees; the contact is
the paper's steel sphere tuned with 4 elements at 37.5 N. The preload is a force on the
block, so the springs take part of it: at the static equilibrium the contact carries
21.4 N, with 3 of its 4 elements closed and no tangential force (the springs are alike
in x and y, so the block moves straight along the normal). Both the tangential
displacement and the normal approach move with x and y, so the normal load -- and its
share among the elements -- varies along the cycle. The block is shaken along x with
0.6 N.

The script computes the forced response (H = 7) and compares it with explicit time
integration of the same structure and contact to the periodic steady state at five
frequencies including the resonance peak, then shows the harmonic truncation error
at the peak as H grows. Run ``python examples/inclined_block.py [--out DIR]``; it prints both
tables and writes them to ``inclined_block.csv`` and ``inclined_block_truncation.csv`` in ``DIR``
(default ``./microslip-examples``). The same structure is the configuration ``inclined_block.toml``
of ``microslip frf``.
"""

from __future__ import annotations

import argparse
import csv
from pathlib import Path

import numpy as np

from microslip import Sphere, Structure, frequency_response, tune
from microslip.frequency import frequency_point
from microslip.frequency.analyses.transient import steady_state

FORCE = [0.6, 0.0]  # N along x: partial slip, varying normal load, the contact never opens
RANGE = (12000.0, 16500.0)  # rad/s, around the first resonance


def inclined_block(sparse: bool = False) -> Structure:
    """The block and its contact (SI units); ``sparse`` stores the matrices as scipy.sparse."""
    M = 0.1 * np.eye(2)
    K = np.diag([1e7, 1e7])
    C = 2 * 0.005 * np.sqrt(3e7 / 0.1) * M
    if sparse:
        import scipy.sparse as sp

        M, C, K = sp.csr_matrix(M), sp.csr_matrix(C), sp.csr_matrix(K)
    block = Structure(M, C, K)
    a = np.radians(30)
    block.add_contact(tune(Sphere.paper(), 37.5, elements=4), tangential=[np.cos(a), np.sin(a)],
                      normal=[-np.sin(a), np.cos(a)], preload=37.5, name="sphere")
    return block


def compare(curve, omegas, steps_per_period=2048):
    """Rows ``(omega, HB amplitude, time-integration amplitude, relative difference)`` (x, first harmonic).

    The curve must be single-valued at ``omegas`` (one steady state per frequency).
    """
    rows = []
    for w in omegas:
        a = frequency_point(curve.structure, FORCE, w, harmonics=curve.harmonics).amplitude(0, 1)[0]
        ss = steady_state(curve.structure, FORCE, w, steps_per_period=steps_per_period, tolerance=1e-8)
        rows.append((w, a, ss.amplitude(0, 1), a / ss.amplitude(0, 1) - 1))
    return rows


def truncation(structure, omega, harmonics=(1, 2, 3, 5, 7, 11, 15)):
    """Rows ``(H, relative error of max |x - x0|)`` against time integration at ``omega``."""
    ss = steady_state(structure, FORCE, omega, steps_per_period=2048, tolerance=1e-8)
    rows = []
    for H in harmonics:
        r = frequency_point(structure, FORCE, omega, harmonics=H)
        rows.append((H, r.amplitude(0)[0] / ss.amplitude(0) - 1))
    return rows


def _write(path: Path, header: list, rows) -> None:
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        writer.writerows([repr(float(v)) if not isinstance(v, int) else str(v) for v in row] for row in rows)


def main(out=Path("microslip-examples")) -> tuple[list, list]:
    """Print the comparison and the truncation tables and write them as CSV into the folder ``out``;
    returns their rows (see :func:`compare` and :func:`truncation`)."""
    out = Path(out)
    block = inclined_block()
    curve = frequency_response(block, FORCE, RANGE, harmonics=7)
    w_peak, _ = curve.peak(0, 1)
    print(f"curve: {curve.points} points in {curve.elapsed:.3f} s; peak at {w_peak:.1f} rad/s")
    print("omega (rad/s)   HB x1 (um)   time integration x1 (um)   difference")
    rows = compare(curve, [12500.0, 14500.0, w_peak, 15900.0, 16400.0])
    for w, a, b, d in rows:
        print(f"{w:12.1f}   {a * 1e6:10.5f}   {b * 1e6:12.5f}              {d:+.2e}")
    print("H    error of max |x - x0| at the peak")
    errors = truncation(block, w_peak)
    for H, e in errors:
        print(f"{H:2d}   {e:+.2e}")
    out.mkdir(parents=True, exist_ok=True)
    _write(out / "inclined_block.csv", ["omega [rad/s]", "harmonic balance x1 [m]", "time integration x1 [m]",
                                        "difference [-]"], rows)
    _write(out / "inclined_block_truncation.csv", ["harmonics H", "error of max |x - x0| at the peak [-]"], errors)
    print(f"wrote {out / 'inclined_block.csv'} and {out / 'inclined_block_truncation.csv'}")
    return rows, errors


def folder(value: str) -> Path:
    """The ``--out`` folder (created by :func:`main` if needed); a file there is refused."""
    path = Path(value)
    if path.exists() and not path.is_dir():
        raise argparse.ArgumentTypeError(f"{path} is a file, not a folder")
    return path


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description="Harmonic balance against time integration for a block pressed on "
                                                 "an inclined plane (writes inclined_block.csv and "
                                                 "inclined_block_truncation.csv).")
    parser.add_argument("--out", type=folder, default=Path("microslip-examples"),
                        help="folder to write into (created if needed; default ./microslip-examples)")
    main(parser.parse_args().out)
