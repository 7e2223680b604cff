"""How an object deforms when pressed: stiffness and a rigid/deformable verdict (seed 2.2).

"Object deformation can be determined by pressing slightly, and then firmly, on an object.
The force information, the change in position along the vector of force application, and
the size and intensity of the tactile images can be integrated to determine roughly how
the object behaves." (Ellis seed, section 2.2.)
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np

from taxel._validation import check_finite, check_instance, check_positive
from taxel.active._deformable_objects import make_deformation_object, top_height
from taxel.active._finger import SimulatedFinger
from taxel.active._imaging import background_level, frame_noise, imaging_sensor
from taxel.active._pad_calibration import PadCalibration, calibrate_pad, core_area
from taxel.active._probe import Probe, ProbeReading
from taxel.active._procedure import ProcedureStep, step_from_reading
from taxel.active._scene import SceneObject
from taxel.features import contact_regions, prepare
from taxel.frames import make_pose, transform_directions
from taxel.sensor import TactileSensor

__all__ = ["Deformation", "DeformationResult", "deflection_exponent", "measure_deformation"]

_HERTZ_EXPONENT = 2.0 / 3.0  # deformation of curved bodies grows as F^(2/3)
_DOWN = np.diag([1.0, -1.0, -1.0])
_STANDOFF = 5e-3


@dataclass(frozen=True)
class DeformationResult:
    """How an object behaved under a touch, a light and a firm press.

    Attributes
    ----------
    deformable : bool
        True when the object yielded more than the sensor's pad between the light and the
        firm press (the object is the softer body in the contact).
    deformability : float
        Object's deformation over the pad's compression between the two presses [-]; > 1
        means deformable.
    stiffness : float
        The object's secant stiffness between the light and the firm press, change of
        force over change of the object's own deformation [N/m]; inf when no deformation
        is measurable.
    total_stiffness : float
        What the finger felt: change of force over change of travel [N/m].
    pad_stiffness : float
        The pad's part: change of force over change of the pad's compression [N/m].
    forces : tuple of float
        Force of each press (touch, light, firm) [N].
    travels : tuple of float
        Finger travel of each press [m].
    pad_compressions : tuple of float
        The pad's compression in each press, from the calibration [m].
    heights : tuple of float
        Height of the object's top above the table in each press [m].
    unloaded_height : float
        The object's height without load [m], extrapolated from the three presses with
        its deformation growing as F^n (`deflection_exponent`).
    deflection_exponent : float
        n of the object's deformation h0 - h = c F^n, fitted to the three heights: 2/3
        for a solid curved body (Hertz), about 1 for a hollow ball's bending wall; 2/3
        when the heights do not tell (a rigid object, or heights within the noise).
    height_change : float
        Height at the light press minus height at the firm press [m].
    areas : tuple of float
        Contact area in each tactile image [m^2].
    area_pixels : tuple of int
        The same in taxels.
    intensities : tuple of float
        Mean image level above the baseline over the contact in each press [image units].
    area_growth : float
        Area at the firm press over area at the light press [-].
    message : str
        The verdict in words.
    steps : tuple of ProcedureStep
        What the finger did and measured.
    """

    deformable: bool
    deformability: float
    stiffness: float
    total_stiffness: float
    pad_stiffness: float
    forces: tuple[float, ...]
    travels: tuple[float, ...]
    pad_compressions: tuple[float, ...]
    heights: tuple[float, ...]
    unloaded_height: float
    deflection_exponent: float
    height_change: float
    areas: tuple[float, ...]
    area_pixels: tuple[int, ...]
    intensities: tuple[float, ...]
    area_growth: float
    message: str
    steps: tuple[ProcedureStep, ...] = field(repr=False)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (infinite stiffness becomes None)."""

        def finite(value: float) -> float | None:
            return float(value) if math.isfinite(value) else None

        return {
            "deformable": self.deformable,
            "deformability": finite(self.deformability),
            "stiffness_n_per_m": finite(self.stiffness),
            "total_stiffness_n_per_m": finite(self.total_stiffness),
            "pad_stiffness_n_per_m": finite(self.pad_stiffness),
            "forces_n": list(self.forces),
            "travels_m": list(self.travels),
            "pad_compressions_m": list(self.pad_compressions),
            "heights_m": list(self.heights),
            "unloaded_height_m": self.unloaded_height,
            "deflection_exponent": self.deflection_exponent,
            "height_change_m": self.height_change,
            "areas_m2": list(self.areas),
            "area_pixels": list(self.area_pixels),
            "intensities": list(self.intensities),
            "area_growth": self.area_growth,
            "message": self.message,
            "steps": [step.to_dict() for step in self.steps],
        }


