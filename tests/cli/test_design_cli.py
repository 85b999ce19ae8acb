"""``microslip design`` and the [cyclic] / [[damper]] tables of the frf configuration."""

import re

import numpy as np
import pytest

from microslip import Sphere, tune
from microslip.cli import main
from microslip.frequency import CyclicStructure, damper_design_curve
from microslip.config import ConfigError, load_config

import sys
from _paths import REPO

sys.path.insert(0, str(REPO / "tests" / "frequency"))
from test_damper import blade_pair, damper  # noqa: E402  (the same blade pair and damper)
from test_design import antiphase  # noqa: E402  (the same excitation)

CONFIG = """
title = "Blade pair with an under-platform damper"
[structure]
matrices = "pair.npz"
dofs = ["px0", "py0", "tip0", "px1", "py1", "tip1"]

[[damper]]
mass = 0.02
inertia = 1e-6
centrifugal_load = "50N"
damping = 200.0
[[damper.interface]]
model = "flat.json"
points = [[{p0x}, {p0y}], [{p1x}, {p1y}]]
angle = 135
platform = {{x = 0, y = 1}}
name = "flat"
[[damper.interface]]
model = "curved.json"
points = [["3mm", "2mm"]]
angle = 45
platform = {{x = 3, y = 4}}
name = "curved"

[excitation]
h1 = [0, 0, 0.5, 0, 0, 0]

[sweep]
omega = [3000, 5000]
harmonics = 3

[design]
loads = ["3N", "20N", "300N"]           # from a damper sliding through the cycle to a stuck one
dof = 2
"""


@pytest.fixture
def config(tmp_path):
    return write_config(tmp_path)


def write_config(folder, replace=lambda text: text):
    """The blade pair's matrices, its two contact models and :data:`CONFIG` (edited by ``replace``) in ``folder``."""
    s = blade_pair()
    np.savez(folder / "pair.npz", M=s.M, C=s.C, K=s.K)
    model = tune(Sphere.paper(), 37.5, elements=4)
    model.save(folder / "flat.json")
    model.save(folder / "curved.json")
    a = np.radians(135.0)
    tau = np.array([-np.sin(a), np.cos(a)])
    c = np.array([-3e-3, 2e-3])
    p0, p1 = c - 1.5e-3 * tau, c + 1.5e-3 * tau
    path = folder / "pair.toml"
    path.write_text(replace(CONFIG.format(p0x=p0[0], p0y=p0[1], p1x=p1[0], p1y=p1[1])))
    return path


def test_the_damper_table_builds_the_api_damper(config):
    cfg = load_config(config)
    assert cfg.structure.ndof == 9 and cfg.bare.ndof == 6 and len(cfg.dampers) == 1
    assert cfg.dof_names[-3:] == ["damper0 X", "damper0 Y", "damper0 R"]
    d, ref = cfg.dampers[0], damper(load=50.0)
    assert d.centrifugal_load == 50.0 and d.damping == ref.damping
    for a, b in zip(d.contacts, ref.contacts):
        assert a.platform == b.platform and np.allclose(a.point, b.point) and np.allclose(a.normal, b.normal)
    np.testing.assert_array_equal(cfg.design_loads, [3.0, 20.0, 300.0])


def test_microslip_design_writes_the_curve_of_the_api(config, tmp_path, capsys):
    # the tips in antiphase, as in test_design.py: the damper slides through the cycle at 3 N (pushed at one tip
    # only, the curve at 3 N does not reach 5000 rad/s in 5000 points); 128 samples resolve its slip
    config.write_text(config.read_text().replace("h1 = [0, 0, 0.5, 0, 0, 0]", "h1 = [0, 0, 0.5, 0, 0, -0.5]")
                      .replace("harmonics = 3\n", "harmonics = 3\nsamples = 128\n"))
    out = tmp_path / "out"
    assert main(["design", str(config), "--out", str(out), "--quiet"]) == 0
    for name in ("design.csv", "design.png", "report.html", "report.md"):
        assert (out / name).stat().st_size > 0
    api = damper_design_curve(blade_pair(), damper(), [3.0, 20.0, 300.0], antiphase(), (3000.0, 5000.0), dof=2,
                              harmonics=3, samples=128)
    rows = np.genfromtxt(out / "design.csv", delimiter=",", names=True)
    np.testing.assert_allclose(rows["peak_amplitude_m"], api.peak_amplitude, rtol=1e-10)
    assert "lowest peak" in capsys.readouterr().out


