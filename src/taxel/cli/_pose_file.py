"""The ``--pose`` file of ``taxel features``: the sensor's pose in the base frame, as JSON."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from taxel._validation import is_json_number

__all__ = ["POSE_FORMATS", "load_pose"]

_LARGEST_FILE = 100_000  # [bytes]


def load_pose(path: Path) -> np.ndarray:
    """The --pose file's 4x4 pose; any problem with it is a ValueError naming --pose."""
    try:
        return _read_pose(path)
    except RecursionError:
        raise ValueError(f"--pose {path}: nested too deeply to be a pose") from None
    except (ValueError, TypeError, KeyError, OSError, OverflowError) as error:
        message = error.strerror if isinstance(error, OSError) and error.strerror else error
        raise ValueError(f"--pose {path}: {message}") from None


def _shown(value: Any) -> str:
    """A JSON value as an error shows it, cut to 40 characters."""
    text = json.dumps(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _numbers(data: dict[str, Any], key: str, length: int) -> list[float]:
    """``data[key]``, a list of `length` numbers, or a ValueError naming the key."""
    value = data[key]
    if not (isinstance(value, list) and len(value) == length and all(map(is_json_number, value))):
        raise ValueError(f"{key!r} must be a list of {length} numbers, got {_shown(value)}")
    return [float(number) for number in value]  # (finite: see `_finite`)


# the accepted layouts of a --pose file, for its help and its errors
POSE_FORMATS = (
    "a 4x4 list, {'matrix': 4x4}, or {'translation': [x, y, z]} with at most one of "
    "'rotation': 3x3, 'quaternion': [x, y, z, w], 'rotvec': [rx, ry, rz]"
)
_ROTATION_KEYS = ("rotation", "quaternion", "rotvec")


def _rotation_matrix(data: dict[str, Any]) -> list[list[float]]:
    """``data["rotation"]``, a 3x3 list of numbers, or a ValueError naming the key."""
    value = data["rotation"]
    if not (isinstance(value, list) and len(value) == 3 and all(
        isinstance(row, list) and len(row) == 3 and all(map(is_json_number, row)) for row in value
    )):  # fmt: skip
        raise ValueError(f"'rotation' must be a 3x3 list of numbers (rows), got {_shown(value)}")
    return value


def _unit_quaternion(data: dict[str, Any]) -> list[float]:
    """``data["quaternion"]`` scaled to unit length, or a ValueError naming the key.

    Scaled by its largest component first, so that ``math.hypot`` neither overflows nor
    underflows where SciPy's norm would (1e300, 1e-300; four components of 1e308 overflow
    hypot itself).
    """
    quaternion = _numbers(data, "quaternion", 4)
    largest = max(abs(component) for component in quaternion)
    if largest == 0.0:
        raise ValueError("'quaternion' [0, 0, 0, 0] is no rotation: its length must not be 0")
    scaled = [component / largest for component in quaternion]
    norm = math.hypot(*scaled)
    return [component / norm for component in scaled]


def _rotation_vector(data: dict[str, Any]) -> list[float]:
    """``data["rotvec"]`` (axis times angle [rad]), or a ValueError naming the key.

    Refused when a double cannot hold its angle to a microradian (from 2**33, 8.6e9 rad).
    """
    vector = _numbers(data, "rotvec", 3)
    angle = math.hypot(*vector)
    if math.ulp(angle) > 1e-6:
        raise ValueError(
            f"'rotvec' has length {angle:.3g}: its length is the angle in rad, which a "
            "double cannot hold to 1 urad beyond about 8.6e9 rad"
        )
    return vector


def _unique_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """A JSON object as a dict, refusing a key given twice (JSON keeps the last silently)."""
    data: dict[str, Any] = {}
    for key, value in pairs:
        if key in data:
            raise ValueError(f"key {key!r} given twice")
        data[key] = value
    return data


def _finite(text: str) -> float:
    """A JSON number as a double, or a ValueError when it is too large for one (1e400)."""
    value = float(text)
    if not math.isfinite(value):
        shown = text if len(text) <= 20 else text[:17] + "..."
        raise ValueError(f"the number {shown} is too large for a double")
    return value


def _finite_int(text: str) -> int:
    """A JSON integer, kept whole (as errors show it), when a double can hold it."""
    _finite(text)
    return int(text)


def _not_a_number(name: str) -> float:
    """JSON's NaN, Infinity and -Infinity (which Python reads) are no part of a pose."""
    raise ValueError(f"{name} is not a number a pose may hold")


def _read_pose(path: Path) -> np.ndarray:
    """A 4x4 pose from JSON in one of the `POSE_FORMATS`; any other key is refused."""
    from taxel.frames import as_pose, make_pose

    with path.open("rb") as stream:  # a pose is a few hundred bytes; /dev/zero is endless
        content = stream.read(_LARGEST_FILE + 1)
    if len(content) > _LARGEST_FILE:
        raise ValueError(f"more than {_LARGEST_FILE // 1000} kB: not a pose file")
    try:
        text = content.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ValueError("not a text file (cannot decode it as UTF-8)") from None
    try:
        data = json.loads(
            text,
            object_pairs_hook=_unique_keys,
            parse_float=_finite,
            parse_int=_finite_int,
            parse_constant=_not_a_number,
        )
    except json.JSONDecodeError as error:
        raise ValueError(f"not valid JSON ({error.msg})") from None
    if isinstance(data, list):
        return as_pose(data, name="pose")
    if not isinstance(data, dict):
        raise ValueError(f"a pose is {POSE_FORMATS}")
    if "matrix" in data:
        others = sorted(key for key in data if key != "matrix")
        if others:
            raise ValueError(
                f"'matrix' is the whole pose (its last column the translation), "
                f"so {others[0]!r} cannot go beside it"
            )
        return as_pose(data["matrix"], name="pose")
    unknown = sorted(key for key in data if key not in ("translation", *_ROTATION_KEYS))
    if unknown:
        raise ValueError(f"unknown key {unknown[0]!r}: a pose is {POSE_FORMATS}")
    if "translation" not in data:
        raise ValueError(f"no 'translation': a pose is {POSE_FORMATS}")
    given = [key for key in _ROTATION_KEYS if key in data]
    if len(given) > 1:
        raise ValueError(f"give one rotation: {given[0]!r} or {given[1]!r}, not both")
    rotation: Any = None
    if given == ["rotation"]:
        rotation = _rotation_matrix(data)
    elif given:
        from scipy.spatial.transform import Rotation

        if given == ["quaternion"]:
            rotation = Rotation.from_quat(_unit_quaternion(data))  # (x, y, z, w)
        else:
            rotation = Rotation.from_rotvec(_rotation_vector(data))
    return make_pose(rotation, _numbers(data, "translation", 3))
