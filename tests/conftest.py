"""Test-wide settings (single-threaded BLAS, as the command line and the benchmarks run) and
fixtures shared by several test folders."""

import os

import pytest

for _variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")


@pytest.fixture
def full_disk_savefig(monkeypatch):
    """matplotlib's savefig on a full disk: a PNG cut short, then ENOSPC (undo to restore)."""
    from matplotlib.figure import Figure

    def disk_full(self, target, **kwargs):
        with open(target, "wb") as stream:
            stream.write(b"\x89PNG cut short")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(Figure, "savefig", disk_full)
    return monkeypatch


@pytest.fixture
def spoil_deflate():
    """Zero one member's compressed bytes in an .npz, keeping the archive's layout."""
    import zipfile

    def spoil(path, name):
        with zipfile.ZipFile(path) as archive:
            member = archive.getinfo(name)
        data = bytearray(path.read_bytes())
        body = member.header_offset + 30 + len(member.filename) + len(member.extra)
        data[body : body + member.compress_size] = bytes(member.compress_size)
        path.write_bytes(bytes(data))

    return spoil
