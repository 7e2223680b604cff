"""`plot_slip`: the statistics against their thresholds, the events and the truth."""

import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure

from taxel.active import SlipDetector, detect_slip
from taxel.viz import plot_slip

RATE = 1000.0


@pytest.fixture(scope="module")
def frames():
    """The blob of `detect_slip`'s example: still for 60 frames, then sliding at 30 mm/s."""
    rows, cols = np.mgrid[:16, :16] * 2e-3
    centre = np.where(np.arange(120) < 60, 0.0, 30e-3 * (np.arange(120) - 60) / RATE)
    blob = np.array(
        [
            1000 * np.exp(-((cols - 0.014 - c) ** 2 + (rows - 0.015) ** 2) / 2 / 0.004**2)
            for c in centre
        ]
    )
    return blob + np.random.default_rng(0).normal(0, 2, blob.shape)


@pytest.fixture(scope="module")
def detection(frames):
    return detect_slip(frames, frame_rate=RATE)


def _dashed(axes):
    """{colour: height} of the horizontal dashed lines (the thresholds)."""
    return {
        to_rgba(line.get_color()): line.get_ydata()[0]
        for line in axes.get_lines()
        if line.get_linestyle() == "--"
    }


def _labelled(axes):
    """{label: colour} of the labelled statistics."""
    return {
        line.get_label(): to_rgba(line.get_color())
        for line in axes.get_lines()
        if not line.get_label().startswith("_")
    }


def _vertical(axes, colour):
    """The x of the solid vertical lines of `colour` (the events)."""
    return sorted(
        line.get_xdata()[0]
        for line in axes.get_lines()
        if line.get_linestyle() == "-"
        and to_rgba(line.get_color(), 1.0) == to_rgba(colour, 1.0)
        and len(line.get_xdata()) == 2
        and line.get_xdata()[0] == line.get_xdata()[1]
    )


def test_the_figure_has_a_displacement_and_a_statistics_panel(detection):
    figure = plot_slip(detection)
    upper, lower = figure.axes
    assert upper.get_ylabel() == "displacement [mm]"
    assert lower.get_ylabel() == "statistic [noise units]"
    assert lower.get_xlabel() == "time [ms]"
    assert lower.get_xlim() == pytest.approx((0.0, 119.0))
    assert "initial state holding" in upper.get_title()
    # the warm-up (40 frames, read from the statistics) is shaded in both panels
    for axes in (upper, lower):
        (shade,) = [patch for patch in axes.patches if patch.get_label() == "warm-up"]
        assert shade.get_x() + shade.get_width() == pytest.approx(39.5)


def test_static_thresholds_sit_at_the_detectors_values(detection):
    detector = SlipDetector(gross_threshold=6.5, late_threshold=21.0, incipient_threshold=4.0)
    figure = plot_slip(detector.decide(detection), detector)
    upper, lower = figure.axes
    statistics = _labelled(lower)
    speed = statistics["speed run-ahead, threshold 6.5 dashed"]
    (late_label,) = [label for label in statistics if label.startswith("late run-ahead")]
    assert _dashed(lower) == {speed: 6.5, statistics[late_label]: 21.0}
    # the incipient limit: 4 sigma / sqrt(3), in mm, dashed in the size's colour
    limit = 4.0 * detection.position_noise / np.sqrt(3.0) * 1e3
    assert list(_dashed(upper).values()) == pytest.approx([limit])


def test_piezo_channels_are_drawn_with_their_thresholds(frames):
    piezo = np.random.default_rng(1).normal(0, 1, (len(frames), 4, 4))
    detector = SlipDetector(
        piezo_threshold=12.0, onset_threshold=3.5, backup_threshold=7.0, late_threshold=None
    )
    found = detector.run(frames, piezo, frame_rate=RATE)
    statistics = _labelled(plot_slip(found, detector).axes[1])
    labels = sorted(statistics)
    assert labels[:2] == ["onset filter, threshold 3.5 dashed", "piezo CUSUM, threshold 12 dashed"]
    assert labels[2].startswith("speed run-ahead (armed from") and len(labels) == 3
    assert _dashed(plot_slip(found, detector).axes[1]) == {
        statistics[labels[0]]: 3.5,
        statistics[labels[1]]: 12.0,
        statistics[labels[2]]: 7.0,
    }


