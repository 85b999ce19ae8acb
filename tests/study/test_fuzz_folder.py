"""A finished study's folder fuzzed: damaged case files, leftovers, a run killed at random, two runs at once.

Every rerun must end as a clean run did (the same summary and curves, bit for
bit), with the exit status documented (0: every case solved; 2: the folder in
use by another run), naming each case file it did not trust and never
printing a traceback.
"""

import json
import os
import re
import signal
import subprocess
import time

import numpy as np
import pytest
from _study_folder import assert_same_results, cli_command, cli_env, copy, dead_pid, rewrite_meta, stale_lock

from microslip.cli import main
from microslip.study import load_study
from microslip.study.folder import leftovers
from microslip.study.store import case_file

distributed = pytest.importorskip("dask.distributed")


@pytest.fixture(scope="module")
def client():
    """Two single-threaded workers in this process, reached over TCP: runs in other processes share them."""
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, protocol="tcp",
                                  dashboard_address=":0") as c, distributed.Client(c) as cl:
        yield cl


def _truncate(path, rng, cases):
    data = path.read_bytes()
    path.write_bytes(data[:rng.integers(0, len(data))])


def _flip(path, rng, cases):
    data = bytearray(path.read_bytes())
    data[rng.integers(0, len(data))] ^= 1 << int(rng.integers(0, 8))
    path.write_bytes(bytes(data))


def _empty(path, rng, cases):
    path.write_bytes(b"")


def _drop_key(path, rng, cases):
    name = str(rng.choice(["key", "values", "mistuning_sample", "row", "error", "warnings", "time"]))
    rewrite_meta(path, lambda meta: meta.pop(name))


def _wrong_type(path, rng, cases):
    name, value = [("row", []), ("values", 3), ("time", "1 s"), ("error", None), ("key", 7),
                   ("row", {"complete": "yes"})][rng.integers(0, 6)]
    rewrite_meta(path, lambda meta: meta.update({name: value}))


def _another_case(path, rng, cases):
    others = [c for c in cases if case_file(path.parent.parent, c) != path]
    path.write_bytes(case_file(path.parent.parent, others[rng.integers(0, len(others))]).read_bytes())


def _random_bytes(path, rng, cases):
    path.write_bytes(rng.bytes(int(rng.integers(1, 20000))))


def _not_an_object(path, rng, cases):
    with np.load(path) as f:
        arrays = {k: np.array(f[k]) for k in f.files if k != "meta"}
    np.savez(path.with_suffix(""), meta=np.array(json.dumps(["a", "list"])), **arrays)


DAMAGES = [_truncate, _flip, _empty, _drop_key, _wrong_type, _another_case, _random_bytes, _not_an_object]


def _plant_leftovers(out, rng, key):
    """Some of what SIGKILL leaves during atomic writes, the Zarr store's replacement and the report."""
    names = [f"cases/.{key}.npz.{_random_name(rng)}.tmp", f".summary.csv.{_random_name(rng)}.tmp",
             f".summary.parquet.{_random_name(rng)}.tmp", f".report.md.{_random_name(rng)}.tmp",
             f".curves.png.{_random_name(rng)}.tmp", f".curves.{_random_name(rng)}.tmp/store.zarr/omega/0",
             f".curves.zarr.old.{rng.integers(2, 99999)}/zarr.json"]
    planted = [n for n in names if rng.random() < 0.6]
    for name in planted:
        path = out / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(rng.bytes(int(rng.integers(0, 500))))
    return planted


def _random_name(rng):
    return "".join(rng.choice(list("abcdefghijklmnopqrstuvwxyz0123456789_"), 8))


