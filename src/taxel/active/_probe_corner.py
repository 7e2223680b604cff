"""Edges and corners of a box located by probing its faces (Ellis seed, section 2).

A corner is where three faces meet and an edge where two do. Pressing the pad on a sharp
edge or corner says little about where exactly the sharp geometry lies (edges are rounded,
and the pad blurs them), but faces are easy: each press on a face gives a precise contact
point (`estimate_contact_point`). So the procedure probes the three faces around an
approximately known corner, fits a plane to each, and intersects them: the edges are the
lines where two planes meet, the corner the point where all three do.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel._validation import check_instance, check_positive, is_whole
from taxel.active._contact_point import ContactPointCalibration
from taxel.active._probe import Probe
from taxel.active._probe_plane import (
    MIN_PROBES,
    PlaneEstimate,
    contact_step,
    default_calibration,
    fit_plane,
    press_and_locate,
)
from taxel.active._procedure import ProcedureStep
from taxel.active._progress import Progress, check_progress
from taxel.active._scene import Box
from taxel.frames import as_pose, make_pose, transform_points

__all__ = ["CornerEstimate", "CornerProbing", "box_corner_frame", "locate_corner"]


def box_corner_frame(box: Box, index: int) -> np.ndarray:
    """The frame of corner `index` of a box, as `CornerProbing` expects its guess.

    Parameters
    ----------
    box : Box
    index : int
        0-7, the order of `Box.corners`.

    Returns
    -------
    numpy.ndarray
        (4, 4) pose T_BC: origin at the sharp corner, axes along the three edges that leave
        it, each pointing along the box (the box fills the positive octant near the corner);
        the axes are ordered to make the frame right-handed.

    Examples
    --------
    >>> box = Box("box", size=(0.1, 0.08, 0.06))
    >>> frame = box_corner_frame(box, 7)  # the top corner at (+x, +y)
    >>> frame[:3, 3].tolist()
    [0.05, 0.04, 0.06]
    >>> frame[:3, :3].astype(int).tolist()  # columns: along -y, along -x, down
    [[0, -1, 0], [-1, 0, 0], [0, 0, -1]]
    """
    if not isinstance(box, Box):
        raise TypeError(f"`box` must be a Box, got {box!r}")
    if not is_whole(index) or not 0 <= index < 8:
        raise ValueError(f"`index` must be an integer in [0, 7], got {index!r}")
    corners = box.corners
    local = transform_points(np.linalg.inv(box.pose), corners[index])
    centre = np.array([0.0, 0.0, box.size[2] / 2])
    axes = -np.diag(np.sign(local - centre))  # towards the box's centre along each axis
    if np.linalg.det(axes) < 0:
        axes[:, [0, 1]] = axes[:, [1, 0]]
    return make_pose(box.pose[:3, :3] @ axes, corners[index])


@dataclass(frozen=True)
class CornerEstimate:
    """A box corner and its three edges, from three probed faces.

    Attributes
    ----------
    corner : numpy.ndarray
        (3,) the corner in the base frame [m].
    edge_directions : numpy.ndarray
        (3, 3) unit directions of the edges leaving the corner (rows), each the
        intersection of two face planes, oriented along the box; edge k is opposite face k.
    faces : tuple of PlaneEstimate
        The three fitted faces (face k is the one the guess's axis k points into).
    residual : float
        Largest planarity residual of the faces [m].
    steps : tuple of ProcedureStep
        What the finger did.
    message : str
        How the procedure ended.
    """

    corner: np.ndarray
    edge_directions: np.ndarray
    faces: tuple[PlaneEstimate, ...] = field(repr=False)
    residual: float
    steps: tuple[ProcedureStep, ...] = field(repr=False)
    message: str = ""

    @property
    def face_normals(self) -> np.ndarray:
        """(3, 3) outward normals of the three faces (rows)."""
        return np.array([face.normal for face in self.faces])

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (SI units)."""
        return {
            "corner_m": self.corner.tolist(),
            "edge_directions": self.edge_directions.tolist(),
            "face_normals": self.face_normals.tolist(),
            "face_residuals_m": [face.residual for face in self.faces],
            "residual_m": self.residual,
            "steps": [step.to_dict() for step in self.steps],
            "message": self.message,
        }


class CornerProbing:
    """Locate a box corner and its edges by probing the three faces around it.

    Parameters
    ----------
    normal_force : float, default 5.0
        Force of each press [N].
    probes_per_face : int, default 3
        Presses on each face (>= 3), on an L of three points then around a circle.
    inset : float, optional
        Distance of the nearest probe centres from the guessed edges [m]; default: half the
        pad's diagonal plus 2 mm, so the pad stays on the face.
    spread : float, default 0.015
        Size of the probe pattern on each face [m].
    standoff : float, default 0.01
        Approach distance in front of the guessed face [m].
    calibration : ContactPointCalibration, optional
        The sensor's calibration (made on first use when omitted).

    Notes
    -----
    The guess is a corner frame T_BC (see `box_corner_frame`) known to a few millimetres
    and degrees, as from vision or a CAD model. For face k (the plane through the corner
    normal to axis k) the sensor faces along +axis k, centred at `inset` (+ the pattern) along
    the two other axes and `standoff` in front of the face. Three plane fits
    n_k . p = d_k give the corner as the solution of the 3x3 system and the edges as
    n_i x n_j.
    """

    def __init__(
        self,
        *,
        normal_force: float = 5.0,
        probes_per_face: int = 3,
        inset: float | None = None,
        spread: float = 0.015,
        standoff: float = 0.01,
        calibration: ContactPointCalibration | None = None,
    ) -> None:
        self.normal_force = check_positive("normal_force", normal_force)
        if not is_whole(probes_per_face) or probes_per_face < MIN_PROBES:
            raise ValueError(
                f"`probes_per_face` must be an integer >= {MIN_PROBES}, got {probes_per_face!r}"
            )
        self.probes_per_face = int(probes_per_face)
        self.inset = None if inset is None else check_positive("inset", inset)
        self.spread = check_positive("spread", spread)
        self.standoff = check_positive("standoff", standoff)
        if calibration is not None:
            check_instance("calibration", calibration, ContactPointCalibration)
        self.calibration = calibration

    def face_poses(self, guess: Any, face: int, pad_half_diagonal: float) -> list[np.ndarray]:
        """Approach poses T_BS for probing face `face` (0, 1, 2) of the guessed corner."""
        guess = as_pose(guess, name="guess")
        axes = guess[:3, :3]
        normal_axis, first, second = face, (face + 1) % 3, (face + 2) % 3
        inset = self.inset if self.inset is not None else pad_half_diagonal + 2e-3
        pattern = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]
        for k in range(self.probes_per_face - 3):
            angle = 2 * np.pi * k / max(self.probes_per_face - 3, 1)
            pattern.append((0.5 + 0.35 * np.cos(angle), 0.5 + 0.35 * np.sin(angle)))
        # sensor z along the face's inward axis, x along `first`: right-handed by construction
        rotation = np.column_stack([axes[:, first], axes[:, second], axes[:, normal_axis]])
        poses = []
        for a, b in pattern:
            local = np.zeros(3)
            local[first] = inset + a * self.spread
            local[second] = inset + b * self.spread
            local[normal_axis] = -self.standoff
            poses.append(make_pose(rotation, transform_points(guess, local)))
        return poses

    def run(self, probe: Probe, guess: Any, *, progress: Progress | None = None) -> CornerEstimate:
        """Probe the three faces around the guessed corner and intersect their planes.

        Parameters
        ----------
        probe : Probe
        guess : array_like
            (4, 4) approximate corner frame T_BC (see `box_corner_frame`).
        progress : callable, optional
            Called as ``progress(done, 3 * probes_per_face)`` after each press (None: not
            told).

        Returns
        -------
        CornerEstimate

        Raises
        ------
        ValueError
            A bad guess; a probe that finds no face within the finger's reach (the finger
            is retracted and the message names the face and probe).
        """
        check_instance("probe", probe, Probe)
        guess = as_pose(guess, name="guess")
        progress = check_progress(progress)
        calibration = self.calibration or default_calibration(probe.sensor)
        extent = probe.sensor.geometry.extent
        half_diagonal = float(np.hypot(*extent)) / 2
        faces, steps = [], []
        for face in range(3):
            points, compressions = [], []
            for index, pose in enumerate(self.face_poses(guess, face, half_diagonal)):
                label = f"face {face + 1} probe {index + 1}"
                reading, contact = press_and_locate(
                    probe, pose, self.normal_force, calibration, label=label
                )
                point = transform_points(reading.pose, contact.point)
                points.append(point)
                compressions.append(contact.compression)
                steps.append(contact_step(f"{label}: press", reading, contact, point))
                if progress is not None:
                    progress(len(steps), 3 * self.probes_per_face)
            normal, centroid, distances = fit_plane(points, outward=-guess[:3, face])
            faces.append(
                PlaneEstimate(
                    normal=normal,
                    point=centroid,
                    residual=float(np.sqrt(np.mean(distances**2))),
                    max_deviation=float(np.abs(distances).max()),
                    contact_points=np.array(points),
                    contact_normals=np.full((len(points), 3), np.nan),
                    compressions=np.array(compressions),
                    steps=tuple(steps[-len(points) :]),
                    message=f"face {face + 1}",
                )
            )
        normals = np.array([face.normal for face in faces])
        offsets = np.array([face.offset for face in faces])
        if abs(np.linalg.det(normals)) < 0.1:
            raise ValueError(
                "the probed faces are nearly parallel; `guess` does not point at a corner"
            )
        corner = np.linalg.solve(normals, offsets)
        edges = []
        for k in range(3):
            direction = np.cross(normals[(k + 1) % 3], normals[(k + 2) % 3])
            direction /= np.linalg.norm(direction)
            if direction @ guess[:3, k] < 0:
                direction = -direction
            edges.append(direction)
        return CornerEstimate(
            corner=corner,
            edge_directions=np.array(edges),
            faces=tuple(faces),
            residual=max(face.residual for face in faces),
            steps=tuple(steps),
            message=f"corner from three planes fitted to {len(steps)} contact points",
        )


