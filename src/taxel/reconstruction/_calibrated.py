"""Raw frames through a sensor's calibration, in the quantity its forward model predicts."""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel.reconstruction._spec import plate_reading, reading_quantity, spec_from_sensor
from taxel.sensor import Calibration, TactileSensor, as_sensor

__all__ = ["calibrated_readings", "check_calibration_of"]


def check_calibration_of(calibration: Any, sensor: TactileSensor) -> Calibration:
    """Raise unless `calibration` is a `Calibration` made for `sensor` (by name and shape)."""
    if not isinstance(calibration, Calibration):
        raise TypeError(f"`calibration` must be a Calibration, got {calibration!r}")
    if calibration.sensor_name != sensor.name:
        raise ValueError(
            f"`calibration` was made for {calibration.sensor_name}, not {sensor.name}"
        )
    if calibration.shape != sensor.shape:
        raise ValueError(
            f"`calibration` of {sensor.name} reads frames of {calibration.shape}, but "
            f"{sensor.name}'s frames are {sensor.shape}"
        )
    return calibration


def calibrated_readings(raw: Any, calibration: Calibration, sensor: Any) -> np.ndarray:
    """Raw frames of a sensor as the readings its forward model predicts (`spec_from_sensor`).

    A `Calibration` maps each raw code to the pressure of a flat plate that gives it
    (`Calibration.apply`); the sensed quantity is linear in the load, so that pressure
    times the taxel's reading per pascal of plate (`plate_reading`) is what the taxel
    sensed under any load: the pressure felt at its depth [Pa] (`Calibration.felt_pressure`)
    for a stress- or pressure-sensing taxel, the surface displacement u_z [m] for a
    displacement-sensing one (reflective8x8), the strain eps_z [-] for a strain-sensing one.

    Parameters
    ----------
    raw : array_like, shape (..., rows, cols)
        Raw frames (ADC codes, camera levels).
    calibration : Calibration
        The sensor's calibration (`taxel.sensor.calibrate`).
    sensor : TactileSensor or str
        The sensor, or a preset name such as "reflective8x8".

    Returns
    -------
    numpy.ndarray, shape (..., rows, cols)
        Readings in the unit of ``spec_from_sensor(sensor).quantity``; NaN at the taxels
        the calibration excluded.

    Raises
    ------
    ValueError
        If the calibration was made for another sensor, if the sensor senses only changes
        of load (no static calibration maps its codes), or if its readings cannot be
        inverted (`spec_from_sensor`).

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.sensor import calibrate, make_sensor
    >>> sensor = make_sensor("reflective8x8")
    >>> calibration = calibrate(sensor)
    >>> plate = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 1e3))
    >>> readings = calibrated_readings(plate.raw, calibration, sensor)
    >>> print(f"{readings[4, 4]:.3e} m (sensed {plate.quantity[4, 4]:.3e} m)")
    1.017e-04 m (sensed 1.017e-04 m)
    """
    sensor = as_sensor(sensor)
    if sensor.is_dynamic:
        raise ValueError(
            f"`sensor` {sensor.name} senses only changes of load ({sensor.quantity}): no "
            "static calibration maps its raw codes to what it senses"
        )
    spec_from_sensor(sensor)  # refuses the sensors whose readings cannot be inverted
    check_calibration_of(calibration, sensor)
    if reading_quantity(sensor) == "stress":
        return calibration.felt_pressure(raw)  # the calibration's own felt fractions
    return calibration.apply(raw) * plate_reading(sensor)
