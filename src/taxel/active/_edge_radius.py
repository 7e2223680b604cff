"""Edge radius by pressing lightly and firmly and looking the cross-sections up in a table.

Ellis seed, section 2.2: "press first with a light force and then with a heavy force on the
edge, and note the differences in the tactile images ... The most sensitive (purely tactile)
measure of deformation is the average cross-section ... a good estimate of the edge radius
for known applied forces can be found empirically."
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np

from taxel._validation import (
    as_rng,
    check_count,
    check_finite,
    check_instance,
    check_pair,
    check_positive,
)
from taxel.active._edge_section import (
    EdgeCrossSection,
    check_section_fits,
    edge_cross_section,
    section_reach,
)
from taxel.active._edge_table import EdgeRadiusTable, fit_edge_radius_table
from taxel.active._finger import SimulatedFinger
from taxel.active._imaging import imaging_sensor
from taxel.active._probe import Probe
from taxel.active._procedure import ProcedureStep, step_from_reading
from taxel.active._progress import Progress, check_progress
from taxel.active._scene import ProfileObject
from taxel.frames import make_pose
from taxel.io import check_new_file
from taxel.mechanics import Cylinder
from taxel.sensor import TactileSensor

__all__ = [
    "DEFAULT_EDGE_RADII",
    "EdgeRadius",
    "EdgeRadiusResult",
    "build_edge_radius_table",
    "largest_edge_offset",
    "make_edge",
    "measure_edge_radius",
    "sharpest_edge_radius",
]

# the E6 preferred numbers from 1 to 10 mm: equal steps in ln(radius) (ratio ~1.47), since
# the cross-section's widths grow about as a power of the radius (sqrt(R) for a Hertzian
# line contact), so each step changes the descriptors by about the same amount
DEFAULT_EDGE_RADII: tuple[float, ...] = (1.0e-3, 1.5e-3, 2.2e-3, 3.3e-3, 4.7e-3, 6.8e-3, 10e-3)
DEFAULT_FORCES = (12.0, 39.0)  # the seed's light and heavy presses [N]
_DOWN = np.diag([1.0, -1.0, -1.0])  # the sensor facing the table
_EDGE_TOP = 0.02  # height of the edge objects' crest above the table [m]
_STANDOFF = 5e-3  # approach height of the sensor above the crest [m]
OFFSET = 4e-3
_RESOLVED = 0.25  # largest relative uncertainty of an estimate reported as "matched"


def make_edge(
    radius: float,
    *,
    position: tuple[float, float] = (0.0, 0.0),
    angle: float = 0.0,
    top: float = _EDGE_TOP,
) -> ProfileObject:
    """A long straight edge of `radius` [m] lying on the table, crest `top` [m] high.

    Parameters
    ----------
    radius : float
        Radius of the rounded edge [m].
    position : tuple of float, default (0, 0)
        A point of the crest line in the base frame (x, y) [m].
    angle : float, default 0
        Direction of the crest line from the base x axis [rad].
    top : float, default 0.02
        Height of the crest above the table [m].

    Examples
    --------
    >>> edge = make_edge(3.2e-3, angle=np.pi / 6)
    >>> edge.name, round(edge.top, 3)
    ('edge r=3.2 mm', 0.02)
    """
    radius = check_positive("radius", radius)
    angle = check_finite("angle", angle)
    pose = np.eye(4)
    pose[:2, :2] = [[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]]
    pose[:2, 3] = check_pair("position", position)
    return ProfileObject(
        name=f"edge r={radius * 1e3:g} mm", pose=pose, profile=Cylinder(radius), top=top
    )


def sharpest_edge_radius(sensor: TactileSensor) -> float:
    """The radius [m] an edge must exceed for the sensor's load grid to see it.

    The edge is a cylinder's crest, 2 radius wide seen from above: a narrower crest than a
    cell of the grid can fall between the cells' centres, and the contact model does not
    see it at all. So: half the grid's largest spacing.

    Examples
    --------
    >>> from taxel.sensor import make_sensor
    >>> round(sharpest_edge_radius(make_sensor("resistive16")) * 1e3, 3)
    1.0
    """
    return max(sensor.load_grid.spacing) / 2


def largest_edge_offset(sensor: TactileSensor) -> float:
    """How far [m] from the sensor's centre an edge's crest may lie to be measured.

    Its cross-section is read 7 mm either side of the crest, clear of the image's border,
    whatever the edge's direction; beyond this distance (from the centre to the crest line,
    along its normal) an edge along the sensor's side leaves too little of it.

    Examples
    --------
    >>> from taxel.sensor import make_sensor
    >>> round(largest_edge_offset(make_sensor("vhdta128")) * 1e3, 2)
    8.73
    """
    return section_reach(sensor.shape, sensor.taxel_pitch)


def _check_resolved(name: str, radius: float, sensor: TactileSensor) -> None:
    """Raise unless an edge of `radius` is sharper than the sensor's load grid sees."""
    sharpest = sharpest_edge_radius(sensor)
    if radius <= sharpest:
        raise ValueError(
            f"`{name}` must be > half the load grid's spacing ({sharpest * 1e3:.3g} mm) "
            f"of {sensor.name}, got {radius * 1e3:.3g} mm: a sharper edge falls between "
            "the grid's points"
        )


