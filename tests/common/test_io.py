"""Files written through ``atomic_write``: permissions as any program would give them, folders refused."""

import os
import stat

import pytest

from microslip.common._io import atomic_write


def mode(path):
    return stat.S_IMODE(os.stat(path).st_mode)


@pytest.fixture
def umask():
    """Set the umask for one test and restore the previous one."""
    previous = os.umask(0o022)
    yield lambda value: os.umask(value)
    os.umask(previous)


@pytest.mark.parametrize("mask, expected", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664), (0o000, 0o666)])
def test_a_new_file_follows_the_umask(tmp_path, umask, mask, expected):
    umask(mask)
    path = atomic_write(tmp_path / "report.txt", "text\n")
    assert mode(path) == expected  # mkstemp alone gives 0600 whatever the umask


def test_a_replaced_file_keeps_its_mode(tmp_path, umask):
    umask(0o077)
    path = tmp_path / "model.json"
    path.write_text("old\n")
    os.chmod(path, 0o640)
    atomic_write(path, b"new\n")
    assert path.read_bytes() == b"new\n"
    assert mode(path) == 0o640  # not 0600 (mkstemp), not 0600 (0666 less this umask)


def test_a_folder_is_refused_by_name_and_nothing_is_left_behind(tmp_path):
    folder = tmp_path / "out"
    folder.mkdir()
    with pytest.raises(IsADirectoryError, match=f"{str(folder)!r} is a folder: give the name of a file to write"):
        atomic_write(folder, "x")
    assert list(tmp_path.iterdir()) == [folder] and list(folder.iterdir()) == []
