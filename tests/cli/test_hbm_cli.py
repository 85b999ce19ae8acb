"""``microslip frf``: a TOML configuration to a curve, plots and a report; configuration errors."""

import re
import shutil

import numpy as np
import pytest

from microslip.common._table import read_table
from microslip.cli import main
from microslip.config import ConfigError, load_config
from _paths import EXAMPLES



@pytest.fixture
def config_dir(tmp_path):
    shutil.copy(EXAMPLES / "inclined_block.toml", tmp_path / "block.toml")
    shutil.copy(EXAMPLES / "sphere_4_elements.json", tmp_path / "sphere_4_elements.json")
    return tmp_path


def _edit(path, old, new):
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new))


def test_frf_writes_curve_plots_and_report(config_dir, capsys):
    cfg = config_dir / "block.toml"
    _edit(cfg, "omega = [12000, 18000]", "omega = [13000, 16000]")
    out = config_dir / "out"
    assert main(["frf", str(cfg), "--out", str(out)]) == 0
    for name in ("frf.csv", "frf.png", "contacts.png", "report.html", "report.md"):
        assert (out / name).stat().st_size > 0
    printed = capsys.readouterr()
    assert "[10/10] omega =" in printed.err  # progress along the curve
    columns, units = read_table(out / "frf.csv")
    # columns named after the configured DOFs (x, y), frequencies in rad/s and Hz
    assert units["omega"] == "rad/s" and units["x max"] == "m" and units["y a1"] == "m" and units["f"] == "Hz"
    assert columns["omega"][0] == 13000 and columns["omega"][-1] == 16000
    np.testing.assert_allclose(columns["f"], columns["omega"] / (2 * np.pi), rtol=1e-12)
    report = (out / "report.md").read_text()
    assert "| x |" in report and "mean normal load" in report
    assert "excitation frequency from 2069.01 to 2546.48 Hz" in report  # Hz by default, as engineers read it
    assert "| frequency range (Hz) | 2069.01 to 2546.48 |" in report  # the run's table too (it gave rad/s)
    assert "2 DOFs, 1 contact, H = 7" in report  # not "1 contact(s)"
    assert "| 1 | x | 0.6 | 0 |" in report  # the excitation: harmonic, DOF, amplitude (N), phase
    # energies in a unit chosen by magnitude (0.48 µJ is written 484.1 nJ, not 4.841e-07 J)
    assert re.search(r"largest energy dissipated per cycle \d{1,3}(\.\d+)? nJ\.", report)
    # the static state: the 37.5 N preload is shared with the springs (see the configuration's comment)
    static = "static state: normal force N0 = 21.36"
    assert static in printed.out and static in report and "3 of 4 elements closed" in report


def test_frf_prints_and_reports_an_under_resolved_contact(config_dir, capsys):
    """The example's whole range at the default samples: the contact opens at the second mode too fast for them."""
    cfg = config_dir / "block.toml"
    out = config_dir / "out"
    assert main(["frf", str(cfg), "--out", str(out), "--quiet"]) == 0
    assert "warning" not in capsys.readouterr().err  # the example's 256 samples resolve it
    _edit(cfg, "samples = 256", "samples = 128")
    assert main(["frf", str(cfg), "--out", str(out), "--quiet"]) == 0
    err = capsys.readouterr().err
    # one line naming the contact and the setting to change (it was a Python warning pointing inside the package)
    assert re.search(r"^microslip frf: warning: contact 'sphere' opens and closes during the cycle faster than 128 "
                     r"samples per period resolve \(worst at omega = 1\d{4}(\.\d+)? rad/s\): .*; \[sweep\] samples = "
                     r"256 resolves it", err, re.M)
    assert "response.py" not in err and "UnderResolvedWarning" not in err
    assert "**Sampling**: contact 'sphere' opens and closes" in (out / "report.md").read_text()


