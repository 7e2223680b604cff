"""The indenter interface: a height map in the indenter's own frame, placed on the sensor.

Heights are the gap between the undeformed cover surface (the sensor frame's z = 0 plane)
and the indenter's surface, along the sensor's outward normal [m]: 0 at the indenter's
lowest point, +inf where the indenter has no material. An indenter is placed by a position
(x0, y0) on the sensor [m] and an in-plane rotation angle [rad]; the indenter's own axes are
u (along its length or main axis) and v.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_broadcast, check_finite, check_pair
from taxel.mechanics._operators import as_shape, as_spacing

__all__ = ["Indenter", "grid_coordinates"]


def grid_coordinates(shape: Any, spacing: Any) -> tuple[np.ndarray, np.ndarray]:
    """Sensor-frame coordinates (x, y) [m] of the cell centres of a grid.

    Cell (row, col) sits at x = (col - (cols - 1)/2) dx, y = (row - (rows - 1)/2) dy: the
    origin is the centre of the grid (see docs/architecture.md, "Frames").

    Examples
    --------
    >>> x, y = grid_coordinates((2, 3), 1e-3)
    >>> x[0].tolist(), y[:, 0].tolist()
    ([-0.001, 0.0, 0.001], [-0.0005, 0.0005])
    """
    rows, cols = as_shape(shape)
    dy, dx = as_spacing(spacing)
    x = (np.arange(cols) - (cols - 1) / 2) * dx
    y = (np.arange(rows) - (rows - 1) / 2) * dy
    return np.broadcast_to(x[None, :], (rows, cols)), np.broadcast_to(y[:, None], (rows, cols))


class Indenter(ABC):
    """An object that presses on the sensor, described by its height map."""

    @abstractmethod
    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Heights [m] at points (u, v) of the indenter's own frame [m]."""

    def heights(
        self, x: Any, y: Any, *, position: tuple[float, float] = (0.0, 0.0), angle: float = 0.0
    ) -> np.ndarray:
        """Heights [m] at sensor-frame points (x, y) with the indenter placed and rotated.

        Parameters
        ----------
        x, y : array_like
            Sensor-frame coordinates [m].
        position : tuple of float, default (0, 0)
            Where the indenter's origin sits on the sensor, (x0, y0) [m].
        angle : float, default 0
            Rotation of the indenter's u axis from the sensor's x axis [rad].

        Returns
        -------
        numpy.ndarray
            Heights [m], >= 0, +inf where the indenter has no material.
        """
        x = as_finite_array("x", x)
        y = as_finite_array("y", y)
        check_broadcast(("x", "y"), x, y)
        x0, y0 = check_pair("position", position)
        angle = check_finite("angle", angle)
        cosine, sine = np.cos(angle), np.sin(angle)
        u = cosine * (x - x0) + sine * (y - y0)
        v = -sine * (x - x0) + cosine * (y - y0)
        return self.local_heights(u, v)

    def on_grid(
        self,
        shape: Any,
        spacing: Any,
        *,
        position: tuple[float, float] = (0.0, 0.0),
        angle: float = 0.0,
    ) -> np.ndarray:
        """Heights [m] at the cell centres of a sensor grid (see `grid_coordinates`)."""
        x, y = grid_coordinates(shape, spacing)
        return self.heights(x, y, position=position, angle=angle)
