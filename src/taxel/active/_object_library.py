"""The small library of everyday objects that recognition chooses among.

Each model is a rigid object lying on the table, its top surface an indenter profile, built
at any pose: the seed's washer, a coin, a key blank, a bolt head, the corner of a box, a
pen and the top of a drink can. Sizes are those of common parts (an M8 washer and hex
head, a 23 mm coin, a 55 mm key, a 9 mm pen, a 66 mm can).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from taxel._validation import check_choice, check_finite, check_pair
from taxel.active._scene import ProfileObject
from taxel.active._shapes import KeyBlank, RoundedPolygon
from taxel.mechanics import BoxCorner, CanRim, Cylinder, FlatPunch, Indenter, Washer

__all__ = ["MODEL_NAMES", "describe_models", "make_model"]

# name: (profile factory, height of the top above the table [m], where the model's footprint
# is centred in its own frame (u, v) [m], description)
_MODELS: dict[str, tuple[Callable[[], Indenter], float, tuple[float, float], str]] = {
    "washer": (
        lambda: Washer(outer_radius=8e-3, inner_radius=4.2e-3, edge_radius=0.2e-3),
        1.6e-3,
        (0.0, 0.0),
        "M8 washer: 16 mm across, 8.4 mm hole, 1.6 mm thick",
    ),
    "coin": (
        lambda: FlatPunch(radius=11.6e-3, edge_radius=0.4e-3),
        2.3e-3,
        (0.0, 0.0),
        "coin: 23.2 mm disc, 2.3 mm thick, rounded rim",
    ),
    "key blank": (
        KeyBlank,
        2.0e-3,
        (5e-3, 0.0),
        "key blank: 22 mm bow with a 5 mm hole, 32 mm notched shank, 2 mm thick",
    ),
    "bolt head": (
        lambda: RoundedPolygon(13e-3, sides=6, edge_radius=0.5e-3),
        5.3e-3,
        (0.0, 0.0),
        "M8 hexagon head: 13 mm across flats, seen from above",
    ),
    "box corner": (
        lambda: BoxCorner(edge_radius=0.5e-3),
        40e-3,
        (0.0, 0.0),
        "corner (vertex) of a box standing on its opposite corner",
    ),
    "pen": (
        lambda: Cylinder(radius=4.5e-3, length=140e-3),
        9e-3,
        (0.0, 0.0),
        "pen lying on the table: 9 mm across, 140 mm long",
    ),
    "can": (
        lambda: CanRim(rim_radius=26e-3, lip_radius=1.2e-3),
        0.115,
        (0.0, 0.0),
        "top of a drink can standing upright: its rolled rim, 52 mm across",
    ),
}

MODEL_NAMES: tuple[str, ...] = tuple(_MODELS)


def describe_models() -> dict[str, str]:
    """One line on each model of the library.

    Examples
    --------
    >>> describe_models()["washer"]
    'M8 washer: 16 mm across, 8.4 mm hole, 1.6 mm thick'
    """
    return {name: entry[3] for name, entry in _MODELS.items()}


def make_model(
    name: str, *, position: tuple[float, float] = (0.0, 0.0), angle: float = 0.0
) -> ProfileObject:
    """A model of the library lying on the table, its footprint centred at `position`.

    Parameters
    ----------
    name : str
        One of `MODEL_NAMES`: washer, coin, key blank, bolt head, box corner, pen, can.
    position : tuple of float, default (0, 0)
        Centre of the object's footprint in the base frame (x, y) [m] (the centre of a
        can's rim, the vertex of a box corner, the middle of a key).
    angle : float, default 0
        Rotation about the vertical [rad].

    Returns
    -------
    ProfileObject
        A rigid object (no material: it does not deform).

    Examples
    --------
    >>> key = make_model("key blank", position=(0.1, 0.0), angle=np.pi / 2)
    >>> key.name, [round(float(v), 4) for v in key.pose[:2, 3]]  # the key's frame origin
    ('key blank', [0.1, -0.005])
    """
    check_choice("name", name, MODEL_NAMES)
    x0, y0 = check_pair("position", position)
    angle = check_finite("angle", angle)
    factory, top, centre, _ = _MODELS[name]
    cosine, sine = math.cos(angle), math.sin(angle)
    pose = np.eye(4)
    pose[:2, :2] = [[cosine, -sine], [sine, cosine]]
    # the object's frame sits so that its footprint centre lands on `position`
    pose[:2, 3] = [
        x0 - (cosine * centre[0] - sine * centre[1]),
        y0 - (sine * centre[0] + cosine * centre[1]),
    ]
    return ProfileObject(name=name, pose=pose, profile=factory(), top=top)
