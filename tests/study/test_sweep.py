"""Design studies on Dask: the same results as the cases solved one by one, resumption, failures, engines."""

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from microslip.frequency import frequency_response
from microslip.config import load_config
from microslip.study import load_study, sweep

distributed = pytest.importorskip("dask.distributed")

DAMPER_STUDY = '''base = "pair.toml"
title = "Damper load and excitation level"
[vary]
"damper.centrifugal_load" = ["40N", "60N", "90N", "130N", "200N", "300N"]
"excitation.scale" = [1.0, 1.5]
'''


def _one_by_one(study, case, tmp_path):
    """The case solved with frequency_response from a configuration file written with its values."""
    from threadpoolctl import threadpool_limits

    text = study.base.read_text()
    load = case.values["damper.centrifugal_load"]
    text = text.replace('centrifugal_load = "50N"', f'centrifugal_load = "{load}"')
    scale = case.values["excitation.scale"]
    text = text.replace("h1 = [0, 0, 0.5, 0, 0, -0.5]", f"h1 = [0, 0, {0.5 * scale!r}, 0, 0, {-0.5 * scale!r}]")
    path = study.base.with_name(f"case_{case.key}.toml")
    path.write_text(text)
    cfg = load_config(path)
    with threadpool_limits(1):  # as on a worker
        r = frequency_response(cfg.structure, cfg.force, cfg.omega, harmonics=cfg.harmonics, samples=cfg.samples,
                               control=cfg.control, reduction=cfg.reduction, modes=cfg.modes,
                               engine_order=cfg.engine_order)
    return r, cfg


def test_a_study_on_two_workers_equals_the_cases_solved_one_by_one_bit_for_bit(damper_pair, tmp_path, client):
    study_file = damper_pair.with_name("study.toml")
    study_file.write_text(DAMPER_STUDY)
    study = load_study(study_file)
    result = sweep(study, client, out=tmp_path / "out")
    assert len(result.cases) == 12 and result.computed == 12 and not result.failed
    for k, case in enumerate(result.cases):
        r, cfg = _one_by_one(study, case, tmp_path)
        curve = result.curve(k)
        # the same arithmetic in the same order: identical, not merely close
        assert np.array_equal(curve["omega"], r.omega)
        assert np.array_equal(curve["amplitude"][:, 0], r.amplitude(2, None))
        w, a = r.peak(2)
        row = result.rows[k]
        assert row["peak tip0 (m)"] == a and row["peak frequency tip0 (Hz)"] == w / (2 * np.pi)
        assert row["damper.centrifugal_load"] == float(case.values["damper.centrifugal_load"][:-1])
        assert row["complete"] is True
        assert 0 < np.argmax(curve["amplitude"][:, 0]) < r.points - 1  # the window holds the resonance peak
    # the damper's load spans sliding to stuck: the peaks differ from case to case
    assert len({r["peak tip0 (m)"] for r in result.rows}) == 12
    summary = result.summary
    assert list(summary.columns[:3]) == ["case", "damper.centrifugal_load", "excitation.scale"]
    import pandas as pd
    import xarray as xr

    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "out" / "summary.parquet"), summary)
    exact = {"float_precision": "round_trip"} if tuple(map(int, pd.__version__.split(".")[:2])) < (3, 1) else {}
    csv = pd.read_csv(tmp_path / "out" / "summary.csv", **exact)  # 3.1 reads exactly and deprecates the option
    assert np.array_equal(csv["peak tip0 (m)"], summary["peak tip0 (m)"])  # floats written exactly
    ds = xr.open_zarr(tmp_path / "out" / "curves.zarr")
    assert ds.sizes["case"] == 12
    k = 5
    n = int(ds["points"][k])
    assert np.array_equal(ds["omega"][k, :n].values, result.curve(k)["omega"])
    assert np.isnan(ds["omega"][k, n:]).all()
    assert (tmp_path / "out" / "report.html").stat().st_size > 0


def test_a_rerun_solves_only_the_cases_not_finished(block, tmp_path, client):
    out = tmp_path / "out"
    first = sweep(block, client, out=out)
    assert first.computed == 6
    before = (out / "summary.csv").read_text()
    for case in first.cases[1:4]:  # as if the run had been killed before these finished
        (out / "cases" / f"{case.key}.npz").unlink()
    again = sweep(block, client, out=out)
    assert again.computed == 3
    assert _results(out / "summary.csv") == _results_text(before)
    assert sweep(block, client, out=out, report=False).computed == 0


def _results_text(text):
    """The summary without its time column (a case solved again takes its own time)."""
    import csv
    import io

    rows = list(csv.DictReader(io.StringIO(text)))
    return [{k: v for k, v in r.items() if k != "time (s)"} for r in rows]


def _results(path):
    return _results_text(path.read_text())


def test_a_case_that_fails_is_recorded_and_the_others_finish(block, tmp_path, client):
    # each value alone is a valid configuration; harmonics = 1 with a force at harmonic 2 is not
    block.write_text('base = "inclined_block.toml"\n[vary]\n"sweep.harmonics" = [1, 3]\n'
                     '"excitation.h2" = [["0.1N", "0N"]]\n[[case]]\n"sweep.omega" = [13000, 15000]\n')
    result = sweep(block, client, out=tmp_path / "out")
    assert result.computed == 2
    [(case, error)] = result.failed
    assert case.values["sweep.harmonics"] == 1
    assert "ConfigError" in error and "h2 is a harmonic above [sweep] harmonics = 1" in error
    rows = {r["sweep.harmonics"]: r for r in result.rows}
    assert rows[1.0]["complete"] is False and rows[1.0]["error"] == error
    assert rows[3.0]["complete"] is True and rows[3.0]["peak x (m)"] > 0
    assert "Failed cases" in (tmp_path / "out" / "report.md").read_text()
    # a rerun does not solve the failed case again unless asked to
    assert sweep(block, client, out=tmp_path / "out", report=False).computed == 0
    # the case solved again on the same cluster, reached by its scheduler's address
    again = sweep(block, scheduler=client.scheduler.address, out=tmp_path / "out", report=False, retry_failed=True)
    assert again.computed == 1 and len(again.failed) == 1


