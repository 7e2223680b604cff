"""Objects in the robot's workspace, and what a sensor at a given pose sees of them.

Every object lies on a rigid table (the base frame's z = 0 plane, base z pointing up) at a
pose in the base frame. A sensor at pose T_BS looks along its outward normal z_S; for each
cell of its load grid the object's `ray_distances` says how far the object's surface is along
that normal, which is the height map the contact solver needs.

Two kinds of object:
- `ProfileObject`: a flat-bottomed or lying object whose top surface is one of the indenter
  profiles of `taxel.mechanics` (washers, edges, rims, textures, spheres on the table...).
- `Box`: a solid box with rounded edges, for probing faces, edges and corners from any pose.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel._validation import check_instance, check_pair, check_positive
from taxel.frames import as_pose, invert_pose, transform_directions, transform_points
from taxel.mechanics import (
    ElasticMaterial,
    HollowSphere,
    Indenter,
    Sphere,
    effective_modulus,
    hertz_sphere,
)

__all__ = ["Box", "ProfileObject", "SceneObject", "make_ball", "make_hollow_ball"]

_MISS = np.inf


@dataclass(frozen=True, eq=False)
class SceneObject(ABC):
    """An object in the scene.

    Attributes
    ----------
    name : str
        What it is called in reports.
    pose : numpy.ndarray
        4x4 pose of the object's frame in the base frame.
    material : ElasticMaterial or None
        The object's elasticity near the contact; None for a rigid object.
    """

    name: str
    pose: Any = field(default_factory=lambda: np.eye(4))
    material: ElasticMaterial | None = None

    def __post_init__(self) -> None:
        check_instance("name", self.name, str)  # it names the object in every message
        object.__setattr__(self, "pose", as_pose(self.pose, name="pose"))
        if self.material is not None:
            check_instance("material", self.material, ElasticMaterial)

    @abstractmethod
    def local_distances(self, origins: np.ndarray, direction: np.ndarray) -> np.ndarray:
        """Distance along `direction` from each origin to the surface, in the object frame."""

    def ray_distances(self, origins: Any, direction: Any) -> np.ndarray:
        """Distance [m] from base-frame points along a base-frame unit direction to the object.

        +inf where the ray misses; negative where the origin is inside the object.
        """
        to_object = invert_pose(self.pose)
        local_origins = transform_points(to_object, np.asarray(origins, float).reshape(-1, 3))
        local_direction = transform_directions(to_object, np.asarray(direction, float))
        return self.local_distances(local_origins, local_direction).reshape(np.shape(origins)[:-1])

    def support_travel(self, normal_force: float) -> float:
        """Extra travel [m] of a finger pressing with `normal_force` from the object's support.

        An elastic ball also flattens against the table it lies on; rigid or flat-bottomed
        objects add nothing.
        """
        return 0.0

    def flattening(self, normal_force: float) -> float:
        """How far [m] the object's own structure gives way where the sensor presses it.

        A hollow ball's wall flattens against the sensor (see `make_hollow_ball`); a solid
        object's deformation near the contact is the contact solver's, so it adds nothing.
        """
        return 0.0

    @property
    def gives_way(self) -> bool:
        """Whether `flattening` or `support_travel` grow with the force (else both are 0)."""
        return False

    @property
    def largest_force(self) -> float:
        """The largest force [N] the object's model describes (inf: no limit of its own)."""
        return math.inf

    @property
    def contact_material(self) -> ElasticMaterial | None:
        """The elasticity the contact solver gives the object's surface (None: rigid)."""
        return self.material