@pytest.mark.parametrize("seed", range(5))
def test_a_damaged_folder_resumes_to_the_results_of_a_clean_run(finished, tmp_path, client, capsys, seed):
    rng = np.random.default_rng(seed)
    study_file, reference = finished
    out = copy(reference, tmp_path / "out")
    cases = load_study(study_file).cases()
    damaged = sorted(rng.choice(len(cases), size=int(rng.integers(1, len(cases) + 1)), replace=False))
    for i in damaged:
        DAMAGES[rng.integers(0, len(DAMAGES))](case_file(out, cases[i]), rng, cases)
    planted = _plant_leftovers(out, rng, cases[0].key)
    if rng.random() < 0.5:
        stale_lock(out, dead_pid())  # the killed run's lock: its leftovers go at once
    else:  # no lock to tell whose they are: they go when old
        old = time.time() - 7200
        for path in [out / n.split("/")[0] if not n.startswith("cases/") else out / n for n in planted]:
            for p in [path, *path.rglob("*")] if path.is_dir() else [path]:
                os.utime(p, (old, old))
    assert main(["sweep", str(study_file), "-o", str(out), "--scheduler", client.scheduler.address, "--quiet"]) == 0
    captured = capsys.readouterr()
    assert "Traceback" not in captured.err
    named = [i for i, c in enumerate(cases) if f"{case_file(out, c)} " in captured.err]
    assert set(named) <= set(damaged)  # a bit flip may miss the data: that file is still sound
    assert all(f"its case ({cases[i].label}) is solved again" in captured.err for i in named)
    assert f"({len(named)} solved now, 0 failed, 0 incomplete)" in captured.out
    if planted:
        assert "microslip sweep: warning: removed what an interrupted run left in " in captured.err
    assert leftovers(out) == [] and not (out / ".sweep.lock").exists()
    assert_same_results(out, reference)


@pytest.mark.parametrize("delay", [0.3, 1.5, 3.0])
def test_a_run_killed_at_any_moment_is_resumed_to_the_results_of_a_clean_run(finished, tmp_path, client, capsys,
                                                                              delay):
    """``microslip sweep`` killed (SIGKILL) ``delay`` s after it took the folder: solving, or writing the results."""
    study_file, reference = finished
    out = copy(reference, tmp_path / "out")
    cases = load_study(study_file).cases()
    for case in cases[1:]:
        case_file(out, case).unlink()
    proc = subprocess.Popen(cli_command(study_file, out, "--scheduler", client.scheduler.address, "--quiet"),
                            env=cli_env(), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    lock = out / ".sweep.lock"
    deadline = time.monotonic() + 120
    while proc.poll() is None and time.monotonic() < deadline and not (lock.exists() and lock.read_text()):
        time.sleep(0.01)
    try:
        proc.wait(timeout=delay)
    except subprocess.TimeoutExpired:
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    err = proc.stderr.read().decode()
    assert "Traceback" not in err and "error" not in err, err
    assert main(["sweep", str(study_file), "-o", str(out), "--scheduler", client.scheduler.address, "--quiet"]) == 0
    assert "Traceback" not in capsys.readouterr().err
    assert leftovers(out) == [] and not lock.exists()
    assert_same_results(out, reference)


def test_two_runs_at_once_solve_each_case_once(finished, tmp_path, client):
    study_file, reference = finished
    out = tmp_path / "out"
    procs = [subprocess.Popen(cli_command(study_file, out, "--scheduler", client.scheduler.address), env=cli_env(),
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for _ in range(2)]
    runs = [(p.pid, *p.communicate(timeout=600), p.returncode) for p in procs]
    assert sorted(code for *_, code in runs) in ([0, 0], [0, 2]), runs
    solved = 0
    for pid, stdout, stderr, code in runs:
        assert "Traceback" not in stderr
        if code == 2:  # refused, naming the run that holds the folder
            other = next(p for p, *_ in runs if p != pid)
            assert (f"microslip sweep: error: {str(out)!r} is in use by another microslip sweep (pid {other} on "
                    in stderr)
        else:
            solved += int(re.search(r"\((\d+) solved now", stdout).group(1))
    assert solved == 3  # each case once: by the first run, or the second found them finished
    assert_same_results(out, reference)
