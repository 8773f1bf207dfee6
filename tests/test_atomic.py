"""Atomic file writes (femoat.atomic): all or nothing, with ordinary permissions."""

import os
import stat

import pytest

from femoat.atomic import atomic_path, write_text


def _mode(path):
    return stat.S_IMODE(path.stat().st_mode)


def test_new_file_gets_the_mode_of_an_ordinary_write(tmp_path):
    # open(..., "w") creates files 0666 less the umask; mkstemp alone would leave 0600.
    mask = os.umask(0o022)
    try:
        write_text(tmp_path / "a.txt", "x")
        with open(tmp_path / "b.txt", "w") as f:
            f.write("x")
    finally:
        os.umask(mask)
    assert _mode(tmp_path / "a.txt") == _mode(tmp_path / "b.txt") == 0o644


def test_replacing_keeps_the_file_mode(tmp_path):
    path = tmp_path / "a.txt"
    write_text(path, "old")
    os.chmod(path, 0o640)
    write_text(path, "new")
    assert path.read_text() == "new"
    assert _mode(path) == 0o640


def test_a_failed_write_leaves_the_old_file_and_no_debris(tmp_path):
    path = tmp_path / "a.txt"
    write_text(path, "old")
    with pytest.raises(RuntimeError):
        with atomic_path(path) as tmp:
            tmp.write_text("half")
            raise RuntimeError("writer failed")
    assert path.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]