def test_the_damper_table_takes_the_retention(config):
    assert load_config(config).dampers[0].retention == 0.0  # the API's default when the key is absent
    config.write_text(config.read_text().replace("damping = 200.0", 'damping = 200.0\nretention = "2N/mm"'))
    cfg = load_config(config)
    assert cfg.dampers[0].retention == 2e3  # N/m: the unit converted
    # it reaches the attached structure: a spring on each of the damper's three DOFs
    np.testing.assert_array_equal(np.diag(cfg.structure.K)[6:], 2e3)


@pytest.mark.parametrize("value, message", [
    ("-1.0", "retention must be non-negative, got -1.0"),
    ("nan", "retention must be finite, got nan"),
    ("inf", "retention must be finite, got inf"),
    ('"3mm"', "retention: unknown stiffness unit 'mm'"),
])
def test_a_bad_retention_is_refused_naming_the_file_and_the_key(config, value, message):
    config.write_text(config.read_text().replace("damping = 200.0", f"damping = 200.0\nretention = {value}"))
    with pytest.raises(ConfigError, match=f"^{re.escape(str(config))}: \\[\\[damper\\]\\] 1.*{message}"):
        load_config(config)


@pytest.mark.parametrize("old, new, message", [
    ("mass = 0.02", "mas = 0.02", "\\[\\[damper\\]\\] has an unknown key 'mas'; did you mean 'mass'"),
    ("damping = 200.0", "retension = 1e3", "\\[\\[damper\\]\\] has an unknown key 'retension'; did you mean "
     "'retention'"),
    ("angle = 45", "angel = 45", "\\[\\[damper.interface\\]\\] has an unknown key 'angel'; did you mean 'angle'"),
    ("platform = {x = 3, y = 4}", 'platform = {x = "next:3", y = 4}', "names a next-sector DOF, which needs a "
     "\\[cyclic\\] table"),
    ("dof = 2", "dof = 7", "\\[design\\] dof names DOF 7; the structure has 6"),
    ("dof = 2", 'dof = "tipp0"', "\\[design\\] dof: 'tipp0' is not a DOF; did you mean 'tip0'\\?"),
    ("dof = 2", "dof = 2.0", "\\[design\\] dof: 2.0 is not a DOF \\(an index from 0 to 5, or one of the names px0"),
    ("dof = 2", 'dof = "damper0 X"', "\\[design\\] dof: 'damper0 X' is not a DOF"),  # the damper's own: not a peak
])
def test_damper_and_design_tables_are_checked(config, old, new, message):
    config.write_text(config.read_text().replace(old, new))
    with pytest.raises(ConfigError, match=message):
        load_config(config)


def cyclic(config, left="[0]"):
    """Make ``config`` a sector of 12 (boundaries ``left`` and DOF 3), its curved contact on the next sector."""
    text = config.read_text().replace('[excitation]', f'[cyclic]\nsectors = 12\nleft = {left}\nright = [3]\n'
                                      'engine_order = 2\n\n[excitation]')
    config.write_text(text.replace("platform = {x = 3, y = 4}", 'platform = {x = "next:0", y = 4}'))


@pytest.mark.parametrize("left", ["[0]", '["px0"]', '"px0"'])  # the boundaries by index or name (issue 24, item 18)
def test_a_cyclic_table_makes_a_sector(config, left):
    cyclic(config, left)
    cfg = load_config(config)
    assert isinstance(cfg.structure, CyclicStructure) and cfg.engine_order == 2 and cfg.structure.sectors == 12
    assert list(cfg.structure.left) == [0] and list(cfg.structure.right) == [3]
    assert cfg.structure.next_directions[-1][0][0] != 0  # the curved contact reaches the next sector's DOF 0


def test_a_cyclic_boundary_that_is_not_a_dof_is_named(config):
    cyclic(config, '["pz0"]')
    with pytest.raises(ConfigError, match="\\[cyclic\\] left: 'pz0' is not a DOF; did you mean 'py0'\\?"):
        load_config(config)


def test_the_design_dof_takes_a_name_and_the_damper_speed_rpm(config):
    """Issue 24, item 18: ``[design] dof`` needed an integer where [output] plot and [modes] dof take a name, and a
    rotation speed in rpm was an unknown unit."""
    config.write_text(config.read_text().replace("dof = 2", 'dof = "tip0"')
                      .replace('centrifugal_load = "50N"', 'speed = "3000rpm"\nradius = "0.25m"'))
    cfg = load_config(config)
    assert cfg.design_dof == 2
    assert cfg.dampers[0].centrifugal_load == pytest.approx(0.02 * 0.25 * (100 * np.pi) ** 2, rel=1e-14)


# -- loads without a peak, failures and Ctrl-C: marked, left out of the optimum, the command says so ---------------

