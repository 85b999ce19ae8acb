"""Configurations the study tests vary: the inclined block, and a blade pair with an under-platform damper."""

import shutil
import sys

import numpy as np
import pytest

from _paths import REPO

sys.path.insert(0, str(REPO / "tests" / "frequency"))
sys.path.insert(0, str(REPO / "tests" / "cli"))


@pytest.fixture
def block(tmp_path):
    """The example configuration examples/inclined_block.toml with its contact model, and the issue's study."""
    for name in ("inclined_block.toml", "sphere_4_elements.json"):
        shutil.copy(REPO / "examples" / name, tmp_path / name)
    study = tmp_path / "study.toml"
    study.write_text(EXAMPLE_STUDY)
    return study


EXAMPLE_STUDY = '''base = "inclined_block.toml"                          # an frf configuration, relative to this file
[vary]
"contact.sphere.preload" = ["25N", "37.5N", "50N"]    # a list; a [[contact]] table named by its name
"excitation.h1" = [["0.3N", "0N"], ["0.6N", "0N"]]    # grid: every combination (6 cases)
'''


@pytest.fixture
def damper_pair(tmp_path):
    """A blade pair with an under-platform damper (tests/cli/test_design_cli.py), tips in antiphase, near the peak."""
    from test_damper import blade_pair
    from test_design_cli import CONFIG

    from microslip import Sphere, tune

    s = blade_pair()
    np.savez(tmp_path / "pair.npz", M=s.M, C=s.C, K=s.K)
    model = tune(Sphere.paper(), 37.5, elements=4)
    model.save(tmp_path / "flat.json")
    model.save(tmp_path / "curved.json")
    a = np.radians(135.0)
    tau = np.array([-np.sin(a), np.cos(a)])
    c = np.array([-3e-3, 2e-3])
    p0, p1 = c - 1.5e-3 * tau, c + 1.5e-3 * tau
    text = (CONFIG.format(p0x=p0[0], p0y=p0[1], p1x=p1[0], p1y=p1[1])
            .replace("h1 = [0, 0, 0.5, 0, 0, 0]", "h1 = [0, 0, 0.5, 0, 0, -0.5]")
            .replace("omega = [3000, 5000]", "omega = [4320, 4440]")
            .replace('[design]\nloads = ["3N", "20N", "300N"]           # from a damper sliding through the cycle '
                     'to a stuck one\ndof = 2\n', "[output]\nplot = [\"tip0\"]\n"))
    path = tmp_path / "pair.toml"
    path.write_text(text)
    return path
