"""Harmon's criteria for tactile sensors (chapter section 25.2), measured on a simulated sensor.

Harmon's 1980 survey asked for: spatial resolution of 1 to 2 mm; arrays of 5 x 10 to
10 x 20 points; a sensitivity of 0.005 to 0.01 N per element; a dynamic range of 1000:1;
stable behaviour without hysteresis; 100 Hz to 1 kHz sampling; a monotonic (not
necessarily linear) response; a compliant, rugged and inexpensive interface. Every value
here is measured on the sensor model (frames, sequences, a calibration), not read off its
parameters, except the array size, the frame rate and the pad's modulus, which are
what they are.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel._validation import as_rng
from taxel.sensor._calibrate import calibrate
from taxel.sensor._calibration import Calibration, check_calibration
from taxel.sensor._harmon_measures import (
    hysteresis_width,
    monotonic_fraction,
    reading_step,
    sensitivity_force,
    stability_change,
)
from taxel.sensor._resolution import TwoPointResolution, two_point_resolution
from taxel.sensor._sensor import TactileSensor

__all__ = ["HarmonRow", "HarmonTable", "harmon_table"]

# Harmon's targets in SI units (chapter section 25.2, "Requirements for Tactile Sensors")
_RESOLUTION = (1e-3, 2e-3)  # [m]
_ARRAY_POINTS = (50, 200)  # 5 x 10 to 10 x 20
_SENSITIVITY = (0.005, 0.01)  # [N per element]
_DYNAMIC_RANGE = 1000.0
_SAMPLING_RATE = (100.0, 1000.0)  # [Hz]
# our reading of "compliant": an elastomer pad, from fingertip-soft (~0.1 MPa) to rubber
_COMPLIANT_MODULUS = 5e6  # [Pa]


@dataclass(frozen=True)
class HarmonRow:
    """One criterion: the measured value, Harmon's target and the verdict.

    Attributes
    ----------
    criterion : str
        Its name (e.g. ``'spatial resolution'``).
    value : float or None
        The measured value in `unit`; None when it cannot be measured on this sensor.
    unit : str
        SI unit of `value` and the target (``'-'`` for ratios and fractions).
    target : tuple of (float or None)
        Harmon's range (low, high) in `unit`; None for an open end.
    passed : bool or None
        The verdict, computed from `value`; None for rows that are information only.
    method : str
        How it was measured, or why it was not.
    """

    criterion: str
    value: float | None
    unit: str
    target: tuple[float | None, float | None]
    passed: bool | None
    method: str

    def display(self) -> tuple[str, str]:
        """(measured, target) in display units, e.g. ("1.16 mm", "1-2 mm")."""
        from taxel.sensor._harmon_display import display_cells

        return display_cells(self)

    def to_dict(self) -> dict[str, Any]:
        """The row as plain JSON types (SI units)."""
        return {
            "criterion": self.criterion,
            "value": self.value,
            "unit": self.unit,
            "target": list(self.target),
            "passed": self.passed,
            "method": self.method,
        }


@dataclass(frozen=True)
class HarmonTable:
    """Harmon's criteria measured on one sensor (see `harmon_table`).

    Attributes
    ----------
    sensor_name : str
        The sensor.
    density_class : str
        LDTA, MDTA, HDTA or VHDTA (Ellis seed, section 1).
    rows : tuple of HarmonRow
        Harmon's eight criteria, then the qualities added later (reliability, levels).
    resolution : TwoPointResolution or None
        The two-point measurement behind the first row.
    calibration : Calibration or None
        The calibration used (static sensors).
    """

    sensor_name: str
    density_class: str
    rows: tuple[HarmonRow, ...]
    resolution: TwoPointResolution | None = field(default=None, repr=False)
    calibration: Calibration | None = field(default=None, repr=False)

    def row(self, criterion: str) -> HarmonRow:
        """The row called `criterion`."""
        for row in self.rows:
            if row.criterion == criterion:
                return row
        names = ", ".join(row.criterion for row in self.rows)
        raise ValueError(f"`criterion` must be one of {names}; got {criterion!r}")

    @property
    def n_passed(self) -> int:
        """Rows that pass."""
        return sum(row.passed is True for row in self.rows)

    @property
    def n_failed(self) -> int:
        """Rows that fail."""
        return sum(row.passed is False for row in self.rows)

    def to_dict(self) -> dict[str, Any]:
        """The table as plain JSON types (SI units)."""
        return {
            "sensor": self.sensor_name,
            "density_class": self.density_class,
            "rows": [row.to_dict() for row in self.rows],
            "passed": self.n_passed,
            "failed": self.n_failed,
        }


def _verdict(value: float | None, low: float | None, high: float | None) -> bool | None:
    if value is None:
        return None
    return (low is None or value >= low) and (high is None or value <= high)


def harmon_table(
    sensor: TactileSensor, *, rng: Any = 0, calibration: Calibration | None = None
) -> HarmonTable:
    """Measure a sensor against Harmon's criteria.

    Parameters
    ----------
    sensor : TactileSensor
        The sensor.
    rng : numpy.random.Generator or int or None, default 0
        The sensor's noise, reproducibly; None measures the noise-free sensor (then one
        ADC step is the smallest change a reading shows).
    calibration : Calibration, optional
        A calibration of this sensor; made with `calibrate` (8 noisy repeats of 21 plate
        pressures) when not given and the sensor can be calibrated.

    Returns
    -------
    HarmonTable

    Notes
    -----
    - *Spatial resolution*: `two_point_resolution` in the calibrated frame, with noise
      (two peaks whose valley is at least 20 % below the lower one).
    - *Sensitivity*: the smallest force, spread over one element's cell, that moves the
      mean reading of some channel by more than one step, the larger of one ADC level and
      the rms noise at rest (`reading_step`). *Dynamic range*: the element's full-scale
      force (full-scale pressure times its cell) over that force.
    - *Hysteresis*: a flat plate loaded to full scale and unloaded (`read_sequence`); the
      widest gap between the loading and unloading readings of a taxel, over its span.
      *Stability*: the change of the reading over a 1 s full-scale hold (creep, drift).
      Both pass when below one reliable level (step / span).
    - *Monotonic*: a 101-step flat-plate sweep of the noise-free mean reading.
    - *Compliant interface*: the pad's Young's modulus, at most 5 MPa (an elastomer; a
      fingertip is about 0.1 MPa). Ruggedness and cost cannot be simulated.
    - Added after Harmon: reliability (the share of taxels the calibration keeps) and
      speed (the sampling rate) are measured; modularity and multisensor support are not
      properties of one simulated array. The density class and the distinct reliable
      levels (the Ellis seed's "resolution" of a taxel) are reported for information.

    Examples
    --------
    >>> from taxel.sensor import make_sensor
    >>> table = harmon_table(make_sensor("capacitive4x4"))
    >>> row = table.row("array size")
    >>> row.value, row.passed
    (16.0, False)
    >>> table.row("sampling rate").passed
    True
    """
    if not isinstance(sensor, TactileSensor):
        raise TypeError(f"`sensor` must be a TactileSensor, got {sensor!r}")
    generator = as_rng("rng", rng)
    calibratable = not sensor.is_dynamic and sensor.quantity != "stress_difference"
    if calibration is None and calibratable:
        calibration = calibrate(sensor, rng=generator)
    elif calibration is not None:
        check_calibration(calibration, sensor)
    rows: list[HarmonRow] = []

    # 1. spatial resolution, measured with two point loads
    resolution = None
    if sensor.quantity == "stress_difference":
        rows.append(
            HarmonRow("spatial resolution", None, "m", _RESOLUTION, None,
                      "not measurable as two peaks: a photoelastic frame shows fringes")
        )  # fmt: skip
    else:
        resolution = two_point_resolution(sensor, calibration=calibration, rng=generator)
        frame = "calibrated frame" if calibration is not None else "change of raw frame"
        rows.append(
            HarmonRow("spatial resolution", resolution.resolution, "m", _RESOLUTION,
                      _verdict(resolution.resolution, None, _RESOLUTION[1])
                      if resolution.resolution is not None else False,
                      f"two point loads of {resolution.point_force:.3g} N each, two peaks "
                      f"with a valley >= {resolution.dip:.0%} below the lower in the {frame}, "
                      "with noise")
        )  # fmt: skip

    # 2. array size
    rows_count, cols_count = sensor.shape
    count = float(rows_count * cols_count)
    rows.append(
        HarmonRow("array size", count, "-", (float(_ARRAY_POINTS[0]), float(_ARRAY_POINTS[1])),
                  count >= _ARRAY_POINTS[0] and min(sensor.shape) >= 5,
                  f"{rows_count} x {cols_count} taxels; larger arrays meet the need too")
    )  # fmt: skip

    # 3-4. sensitivity and dynamic range
    step = reading_step(sensor, rng=generator)
    element_area = sensor.taxel_pitch[0] * sensor.taxel_pitch[1]
    full_force = sensor.full_scale * element_area
    single = sensitivity_force(sensor, step.step, spread="element")
    uniform = sensitivity_force(sensor, step.step, spread="uniform")
    uniform_text = "above full scale" if uniform is None else f"{uniform:.3g} N"
    rows.append(
        HarmonRow("sensitivity", single, "N", _SENSITIVITY,
                  _verdict(single, None, _SENSITIVITY[1]) if single is not None else False,
                  f"force on one element's cell that moves a reading by one step "
                  f"({step.describe()}); under a uniform load: {uniform_text} per element")
    )  # fmt: skip
    dynamic_range = None if single is None else full_force / single
    uniform_text = "-" if uniform is None else f"{full_force / uniform:.0f}:1"
    rows.append(
        HarmonRow("dynamic range", dynamic_range, "-", (_DYNAMIC_RANGE, None),
                  _verdict(dynamic_range, _DYNAMIC_RANGE, None)
                  if dynamic_range is not None else False,
                  f"full-scale force per element {full_force:.3g} N / sensitivity; with the "
                  f"uniform-load sensitivity: {uniform_text}")
    )  # fmt: skip

    # 5. stable, no hysteresis
    levels = step.levels
    tolerance = 1.0 / levels if levels > 0 else None
    if sensor.is_dynamic:
        rows.append(
            HarmonRow("hysteresis", None, "-", (None, tolerance), None,
                      "not measurable: a piezoelectric sensor reads changes, not a held load")
        )  # fmt: skip
    else:
        width = hysteresis_width(sensor, calibration)
        rows.append(
            HarmonRow("hysteresis", width, "-", (None, tolerance),
                      _verdict(width, None, tolerance),
                      "flat plate loaded to full scale and unloaded in 100 frames: widest "
                      "gap between the two branches over the span, worst taxel; target: "
                      "below one reliable level")
        )  # fmt: skip
    change = stability_change(sensor, calibration)
    rows.append(
        HarmonRow("stability", change, "-", (None, tolerance), _verdict(change, None, tolerance),
                  "change of the reading over a 1 s full-scale hold (creep, drift), over "
                  "the span, worst taxel"
                  + ("; a piezoelectric reading fades" if sensor.is_dynamic else ""))
    )  # fmt: skip

    # 6. sampling rate
    rows.append(
        HarmonRow("sampling rate", float(sensor.frame_rate), "Hz", _SAMPLING_RATE,
                  _verdict(float(sensor.frame_rate), _SAMPLING_RATE[0], None),
                  "frames per second of the readout")
    )  # fmt: skip

    # 7. monotonic response
    monotonic = monotonic_fraction(sensor, calibration)
    rows.append(
        HarmonRow("monotonic response", monotonic, "-", (1.0, None),
                  _verdict(monotonic, 1.0, None),
                  "fraction of working taxels whose mean reading moves one way only over "
                  "a 101-step flat-plate sweep to full scale")
    )  # fmt: skip

    # 8. compliant interface
    modulus = float(sensor.cover.material.youngs_modulus)
    rows.append(
        HarmonRow("compliant interface", modulus, "Pa", (None, _COMPLIANT_MODULUS),
                  _verdict(modulus, None, _COMPLIANT_MODULUS),
                  f"Young's modulus of the {sensor.cover.depth * 1e3:g} mm pad; ruggedness "
                  "and cost cannot be simulated")
    )  # fmt: skip

    # qualities added after Harmon: reliability; Ellis's resolution of a taxel
    if calibration is not None:
        working = float(calibration.valid.mean())
        rows.append(
            HarmonRow("working taxels", working, "-", (1.0, None), None,
                      f"{int(calibration.valid.sum())} of {calibration.valid.size} respond "
                      "in the calibration (reliability)")
        )  # fmt: skip
    rows.append(
        HarmonRow("reliable levels", levels, "-", (None, None), None,
                  f"span of the median taxel from no load to full scale over one step "
                  f"({np.log2(max(levels, 1.0)):.1f} bits; the seed's sensors: 5 to 8)")
    )  # fmt: skip
    rows.append(
        HarmonRow("density", sensor.geometry.density * 1e4, "1/m^2", (None, None), None,
                  f"taxels per area: {sensor.density_class}")
    )  # fmt: skip
    return HarmonTable(
        sensor_name=sensor.name,
        density_class=sensor.density_class,
        rows=tuple(rows),
        resolution=resolution,
        calibration=calibration,
    )