def quick_config(folder, old="", new=""):
    """:data:`CONFIG` at 5 N (the damper slips) and 300 N (stuck), the tips in antiphase, one harmonic."""
    return write_config(folder, lambda text: text.replace('loads = ["3N", "20N", "300N"]', 'loads = ["5N", "300N"]')
                        .replace("h1 = [0, 0, 0.5, 0, 0, 0]", "h1 = [0, 0, 0.5, 0, 0, -0.5]")
                        .replace("harmonics = 3", "harmonics = 1").replace(old, new))


def design_rows(out):
    import csv

    return list(csv.DictReader(open(out / "design.csv")))


def test_design_from_curves_cut_short_fails_and_names_them(tmp_path, capsys):
    config = quick_config(tmp_path, "[design]", "[continuation]\nmax_points = 5\n\n[design]")
    out = tmp_path / "out"
    assert main(["design", str(config), "--out", str(out), "--quiet"]) == 1
    assert [r["status"] for r in design_rows(out)] == ["incomplete curve"] * 2
    err = capsys.readouterr().err
    assert "microslip design: error: 2 loads without a peak, left out of the optimum: load 5 N: the forced " in err
    assert "load 300 N: the forced response stopped at omega = " in err and "(raise [continuation] max_points)" in err
    report = (out / "report.md").read_text()
    assert "No optimum: no load has a peak inside the frequency range" in report and "Lowest peak" not in report
    assert "**Left out of the optimum**: load 300 N" in report


def test_design_over_a_range_that_stops_below_a_resonance_says_how_to_widen_it(tmp_path, capsys):
    config = quick_config(tmp_path, "omega = [3000, 5000]", "omega = [3000, 4200]")
    out = tmp_path / "out"
    assert main(["design", str(config), "--out", str(out), "--quiet"]) == 1
    rows = design_rows(out)
    assert [r["status"] for r in rows] == ["peak", "peak on the range's edge"]
    assert [r["peak on edge [-]"] for r in rows] == ["0", "1"]
    captured = capsys.readouterr()
    # the stuck damper's 5.76 um at 4200 rad/s is lower than the 5 N peak, and no peak: the optimum is 5 N
    assert captured.out.startswith("lowest peak 7.238 µm at 5 N (among the loads with a peak inside the range)")
    assert ("load 300 N: the response is highest at the end of the frequency range (4200 rad/s, 668.451 Hz) and "
            "still rises there: the resonance lies above it") in captured.err
    assert "raise the end of [sweep] omega past the resonance" in captured.err
    assert "microslip design: warning: load 300 N: the highest point of the curve is the end" in captured.err
    report = (out / "report.md").read_text()
    assert "| 300 | 5.759 | 668.451 | peak on the range's edge |" in report


def test_design_keeps_the_loads_finished_when_a_later_one_fails(tmp_path, capsys, monkeypatch):
    from test_design import fail_at

    fail_at(monkeypatch, 2, "the continuation stalled at omega = 4321 rad/s")
    out = tmp_path / "out"
    assert main(["design", str(quick_config(tmp_path)), "--out", str(out), "--quiet"]) == 1
    rows = design_rows(out)
    assert [r["status"] for r in rows] == ["peak", "failed"] and float(rows[0]["peak amplitude [m]"]) > 0
    err = capsys.readouterr().err
    assert "load 300 N: the forced response failed: the continuation stalled at omega = 4321 rad/s" in err
    assert "Traceback" not in err


def test_an_interrupted_design_writes_the_loads_finished_and_exits_130(tmp_path, capsys, monkeypatch):
    from test_design import interrupt_after

    interrupt_after(monkeypatch, 4, call=2)  # Ctrl-C in the second load's curve, at its fourth point
    out = tmp_path / "out"
    assert main(["design", str(quick_config(tmp_path)), "--out", str(out), "--quiet"]) == 130
    rows = design_rows(out)
    assert [r["status"] for r in rows] == ["peak", "incomplete curve"]
    assert [r["complete [-]"] for r in rows] == ["1", "0"]
    err = capsys.readouterr().err
    assert err.strip().splitlines()[-1].startswith("microslip design: interrupted: load 300 N: interrupted at omega")
    assert "Traceback" not in err
    assert "**Interrupted**" in (out / "report.md").read_text()


# -- a sector in the global Cartesian frame (issue 25, item 2) --------------------------------------------------
RIGHT_NODE = f"[{float(0.1 * np.cos(np.pi / 6))!r}, 0.05]"  # the left node (0.1, 0) turned by 2 pi / 12


