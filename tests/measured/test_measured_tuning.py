"""End to end on the shipped synthetic data: tune at the highest load, validate at the others,
the Fig. 4-like transition, the report, the Fig. 6 section and the command line."""

import json
import re

import matplotlib
import numpy as np
import pytest

from microslip import Cylinder, MicroslipModel, Sphere, loops, tune, tune_on_loops, validate
from microslip.cli import main
from microslip.figures import SECTIONS, fig6
from microslip.measured.loop_tuning import raised_load_path
from microslip.loops.synthetic import dataset_files, normal_curve_file
from microslip.tuning import model_from_points
from _paths import DAMPER

matplotlib.use("Agg")
GEOM = dict(length=10e-3, radius=5e-3, E=200e9, nu=0.3)


@pytest.fixture(scope="module")
def records():
    return [loops.analyse(loops.read(p)) for p in dataset_files()]


@pytest.fixture(scope="module")
def result(records):
    return tune_on_loops(records, Cylinder.from_file(normal_curve_file(), **GEOM), elements=6)


def test_model_tuned_at_the_highest_load_reproduces_the_lower_ones(result):
    assert result.model.elements == 6 and result.reference.normal_load == pytest.approx(36.6)
    assert [round(v.normal_load, 1) for v in result.validation.loads] == [36.6, 31.6, 26.5, 21.5, 16.4]
    worst = result.validation.worst()
    # the specimen obeys the superposition rule and its normal curve is given: the 6-element array
    # misses only by its discreteness and the noise (the stiffness most: the array is straight until
    # its first element slips, the data curve). The README states what this measures: 0.552 % in
    # energy, 0.723 % in slip force, 4.62 % in stick stiffness. The data, the fit and the tuning are
    # deterministic; each bound is that value rounded up to the next 0.1 %, a margin of 0.05-0.08
    # points, more than 15 times what a relative perturbation of 1e-6 of every displacement sample
    # moves them (<= 0.003 points; round-off differences between platforms are far smaller)
    assert worst["energy"] < 0.006 and worst["slip_force"] < 0.008 and worst["stiffness"] < 0.047
    assert len(result.validation.rows()) == 5 and len(result.validation.rows()[0]) == len(result.validation.HEADERS)


def test_wrong_normal_law_shows_in_the_validation(records, result):
    palmgren = tune_on_loops(records, Cylinder(**GEOM, law="palmgren"), elements=6)
    # same branch, same tangential stiffnesses; only the normal law differs
    np.testing.assert_allclose(palmgren.model.kt, result.model.kt, rtol=1e-12)
    # the README: 5.54 % in energy, 0.69 % in slip force, 14.0 % in stiffness with Palmgren's law;
    # above, each rounded up to the next 0.1 % (as in the test above); below, the wrong law must show
    # (energy and stiffness errors at least 9/10 of what the README states)
    worst = palmgren.validation.worst()
    assert 0.05 < worst["energy"] < 0.056 and worst["slip_force"] < 0.007 and 0.126 < worst["stiffness"] < 0.141
    assert worst["energy"] > 2 * result.validation.worst()["energy"]


def test_model_gives_mu_n_at_every_load(result):
    mu = result.reference.mu
    for v in result.validation.loads:
        n = float(result.reference.approach(v.normal_load))
        # exact at the tuning load (eq. 8) and at each gap (eq. 9); between gaps the array's normal
        # curve is the chord of the convex law (6 gaps over the range): within 2 %
        rel = 1e-9 if v.normal_load == result.reference.normal_load else 0.02
        assert float(result.model.slip_force(n)) == pytest.approx(mu * v.normal_load, rel=rel)
    gaps = result.model.gaps[1:]
    np.testing.assert_allclose(result.model.normal_force(gaps), result.reference.normal_force(gaps), rtol=1e-9)


