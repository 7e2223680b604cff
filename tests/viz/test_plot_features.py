import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parents[1] / "features"))
from synthetic import arc, band, plate_with_slot, render

from taxel.features import extract
from taxel.viz import plot_features

PITCH = 2.5e-4


def test_figures_draw_and_save(tmp_path):
    drawn = {"band": "fitted line", "arc": "fitted circle", "plate_with_slot": "slot"}
    for pattern in (band, arc, plate_with_slot):
        image = render(pattern, (64, 64), rng=0, noise=0.01)
        figure = plot_features(image, extract(image, PITCH), PITCH)
        path = tmp_path / f"{pattern.__name__}.png"
        figure.savefig(path)
        assert path.stat().st_size > 1000
        # the legend names what is drawn; the axes give the pitch
        axes = figure.axes[0]
        labels = [text.get_text() for text in axes.get_legend().get_texts()]
        assert labels[0] == "edges" and labels[-1] == "centroid"
        assert drawn[pattern.__name__] in labels
        assert axes.get_xlabel() == "column [taxels of 0.25 mm]"


def test_importing_taxel_does_not_import_matplotlib():
    import subprocess

    code = "import sys, taxel, taxel.features; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_blank_image_draws():
    figure = plot_features(np.zeros((16, 16)), extract(np.zeros((16, 16)), 1e-3), 1e-3)
    assert figure.axes[0].get_title() == "none, 0 hole(s), 0 slot(s)"


def test_a_binary_mask_draws_as_extract_reads_it():
    # a switch-matrix sensor's frame: contact or not, as booleans
    mask = _washer() > 0
    features = extract(mask, 1e-3)
    assert features.holes.count == 1
    figure = plot_features(mask, features, 1e-3)
    assert figure.axes[0].get_title() == f"{features.contact_type}, 1 hole(s), 0 slot(s)"


def _washer(size=48):
    y, x = np.mgrid[:size, :size]
    r = np.hypot(x - size / 2, y - size / 2)
    return ((r < 0.375 * size) & (r > 0.15 * size)) * 1.0


def test_bad_features_and_axes_are_named():
    import pytest

    image = _washer()
    with pytest.raises(TypeError, match=r"`features` must be a TactileFeatures, got None"):
        plot_features(image, None, 1e-3)
    with pytest.raises(TypeError, match=r"`ax` must be an Axes, got 'x'"):
        plot_features(image, extract(image, 1e-3), 1e-3, ax="x")


def test_image_must_be_two_dimensional():
    import pytest

    image = _washer()
    with pytest.raises(ValueError, match=r"`image` must be 2-D, got shape \(48,\)"):
        plot_features(image[0], extract(image, 1e-3), 1e-3)


def test_features_of_another_image_or_pitch_are_refused():
    import pytest

    image = _washer()
    features = extract(image, 1e-3)
    assert features.contact.present and features.holes.count == 1
    with pytest.raises(
        ValueError, match=r"`features` must be of `image` \(shape \(10, 10\)\).*shape \(48, 48\)"
    ):
        plot_features(np.zeros((10, 10)), features, 1e-3)
    with pytest.raises(ValueError, match=r"`features` must be of `image`.*another pitch"):
        plot_features(image, features, 2e-3)
    # the same image at the same pitch is drawn, on given axes too
    from matplotlib.figure import Figure

    axes = Figure().add_subplot()
    assert plot_features(image, features, (1e-3, 1e-3), ax=axes) is axes.figure


def test_edges_are_drawn_as_the_features_were_prepared():
    from taxel.features import detect_edges
    from taxel.mechanics import make_indenter
    from taxel.sensor import make_sensor

    sensor = make_sensor("vhdta128")
    rest = np.zeros(sensor.load_grid.shape)
    reference = np.mean([sensor.frame_from_pressure(rest, rng=s).raw for s in range(4)], axis=0)
    frame = sensor.press(make_indenter("washer"), normal_force=10.0, rng=3).raw
    features = extract(frame, sensor, reference=reference)
    figure = plot_features(frame, features, sensor, reference=reference)
    axes = figure.axes[0]
    # the sensor's own preparation (not a bare pitch: the glass's scratches would be kept)
    edges = detect_edges(frame, sensor, reference=reference)
    drawn = axes.get_lines()[0]
    np.testing.assert_array_equal(drawn.get_xdata(), edges.cols)
    np.testing.assert_array_equal(drawn.get_ydata(), edges.rows)
    assert edges.n_edges != detect_edges(frame, sensor.taxel_pitch).n_edges
    np.testing.assert_allclose(axes.get_images()[0].get_array(), frame - reference)
    assert axes.get_title() == "surface, 1 hole(s), 0 slot(s) (reference subtracted)"