@dataclass(frozen=True, eq=False)
class ProfileObject(SceneObject):
    """An object lying on the table, its top surface given by an indenter profile.

    The surface in the object frame is z = top - profile(u, v): `top` [m] is the height of
    the object's highest point above the table, and the profile's heights are measured down
    from it (as `taxel.mechanics` indenters are). The object is meant to be pressed from
    above (the sensor facing down, tilted by a modest angle at most).

    Parameters
    ----------
    name, pose, material
        As `SceneObject`.
    profile : Indenter
        The top surface.
    top : float
        Height of the highest point above the table [m].
    support_radius : float, optional
        For a ball on the table: its radius [m]; the ball then also flattens (Hertz) against
        the rigid table when pressed.
    shell : HollowSphere, optional
        For a hollow ball: its wall and air, which flatten by the same amount against the
        sensor and against the table (`taxel.mechanics.HollowSphere`); the flattened
        surface then meets the sensor's cover as a rigid body.
    """

    profile: Indenter | None = None
    top: float = 0.01
    support_radius: float | None = None
    shell: HollowSphere | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        if not isinstance(self.profile, Indenter):
            raise TypeError(f"`profile` must be an Indenter, got {self.profile!r}")
        check_positive("top", self.top)
        if self.support_radius is not None:
            check_positive("support_radius", self.support_radius)
        if self.shell is not None:
            check_instance("shell", self.shell, HollowSphere)

    def local_distances(self, origins: np.ndarray, direction: np.ndarray) -> np.ndarray:
        if direction[2] >= -1e-6:
            raise ValueError(
                f"`pose` must face the sensor down at {self.name!r}: an object lying on the "
                "table is pressed from above, the sensor's normal pointing down (its z in the "
                f"object's frame: {np.round(direction, 3).tolist()})"
            )
        # fixed-point iteration on the height field; exact in one step for a vertical ray
        profile = self.profile
        assert profile is not None  # checked in __post_init__
        t = (origins[:, 2] - self.top) / -direction[2]
        for _ in range(8):
            point = origins + t[:, None] * direction
            surface = self.top - profile.local_heights(point[:, 0], point[:, 1])
            t_next = (origins[:, 2] - surface) / -direction[2]
            if np.allclose(t_next, t, rtol=0, atol=1e-10, equal_nan=True):
                t = t_next
                break
            t = np.where(np.isfinite(t_next), t_next, t)
        point = origins + t[:, None] * direction
        hit = np.isfinite(profile.local_heights(point[:, 0], point[:, 1]))
        return np.where(hit & np.isfinite(t), t, _MISS)

    def support_travel(self, normal_force: float) -> float:
        if self.shell is not None:
            return self.shell.deflection(normal_force)  # its pole on the table
        if self.support_radius is None or self.material is None:
            return 0.0
        table = hertz_sphere(normal_force, self.support_radius, effective_modulus(self.material))
        return table.indentation  # flattening against the rigid table

    def flattening(self, normal_force: float) -> float:
        return 0.0 if self.shell is None else self.shell.deflection(normal_force)

    @property
    def gives_way(self) -> bool:
        elastic_ball = self.support_radius is not None and self.material is not None
        return self.shell is not None or elastic_ball

    @property
    def largest_force(self) -> float:
        return math.inf if self.shell is None else self.shell.largest_force

    @property
    def contact_material(self) -> ElasticMaterial | None:
        # a hollow ball's give is its shell's (in `flattening`): its surface meets the
        # cover as a rigid body, else the wall's elasticity would count twice
        return None if self.shell is not None else self.material


def make_ball(
    name: str,
    radius: float,
    material: ElasticMaterial | None = None,
    *,
    position: tuple[float, float] = (0.0, 0.0),
) -> ProfileObject:
    """A ball of `radius` [m] lying on the table at (x, y) [m] of the base frame.

    An elastic ball flattens at both contacts: against the sensor (through the contact
    solver, with the ball as the elastic indenter) and against the table (Hertz).

    Examples
    --------
    >>> acrylic = make_ball("acrylic sphere", 6.25e-3, ElasticMaterial(3.2e9, 0.37))
    >>> round(acrylic.top * 1e3, 2)
    12.5
    """
    return _ball_on_table(name, radius, material, position, support_radius=radius)


def _ball_on_table(
    name: str,
    radius: float,
    material: ElasticMaterial | None,
    position: tuple[float, float],
    **support: Any,
) -> ProfileObject:
    """A ball resting on the table at (x, y) [m]: `support` says how it gives way there."""
    pose = np.eye(4)
    pose[:2, 3] = check_pair("position", position)
    return ProfileObject(
        name=name,
        pose=pose,
        material=material,
        profile=Sphere(radius),
        top=2 * radius,
        **support,
    )


