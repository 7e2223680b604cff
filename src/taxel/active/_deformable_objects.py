"""Balls and blocks of any size and elasticity on the table, to press and judge.

The deformation procedure and its pad calibration press these: a solid ball flattens
against the sensor and against the table it lies on (Hertz), a hollow ball's wall bends
and its air is compressed (`taxel.mechanics.HollowSphere`), a cube stands flat on the
table with its top face rounded by a small fillet.
"""

from __future__ import annotations

from typing import Any

from taxel._validation import check_positive
from taxel.active._scene import ProfileObject, SceneObject, make_ball, make_hollow_ball
from taxel.active._shapes import RoundedPolygon
from taxel.mechanics import ElasticMaterial

__all__ = [
    "DEFORMATION_OBJECTS",
    "SHAPES",
    "WALL_THICKNESS",
    "make_block",
    "make_deformation_object",
    "top_height",
]


def make_block(name: str, size: float, material: Any = None) -> ProfileObject:
    """A cube of edge `size` [m] on the table, its top face rounded by a 1 mm fillet.

    Examples
    --------
    >>> block = make_block("wood block", 20e-3)
    >>> round(block.top * 1e3, 1), block.support_travel(10.0)
    (20.0, 0.0)
    """
    size = check_positive("size", size)
    face = RoundedPolygon(size, sides=4, edge_radius=min(1e-3, size / 4))
    return ProfileObject(name=name, material=material, profile=face, top=size)


# name: (shape, size [m], Young's modulus [Pa], Poisson's ratio); a ball's size is its radius,
# a block's its edge. The racquet ball is hollow: a 4 mm rubber wall (the 39.7 g of a
# regulation ball at 1.1 g/cm^3) sealed at ambient pressure, its modulus set by the seed's
# 57 -> 53 mm at 12 N (`taxel.mechanics.HollowSphere`).
DEFORMATION_OBJECTS: dict[str, tuple[str, float, float, float]] = {
    "racquet ball": ("hollow ball", 28.5e-3, 3.64e6, 0.5),
    "acrylic sphere": ("ball", 6.25e-3, 3.2e9, 0.37),
    "steel ball": ("ball", 10e-3, 200e9, 0.3),
    "rubber ball": ("ball", 15e-3, 2e6, 0.49),
    "foam block": ("block", 25e-3, 0.2e6, 0.3),
    "wood block": ("block", 20e-3, 10e9, 0.35),
}
# the wall of each named hollow ball [m]
WALL_THICKNESS: dict[str, float] = {"racquet ball": 4e-3}
SHAPES: tuple[str, ...] = ("ball", "hollow ball", "block")


def make_deformation_object(
    name: str = "racquet ball",
    *,
    shape: str | None = None,
    size: float | None = None,
    youngs_modulus: float | None = None,
    poisson_ratio: float | None = None,
    thickness: float | None = None,
    gauge_pressure: float = 0.0,
) -> ProfileObject:
    """A ball or block on the table, named from `DEFORMATION_OBJECTS` or given by parameters.

    Parameters
    ----------
    name : str, default "racquet ball"
        A name of `DEFORMATION_OBJECTS`, or any name when all parameters are given.
    shape : {"ball", "hollow ball", "block"}, optional
        Overrides the named object's shape.
    size : float, optional
        Radius of a ball or edge of a cubic block [m].
    youngs_modulus : float, optional
        The object's Young's modulus [Pa] (a hollow ball's wall's).
    poisson_ratio : float, optional
        The object's Poisson's ratio.
    thickness : float, optional
        The wall of a hollow ball [m] (needed for one not named in `WALL_THICKNESS`).
    gauge_pressure : float, default 0.0
        A hollow ball's air above the atmosphere's [Pa] (a tennis ball: about 80 kPa).

    Returns
    -------
    ProfileObject
        A solid ball (it also flattens against the table), a sealed hollow ball
        (`make_hollow_ball`: its wall bends and its air is compressed, at the sensor and
        at the table) or a cube (flat-bottomed, its top face rounded by a 1 mm
        fillet), centred at the base origin.

    Examples
    --------
    >>> ball = make_deformation_object("racquet ball")
    >>> round(ball.top * 1e3, 1), ball.shell.thickness, ball.material.youngs_modulus
    (57.0, 0.004, 3640000.0)
    """
    known = DEFORMATION_OBJECTS.get(name)
    if known is None and None in (shape, size, youngs_modulus):
        raise ValueError(
            f"`name` must be one of {', '.join(DEFORMATION_OBJECTS)} unless shape, size and "
            f"youngs_modulus are all given; got {name!r}"
        )
    base = known or ("ball", 0.0, 0.0, 0.5)
    shape = shape or base[0]
    if shape not in SHAPES:
        raise ValueError(f"`shape` must be one of {', '.join(SHAPES)}; got {shape!r}")
    size = check_positive("size", size if size is not None else base[1])
    modulus = check_positive(
        "youngs_modulus", youngs_modulus if youngs_modulus is not None else base[2]
    )
    material = ElasticMaterial(modulus, poisson_ratio if poisson_ratio is not None else base[3])
    if shape == "ball":
        return make_ball(name, size, material)
    if shape == "block":
        return make_block(name, size, material)
    wall = thickness if thickness is not None else WALL_THICKNESS.get(name)
    if wall is None:
        raise ValueError(f"`thickness` (the wall) must be given for a hollow ball {name!r}")
    wall = check_positive("thickness", wall)
    if not wall < size / 2:  # (the shell would name its own `radius`, not `size`)
        given = "" if thickness is not None else f" ({name!r}'s wall)"
        raise ValueError(
            f"`thickness` must be less than half the `size` {size:g} m (a hollow ball's "
            f"radius), got {wall:g}{given}"
        )
    return make_hollow_ball(name, size, wall, material, gauge_pressure=gauge_pressure)


def top_height(item: SceneObject) -> float:
    """Height of an object's top above the table [m] (a profile object's or a box's)."""
    return float(getattr(item, "top", None) or getattr(item, "size", (0, 0, 0))[2])
