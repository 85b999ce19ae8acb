"""``examples/inclined_block.py`` run as a script: it writes into the folder of ``--out`` and refuses what it does not
know, as the other examples."""

import csv
import os
import subprocess
import sys

from _paths import EXAMPLES

SCRIPT = str(EXAMPLES / "inclined_block.py")


def run(*args, cwd):
    path = os.pathsep.join([str(EXAMPLES.parent / "src"), os.environ.get("PYTHONPATH", "")])
    env = {**os.environ, "PYTHONPATH": path}
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True, env=env, cwd=cwd,
                          timeout=600)


def test_the_script_refuses_unknown_options_and_a_file_for_a_folder(tmp_path):
    bad = run("--bogus", cwd=tmp_path)
    assert bad.returncode == 2 and "unrecognized arguments: --bogus" in bad.stderr
    (tmp_path / "a_file").write_text("")
    bad = run("--out", str(tmp_path / "a_file"), cwd=tmp_path)
    assert bad.returncode == 2 and "is a file, not a folder" in bad.stderr
    assert list(tmp_path.iterdir()) == [tmp_path / "a_file"]  # nothing written


def test_the_script_writes_its_tables_into_the_folder_given(tmp_path):
    done = run("--out", str(tmp_path / "tables"), cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(open(tmp_path / "tables" / "inclined_block.csv")))
    assert len(rows) == 5 and max(abs(float(r["difference [-]"])) for r in rows) < 1.3e-4  # as the README says
    errors = list(csv.DictReader(open(tmp_path / "tables" / "inclined_block_truncation.csv")))
    assert [r["harmonics H"] for r in errors] == ["1", "2", "3", "5", "7", "11", "15"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["tables"]  # nothing in the working folder
