"""Surface normal and planarity of a large object from several contacts (Ellis seed, section 2).

The seed lists, among the features its system extracts, the "three-dimensional position of
the area of contact ... relative to the robot's base reference frame", "a measure of the
planarity of the contact area" and "if the contact is with a plane, the surface normal of
that plane". A sensor much smaller than the object sees one small patch per contact, so the
plane comes from integrating several contacts: press at N poses, turn each contact into a
base-frame point (`estimate_contact_point`: tactile frame + force + cover model), and fit a
plane to the points.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_instance, check_positive
from taxel.active._contact_point import (
    ContactPoint,
    ContactPointCalibration,
    calibrate_contact_points,
    estimate_contact_point,
)
from taxel.active._probe import Probe, ProbeReading
from taxel.active._procedure import ProcedureStep, step_from_reading
from taxel.active._progress import Progress, check_progress
from taxel.frames import as_pose, transform_directions, transform_points
from taxel.sensor import TactileSensor

__all__ = ["PlaneEstimate", "PlaneProbing", "fit_plane", "probe_plane"]

MIN_PROBES = 3


@lru_cache(maxsize=4)
def default_calibration(sensor: TactileSensor) -> ContactPointCalibration:
    """The flat-plate calibration of a sensor, made once per sensor object."""
    return calibrate_contact_points(sensor)


@dataclass(frozen=True)
class PlaneEstimate:
    """A plane fitted to contact points in the base frame.

    Attributes
    ----------
    normal : numpy.ndarray
        (3,) unit outward normal of the plane in the base frame (pointing out of the object,
        towards where the sensor came from).
    point : numpy.ndarray
        (3,) a point of the plane: the mean of the contact points [m].
    residual : float
        Planarity residual: RMS distance of the contact points from the plane [m]; 0 for
        three points, a few micrometres on a flat face, large on a curved object.
    max_deviation : float
        Largest distance of a contact point from the plane [m].
    contact_points : numpy.ndarray
        (N, 3) the base-frame contact points [m].
    contact_normals : numpy.ndarray
        (N, 3) the local outward normals where a contact was wide enough, else NaN rows.
    compressions : numpy.ndarray
        (N,) estimated pad compression at each contact [m].
    steps : tuple of ProcedureStep
        What the finger did.
    message : str
        How the procedure ended.
    """

    normal: np.ndarray
    point: np.ndarray
    residual: float
    max_deviation: float
    contact_points: np.ndarray = field(repr=False)
    contact_normals: np.ndarray = field(repr=False)
    compressions: np.ndarray = field(repr=False)
    steps: tuple[ProcedureStep, ...] = field(repr=False)
    message: str = ""

    @property
    def offset(self) -> float:
        """The offset d of the plane n . p = d [m]."""
        return float(self.normal @ self.point)

    def distance(self, points: Any) -> np.ndarray:
        """Signed distance [m] of base-frame points from the plane, > 0 outside the object."""
        return (np.asarray(points, float) - self.point) @ self.normal

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (SI units, names from docs/nomenclature.md)."""
        return {
            "normal": self.normal.tolist(),
            "point_m": self.point.tolist(),
            "residual_m": self.residual,
            "max_deviation_m": self.max_deviation,
            "contact_points_m": self.contact_points.tolist(),
            "compressions_m": self.compressions.tolist(),
            "steps": [step.to_dict() for step in self.steps],
            "message": self.message,
        }


_IN_PLANE = 1e-3  # |cos| between `outward` and the normal below which it cannot choose