def test_transition_joins_the_curve_at_the_higher_load(result):
    d = result.transition()
    # before: points=2.5 failed inside numpy, points=0 gave an empty reference curve
    with pytest.raises(TypeError, match=r"points must be an integer, got 2\.5"):
        result.transition(points=2.5)
    with pytest.raises(ValueError, match=r"points must be an integer >= 3, got 0"):
        result.transition(points=0)
    assert d["N"] == pytest.approx(16.4) and d["N"] + d["dN"] == pytest.approx(36.6)
    mu = result.reference.mu
    # the model ends in gross slip at the higher load, like the reference
    assert d["T_model"][-1] == pytest.approx(mu * 36.6, rel=1e-9)
    assert d["T_reference"][-1] == pytest.approx(mu * 36.6)
    # up to point A both follow the lower-load curve; the array's chords stay within 5 % of mu N
    t = d["t_model"][d["t_model"] <= d["t_reference"][np.searchsorted(d["T_reference"], d["T_A"])]]
    ref_T = np.interp(t, d["t_reference"], d["T_reference"])
    assert np.max(np.abs(d["T_model"][: t.size] - ref_T)) < 0.05 * mu * 16.4


def test_raised_load_path_on_the_sphere_matches_its_closed_form():
    s = Sphere.paper()
    N, dN, T_A = 25.0, 12.5, 5.0
    T = np.linspace(0, 0.4 * (N + dN), 50)
    # Cattaneo-Mindlin: t(T; N) = c (N^(2/3) - (N - T/mu)^(2/3)), with c = t_gs(N) / N^(2/3) the same at all loads
    c = float(s.gross_slip_displacement(N)) / N ** (2 / 3)
    virgin = lambda T_, N_: c * (N_ ** (2 / 3) - (N_ - T_ / 0.4) ** (2 / 3))  # noqa: E731
    T_B = T_A + 0.4 * dN
    closed = np.where(T <= T_A, virgin(np.minimum(T, 0.4 * N), N),
                      np.where(T <= T_B, virgin(T_A, N) + virgin(np.clip(T - T_A, 0, None), N + dN),
                               virgin(T, N + dN)))
    np.testing.assert_allclose(raised_load_path(s, T, N, dN, T_A), closed, rtol=1e-12, atol=1e-18)
    with pytest.raises(ValueError, match=r"T_A must not exceed mu\*N = 10 N, got 11 N"):
        raised_load_path(s, T, N, dN, 11.0)
    with pytest.raises(ValueError, match=re.escape("T must lie in [0, mu*(N+dN)] = [0, 15] N, got 16 N")):
        raised_load_path(s, [1.0, 16.0], N, dN, T_A)


def test_tune_on_loops_chooses_the_points_once(records, result, monkeypatch):
    import microslip.tuning._front as front

    def twice(*args, **kwargs):
        raise AssertionError("tuning points computed a second time")

    monkeypatch.setattr(front, "tuning_points", twice)  # what tune() would call again
    again = tune_on_loops(records, Cylinder.from_file(normal_curve_file(), **GEOM), elements=6)
    monkeypatch.undo()
    # the same model as tune() on the same reference
    assert again.model == tune(result.reference, result.reference.normal_load, elements=6) == result.model
    with pytest.raises(TypeError, match="points must be TuningPoints"):
        model_from_points(result.reference, (result.points.t, result.points.T))


def test_report_leaves_the_backend_and_pyplot_alone(result, tmp_path):
    import matplotlib.pyplot as plt

    matplotlib.use("svg")  # stands for a user's own backend
    try:
        figures = plt.get_fignums()
        result.report(tmp_path, stem="b")
        assert matplotlib.get_backend() == "svg" and plt.get_fignums() == figures
    finally:
        matplotlib.use("Agg")
    assert (tmp_path / "b-branch.png").read_bytes()[:4] == b"\x89PNG"


def test_plots_and_report(result, tmp_path):
    for ax in (result.plot_branch(), result.plot_elements(), result.plot_elements(16.4), result.plot_normal(),
               result.plot_transition(), result.validation.plot(), result.reference.fit.plot()):
        assert ax.get_xlabel() and "(N)" in ax.get_ylabel()
    with pytest.raises(ValueError, match=r"normal_load: no record at 20 N"):
        result.plot_elements(20.0)
    html, md = result.report(tmp_path, stem="cyl")
    text = md.read_text(encoding="utf-8")
    assert "Validation at the other loads" in text and "cyl-normal.png" in text
    assert html.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    assert (tmp_path / "cyl-elements.png").stat().st_size > 1000


