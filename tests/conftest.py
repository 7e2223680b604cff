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


# the slip tests' trials (tests/active): one hold-then-slip and one hold, simulated once


@pytest.fixture(scope="session")
def slip_scenario():
    """A 2 N contact of a 50 mm ball, held 60 ms, loaded to slip over 100 ms (seed 7)."""
    from taxel.active import SlipScenario

    return SlipScenario(
        kind="slip",
        normal_force=2.0,
        radius=0.05,
        friction=0.8,
        kinetic_ratio=0.8,
        initial_load=0.0,
        hold_time=0.06,
        load_time=0.1,
        sliding_speed=0.04,
        relaxation_time=2e-3,
        direction=0.5,
        seed=7,
    )


@pytest.fixture(scope="session")
def slip(slip_scenario):
    from taxel.active import simulate_slip

    return simulate_slip(slip_scenario)


@pytest.fixture(scope="session")
def hold():
    from taxel.active import SlipScenario, simulate_slip

    return simulate_slip(SlipScenario(kind="hold", load_time=0.0, seed=3))


@pytest.fixture
def frame_file(tmp_path):
    """A resistive16 reading of a 3 x 3 taxel 40 kPa load with 1 kPa of noise, saved as .npy
    (for ``taxel reconstruct``)."""
    import numpy as np  # (here: the thread settings above come before NumPy loads BLAS)

    from taxel.reconstruction import forward_operator

    truth = np.zeros((16, 16))
    truth[5:8, 6:9] = 40e3
    frame = forward_operator("resistive16").apply(truth)
    frame += np.random.default_rng(0).normal(0, 1e3, frame.shape)
    path = tmp_path / "frame.npy"
    np.save(path, frame)
    return path
