"""The model file: every key checked, units honoured, messages naming the file, older files still read."""

from __future__ import annotations

import json
import re
import shutil

import numpy as np
import pytest

from _paths import EXAMPLES
from microslip import MicroslipModel, Sphere, tune
from microslip.model import Provenance

SPHERE = Sphere.paper()


@pytest.fixture(scope="module")
def paper_model():
    return tune(SPHERE, 37.5, elements=4)


def changed(data, change):
    """``data`` with the keys of ``change`` set, or deleted where the value is None."""
    for k, v in change.items():
        if v is None:
            del data[k]
        else:
            data[k] = v
    return data


def write(path, data):
    path.write_text(json.dumps(data))
    return path


def test_a_file_written_before_provenance_still_loads(tmp_path):
    """examples/sphere_4_elements.json was written by the package before the model file had a provenance."""
    old = shutil.copy(EXAMPLES / "sphere_4_elements.json", tmp_path / "old.json")
    assert "provenance" not in json.loads((tmp_path / "old.json").read_text())
    model = MicroslipModel.load(old)
    assert model.provenance is None
    # the file holds the paper's model, as tuned on the machine that wrote it: tune's last bits follow
    # the platform's pow/cbrt (up to 65 ulps, 1.2e-14 relative, apart on the next machine)
    paper = tune(SPHERE, 37.5, elements=4)
    for name in ("kt", "kn", "gaps"):
        np.testing.assert_allclose(getattr(model, name), getattr(paper, name), rtol=1e-12, atol=0, err_msg=name)
    assert model.mu == paper.mu


@pytest.mark.parametrize("key, message", [
    ("unit", "unknown key 'unit' (did you mean 'units'?)"),
    ("gap", "unknown key 'gap' (did you mean 'gaps'?)"),
    ("colour", "unknown key 'colour';"),
])
def test_unknown_keys_are_refused_naming_the_key_the_file_and_the_accepted_keys(paper_model, tmp_path, key,
                                                                               message):
    data = paper_model.to_dict()
    data[key] = "x"
    path = write(tmp_path / "m.json", data)
    with pytest.raises(ValueError, match=re.escape(f"model file {str(path)!r}: {message}")) as info:
        MicroslipModel.load(path)
    assert "the accepted keys are format, version, units, kt, kn, gaps, mu, provenance" in str(info.value)


def test_units_in_the_file_are_honoured_not_ignored(paper_model, tmp_path):
    """Gaps in um, stiffnesses in N/um: the model is the one the file describes (before: gaps taken as metres)."""
    data = paper_model.to_dict()
    data["units"] = {"kt": "N/um", "kn": "N/mm", "gaps": "um"}
    data["kt"] = [k / 1e6 for k in data["kt"]]
    data["kn"] = [k / 1e3 for k in data["kn"]]
    data["gaps"] = [g * 1e6 for g in data["gaps"]]
    model = MicroslipModel.load(write(tmp_path / "um.json", data))
    # a conversion there and back: equal to a few ulps, not bit for bit
    np.testing.assert_allclose(model.gaps, paper_model.gaps, rtol=1e-15, atol=0)
    np.testing.assert_allclose(model.kt, paper_model.kt, rtol=1e-15)
    np.testing.assert_allclose(model.kn, paper_model.kn, rtol=1e-15)


@pytest.mark.parametrize("units, error, message", [
    ({"gap": "um"}, ValueError, "['units']: unknown key 'gap' (did you mean 'gaps'?); the accepted keys are kt, kn, "
                                "gaps, mu"),
    ({"gaps": "furlong"}, ValueError, "['units']['gaps']: unknown length unit 'furlong'"),
    ({"gaps": "N"}, ValueError, "['units']['gaps']: unknown length unit 'N'"),
    ({"kt": 1e6}, TypeError, "['units']['kt'] must be a unit symbol such as 'N/m', got 1000000.0"),
    ("um", TypeError, "['units'] must be an object such as"),
])
def test_bad_units_are_named(paper_model, tmp_path, units, error, message):
    data = paper_model.to_dict()
    data["units"] = units
    path = write(tmp_path / "m.json", data)
    with pytest.raises(error, match=re.escape(f"model file {str(path)!r}{message}")):
        MicroslipModel.load(path)


@pytest.mark.parametrize("change, error, message", [
    ({"mu": None}, ValueError, " is missing the key(s) ['mu']; expected kt, kn, gaps, mu"),
    ({"kt": [1.0, -1.0, 1.0, 1.0]}, ValueError, ": kt must be positive, got -1.0 at flat index 1"),
    ({"gaps": "0"}, TypeError, ": gaps must be an array of real numbers"),
    ({"version": 7}, ValueError, "['version'] must be 1, got 7"),
])
def test_every_error_of_a_model_file_names_the_file(paper_model, tmp_path, change, error, message):
    path = write(tmp_path / "m.json", changed(paper_model.to_dict(), change))
    with pytest.raises(error, match=re.escape(f"model file {str(path)!r}{message}")):
        MicroslipModel.load(path)


