"""Resuming from an earlier run's folder: damaged case files, leftovers, a second run, every case failing."""

import json
import os
import re
import time

import numpy as np
import pytest
from _study_folder import assert_same_results, copy, dead_pid, rewrite_meta, stale_lock, write_block

from microslip.cli import main
from microslip.study import load_study, sweep
from microslip.study.folder import FolderInUseError, FolderLock, StudyFolderWarning
from microslip.study.store import case_file

pytest.importorskip("dask.distributed")


def _flip(path):
    """Flip one bit in the middle of the file (inside the curves' data: their CRC no longer matches)."""
    data = bytearray(path.read_bytes())
    data[len(data) // 2] ^= 0x01
    path.write_bytes(bytes(data))


DAMAGES = {
    "truncated": (lambda p, other: p.write_bytes(p.read_bytes()[:p.stat().st_size // 2]), "is damaged or truncated"),
    "emptied": (lambda p, other: p.write_bytes(b""), "is empty"),
    "bit flipped": (lambda p, other: _flip(p), "is damaged or truncated (Bad CRC-32"),
    "without row": (lambda p, other: rewrite_meta(p, lambda m: m.pop("row")), "has metadata without 'row'"),
    "another case's values": (lambda p, other: rewrite_meta(p, lambda m: m.update(values=other.values)),
                              "not those of its key"),
    "random bytes": (lambda p, other: p.write_bytes(np.random.default_rng(1).bytes(3000)), "is not a NumPy .npz"),
}


@pytest.mark.parametrize("damage", list(DAMAGES))
def test_a_case_file_that_cannot_be_trusted_is_named_and_its_case_solved_again(finished, tmp_path, client, damage):
    study_file, reference = finished
    out = copy(reference, tmp_path / "out")
    cases = load_study(study_file).cases()
    path = case_file(out, cases[1])
    make, why = DAMAGES[damage]
    make(path, cases[2])
    with pytest.warns(StudyFolderWarning) as caught:
        result = sweep(study_file, client, out=out, report=False)
    [message] = [str(w.message) for w in caught]
    assert message.startswith(f"{path} ") and why in message
    assert message.endswith(f"its case ({cases[1].label}) is solved again")
    assert result.computed == 1 and not result.failed
    assert_same_results(out, reference)


def test_a_rerun_removes_what_a_killed_run_left_and_says_so(finished, tmp_path, client):
    """What SIGKILL leaves while atomic writes are in flight, and the killed run's lock file with its record."""
    study_file, reference = finished
    out = copy(reference, tmp_path / "out")
    key = load_study(study_file).cases()[0].key
    planted = [out / "cases" / f".{key}.npz.a1b2c3d4.tmp", out / ".summary.csv.k2j3h4_2.tmp",
               out / ".summary.parquet.zz9yy8xx.tmp", out / ".against_x_tip.png.q1w2e3r4.tmp",
               out / ".report.html.abcdefgh.tmp"]
    for p in planted:
        p.write_bytes(b"half written")
    (out / ".curves.u7i8o9p0.tmp" / "store.zarr" / "omega").mkdir(parents=True)  # a Zarr store half written
    (out / ".curves.zarr.old.4242" / "omega").mkdir(parents=True)  # the old store moved aside, not yet removed
    mine = [out / ".notes.txt.tmp", out / "cases" / "notes.npz.tmp", out / ".summary.csv.swp"]  # not the writer's
    for p in mine:
        p.write_text("the user's")
    pid = dead_pid()
    stale_lock(out, pid)
    with pytest.warns(StudyFolderWarning) as caught:
        result = sweep(study_file, client, out=out, report=False)
    said = [str(w.message) for w in caught]
    assert len(said) == 2, said
    assert f"({pid=} on host {os.uname().nodename}, started 2024-05-01T10:00:00+00:00) ended without releasing its " \
           "lock (it was killed): lock taken over".replace("pid=", "pid ") in said[0]
    assert said[1].startswith(f"removed what an interrupted run left in {str(out)!r}: ")
    for name in [f"cases/.{key}.npz.a1b2c3d4.tmp", ".curves.u7i8o9p0.tmp/", ".curves.zarr.old.4242/",
                 ".summary.csv.k2j3h4_2.tmp", ".against_x_tip.png.q1w2e3r4.tmp"]:
        assert name in said[1]
    assert result.computed == 0
    left = sorted(p.name for d in (out, out / "cases") for p in d.iterdir()
                  if p.name.startswith(".") or p.name.endswith(".tmp"))
    assert left == sorted(p.name for p in mine)  # the lock file is gone after the run, the user's files are kept
    assert_same_results(out, reference)


def test_leftovers_without_a_killed_runs_lock_are_removed_only_when_old(finished, tmp_path, client):
    study_file, reference = finished
    out = copy(reference, tmp_path / "out")
    old, young = out / ".summary.csv.oldoldol.tmp", out / ".report.md.youngyou.tmp"
    for p in (old, young):
        p.write_text("x")
    two_hours_ago = time.time() - 7200
    os.utime(old, (two_hours_ago, two_hours_ago))
    with pytest.warns(StudyFolderWarning) as caught:
        sweep(study_file, client, out=out, report=False)
    said = [str(w.message) for w in caught]
    assert said == [f"removed what an interrupted run left in {str(out)!r}: .summary.csv.oldoldol.tmp",
                    f"left alone in {str(out)!r}, written less than 1 h ago by a run not known to have ended: "
                    ".report.md.youngyou.tmp"]
    assert not old.exists() and young.exists()


def test_a_second_run_on_a_folder_in_use_is_refused_naming_the_first(finished, tmp_path, client, capsys):
    study_file, reference = finished
    out = copy(reference, tmp_path / "out")
    for path in (out / "cases").glob("*.npz"):
        path.unlink()
    with FolderLock(out):  # a run writing into out
        record = json.loads((out / ".sweep.lock").read_text())
        assert record["pid"] == os.getpid() and record["host"] == os.uname().nodename
        with pytest.raises(FolderInUseError, match=re.escape(
                f"{str(out)!r} is in use by another microslip sweep (pid {os.getpid()} on host "
                f"{os.uname().nodename}, started {record['started']}): wait for it to finish, or give another "
                "results folder")):
            sweep(study_file, client, out=out, report=False)
        assert main(["sweep", str(study_file), "-o", str(out), "--scheduler", client.scheduler.address]) == 2
        assert "is in use by another microslip sweep (pid" in capsys.readouterr().err
        assert not list((out / "cases").glob("*"))  # nothing solved, nothing written
    assert not (out / ".sweep.lock").exists()
    assert sweep(study_file, client, out=out, report=False).computed == 3


def test_a_study_where_every_case_fails_exits_1_with_each_error_and_a_report_saying_so(tmp_path, client, capsys):
    # each value alone is valid; harmonics = 1 with a force at harmonic 2 is not
    study_file = write_block(tmp_path, 'base = "inclined_block.toml"\n[vary]\n"sweep.harmonics" = [1]\n'
                                       '"excitation.h2" = [["0.1N", "0N"]]\n'
                                       '"contact.sphere.preload" = ["25N", "50N"]\n')
    out = tmp_path / "out"
    assert main(["sweep", str(study_file), "-o", str(out), "--scheduler", client.scheduler.address]) == 1
    captured = capsys.readouterr()
    cases = load_study(study_file).cases()
    for case in cases:
        assert (f"microslip sweep: case {case.key} ({case.label}) failed: ConfigError: "
                f"{study_file.with_name('inclined_block.toml')}: [excitation] h2 is a harmonic above [sweep] "
                "harmonics = 1") in captured.err
    assert "microslip sweep: every case failed (2 of 2)" in captured.err
    assert "2 cases (2 solved now, 2 failed, 0 incomplete)" in captured.out
    import pandas as pd

    summary = pd.read_csv(out / "summary.csv")
    assert len(summary) == 2 and not summary["complete"].any() and summary["error"].str.startswith("ConfigError").all()
    report = (out / "report.md").read_text()
    assert "**Every case failed**" in report and "Failed cases" in report
    assert (out / "report.html").is_file()


def _timed_solve(study, case):
    """A stand-in for solve_case: the 25 N case at once, the others in 0.4 s."""
    seconds = 0.0 if case.values["contact.sphere.preload"] == "25N" else 0.4
    time.sleep(seconds)
    return {"row": {"complete": True}, "curves": {}, "error": "", "warnings": "", "time": seconds}


def test_progress_gives_no_time_left_from_one_fast_case_and_counts_the_cases_in_flight(tmp_path, client, capsys,
                                                                                      monkeypatch):
    from microslip.study import engine

    monkeypatch.setattr(engine, "solve_case", _timed_solve)
    monkeypatch.setattr(engine, "REFRESH", 0.25)
    study_file = write_block(tmp_path, 'base = "inclined_block.toml"\n[vary]\n'
                                       '"contact.sphere.preload" = ["25N", "30N", "35N", "40N", "45N", "50N"]\n')
    sweep(study_file, client, out=tmp_path / "out", report=False, progress=True)
    lines = capsys.readouterr().err.splitlines()
    done = [line for line in lines if line.startswith("[")]
    # the first case took no time: the others are not assumed to (the old estimate said "about 0 s left")
    assert done[0].startswith("[1/6] done, 2 running, 0 failed, time left estimated after 3 cases (")
    assert any(re.match(r"\[3/6\] done, 2 running, 0 failed, about \d+ s left \(estimate after 3 cases\) \(", line)
               for line in done)
    # the line is repeated while no case finishes: cases done, in flight, and the time left
    assert any(re.fullmatch(r"\[\d/6\] done, \d running, 0 failed, (time left estimated after 3 cases|about \d+ s "
                            r"left \(estimate after \d cases\))", line) for line in done)
    assert done[-1].startswith("[6/6] done, 0 running, 0 failed, none left (")


def test_the_time_left_rests_on_the_cases_finished_and_those_in_flight():
    from microslip.common._progress import TimeLeft

    now = [0.0]
    clock = TimeLeft(20, 2, clock=lambda: now[0])
    # a fast first case, then cases of 3 s: nothing is claimed from the first
    now[0] = 0.1
    clock.finished(0.1)
    assert clock.seconds() is None and clock.text() == "time left estimated after 3 cases"
    for t in (3.0, 3.1, 6.0):  # cases of 3 s end on each worker, the next ones start
        now[0] = t
        clock.finished(3.0)
    # 14 cases wait, one in flight since 3.1 s and one just started: (14 * 3 + 0.1 + 3) / 2 s
    assert clock.seconds() == pytest.approx((14 * 3.0 + 0.1 + 3.0) / 2)
    assert clock.text() == "about 23 s left (estimate after 4 cases)"
    # a case in flight that runs long raises the estimate before it ends
    before = clock.seconds()
    now[0] = 40.0
    assert clock.seconds() > before
    assert TimeLeft(1, 4).text() == "time left estimated after 1 case"
