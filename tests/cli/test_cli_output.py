"""The command line refuses outputs it cannot write with a message, not a traceback."""

from microslip.cli import main


def test_an_output_that_is_a_folder_is_an_error_with_code_2(tmp_path, capsys):
    model = tmp_path / "model.json"
    assert main(["tune", "-o", str(model)]) == 0
    history = tmp_path / "h.csv"
    history.write_text("t [um]\n0\n1\n")
    folder = tmp_path / "out"
    folder.mkdir()
    capsys.readouterr()
    code = main(["simulate", str(model), str(history), "--n", "2um", "-o", str(folder)])
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith("microslip simulate: error:") and "Traceback" not in err
    assert not [p for p in folder.parent.iterdir() if p.name.endswith(".tmp")]
