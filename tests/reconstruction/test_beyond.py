"""Readings beyond the array's edges (`extend_readings`): the grown array's forward model."""

from dataclasses import replace

import numpy as np
import pytest

from taxel.reconstruction import extend_readings, forward_model_preset, forward_operator

# a corner of vhdta128: its cover (1 mm) spreads a load 3.9 taxels deep
SPEC = forward_model_preset("vhdta128", shape=(48, 48))
MARGIN = 14  # 3.5 cover depths, the features' reach


def _loads(oversampling: int = 1) -> np.ndarray:
    """A 50 kPa disc the left edge cuts and a 20 kPa plate along the top edge [Pa]."""
    rows, cols = np.indices((48, 48))
    disc = np.where((rows - 20) ** 2 + (cols - 2) ** 2 < 100, 50e3, 0.0)
    plate = np.where((rows < 6) & (cols > 20) & (cols < 40), 20e3, 0.0)
    return np.kron(disc + plate, np.ones((oversampling, oversampling)))


def _grown_truth(spec, load: np.ndarray) -> np.ndarray:
    grown = replace(spec, shape=(48 + 2 * MARGIN, 48 + 2 * MARGIN))
    padded = np.pad(load, MARGIN * spec.oversampling)
    return forward_operator(grown, boundary="zero").apply(padded)


def _outside() -> np.ndarray:
    outside = np.ones((48 + 2 * MARGIN,) * 2, bool)
    outside[MARGIN:-MARGIN, MARGIN:-MARGIN] = False
    return outside


def _beyond(grown: np.ndarray) -> np.ndarray:
    return grown[_outside()]


@pytest.mark.parametrize("oversampling", [1, 2])
def test_the_readings_beyond_are_the_grown_arrays(oversampling):
    spec = SPEC.with_changes(oversampling=oversampling)
    load = _loads(oversampling)
    readings = forward_operator(spec, boundary="zero").apply(load)
    truth = _grown_truth(spec, load)
    grown = extend_readings(spec, readings, MARGIN)
    assert grown.shape == truth.shape
    np.testing.assert_array_equal(grown[MARGIN:-MARGIN, MARGIN:-MARGIN], readings)
    # every taxel beyond within 2 % of the disc's pressure (0.8 and 1.4 %); what they read
    # together (10 % of the load) within 5 % of the truth (97 % of it), and closer when the
    # iterations go on (99 and 97 % at a tolerance of 1e-4)
    assert np.abs(grown - truth).max() < 0.02 * 50e3
    wanted = _beyond(truth).sum()
    assert wanted > 0.08 * load.sum() / oversampling**2
    assert _beyond(grown).sum() == pytest.approx(wanted, rel=0.05)
    closer = extend_readings(spec, readings, MARGIN, tolerance=1e-4)
    assert _beyond(closer).sum() == pytest.approx(wanted, rel=0.03)
    assert abs(_beyond(closer).sum() - wanted) < abs(_beyond(grown).sum() - wanted)


def test_a_load_far_from_the_edges_reads_nothing_beyond_them():
    rows, cols = np.indices((48, 48))
    load = np.where((rows - 24) ** 2 + (cols - 24) ** 2 < 16, 50e3, 0.0)
    grown = extend_readings(SPEC, forward_operator(SPEC, boundary="zero").apply(load), MARGIN)
    assert np.abs(_beyond(grown)).max() < 1e-3 * 50e3  # 2.5e-4 of it


def test_the_noise_beyond_is_smoothed():
    # unit noise on the array: beyond it, the load that explains it presses a smoothed
    # sum of the noise near the edges (std 0.15 in all, 0.42 on the first ring)
    noise = np.random.default_rng(0).normal(0.0, 1.0, (48, 48))
    grown = extend_readings(SPEC, noise, MARGIN)
    assert _beyond(grown).std() < 0.25
    assert grown[MARGIN - 1, MARGIN:-MARGIN].std() < 0.6


def test_a_dead_taxel_is_left_out_of_the_fit():
    load = _loads()
    readings = forward_operator(SPEC, boundary="zero").apply(load)
    truth = _grown_truth(SPEC, load)
    broken = readings.copy()
    broken[20, 0] = 10 * broken.max()  # on the edge, under the disc
    dead = SPEC.with_changes(dead_taxels=[(20, 0)])
    grown = extend_readings(dead, broken, MARGIN)
    assert grown[MARGIN + 20, MARGIN] == broken[20, 0]  # kept inside as given
    # beyond the edge within 0.9 % of the disc's pressure; fitted, the broken reading is
    # carried beyond the edge 2.3 times the disc's pressure off
    assert np.abs(grown - truth)[_outside()].max() < 0.02 * 50e3
    assert np.abs(extend_readings(SPEC, broken, MARGIN) - truth)[_outside()].max() > 0.2 * 50e3


def test_bad_input_is_refused_by_name():
    readings = np.zeros((48, 48))
    with pytest.raises(ValueError, match="margin"):
        extend_readings(SPEC, readings, 0)
    with pytest.raises(ValueError, match="regularization"):
        extend_readings(SPEC, readings, 2, regularization=-1.0)
    with pytest.raises(ValueError, match="readings.*shape"):
        extend_readings(SPEC, np.zeros((40, 48)), 2)
    with pytest.raises(ValueError, match="readings"):
        extend_readings(SPEC, np.full((48, 48), np.nan), 2)
