"""Resuming from an earlier run's folder: damaged case files, leftovers, a second run, every case failing."""

import pytest
from _study_folder import write_block

from microslip.cli import main
from microslip.study import load_study

pytest.importorskip("dask.distributed")


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
