"""The calibration rig: flat-plate presses at known pressures, fitted into a `Calibration`.

The rig presses a flat plate on the whole array at a set of pressures spanning the sensor's
range, several times each, through the sensor's own simulation (cover, transducer, readout,
noise, faults), and fits each taxel's mean readings (isotonic regression, then a monotone
cubic); the resulting `Calibration` inverts them frame by frame.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel._validation import as_finite_array, as_rng, check_count, check_positive, check_range
from taxel.sensor._calibration import Calibration
from taxel.sensor._fields import taxel_fields
from taxel.sensor._monotone import isotonic_increasing
from taxel.sensor._sensor import TactileSensor

__all__ = ["calibrate"]


def _rails(sensor: TactileSensor) -> tuple[float, float] | None:
    """(bottom, top) raw values a taxel pinned at a rail reads; None if unbounded."""
    if sensor.readout.bits is not None:
        return 0.0, float(2**sensor.readout.bits - 1)
    camera_bits = getattr(sensor.transducer, "bits", None)
    if sensor.transducer.signal_unit == "DN" and camera_bits is not None:
        return 0.0, float(2**camera_bits - 1)
    if sensor.readout.is_identity:
        return None
    return sensor.readout_chain.rails


def calibrate(
    sensor: TactileSensor,
    *,
    pressures: Any = None,
    n_levels: int | None = None,
    repeats: int = 8,
    rng: Any = None,
    min_response: float = 0.1,
) -> Calibration:
    """Calibrate every taxel of a static sensor with flat-plate presses.

    Parameters
    ----------
    sensor : TactileSensor
        A sensor that measures static load (not piezoelectric, not photoelastic).
    pressures : array_like, optional
        Plate pressures [Pa], increasing from 0; default `n_levels` evenly spaced from 0
        to the sensor's `full_scale`.
    n_levels : int, optional
        Number of pressures when `pressures` is not given, >= 4; default the sensor's
        `calibration_levels` (21, or 81 for the 8-bit camera of vhdta128).
    repeats : int, default 8
        Frames averaged per pressure (with noise on); 1 is used without noise.
    rng : numpy.random.Generator or int, optional
        Switches the sensor's noise on, as a real rig would see it; None calibrates on
        noise-free frames.
    min_response : float, default 0.1
        A taxel whose reading changes from no load to the largest pressure by less than
        this fraction of the median taxel's change is excluded (dead or stuck).

    Returns
    -------
    Calibration

    Raises
    ------
    ValueError
        For a piezoelectric sensor (it sees only changes of load: a static calibration
        is not defined) or a photoelastic one (a flat plate makes no fringes: its load is
        fitted to whole fringe maps, see `taxel.transducers.fit_load_scale`).

    Notes
    -----
    Per taxel, the mean readings are fitted by isotonic regression (monotonic in the
    direction most taxels respond) and joined by a PCHIP cubic, which stays monotonic;
    `Calibration.apply` inverts it by bisection on the right segment. The frames come from
    ``sensor.frame_from_pressure(np.full(sensor.load_grid.shape, p))``.

    A microbend array is calibrated per fibre, not per crossing: each reading is the sum
    of the loads on the 16 crossings along a fibre, so no load on the whole array can tell
    one crossing's response from its neighbours'. Its calibrated value is the mean plate
    pressure along each fibre; `taxel.transducers.separable_pressure` turns the row and
    column values into an image. Crosstalk between taxels is a spatial effect that no
    per-taxel map can undo: under a plate it folds into each taxel's gain, under a local
    load it still spreads the reading (about 1 % of full scale for resistive16).

    Examples
    --------
    >>> from taxel.sensor import make_sensor
    >>> sensor = make_sensor("resistive16")
    >>> calibration = calibrate(sensor, rng=0)
    >>> frame = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 80e3))
    >>> pressure = calibration.apply(frame.raw)
    >>> round(float(np.abs(pressure - 80e3).max()) / sensor.full_scale, 4) < 0.005
    True
    >>> int(calibration.valid.sum())
    256
    """
    if not isinstance(sensor, TactileSensor):
        raise TypeError(f"`sensor` must be a TactileSensor, got {sensor!r}")
    if sensor.is_dynamic:
        raise ValueError(
            f"`sensor` {sensor.name!r} senses only changes of load ({sensor.quantity}): "
            "a static calibration is not defined"
        )
    if sensor.quantity == "stress_difference":
        raise ValueError(
            f"`sensor` {sensor.name!r} is photoelastic: a flat plate makes no fringes and its "
            "load is fitted to whole fringe maps (fit_load_scale), not calibrated per taxel"
        )
    if n_levels is None:
        n_levels = sensor.calibration_levels
    levels = _levels(sensor, pressures, n_levels)
    repeats = check_count("repeats", repeats)
    min_response = check_range("min_response", min_response, 0.0, 1.0, high_inclusive=False)
    count = repeats if rng is not None else 1
    generator = as_rng("rng", rng)
    means, lows, highs, spreads = [], [], [], []
    for level in levels:
        quantity = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, level)).quantity
        frames = np.stack(
            [np.asarray(sensor.read(quantity, rng=generator), float) for _ in range(count)]
        )
        means.append(frames.mean(axis=0))
        lows.append(frames.min(axis=0))
        highs.append(frames.max(axis=0))
        spreads.append(frames.std(axis=0, ddof=1) if count > 1 else np.zeros(frames.shape[1:]))
    readings = np.stack(means)
    lowest, highest, noise = np.min(lows, axis=0), np.max(highs, axis=0), spreads[0]
    change = readings[-1] - readings[0]
    direction = -1.0 if np.median(change) < 0 else 1.0
    fitted = direction * isotonic_increasing(direction * readings)
    rise = direction * (fitted[-1] - fitted[0])
    unresponsive = ~(rise > min_response * np.median(rise))
    pinned = np.zeros(readings.shape[1:], dtype=bool)
    rails = _rails(sensor)
    if rails is not None:
        tolerance = 0.5 if sensor.readout.bits or sensor.transducer.signal_unit == "DN" else 0.0
        pinned = (highest <= rails[0] + tolerance) | (lowest >= rails[1] - tolerance)
    return Calibration(
        sensor_name=sensor.name,
        pressures=levels,
        readings=fitted,
        felt_fraction=_felt_fraction(sensor, readings.shape[1:]),
        valid=~(unresponsive | pinned),
        unresponsive=unresponsive,
        pinned=pinned,
        noise=np.asarray(noise, dtype=float),
        full_scale=float(sensor.full_scale),
        repeats=count,
    )


def _felt_fraction(sensor: TactileSensor, shape: tuple[int, ...]) -> np.ndarray:
    """Normal stress at the sensing depth per pascal of plate pressure, per channel [-]."""
    plate = np.ones(sensor.load_grid.shape)
    stress = taxel_fields(plate, sensor.load_grid, sensor.cover, need=("stress",)).stress
    felt = np.clip(-stress, 0.0, None)
    rows, cols = sensor.shape
    if shape == (rows, cols):
        return felt
    if shape == (rows + cols,):  # fibres: the mean along each row, then each column
        return np.concatenate([felt.mean(axis=1), felt.mean(axis=0)])
    return np.ones(shape)


def _levels(sensor: TactileSensor, pressures: Any, n_levels: int) -> np.ndarray:
    if pressures is None:
        return np.linspace(0.0, sensor.full_scale, check_count("n_levels", n_levels, minimum=4))
    levels = as_finite_array("pressures", pressures, ndim=1)
    if levels.size < 4 or levels[0] != 0 or np.any(np.diff(levels) <= 0):
        raise ValueError(
            "`pressures` must hold at least 4 increasing values starting at 0, "
            f"got {np.array2string(levels, precision=3, threshold=6)}"
        )
    check_positive("pressures[-1]", levels[-1])
    return levels
