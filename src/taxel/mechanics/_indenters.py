"""Indenters with smooth or edged profiles: spheres, edges, pen tips, punches, washers, rims."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from taxel._validation import check_positive, check_range
from taxel.mechanics._indenter_base import Indenter

__all__ = ["BoxEdge", "CanRim", "Cone", "Cylinder", "FlatPunch", "Sphere", "Washer"]


def _cap(distance: np.ndarray, radius: float) -> np.ndarray:
    """Height of a circular profile of given radius at a distance from its lowest point."""
    inside = np.abs(distance) < radius
    safe = np.where(inside, distance, 0.0)
    return np.where(inside, radius - np.sqrt(radius**2 - safe**2), np.inf)


def _rounded_edge(distance: np.ndarray, radius: float) -> np.ndarray:
    """Height of a flat face ending in a quarter-round fillet: 0 until distance 0, then a cap."""
    beyond = np.clip(distance, 0.0, None)
    return (
        np.where(distance <= 0, 0.0, _cap(beyond, radius))
        if radius > 0
        else (np.where(distance <= 0, 0.0, np.inf))
    )


@dataclass(frozen=True)
class Sphere(Indenter):
    """A sphere of given radius [m] (the exact spherical cap, not a paraboloid).

    Examples
    --------
    >>> round(float(Sphere(10e-3).local_heights(np.array(3e-3), np.array(4e-3))), 9)
    0.001339746
    """

    radius: float

    def __post_init__(self) -> None:
        check_positive("radius", self.radius)

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        return _cap(np.hypot(u, v), self.radius)


@dataclass(frozen=True)
class Cylinder(Indenter):
    """A cylinder or straight rounded edge of given radius [m], its axis along u.

    `length` [m] ends it with flat faces; None (default) means longer than the sensor.
    """

    radius: float
    length: float | None = None

    def __post_init__(self) -> None:
        check_positive("radius", self.radius)
        if self.length is not None:
            check_positive("length", self.length)

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        heights = _cap(v, self.radius)
        if self.length is not None:
            heights = np.where(np.abs(u) <= self.length / 2, heights, np.inf)
        return heights


@dataclass(frozen=True)
class Cone(Indenter):
    """A cone of half-angle `half_angle` [rad] (from its axis) ending in a ball of `tip_radius`.

    A ball-point pen is a small ball (radius ~0.35 mm) held by a steep cone.

    Examples
    --------
    >>> pen = Cone(tip_radius=0.35e-3, half_angle=np.radians(20))
    >>> float(pen.local_heights(np.array(0.0), np.array(0.0)))
    0.0
    """

    tip_radius: float
    half_angle: float

    def __post_init__(self) -> None:
        check_positive("tip_radius", self.tip_radius)
        check_range(
            "half_angle",
            self.half_angle,
            0.0,
            np.pi / 2,
            low_inclusive=False,
            high_inclusive=False,
        )

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        r = np.hypot(u, v)
        rho, alpha = self.tip_radius, self.half_angle
        tangent = rho * np.cos(alpha)  # where the ball meets the cone
        ball = rho - np.sqrt(np.clip(rho**2 - np.minimum(r, tangent) ** 2, 0.0, None))
        cone = rho * (1 - np.sin(alpha)) + (r - tangent) / np.tan(alpha)
        return np.where(r <= tangent, ball, cone)


@dataclass(frozen=True)
class FlatPunch(Indenter):
    """A flat-ended circular punch of `radius` [m]; `edge_radius` [m] rounds its rim."""

    radius: float
    edge_radius: float = 0.0

    def __post_init__(self) -> None:
        check_positive("radius", self.radius)
        check_positive("edge_radius", self.edge_radius, allow_zero=True)

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        return _rounded_edge(np.hypot(u, v) - self.radius, self.edge_radius)


@dataclass(frozen=True)
class Washer(Indenter):
    """A flat washer (an annulus) with rounded rims: radii in metres."""

    outer_radius: float
    inner_radius: float
    edge_radius: float = 0.2e-3

    def __post_init__(self) -> None:
        check_positive("outer_radius", self.outer_radius)
        check_positive("inner_radius", self.inner_radius)
        check_positive("edge_radius", self.edge_radius, allow_zero=True)
        if self.inner_radius + 2 * self.edge_radius >= self.outer_radius:
            raise ValueError(
                f"`inner_radius` + 2 `edge_radius` must be < `outer_radius` "
                f"({self.outer_radius:g} m), got {self.inner_radius + 2 * self.edge_radius:g}"
            )

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        r = np.hypot(u, v)
        flat_inner = self.inner_radius + self.edge_radius
        flat_outer = self.outer_radius - self.edge_radius
        distance = np.maximum(flat_inner - r, r - flat_outer)  # > 0 outside the flat ring
        return _rounded_edge(distance, self.edge_radius)


@dataclass(frozen=True)
class CanRim(Indenter):
    """The rolled rim of a drink can: a torus of `rim_radius` [m] and `lip_radius` [m].

    The indenter's origin is the centre of the rim circle, so a rim pressed on a small
    sensor is placed with its origin off the sensor and shows an arc.
    """

    rim_radius: float = 26e-3
    lip_radius: float = 1.0e-3

    def __post_init__(self) -> None:
        check_positive("rim_radius", self.rim_radius)
        check_positive("lip_radius", self.lip_radius)
        if self.lip_radius >= self.rim_radius:
            raise ValueError(f"`lip_radius` must be < `rim_radius`, got {self.lip_radius:g}")

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        return _cap(np.hypot(u, v) - self.rim_radius, self.lip_radius)


@dataclass(frozen=True)
class BoxEdge(Indenter):
    """The edge of a box along u: two faces meeting at `included_angle` [rad], rounded.

    Pressed symmetrically: each face rises at (pi - included_angle)/2 from the sensor.
    """

    edge_radius: float = 0.5e-3
    included_angle: float = np.pi / 2

    def __post_init__(self) -> None:
        check_positive("edge_radius", self.edge_radius)
        check_range(
            "included_angle",
            self.included_angle,
            0.0,
            np.pi,
            low_inclusive=False,
            high_inclusive=False,
        )

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        slope_angle = (np.pi - self.included_angle) / 2
        rho = self.edge_radius
        tangent = rho * np.sin(slope_angle)
        distance = np.abs(v)
        round_part = rho - np.sqrt(np.clip(rho**2 - np.minimum(distance, tangent) ** 2, 0, None))
        face = rho * (1 - np.cos(slope_angle)) + (distance - tangent) * np.tan(slope_angle)
        return np.where(distance <= tangent, round_part, face)
