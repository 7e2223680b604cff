"""How far the sensor's own pad compresses, calibrated on rigid objects of known height.

A finger that presses an object moves by the object's deformation plus the compression of
its own compliant pad. To tell a soft object from a rigid one the two must be separated.
The pad's compression under a contact is set by the force and by the size of the contact
(the pressure under two curved elastic bodies has Hertz's shape whichever of them is the
softer, and a flat face's is set by its size), and the tactile image shows that size. So
the pad is calibrated once, like any sensor: press rigid reference objects of known
height at the forces the procedure uses, read the compression as the finger's travel past
the known surface, and keep it against the size of the imprint's core (`core_area`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy import ndimage

from taxel._validation import as_finite_array, as_rng, check_positive
from taxel.active._deformable_objects import make_block
from taxel.active._finger import SimulatedFinger
from taxel.active._imaging import imaging_sensor
from taxel.active._json_files import parsing, read_json, write_json
from taxel.active._progress import Progress, check_progress
from taxel.active._scene import ProfileObject, make_ball
from taxel.features import prepare
from taxel.frames import make_pose
from taxel.sensor import TactileSensor

__all__ = [
    "REFERENCE_CUBES",
    "REFERENCE_RADII",
    "PadCalibration",
    "calibrate_pad",
    "core_area",
]

_FORMAT = "taxel.pad_calibration"
_CORE_LEVEL = 0.25  # the imprint's core: above this fraction of its peak
_VERSION = 1
# rigid balls from a 4 mm bearing ball to a 128 mm one, and the flat faces of a 20 mm and a
# 28 mm cube: image areas from a point-like imprint to three quarters of the pad
REFERENCE_RADII: tuple[float, ...] = (2e-3, 4e-3, 8e-3, 16e-3, 32e-3, 64e-3)
REFERENCE_CUBES: tuple[float, ...] = (20e-3, 28e-3)
_DOWN = np.diag([1.0, -1.0, -1.0])
_STANDOFF = 5e-3


def _sequence(name: str, values: Any) -> list[Any]:
    """`values` as a list, or raise naming `name` when it is not a sequence of numbers."""
    if isinstance(values, str) or np.ndim(values) != 1:
        raise ValueError(f"`{name}` must be a sequence of numbers, got {values!r}")
    return list(values)


def core_area(image: Any, sensor_or_pitch: Any) -> float:
    """Area of the tactile image above a quarter of its peak over the baseline [m^2].

    The imprint's core: its edge lies where the image falls to a quarter of its peak, so it
    grows less with the pressure that the pad spreads beyond the contact (which widens the
    low-threshold outline of a small contact by a millimetre all round) and it shrugs off
    the noise at the outline's edge. It follows the true contact area. Whatever the core
    encloses counts too: a flat face presses hardest along its rim.

    Examples
    --------
    >>> image = np.full((32, 32), 20.0)
    >>> image[8:16, 8:12] = 100.0  # 32 taxels of contact at 1 mm pitch
    >>> round(core_area(image, 1e-3) * 1e6, 1)
    32.0
    """
    prepared = prepare(image, sensor_or_pitch, smoothing=0.0)
    excess = prepared.image - prepared.baseline
    peak = float(excess.max())
    if peak <= 0:
        return 0.0
    # a flat face presses hardest at its rim: its core is the ring with what it encloses
    core = ndimage.binary_fill_holes(excess > _CORE_LEVEL * peak)
    return float(np.count_nonzero(core) * prepared.taxel_area)


@dataclass(frozen=True, eq=False)
class PadCalibration:
    """The pad's compression against the imprint's core area, at each calibrated force.

    Attributes
    ----------
    forces : numpy.ndarray
        (n_forces,) the calibrated pressing forces [N], increasing.
    areas : numpy.ndarray
        (n_forces, n_references) `core_area` of each reference press's image [m^2].
    compressions : numpy.ndarray
        (n_forces, n_references) the pad's compression in that press [m].
    sensor : str
        The sensor the calibration belongs to.
    """

    forces: np.ndarray
    areas: np.ndarray
    compressions: np.ndarray
    sensor: str = ""

    def __post_init__(self) -> None:
        forces = as_finite_array("forces", self.forces, ndim=1)
        if forces.size < 1 or np.any(forces <= 0) or np.any(np.diff(forces) <= 0):
            raise ValueError(f"`forces` must be positive and increasing, got {forces.tolist()}")
        areas = as_finite_array("areas", self.areas, ndim=2)
        compressions = as_finite_array("compressions", self.compressions, ndim=2)
        if areas.shape != compressions.shape or areas.shape[0] != forces.size:
            raise ValueError(
                f"`areas` and `compressions` must both be (n_forces={forces.size}, "
                f"n_references), got {areas.shape} and {compressions.shape}"
            )
        if areas.shape[1] < 2 or np.any(areas <= 0) or np.any(compressions <= 0):
            raise ValueError("a calibration needs two or more presses with positive values")
        object.__setattr__(self, "forces", forces)
        object.__setattr__(self, "areas", areas)
        object.__setattr__(self, "compressions", compressions)

    def compression(self, normal_force: float, area: float) -> float:
        """The pad's compression [m] for a press of `normal_force` [N] of core `area` [m^2].

        Linear interpolation of ln(compression) in ln(area) among the references pressed
        at the same force (after making it decrease with area, as a larger contact
        spreads the load). Beyond the largest reference the last segment's slope goes on
        (about -2: a thin, nearly incompressible pad under a flat face compresses as
        F h^3 / (G a^4)); below the smallest the compression is held.
        """
        normal_force = check_positive("normal_force", normal_force)
        area = check_positive("area", area)
        index = np.flatnonzero(np.isclose(self.forces, normal_force, rtol=1e-3))
        if index.size == 0:
            raise ValueError(
                f"`normal_force` must be one of the calibrated forces "
                f"{self.forces.tolist()} N, got {normal_force:g}"
            )
        areas, compressions = self.areas[index[0]], self.compressions[index[0]]
        order = np.argsort(areas)
        log_area = np.log(areas[order])
        log_compression = np.minimum.accumulate(np.log(compressions[order]))
        x = math.log(area)
        if x > log_area[-1] and log_area[-1] > log_area[-2]:
            slope = (log_compression[-1] - log_compression[-2]) / (log_area[-1] - log_area[-2])
            return float(math.exp(log_compression[-1] + slope * (x - log_area[-1])))
        return float(np.exp(np.interp(x, log_area, log_compression)))

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (the file layout of `save`)."""
        return {
            "format": _FORMAT,
            "version": _VERSION,
            "sensor": self.sensor,
            "forces_n": self.forces.tolist(),
            "areas_m2": self.areas.tolist(),
            "compressions_m": self.compressions.tolist(),
        }

    def save(self, path: str | os.PathLike[str], *, overwrite: bool = False) -> Path:
        """Write the calibration as JSON (an existing file only with `overwrite`)."""
        return write_json(path, self.to_dict(), overwrite=overwrite)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> PadCalibration:
        """Read a calibration written by `save`."""
        source = Path(path)
        data = read_json(
            source, _FORMAT, ("forces_n", "areas_m2", "compressions_m"), "a pad calibration"
        )
        with parsing(source, "a pad calibration"):
            return cls(
                forces=np.array(data["forces_n"], float),
                areas=np.array(data["areas_m2"], float),
                compressions=np.array(data["compressions_m"], float),
                sensor=str(data.get("sensor", "")),
            )


