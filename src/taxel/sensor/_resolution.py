"""Two-point spatial resolution: how close two point loads may be and still give two peaks."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel._validation import as_rng, check_positive, check_range
from taxel.sensor._calibration import Calibration, check_calibration
from taxel.sensor._harmon_measures import sensed
from taxel.sensor._sensor import TactileSensor

__all__ = ["TwoPointResolution", "two_point_resolution"]

_FINEST_STEP = 0.25e-3  # separations are scanned in steps of at most this [m] ...
_MAX_CELLS = 256  # ... unless the load grid would exceed this many cells along a row
_CONFIRM = 3  # a separation counts once it and the next three are all resolved


@dataclass(frozen=True)
class TwoPointResolution:
    """Outcome of `two_point_resolution`.

    Attributes
    ----------
    resolution : float or None
        Smallest separation from which on two point loads are resolved [m]; None when
        no separation that fits on the array is.
    separations : numpy.ndarray
        Separations tried, increasing [m].
    dips : numpy.ndarray
        Depth of the valley between the two peaks, 1 - valley / lower peak, at each
        separation [-]; 0 where there are not two peaks.
    resolved : numpy.ndarray of bool
        Whether each separation met the criterion.
    point_force : float
        Force of each point load [N].
    dip : float
        The criterion: two peaks whose valley lies at least this fraction below the lower.
    """

    resolution: float | None
    separations: np.ndarray = field(repr=False)
    dips: np.ndarray = field(repr=False)
    resolved: np.ndarray = field(repr=False)
    point_force: float
    dip: float


def _refined(sensor: TactileSensor) -> TactileSensor:
    """The same sensor on a load grid fine enough to place loads between taxel centres."""
    pitch = sensor.taxel_pitch[1]
    per_taxel = 2 if sensor.geometry.layout == "hexagonal" else 1
    wanted = max(sensor.oversampling, math.ceil(pitch / (per_taxel * _FINEST_STEP)))
    room = max(1, _MAX_CELLS // (sensor.shape[1] * per_taxel))
    oversampling = max(sensor.oversampling, min(wanted, room))
    if oversampling == sensor.oversampling:
        return sensor
    return dataclasses.replace(sensor, oversampling=oversampling)


def _profile(sensor: TactileSensor, frame: np.ndarray, row: int) -> np.ndarray:
    """Values along x through taxel row `row`: that row, or the column fibres (microbend)."""
    rows, cols = sensor.shape
    if frame.shape == (rows, cols):
        values = frame[row]
    elif frame.shape == (rows + cols,):
        values = frame[rows:]
    else:
        raise ValueError(f"cannot read a profile along x from a frame of shape {frame.shape}")
    values = np.asarray(values, dtype=float)
    missing = np.isnan(values)
    if missing.all():
        return np.zeros_like(values)
    if missing.any():  # excluded taxels: bridge them from their neighbours
        index = np.arange(values.size)
        values = values.copy()
        values[missing] = np.interp(index[missing], index[~missing], values[~missing])
    return values


def peak_dip(profile: np.ndarray, x: np.ndarray, left: float, right: float, reach: float) -> float:
    """Valley depth between the two peaks of two loads at `left` and `right` [-].

    A peak is a local maximum at least half the profile's highest value, within `reach`
    outside its load and on its side of the middle; of each side's peaks the highest
    counts. Returns ``1 - valley / lower peak``, or 0 when a side has no peak.

    Examples
    --------
    >>> x = np.arange(7.0)
    >>> peak_dip(np.array([0, 1, 4, 2, 4, 1, 0.0]), x, 2.0, 4.0, 1.0)
    0.5
    >>> peak_dip(np.array([0, 1, 2, 4, 2, 1, 0.0]), x, 2.0, 4.0, 1.0)  # one peak, between
    0.0
    >>> peak_dip(np.array([1, 0, 0, 4, 2, 1, 0.0]), x, 2.0, 4.0, 3.0)  # a bump is no peak
    0.0
    """
    middle = 0.5 * (left + right)
    padded = np.concatenate([[-np.inf], profile, [-np.inf]])
    local = (padded[1:-1] >= padded[:-2]) & (padded[1:-1] >= padded[2:])
    local &= profile >= 0.5 * profile.max()
    left_peaks = np.flatnonzero(local & (x < middle) & (x >= left - reach))
    right_peaks = np.flatnonzero(local & (x > middle) & (x <= right + reach))
    if left_peaks.size == 0 or right_peaks.size == 0:
        return 0.0
    i = int(left_peaks[np.argmax(profile[left_peaks])])
    j = int(right_peaks[np.argmax(profile[right_peaks])])
    lower = min(profile[i], profile[j])
    if lower <= 0 or j - i < 2:
        return 0.0
    valley = float(profile[i : j + 1].min())
    return float(max(0.0, 1.0 - valley / lower))


def two_point_resolution(
    sensor: TactileSensor,
    *,
    calibration: Calibration | None = None,
    rng: Any = None,
    dip: float = 0.2,
    peak_fraction: float = 0.5,
) -> TwoPointResolution:
    """Smallest separation at which two point loads give two peaks in the sensor's frame.

    Parameters
    ----------
    sensor : TactileSensor
        The sensor (any but photoelastic: fringes are not peaks).
    calibration : Calibration, optional
        Its calibration: peaks are sought in the calibrated frame. None uses the change
        of the raw reading from rest (a dynamic sensor: the step response).
    rng : numpy.random.Generator or int, optional
        Switches the sensor's noise on; each separation is judged on one noisy frame.
    dip : float, default 0.2
        The peak criterion: the valley between the two peaks lies at least this fraction
        below the lower peak (Rayleigh's criterion for two Airy discs is about 0.26).
    peak_fraction : float, default 0.5
        Each point load alone makes the taxel under it feel this fraction of what a
        full-scale flat plate makes it feel.

    Returns
    -------
    TwoPointResolution

    Notes
    -----
    Each point load is the force on one cell of the load grid, placed along the x axis
    through the middle taxel row, the pair centred on the middle taxel. The grid is
    refined (more cells per taxel) until separations step by at most 0.25 mm, so the
    result is not a multiple of the pitch by construction. Separations grow from one
    cell until one is resolved and so are the next three; that one is the resolution.
    Two peaks need a taxel between them, so no array resolves less than about two
    pitches, whatever its cover.

    Examples
    --------
    >>> from taxel.sensor import calibrate, make_sensor
    >>> sensor = make_sensor("resistive16")
    >>> result = two_point_resolution(sensor, calibration=calibrate(sensor))
    >>> round(result.resolution * 1e3, 2)  # [mm], 2 mm pitch under a 1.5 mm pad
    3.0
    """
    if not isinstance(sensor, TactileSensor):
        raise TypeError(f"`sensor` must be a TactileSensor, got {sensor!r}")
    if sensor.quantity == "stress_difference":
        raise ValueError(
            f"`sensor` {sensor.name!r} is photoelastic: its frames are fringes, not peaks"
        )
    if calibration is not None:
        check_calibration(calibration, sensor)
    dip = check_range("dip", dip, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
    peak_fraction = check_positive("peak_fraction", peak_fraction)
    fine = _refined(sensor)
    grid = fine.load_grid
    cell_x, cell_y = grid.coordinates()
    taxel_x, taxel_y = sensor.geometry.positions()
    row, col = sensor.shape[0] // 2, sensor.shape[1] // 2
    cell_row = int(np.argmin(np.abs(cell_y[:, 0] - taxel_y[row, col])))
    xs = cell_x[cell_row]
    centre = int(np.argmin(np.abs(xs - taxel_x[row, col])))
    cell_area = grid.spacing[0] * grid.spacing[1]

    def pressure(columns: tuple[int, ...], force: float) -> np.ndarray:
        load = np.zeros(grid.shape)
        load[cell_row, list(columns)] = force / cell_area
        return load

    # one point alone, 1 N: scale it so the taxel under it feels `peak_fraction` of FS
    single = np.abs(sensed(fine, pressure((centre,), 1.0))).max()
    plate = sensed(fine, np.full(grid.shape, sensor.full_scale))
    force = peak_fraction * float(np.abs(plate).max()) / float(single)
    rest = fine.mean_reading(sensed(fine, np.zeros(grid.shape)))
    generator = as_rng("rng", rng)
    separations, dips = [], []
    spacing = grid.spacing[1]
    for n in range(1, xs.size):
        left = centre - n // 2
        right = left + n
        if left < 0 or right >= xs.size:
            break
        raw = fine.frame_from_pressure(pressure((left, right), force), rng=generator).raw
        if calibration is not None:
            frame = calibration.apply(raw)
        else:
            frame = np.abs(np.asarray(raw, dtype=float) - rest)
        profile = _profile(sensor, frame, row)
        reach = sensor.taxel_pitch[1]
        dips.append(peak_dip(profile, taxel_x[row], xs[left], xs[right], reach))
        separations.append(n * spacing)
        flags = np.asarray(dips) >= dip
        if flags.size > _CONFIRM and flags[-_CONFIRM - 1 :].all():
            break
    flags = np.asarray(dips) >= dip
    resolution = None
    if flags.size > _CONFIRM and flags[-_CONFIRM - 1 :].all():
        resolution = float(separations[-_CONFIRM - 1])
    return TwoPointResolution(
        resolution=resolution,
        separations=np.asarray(separations),
        dips=np.asarray(dips),
        resolved=flags,
        point_force=force,
        dip=dip,
    )
