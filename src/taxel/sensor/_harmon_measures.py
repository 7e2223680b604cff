"""Measurements behind Harmon's criteria: step, sensitivity, hysteresis, stability."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from taxel._validation import as_rng, check_instance
from taxel.sensor._calibration import Calibration
from taxel.sensor._sensor import TactileSensor

__all__ = [
    "ReadingStep",
    "hysteresis_width",
    "monotonic_fraction",
    "reading_step",
    "sensitivity_force",
    "stability_change",
]

_NOISE_FRAMES = 32
_BISECTIONS = 50


def sensed(sensor: TactileSensor, pressure: np.ndarray) -> np.ndarray:
    """The transducer's input for a surface pressure [Pa], mechanics only (no readout)."""
    return sensor.sensed_quantity(pressure, sensor.fields(pressure))


def _plate(sensor: TactileSensor, pressure: float) -> np.ndarray:
    """Sensed quantity under a flat plate at `pressure` [Pa] over the whole array."""
    return sensed(sensor, np.full(sensor.load_grid.shape, pressure))


def _channels(sensor: TactileSensor, calibration: Calibration | None, span: np.ndarray) -> Any:
    """Channels that count: working (per the calibration) and responding at all."""
    working = np.ones(span.shape, bool) if calibration is None else calibration.valid
    return working & (span > 0)


@dataclass(frozen=True)
class ReadingStep:
    """The smallest change a reading shows, and how many such steps its span holds.

    Attributes
    ----------
    step : float
        max(lsb, noise) [raw unit].
    noise : float
        Median over taxels of the rms reading at rest [raw unit]; 0 without noise.
    lsb : float
        One output level: 1 for integer codes, 0 for a continuous output [raw unit].
    span : float
        Median over taxels of the change of the mean reading from no load to a
        full-scale plate [raw unit].
    """

    step: float
    noise: float
    lsb: float
    span: float

    @property
    def levels(self) -> float:
        """Distinct reliable levels over the working range, span / step."""
        return self.span / self.step

    def describe(self) -> str:
        """The step in words."""
        if self.noise > self.lsb:
            return f"rms noise {self.noise:.3g} > 1 level"
        return "1 level" if self.lsb else "no noise, no ADC"


def reading_step(sensor: TactileSensor, *, rng: Any = None) -> ReadingStep:
    """Measure the reading step of `sensor`: one ADC level or the rms noise at rest.

    Examples
    --------
    >>> from taxel.sensor import make_sensor
    >>> step = reading_step(make_sensor("harmon10x20"), rng=0)
    >>> step.lsb, round(step.noise, 1), round(step.levels)  # 12 bits, noise about 1 level
    (1.0, 1.2, 2910)
    """
    check_instance("sensor", sensor, TactileSensor)
    generator = as_rng("rng", rng)
    rest = _plate(sensor, 0.0)
    full = _plate(sensor, sensor.full_scale)
    raw = np.asarray(sensor.read(rest))
    lsb = 1.0 if np.issubdtype(raw.dtype, np.integer) else 0.0
    noise = 0.0
    if generator is not None:
        frames = np.stack(
            [np.asarray(sensor.read(rest, rng=generator), float) for _ in range(_NOISE_FRAMES)]
        )
        noise = float(np.median(frames.std(axis=0, ddof=1)))
    span = float(np.median(np.abs(sensor.mean_reading(full) - sensor.mean_reading(rest))))
    step = max(lsb, noise)
    if step == 0:
        step = 1e-12 * span if span > 0 else 1.0
    return ReadingStep(step=step, noise=noise, lsb=lsb, span=span)


def _element_block(sensor: TactileSensor) -> np.ndarray:
    """Load-grid mask of the cell of the middle taxel."""
    grid = sensor.load_grid
    k = sensor.oversampling
    row, col = sensor.shape[0] // 2, sensor.shape[1] // 2
    mask = np.zeros(grid.shape, dtype=bool)
    if sensor.geometry.layout == "hexagonal":
        start = col * 2 * k + (k if row % 2 else 0)
        mask[row * k : (row + 1) * k, start : start + 2 * k] = True
    else:
        mask[row * k : (row + 1) * k, col * k : (col + 1) * k] = True
    return mask


