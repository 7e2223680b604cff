"""The named indenter library: the objects of the Ellis seed with realistic default sizes."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from taxel._validation import check_choice
from taxel.mechanics._indenter_base import Indenter
from taxel.mechanics._indenters import BoxEdge, CanRim, Cone, Cylinder, FlatPunch, Sphere, Washer
from taxel.mechanics._indenters_plates import BoxCorner, PlateWithHole, SlottedPlate
from taxel.mechanics._textures import PerforatedScreen, StiffFoam, WoodRasp

__all__ = ["INDENTER_NAMES", "describe_indenters", "make_indenter"]

_LIBRARY: dict[str, tuple[Callable[..., Indenter], dict[str, Any], str]] = {
    "pen": (
        Cone,
        {"tip_radius": 0.35e-3, "half_angle": np.radians(20)},
        "ball-point pen tip, 0.7 mm across",
    ),
    "sphere": (Sphere, {"radius": 6.25e-3}, "12.5 mm acrylic sphere"),
    "edge": (Cylinder, {"radius": 3.2e-3}, "straight edge of radius 3.2 mm"),
    "cylinder": (Cylinder, {"radius": 5e-3, "length": 20e-3}, "short cylinder, 10 mm across"),
    "punch": (FlatPunch, {"radius": 3e-3, "edge_radius": 0.1e-3}, "flat punch, 6 mm across"),
    "washer": (
        Washer,
        {"outer_radius": 8e-3, "inner_radius": 4.2e-3, "edge_radius": 0.2e-3},
        "M8 washer (16 mm outside, 8.4 mm hole)",
    ),
    "can": (
        CanRim,
        {"rim_radius": 26e-3, "lip_radius": 1.0e-3},
        "rim of a drink can, 52 mm across, 1 mm lip radius",
    ),
    "box-edge": (
        BoxEdge,
        {"edge_radius": 0.5e-3},
        "edge of a box (90 degrees), rounded to 0.5 mm",
    ),
    "box-corner": (
        BoxCorner,
        {"edge_radius": 0.5e-3},
        "corner (vertex) of a box, edges rounded to 0.5 mm",
    ),
    "slot": (
        SlottedPlate,
        {"slot_width": 3e-3, "slot_length": 15e-3},
        "plate with a 3 mm x 15 mm slot",
    ),
    "hole": (PlateWithHole, {"hole_radius": 3e-3}, "plate with a 6 mm hole"),
    "foam": (StiffFoam, {}, "stiff conductive foam"),
    "rasp": (WoodRasp, {}, "teeth of a wood rasp"),
    "screen": (PerforatedScreen, {}, "perforated metal screen, 4 mm holes"),
}

INDENTER_NAMES: tuple[str, ...] = tuple(_LIBRARY)


def make_indenter(name: str, **parameters: Any) -> Indenter:
    """Build a named indenter of the library, overriding any default parameter.

    Parameters
    ----------
    name : str
        One of `INDENTER_NAMES`: pen, sphere, edge, cylinder, punch, washer, can, box-edge,
        box-corner, slot, hole, foam, rasp, screen.
    **parameters
        Parameters of the indenter's class to change from the defaults (SI units).

    Returns
    -------
    Indenter

    Examples
    --------
    >>> make_indenter("edge")
    Cylinder(radius=0.0032, length=None)
    >>> make_indenter("sphere", radius=2e-3)
    Sphere(radius=0.002)
    """
    check_choice("name", name, INDENTER_NAMES)
    factory, defaults, _ = _LIBRARY[name]
    return factory(**(defaults | parameters))


def describe_indenters() -> dict[str, str]:
    """One-line description of each named indenter."""
    return {name: entry[2] for name, entry in _LIBRARY.items()}