def test_frf_exits_non_zero_on_a_curve_cut_short_by_max_points(config_dir, capsys):
    cfg = config_dir / "block.toml"
    _edit(cfg, "harmonics = 7", "harmonics = 3\n[continuation]\nmax_points = 5")
    out = config_dir / "out"
    assert main(["frf", str(cfg), "--out", str(out), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert "microslip frf: error: incomplete curve: the continuation stopped at max_points = 5 points at " \
           "omega = 1" in err and "before the end of the range (18000 rad/s)" in err
    columns, _ = read_table(out / "frf.csv")  # what was computed is written, and the report says so
    assert len(columns["omega"]) == 5 and columns["omega"][-1] < 18000
    assert "**Incomplete curve**" in (out / "report.md").read_text()


@pytest.mark.parametrize("sweep, expected", [
    ('omega = ["60Hz", "160Hz"]', (2 * np.pi * 60, 2 * np.pi * 160)),  # used to run 60-160 rad/s
    ('omega = [12000, "2.5kHz"]', (12000.0, 2 * np.pi * 2500)),
    ('omega = ["12000rad/s", "16000 rad/s"]', (12000.0, 16000.0)),
    ("frequency = [1900, 2600]", (2 * np.pi * 1900, 2 * np.pi * 2600)),
    ('frequency = ["12000rad/s", "2.6kHz"]', (12000.0, 2 * np.pi * 2600)),
])
def test_sweep_frequencies_in_hz_are_converted_to_rad_per_s(config_dir, sweep, expected):
    cfg = config_dir / "block.toml"
    _edit(cfg, "omega = [12000, 18000]", sweep)
    assert load_config(cfg).omega == pytest.approx(expected, rel=1e-15)


def test_config_matrices_from_npz_and_frequency_in_hz(config_dir):
    cfg = config_dir / "block.toml"
    np.savez(config_dir / "m.npz", M=0.1 * np.eye(2), K=1e7 * np.eye(2))
    _edit(cfg, "M = [[0.1, 0.0], [0.0, 0.1]]          # kg", 'matrices = "m.npz"\nrayleigh = [173.2, 0.0]')
    _edit(cfg, "K = [[1e7, 0.0], [0.0, 1e7]]          # N/m\n", "")
    _edit(cfg, "C = [[17.32, 0.0], [0.0, 17.32]]      # N s/m\n", "")
    _edit(cfg, "omega = [12000, 18000]                # rad/s", 'frequency = ["2kHz", "2.5kHz"]')
    c = load_config(cfg)
    assert np.allclose(c.structure.C, 17.32 * np.eye(2))
    assert np.allclose(c.omega, (2 * np.pi * 2000, 2 * np.pi * 2500))
    assert c.dof_names == ["x", "y"] and c.harmonics == 7 and c.harmonic == 1


@pytest.mark.parametrize("old, new, message", [
    ("[sweep]", "[swep]", "the file has an unknown key 'swep'; did you mean 'sweep'\\? \\(it accepts title, "
     "structure, cyclic, contact, damper, excitation, sweep, design, continuation, output, modes, prestress, speed, campbell\\)"),
    # a misspelled key used to be ignored: the contact carried 0 N, H fell back to 5, the damping vanished
    ('preload = "37.5N"', 'pre_load = "37.5N"', "\\[\\[contact\\]\\] has an unknown key 'pre_load'; did you mean "
     "'preload'\\? \\(it accepts model, reference, load, elements, tangential, normal, preload, approach, name\\)"),
    ("harmonics = 7", "harmonicz = 7", "\\[sweep\\] has an unknown key 'harmonicz'; did you mean 'harmonics'"),
    ("C = [[17.32, 0.0], [0.0, 17.32]]", "Cx = [[17.32, 0.0], [0.0, 17.32]]",
     "\\[structure\\] has an unknown key 'Cx'; did you mean 'C'"),
    ("plot = [0, 1]", "plot = [0, 1]\nplots = [0]", "\\[output\\] has an unknown key 'plots'; did you mean 'plot'"),
    ('h1 = ["0.6N", "0N"]', 'h1 = ["0.6N"]', "block.toml: \\[excitation\\] h1 has 1 value\\(s\\); the structure has 2 "
     "DOFs"),
    ("harmonics = 7", 'harmonics = 7\nreduction = "fast"', "\\[sweep\\] reduction must be one of 'auto', 'none', "
     "'exact', 'modal', got 'fast'"),
    ('h1 = ["0.6N", "0N"]', 'h1 = ["0.6m", "0N"]', "unknown force unit 'm'"),
    ('h1 = ["0.6N", "0N"]', 'first = [0.6, 0.0]', "\\[excitation\\] has an unknown key 'first' \\(it accepts static, "
     "h<harmonic> such as h1, phase_h<harmonic> such as phase_h1, and scale\\)"),
    # the [excitation] table, its did-you-mean, and harmonics beyond the sweep's named with the file and table
    ('h1 = ["0.6N", "0N"]', 'statc = [0.0, 0.0]\nh1 = [0.6, 0.0]', "\\[excitation\\] has an unknown key 'statc'; "
     "did you mean 'static'\\?"),
    ('h1 = ["0.6N", "0N"]', 'h1 = [0.6, 0.0]\nphse_h1 = [0.0, 0.0]', "\\[excitation\\] has an unknown key 'phse_h1'; "
     "did you mean 'phase_h1'\\?"),
    ('h1 = ["0.6N", "0N"]', 'h9 = [0.6, 0.0]', "block.toml: \\[excitation\\] h9 is a harmonic above \\[sweep\\] "
     "harmonics = 7; raise harmonics to 9 or more, or remove h9"),
    ('h1 = ["0.6N", "0N"]', 'h1 = [0.6, 0.0]\nphase_static = [0.0, 0.0]', "\\[excitation\\] phase_static: a static "
     "force has no phase"),
    ("[excitation]", "[[excitation]]", "\\[excitation\\] must be a table, got \\[\\{'h1'"),
    ('preload = "37.5N"', 'PRELOAD = "37.5N"', "has an unknown key 'PRELOAD'; did you mean 'preload'\\?"),
    ("[[contact]]", "[contact]", "block.toml: contact must be an array of tables, written \\[\\[contact\\]\\] \\(one "
     "per contact\\), got a single table \\[contact\\]"),
    # DOF names: a string was split into letters, a repeated name gave two CSV columns of one name
    ('dofs = ["x", "y"]', 'dofs = "xy"', "\\[structure\\] dofs must be a list of names \\(non-empty strings\\), one "
     "per DOF, got 'xy'"),
    ('dofs = ["x", "y"]', 'dofs = ["x", "x"]', "\\[structure\\] dofs names 'x' twice; each DOF needs its own name"),
    ("plot = [0, 1]", 'plot = ["z"]', "\\[output\\] plot: 'z' is not a DOF \\(an index from 0 to 1, or one of the "
     "names x, y\\)"),
    ("plot = [0, 1]", 'plot = ["X"]', "\\[output\\] plot: 'X' is not a DOF; did you mean 'x'\\?"),
    ("plot = [0, 1]", "plot = 0", "\\[output\\] plot must be a list of DOFs \\(indices or names\\), got 0"),
    # sizes that ended in a MemoryError
    ("harmonics = 7", "harmonics = 100000", "\\[sweep\\] harmonics must be at most 256"),
    ("samples = 256", "samples = 9000000", "\\[sweep\\] samples must be at most 279620 with "
     "harmonics = 7"),
    ('model = "sphere_4_elements.json"', 'model = "nope.json"', "model file .*nope.json.* does not exist"),
    ('preload = "37.5N"', 'preload = "37.5N"\napproach = "1um"\nbogus = 1', "has an unknown key 'bogus' \\(it"),
    ("omega = [12000, 18000]", "omega = [12000]", "the range must have 2 values"),
    ("tangential = [0.8660254, 0.5]", "tangential = [1.0]", "tangential must have one coefficient per DOF"),
    ('dofs = ["x", "y"]', 'dofs = ["x"]', "dofs names 1 DOFs, the matrices have 2"),
    ("plot = [0, 1]", "plot = [4]", "plot names DOF 4; the structure has 2"),
    ("harmonics = 7", "harmonics = 7\n[continuation]\nstep = 1", "\\[continuation\\] has an unknown key 'step'"),
    ("M = [[0.1, 0.0], [0.0, 0.1]]", 'M = "heavy"', "\\[structure\\] M is a file name \\('heavy'\\) but K is written "
     "inline"),
    ("M = [[0.1, 0.0], [0.0, 0.1]]", "M = [[0.1, 0.0], [0.0, -0.1]]",
     "\\[structure\\] M must be positive definite: its diagonal entry 1 is -0.1"),
    ("omega = [12000, 18000]", 'omega = [12000, "18kN"]',
     "\\[sweep\\] omega\\[1\\] must be a frequency: a number \\(rad/s\\) or a string with a unit of angular "
     "frequency \\(rad/s, rpm\\) or frequency \\(Hz, kHz; converted with 2 pi\\), got '18kN'"),
    ("omega = [12000, 18000]", 'frequency = ["2kHz", "x"]', "\\[sweep\\] frequency\\[1\\] must be a frequency: a "
     "number \\(Hz\\)"),
    ("omega = [12000, 18000]", 'omega = "12000"', "\\[sweep\\] omega must be a list \\[start, end\\], got '12000'"),
    ("C = [[17.32, 0.0], [0.0, 17.32]]      # N s/m", "rayleigh = [1.0, 2.0, 3.0]",
     "\\[structure\\] rayleigh must be a list \\[alpha, beta\\] \\(1/s, s\\) giving C = alpha M \\+ beta K, "
     "got \\[1.0, 2.0, 3.0\\]"),
    ("C = [[17.32, 0.0], [0.0, 17.32]]      # N s/m", "rayleigh = 5", "\\[structure\\] rayleigh must be a list"),
    ("C = [[17.32, 0.0], [0.0, 17.32]]      # N s/m", 'rayleigh = [1.0, "x"]',
     "\\[structure\\] rayleigh\\[1\\]: cannot read 'x' as a number"),
    ("harmonic = 1", "harmonic = 9", "\\[output\\] harmonic must be at most \\[sweep\\] harmonics = 7 \\(or "
     "omitted for max \\|q - q0\\|\\), got 9"),
    ("harmonic = 1", 'harmonic = "one"', "\\[output\\] harmonic must be an integer, got 'one'"),
    ("harmonic = 1", "harmonic = -1", "\\[output\\] harmonic must be an integer >= 0, got -1"),
    ("harmonics = 7", "harmonics = 0", "\\[sweep\\] harmonics must be an integer >= 1, got 0"),
    ("samples = 256", "samples = 8", "\\[sweep\\] samples must be at least 2 \\* harmonics \\+ 1 "
     "= 15"),
    ("harmonics = 7", 'harmonics = 7\n[continuation]\nmax_angle = "big"',
     "\\[continuation\\] max_angle must be a real number, got 'big'"),
    ("harmonics = 7", "harmonics = 7\n[continuation]\nds_initial = -0.1",
     "\\[continuation\\] ds_initial must be positive, got -0.1"),
    ("harmonics = 7", "harmonics = 7\n[continuation]\nchord_error = 0.0",
     "\\[continuation\\] chord_error must be positive, got 0.0"),
    ("harmonics = 7", "harmonics = 7\n[continuation]\nchord_error = true",
     "\\[continuation\\] chord_error must be a positive number \\(the target\\) or false \\(no chord rule\\), got true"),
    ("harmonics = 7", 'harmonics = 7\n[continuation]\nchord_error = "fine"',
     "\\[continuation\\] chord_error must be a real number or false, got 'fine'"),
])
def test_config_errors_name_the_key(config_dir, old, new, message):
    cfg = config_dir / "block.toml"
    _edit(cfg, old, new)
    if message is None:  # extra keys in a contact table are tolerated; a preload and an approach together too
        load_config(cfg)
        return
    with pytest.raises((ConfigError, FileNotFoundError, ValueError), match=message):
        load_config(cfg)


def test_plot_takes_dof_names(config_dir):
    cfg = config_dir / "block.toml"
    _edit(cfg, "plot = [0, 1]", 'plot = ["y", 0]')
    assert load_config(cfg).plot_dofs == [1, 0]


def test_frf_reports_errors_without_traceback(config_dir, capsys):
    cfg = config_dir / "block.toml"
    _edit(cfg, "[sweep]", "[sweeep]")
    assert main(["frf", str(cfg)]) == 2
    assert "microslip frf: error:" in capsys.readouterr().err
    assert main(["frf", str(config_dir / "missing.toml")]) == 2


def test_frf_help_documents_every_option(capsys):
    with pytest.raises(SystemExit):
        main(["frf", "--help"])
    text = " ".join(capsys.readouterr().out.split())  # the description wrapped to the terminal: words rejoined
    for option in ("config", "--out", "--quiet", "microslip config-reference"):
        assert option in text


# -- issue 24, item 18: DOFs by name in [excitation] and [output]; a DOF map's names ----------------------------------

@pytest.mark.parametrize("table", ['h1 = {x = "0.6N"}', 'h1 = {"0" = 0.6}', 'h1 = {x = "0.4N", "0" = "200mN"}',
                                   'h1 = {x = 0.6, y = "0N"}'])
def test_the_excitation_takes_a_table_of_dofs_by_name_or_index(config_dir, table):
    cfg = config_dir / "block.toml"
    listed = load_config(cfg).force
    _edit(cfg, 'h1 = ["0.6N", "0N"]', table)
    by_name = load_config(cfg).force
    assert by_name.keys() == listed.keys()
    np.testing.assert_allclose(by_name[1], listed[1], rtol=1e-15)


def test_a_phase_table_goes_with_an_amplitude_table(config_dir):
    cfg = config_dir / "block.toml"
    _edit(cfg, 'h1 = ["0.6N", "0N"]', 'h1 = {x = 0.6, y = 0.3}\nphase_h1 = {y = 90}')
    np.testing.assert_allclose(load_config(cfg).force[1], [0.6, 0.3j], atol=1e-15)


@pytest.mark.parametrize("table, message", [
    ('h1 = {z = 0.6}', "block.toml: \\[excitation\\] h1: 'z' is not a DOF \\(an index from 0 to 1, or one of the names "
                       "x, y\\)"),
    ('h1 = {X = 0.6}', "\\[excitation\\] h1: 'X' is not a DOF; did you mean 'x'\\?"),
    ('h1 = {"2" = 0.6}', "\\[excitation\\] h1 names DOF 2; the structure has 2"),
    ('h1 = {x = "0.6m"}', "\\[excitation\\] h1\\['x'\\]: unknown force unit 'm'"),
    ('h1 = 0.6', "\\[excitation\\] h1 must be a list of numbers \\(one per DOF\\) or a table of DOFs, e.g. "
                 "\\{\"x\" = 1.0\\}, got 0.6"),
    ('h1 = [0.6, 0.0]\nphase_h1 = {w = 90}', "\\[excitation\\] phase_h1: 'w' is not a DOF"),
])
def test_a_bad_dof_in_the_excitation_is_named(config_dir, table, message):
    cfg = config_dir / "block.toml"
    _edit(cfg, 'h1 = ["0.6N", "0N"]', table)
    with pytest.raises(ConfigError, match=message):
        load_config(cfg)


def test_names_of_a_dof_map_in_the_excitation_and_the_outputs(config_dir):
    """With matrices read from a file and a DOF map, '1113:y' (or '1113:2') names a DOF in [excitation], [output]
    plot and [modes] dof: ``h1 = {"1113:y" = "1N"}`` used to fail with "unknown force unit ':y'"."""
    cfg = config_dir / "block.toml"
    np.savez(config_dir / "block.npz", M=0.1 * np.eye(2), K=1e7 * np.eye(2), C=17.32 * np.eye(2))
    (config_dir / "block_dofs.csv").write_text("node,component\n1113,x\n1113,y\n")
    _edit(cfg, "M = [[0.1, 0.0], [0.0, 0.1]]          # kg", 'file = "block.npz"\ndof_map = "block_dofs.csv"')
    _edit(cfg, "K = [[1e7, 0.0], [0.0, 1e7]]          # N/m\n", "")
    _edit(cfg, "C = [[17.32, 0.0], [0.0, 17.32]]      # N s/m\n", "")
    _edit(cfg, 'dofs = ["x", "y"]\n', "")
    _edit(cfg, 'h1 = ["0.6N", "0N"]', 'h1 = {"1113:x" = "0.6N"}\nstatic = {"1113:2" = "1N"}')
    _edit(cfg, "plot = [0, 1]", 'plot = ["1113:y", "1113:1"]')
    _edit(cfg, 'dof = "x"', 'dof = "1113:y"')
    c = load_config(cfg, nonlinear=True)
    np.testing.assert_array_equal(c.force[1], [0.6, 0.0])
    np.testing.assert_array_equal(c.force[0], [0.0, 1.0])
    assert c.plot_dofs == [1, 0] and c.nonlinear_mode.dof == 1 and c.dof_names == ["1113:x", "1113:y"]
    _edit(cfg, 'h1 = {"1113:x" = "0.6N"}', 'h1 = {"1114:x" = "0.6N"}')
    with pytest.raises(ConfigError, match="\\[excitation\\] h1: DOF '1114:x': node 1114 is not in the DOF map"):
        load_config(cfg)