@pytest.mark.parametrize("change, error, message", [
    ({"format": "other"}, ValueError, "data['format'] must be 'microslip.MicroslipModel', got 'other'"),
    ({"version": 2}, ValueError, "data['version'] must be 1, got 2"),
    ({"kn": None, "mu": None}, ValueError, "data is missing the key(s) ['kn', 'mu']; expected kt, kn, gaps, mu"),
    ({"kt": [1.0, -1.0, 1.0, 1.0]}, ValueError, "kt must be positive, got -1.0 at flat index 1"),
])
def test_from_dict_errors(paper_model, change, error, message):
    with pytest.raises(error, match=re.escape(message)):
        MicroslipModel.from_dict(changed(paper_model.to_dict(), change))


def test_a_folder_or_a_json_list_is_named(tmp_path):
    with pytest.raises(IsADirectoryError, match=re.escape(f"model file {str(tmp_path)!r} is a folder, not a file")):
        MicroslipModel.load(tmp_path)
    path = write(tmp_path / "list.json", [1, 2])
    with pytest.raises(TypeError, match=re.escape(f"model file {str(path)!r} must be a dict")):
        MicroslipModel.load(path)


# -- provenance --------------------------------------------------------------------------------
def test_tune_records_how_the_model_was_tuned_and_the_file_keeps_it(paper_model, tmp_path):
    p = paper_model.provenance
    assert p.kind == "Sphere"
    assert p.reference == {"kind": "Sphere", "radius": 5e-3, "E": 200e9, "nu": 0.3, "mu": 0.4}
    assert p.normal_load == 37.5 and p.approach == float(SPHERE.approach(37.5))
    np.testing.assert_array_equal(p.points_T, [3.75, 7.5, 11.25, 15.0])  # even in force, the paper's
    assert p.mu_source == "given with the reference" and p.load_range is None
    from microslip import __version__

    assert p.version == __version__ and re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\+00:00", p.date)
    again = MicroslipModel.load(paper_model.save(tmp_path / "m.json"))
    assert again.provenance == p
    assert "tuned on a Sphere (radius = 0.005 m, E = 2e+11 Pa, nu = 0.3, mu = 0.4) at 37.5 N with 4 points" \
        in p.describe()


def test_a_hand_built_model_has_no_provenance_and_its_file_none():
    m = MicroslipModel([1e7], [1e8], [0.0], 0.4)
    assert m.provenance is None and "provenance" not in m.to_dict()


def test_equality_ignores_the_provenance(paper_model):
    """Same parameters, same behaviour: the record of the tuning (its date, say) does not make another model."""
    bare = MicroslipModel(paper_model.kt, paper_model.kn, paper_model.gaps, paper_model.mu)
    assert bare == paper_model and bare.provenance is None
    later = paper_model.with_provenance(Provenance(**{**paper_model.provenance.__dict__, "date": "2030-01-01"}))
    assert later == paper_model and later.provenance != paper_model.provenance


def test_tuning_over_a_load_range_records_the_range_and_the_targets():
    p = tune(SPHERE, 37.5, elements=11, load_range=(7.5, 37.5)).provenance  # stored points: instant
    assert p.load_range == (7.5, 37.5) and p.notes["energy_target"] == 0.02 and p.notes["force_target"] == 0.02
    assert "chosen for 7.5-37.5 N" in p.describe()


@pytest.mark.parametrize("change, error, message", [
    ({"referenc": {}}, ValueError, "['provenance']: unknown key 'referenc' (did you mean 'reference'?)"),
    ({"normal_load": -1.0}, ValueError, "['provenance']: normal_load must be positive, got -1.0"),
    ({"reference": {"radius": 1.0}}, TypeError, "['provenance']: reference must be a dict with a 'kind'"),
    ({"points": {"t": [1e-6], "F": [1.0]}}, ValueError, "['provenance']['points']: unknown key 'F'"),
    ({"loops": "run.csv"}, TypeError, "['provenance']: loops must be a sequence of file names, got 'run.csv'"),
])
def test_a_bad_provenance_block_is_refused_by_name(paper_model, tmp_path, change, error, message):
    data = paper_model.to_dict()
    data["provenance"].update(change)
    if "referenc" in change:
        del data["provenance"]["reference"]
    path = write(tmp_path / "m.json", data)
    with pytest.raises(error, match=re.escape(f"model file {str(path)!r}{message}")):
        MicroslipModel.load(path)
