"""How well a calibration returns the pressure that was applied: the round-trip error."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, as_rng, check_range
from taxel.sensor._calibration import Calibration, check_calibration
from taxel.sensor._sensor import TactileSensor

__all__ = ["CalibrationError", "calibration_error"]


@dataclass(frozen=True)
class CalibrationError:
    """Round-trip error of a calibration: flat-plate frames read back through it.

    Attributes
    ----------
    pressures : numpy.ndarray, shape (n,)
        Applied plate pressures [Pa].
    max_error : numpy.ndarray, shape (n,)
        Largest abs(calibrated - applied) over the valid taxels at each pressure [Pa].
    rms_error : numpy.ndarray, shape (n,)
        Root-mean-square of the same [Pa].
    full_scale : float
        The sensor's working range [Pa].
    noisy : bool
        Whether the frames carried the sensor's noise.
    """

    pressures: np.ndarray = field(repr=False)
    max_error: np.ndarray = field(repr=False)
    rms_error: np.ndarray = field(repr=False)
    full_scale: float
    noisy: bool

    @property
    def worst(self) -> float:
        """Largest error over all pressures, as a fraction of full scale [-]."""
        return float(self.max_error.max() / self.full_scale)

    @property
    def rms(self) -> float:
        """Root-mean-square error over all pressures and taxels, fraction of full scale."""
        return float(np.sqrt(np.mean(self.rms_error**2)) / self.full_scale)

    def measuring_range(self, tolerance: float = 0.02) -> float:
        """Largest tested pressure up to which every error is within `tolerance` of FS [Pa].

        Examples
        --------
        >>> error = CalibrationError(np.array([0.0, 1.0, 2.0, 3.0]),
        ...                          np.array([0.0, 0.01, 0.05, 0.01]), np.zeros(4), 3.0, False)
        >>> error.measuring_range(0.01), error.measuring_range(0.02)
        (1.0, 3.0)
        """
        tolerance = check_range("tolerance", tolerance, 0.0, 1.0, low_inclusive=False)
        within = self.max_error <= tolerance * self.full_scale
        if not within[0]:
            return 0.0
        failing = np.flatnonzero(~within)
        last = len(within) - 1 if failing.size == 0 else int(failing[0]) - 1
        return float(self.pressures[last])


def calibration_error(
    sensor: TactileSensor,
    calibration: Calibration,
    *,
    pressures: Any = None,
    rng: Any = None,
) -> CalibrationError:
    """Press a flat plate at known pressures and compare the calibrated frame with them.

    Parameters
    ----------
    sensor : TactileSensor
        The sensor the calibration was made for.
    calibration : Calibration
        Its calibration (see `calibrate`).
    pressures : array_like, optional
        Plate pressures to test [Pa], in [0, full_scale]; default the calibration's own
        pressures and the quarter, half and three-quarter points between each two of
        them, so that three of every four fall where the map interpolates.
    rng : numpy.random.Generator or int, optional
        Switches the sensor's noise on; None tests noise-free frames.

    Returns
    -------
    CalibrationError

    Examples
    --------
    >>> from taxel.sensor import calibrate, make_sensor
    >>> sensor = make_sensor("capacitive4x4")
    >>> error = calibration_error(sensor, calibrate(sensor))
    >>> error.worst < 1e-3  # fraction of full scale, noise off
    True
    """
    if not isinstance(sensor, TactileSensor):
        raise TypeError(f"`sensor` must be a TactileSensor, got {sensor!r}")
    check_calibration(calibration, sensor)
    if pressures is None:
        knots = calibration.pressures
        quarters = np.interp(np.arange(4 * len(knots) - 3) / 4, np.arange(len(knots)), knots)
        levels = quarters[quarters <= sensor.full_scale]
    else:
        levels = as_finite_array("pressures", pressures, ndim=1)
        if levels.size == 0 or np.any(levels < 0) or np.any(levels > sensor.full_scale):
            raise ValueError(
                f"`pressures` must lie in [0, full_scale = {sensor.full_scale:g}] Pa, "
                f"got {np.array2string(levels, precision=3, threshold=6)}"
            )
    generator = as_rng("rng", rng)
    worst, rms = [], []
    for level in levels:
        frame = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, level), rng=generator)
        error = calibration.apply(frame.raw)[calibration.valid] - level
        worst.append(float(np.abs(error).max()))
        rms.append(float(np.sqrt(np.mean(error**2))))
    return CalibrationError(
        pressures=levels,
        max_error=np.asarray(worst),
        rms_error=np.asarray(rms),
        full_scale=float(sensor.full_scale),
        noisy=rng is not None,
    )