def cartesian(config, coordinates=f"[[[0.1, 0.0]], [{RIGHT_NODE}]]", frame='"cartesian"'):
    """Make ``config`` a sector of 12 in the Cartesian frame: platform 0 (px0, py0) on the left boundary, platform 1
    on the right, the curved interface on the next sector's platform 0."""
    table = f'[cyclic]\nsectors = 12\nframe = {frame}\nleft = [["px0", "py0"]]\nright = [["px1", "py1"]]\n'
    if coordinates is not None:
        table += f"coordinates = {coordinates}\n"
    text = config.read_text().replace("[excitation]", table + "engine_order = 2\n\n[excitation]")
    config.write_text(text.replace("platform = {x = 3, y = 4}", 'platform = {x = "next:0", y = "next:1"}'))


def test_a_cyclic_table_takes_the_cartesian_frame(config):
    cartesian(config)
    cfg = load_config(config)
    c, s = np.cos(np.pi / 6), np.sin(np.pi / 6)
    for sector in (cfg.bare, cfg.structure):  # the damper attached keeps the frame
        assert isinstance(sector, CyclicStructure) and sector.frame == "cartesian"
        np.testing.assert_allclose(sector.boundary_rotation.toarray(), [[c, -s], [s, c]], rtol=0, atol=1e-16)
    given = cfg.structure.next_directions[-1][0][:2]  # the curved contact on the next sector's platform, global
    np.testing.assert_allclose(cfg.structure.contact_directions_next()[0][:2, -1], given @ [[c, -s], [s, c]],
                               rtol=0, atol=1e-15)  # R^T given: in this sector's frame


@pytest.mark.parametrize("change, message", [
    ({"coordinates": "[[[0.1, 0.0]], [[0.0866, 0.06]]]"}, "\\[cyclic\\] coordinates: the right boundary's node 0 "
     "\\(left DOFs \\[0, 1\\], right DOFs \\[3, 4\\]\\) at \\[0.0866, 0.06, 0\\] m is 0.01 m from its left node"),
    ({"coordinates": None}, "\\[cyclic\\] coordinates must be given with frame='cartesian'"),
    ({"coordinates": '"nodes.csv"'}, "\\[cyclic\\] coordinates file .*nodes.csv' does not exist"),
    ({"coordinates": "[0.1, 0.0]"}, "\\[cyclic\\] coordinates must be a file name, a table"),
    ({"frame": '"polar"'}, "\\[cyclic\\] frame must be one of 'cylindrical', 'cartesian', got 'polar'"),
])
def test_a_cartesian_cyclic_table_is_checked(config, change, message):
    cartesian(config, **change)
    with pytest.raises((ConfigError, FileNotFoundError), match=message):
        load_config(config)


def test_the_coordinates_may_come_from_the_dof_map_file(config):
    """A DOF map with x, y columns names the boundaries' nodes and places them."""
    rows = [(10, "x", 0.1, 0.0), (10, "y", 0.1, 0.0), (12, "z", 0.2, 0.0), (11, "x", 0.1 * np.cos(np.pi / 6), 0.05),
            (11, "y", 0.1 * np.cos(np.pi / 6), 0.05), (13, "z", 0.17, 0.1)]
    (config.parent / "dofs.csv").write_text("node,component,x,y\n" + "".join(f"{n},{c},{float(x)!r},{y!r}\n"
                                                                              for n, c, x, y in rows))
    config.write_text(config.read_text().replace('matrices = "pair.npz"', 'file = "pair.npz"\ndof_map = "dofs.csv"')
                      .replace('dofs = ["px0", "py0", "tip0", "px1", "py1", "tip1"]\n', ""))
    cartesian(config, coordinates='"dofs.csv"')
    config.write_text(config.read_text().replace('[["px0", "py0"]]', '["10:x", "10:y"]')
                      .replace('[["px1", "py1"]]', '["11:1", "11:2"]'))
    cfg = load_config(config)
    assert cfg.bare.frame == "cartesian" and list(cfg.bare.left) == [0, 1] and list(cfg.bare.right) == [3, 4]
    np.testing.assert_allclose(cfg.bare.coordinates[1, 0], [0.1 * np.cos(np.pi / 6), 0.05, 0.0], rtol=0, atol=0)
    (config.parent / "nodes.csv").write_text("node,x,y\n10,0.1,0\n# the same node elsewhere\n10,0.1,0.001\n")
    config.write_text(config.read_text().replace('coordinates = "dofs.csv"', 'coordinates = "nodes.csv"'))
    with pytest.raises(ConfigError, match="nodes.csv: line 4: node 10 at \\[0.1, 0.001\\] m, but at \\[0.1, 0.0\\] m"):
        load_config(config)
