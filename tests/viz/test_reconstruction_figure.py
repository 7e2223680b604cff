"""The naive-against-regularized figure is written as a PNG."""

import matplotlib
import numpy as np

from taxel.viz import plot_reconstruction


def test_writes_a_png(tmp_path):
    path = plot_reconstruction(tmp_path / "inverse.png", noise_fraction=0.002, rng=1)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert path.stat().st_size > 20_000
    image = matplotlib.image.imread(path)
    assert image.shape[0] > 500 and np.ptp(image) > 0.5  # not blank


def test_import_taxel_stays_light():
    import subprocess
    import sys

    code = "import sys, taxel, taxel.reconstruction; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