def _finger_over(sensor: TactileSensor, edge: ProfileObject, rng: Any) -> SimulatedFinger:
    """A finger facing down over the base origin, above the edge's crest."""
    return SimulatedFinger(
        sensor, [edge], make_pose(_DOWN, [0.0, 0.0, edge.top + _STANDOFF]), rng=rng
    )


@dataclass(frozen=True)
class EdgeRadiusResult:
    """The radius of an edge from a light and a firm press.

    Attributes
    ----------
    radius : float
        Interpolated estimate of the edge radius [m].
    nearest_radius : float
        The table radius nearest the estimate [m].
    radius_uncertainty : float
        Standard uncertainty of the estimate from the table's descriptor spreads [m].
    candidates : tuple of (float, float)
        Every table radius [m] with its distance to the measured cross-sections (mean
        squared standardised difference), nearest first.
    sections : tuple of EdgeCrossSection
        The average cross-section of each press.
    residual : float
        Mean squared standardised difference at the estimate (about 1 when the edge
        matches the table's edges).
    message : str
        How the estimate went, in words.
    steps : tuple of ProcedureStep
        What the finger did and measured.
    """

    radius: float
    nearest_radius: float
    radius_uncertainty: float
    candidates: tuple[tuple[float, float], ...]
    sections: tuple[EdgeCrossSection, ...] = field(repr=False)
    residual: float
    message: str
    steps: tuple[ProcedureStep, ...] = field(repr=False)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary."""
        return {
            "radius_m": self.radius,
            "nearest_radius_m": self.nearest_radius,
            "radius_uncertainty_m": self.radius_uncertainty
            if math.isfinite(self.radius_uncertainty)
            else None,
            "residual": self.residual,
            "message": self.message,
            "candidates": [
                {"radius_m": radius, "distance": distance} for radius, distance in self.candidates
            ],
            "sections": [
                {
                    "normal_force_n": section.normal_force,
                    "force_per_length_n_per_m": section.force_per_length,
                    "chord_m": section.chord_m,
                    "loaded_length_m": section.loaded_length_m,
                    "angle_rad": section.angle_rad,
                    "offset_m": section.offset_m,
                    "descriptors": dict(section.descriptors),
                }
                for section in self.sections
            ],
            "steps": [step.to_dict() for step in self.steps],
        }


class EdgeRadius:
    """Estimate an edge's radius by a light and a firm press (Ellis seed, section 2.2).

    Parameters
    ----------
    table : EdgeRadiusTable or path
        The empirical table (its forces are the presses made).

    Notes
    -----
    The finger presses the edge at each of the table's forces from its approach pose,
    retracting in between; each tactile frame gives an average cross-section
    (`edge_cross_section`: edges, line fit, average normal to the line, widths, arc fit).
    The table predicts every known radius's cross-section at the measured line loads; the
    estimate is interpolated between them (`EdgeRadiusTable.estimate`) and the nearest
    table radius is reported with it. The message says "not resolved" when the
    uncertainty exceeds a quarter of the estimate: on a coarse array (resistive16's 2 mm
    taxels) an edge along the rows reads as its crest's phase on the taxels more than as
    its radius. A bad command or an image without an edge raises a
    `ValueError` after the finger has retracted.
    """

    def __init__(self, table: EdgeRadiusTable | str | os.PathLike[str]) -> None:
        if not isinstance(table, EdgeRadiusTable):
            if not isinstance(table, str | os.PathLike):
                raise TypeError(f"`table` must be an EdgeRadiusTable or its file, got {table!r}")
            table = EdgeRadiusTable.load(table)
        self.table = table

    def measure(self, probe: Probe) -> tuple[list[EdgeCrossSection], list[ProcedureStep]]:
        """Press at each table force and return the cross-sections and the steps."""
        sections: list[EdgeCrossSection] = []
        steps: list[ProcedureStep] = []
        sensor = probe.sensor
        if self.table.sensor and sensor.name != self.table.sensor:
            raise ValueError(
                f"`table` was made on sensor {self.table.sensor!r}, the probe carries "
                f"{sensor.name!r}"
            )
        try:
            for force in self.table.forces:
                reading = probe.press(normal_force=float(force))
                section = edge_cross_section(
                    reading.frame.raw, sensor, normal_force=reading.normal_force
                )
                sections.append(section)
                steps.append(
                    step_from_reading(
                        f"press {force:g} N",
                        reading,
                        force_per_length=section.force_per_length,
                        width=section.descriptors["width_50"],
                        peak=section.descriptors["peak"],
                    )
                )
                probe.retract()
        finally:
            probe.retract()
        steps.append(ProcedureStep("retract", position=probe.pose[:3, 3].copy()))
        return sections, steps

    def run(self, probe: Probe) -> EdgeRadiusResult:
        """Press, measure the cross-sections and look the radius up in the table."""
        check_instance("probe", probe, Probe)
        sections, steps = self.measure(probe)
        radius, uncertainty, residual = self.table.estimate(sections)
        distances = self.table.distances(sections)
        order = np.argsort(distances)
        candidates = tuple((float(self.table.radii[i]), float(distances[i])) for i in order)
        nearest = float(self.table.radii[np.argmin(np.abs(self.table.radii - radius))])
        radii = self.table.radii
        if radius <= radii[0] * (1 + 1e-9) or radius >= radii[-1] * (1 - 1e-9):
            message = "at the end of the table: the edge may lie outside its radii"
        elif residual > 25.0:
            message = f"poor match (residual {residual:.3g}): the edge is unlike the table's"
        elif not uncertainty <= _RESOLVED * radius:
            message = (
                f"not resolved: +-{uncertainty * 1e3:.2g} mm on {radius * 1e3:.2g} mm; the "
                f"{max(probe.sensor.taxel_pitch) * 1e3:.2g} mm taxels of "
                f"{probe.sensor.name} may be too coarse for this edge's cross-section"
            )
        else:
            message = "matched"
        return EdgeRadiusResult(
            radius=radius,
            nearest_radius=nearest,
            radius_uncertainty=uncertainty,
            candidates=candidates,
            sections=tuple(sections),
            residual=residual,
            message=message,
            steps=tuple(steps),
        )


def build_edge_radius_table(
    radii: Sequence[float] | None = None,
    *,
    sensor: str | TactileSensor = "vhdta128",
    forces: Sequence[float] = DEFAULT_FORCES,
    orientations: int = 4,
    rng: Any = 0,
    path: str | os.PathLike[str] | None = None,
    progress: Progress | None = None,
) -> EdgeRadiusTable:
    """Build the edge radius table in simulation by pressing edges of known radius.

    Parameters
    ----------
    radii : sequence of float, optional
        The known radii [m] (at least 2). By default those of `DEFAULT_EDGE_RADII` that
        the sensor's load grid resolves (wider than half its spacing): all seven on
        vhdta128, from 1.5 mm on resistive16 (2 mm cells).
    sensor : str or TactileSensor, default "vhdta128"
        The sensor (a preset name or a sensor).
    forces : sequence of float, default (12, 39)
        The pressing forces [N], increasing.
    orientations : int, default 4
        Edge angles per radius, evenly spaced from 0 to 45 degrees to the sensor's x axis
        (the line load then spans the sensor's side to its diagonal), each at a random
        offset of up to 4 mm from the sensor's centre.
    rng : numpy.random.Generator or int, optional
        Noise of the frames and the offsets (default seed 0; None: noise-free frames).
    path : path, optional
        Where to save the table as JSON.
    progress : callable, optional
        Called as ``progress(done, len(radii) * orientations)`` after each edge pressed
        (None: not told).

    Returns
    -------
    EdgeRadiusTable

    Examples
    --------
    >>> table = build_edge_radius_table([2e-3, 6e-3], orientations=2)
    >>> table.radii.tolist()
    [0.002, 0.006]
    """
    chosen = imaging_sensor(sensor)
    if radii is None:
        sharpest = sharpest_edge_radius(chosen)
        radii = [radius for radius in DEFAULT_EDGE_RADII if radius > sharpest]
    radii = [check_positive("radii", radius) for radius in radii]
    if len(set(radii)) < 2:
        raise ValueError(f"`radii` must hold at least 2 distinct radii, got {radii}")
    forces = [check_positive("forces", force) for force in forces]
    if not forces or len(set(forces)) != len(forces):
        raise ValueError(f"`forces` must hold one or more distinct forces [N], got {forces}")
    orientations = check_count("orientations", orientations, minimum=2)
    if path is not None:  # refused now, not after the presses
        check_new_file(path, name="path")
    generator = as_rng("rng", rng)
    progress = check_progress(progress)
    check_section_fits("sensor", chosen.shape, chosen.taxel_pitch)
    for radius in radii:
        _check_resolved("radii", radius, chosen)
    offsets = np.random.default_rng(rng if rng is not None else 0)
    procedure_forces = sorted(forces)
    pairs, pair_radii = [], []
    for radius in radii:
        for angle in np.linspace(0.0, np.pi / 4, int(orientations)):
            position = tuple(offsets.uniform(-OFFSET, OFFSET, 2))
            edge = make_edge(radius, position=position, angle=float(angle))
            finger = _finger_over(chosen, edge, generator)
            sections = []
            for force in procedure_forces:
                reading = finger.press(normal_force=force)
                sections.append(edge_cross_section(reading.frame.raw, chosen, normal_force=force))
                finger.retract()
            pairs.append(sections)
            pair_radii.append(radius)
            if progress is not None:
                progress(len(pairs), len(radii) * int(orientations))
    table = fit_edge_radius_table(pair_radii, pairs, sensor=chosen.name)
    if path is not None:
        table.save(path)
    return table


@lru_cache(maxsize=4)
def _default_table(sensor_name: str, forces: tuple[float, ...]) -> EdgeRadiusTable:
    return build_edge_radius_table(sensor=sensor_name, forces=forces)


def measure_edge_radius(
    radius: float,
    *,
    table: EdgeRadiusTable | str | os.PathLike[str] | None = None,
    sensor: str | TactileSensor = "vhdta128",
    position: tuple[float, float] = (0.0, 0.0),
    angle: float = 0.0,
    rng: Any = None,
) -> EdgeRadiusResult:
    """Simulate pressing an edge of `radius` and estimate its radius from the table.

    Parameters
    ----------
    radius : float
        The true radius of the simulated edge [m] (the procedure never sees it).
    table : EdgeRadiusTable or path, optional
        The table; None builds the default one for this sensor (`build_edge_radius_table`,
        a few seconds, then kept for the session).
    sensor : str or TactileSensor, default "vhdta128"
        The sensor on the finger (must be the table's).
    position : tuple of float, default (0, 0)
        A point of the edge's crest in the base frame [m]; the sensor's centre is over the
        base origin, so this is the edge's offset from the centre of the sensor.
    angle : float, default 0
        Direction of the edge in the base frame [rad].
    rng : numpy.random.Generator or int, optional
        Sensor noise (None: noise-free frames).

    Returns
    -------
    EdgeRadiusResult
    """
    edge = make_edge(radius, position=position, angle=angle)
    rng = as_rng("rng", rng)
    chosen = imaging_sensor(sensor)
    check_section_fits("sensor", chosen.shape, chosen.taxel_pitch)
    _check_resolved("radius", float(radius), chosen)
    if table is None:
        table = (
            _default_table(sensor, DEFAULT_FORCES)
            if isinstance(sensor, str)
            else build_edge_radius_table(sensor=chosen)
        )
    procedure = EdgeRadius(table)
    return procedure.run(_finger_over(chosen, edge, rng))
