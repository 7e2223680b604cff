import errno
from pathlib import Path

import numpy as np
import pytest

from taxel.io import check_new_file, read_frame, write_files, write_frame, write_text


def test_write_frame_round_trip_and_refuses_to_overwrite(tmp_path):
    target = tmp_path / "frame.npy"
    write_frame(target, np.arange(6.0).reshape(2, 3))
    assert np.array_equal(read_frame(target), np.arange(6.0).reshape(2, 3))
    with pytest.raises(FileExistsError, match="`path` '.*frame.npy' exists; pass overwrite=True"):
        write_frame(target, np.zeros((2, 3)))
    assert read_frame(target)[1, 2] == 5.0  # untouched
    write_frame(target, np.zeros((2, 3)), overwrite=True)
    assert read_frame(target).sum() == 0.0
    assert [path.name for path in tmp_path.iterdir()] == ["frame.npy"]  # no leftovers


def test_never_over_an_input_even_when_asked(tmp_path):
    source = tmp_path / "in.npy"
    write_frame(source, np.ones((2, 2)))
    with pytest.raises(ValueError, match="is an input file"):
        write_frame(source, np.zeros((2, 2)), overwrite=True, inputs=(source,))
    assert read_frame(source).sum() == 4.0


def test_bad_targets_are_named(tmp_path):
    with pytest.raises(ValueError, match="must name a .npy file"):
        write_frame(tmp_path / "frame.csv", np.ones(3))
    with pytest.raises(ValueError, match="folder that does not exist"):
        check_new_file(tmp_path / "missing" / "x.npy")
    write_text(tmp_path / "a.json", "{}")
    with pytest.raises(FileExistsError):
        write_text(tmp_path / "a.json", "[]")


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux's /proc")
def test_a_failed_write_names_the_file_asked_for():
    # /proc takes no new files, even from root; the error names the file, not the
    # temporary one the write goes through
    with pytest.raises(OSError, match=r"/proc/frame\.npy cannot be written") as error:
        write_frame("/proc/frame.npy", np.zeros((2, 2)))
    assert ".partial" not in str(error.value)


def test_several_files_are_written_all_or_none(tmp_path):
    first, second = tmp_path / "a.txt", tmp_path / "b.txt"
    second.write_text("kept")

    def fail(temporary: Path) -> None:
        temporary.write_text("half")
        raise OSError(28, "No space left on device")

    with pytest.raises(OSError, match="b.txt"):
        write_files([(first, lambda t: t.write_text("new")), (second, fail)])
    assert not first.exists()  # the first write succeeded, but was never renamed
    assert second.read_text() == "kept"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["b.txt"]  # no temporaries left
    write_files([(first, lambda t: t.write_text("1")), (second, lambda t: t.write_text("2"))])
    assert (first.read_text(), second.read_text()) == ("1", "2")


def test_a_read_only_file_system_names_the_file_asked_for(tmp_path, monkeypatch):
    # there, creating the temporary fails, and so does removing it afterwards: the error
    # still names the file asked for, not the hidden temporary
    def read_only(path, *args, **kwargs):
        raise OSError(errno.EROFS, "Read-only file system", str(path))

    monkeypatch.setattr(Path, "unlink", read_only)
    target = tmp_path / "frame.npy"
    with pytest.raises(OSError, match="Read-only file system") as error:
        write_files([(target, read_only)])
    assert error.value.filename == str(target)
    assert error.value.errno == errno.EROFS


def test_a_folder_that_takes_no_files_is_found_before_any_work(tmp_path, monkeypatch):
    from taxel.io import _writers

    def refuse(*args, **kwargs):
        raise PermissionError(errno.EACCES, "Permission denied")

    monkeypatch.setattr(_writers.tempfile, "mkstemp", refuse)
    with pytest.raises(PermissionError, match=r"^--out .*x\.npy cannot be written \(Permission"):
        check_new_file(tmp_path / "x.npy", suffix=".npy", name="--out")


def test_checking_a_folder_leaves_nothing_in_it(tmp_path):
    assert check_new_file(tmp_path / "x.npy", suffix=".npy") == tmp_path / "x.npy"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux's /proc")
def test_a_virtual_folder_is_refused_when_checked():
    with pytest.raises(OSError, match=r"^`path` /proc/frame.npy cannot be written"):
        check_new_file("/proc/frame.npy")


def test_the_suffix_is_checked_in_any_case(tmp_path):
    # A.NPY is a .npy file (the readers take it too); a .txt is not
    target = write_frame(tmp_path / "A.NPY", np.eye(2))
    assert target.name == "A.NPY" and np.array_equal(read_frame(target), np.eye(2))
    with pytest.raises(ValueError, match=r"must name a .npz file, got '.*C.txt'"):
        check_new_file(tmp_path / "C.txt", suffix=".npz")
