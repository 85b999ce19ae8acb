"""Reports as an engineer reads them: version, date and parameters first; aligned tables; one energy unit."""

import datetime
import re

import pytest

from microslip.common._version import __version__
from microslip.common.report import ENERGY_UNIT, Energy, Report, energy_unit, plural


def _md_table(md: str, first_header: str):
    """Header, alignment row and rows of the Markdown table whose first header cell is ``first_header``."""
    lines = md.splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith(f"| {first_header} |"))
    rows = []
    for ln in lines[k + 2:]:
        if not ln.startswith("|"):
            break
        rows.append([c.strip() for c in ln.strip("|").split("|")])
    return [c.strip() for c in lines[k].strip("|").split("|")], lines[k + 1], rows


def test_plural():
    assert plural(1, "element") == "1 element"
    assert plural(0, "element") == "0 elements" and plural(4, "path") == "4 paths"
    assert plural(2, "index", "indices") == "2 indices"


@pytest.mark.parametrize("values, unit", [([1.2e-5, 3e-7], "µJ"), ([2.5e-3, 1e-6], "mJ"), ([4.0], "J"),
                                          ([5e-9], "nJ"), ([3e-12], "nJ"), ([], "J"), ([0.0], "J"),
                                          ([float("nan"), 2e-6], "µJ")])
def test_energy_unit_follows_the_largest_magnitude(values, unit):
    assert energy_unit(values)[0] == unit


def test_report_states_version_date_and_parameters():
    rep = Report("t", parameters={"tuning load N_tot": "37.5 N", "elements J": 4})
    md, html = rep.to_markdown(), rep.to_html()
    header, _, rows = _md_table(md, "run")
    assert rows[0] == ["microslip version", __version__]
    assert rows[1][0] == "date" and rows[1][1].startswith(datetime.date.today().isoformat())
    assert rows[2:] == [["tuning load N_tot", "37.5 N"], ["elements J", "4"]]
    assert f"<td>{__version__}</td>" in html and "tuning load N_tot" in html
    # the run table comes first, before anything added
    rep2 = Report("t")
    rep2.text("body")
    assert rep2.to_markdown().index("microslip version") < rep2.to_markdown().index("body")


def test_text_left_numbers_right_and_never_broken():
    rep = Report("t")
    rep.table(["quantity", "value", "error (%)", "note"],
              [["a long label", 1.5, "12.3", "text"], ["b", None, "167 / 30.1", ""], ["c", 3, "-1e-05", "x"]])
    _, align, rows = _md_table(rep.to_markdown(), "quantity")
    assert align == "|:---|---:|---:|:---|"
    assert rows[1] == ["b", "", "167 / 30.1", ""]
    html = rep.to_html()
    assert ".num{text-align:right;white-space:nowrap}" in html.replace(" ", "")
    assert "<tr><td>a long label</td><td class='num'>1.5</td><td class='num'>12.3</td><td>text</td></tr>" in html
    assert "<th>quantity</th><th class=num>value</th>" in html


def test_one_energy_unit_for_the_whole_report():
    rep = Report("t")
    rep.text(f"energies in {ENERGY_UNIT}")
    rep.table(["quantity", f"W ({ENERGY_UNIT})"], [["small", Energy(4e-6)]])
    rep.table([f"energy ({ENERGY_UNIT})"], [[Energy(2.5e-3)]], caption=f"in {ENERGY_UNIT}")
    md = rep.to_markdown()
    # the largest energy (2.5 mJ) sets the unit of every table and of the text
    assert "energies in mJ" in md and "*in mJ*" in md and "| W (mJ) |" in md and "| energy (mJ) |" in md
    assert "| small | 0.004 |" in md and "| 2.5 |" in md
    assert ENERGY_UNIT not in md and ENERGY_UNIT not in rep.to_html()


@pytest.fixture(scope="module")
def loop_report(tmp_path_factory):
    from microslip.figures import fig6
    from microslip.measured.loop_report import write_report

    out = tmp_path_factory.mktemp("loops")
    result = fig6.compute()["result"]
    _, md = write_report(result, out, parameters={"command": "microslip tune ..."})
    return result, md.read_text(encoding="utf-8")


def test_loop_report_states_every_parameter(loop_report):
    result, md = loop_report
    _, _, rows = _md_table(md, "run")
    names = [r[0] for r in rows]
    assert names[:2] == ["microslip version", "date"]
    for name in ("records", "tuning load N_tot", "elements J", "tuning points T", "normal law",
                 "friction coefficient mu", "command"):
        assert name in names
    assert dict((r[0], r[1]) for r in rows)["elements J"] == str(result.model.elements)


def test_loop_report_has_one_energy_unit(loop_report):
    _, md = loop_report
    units = set(re.findall(r"energy[^|]*\((\w?J)\)", md))
    # the synthetic loops dissipate 7 to 12 µJ per cycle: µJ in both tables
    assert units == {"µJ"}
    assert not re.search(r"\b1 elements\b", md) and "issue" not in md.lower()


def test_a_figure_is_saved_into_the_report_and_closed(tmp_path):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot([0.0, 1.0], [0.0, 1.0])
    rep = Report("t")
    path = rep.figure(fig, "line", "A line.", tmp_path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"  # a PNG file, the one the report embeds
    assert fig.number not in plt.get_fignums()  # closed: the report holds its picture
    assert "A line." in rep.to_markdown()
