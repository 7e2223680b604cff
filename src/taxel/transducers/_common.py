"""Shared pieces of the transducer models: the common interface and the `rng` helper."""

from __future__ import annotations

from typing import Any, ClassVar, Protocol, runtime_checkable

import numpy as np

from taxel._validation import as_rng

__all__ = ["Transducer", "as_generator"]


@runtime_checkable
class Transducer(Protocol):
    """What every transducer model of `taxel.transducers` offers.

    A transducer is a frozen dataclass holding its configuration. `respond` maps the physical
    quantity it senses (named by `quantity`, in `quantity_unit`) to its electrical or optical
    signal (in `signal_unit`); `invert` maps a signal back to the quantity, assuming the
    nominal configuration. Both are vectorised over arrays of taxels; options such as a time
    step, a shear offset or a temperature are keyword-only.

    Attributes
    ----------
    quantity : str
        Name of the sensed quantity, from the project glossary (e.g. ``"strain"``).
    quantity_unit : str
        Its SI unit, e.g. ``"Pa"`` or ``"-"`` for a dimensionless strain.
    signal_unit : str
        Unit of the output signal, e.g. ``"V"``, ``"W"`` or ``"DN"`` (camera digital number).
    """

    quantity: ClassVar[str]
    quantity_unit: ClassVar[str]
    signal_unit: ClassVar[str]

    # `*args: Any, **options: Any` is how a type checker is told "any further parameters":
    # each model declares its own keyword-only options (none take more positionals).
    def respond(self, value: Any, /, *args: Any, **options: Any) -> Any:
        """Signal produced by the sensed quantity `value`."""
        ...

    def invert(self, signal: Any, /, *args: Any, **options: Any) -> Any:
        """Sensed quantity recovered from `signal`."""
        ...


def as_generator(name: str, rng: Any) -> np.random.Generator:
    """Return `rng` as a NumPy Generator; an int is a seed. Anything else raises TypeError.

    There is no default: randomness is always explicit, and no global state is touched.
    """
    generator = as_rng(name, rng, allow_none=False)
    assert generator is not None
    return generator
