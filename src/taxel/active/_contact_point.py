"""Where the pad touched: a contact point from the tactile frame, the force and the cover model.

A robot knows the sensor's pose when pressed, the force along the sensor normal (a wrist
force sensor) and the tactile frame. From these, the point where the object's surface
meets the sensor is found in three steps:

1. Calibration (`calibrate_contact_points`): a flat plate presses the whole pad at known pressures
   (known forces over the pad's area); each taxel's raw reading is tabulated against the
   plate pressure. A frame is then read as an *equivalent plate pressure* per taxel.
2. Deconvolution: the cover spreads the surface pressure before it reaches the sensing
   elements. The surface pressure p >= 0 on the sensor's load grid is found by
   non-negative least squares against the cover model (FISTA with projection), and scaled
   so that sum(p) dA equals the measured normal force.
3. Compression: the cover's surface displacement u = D p (the same bonded-layer model) is
   how far the object's surface sits inside the undeformed pad. The contact point in the
   sensor frame is the pressure-weighted mean of the points (x, y, -u) of the contact cells;
   on a rigid plane every such point lies on the object, so their mean does too.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, as_rng, check_count, check_positive
from taxel.mechanics import (
    ConvolutionOperator,
    depth_strain_operator,
    depth_stress_operator,
    surface_displacement_operator,
)
from taxel.sensor import TactileSensor

__all__ = [
    "ContactPoint",
    "ContactPointCalibration",
    "calibrate_contact_points",
    "estimate_contact_point",
]

_LINEAR_QUANTITIES = ("pressure", "stress", "strain", "displacement")
_ITERATIONS = 150  # FISTA steps: the contact's centroid and compression settle well before
_FLOOR = 0.02  # cells below this fraction of the peak pressure are not in contact


@dataclass(frozen=True)
class ContactPointCalibration:
    """Per-taxel tables from raw readings to the pressure of a flat plate.

    Attributes
    ----------
    pressure : numpy.ndarray
        (n_levels,) plate pressures of the calibration presses [Pa], increasing from 0.
    raw : numpy.ndarray
        (n_levels, rows, cols) mean raw reading of each taxel at each level.
    noise : float
        Standard deviation of an unloaded reading, as an equivalent pressure [Pa].
    """

    pressure: np.ndarray = field(repr=False)
    raw: np.ndarray = field(repr=False)
    noise: float

    def equivalent_pressure(self, raw: Any) -> np.ndarray:
        """The plate pressure [Pa] each taxel's `raw` reading stands for, (rows, cols).

        Linear interpolation in each taxel's table, extrapolated beyond its ends.
        """
        raw = as_finite_array("raw", raw)
        if raw.shape != self.raw.shape[1:]:
            raise ValueError(f"`raw` must have shape {self.raw.shape[1:]}, got {raw.shape}")
        table = self.raw
        sign = np.sign(table[-1] - table[0])
        sign[sign == 0] = 1.0
        table, value = table * sign, raw * sign  # increasing along the levels
        index = np.clip((table <= value).sum(axis=0) - 1, 0, len(self.pressure) - 2)
        low = np.take_along_axis(table, index[None], axis=0)[0]
        high = np.take_along_axis(table, index[None] + 1, axis=0)[0]
        step = np.where(high > low, high - low, 1.0)
        weight = (value - low) / step
        return self.pressure[index] + weight * (self.pressure[index + 1] - self.pressure[index])


def calibrate_contact_points(
    sensor: TactileSensor, *, n_levels: int = 21, n_frames: int = 8, rng: Any = 0
) -> ContactPointCalibration:
    """Calibrate a sensor with a flat plate pressing its whole pad at known pressures.

    Parameters
    ----------
    sensor : TactileSensor
        A static sensor (not piezoelectric).
    n_levels : int, default 21
        Plate pressures, evenly from 0 to the sensor's full scale.
    n_frames : int, default 8
        Noisy frames averaged per level.
    rng : numpy.random.Generator or int, default 0
        The calibration's frame noise (None: noise-free frames).

    Returns
    -------
    ContactPointCalibration

    Examples
    --------
    >>> from taxel.sensor import make_sensor
    >>> sensor = make_sensor("resistive16")
    >>> calibration = calibrate_contact_points(sensor)
    >>> frame = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 50e3))
    >>> pressure = calibration.equivalent_pressure(frame.raw)
    >>> bool(np.all(np.abs(pressure - 50e3) < 2e3))
    True
    """
    _check_static(sensor)
    n_levels = check_count("n_levels", n_levels, minimum=2)
    n_frames = check_count("n_frames", n_frames)
    generator = as_rng("rng", rng)
    levels = np.linspace(0.0, sensor.full_scale, n_levels)
    shape = sensor.load_grid.shape
    raw = np.array(
        [
            np.mean(
                [
                    sensor.frame_from_pressure(np.full(shape, level), rng=generator).raw
                    for _ in range(n_frames)
                ],
                axis=0,
            )
            for level in levels
        ]
    )
    unloaded = np.array(
        [sensor.frame_from_pressure(np.zeros(shape), rng=generator).raw for _ in range(16)]
    )
    slope = (raw[1] - raw[0]) / (levels[1] - levels[0])
    slope = np.where(np.abs(slope) > 0, np.abs(slope), np.inf)
    noise = float(np.median(unloaded.std(axis=0) / slope))
    return ContactPointCalibration(levels, raw, noise)


def _check_static(sensor: TactileSensor) -> None:
    if not isinstance(sensor, TactileSensor):
        raise TypeError(f"`sensor` must be a TactileSensor, got {sensor!r}")
    if sensor.is_dynamic or sensor.quantity not in _LINEAR_QUANTITIES:
        raise ValueError(
            f"`sensor` {sensor.name!r} senses {sensor.quantity!r}"
            + (" changes only" if sensor.is_dynamic else "")
            + "; contact points need a static sensor linear in the pressure"
        )


@dataclass(frozen=True)
class ContactPoint:
    """Where the pad touched, in the sensor frame of the pressed pose.

    Attributes
    ----------
    point : numpy.ndarray
        (3,) the contact point (x, y, -compression) [m]: on the object's surface.
    compression : float
        Pressure-weighted depth of the object's surface into the pad [m].
    normal : numpy.ndarray or None
        (3,) the object's outward surface normal, from the plane through the contact cells'
        surface points: (0, 0, -1) for a face pressed flat on the pad (the object faces the
        sensor, against +z_S); None when the contact spans fewer than 3 cells each way.
    pressure : numpy.ndarray
        Estimated surface pressure on the load grid [Pa].
    displacement : numpy.ndarray
        Estimated surface displacement of the pad on the load grid [m].
    n_cells : int
        Load-grid cells in contact.
    touches_border : bool
        Whether the contact reaches the edge of the pad (it may continue beyond).
    """

    point: np.ndarray
    compression: float
    normal: np.ndarray | None
    pressure: np.ndarray = field(repr=False)
    displacement: np.ndarray = field(repr=False)
    n_cells: int
    touches_border: bool


@lru_cache(maxsize=8)
def _operators(sensor: TactileSensor) -> tuple[ConvolutionOperator, ConvolutionOperator, float]:
    """The sensed-quantity and surface-displacement operators of a sensor's cover."""
    grid, cover = sensor.load_grid, sensor.cover
    if sensor.quantity in ("pressure", "stress"):
        sensed = depth_stress_operator(
            grid.shape, grid.spacing, cover.depth, cover.material, thickness=cover.thickness
        )
    elif sensor.quantity == "strain":
        sensed = depth_strain_operator(
            grid.shape, grid.spacing, cover.depth, cover.material, thickness=cover.thickness
        )
    else:
        sensed = surface_displacement_operator(
            grid.shape, grid.spacing, cover.material, thickness=cover.thickness
        )
    displacement = surface_displacement_operator(
        grid.shape, grid.spacing, cover.material, thickness=cover.thickness
    )
    # the largest eigenvalue of A^T A (power iteration), for the FISTA step
    model = _SensedModel(sensed, sensor)
    vector = np.random.default_rng(0).random(grid.shape)
    norm = 1.0
    for _ in range(30):
        vector = model.adjoint(model.apply(vector))
        norm = float(np.linalg.norm(vector))
        vector /= norm
    return sensed, displacement, norm


