"""Argument types shared by the subcommands: argparse turns their errors into one line."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable

__all__ = [
    "DEFORMATION_OBJECTS",
    "INDENTER_DESCRIPTIONS",
    "INDENTER_NAMES",
    "MODEL_NAMES",
    "NORMALIZATIONS",
    "PRESET_NAMES",
    "choice",
    "finite",
    "integer_in",
    "nonnegative_in",
    "positive",
    "positive_in",
    "preset",
    "real_in",
    "seed",
]

# `taxel.sensor.PRESET_NAMES`, `taxel.mechanics.INDENTER_NAMES` (with what each is),
# `taxel.active.NORMALIZATIONS`, `taxel.active.MODEL_NAMES` and
# `taxel.active.DEFORMATION_OBJECTS`, written out so that
# building the parser (``taxel --help``, and every command) does not import those layers,
# whose SciPy dependencies take seconds to load; a test checks they agree.
PRESET_NAMES = (
    "vhdta128",
    "harmon10x20",
    "resistive16",
    "capacitive4x4",
    "piezo8x8",
    "photoelastic64",
    "microbend16",
    "reflective8x8",
)
NORMALIZATIONS = ("static", "load")
# what each indenter is, as `taxel.mechanics.describe_indenters` says
INDENTER_DESCRIPTIONS = {
    "pen": "ball-point pen tip, 0.7 mm across",
    "sphere": "12.5 mm acrylic sphere",
    "edge": "straight edge of radius 3.2 mm",
    "cylinder": "short cylinder, 10 mm across",
    "punch": "flat punch, 6 mm across",
    "washer": "M8 washer (16 mm outside, 8.4 mm hole)",
    "can": "rim of a drink can, 52 mm across, 1 mm lip radius",
    "box-edge": "edge of a box (90 degrees), rounded to 0.5 mm",
    "box-corner": "corner (vertex) of a box, edges rounded to 0.5 mm",
    "slot": "plate with a 3 mm x 15 mm slot",
    "hole": "plate with a 6 mm hole",
    "foam": "stiff conductive foam",
    "rasp": "teeth of a wood rasp",
    "screen": "perforated metal screen, 4 mm holes",
}
INDENTER_NAMES = tuple(INDENTER_DESCRIPTIONS)

MODEL_NAMES = ("washer", "coin", "key blank", "bolt head", "box corner", "pen", "can")
DEFORMATION_OBJECTS = (
    "racquet ball",
    "acrylic sphere",
    "steel ball",
    "rubber ball",
    "foam block",
    "wood block",
)


def _number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number, got {text!r}") from None


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}") from None


def finite(text: str) -> float:
    """A finite real number."""
    value = _number(text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be finite, got {text}")
    return value


def positive(text: str) -> float:
    """A finite number > 0."""
    value = _number(text)
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"must be > 0, got {text}")
    return value


def positive_in(low: float, high: float) -> Callable[[str], float]:
    """A number > 0 within physical bounds [low, high] (beyond them the models overflow).

    A value <= 0 is refused as by `positive`; one outside the bounds names them.
    """

    def parse(text: str) -> float:
        value = positive(text)
        if value < low:
            raise argparse.ArgumentTypeError(f"must be at least {low:g}, got {text}")
        if value > high:
            raise argparse.ArgumentTypeError(f"must be at most {high:g}, got {text}")
        return value

    return parse


def nonnegative_in(high: float) -> Callable[[str], float]:
    """A finite number >= 0 and at most `high` (beyond it the models overflow)."""

    def parse(text: str) -> float:
        value = _number(text)
        if not (math.isfinite(value) and value >= 0):
            raise argparse.ArgumentTypeError(f"must be >= 0, got {text}")
        if value > high:
            raise argparse.ArgumentTypeError(f"must be at most {high:g}, got {text}")
        return value + 0.0  # -0 as 0, which is how it is printed and stored

    return parse


def real_in(low: float, high: float) -> Callable[[str], float]:
    """A number in [low, high]."""

    def parse(text: str) -> float:
        value = _number(text)
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"must lie in [{low:g}, {high:g}], got {text}")
        return value

    return parse


def integer_in(low: int, high: int | None = None) -> Callable[[str], int]:
    """An integer >= low (and <= high when given)."""

    def parse(text: str) -> int:
        value = _integer(text)
        if value < low or (high is not None and value > high):
            bound = f"be >= {low}" if high is None else f"lie in {low}..{high}"
            raise argparse.ArgumentTypeError(f"must {bound}, got {text}")
        return value

    return parse


def seed(text: str) -> int:
    """A random seed: an integer >= 0."""
    return integer_in(0)(text)


def choice(names: tuple[str, ...]) -> Callable[[str], str]:
    """One of `names` (which may hold spaces: argparse's choices would list them unquoted)."""

    def parse(text: str) -> str:
        if text not in names:
            raise argparse.ArgumentTypeError(f"must be one of {', '.join(names)}; got {text!r}")
        return text

    return parse


def preset(text: str) -> str:
    """The name of a sensor preset (`taxel.sensor.PRESET_NAMES`)."""
    return choice(PRESET_NAMES)(text)