class Deformation:
    """Press slightly, then firmly, and tell how the object deforms (Ellis seed, 2.2).

    Parameters
    ----------
    calibration : PadCalibration or path
        The sensor pad's compression against contact area (`calibrate_pad`); its forces are
        the presses made: the smallest is the touch, the last two the light and firm press.
    table_height : float, default 0.0
        Height of the table the object rests on, along base z [m].

    Notes
    -----
    Three presses from the same approach pose, retracting in between: a touch (finds the
    surface), a light and a firm press. A touch on a broad face may leave an imprint too
    faint for the sensor to show (a 25 mm flat face at 0.5 N is under 1 kPa); the pad's
    compression is then taken as zero (it is microns at such a pressure) and the touch's
    area as zero. The light and firm presses must show an imprint.

    In each press, the area of the imprint's core (above a quarter of its peak,
    `core_area`) gives the pad's compression from the calibration
    (`PadCalibration.compression`), and the object's top lies that far beyond the pressed
    sensor surface. Between the light and the firm press the finger's travel grows by the
    object's deformation plus the pad's compression, so

        object deformation = change of travel - change of pad compression,

    and the object is deformable when that exceeds the change of pad compression: under the
    same load the object yields more than the sensor. Its stiffness is the change of force
    over its deformation. Contact area and intensity are reported but not used for the
    verdict: for curved elastic bodies Hertz's area grows as F^(2/3) whatever their moduli.
    """

    def __init__(
        self, calibration: PadCalibration | str | os.PathLike[str], *, table_height: float = 0.0
    ) -> None:
        if not isinstance(calibration, PadCalibration):
            if not isinstance(calibration, str | os.PathLike):
                raise TypeError(
                    f"`calibration` must be a PadCalibration or its file, got {calibration!r}"
                )
            calibration = PadCalibration.load(calibration)
        if calibration.forces.size < 3:
            raise ValueError(
                f"`calibration` must hold 3 forces (touch, light, firm), got "
                f"{calibration.forces.tolist()}"
            )
        self.calibration = calibration
        self.table_height = check_finite("table_height", table_height)

    def _press(
        self, probe: Probe, force: float, *, touch: bool, noise: float | None
    ) -> tuple[ProbeReading, float, int, float, float]:
        reading = probe.press(normal_force=force)
        sensor = probe.sensor
        raw = reading.frame.raw
        if sensor.reaches_turn(raw):  # (a photoelastic layer at its first fringe)
            raise ValueError(
                f"the press at {force:g} N takes {sensor.name}'s reading to where it turns "
                f"back ({sensor.reading_turns_at:.4g}): past it the imprint no longer grows "
                "with the load, and its area says nothing of the compression; press lighter"
            )
        # the imprint's outline at a fraction of its contrast over the background itself,
        # whatever the force (see `background_level`), so that the presses' areas compare
        level = background_level(prepare(raw, sensor, noise=noise), sensor)
        prepared = prepare(raw, sensor, noise=noise, baseline=level)
        contact = contact_regions(prepared)
        if not contact.present:
            if touch:  # a broad face at a light touch: too faint to see, too light to matter
                return reading, 0.0, 0, 0.0, 0.0
            raise ValueError(f"the press at {force:g} N shows no contact in the tactile image")
        excess = np.clip(prepared.smooth - prepared.baseline, 0.0, None)
        mask = prepared.mask.astype(bool)
        intensity = float(excess[mask].mean()) if mask.any() else 0.0
        pixels = round(contact.area_m2 / (sensor.taxel_pitch[0] * sensor.taxel_pitch[1]))
        core = core_area(raw, sensor)
        return reading, contact.area_m2, int(pixels), intensity, core

    def run(self, probe: Probe) -> DeformationResult:
        """Touch, press lightly and firmly, and integrate force, travel and images.

        Raises
        ------
        ValueError
            When a press shows no contact or no imprint core, or takes the sensor's reading
            to where it turns back (a photoelastic layer's first fringe), naming the force.
        """
        check_instance("probe", probe, Probe)
        sensor = probe.sensor
        if self.calibration.sensor and sensor.name != self.calibration.sensor:
            raise ValueError(
                f"`calibration` was made on sensor {self.calibration.sensor!r}, the probe "
                f"carries {sensor.name!r}"
            )
        forces = [float(f) for f in self.calibration.forces[-3:]]
        noise = frame_noise(sensor)  # None: the images show their own noise
        steps: list[ProcedureStep] = []
        travels, pads, heights, areas, pixels, intensities = [], [], [], [], [], []
        try:
            for force, action in zip(forces, ("touch", "light press", "firm press"), strict=True):
                touch = action == "touch"
                reading, area, count, intensity, core = self._press(
                    probe, force, touch=touch, noise=noise
                )
                probe.retract()
                if core <= 0 and not touch:
                    raise ValueError(f"the press at {force:g} N shows no imprint core")
                # an imprint too faint to see is a pressure below the sensor's threshold
                # spread over a broad face: the pad's compression is negligible there
                pad = self.calibration.compression(force, core) if core > 0 else 0.0
                # the object's top is the pad's compression beyond the pressed sensor surface
                down = transform_directions(reading.pose, [0.0, 0.0, 1.0])
                height = float(reading.pose[2, 3] - self.table_height - pad * down[2])
                travels.append(reading.travel)
                pads.append(pad)
                heights.append(height)
                areas.append(area)
                pixels.append(count)
                intensities.append(intensity)
                steps.append(
                    step_from_reading(
                        f"{action} {force:g} N",
                        reading,
                        contact_area=area,
                        core_area=core,
                        pad_compression=pad,
                        height=height,
                        intensity=intensity,
                    )
                )
        finally:
            probe.retract()
        steps.append(ProcedureStep("retract", position=probe.pose[:3, 3].copy()))
        return _integrate(forces, travels, pads, heights, areas, pixels, intensities, steps)