def sensitivity_force(sensor: TactileSensor, step: float, *, spread: str) -> float | None:
    """Smallest force per element that moves some mean reading by more than `step` [N].

    Parameters
    ----------
    sensor : TactileSensor
        The sensor.
    step : float
        The reading step [raw unit] (see `reading_step`).
    spread : {'element', 'uniform'}
        Where the force acts: on the middle taxel's cell only, or on every element alike
        (a flat plate of that force per element).

    Returns
    -------
    float or None
        The force [N], to 1e-15 relative (bisection on its logarithm); None when even the
        element's full-scale force does not move a reading that far.
    """
    grid = sensor.load_grid
    area = sensor.taxel_pitch[0] * sensor.taxel_pitch[1]
    if spread == "element":
        load = _element_block(sensor) / area
    elif spread == "uniform":
        load = np.full(grid.shape, 1.0 / area)
    else:
        raise ValueError(f"`spread` must be one of element, uniform; got {spread!r}")
    unit = sensed(sensor, load)  # per newton: the fields are linear
    rest = sensor.mean_reading(_plate(sensor, 0.0))

    def moves(force: float) -> bool:
        return bool(np.max(np.abs(sensor.mean_reading(force * unit) - rest)) > step)

    high = sensor.full_scale * area
    if not moves(high):
        return None
    low = high * 1e-9
    if moves(low):
        return low
    for _ in range(_BISECTIONS):
        middle = np.sqrt(low * high)
        if moves(middle):
            high = middle
        else:
            low = middle
    return float(high)


def hysteresis_width(sensor: TactileSensor, calibration: Calibration | None = None) -> float:
    """Widest gap between loading and unloading readings, over the span, worst taxel [-].

    A flat plate goes from no load to full scale in 50 frames and back in 50
    (`TactileSensor.read_sequence`, noise off).
    """
    full = _plate(sensor, sensor.full_scale)
    factors = np.concatenate([np.linspace(0.0, 1.0, 51), np.linspace(1.0, 0.0, 51)[1:]])
    series = factors.reshape(-1, *([1] * full.ndim)) * full
    raw = np.asarray(sensor.read_sequence(series), dtype=float)
    loading, unloading = raw[:51], raw[50:][::-1]
    span = np.abs(raw[50] - raw[0])
    channels = _channels(sensor, calibration, span)
    gap = np.abs(loading - unloading).max(axis=0)
    return float((gap[channels] / span[channels]).max())


def stability_change(sensor: TactileSensor, calibration: Calibration | None = None) -> float:
    """Change of the reading over a 1 s hold at full scale, over the span, worst taxel [-].

    The plate steps from no load to full scale at the first frame and stays; creep and
    drift move the reading, and a piezoelectric one fades back to rest.
    """
    full = _plate(sensor, sensor.full_scale)
    count = max(2, round(sensor.frame_rate))
    raw = np.asarray(sensor.read_sequence(np.repeat(full[None], count, axis=0)), float)
    rest = np.asarray(sensor.read(_plate(sensor, 0.0)), dtype=float)
    span = np.abs(raw[0] - rest)
    channels = _channels(sensor, calibration, span)
    return float((np.abs(raw[-1] - raw[0])[channels] / span[channels]).max())


def monotonic_fraction(sensor: TactileSensor, calibration: Calibration | None = None) -> float:
    """Fraction of working taxels whose mean reading moves one way over a plate sweep [-].

    101 plate pressures from 0 to full scale, noise-free mean readings
    (`TactileSensor.mean_reading`); the way is the one most taxels move.
    """
    full = _plate(sensor, sensor.full_scale)
    readings = np.stack([sensor.mean_reading(f * full) for f in np.linspace(0.0, 1.0, 101)])
    change = readings[-1] - readings[0]
    direction = -1.0 if np.median(change) < 0 else 1.0
    steps = direction * np.diff(readings, axis=0)
    tolerance = 1e-9 * float(np.abs(change).max() or 1.0)
    channels = _channels(sensor, calibration, np.ones(change.shape))
    monotone = np.all(steps >= -tolerance, axis=0)
    return float(monotone[channels].mean())
