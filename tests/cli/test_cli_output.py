"""Every argument is checked before any work: outputs that cannot be written are refused by option, in words."""

import os
import re

import pytest

from microslip.cli import main
from microslip.measured import loops as loops_module


@pytest.fixture
def model(tmp_path):
    path = tmp_path / "model.json"
    assert main(["tune", "-o", str(path)]) == 0
    return path


@pytest.fixture
def history(tmp_path):
    path = tmp_path / "h.csv"
    path.write_text("t [um]\n0\n1\n")
    return path


def refused(argv, capsys):
    """Run ``argv``: it must stop with status 2 before writing anything; returns standard error."""
    capsys.readouterr()
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and ".tmp" not in err and "Errno" not in err  # no raw OS text
    return err


def test_a_folder_given_for_a_file_is_named_as_such(model, history, tmp_path, capsys):
    """Before: [Errno 21] Is a directory: '/.tmp.hhwa4yd0.tmp' -> '/tmp', after the work."""
    folder = tmp_path / "out"
    folder.mkdir()
    err = refused(["simulate", str(model), str(history), "--n", "2um", "-o", str(folder)], capsys)
    assert f"argument -o/--output: {str(folder)!r} is a folder; give a file to write, e.g. " \
           f"{str(folder / 'forces.csv')!r}" in err
    assert list(folder.iterdir()) == [] and not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]
    err = refused(["tune", "-o", str(folder)], capsys)
    assert f"argument -o/--output: {str(folder)!r} is a folder" in err and "model.json" in err


@pytest.mark.parametrize("command", [["tune"], ["target", "--elements", "3"]])
def test_a_missing_folder_of_an_output_file_is_named(command, tmp_path, capsys):
    target = tmp_path / "no-such-folder" / "m.json"
    err = refused([*command, "-o", str(target)], capsys)
    assert f"the folder {str(target.parent)!r} does not exist; create it first" in err
    assert not target.parent.exists()


def test_a_folder_one_cannot_write_into_is_named(model, history, tmp_path, capsys, monkeypatch):
    """The tests run as root, for whom every folder is writable: the permission is taken away at os.access."""
    locked = tmp_path / "locked"
    locked.mkdir()
    real = os.access
    monkeypatch.setattr(os, "access", lambda p, mode, **kw: False if str(p) == str(locked) else real(p, mode, **kw))
    err = refused(["simulate", str(model), str(history), "--n", "2um", "-o", str(locked / "f.csv")], capsys)
    assert f"cannot write the file into the folder {str(locked)!r} (permission denied)" in err
    err = refused(["reproduce", "--out", str(locked / "results")], capsys)
    assert "argument --out:" in err and f"cannot write the results into the folder {str(locked)!r}" in err


def test_an_output_folder_that_is_a_file_is_refused(model, tmp_path, capsys):
    for argv in (["reproduce", "--out", str(model)], ["accuracy", str(model), "--out", str(model)],
                 ["target", "--sweep", "2", "--out", str(model)]):
        assert f"argument --out: {str(model)!r} is a file, not a folder" in refused(argv, capsys)


def test_an_image_format_matplotlib_cannot_write_is_refused_before_the_csv(model, history, tmp_path, capsys):
    """Before: the CSV was written, then matplotlib failed on .xyz."""
    csv = tmp_path / "f.csv"
    err = refused(["simulate", str(model), str(history), "--n", "2um", "-o", str(csv), "--plot",
                   str(tmp_path / "o.xyz")], capsys)
    assert re.search(r"argument --plot: '.*o\.xyz': cannot write an image of type 'xyz'; use one of .*\.png", err)
    assert not csv.exists()


def test_an_unknown_normal_law_is_refused_before_any_loop_is_read(tmp_path, capsys, monkeypatch):
    """Before: 'hertzian' was refused after reading, analysing and fitting the loops."""
    from microslip.loops.synthetic import dataset_files

    def read(*args, **kwargs):
        raise AssertionError("a loop file was read before --normal-law was checked")

    monkeypatch.setattr(loops_module, "read", read)
    code = main(["tune", str(dataset_files()[0]), "--normal-law", "hertzian", "-o", str(tmp_path / "m.json"),
                 "--quiet"])
    assert code == 2
    assert "--normal-law must be 'palmgren', 'lundberg' or an existing table file, got 'hertzian'" in \
        capsys.readouterr().err
