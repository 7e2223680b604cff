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