def locate_corner(
    probe: Probe,
    guess: Any,
    *,
    normal_force: float = 5.0,
    probes_per_face: int = 3,
    calibration: ContactPointCalibration | None = None,
    progress: Progress | None = None,
) -> CornerEstimate:
    """Locate a box corner and its edges by probing three faces (one call of `CornerProbing`).

    Parameters
    ----------
    probe : Probe
    guess : array_like
        (4, 4) approximate corner frame T_BC (see `box_corner_frame`), good to a few mm.
    normal_force : float, default 5.0
        Force of each press [N].
    probes_per_face : int, default 3
        Presses per face (>= 3).
    calibration : ContactPointCalibration, optional
    progress : callable, optional
        Called as ``progress(done, 3 * probes_per_face)`` after each press (None: not told).

    Returns
    -------
    CornerEstimate

    Examples
    --------
    >>> from taxel.active import Box, SimulatedFinger
    >>> from taxel.frames import make_pose
    >>> from taxel.sensor import make_sensor
    >>> box = Box("box", size=(0.1, 0.08, 0.06))
    >>> true = box_corner_frame(box, 7)
    >>> guess = true.copy()
    >>> guess[:3, 3] += [0.002, -0.003, 0.001]  # known to a few mm
    >>> above = make_pose(translation=[0.0, 0.0, 0.2])
    >>> finger = SimulatedFinger(make_sensor("resistive16"), [box], above)
    >>> found = locate_corner(finger, guess)
    >>> bool(np.linalg.norm(found.corner - true[:3, 3]) < 0.1e-3)
    True
    """
    procedure = CornerProbing(
        normal_force=normal_force, probes_per_face=probes_per_face, calibration=calibration
    )
    return procedure.run(probe, guess, progress=progress)