def deflection_exponent(forces: Sequence[float], heights: Sequence[float]) -> float:
    """The exponent n of h = h0 - c F^n through three (force, height) presses [N, m].

    2/3 (Hertz) when the heights do not fall with the force, or fall in a ratio no
    exponent in [0.2, 3] gives (heights within their noise).

    Examples
    --------
    >>> forces = (0.5, 12.0, 39.0)
    >>> round(deflection_exponent(forces, [0.05 - 1e-4 * f for f in forces]), 6)  # linear
    1.0
    >>> round(deflection_exponent(forces, [0.05 - 1e-4 * f ** (2 / 3) for f in forces]), 6)
    0.666667
    >>> deflection_exponent(forces, [0.0125, 0.0125, 0.0125])  # a rigid object
    0.6666666666666666
    """
    from scipy.optimize import brentq

    touch, light, firm = forces
    first, second = heights[0] - heights[1], heights[0] - heights[2]
    if not (first > 0 and second > first):
        return _HERTZ_EXPONENT
    ratio = first / second

    def excess(n: float) -> float:
        return (light**n - touch**n) / (firm**n - touch**n) - ratio

    low, high = 0.2, 3.0  # the fraction falls as n grows
    if not excess(high) < 0.0 < excess(low):
        return _HERTZ_EXPONENT
    return float(brentq(excess, low, high, xtol=1e-12))


def _ratio(numerator: float, denominator: float) -> float:
    return numerator / denominator if denominator > 0 else math.inf


def _integrate(
    forces: Sequence[float],
    travels: Sequence[float],
    pads: Sequence[float],
    heights: Sequence[float],
    areas: Sequence[float],
    pixels: Sequence[int],
    intensities: Sequence[float],
    steps: Sequence[ProcedureStep],
) -> DeformationResult:
    touch, light, firm = forces
    change = firm - light
    pad_change = max(pads[2] - pads[1], 0.0)
    travel_change = travels[2] - travels[1]
    deformation = max(travel_change - pad_change, 0.0)
    deformability = _ratio(deformation, pad_change)
    deformable = deformation > pad_change
    # deformation from zero load grows as F^n: extrapolate the touch back to no load
    exponent = deflection_exponent(forces, heights)
    sink = max(heights[0] - heights[1], 0.0)
    scale = sink / (light**exponent - touch**exponent)
    unloaded = heights[0] + scale * touch**exponent
    verdict = "deformable" if deformable else "rigid"
    message = (
        f"{verdict}: between {light:g} and {firm:g} N the object gave "
        f"{deformation * 1e3:.3f} mm and the pad {pad_change * 1e3:.3f} mm"
    )
    return DeformationResult(
        deformable=bool(deformable),
        deformability=float(deformability),
        stiffness=_ratio(change, deformation),
        total_stiffness=_ratio(change, travel_change),
        pad_stiffness=_ratio(change, pad_change),
        forces=tuple(forces),
        travels=tuple(travels),
        pad_compressions=tuple(pads),
        heights=tuple(heights),
        unloaded_height=float(unloaded),
        deflection_exponent=float(exponent),
        height_change=float(heights[1] - heights[2]),
        areas=tuple(areas),
        area_pixels=tuple(pixels),
        intensities=tuple(intensities),
        area_growth=_ratio(areas[2], areas[1]),
        message=message,
        steps=tuple(steps),
    )


