"""The ``[[damper]]`` table's angles, platform DOFs and what the damper refuses, read from a configuration."""

import re

import numpy as np
import pytest

from microslip.config import ConfigError, load_config
from test_design_cli import write_config  # the blade pair with its damper, its faces' normals at 135 and 45 degrees

CYCLIC = "[cyclic]\nsectors = 12\nleft = [2]\nright = [5]\nengine_order = 2\n\n[excitation]"  # the tips


@pytest.fixture
def config(tmp_path):
    return write_config(tmp_path)


def normals(path):
    return [c.normal for c in load_config(path).dampers[0].contacts]


def refused(config, old: str, new: str, message: str, *, sector: bool = False) -> None:
    """The configuration with ``old`` replaced by ``new`` (and a [cyclic] table) is refused: the file, ``message``."""
    text = config.read_text().replace(old, new)
    config.write_text(text.replace("[excitation]", CYCLIC) if sector else text)
    with pytest.raises(ConfigError, match=f"^{re.escape(str(config))}: {re.escape(message)}"):
        load_config(config)


@pytest.mark.parametrize("angle", ['"45deg"', '"45°"', f'"{float(np.radians(45.0))!r}rad"', "45", "45.0"])
def test_an_angle_is_degrees_or_carries_its_unit(config, angle):
    reference = normals(config)
    config.write_text(config.read_text().replace("angle = 45", f"angle = {angle}"))
    np.testing.assert_allclose(normals(config), reference, rtol=0, atol=1e-15)


@pytest.mark.parametrize("angle, message", [
    # 2.1 rad (120 degrees) written bare: a normal 2.1 degrees from x, which the solver met as a singular Jacobian
    ("2.1", "[[damper]] 1 interface 2 angle = 2.1 is read in degrees (a normal 2.1° from x), but it looks like "
            "radians (120.3°): write its unit, \"2.1deg\" or \"2.1rad\""),
    ("-0.5", "[[damper]] 1 interface 2 angle = -0.5 is read in degrees"),
    ('"45 grad"', "[[damper]] 1 interface 2 angle must be an angle: a number (degrees) or a string with a unit, "
                  "\"120deg\" or \"2.1rad\", got '45 grad'"),
    ('"xdeg"', "[[damper]] 1 interface 2 angle must be an angle: a number (degrees) or a string with a unit"),
    # 120 degrees on the curved face: no platform pushes the load back (refused by the damper, as a ConfigError)
    ("120", "[[damper]] 1: the damper cannot be held against its platforms"),
])
def test_an_ambiguous_or_impossible_angle_is_refused(config, angle, message):
    refused(config, "angle = 45", f"angle = {angle}", message)


@pytest.mark.parametrize("platform, shown", [("{x = 4, y = 4}", "x = 4 and y = 4"),
                                              ('{x = "next:0", y = "next:0"}', "x = 'next:0' and y = 'next:0'")])
def test_a_platform_with_x_and_y_on_one_dof_is_refused_by_name(config, platform, shown):
    refused(config, "platform = {x = 3, y = 4}", f"platform = {platform}",
            f"[[damper]] 1 interface 2 platform: {shown} are the same DOF", sector="next" in platform)


def test_an_unloaded_or_rolling_damper_is_refused_as_a_configuration_error(config):
    text = config.read_text()
    refused(config, 'centrifugal_load = "50N"', 'centrifugal_load = "0N"',
            "[[damper]] 1: centrifugal_load must be > 0 N")
    # one contact on the flat face, on the normal through the centre of mass as the curved one: it rolls
    config.write_text(re.sub(r"points = \[\[.*\]\]\nangle = 135", "points = [[-2e-3, 2e-3]]\nangle = 135", text))
    refused(config, 'points = [["3mm", "2mm"]]', 'points = [["2mm", "2mm"]]',
            "[[damper]] 1: the damper's contacts hold only 2 of its 3 motions")
    config.write_text(config.read_text().replace("damping = 200.0", 'damping = 200.0\nretention = "1N/mm"'))
    assert load_config(config).structure.ndof == 9  # with a retention it is a damper


def test_a_sector_whose_damper_names_no_next_sector_dof_is_warned(config):
    # both faces on this sector's platforms: the damper joins the blade to itself
    config.write_text(config.read_text().replace("[excitation]", CYCLIC))
    with pytest.warns(UserWarning, match=r"every face of the damper \('flat', 'curved'\) touches this sector's "
                                         r"platform"):
        load_config(config)


def test_mass_inertia_and_damping_may_carry_their_units(config):
    """``mass = "20g"``, ``inertia = "1g*cm^2"`` (1e-7 kg m^2 each g cm^2) and ``damping = "200 1/s"`` are the
    numbers 0.02, 1e-6 and 200.0 of the file (SI); a unit of another kind is refused by name."""
    reference = load_config(config).dampers[0]
    text = config.read_text()
    config.write_text(text.replace("mass = 0.02", 'mass = "20g"').replace("inertia = 1e-6", 'inertia = "10g*cm^2"')
                      .replace("damping = 200.0", 'damping = "200 1/s"'))
    damper = load_config(config).dampers[0]
    assert (damper.mass, damper.damping) == (reference.mass, reference.damping)
    assert damper.inertia == pytest.approx(reference.inertia, rel=1e-15)  # 10 x 1e-7 in floating point
    config.write_text(text.replace("mass = 0.02", 'mass = "20N"'))
    with pytest.raises(ConfigError, match=r"\[\[damper\]\] 1 mass"):
        load_config(config)


def test_a_sector_without_its_boundary_keys_is_told_to_write_an_empty_list(config):
    config.write_text(config.read_text().replace("[excitation]", CYCLIC.replace("left = [2]\n", "")))
    with pytest.raises(ConfigError, match=re.escape("[cyclic] needs the key 'left': the DOFs this sector shares "
                                                    "with the previous one, left = [] when it shares none")):
        load_config(config)
