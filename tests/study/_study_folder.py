"""A finished study folder to damage, and what its results are (the resumption and folder-fuzz tests)."""

import csv
import io
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

from _paths import REPO

#: three forced responses of the inclined block (the smallest study that leaves cases intact beside a damaged one)
THREE = 'base = "inclined_block.toml"\n[vary]\n"contact.sphere.preload" = ["25N", "37.5N", "50N"]\n'


def write_block(folder, study_text=None):
    """The inclined block's files in ``folder``; the study file (``study_text`` if given, else the example's)."""
    for name in ("inclined_block.toml", "sphere_4_elements.json"):
        shutil.copy(REPO / "examples" / name, Path(folder) / name)
    study = Path(folder) / "study.toml"
    study.write_text(study_text or (REPO / "examples" / "inclined_block_study.toml").read_text())
    return study


def solved(folder, client, study_text=THREE):
    """``(study file, results folder)``: the study written in ``folder`` and solved there once."""
    from microslip.study import sweep

    study = write_block(folder, study_text)
    sweep(study, client, out=folder / "reference", report=False)
    return study, folder / "reference"


def copy(reference, target):
    """A copy of a finished results folder."""
    shutil.copytree(reference, target)
    return target


def results(out):
    """The summary without its time column, and every case's curves from its file: what a rerun must give again."""
    rows = list(csv.DictReader(io.StringIO((out / "summary.csv").read_text())))
    curves = {}
    for path in sorted((out / "cases").glob("*.npz")):
        with np.load(path) as f:
            curves[path.stem] = {k: np.array(f[k]) for k in f.files if k.startswith("curve_")}
    return [{k: v for k, v in r.items() if k != "time (s)"} for r in rows], curves


def assert_same_results(out, reference):
    rows, curves = results(out)
    ref_rows, ref_curves = results(reference)
    assert rows == ref_rows
    assert curves.keys() == ref_curves.keys()
    for key, c in curves.items():
        assert c.keys() == ref_curves[key].keys()
        for name, values in c.items():
            assert np.array_equal(values, ref_curves[key][name], equal_nan=True), (key, name)


def rewrite_meta(path, change):
    """Rewrite a case file with its metadata changed by ``change(meta)`` (a valid archive, the same curves)."""
    with np.load(path) as f:
        meta = json.loads(str(f["meta"]))
        arrays = {k: np.array(f[k]) for k in f.files if k != "meta"}
    change(meta)
    buf = io.BytesIO()
    np.savez(buf, meta=np.array(json.dumps(meta)), **arrays)
    path.write_bytes(buf.getvalue())


def dead_pid():
    """The process id of a process that has ended."""
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def stale_lock(out, pid):
    """The lock file a run killed while it held ``out`` leaves: its record."""
    (out / ".sweep.lock").write_text(json.dumps({"pid": pid, "host": os.uname().nodename,
                                                 "started": "2024-05-01T10:00:00+00:00"}))


def cli_command(study, out, *options):
    """``microslip sweep`` run in a new Python process (the tests' sys.path)."""
    return [sys.executable, "-c", "import sys; from microslip.cli import main; sys.exit(main())", "sweep", str(study),
            "-o", str(out), *options]


def cli_env():
    return dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