class _SensedModel:
    """Surface pressure on the load grid -> equivalent plate pressure at each taxel."""

    def __init__(self, operator: ConvolutionOperator, sensor: TactileSensor) -> None:
        self._operator = operator
        self._grid = sensor.load_grid
        rows, cols = sensor.shape
        self._block = self._grid.shape[0] // rows, self._grid.shape[1] // cols
        self._unit = self._grid.taxel_means(operator.apply(np.ones(self._grid.shape)))

    def apply(self, pressure: np.ndarray) -> np.ndarray:
        return self._grid.taxel_means(self._operator.apply(pressure)) / self._unit

    def adjoint(self, values: np.ndarray) -> np.ndarray:
        spread = np.repeat(np.repeat(values / self._unit, self._block[0], 0), self._block[1], 1)
        return self._operator.adjoint(spread / (self._block[0] * self._block[1]))


def estimate_contact_point(
    raw: Any,
    normal_force: float,
    sensor: TactileSensor,
    calibration: ContactPointCalibration,
) -> ContactPoint:
    """Estimate the contact point of a pressed frame, with the pad's compression.

    Parameters
    ----------
    raw : array_like
        (rows, cols) the raw tactile frame.
    normal_force : float
        Measured force along the sensor normal [N], > 0.
    sensor : TactileSensor
        The sensor model (its cover gives the deconvolution and the compression).
    calibration : ContactPointCalibration
        From `calibrate_contact_points`.

    Returns
    -------
    ContactPoint

    Notes
    -----
    See the module notes: equivalent plate pressure -> non-negative deconvolution through
    the cover (min ||A p - e||^2, p >= 0, FISTA) -> scaling to the measured force ->
    displacement u = D p -> pressure-weighted surface point. The local normal is the plane
    fitted to the contact cells' points (x, y, -u), when they span at least 3 cells in
    both directions.

    Examples
    --------
    A flat plate pressing the whole pad at 20 kPa compresses it evenly:

    >>> from taxel.sensor import make_sensor
    >>> sensor = make_sensor("resistive16")
    >>> calibration = calibrate_contact_points(sensor)
    >>> frame = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 20e3))
    >>> force = 20e3 * sensor.geometry.active_area
    >>> contact = estimate_contact_point(frame.raw, force, sensor, calibration)
    >>> (np.round(contact.point[:2] * 1e3, 2) + 0.0).tolist(), contact.n_cells
    ([0.0, 0.0], 256)
    >>> (np.round(contact.normal, 3) + 0.0).tolist()
    [0.0, 0.0, -1.0]
    """
    _check_static(sensor)
    normal_force = check_positive("normal_force", normal_force)
    sensed, displacement_operator, lipschitz = _operators(sensor)
    model = _SensedModel(sensed, sensor)
    equivalent = calibration.equivalent_pressure(raw)
    equivalent = np.where(equivalent > 3 * calibration.noise, equivalent, 0.0)
    if not equivalent.any():
        raise ValueError("`raw` shows no contact above the noise; nothing to locate")
    pressure = _deconvolve(model, equivalent, lipschitz)
    grid = sensor.load_grid
    cell_area = grid.spacing[0] * grid.spacing[1]
    pressure = np.where(pressure > _FLOOR * pressure.max(), pressure, 0.0)
    pressure *= normal_force / (pressure.sum() * cell_area)
    displacement = displacement_operator.apply(pressure)
    x, y = grid.coordinates()
    weight = pressure / pressure.sum()
    compression = float((weight * displacement).sum())
    point = np.array([(weight * x).sum(), (weight * y).sum(), -compression])
    contact = pressure > 0
    rows, cols = np.nonzero(contact)
    normal = None
    if np.ptp(rows) >= 2 and np.ptp(cols) >= 2:
        design = np.column_stack([x[contact], y[contact], np.ones(rows.size)])
        (a, b, _), *_ = np.linalg.lstsq(design, -displacement[contact], rcond=None)
        normal = np.array([a, b, -1.0]) / np.sqrt(a * a + b * b + 1.0)
    border = bool(
        contact[0].any() or contact[-1].any() or contact[:, 0].any() or contact[:, -1].any()
    )
    return ContactPoint(
        point=point,
        compression=compression,
        normal=normal,
        pressure=pressure,
        displacement=displacement,
        n_cells=int(contact.sum()),
        touches_border=border,
    )


def _deconvolve(model: _SensedModel, equivalent: np.ndarray, lipschitz: float) -> np.ndarray:
    """Non-negative least squares by FISTA (Beck & Teboulle 2009) from a spread start."""
    start = model.adjoint(equivalent)
    estimate = np.clip(start, 0.0, None)
    momentum, t = estimate.copy(), 1.0
    step = 1.0 / lipschitz
    for _ in range(_ITERATIONS):
        gradient = model.adjoint(model.apply(momentum) - equivalent)
        following = np.clip(momentum - step * gradient, 0.0, None)
        t_next = (1.0 + np.sqrt(1.0 + 4.0 * t * t)) / 2.0
        momentum = following + (t - 1.0) / t_next * (following - estimate)
        estimate, t = following, t_next
    return estimate
