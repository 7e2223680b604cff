"""Raw frames through a calibration land in the forward model's quantity, for every preset."""

import numpy as np
import pytest

from taxel.mechanics import make_indenter
from taxel.reconstruction import calibrated_readings, reconstruct, spec_from_sensor
from taxel.sensor import calibrate, make_sensor


def test_a_displacement_sensor_reads_metres_and_its_force_is_recovered():
    # reflective8x8 senses the surface displacement: its calibrated plate pressure [Pa]
    # was taken as metres, and a 0.05 N press came back as 5e5 N
    sensor = make_sensor("reflective8x8")
    calibration = calibrate(sensor)
    clean = sensor.press(make_indenter("sphere"), normal_force=0.05)
    sensed = clean.quantity  # the displacement each taxel sensed [m]
    assert spec_from_sensor(sensor).quantity == "displacement"
    assert 1e-5 < sensed.max() < 1e-4  # tens of micrometres, not the ~1 kPa of the plate scale
    error = calibrated_readings(clean.raw, calibration, sensor) - sensed
    assert np.abs(error).max() < 0.01 * sensed.max()
    frame = sensor.press(make_indenter("sphere"), normal_force=0.05, rng=2)
    readings = calibrated_readings(frame.raw, calibration, sensor)
    for method in ("tikhonov", "support"):
        force = reconstruct(readings, sensor, method=method).normal_force
        assert force == pytest.approx(0.05, rel=0.02), method


def test_a_stress_sensor_reads_the_felt_pressure_as_before():
    sensor = make_sensor("resistive16")
    calibration = calibrate(sensor)
    raw = sensor.press(make_indenter("sphere"), normal_force=2.0).raw
    assert np.array_equal(
        calibrated_readings(raw, calibration, "resistive16"), calibration.felt_pressure(raw)
    )


def test_the_full_scale_of_a_displacement_spec_is_in_metres():
    sensor = make_sensor("reflective8x8")
    plate = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, sensor.full_scale))
    assert spec_from_sensor(sensor).full_scale == pytest.approx(plate.quantity.max())
    assert spec_from_sensor(make_sensor("resistive16")).full_scale == 200e3


def test_what_no_calibration_can_map_is_refused():
    calibration = calibrate(make_sensor("resistive16"))
    with pytest.raises(ValueError, match="`calibration` was made for resistive16, not vhdta128"):
        calibrated_readings(np.zeros((128, 128)), calibration, "vhdta128")
    with pytest.raises(ValueError, match="`sensor` piezo8x8 senses only changes of load"):
        calibrated_readings(np.zeros((8, 8)), calibration, "piezo8x8")
    with pytest.raises(TypeError, match="`calibration` must be a Calibration"):
        calibrated_readings(np.zeros((16, 16)), "cal.npz", "resistive16")


def _faulty_resistive16():
    """resistive16 with 2 % of its taxels dead (they read the bottom of the ADC's range)."""
    from dataclasses import replace

    sensor = make_sensor("resistive16")
    return replace(sensor, readout=replace(sensor.readout, dead=0.02))


def test_the_taxels_a_calibration_excludes_are_left_out_of_the_fit():
    # the issue: dead taxels marked by calibration are excluded from the fit rather than
    # read as zero; the calibrated readings are NaN there, which a fit refused outright
    sensor = _faulty_resistive16()
    calibration = calibrate(sensor, rng=1)
    dead = ~calibration.valid
    assert 3 <= np.count_nonzero(dead) <= 10
    raw = sensor.press(make_indenter("sphere"), normal_force=2.0, rng=3).raw
    readings = calibrated_readings(raw, calibration, sensor)
    assert np.array_equal(np.isnan(readings), dead)
    with pytest.raises(ValueError, match="`frame` must be finite at live taxels"):
        reconstruct(readings, sensor)
    for method in ("tikhonov", "support"):
        result = reconstruct(readings, sensor, method=method, dead_taxels=dead)
        assert result.normal_force == pytest.approx(2.0, rel=0.03), method
    # a dead taxel under the contact (one of the four that feel 98 kPa; its neighbours feel
    # 9 kPa) read as zero instead loses its share of the load
    under = np.zeros(sensor.shape, dtype=bool)
    under[7, 7] = True
    spec = spec_from_sensor(sensor)
    clean = -sensor.press(make_indenter("sphere"), normal_force=2.0).fields.stress  # felt
    zeroed = np.where(under, 0.0, clean)
    read_as_zero = reconstruct(zeroed, spec, method="support").normal_force
    holes = np.where(under, np.nan, clean)
    left_out = reconstruct(holes, spec, method="support", dead_taxels=under)
    assert left_out.normal_force == pytest.approx(2.0, rel=0.02)
    assert read_as_zero < 0.9 * 2.0  # 1.65 N
