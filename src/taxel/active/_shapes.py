"""Top surfaces of everyday objects for the active procedures: polygons, key blanks.

These are `taxel.mechanics.Indenter` profiles (heights measured down from the object's
highest point, +inf where there is no material), used as the tops of `ProfileObject`s:
blocks and bolt heads are rounded regular polygons, a key blank is a bow with a hole and a
notched shank. All are flat-topped with a quarter-round fillet at their rim.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from taxel._validation import check_positive
from taxel.mechanics import Indenter

__all__ = ["KeyBlank", "RoundedPolygon", "fillet_heights"]


def fillet_heights(distance: np.ndarray, edge_radius: float) -> np.ndarray:
    """Height of a flat top ending in a quarter-round fillet, at a distance outside the flat.

    0 on the flat (distance <= 0), r - sqrt(r^2 - d^2) on the fillet, +inf beyond it.

    Examples
    --------
    >>> fillet_heights(np.array([-1.0, 0.0, 0.5, 2.0]), 1.0).tolist()
    [0.0, 0.0, 0.1339745962155614, inf]
    """
    d = np.clip(distance, 0.0, None)
    inside = d < edge_radius
    safe = np.where(inside, d, 0.0)
    return np.where(inside, edge_radius - np.sqrt(edge_radius**2 - safe**2), np.inf)


def _polygon_distance(u: np.ndarray, v: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Euclidean distance from points to a convex polygon (0 inside); vertices CCW."""
    inside = np.ones(np.shape(u), dtype=bool)
    best = np.full(np.shape(u), np.inf)
    for start, end in zip(vertices, np.roll(vertices, -1, axis=0), strict=True):
        edge = end - start
        length2 = float(edge @ edge)
        t = np.clip(((u - start[0]) * edge[0] + (v - start[1]) * edge[1]) / length2, 0.0, 1.0)
        du, dv = u - (start[0] + t * edge[0]), v - (start[1] + t * edge[1])
        best = np.minimum(best, np.hypot(du, dv))
        inside &= edge[0] * (v - start[1]) - edge[1] * (u - start[0]) >= 0
    return np.where(inside, 0.0, best)


@dataclass(frozen=True)
class RoundedPolygon(Indenter):
    """A flat regular polygon (a block's face, a bolt head) with a filleted rim.

    Parameters
    ----------
    across_flats : float
        Distance between opposite flat sides [m] (a square block's edge; a hexagon's
        spanner size).
    sides : int, default 4
        Number of sides (>= 3); one side faces +v.
    edge_radius : float, default 0.5e-3
        Radius of the fillet round the rim [m].

    Examples
    --------
    >>> head = RoundedPolygon(13e-3, sides=6)  # an M8 bolt's head, 13 mm across flats
    >>> across = np.array([0.0, 5.9e-3, 6.3e-3, 6.6e-3])  # from the centre towards a side
    >>> (head.local_heights(np.zeros(4), across) * 1e3).round(3).tolist()
    [0.0, 0.0, 0.1, inf]
    """

    across_flats: float
    sides: int = 4
    edge_radius: float = 0.5e-3

    def __post_init__(self) -> None:
        check_positive("across_flats", self.across_flats)
        check_positive("edge_radius", self.edge_radius)
        if int(self.sides) < 3:
            raise ValueError(f"`sides` must be >= 3, got {self.sides}")
        if 2 * self.edge_radius >= self.across_flats:
            raise ValueError(
                f"`edge_radius` must be < half of `across_flats`, got {self.edge_radius:g}"
            )

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        apothem = self.across_flats / 2 - self.edge_radius
        n = int(self.sides)
        circumradius = apothem / math.cos(math.pi / n)
        # a side faces +v: its normal at 90 degrees, vertices half a side either side of it
        angles = math.pi / 2 + (np.arange(n) + 0.5) * 2 * math.pi / n
        vertices = circumradius * np.column_stack((np.cos(angles), np.sin(angles)))
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        return fillet_heights(_polygon_distance(u, v, vertices), self.edge_radius)


@dataclass(frozen=True)
class KeyBlank(Indenter):
    """A flat key blank lying on the table: a round bow with a hole and a notched shank.

    The bow's centre is at u = -`bow_radius`, the shank runs along +u from the bow to
    u = `shank_length`; one long edge of the shank carries `notches` V-shaped cuts.
    Its origin is thus where the shank meets the bow.

    Parameters
    ----------
    bow_radius : float, default 11e-3
        Radius of the round bow [m].
    hole_radius : float, default 2.5e-3
        Radius of the hole in the bow [m].
    shank_length : float, default 32e-3
        Length of the shank from the bow's edge [m].
    shank_width : float, default 7.5e-3
        Width of the shank [m].
    notches : int, default 5
        Number of cuts along the shank's +v edge.
    notch_depth : float, default 2.5e-3
        Depth of the cuts [m].
    edge_radius : float, default 0.3e-3
        Fillet round every rim [m].

    Examples
    --------
    >>> key = KeyBlank()
    >>> points = np.array([-11e-3, 10e-3, 40e-3])  # the hole, the shank, past the tip
    >>> np.isinf(key.local_heights(points, np.zeros(3))).tolist()
    [True, False, True]
    """

    bow_radius: float = 11e-3
    hole_radius: float = 2.5e-3
    shank_length: float = 32e-3
    shank_width: float = 7.5e-3
    notches: int = 5
    notch_depth: float = 2.5e-3
    edge_radius: float = 0.3e-3

    def __post_init__(self) -> None:
        for name in ("bow_radius", "hole_radius", "shank_length", "shank_width", "edge_radius"):
            check_positive(name, getattr(self, name))
        check_positive("notch_depth", self.notch_depth, allow_zero=True)
        if self.hole_radius + 2 * self.edge_radius >= self.bow_radius:
            raise ValueError(f"`hole_radius` must leave a rim on the bow, got {self.hole_radius}")
        if self.notch_depth >= self.shank_width - 2 * self.edge_radius:
            raise ValueError(f"`notch_depth` must be < the shank's width, got {self.notch_depth}")

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        rho = self.edge_radius
        # signed distance outside each part's flat top (negative inside)
        r = np.hypot(u + self.bow_radius, v)
        bow = np.maximum(r - (self.bow_radius - rho), (self.hole_radius + rho) - r)
        half = self.shank_width / 2 - rho
        along = np.maximum(-u, u - (self.shank_length - rho))
        across = np.abs(v) - half
        # V notches on the +v edge, centred at multiples of the pitch along the shank
        if self.notches and self.notch_depth > 0:
            pitch = self.shank_length / (self.notches + 1)
            fraction = (u / pitch) % 1.0
            to_cut = np.minimum(fraction, 1.0 - fraction)  # in pitches, 0 at a cut's centre
            dip = self.notch_depth * np.clip(1.0 - to_cut / 0.3, 0.0, 1.0)
            dip = np.where((u > pitch / 2) & (u < self.shank_length - pitch / 2), dip, 0.0)
            across = np.where(v > 0, v - (half - dip), across)
        distance = np.minimum(bow, np.maximum(along, across))
        return fillet_heights(distance, rho)