def make_hollow_ball(
    name: str,
    radius: float,
    thickness: float,
    material: ElasticMaterial,
    *,
    gauge_pressure: float = 0.0,
    sealed: bool = True,
    position: tuple[float, float] = (0.0, 0.0),
) -> ProfileObject:
    """A hollow ball of `radius` [m] with a wall `thickness` [m] thick, lying on the table.

    Pressed by the sensor with force F, its wall bends and its air is compressed (see
    `taxel.mechanics.HollowSphere`): it flattens by delta(F) at the sensor and again at the
    table, and the sensor meets a flattened disc of radius sqrt(2 R delta - delta^2), not a
    Hertz contact. `material` is the wall's.

    Examples
    --------
    >>> from taxel.mechanics import ElasticMaterial
    >>> ball = make_hollow_ball("racquet ball", 28.5e-3, 4e-3, ElasticMaterial(3.64e6, 0.5))
    >>> round((ball.flattening(12.0) + ball.support_travel(12.0)) * 1e3, 2)  # [mm]
    4.0
    """
    check_instance("material", material, ElasticMaterial)
    shell = HollowSphere(radius, thickness, material, gauge_pressure=gauge_pressure, sealed=sealed)
    return _ball_on_table(name, shell.radius, material, position, shell=shell)


def _rounded_box_distance(points: np.ndarray, half: np.ndarray, radius: float) -> np.ndarray:
    """Signed distance to a box of half-sizes `half` with edges rounded by `radius`."""
    q = np.abs(points) - (half - radius)
    outside = np.linalg.norm(np.maximum(q, 0.0), axis=-1)
    inside = np.minimum(q.max(axis=-1), 0.0)
    return outside + inside - radius


@dataclass(frozen=True, eq=False)
class Box(SceneObject):
    """A solid box with rounded edges, its frame at the centre of its bottom face.

    Parameters
    ----------
    name, pose, material
        As `SceneObject`.
    size : tuple of float
        Edge lengths (x, y, z) [m].
    edge_radius : float, default 0.5e-3
        Radius of the rounded edges and corners [m].

    Examples
    --------
    >>> box = Box("box", size=(0.1, 0.06, 0.04))
    >>> origins = np.array([[0.0, 0.0, 0.05]])
    >>> round(float(box.ray_distances(origins, [0.0, 0.0, -1.0])[0]), 12)  # 1 cm above
    0.01
    """

    size: tuple[float, float, float] = (0.1, 0.1, 0.05)
    edge_radius: float = 0.5e-3

    def __post_init__(self) -> None:
        super().__post_init__()
        if len(self.size) != 3:
            raise ValueError(f"`size` must have three lengths, got {self.size!r}")
        for length in self.size:
            check_positive("size", length)
        check_positive("edge_radius", self.edge_radius, allow_zero=True)
        if 2 * self.edge_radius >= min(self.size):
            raise ValueError(
                f"`edge_radius` must be < half the smallest size, got {self.edge_radius:g}"
            )

    @property
    def corners(self) -> np.ndarray:
        """The eight corners of the sharp box in the base frame [m], shape (8, 3)."""
        hx, hy = self.size[0] / 2, self.size[1] / 2
        local = [
            (sx * hx, sy * hy, z) for sx in (-1, 1) for sy in (-1, 1) for z in (0, self.size[2])
        ]
        return transform_points(self.pose, np.array(local))

    def local_distances(self, origins: np.ndarray, direction: np.ndarray) -> np.ndarray:
        half = np.asarray(self.size) / 2
        centre = np.array([0.0, 0.0, half[2]])
        start = _rounded_box_distance(origins - centre, half, self.edge_radius)
        t = np.zeros(len(origins))
        reach = 10 * float(np.linalg.norm(self.size)) + float(np.abs(start).max())
        active = np.ones(len(origins), dtype=bool)
        for _ in range(400):  # sphere tracing: safe steps of the distance to the surface
            distance = _rounded_box_distance(
                origins + t[:, None] * direction - centre, half, self.edge_radius
            )
            active &= (distance > 1e-10) & (t < reach)
            if not active.any():
                break
            t = np.where(active, t + distance, t)
        distance = _rounded_box_distance(
            origins + t[:, None] * direction - centre, half, self.edge_radius
        )
        result = np.where(np.abs(distance) < 1e-8, t, _MISS)
        return np.where(start < 0, start, result)  # inside: report the penetration
