"""``microslip target``: option checks named as typed, and --reuse-points refused for another problem."""

import pytest

from microslip.cli import build_parser, main


@pytest.mark.parametrize("args, message", [
    (["--energy-target", "-1"], r"--energy-target must be a positive percentage, got -1 \(%\)"),
    (["--force-target", "0"], r"--force-target must be a positive percentage, got 0 \(% of the reference's peak"),
    (["--energy-target", "nan"], r"--energy-target must be a positive percentage, got nan"),
    (["--min-amplitude", "-0.5"], "--min-amplitude must be a non-negative multiple of the gross-slip displacement, "
                                  "got -0.5"),
    (["--elements", "0"], "--elements must be a positive integer, got 0"),
    (["--max-elements", "0"], "--max-elements must be a positive integer, got 0"),
    (["--budget", "-3"], "--budget must be a positive integer, got -3"),
    (["--seed", "-1"], "--seed must be a non-negative integer, got -1"),
    (["--reuse-points"], "--reuse-points applies to --sweep only"),
    (["--sweep", "4", "--reuse-points", "--mu", "0.3"],
     r"--reuse-points: the stored points do not solve this problem \(they are for mu = 0.4, not 0.3\)"),
    (["--sweep", "4", "--reuse-points", "--load-range", "15N,37.5N"],
     r"they are for the load range 7.5-37.5 N, not 15-37.5 N\); drop --reuse-points"),
    (["--sweep", "4", "--reuse-points", "--min-amplitude", "1"], "they are for min_amplitude 0.5, not 1"),
])
def test_bad_options_are_refused(args, message, tmp_path):
    parsed = build_parser().parse_args(["target", *args, "--quiet", "--out", str(tmp_path),
                                        "-o", str(tmp_path / "m.json")])
    with pytest.raises(ValueError, match=message):
        parsed.func(parsed)
    assert not (tmp_path / "sweep.csv").exists() and not (tmp_path / "m.json").exists()


def test_main_reports_the_error_and_exits_2(tmp_path, capsys):
    assert main(["target", "--energy-target", "-1", "--quiet", "-o", str(tmp_path / "m.json")]) == 2
    assert "microslip target: error: --energy-target must be a positive percentage, got -1 (%)" in \
        capsys.readouterr().err
