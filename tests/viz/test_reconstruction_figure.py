"""The naive-against-regularized figure is written as a PNG (or the format its suffix names)."""

import matplotlib
import numpy as np

from taxel.viz import plot_reconstruction


def test_writes_a_png(tmp_path):
    path = plot_reconstruction(tmp_path / "inverse.png", noise_fraction=0.002, rng=1)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert path.stat().st_size > 20_000
    image = matplotlib.image.imread(path)
    assert image.shape[0] > 500 and np.ptp(image) > 0.5  # not blank


def test_writes_the_format_its_suffix_names(tmp_path):
    svg = plot_reconstruction(tmp_path / "inverse.svg", sensor="resistive16")
    assert svg.read_bytes().lstrip()[:5] == b"<?xml"
    odd = plot_reconstruction(tmp_path / "inverse.figure", sensor="resistive16")
    assert odd.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"  # a suffix matplotlib does not know
    assert sorted(p.name for p in tmp_path.iterdir()) == ["inverse.figure", "inverse.svg"]


def test_import_taxel_stays_light():
    import subprocess
    import sys

    code = "import sys, taxel, taxel.reconstruction; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_a_failed_write_keeps_the_old_file(tmp_path, full_disk_savefig):
    import pytest

    path = tmp_path / "inverse.png"
    path.write_bytes(b"old figure")
    with pytest.raises(OSError, match="No space left") as error:
        plot_reconstruction(path, sensor="resistive16")
    assert error.value.filename == str(path)
    assert path.read_bytes() == b"old figure"
    assert [item.name for item in tmp_path.iterdir()] == ["inverse.png"]


def test_bad_arguments_are_named_before_any_work(tmp_path):
    import pytest

    path = tmp_path / "inverse.png"
    with pytest.raises(ValueError, match=r"`noise_fraction` must be >= 0, got -1"):
        plot_reconstruction(path, noise_fraction=-1)
    with pytest.raises(ValueError, match=r"`noise_fraction` must be finite, got nan"):
        plot_reconstruction(path, noise_fraction=float("nan"))
    with pytest.raises(ValueError, match=r"`rng` seed must be >= 0, got -1"):
        plot_reconstruction(path, rng=-1)
    with pytest.raises(TypeError, match=r"`rng` must be a numpy.random.Generator.*got None"):
        plot_reconstruction(path, rng=None)
    with pytest.raises(TypeError, match=r"`path` must be a file path, got None"):
        plot_reconstruction(None)
    assert not path.exists()
