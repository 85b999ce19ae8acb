"""``microslip target``: option checks named as typed, -o and --out each where it applies, --reuse-points refused
for another problem."""

import pytest

from microslip.cli import build_parser, main


@pytest.mark.parametrize("args, message", [
    (["--min-amplitude", "-0.5"], "--min-amplitude must be a non-negative multiple of the gross-slip displacement, "
                                  "got -0.5"),
    (["--seed", "-1"], "--seed must be a non-negative integer, got -1"),
    (["--reuse-points"], "--reuse-points applies to --sweep only"),
    (["--sweep", "4", "--reuse-points", "--mu", "0.3"],
     r"--reuse-points: the stored points do not solve this problem \(they are for mu = 0.4, not 0.3\)"),
    (["--sweep", "4", "--reuse-points", "--load-range", "15N,37.5N"],
     r"they are for the load range 7.5-37.5 N, not 15-37.5 N\); drop --reuse-points"),
    (["--sweep", "4", "--reuse-points", "--min-amplitude", "1"], "they are for min_amplitude 0.5, not 1"),
])
def test_bad_options_are_refused(args, message, tmp_path):
    out = ["--out", str(tmp_path)] if "--sweep" in args else ["-o", str(tmp_path / "m.json")]
    parsed = build_parser().parse_args(["target", *args, "--quiet", *out])
    with pytest.raises(ValueError, match=message):
        parsed.func(parsed)
    assert not (tmp_path / "sweep.csv").exists() and not (tmp_path / "m.json").exists()


@pytest.mark.parametrize("args, message", [
    (["--energy-target", "2"], "argument --energy-target: value: '2' is a fraction above 1 (fractions: 0.02 means "
                               "2 %); write 2% for 2 percent, or 0.02"),
    (["--energy-target", "-1%"], "argument --energy-target: must be a fraction in (0, 1] such as 0.02 or 2%, "
                                 "got '-1%'"),
    (["--force-target", "0"], "argument --force-target: must be a fraction in (0, 1] such as 0.02 or 2%, got '0'"),
    (["--energy-target", "nan"], "argument --energy-target: value: cannot read 'nan' as a fraction"),
    (["--elements", "0"], "argument --elements: must be a positive integer, got '0'"),
    (["--max-elements", "0"], "argument --max-elements: must be a positive integer, got '0'"),
    (["--budget", "-3"], "argument --budget: must be a positive integer, got '-3'"),
])
def test_bad_numbers_are_refused_when_read(args, message, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["target", *args])
    assert exc.value.code == 2 and message in capsys.readouterr().err


@pytest.mark.parametrize("text", ["2%", "0.02", "2 %"])
def test_a_target_in_percent_or_as_a_fraction_means_the_same(text):
    """The API takes fractions; the command line takes the same fraction or a percentage (before: 2 meant 2 %)."""
    parsed = build_parser().parse_args(["target", "--energy-target", text, "--force-target", text])
    assert parsed.energy_target == pytest.approx(0.02, rel=1e-15) and parsed.force_target == parsed.energy_target


@pytest.mark.parametrize("args, message", [
    (["--sweep", "4", "-o", "m.json"], "-o m.json names a model file, which --sweep does not write: --sweep writes "
                                       "sweep.csv, sweep.png and sweep.txt into the folder --out DIR"),
    (["--elements", "4", "--out", "folder"], "--out applies to --sweep only; without it the model goes to -o FILE"),
    (["--elements", "4", "--save-points", "p.json"], "--save-points applies to --sweep only"),
])
def test_o_is_the_model_file_and_out_the_folder_of_a_sweep(args, message, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    parsed = build_parser().parse_args(["target", *args, "--quiet"])
    with pytest.raises(ValueError, match=message):
        parsed.func(parsed)
    assert list(tmp_path.iterdir()) == []


def test_out_is_not_taken_for_an_abbreviation_of_output(capsys):
    """With argparse's abbreviations, 'tune --out DIR' wrote the model to a file named DIR."""
    with pytest.raises(SystemExit):
        main(["simulate", "m.json", "h.csv", "--out", "results"])
    assert "unrecognized arguments: --out results" in capsys.readouterr().err


def test_main_reports_the_error_and_exits_2(tmp_path, capsys):
    assert main(["target", "--min-amplitude", "-1", "--quiet", "-o", str(tmp_path / "m.json")]) == 2
    assert "microslip target: error: --min-amplitude must be a non-negative multiple" in capsys.readouterr().err