def test_validate_checks_its_model(records):
    with pytest.raises(TypeError, match="model must be a MicroslipModel"):
        validate("model", Cylinder(**GEOM), records)
    m = MicroslipModel(kt=[1e7], kn=[1e8], gaps=[0.0], mu=0.4)
    with pytest.raises(TypeError, match=r"normal must provide approach\(\) of a normal law \(e.g. "
                                        r"microslip.Cylinder\); str lacks approach"):
        validate(m, "palmgren", records)

    class Broken:
        def approach(self, N):
            return float("nan")

    with pytest.raises(ValueError, match=r"normal.approach\(36.6 N\) must be finite, got nan"):
        validate(m, Broken(), records)
    v = validate(m, Cylinder(**GEOM), records[:1])
    assert v.loads[0].predicted.cycles == records[0].cycles


def test_fig6_section_follows_the_contract():
    assert fig6 in SECTIONS
    data = fig6.compute(None)
    fig = fig6.plot(data)
    assert len(fig.axes) == 4
    cols = fig6.columns(data)
    assert all(np.asarray(v).ndim == 1 for v in cols.values())
    # the cylinder is measured against a model, not discrete against continuous: its own table
    assert fig6.error_rows(data) == []
    (caption, headers, rows), = fig6.tables(data)
    assert "SYNTHETIC" in caption and headers == fig6.TABLE_HEADERS
    assert len(rows) == 15 and all(len(r) == len(headers) for r in rows)
    # the tuning load is marked as such, the four others as predictions
    roles = {r[0]: r[1] for r in rows}
    assert roles["36.6"] == "tuning load (fitted, not a prediction)"
    assert [k for k, role in roles.items() if role.startswith("predicted")] == ["31.6", "26.5", "21.5", "16.4"]
    for load, role, quantity, measured, model, diff, bound, why in rows:
        assert diff == pytest.approx(100 * (model - measured) / measured, rel=1e-9)
        assert abs(diff) < bound and len(why) > 20  # every bound holds, and says why it is what it is


def test_reproduce_writes_the_fig6_table(tmp_path):
    from microslip.figures import reproduce

    reproduce(tmp_path, sections=[fig6], progress=False)
    md = (tmp_path / "report.md").read_text(encoding="utf-8")
    assert "| N (N) | role | quantity | measured | model |" in md and "tuning load (fitted, not a prediction)" in md
    assert "cylinder 36.6 N" not in md  # no longer in the discrete-vs-continuous table


# -- command line ------------------------------------------------------------------------------------

def test_cli_tunes_on_loops_and_writes_a_report(tmp_path, capsys):
    out = tmp_path / "model.json"
    files = [str(p) for p in dataset_files()]
    rc = main(["tune", *files, "--normal-law", "palmgren", "--length", "10mm", "--radius", "5mm",
               "--elements", "6", "-o", str(out), "--quiet"])
    assert rc == 0
    summary = json.loads(capsys.readouterr().out)
    model = MicroslipModel.load(out)
    assert model.elements == 6 and summary["mu"] == pytest.approx(0.4, rel=0.005)
    assert (tmp_path / "model-report.html").is_file() and (tmp_path / "model-report.md").is_file()


def test_cli_table_law_mu_and_load_suffix(tmp_path, capsys):
    out = tmp_path / "m.json"
    first = str(dataset_files()[-1])
    rc = main(["tune", f"{first}@36.6N", "--normal-law", str(normal_curve_file()), "--mu", "0.41",
               "--elements", "3", "-o", str(out), "--report", str(tmp_path / "rep"), "--quiet"])
    assert rc == 0
    assert MicroslipModel.load(out).mu == 0.41
    assert (tmp_path / "rep" / "m-report.md").is_file()


def test_cli_errors_are_plain(tmp_path, capsys):
    rc = main(["tune", str(dataset_files()[0]), "--normal-law", "hertz", "-o", str(tmp_path / "x.json"), "--quiet"])
    assert rc == 2 and "--normal-law must be 'palmgren', 'lundberg' or an existing table file" in capsys.readouterr().err
    rc = main(["tune", str(tmp_path / "absent.csv"), "-o", str(tmp_path / "x.json"), "--quiet"])
    assert rc == 2 and "does not exist" in capsys.readouterr().err


