"""Rigid transforms as 4x4 homogeneous matrices: build, check, invert, compose, apply.

A pose ``T_AB`` maps points given in frame ``B`` to frame ``A``: ``p_A = T_AB @ [p_B, 1]``.
Composition follows the subscripts: ``T_AC = T_AB @ T_BC``. Directions (unit vectors,
normals, axes) are rotated but not translated.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel._validation import as_finite_array

__all__ = [
    "as_pose",
    "compose_poses",
    "invert_pose",
    "make_pose",
    "sensor_pose",
    "transform_directions",
    "transform_points",
]

# a rotation block is accepted when R^T R is within this of the identity: loose enough for
# poses typed into a JSON file with 4-6 decimals, tight enough to reject a scaled matrix
_ORTHONORMAL_TOLERANCE = 1e-4
_IDENTITY = np.eye(3)
_LAST_ROW = np.array([0.0, 0.0, 0.0, 1.0])
_LAST_ROW_TOLERANCE = 1e-9 + 1e-5 * _LAST_ROW  # np.allclose's atol + rtol |b|


def _determinant(m: list[list[float]]) -> float:
    """Determinant of a 3x3 matrix (cofactors along the first row; cheaper than LAPACK)."""
    return (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )


def as_pose(value: Any, *, name: str = "pose") -> np.ndarray:
    """Check a 4x4 homogeneous rigid transform and return it as a float64 array.

    Parameters
    ----------
    value : array_like, shape (4, 4)
        Rotation block R (3x3, orthonormal, det +1), translation t [m] in the last column,
        last row ``[0, 0, 0, 1]``.
    name : str, default 'pose'
        The parameter name used in error messages.

    Returns
    -------
    numpy.ndarray, shape (4, 4)

    Raises
    ------
    ValueError
        When the shape, the last row or the rotation block is wrong; the message names
        `name` and the problem.

    Examples
    --------
    >>> as_pose(np.eye(4)).shape
    (4, 4)
    >>> as_pose(2 * np.eye(4))
    Traceback (most recent call last):
    ...
    ValueError: `pose` must have last row [0, 0, 0, 1], got [0.0, 0.0, 0.0, 2.0]
    """
    _refuse_bool(name, value)  # (a mask is an array of booleans; no pose holds one)
    pose = as_finite_array(name, value, ndim=2)
    if pose.shape != (4, 4):
        raise ValueError(f"`{name}` must have shape (4, 4), got {pose.shape}")
    # np.allclose(pose[3], [0, 0, 0, 1], atol=1e-9), without its overhead
    if not (np.abs(pose[3] - _LAST_ROW) <= _LAST_ROW_TOLERANCE).all():
        raise ValueError(f"`{name}` must have last row [0, 0, 0, 1], got {pose[3].tolist()}")
    rotation = pose[:3, :3]
    error = float(np.maximum.reduce(np.abs(rotation.T @ rotation - _IDENTITY), axis=None))
    if error > _ORTHONORMAL_TOLERANCE or _determinant(rotation.tolist()) < 0:
        raise ValueError(
            f"`{name}` must have a proper rotation block (orthonormal, det +1), "
            f"got max |R^T R - I| = {error:.3g} and det = {np.linalg.det(rotation):.3g}"
        )
    return pose


def _holds_bool(value: Any) -> bool:
    """Whether `value` holds a boolean: is one, or an array or list that holds one."""
    if isinstance(value, list | tuple):
        return any(map(_holds_bool, value))
    dtype = getattr(value, "dtype", None)
    if dtype == np.object_:
        return any(map(_holds_bool, np.asarray(value).ravel().tolist()))
    return isinstance(value, bool | np.bool_) or dtype == np.bool_


def _refuse_bool(name: str, value: Any) -> None:
    """Raise TypeError naming `name` when `value` holds a boolean (see `_holds_bool`)."""
    if _holds_bool(value):
        raise TypeError(f"`{name}` must be numeric, got a boolean in it")


def _is_rotation(value: Any) -> bool:
    """Whether `value` is a scipy Rotation, without importing scipy's rotations for arrays.

    (They take about 0.5 s to import: every import of taxel, each command-line run
    included, would pay it.)
    """
    if isinstance(value, np.ndarray | list | tuple):
        return False
    from scipy.spatial.transform import Rotation

    return isinstance(value, Rotation)


def make_pose(rotation: Any = None, translation: Any = (0.0, 0.0, 0.0)) -> np.ndarray:
    """Build a 4x4 pose from a rotation and a translation [m].

    Parameters
    ----------
    rotation : scipy.spatial.transform.Rotation or array_like, shape (3, 3), optional
        The rotation; identity when omitted. A matrix must be orthonormal with det +1.
    translation : array_like, shape (3,), default (0, 0, 0)
        Position of the moving frame's origin in the reference frame [m].

    Returns
    -------
    numpy.ndarray, shape (4, 4)

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> T = make_pose(Rotation.from_euler("z", 90, degrees=True), [0.1, 0.0, 0.5])
    >>> transform_points(T, [1.0, 0.0, 0.0]).round(6).tolist()
    [0.1, 1.0, 0.5]
    """
    pose = np.eye(4)
    if rotation is not None:
        if _is_rotation(rotation):
            if not rotation.single:
                raise ValueError("`rotation` must be a single rotation, got a stack")
            pose[:3, :3] = rotation.as_matrix()
        else:
            _refuse_bool("rotation", rotation)
            block = as_finite_array("rotation", rotation, ndim=2)
            if block.shape != (3, 3):
                raise ValueError(f"`rotation` must have shape (3, 3), got {block.shape}")
            pose[:3, :3] = block
    _refuse_bool("translation", translation)  # (True would read as a metre)
    offset = as_finite_array("translation", translation, ndim=1)
    if offset.shape != (3,):
        raise ValueError(f"`translation` must have shape (3,), got {offset.shape}")
    pose[:3, 3] = offset
    return as_pose(pose, name="rotation")


def invert_pose(pose: Any) -> np.ndarray:
    """Inverse of a rigid transform: ``T_BA`` from ``T_AB``, using R^T (no matrix inverse).

    Parameters
    ----------
    pose : array_like, shape (4, 4)

    Returns
    -------
    numpy.ndarray, shape (4, 4)

    Examples
    --------
    >>> T = make_pose(np.diag([1.0, -1.0, -1.0]), [0.0, 0.2, 0.3])
    >>> np.allclose(invert_pose(T) @ T, np.eye(4))
    True
    """
    pose = as_pose(pose)
    inverse = np.eye(4)
    inverse[:3, :3] = pose[:3, :3].T
    inverse[:3, 3] = -pose[:3, :3].T @ pose[:3, 3]
    return inverse


def compose_poses(*poses: Any) -> np.ndarray:
    """Product of poses left to right: ``compose_poses(T_AB, T_BC) = T_AC``.

    Parameters
    ----------
    *poses : array_like, shape (4, 4)
        At least one pose.

    Returns
    -------
    numpy.ndarray, shape (4, 4)

    Examples
    --------
    >>> shift = make_pose(translation=[0.0, 0.0, 0.1])
    >>> compose_poses(shift, shift)[:3, 3].tolist()
    [0.0, 0.0, 0.2]
    """
    if not poses:
        raise ValueError("`poses` must hold at least one pose, got none")
    result = np.eye(4)
    for index, pose in enumerate(poses):
        result = result @ as_pose(pose, name=f"poses[{index}]")
    return result


def sensor_pose(base_to_flange: Any, flange_to_sensor: Any) -> np.ndarray:
    """The chain base -> flange -> sensor: ``T_BS = T_BF @ T_FS``.

    Parameters
    ----------
    base_to_flange : array_like, shape (4, 4)
        ``T_BF``, the flange (tool mounting plate) in the robot's base frame, from the
        robot's forward kinematics.
    flange_to_sensor : array_like, shape (4, 4)
        ``T_FS``, the sensor frame in the flange frame: the fixed mounting of the sensor.

    Returns
    -------
    numpy.ndarray, shape (4, 4)
        ``T_BS``, which maps sensor-frame points to base-frame points.

    Examples
    --------
    >>> flange = make_pose(translation=[0.4, 0.0, 0.3])
    >>> mount = make_pose(translation=[0.0, 0.0, 0.05])
    >>> sensor_pose(flange, mount)[:3, 3].tolist()
    [0.4, 0.0, 0.35]
    """
    return as_pose(base_to_flange, name="base_to_flange") @ as_pose(
        flange_to_sensor, name="flange_to_sensor"
    )


def _apply(pose: Any, vectors: Any, name: str, *, translate: bool) -> np.ndarray:
    pose = as_pose(pose)
    array = as_finite_array(name, vectors)
    if array.ndim == 0 or array.shape[-1] != 3:
        raise ValueError(f"`{name}` must have shape (..., 3), got {array.shape}")
    moved = array @ pose[:3, :3].T
    return moved + pose[:3, 3] if translate else moved


def transform_points(pose: Any, points: Any) -> np.ndarray:
    """Map points [m] from the pose's moving frame to its reference frame.

    Parameters
    ----------
    pose : array_like, shape (4, 4)
        ``T_AB``.
    points : array_like, shape (..., 3)
        Points in frame ``B`` [m].

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        The same points in frame ``A`` [m].

    Examples
    --------
    >>> T = make_pose(translation=[1.0, 2.0, 3.0])
    >>> transform_points(T, [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]).tolist()
    [[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]]
    """
    return _apply(pose, points, "points", translate=True)


def transform_directions(pose: Any, directions: Any) -> np.ndarray:
    """Rotate directions (axes, normals) from the moving frame to the reference frame.

    Parameters
    ----------
    pose : array_like, shape (4, 4)
        ``T_AB``; its translation is ignored.
    directions : array_like, shape (..., 3)
        Vectors in frame ``B``.

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        The same vectors in frame ``A`` (lengths kept).

    Examples
    --------
    >>> T = make_pose(np.diag([1.0, -1.0, -1.0]), [5.0, 5.0, 5.0])
    >>> transform_directions(T, [0.0, 0.0, 1.0]).tolist()
    [0.0, 0.0, -1.0]
    """
    return _apply(pose, directions, "directions", translate=False)