def test_default_thresholds_without_a_detector(detection):
    default = SlipDetector()
    lower = plot_slip(detection).axes[1]
    assert sorted(_dashed(lower).values()) == [default.gross_threshold, default.late_threshold]


def test_event_lines_sit_at_the_event_times(detection):
    incipient, gross = detection.events
    upper, lower = plot_slip(detection).axes
    assert _vertical(lower, "black") == pytest.approx([incipient.time * 1e3])
    assert _vertical(lower, "tab:red") == pytest.approx([gross.time * 1e3])
    texts = [text.get_text() for text in upper.texts]
    assert texts == ["incipient (displacement), 61 ms", "gross (speed), 61 ms"]


def test_truth_is_marked_and_named(detection):
    figure = plot_slip(detection, truth={"incipient": 55, "gross": 60, "other": None})
    upper, lower = figure.axes
    for axes in (upper, lower):
        magenta = [line for line in axes.get_lines() if line.get_color() == "magenta"]
        lines = sorted(line.get_xdata()[0] for line in magenta if line.get_marker() == "None")
        markers = sorted(line.get_xdata()[0] for line in magenta if line.get_marker() == "v")
        assert lines == markers == [55.0, 60.0]
    labels = [text.get_text() for text in upper.get_legend().get_texts()]
    assert "true incipient" in labels and "true gross" in labels
    assert len(plot_slip(detection, truth=[60, None]).axes[0].get_lines()) == len(
        plot_slip(detection, truth=60).axes[0].get_lines()
    )


def test_draws_on_given_axes(detection):
    figure = Figure()
    pair = figure.subplots(2, 1)
    assert plot_slip(detection, ax=pair) is figure


def test_saves_and_refuses_to_overwrite(detection, tmp_path):
    path = tmp_path / "slip.png"
    plot_slip(detection, path=path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(FileExistsError, match=r"`path` .*slip.png' exists; pass overwrite=True"):
        plot_slip(detection, path=path)
    plot_slip(detection, path=str(path), overwrite=True)
    assert not list(tmp_path.glob(".*"))  # no temporary file is left


@pytest.mark.parametrize(
    ("keywords", "error", "message"),
    [
        ({"detection": None}, TypeError, r"`detection` must be a SlipDetection, got None"),
        ({"detector": "strict"}, TypeError, r"`detector` must be a SlipDetector, got 'strict'"),
        ({"truth": 120}, ValueError, r"`truth` frame 120 lies outside the sequence's 120"),
        ({"truth": [-1]}, ValueError, r"`truth` frame -1 lies outside"),
        ({"truth": 6.5}, TypeError, r"`truth` must hold frame numbers \(integers\), got 6.5"),
        ({"truth": {"gross": True}}, TypeError, r"`truth` must hold frame numbers"),
        ({"ax": "x"}, TypeError, r"`ax` must be two Axes \(displacement, statistics\), got 'x'"),
        ({"path": 3}, TypeError, r"`path` must be a file path, got 3"),
        ({"path": "missing/f.png"}, ValueError, r"`path` is in a folder that does not exist"),
        ({"path": "f.png", "overwrite": 1}, TypeError, r"`overwrite` must be True or False"),
    ],
)
def test_bad_arguments_are_named(detection, keywords, error, message):
    arguments = {"detection": detection, **keywords}
    with pytest.raises(error, match=message):
        plot_slip(arguments.pop("detection"), **arguments)


def test_axes_of_two_figures_are_refused(detection):
    with pytest.raises(ValueError, match=r"`ax` must be two Axes of one figure"):
        plot_slip(detection, ax=(Figure().subplots(), Figure().subplots()))


def test_a_contact_sliding_from_the_start_says_no_onset_is_reported(frames):
    sliding = detect_slip(frames[60:], frame_rate=RATE)
    assert sliding.initial_state == "sliding" and sliding.events == ()
    upper, lower = plot_slip(sliding).axes
    assert "initial state sliding (no onset is reported)" in upper.get_title()
    labels = [text.get_text() for text in lower.get_legend().get_texts()]
    assert "late run-ahead (never armed), threshold 15.5 dashed" in labels
