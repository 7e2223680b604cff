"""Simulated probing trials with a known answer: plane probing and corner location.

One call builds a scene (a box at a random pose), a simulated finger with a preset sensor,
runs the procedure and compares its answer with the truth. The command line and the
benchmark use these; the procedures themselves never see the truth.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from taxel._validation import check_count, check_positive, check_range, is_whole
from taxel.active._finger import SimulatedFinger
from taxel.active._imaging import imaging_sensor
from taxel.active._probe_corner import CornerEstimate, CornerProbing, box_corner_frame
from taxel.active._probe_plane import MIN_PROBES, PlaneEstimate, PlaneProbing
from taxel.active._progress import Progress
from taxel.active._scene import Box
from taxel.frames import make_pose, transform_directions, transform_points

__all__ = ["CornerTrial", "PlaneTrial", "corner_probing_trial", "plane_probing_trial"]

_DOWN = np.diag([1.0, -1.0, -1.0])  # sensor z pointing down at the table


def _tilt(rng: np.random.Generator, max_angle: float) -> Rotation:
    """A rotation by an angle uniform in [0, max_angle] about a random horizontal axis."""
    azimuth = rng.uniform(0.0, 2 * np.pi)
    angle = rng.uniform(0.0, max_angle)
    return Rotation.from_rotvec(angle * np.array([np.cos(azimuth), np.sin(azimuth), 0.0]))


@dataclass(frozen=True)
class PlaneTrial:
    """A plane-probing trial and its errors against the truth.

    Attributes
    ----------
    estimate : PlaneEstimate
        What the procedure found.
    true_normal : numpy.ndarray
        (3,) the face's true outward normal.
    normal_error : float
        Angle between the estimated and the true normal [rad].
    offset_error : float
        Distance of the estimated plane's point from the true plane [m].
    point_errors : numpy.ndarray
        (N,) signed distances of the contact points from the true plane [m].
    sensor : str
        The preset used.
    seed : int
        The trial's seed.
    """

    estimate: PlaneEstimate = field(repr=False)
    true_normal: np.ndarray
    normal_error: float
    offset_error: float
    point_errors: np.ndarray = field(repr=False)
    sensor: str
    seed: int

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (SI units; angles in radians and degrees)."""
        return {
            "sensor": self.sensor,
            "seed": self.seed,
            "n_probes": int(len(self.point_errors)),
            "true_normal": self.true_normal.tolist(),
            "normal_error_rad": self.normal_error,
            "normal_error_deg": float(np.degrees(self.normal_error)),
            "offset_error_m": self.offset_error,
            "point_errors_m": self.point_errors.tolist(),
            "estimate": self.estimate.to_dict(),
        }


def plane_probing_trial(
    sensor: str = "resistive16",
    *,
    n_probes: int = 5,
    size: tuple[float, float, float] = (0.2, 0.2, 0.05),
    face_tilt: float = np.radians(15.0),
    pose_tilt: float = np.radians(10.0),
    normal_force: float = 5.0,
    model_error: float = 0.0,
    seed: int = 0,
    progress: Progress | None = None,
) -> PlaneTrial:
    """Probe the top face of a randomly tilted box at random poses and score the plane.

    Parameters
    ----------
    sensor : str, default 'resistive16'
        A static sensor preset (see `taxel.sensor.PRESET_NAMES`).
    n_probes : int, default 5
        Presses (>= 3).
    size : tuple of float, default (0.2, 0.2, 0.05)
        Box edge lengths [m]; the probes land within 80 % of the top face.
    face_tilt : float, default 15 degrees
        Largest tilt of the top face from horizontal [rad] (unknown to the procedure).
    pose_tilt : float, default 10 degrees
        Largest tilt of each approach pose from straight down [rad]; the roll about the
        sensor normal is uniform.
    normal_force : float, default 5.0
        Force of each press [N].
    model_error : float, default 0.0
        Relative error of the cover's Young's modulus in the model the procedure uses to
        turn frames into contact points (0: the true cover; 0.3: 30 % too stiff).
    seed : int, default 0
        Seeds the box pose, the probe poses and the sensor noise.
    progress : callable, optional
        Called as ``progress(done, n_probes)`` after each press (None: not told).

    Returns
    -------
    PlaneTrial

    Examples
    --------
    >>> trial = plane_probing_trial(n_probes=5, seed=1)
    >>> bool(np.degrees(trial.normal_error) < 0.1), bool(trial.offset_error < 50e-6)
    (True, True)
    >>> sorted(trial.to_dict())[:3]
    ['estimate', 'n_probes', 'normal_error_deg']
    """
    probe_sensor = imaging_sensor(sensor)
    if not is_whole(n_probes) or n_probes < MIN_PROBES:
        raise ValueError(f"`n_probes` must be an integer >= {MIN_PROBES}, got {n_probes!r}")
    face_tilt = check_range("face_tilt", face_tilt, 0.0, np.radians(45.0))
    pose_tilt = check_range("pose_tilt", pose_tilt, 0.0, np.radians(30.0))
    model_error = check_range("model_error", model_error, -0.9, 10.0)
    model = None
    if model_error:
        material = probe_sensor.cover.material
        wrong = replace(material, youngs_modulus=material.youngs_modulus * (1 + model_error))
        model = replace(probe_sensor, cover=replace(probe_sensor.cover, material=wrong))
    seed = check_count("seed", seed, minimum=0)
    rng = np.random.default_rng(seed)
    orientation = _tilt(rng, face_tilt) * Rotation.from_euler("z", rng.uniform(0, 2 * np.pi))
    box = Box("box", size=size, pose=make_pose(orientation))
    true_normal = transform_directions(box.pose, [0.0, 0.0, 1.0])
    top_point = transform_points(box.pose, [0.0, 0.0, size[2]])
    poses = []
    for _ in range(int(n_probes)):
        local = [rng.uniform(-0.4, 0.4) * size[0], rng.uniform(-0.4, 0.4) * size[1], size[2]]
        spin = Rotation.from_euler("z", rng.uniform(0.0, 2 * np.pi))
        rotation = (_tilt(rng, pose_tilt) * Rotation.from_matrix(_DOWN) * spin).as_matrix()
        position = transform_points(box.pose, local) + np.array([0.0, 0.0, 0.02])
        poses.append(make_pose(rotation, position))
    finger = SimulatedFinger(probe_sensor, [box], poses[0], rng=seed)
    procedure = PlaneProbing(normal_force=normal_force, model=model)
    estimate = procedure.run(finger, poses, progress=progress)
    cosine = float(np.clip(estimate.normal @ true_normal, -1.0, 1.0))
    point_errors = (estimate.contact_points - top_point) @ true_normal
    return PlaneTrial(
        estimate=estimate,
        true_normal=true_normal,
        normal_error=float(np.arccos(cosine)),
        offset_error=float(abs((estimate.point - top_point) @ true_normal)),
        point_errors=point_errors,
        sensor=sensor,
        seed=int(seed),
    )