def test_cli_without_loops_still_tunes_the_sphere(tmp_path, capsys):
    out = tmp_path / "s.json"
    assert main(["tune", "-o", str(out)]) == 0
    m = MicroslipModel.load(out)
    assert m.elements == 4 and m.mu == 0.4


def test_cli_help_explains_the_loop_options(capsys):
    with pytest.raises(SystemExit):
        main(["tune", "--help"])
    text = capsys.readouterr().out
    for option in ("LOOPS", "--normal-law", "--length", "--t-column", "--report", "@LOAD"):
        assert option in text


def test_cli_loop_options_have_distinct_metavars(capsys):
    with pytest.raises(SystemExit):
        main(["tune", "--help"])
    text = capsys.readouterr().out
    # before: --t-column and --T-column both showed T_COLUMN, --t-unit and --T-unit both T_UNIT
    shown = {option: re.search(rf"{option} ([A-Z_]+)", text).group(1)
             for option in ("--t-column", "--T-column", "--N-column", "--t-unit", "--T-unit")}
    assert shown == {"--t-column": "DISP_COLUMN", "--T-column": "FORCE_COLUMN", "--N-column": "LOAD_COLUMN",
                     "--t-unit": "DISP_UNIT", "--T-unit": "FORCE_UNIT"}


def _loops_file(tmp_path, header, name="run.csv"):
    k = np.arange(64)
    rows = [f"{i * 1e-3:g},{np.sin(i / 8):.6f},{10 * np.cos(i / 8):.6f}" for i in k]
    path = tmp_path / name
    path.write_text(header + "\n" + "\n".join(rows) + "\n")
    return str(path)


@pytest.mark.parametrize("header, options, message", [
    # before: "name it with columns={'T': ...}", Python advice on the command line
    ("time [s],t [um],Fx [N]", [], "no column for 'T' (force): looked for ['T', 'F', 'force', 'friction force', "
                                   "'tangential force'], the columns are ['time', 't', 'Fx']; name it with "
                                   "--T-column NAME"),
    ("time [s],t [um],T [N]", ["--t-column", "disp"], "no column 'disp' (given by --t-column); the columns are"),
    ("time [s],t [um],T [N]", ["--N-column", "load"], "no column 'load' (given by --N-column); the columns are"),
    ("time [s],t,T [N]", [], "column 't' (length) has no unit in the header; write it as 't [unit]' or give "
                             "--t-unit UNIT"),
    # before: "units['t'] (--t-unit) gives 'mm'"
    ("time [s],t [um],T [N]", ["--t-unit", "mm"], "column 't' is in 'um' by its header, but --t-unit gives 'mm'; "
                                                  "--t-unit only applies"),
    ("time [s],t [um],T [N]", ["--T-unit", "kN"], "column 'T' is in 'N' by its header, but --T-unit gives 'kN'"),
])
def test_cli_loop_file_messages_name_the_options(tmp_path, capsys, header, options, message):
    path = _loops_file(tmp_path, header)
    rc = main(["tune", path, *options, "-o", str(tmp_path / "m.json"), "--quiet"])
    err = capsys.readouterr().err
    assert rc == 2 and f"{path}: {message}" in err
    assert "columns=" not in err and "units[" not in err and "units=" not in err


def test_cli_refuses_a_load_that_is_not_positive(tmp_path, capsys):
    path = _loops_file(tmp_path, "time [s],t [um],T [N]")
    rc = main(["tune", f"{path}@-5N", "-o", str(tmp_path / "m.json"), "--quiet"])
    # before: "normal_load must be positive", a name the command line does not have
    assert rc == 2 and f"the load of {path} ('{path}@-5N') must be positive, got '-5N'" in capsys.readouterr().err


def test_cli_refuses_the_damper_data_with_numbers(tmp_path, capsys):
    rc = main(["tune", str(DAMPER / "1Hz80lbtension.json"), "-o", str(tmp_path / "d.json"), "--quiet"])
    err = capsys.readouterr().err
    # a band brake with free play: the branches soften and stiffen again
    assert rc == 2 and "not concave (backlash)" in err and "times stiffer" in err
    assert not (tmp_path / "d.json").exists()