def fit_plane(points: Any, *, outward: Any = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Total-least-squares plane through 3-D points.

    Parameters
    ----------
    points : array_like
        (N >= 3, 3) points [m], not all on one line.
    outward : array_like, optional
        (3,) a direction the normal should agree with (its sign is chosen so); it must
        not lie in the plane.

    Returns
    -------
    normal : numpy.ndarray
        (3,) unit normal.
    centroid : numpy.ndarray
        (3,) mean of the points [m].
    distances : numpy.ndarray
        (N,) signed distances of the points from the plane [m].

    Examples
    --------
    >>> normal, centroid, distances = fit_plane(
    ...     [[0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]], outward=[0, 0, 1])
    >>> normal.tolist(), centroid.tolist(), float(np.abs(distances).max())
    ([0.0, 0.0, 1.0], [0.5, 0.5, 1.0], 0.0)
    """
    points = as_finite_array("points", points, ndim=2)
    if outward is not None:
        outward = as_finite_array("outward", outward, ndim=1)
        if outward.shape != (3,) or not np.any(outward):
            raise ValueError(f"`outward` must be a non-zero 3-vector, got {outward.tolist()}")
    if points.shape[1] != 3 or points.shape[0] < MIN_PROBES:
        raise ValueError(f"`points` must be (N >= 3, 3), got shape {points.shape}")
    centroid = points.mean(axis=0)
    _, singular, vectors = np.linalg.svd(points - centroid)
    if singular[1] <= 1e-9 * max(singular[0], 1e-300):
        raise ValueError("`points` lie on one line; a plane needs points spread in two directions")
    normal = vectors[2]
    if outward is not None:
        agreement = float(normal @ outward) / float(np.linalg.norm(outward))
        if abs(agreement) < _IN_PLANE:
            raise ValueError(
                f"`outward` {outward.tolist()} lies in the fitted plane (normal "
                f"{np.round(normal, 6).tolist()}): it cannot choose the normal's sign"
            )
        if agreement < 0:
            normal = -normal
    normal = normal + 0.0  # no negative zeros in reports
    return normal, centroid, (points - centroid) @ normal


class PlaneProbing:
    """Probe a surface at several poses and fit a plane to the contact points.

    Parameters
    ----------
    normal_force : float, default 5.0
        Force of each press [N].
    calibration : ContactPointCalibration, optional
        The sensor's flat-plate calibration; made with `calibrate_contact_points` on first use when
        omitted.
    model : TactileSensor, optional
        The sensor model whose cover turns frames into contact points; default the probe's
        own sensor. A deliberately wrong one measures the sensitivity to model errors.

    Notes
    -----
    Each press gives one contact point (see `estimate_contact_point`): the pressed pose
    T_BS maps the sensor-frame point (x, y, -compression) to the base frame. The plane is
    the total-least-squares fit (`fit_plane`); its normal is turned to point towards the
    sensors (out of the object). The planarity residual is the RMS point-to-plane distance.
    """

    def __init__(
        self,
        *,
        normal_force: float = 5.0,
        calibration: ContactPointCalibration | None = None,
        model: TactileSensor | None = None,
    ) -> None:
        self.normal_force = check_positive("normal_force", normal_force)
        if calibration is not None and not isinstance(calibration, ContactPointCalibration):
            raise TypeError(
                f"`calibration` must be a ContactPointCalibration, got {calibration!r}"
            )
        if model is not None and not isinstance(model, TactileSensor):
            raise TypeError(f"`model` must be a TactileSensor, got {model!r}")
        self.calibration = calibration
        self.model = model

    def run(
        self, probe: Probe, poses: Sequence[Any], *, progress: Progress | None = None
    ) -> PlaneEstimate:
        """Press at each approach pose in turn and fit the plane.

        Parameters
        ----------
        probe : Probe
            The finger.
        poses : sequence of array_like
            N >= 3 approach poses T_BS (4x4), the sensor facing the surface, not touching;
            their positions must not all lie on one line.
        progress : callable, optional
            Called as ``progress(done, N)`` after each press (None: not told).

        Returns
        -------
        PlaneEstimate

        Raises
        ------
        ValueError
            Too few or collinear poses (before the finger moves); a pose from which the
            finger finds no surface, or a force beyond its limit (the finger is retracted
            and the message names the probe).
        """
        check_instance("probe", probe, Probe)
        poses = check_poses(poses)
        progress = check_progress(progress)
        calibration = self.calibration or default_calibration(probe.sensor)
        points, normals, compressions, steps = [], [], [], []
        outward = np.zeros(3)
        for index, pose in enumerate(poses):
            reading, contact = press_and_locate(
                probe,
                pose,
                self.normal_force,
                calibration,
                label=f"probe {index + 1}",
                model=self.model,
            )
            point = transform_points(reading.pose, contact.point)
            points.append(point)
            compressions.append(contact.compression)
            local = (
                np.full(3, np.nan)
                if contact.normal is None
                else transform_directions(reading.pose, contact.normal)
            )
            normals.append(local)
            outward -= transform_directions(reading.pose, [0.0, 0.0, 1.0])
            steps.append(contact_step(f"probe {index + 1}: press", reading, contact, point))
            if progress is not None:
                progress(index + 1, len(poses))
        normal, centroid, distances = fit_plane(points, outward=outward)
        residual = float(np.sqrt(np.mean(distances**2)))
        return PlaneEstimate(
            normal=normal,
            point=centroid,
            residual=residual,
            max_deviation=float(np.abs(distances).max()),
            contact_points=np.array(points),
            contact_normals=np.array(normals),
            compressions=np.array(compressions),
            steps=tuple(steps),
            message=f"plane fitted to {len(points)} contact points",
        )


def check_poses(poses: Sequence[Any], *, name: str = "poses") -> list[np.ndarray]:
    """Validate approach poses: at least three, positions not on one line."""
    try:
        poses = [as_pose(pose, name=name) for pose in poses]
    except TypeError:
        raise TypeError(f"`{name}` must be a sequence of 4x4 poses, got {poses!r}") from None
    if len(poses) < MIN_PROBES:
        raise ValueError(f"`{name}` must hold at least {MIN_PROBES} poses, got {len(poses)}")
    positions = np.array([pose[:3, 3] for pose in poses])
    singular = np.linalg.svd(positions - positions.mean(axis=0), compute_uv=False)
    if singular[1] < 1e-4 * np.sqrt(len(poses)):  # spread < 0.1 mm across the line
        raise ValueError(
            f"`{name}` positions lie on one line; a plane needs probes spread in two directions"
        )
    return poses


def press_and_locate(
    probe: Probe,
    pose: np.ndarray,
    normal_force: float,
    calibration: ContactPointCalibration,
    *,
    label: str,
    model: TactileSensor | None = None,
) -> tuple[ProbeReading, ContactPoint]:
    """Move, press, read the contact point and retract, whatever goes wrong.

    A `ValueError` (no surface, a force beyond the finger's range, a frame without a
    contact point) comes back naming the probe and its position; any other error of a
    driver (its own limits, a lost connection) passes unchanged, after the retract too.
    """
    try:
        probe.move_to(pose)
        reading = probe.press(normal_force=normal_force)
        contact = estimate_contact_point(
            reading.frame.raw, reading.normal_force, model or probe.sensor, calibration
        )
    except ValueError as error:
        position = ", ".join(f"{v * 1e3:.1f}" for v in pose[:3, 3])
        raise ValueError(f"{label} at ({position}) mm: {error}") from None
    finally:
        probe.retract()
    return reading, contact


def contact_step(
    action: str, reading: ProbeReading, contact: ContactPoint, point: np.ndarray
) -> ProcedureStep:
    """A procedure step recording a located contact."""
    return step_from_reading(
        action,
        reading,
        contact_x=float(point[0]),
        contact_y=float(point[1]),
        contact_z=float(point[2]),
        compression=contact.compression,
        contact_cells=float(contact.n_cells),
    )


def probe_plane(
    probe: Probe,
    poses: Sequence[Any],
    *,
    normal_force: float = 5.0,
    calibration: ContactPointCalibration | None = None,
    progress: Progress | None = None,
) -> PlaneEstimate:
    """Probe a surface at several poses and fit a plane (one call of `PlaneProbing`).

    Parameters
    ----------
    probe : Probe
        The finger.
    poses : sequence of array_like
        N >= 3 approach poses T_BS (4x4) facing the surface.
    normal_force : float, default 5.0
        Force of each press [N].
    calibration : ContactPointCalibration, optional
        The sensor's calibration (made on first use when omitted).
    progress : callable, optional
        Called as ``progress(done, N)`` after each press (None: not told).

    Returns
    -------
    PlaneEstimate

    Examples
    --------
    Four presses on the top of a box tilted by 5 degrees about x:

    >>> from scipy.spatial.transform import Rotation
    >>> from taxel.active import Box, SimulatedFinger
    >>> from taxel.frames import make_pose
    >>> from taxel.sensor import make_sensor
    >>> tilt = Rotation.from_euler("x", 5, degrees=True)
    >>> box = Box("box", size=(0.2, 0.2, 0.05), pose=make_pose(tilt))
    >>> down = np.diag([1.0, -1.0, -1.0])
    >>> poses = [make_pose(down, [x, y, 0.08]) for x, y in
    ...          [(-0.04, -0.04), (0.04, -0.04), (-0.04, 0.04), (0.04, 0.04)]]
    >>> finger = SimulatedFinger(make_sensor("resistive16"), [box], poses[0])
    >>> plane = probe_plane(finger, poses)
    >>> true = tilt.apply([0.0, 0.0, 1.0])
    >>> bool(np.degrees(np.arccos(plane.normal @ true)) < 0.1), plane.residual < 20e-6
    (True, True)
    """
    procedure = PlaneProbing(normal_force=normal_force, calibration=calibration)
    return procedure.run(probe, poses, progress=progress)