@dataclass(frozen=True)
class CornerTrial:
    """A corner-location trial and its errors against the truth.

    Attributes
    ----------
    estimate : CornerEstimate
    true_corner : numpy.ndarray
        (3,) the sharp box corner [m].
    corner_error : float
        Distance from the estimated to the true corner [m].
    edge_errors : numpy.ndarray
        (3,) angles between estimated and true edge directions [rad].
    guess_error : float
        Distance of the guessed corner from the true one [m].
    sensor : str
    seed : int
    """

    estimate: CornerEstimate = field(repr=False)
    true_corner: np.ndarray
    corner_error: float
    edge_errors: np.ndarray
    guess_error: float
    sensor: str
    seed: int

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (SI units; angles in radians)."""
        return {
            "sensor": self.sensor,
            "seed": self.seed,
            "true_corner_m": self.true_corner.tolist(),
            "corner_error_m": self.corner_error,
            "edge_errors_rad": self.edge_errors.tolist(),
            "guess_error_m": self.guess_error,
            "estimate": self.estimate.to_dict(),
        }


def corner_probing_trial(
    sensor: str = "resistive16",
    *,
    size: tuple[float, float, float] = (0.12, 0.1, 0.07),
    corner: int = 7,
    guess_error: float = 3e-3,
    guess_angle: float = np.radians(3.0),
    probes_per_face: int = 3,
    normal_force: float = 5.0,
    seed: int = 0,
    progress: Progress | None = None,
) -> CornerTrial:
    """Locate a corner of a box at a random place and heading from a rough guess.

    Parameters
    ----------
    sensor : str, default 'resistive16'
        A static sensor preset.
    size : tuple of float, default (0.12, 0.1, 0.07)
        Box edge lengths [m]; each face must hold the pad beside the corner.
    corner : int, default 7
        Which corner (order of `Box.corners`; 7 is a top corner).
    guess_error : float, default 3e-3
        Distance of the guessed corner from the true one [m], in a random direction.
    guess_angle : float, default 3 degrees
        Rotation of the guessed corner frame about a random axis [rad].
    probes_per_face : int, default 3
    normal_force : float, default 5.0
    seed : int, default 0
    progress : callable, optional
        Called as ``progress(done, 3 * probes_per_face)`` after each press (None: not told).

    Returns
    -------
    CornerTrial

    Examples
    --------
    >>> trial = corner_probing_trial(seed=2)
    >>> bool(trial.corner_error < 0.2e-3), bool(np.degrees(trial.edge_errors).max() < 0.5)
    (True, True)
    """
    probe_sensor = imaging_sensor(sensor)
    check_positive("guess_error", guess_error, allow_zero=True)
    check_range("guess_angle", guess_angle, 0.0, np.radians(20.0))
    seed = check_count("seed", seed, minimum=0)
    rng = np.random.default_rng(seed)
    heading = Rotation.from_euler("z", rng.uniform(0.0, 2 * np.pi))
    box = Box("box", size=size, pose=make_pose(heading, [*rng.uniform(-0.05, 0.05, 2), 0.0]))
    true = box_corner_frame(box, corner)
    direction = rng.standard_normal(3)
    axis = rng.standard_normal(3)
    twist = Rotation.from_rotvec(guess_angle * axis / np.linalg.norm(axis)).as_matrix()
    guess = make_pose(
        twist @ true[:3, :3],
        true[:3, 3] + guess_error * direction / np.linalg.norm(direction),
    )
    start = make_pose(translation=[0.0, 0.0, float(size[2]) + 0.1])
    finger = SimulatedFinger(probe_sensor, [box], start, rng=seed)
    procedure = CornerProbing(normal_force=normal_force, probes_per_face=probes_per_face)
    estimate = procedure.run(finger, guess, progress=progress)
    cosines = np.clip(np.sum(estimate.edge_directions * true[:3, :3].T, axis=1), -1.0, 1.0)
    return CornerTrial(
        estimate=estimate,
        true_corner=true[:3, 3],
        corner_error=float(np.linalg.norm(estimate.corner - true[:3, 3])),
        edge_errors=np.arccos(cosines),
        guess_error=float(guess_error),
        sensor=sensor,
        seed=int(seed),
    )