def test_an_unreachable_scheduler_is_refused_before_any_work(block, tmp_path, monkeypatch):
    from microslip.study import engine

    monkeypatch.setattr(engine, "CONNECT_TIMEOUT", 1.0)
    with pytest.raises(ConnectionError, match=r"scheduler: no Dask scheduler answers at 'tcp://127.0.0.1:9' "):
        sweep(block, scheduler="tcp://127.0.0.1:9", out=tmp_path / "out")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("kwargs, message", [
    ({"workers": 0}, "workers must be"),
    ({"progress": "yes"}, "progress must be"),
    ({"scheduler": ""}, "scheduler must not be empty"),
    ({"retry_failed": 1}, "retry_failed must be"),
    ({"report": None}, "report must be"),
    ({"out": 3}, "out must be a folder name"),
])
def test_sweep_checks_its_arguments(block, tmp_path, kwargs, message):
    with pytest.raises((ValueError, TypeError), match=message):
        sweep(block, **{"out": tmp_path / "out", **kwargs})


def test_sweep_refuses_a_client_with_workers(block, tmp_path, client):
    with pytest.raises(ValueError, match="either client or workers/scheduler"):
        sweep(block, client, workers=2, out=tmp_path / "out")


def test_a_killed_run_loses_only_the_cases_in_flight(block, tmp_path, capsys):
    """``microslip sweep`` killed (SIGKILL, its workers too) after its first finished case; the rerun completes."""
    out = tmp_path / "out"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    cmd = [sys.executable, "-c", "import sys; from microslip.cli import main; sys.exit(main())", "sweep", str(block),
           "-o", str(out), "--workers", "1", "--quiet"]
    proc = subprocess.Popen(cmd, env=env, start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and not list((out / "cases").glob("*.npz")) and proc.poll() is None:
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    finished = len(list((out / "cases").glob("*.npz")))
    assert finished >= 1, proc.stderr.read().decode()
    assert not list((out / "cases").glob(".*"))  # no half-written case file left behind
    assert f'"pid": {proc.pid}' in (out / ".sweep.lock").read_text()  # the killed run's lock, with its record
    from microslip.cli import main

    assert main(["sweep", str(block), "-o", str(out), "--workers", "1"]) == 0
    err = capsys.readouterr().err
    assert f"microslip sweep: warning: the run that last wrote into {str(out)!r} (pid {proc.pid} on host " in err
    assert "ended without releasing its lock (it was killed): lock taken over" in err
    assert not (out / ".sweep.lock").exists()
    assert f"6 cases: {finished} finished by an earlier run, {6 - finished} to solve on 1 worker" in err
    assert f"[{6 - finished}/{6 - finished}] done, 0 running, 0 failed" in err
    assert len(list((out / "cases").glob("*.npz"))) == 6


def test_the_cli_refuses_a_bad_study_with_status_2(block, tmp_path, capsys):
    from microslip.cli import main

    block.write_text('base = "inclined_block.toml"\n[vary]\n"contact.sphere.preload" = ["25m"]\n')
    assert main(["sweep", str(block), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("microslip sweep: error: ") and "'contact.sphere.preload' = \"25m\"" in err
    assert not (tmp_path / "out").exists()


def test_the_cli_help_explains_every_option(capsys):
    from microslip.cli import main

    with pytest.raises(SystemExit):
        main(["sweep", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for option in ("--workers", "--scheduler", "--retry-failed", "-o", "--quiet", "summary.csv", "curves.zarr",
                   "dask-jobqueue", "pip install microslip[sweep]"):
        assert option in text


def test_a_study_of_nonlinear_modes_gives_each_modes_frequency_and_damping(block, tmp_path, client):
    from microslip.frequency import nonlinear_modes

    block.write_text('base = "inclined_block.toml"\nsolve = "modes"\n[vary]\n"contact.sphere.preload" = ["25N", "50N"]\n'
                     '"sweep.harmonics" = [3]\n')
    study = load_study(block)
    result = sweep(study, client, out=tmp_path / "out")
    assert not result.failed
    for k, case in enumerate(result.cases):
        cfg = study.configuration(case)
        t = cfg.nonlinear_mode
        # the mode's own steps (no [continuation]), as microslip modes computes it; the study passed the forced
        # response's StepControl() before, steps up to four times longer on this range
        mode = nonlinear_modes(cfg.structure, t.mode, t.amplitude, harmonics=cfg.harmonics, samples=cfg.samples)
        row = result.rows[k]
        assert row["linear frequency (Hz)"] == mode.linear_frequency / (2 * np.pi)
        assert row["largest damping ratio"] == mode.damping_ratio.max()
        assert np.array_equal(result.curve(k)["damping_ratio"], mode.damping_ratio)
    # a stiffer contact (higher preload) raises the stuck mode's frequency
    assert result.rows[1]["linear frequency (Hz)"] > result.rows[0]["linear frequency (Hz)"]
    assert "The largest modal damping ratio against `contact.sphere.preload`" in (tmp_path / "out" / "report.md").read_text()
