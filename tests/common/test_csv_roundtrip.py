"""Every CSV the project writes reads back, unchanged, through csv, numpy.genfromtxt and pandas without options."""

import csv
import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

from microslip import MicroslipModel, Sphere, accuracy, mdr, paths, tune  # noqa: E402
from microslip.cli import main  # noqa: E402
from microslip.common._io import write_csv  # noqa: E402
from microslip.frequency import Structure, frequency_response  # noqa: E402

# pandas < 3.1 reads floats exactly only with float_precision="round_trip"; 3.1 reads them all with that
# converter and deprecates the option (a Pandas4Warning per call)
ROUND_TRIP = {"float_precision": "round_trip"} if tuple(map(int, pd.__version__.split(".")[:2])) < (3, 1) else {}


@pytest.fixture(scope="module")
def reproduce_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("reproduce")
    assert main(["reproduce", "--out", str(out), "--quiet"]) == 0
    return out


@pytest.fixture(scope="module")
def other_csvs(tmp_path_factory):
    """One CSV of each other kind: `microslip accuracy`, FrequencyResponse.to_csv, `microslip simulate`,
    `microslip target --sweep`, AccuracyReport.to_csv."""
    out = tmp_path_factory.mktemp("others")
    model = out / "model.json"
    assert main(["tune", "-o", str(model)]) == 0
    assert main(["accuracy", str(model), "--out", str(out / "acc"), "--mdr-elements", "200",
                 "--steps-per-cycle", "16", "--quiet"]) == 0
    history = out / "history.csv"
    history.write_text("t [um], n [um]\n0, 2\n0.5, 2\n1.0, 2.1\n-1.0, 2\n")
    assert main(["simulate", str(model), str(history), "-o", str(out / "forces.csv")]) == 0
    assert main(["target", "--sweep", "2-3", "--reuse-points", "--out", str(out / "target"), "--quiet"]) == 0
    s = Structure(M=[[1.0]], C=[[1.0]], K=[[1e4]])
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential=0, approach=1e-6)
    frequency_response(s, [2.0], (80, 120), harmonics=3).to_csv(out / "frf.csv")
    sphere = Sphere.paper()
    family = paths.default_family(sphere, 37.5, ratios=(0.0, 0.6), phases_deg=(0.0,), amplitudes=(0.5,),
                                  levels=(1.0,), steps_per_cycle=16)
    accuracy(tune(sphere, 37.5, elements=2), mdr(sphere, max_load=37.5, elements=100), family).to_csv(
        out / "report.csv")
    return [out / "acc" / "accuracy.csv", out / "forces.csv", out / "target" / "sweep.csv", out / "frf.csv",
            out / "report.csv"]


def _number(cell: str) -> float:
    return math.nan if cell == "" else float(cell)


def check_round_trip(path):
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    header, data = rows[0], rows[1:]
    assert data, f"{path.name}: no data row"
    widths = {len(r) for r in rows}
    assert widths == {len(header)}, f"{path.name}: rows of {sorted(widths)} fields, the header has {len(header)}"
    numeric = [j for j in range(len(header)) if all(_is_number(r[j]) for r in data)]
    expected = {j: np.array([_number(r[j]) for r in data]) for j in numeric}

    table = np.genfromtxt(path, names=True, delimiter=",", dtype=None, encoding="utf-8")
    table = np.atleast_1d(table)
    assert len(table.dtype.names) == len(header) and table.shape == (len(data),)
    for j, values in expected.items():
        got = np.asarray(table[table.dtype.names[j]], dtype=float)
        np.testing.assert_array_equal(got, values, err_msg=f"{path.name}, numpy, column {header[j]!r}")

    frame = pd.read_csv(path)
    assert list(frame.columns) == header and frame.shape == (len(data), len(header))
    for j, values in expected.items():
        got = frame.iloc[:, j].to_numpy(dtype=float)
        # pandas' default C float parser (before 3.1) is not correctly rounded on 17-digit numbers with large
        # exponents (measured up to 3.5e-13 relative on these files); with ROUND_TRIP it reads repr()
        # exactly, checked next
        np.testing.assert_allclose(got, values, rtol=1e-12, atol=0, err_msg=f"{path.name}, pandas, {header[j]!r}")
        exact = pd.read_csv(path, **ROUND_TRIP).iloc[:, j].to_numpy(dtype=float)
        np.testing.assert_array_equal(exact, values)


def _is_number(cell: str) -> bool:
    try:
        _number(cell)
    except ValueError:
        return False
    return True


REPRODUCED = ["fig2a", "fig2b", "fig3a", "fig3b", "fig4a", "fig4b", "fig6", "accuracy", "accuracy_sweep",
              "accuracy_amplitude"]


@pytest.mark.parametrize("name", REPRODUCED)
def test_every_csv_of_reproduce_round_trips(reproduce_dir, name):
    check_round_trip(reproduce_dir / f"{name}.csv")


def test_reproduce_writes_no_other_csv(reproduce_dir):
    assert sorted(p.stem for p in reproduce_dir.glob("*.csv")) == sorted(REPRODUCED)


@pytest.mark.parametrize("k", range(5), ids=["accuracy-cli", "simulate-cli", "target-sweep", "frequency-response",
                                              "accuracy-report"])
def test_every_other_csv_round_trips(other_csvs, k):
    check_round_trip(other_csvs[k])


def test_padding_and_text_cells_round_trip(tmp_path):
    path = write_csv(tmp_path / "p.csv", {"x [m]": [0.1, 1e-300, -2.5e10], "label": ["a; b", "c", "d"],
                                          "short [N]": [1.5], "k [-]": np.array([1, 2, 3])})
    check_round_trip(path)
    assert pd.read_csv(path)["short [N]"].isna().sum() == 2


@pytest.mark.parametrize("columns, message", [
    ({"a, b [m]": [1.0]}, "the column name 'a, b \\[m\\]' holds one of"),
    ({'say "x"': [1.0]}, "the column name 'say \"x\"' holds one of"),
    ({"# n": [1.0]}, "the column name '# n' holds one of"),
    ({"path": ["N = 1, t = 2"]}, "a cell 'N = 1, t = 2' of column 'path' holds one of"),
])
def test_names_and_cells_that_break_parsers_are_refused(tmp_path, columns, message):
    with pytest.raises(ValueError, match=message):
        write_csv(tmp_path / "x.csv", columns)
    assert not (tmp_path / "x.csv").exists()
