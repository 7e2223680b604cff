"""Which way a sensor's raw reading goes as the load grows, and where it turns back.

Most transducers read more as they are pressed harder. A PVDF array's charge amplifiers
swing down when the film is compressed, and a microbend fibre loses light: their readings
fall. A photoelastic layer's intensity follows the load only up to its first fringe (half a
wavelength of retardation), then turns back. Features that read an image as "brighter is
pressed harder" need both facts (`taxel.features.prepare`, `taxel features`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, cast

import numpy as np

from taxel.transducers import PhotoelasticTransducer

if TYPE_CHECKING:  # pragma: no cover - the sensor imports this module
    from taxel.sensor._sensor import TactileSensor

__all__ = ["flat_plate_gain", "reaches_turn", "reading_turns_at"]

# a frame has reached the turn when some taxel has gone this far from rest towards it
_TURN_REACHED = 0.97


def flat_plate_gain(sensor: TactileSensor) -> float:
    """Mean change of the raw reading per pascal near rest [raw units / Pa].

    Read off the mean raw frame (`TactileSensor.mean_reading`) unloaded and under a flat
    plate at a tenth of the sensor's `full_scale`. Negative when the reading falls as the
    pressure rises.

    Examples
    --------
    >>> from taxel.sensor import make_sensor
    >>> round(make_sensor("capacitive4x4").flat_plate_gain, 2)  # 16-bit codes per Pa
    1.11
    >>> [make_sensor(name).reading_falls_with_pressure for name in ("piezo8x8", "resistive16")]
    [True, False]
    """
    grid = sensor.load_grid.shape
    readings = []
    for pressure in (np.zeros(grid), np.full(grid, 0.1 * sensor.full_scale)):
        quantity = sensor.sensed_quantity(pressure, sensor.fields(pressure))
        readings.append(float(np.mean(sensor.mean_reading(quantity))))
    return (readings[1] - readings[0]) / (0.1 * sensor.full_scale)


def reading_turns_at(sensor: TactileSensor) -> float | None:
    """The mean raw reading past which the reading no longer follows the load [raw units].

    A photoelastic layer's first fringe: its intensity peaks (dark field) or bottoms out
    (light field) at half a wavelength of retardation, then turns back as the stress grows.
    None for the other transducers, whose reading is monotonic in the load.

    Examples
    --------
    >>> from taxel.sensor import make_sensor
    >>> round(make_sensor("photoelastic64").reading_turns_at, 1)  # 8-bit codes, dark field
    243.9
    >>> make_sensor("resistive16").reading_turns_at is None
    True
    """
    if sensor.quantity != "stress_difference":
        return None
    photoelastic = cast(PhotoelasticTransducer, sensor.transducer)
    half_fringe = np.full(sensor.shape, 0.5 * photoelastic.fringe_stress)
    return float(np.mean(sensor.mean_reading(half_fringe)))


def reaches_turn(sensor: TactileSensor, frame: np.ndarray) -> bool:
    """Whether a raw frame has gone 97 % of the way from rest to `reading_turns_at`.

    Past that reading the brightest (or darkest) taxels are no longer where the load is
    highest. Always False for a sensor whose reading does not turn.

    Examples
    --------
    >>> from taxel.mechanics import make_indenter
    >>> from taxel.sensor import make_sensor
    >>> sensor, sphere = make_sensor("photoelastic64"), make_indenter("sphere")
    >>> [sensor.reaches_turn(sensor.press(sphere, normal_force=f).raw) for f in (0.5, 2.0)]
    [False, True]
    """
    turn = sensor.reading_turns_at
    if turn is None:
        return False
    rest = float(np.mean(sensor.mean_reading(np.zeros(sensor.shape))))
    return bool(np.max((frame - rest) / (turn - rest)) >= _TURN_REACHED)
