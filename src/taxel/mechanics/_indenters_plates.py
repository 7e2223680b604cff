"""Indenters with features a tactile sensor should find: corners, slots, holes, height maps."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import ndimage

from taxel._validation import check_positive
from taxel.mechanics._indenter_base import Indenter
from taxel.mechanics._operators import as_spacing

__all__ = ["BoxCorner", "HeightMap", "PlateWithHole", "SlottedPlate"]


@dataclass(frozen=True)
class BoxCorner(Indenter):
    r"""The vertex of a cube pressed along its body diagonal, rounded with `edge_radius` [m].

    Three faces meet at the vertex; each rises at atan(sqrt(2)) = 54.7 degrees from the sensor.
    Three edges leave the vertex, the first along +u.

    Notes
    -----
    With the cube's axes :math:`e_i` (each at 1/sqrt(3) to the normal), the rounded corner is
    the set of points within `edge_radius` of the sharp octant :math:`e_i \cdot P \ge 0`. Its
    lower surface at (u, v) solves :math:`\sum_{active} (a_i + w)^2 = \rho^2`, a quadratic for
    each number of active faces, with :math:`a_i = e_i \cdot (u, v, 0)` and z = sqrt(3) w.

    Examples
    --------
    >>> corner = BoxCorner(edge_radius=0.5e-3)
    >>> float(corner.local_heights(np.array(0.0), np.array(0.0)))
    0.0
    """

    edge_radius: float = 0.5e-3

    def __post_init__(self) -> None:
        check_positive("edge_radius", self.edge_radius, allow_zero=True)

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        # edges of the cube leave the vertex at 0, 120, 240 degrees; faces lie between them,
        # so a face's axis e_i points (horizontally) opposite an edge: 180, 300, 60 degrees
        azimuths = np.radians([180.0, 300.0, 60.0])
        horizontal = np.sqrt(2.0 / 3.0)
        a = np.stack([horizontal * (np.cos(t) * u + np.sin(t) * v) for t in azimuths])
        a = np.sort(a, axis=0)
        rho = self.edge_radius
        w = -a[0] - rho  # one face active (the fallback when none of the others is valid)
        for active in (3, 2, 1):
            s1 = a[:active].sum(axis=0)
            s2 = (a[:active] ** 2).sum(axis=0)
            discriminant = s1**2 - active * (s2 - rho**2)
            root = (-s1 - np.sqrt(np.clip(discriminant, 0, None))) / active
            valid = (discriminant >= 0) & (a[active - 1] + root <= 1e-15)
            if active < 3:
                valid &= a[active] + root >= -1e-15
            w = np.where(valid, root, w)
            if active == 1:
                break
        return np.sqrt(3.0) * w + rho


def _crown(u: np.ndarray, v: np.ndarray, crown_radius: float | None) -> np.ndarray:
    """Height of a gently crowned face (0 when flat)."""
    if crown_radius is None:
        return np.zeros(np.broadcast_shapes(np.shape(u), np.shape(v)))
    return (u**2 + v**2) / (2.0 * crown_radius)


@dataclass(frozen=True)
class SlottedPlate(Indenter):
    """A plate with a straight slot of `slot_width` x `slot_length` [m] along u.

    `crown_radius` [m] makes the face gently convex (None: flat).
    """

    slot_width: float = 3e-3
    slot_length: float = 15e-3
    crown_radius: float | None = None

    def __post_init__(self) -> None:
        check_positive("slot_width", self.slot_width)
        check_positive("slot_length", self.slot_length)
        if self.crown_radius is not None:
            check_positive("crown_radius", self.crown_radius)

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        slot = (np.abs(u) <= self.slot_length / 2) & (np.abs(v) <= self.slot_width / 2)
        return np.where(slot, np.inf, _crown(u, v, self.crown_radius))


@dataclass(frozen=True)
class PlateWithHole(Indenter):
    """A plate with a round hole of `hole_radius` [m]; `crown_radius` [m] as `SlottedPlate`."""

    hole_radius: float = 3e-3
    crown_radius: float | None = None

    def __post_init__(self) -> None:
        check_positive("hole_radius", self.hole_radius)
        if self.crown_radius is not None:
            check_positive("crown_radius", self.crown_radius)

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        hole = np.hypot(u, v) < self.hole_radius
        return np.where(hole, np.inf, _crown(u, v, self.crown_radius))


@dataclass(frozen=True, eq=False)
class HeightMap(Indenter):
    """Any indenter given as a sampled height map (bilinear in between; +inf outside).

    Parameters
    ----------
    values : array_like, shape (rows, cols)
        Heights [m] above the indenter's lowest point, so >= 0 (+inf allowed for "no
        material"; NaN is not), cell centred at the indenter's origin as in
        `grid_coordinates`.
    spacing : float or tuple of float
        Sample spacing, or (dy, dx) [m].

    Examples
    --------
    >>> bowl = HeightMap(np.array([[1.0, 0.0], [0.0, 1.0]]) * 1e-4, 1e-3)
    >>> float(bowl.local_heights(np.array(0.0), np.array(0.0)))
    5e-05
    """

    values: Any
    spacing: Any
    _array: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        array = np.array(self.values, dtype=float)
        if array.ndim != 2:
            raise ValueError(f"`values` must be 2-D, got shape {array.shape}")
        if np.isnan(array).any() or (array == -np.inf).any():
            raise ValueError("`values` must not contain NaN or -inf")
        if array.size and array.min() < 0:
            raise ValueError(
                "`values` must be heights above the indenter's lowest point (>= 0), got a "
                f"minimum of {array.min():g} m: subtract it"
            )
        object.__setattr__(self, "_array", array)
        object.__setattr__(self, "spacing", as_spacing(self.spacing))

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        rows, cols = self._array.shape
        dy, dx = self.spacing
        u, v = np.broadcast_arrays(u, v)
        coordinates = np.stack([v.ravel() / dy + (rows - 1) / 2, u.ravel() / dx + (cols - 1) / 2])
        finite = np.where(np.isfinite(self._array), self._array, 0.0)
        missing = (~np.isfinite(self._array)).astype(float)
        heights = ndimage.map_coordinates(finite, coordinates, order=1, cval=np.nan)
        gaps = ndimage.map_coordinates(missing, coordinates, order=1, cval=1.0)
        result = np.where(np.isnan(heights) | (gaps > 0), np.inf, heights)
        return result.reshape(u.shape)