@lru_cache(maxsize=4)
def _default_calibration(sensor_name: str, forces: tuple[float, ...]) -> PadCalibration:
    return calibrate_pad(sensor_name, forces=forces)


def measure_deformation(
    item: str | SceneObject = "racquet ball",
    *,
    sensor: str | TactileSensor = "vhdta128",
    forces: Sequence[float] = (12.0, 39.0),
    touch_force: float = 0.5,
    calibration: PadCalibration | str | os.PathLike[str] | None = None,
    rng: Any = None,
    shape: str | None = None,
    size: float | None = None,
    youngs_modulus: float | None = None,
    poisson_ratio: float | None = None,
    thickness: float | None = None,
    gauge_pressure: float = 0.0,
) -> DeformationResult:
    """Simulate the touch, light and firm press on an object and judge its deformation.

    Parameters
    ----------
    item : str or SceneObject, default "racquet ball"
        A name of `DEFORMATION_OBJECTS` or an object on the table under the base origin
        (see `make_deformation_object` for balls and blocks of any size and modulus).
    sensor : str or TactileSensor, default "vhdta128"
        The sensor on the finger.
    forces : (float, float), default (12, 39)
        The light and firm press [N] (the seed's).
    touch_force : float, default 0.5
        The touch that finds the surface [N].
    calibration : PadCalibration or path, optional
        The pad calibration at (touch, light, firm); None calibrates in simulation
        (`calibrate_pad`, a few seconds, then kept for the session).
    rng : numpy.random.Generator or int, optional
        Sensor noise (None: noise-free frames).
    shape, size, youngs_modulus, poisson_ratio, thickness, gauge_pressure : optional
        With a name, build the object from these (see `make_deformation_object`): any
        solid or hollow ball or cube, named or not.

    Returns
    -------
    DeformationResult

    Examples
    --------
    >>> result = measure_deformation("racquet ball", rng=1)
    >>> result.deformable, round(result.heights[1] * 1e3)
    (True, 53)
    """
    chosen = imaging_sensor(sensor)
    if isinstance(forces, str) or np.ndim(forces) != 1 or len(forces) != 2:
        raise ValueError(f"`forces` must be a (light, firm) pair of forces [N], got {forces!r}")
    light, firm = (check_positive("forces", force) for force in forces)
    touch = check_positive("touch_force", touch_force)
    if not touch < light < firm:
        raise ValueError(
            f"`forces` must be a light and a firm force above `touch_force` {touch:g} N, "
            f"got {list(forces)}"
        )
    if calibration is None:
        calibration = (
            _default_calibration(sensor, (touch, light, firm))
            if isinstance(sensor, str)
            else calibrate_pad(chosen, forces=(touch, light, firm))
        )
    procedure = Deformation(calibration)
    if not np.allclose(procedure.calibration.forces[-3:], [touch, light, firm], rtol=1e-3):
        raise ValueError(
            f"`calibration` holds forces {procedure.calibration.forces.tolist()} N, not "
            f"the touch and presses {[touch, light, firm]} N"
        )
    if isinstance(item, str):
        target: SceneObject = make_deformation_object(
            item,
            shape=shape,
            size=size,
            youngs_modulus=youngs_modulus,
            poisson_ratio=poisson_ratio,
            thickness=thickness,
            gauge_pressure=gauge_pressure,
        )
    else:
        target = item
    above = make_pose(_DOWN, [0.0, 0.0, top_height(target) + _STANDOFF])
    finger = SimulatedFinger(chosen, [target], above, rng=rng)
    return procedure.run(finger)