def _references(radii: Sequence[float]) -> list[ProfileObject]:
    """Rigid reference objects: balls of the given radii and cubes of `REFERENCE_CUBES`."""
    references = [make_ball(f"rigid ball r={radius * 1e3:g} mm", radius) for radius in radii]
    references += [make_block(f"rigid cube {size * 1e3:g} mm", size) for size in REFERENCE_CUBES]
    return references


def _nearest_grid_point(sensor: TactileSensor) -> float:
    """Distance of the load grid's point nearest the sensor's centre from it [m]."""
    (rows, cols), (dy, dx) = sensor.load_grid.shape, sensor.load_grid.spacing
    return math.hypot(dy / 2 if rows % 2 == 0 else 0.0, dx / 2 if cols % 2 == 0 else 0.0)


def calibrate_pad(
    sensor: str | TactileSensor = "vhdta128",
    *,
    forces: Sequence[float] = (0.5, 12.0, 39.0),
    radii: Sequence[float] | None = None,
    rng: Any = 0,
    progress: Progress | None = None,
) -> PadCalibration:
    """Calibrate the pad's compression in simulation on rigid balls and a rigid cube.

    Parameters
    ----------
    sensor : str or TactileSensor, default "vhdta128"
        The sensor (preset name or sensor).
    forces : sequence of float, default (0.5, 12, 39)
        The forces the deformation procedure will press with [N]: at least three distinct
        ones (its touch, light and firm press).
    radii : sequence of float, optional
        Radii of the rigid reference balls [m], at least two distinct ones (the small
        imprints); rigid cubes of 20 and 28 mm are added. By default those of
        `REFERENCE_RADII` that the sensor's load grid sees: a ball is pressed at the
        sensor's centre, and one that does not reach the nearest point of the grid falls
        between its points (capacitive4x4's, 5 mm apart, miss the 2 mm ball).
    rng : numpy.random.Generator or int, optional
        Noise of the frames (default seed 0; None: noise-free).
    progress : callable, optional
        Called as ``progress(done, total)`` after each press, ``total`` being the distinct
        forces times the references (None: not told).

    Returns
    -------
    PadCalibration

    Notes
    -----
    Each reference lies on the table with a known top height; the finger starts 5 mm above
    it, so the pad's compression is the travel minus 5 mm (a rigid object does not deform).
    The imprint is measured by `core_area`, as the procedure measures it.
    """
    forces = sorted({check_positive("forces", force) for force in _sequence("forces", forces)})
    if len(forces) < 3:
        raise ValueError(
            f"`forces` must hold at least 3 distinct forces (touch, light, firm), got {forces}"
        )
    generator = as_rng("rng", rng)
    progress = check_progress(progress)
    chosen = imaging_sensor(sensor)
    nearest = _nearest_grid_point(chosen)
    if radii is None:
        radii = [radius for radius in REFERENCE_RADII if radius > nearest]
    radii = sorted({check_positive("radii", radius) for radius in _sequence("radii", radii)})
    if len(radii) < 2:
        raise ValueError(f"`radii` must hold at least 2 distinct radii, got {radii}")
    if radii[0] <= nearest:
        raise ValueError(
            f"`radii` must be > {nearest * 1e3:.3g} mm for {chosen.name}, got "
            f"{radii[0] * 1e3:g} mm: a smaller ball falls between the load grid's points"
        )
    references = _references(radii)
    areas = np.zeros((len(forces), len(references)))
    compressions = np.zeros_like(areas)
    for j, reference in enumerate(references):
        above = make_pose(_DOWN, [0.0, 0.0, reference.top + _STANDOFF])
        finger = SimulatedFinger(chosen, [reference], above, rng=generator)
        for i, force in enumerate(forces):
            reading = finger.press(normal_force=force)
            finger.retract()
            areas[i, j] = core_area(reading.frame.raw, chosen)
            compressions[i, j] = reading.travel - _STANDOFF
            if progress is not None:
                progress(j * len(forces) + i + 1, areas.size)
    return PadCalibration(
        forces=np.array(forces), areas=areas, compressions=compressions, sensor=chosen.name
    )
