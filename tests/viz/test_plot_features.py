import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parents[1] / "features"))
from synthetic import arc, band, plate_with_slot, render

from taxel.features import extract
from taxel.viz import plot_features

PITCH = 2.5e-4


def test_figures_draw_and_save(tmp_path):
    for pattern in (band, arc, plate_with_slot):
        image = render(pattern, (64, 64), rng=0, noise=0.01)
        figure = plot_features(image, extract(image, PITCH), PITCH)
        path = tmp_path / f"{pattern.__name__}.png"
        figure.savefig(path)
        assert path.stat().st_size > 1000


def test_importing_taxel_does_not_import_matplotlib():
    import subprocess

    code = "import sys, taxel, taxel.features; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_blank_image_draws():
    figure = plot_features(np.zeros((16, 16)), extract(np.zeros((16, 16)), 1e-3), 1e-3)
    assert figure.axes[0].get_title() == "none, 0 hole(s), 0 slot(s)"
