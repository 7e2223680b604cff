"""The CPM-Finger of FabricSlide as a sensor model: the known facts hold, the rest is named."""

import subprocess
import sys

import numpy as np
import pytest

from taxel.io import CPM_FINGER, CPM_FINGER_ASSUMED, cpm_finger_sensor
from taxel.mechanics import make_indenter
from taxel.sensor import calibrate


@pytest.fixture(scope="module")
def sensor():
    return cpm_finger_sensor()


def test_known_facts(sensor):
    assert sensor.geometry.count == CPM_FINGER["n_taxels"] == 16
    assert CPM_FINGER["transduction"] == "capacitive" and sensor.quantity == "strain"
    assert sensor.readout.bits == 16  # two bytes per channel on the CAN bus
    assert sensor.frame_rate == pytest.approx(35.6, abs=0.1)  # the recordings' rate
    assert any("taxel_pitch" in name for name in CPM_FINGER_ASSUMED)
    assert CPM_FINGER["taxel_positions"] is None  # still unknown: the layout is assumed


def test_noise_at_rest_matches_the_recordings(sensor):
    rest = sensor.frame_from_pressure(np.zeros(sensor.load_grid.shape)).quantity
    frames = np.stack([sensor.read(rest, rng=seed) for seed in range(300)])
    assert frames.dtype.kind == "i" and frames.max() < 2**16
    # the quietest FabricSlide channels move by 1.1-1.3 counts rms (over sqrt 2) per frame
    assert frames.std(axis=0).mean() == pytest.approx(1.2, abs=0.1)


def test_a_press_reads_counts_above_rest_and_calibrates(sensor):
    rest = sensor.frame_from_pressure(np.zeros(sensor.load_grid.shape)).raw
    frame = sensor.press(make_indenter("sphere"), normal_force=1.0)
    above = frame.raw - rest  # what FabricSlide records: counts above rest
    assert above.min() > 0 and above[1:3, 1:3].min() > 10 * above[0, 0]
    calibration = calibrate(sensor, n_levels=9)
    assert calibration.valid.all()
    plate = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 2e4)).raw
    assert np.abs(calibration.apply(plate) - 2e4).max() < 0.02 * sensor.full_scale


def test_reading_files_does_not_load_the_sensor_models():
    code = "import sys, taxel.io; print('taxel.sensor' in sys.modules)"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.stdout.strip() == "False"
