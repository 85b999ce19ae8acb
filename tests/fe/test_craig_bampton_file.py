"""A saved Craig-Bampton model that is damaged or tampered with is refused by name (issue 24, items 9 and 22)."""

import io
import json
from pathlib import Path

import numpy as np
import pytest

from _writers import damage_npz
from microslip import MicroslipModel
from microslip.fe import FileFormatError
from microslip.frequency import CraigBampton, Structure, craig_bampton


def _saved_reduction(tmp_path) -> Path:
    s = Structure(np.eye(3), None, np.array([[2e4, -1e4, 0.0], [-1e4, 2e4, -1e4], [0.0, -1e4, 1e4]]))
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential=0, approach=1e-6)
    return Path(craig_bampton(s, [0], 1).save(tmp_path / "reduced.npz"))


def _tampered(path, **arrays):
    """The saved model at ``path`` with some arrays replaced."""
    with np.load(path) as data:
        content = {k: data[k] for k in data.files} | arrays
    buffer = io.BytesIO()
    np.savez(buffer, **content)
    path.write_bytes(buffer.getvalue())
    return path


def test_a_saved_model_reads_back(tmp_path):
    back = CraigBampton.load(_saved_reduction(tmp_path))
    assert back.structure.ndof == 2 and back.recovery.shape == (3, 2) and back.keep.tolist() == [0]
    assert len(back.structure.contacts) == 1


@pytest.mark.parametrize("damage", ["empty", "truncated", "bit flip"])
def test_9_a_damaged_file_is_refused_by_name(tmp_path, damage):
    path = _saved_reduction(tmp_path)
    damage_npz(path, damage)
    with pytest.raises(FileFormatError, match="reduced.npz: "):
        CraigBampton.load(path)


@pytest.mark.parametrize("arrays, message", [
    (dict(contacts=np.array("[{")), "contacts is not valid JSON (Expecting"),
    (dict(contacts=np.array(json.dumps("abc"))), "contacts must be a list of tables"),
    (dict(contacts=np.array(json.dumps([{"model": 1}]))), "not a valid Craig-Bampton model file"),
    (dict(recovery=np.ones((3, 5))), "recovery (3, 5), keep (1,) and frequencies (1,) do not fit a reduced structure "
                                     "of 2 DOFs"),
    (dict(keep=np.array([7])), "do not fit a reduced structure of 2 DOFs (keep: distinct rows of recovery)"),
    (dict(frequencies=np.ones(3)), "do not fit a reduced structure of 2 DOFs"),
    (dict(static_force=np.ones(5)), "static_force has 5 entries; the structure has 2 DOFs"),
    (dict(M=np.ones((2, 3))), "not a valid Craig-Bampton model file (ValueError: M must be"),
    (dict(K=np.array([{"a": 1}], dtype=object)), "array 'K' holds Python objects"),
    (dict(cyclic=np.array(json.dumps({"sectors": 2}))), "not a valid Craig-Bampton model file"),
])
def test_22_a_tampered_file_is_named(tmp_path, arrays, message):
    path = _tampered(_saved_reduction(tmp_path), **arrays)
    with pytest.raises(FileFormatError) as err:
        CraigBampton.load(path)
    assert str(path) in str(err.value) and message in str(err.value), str(err.value)
