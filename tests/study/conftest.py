"""Configurations the study tests vary: the inclined block, and a blade pair with an under-platform damper."""

import sys

import numpy as np
import pytest

from _paths import REPO

sys.path.insert(0, str(REPO / "tests" / "frequency"))
sys.path.insert(0, str(REPO / "tests" / "cli"))
sys.path.insert(0, str(REPO / "tests" / "study"))

from _study_folder import solved, write_block  # noqa: E402


@pytest.fixture(scope="module")
def client():
    """An in-process cluster of two single-threaded workers."""
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0") as c, \
            distributed.Client(c) as cl:
        yield cl


@pytest.fixture(scope="module")
def finished(tmp_path_factory, client):
    """``(study file, results folder)`` of three cases solved once; a test damages a copy of the folder."""
    return solved(tmp_path_factory.mktemp("finished"), client)


@pytest.fixture
def block(tmp_path):
    """examples/inclined_block_study.toml (the smallest study) beside its base configuration and contact model."""
    return write_block(tmp_path)


@pytest.fixture
def damper_pair(tmp_path):
    """A blade pair with an under-platform damper (tests/cli/test_design_cli.py), tips in antiphase, near the peak."""
    return write_damper_pair(tmp_path)


def write_damper_pair(folder, omega=(4320, 4440)):
    """The files of :func:`damper_pair` written in ``folder``, the sweep over ``omega`` (rad/s); the configuration."""
    from test_design_cli import write_config

    return write_config(folder, lambda text: (
        text.replace("h1 = [0, 0, 0.5, 0, 0, 0]", "h1 = [0, 0, 0.5, 0, 0, -0.5]")
        .replace("omega = [3000, 5000]", f"omega = [{omega[0]}, {omega[1]}]")
        .replace('[design]\nloads = ["3N", "20N", "300N"]           # from a damper sliding through the cycle '
                 'to a stuck one\ndof = 2\n', "[output]\nplot = [\"tip0\"]\n")))
