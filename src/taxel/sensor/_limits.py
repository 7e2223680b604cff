"""Loads a transducer cannot take, said in physical terms (for `TactileSensor.press`).

A transducer refuses an input past its physical end: a reflective membrane that would move
through its whole gap, a capacitive dielectric squeezed to less than nothing. It names its
own input (``displacement``, ``strain``); a user who pressed with a force asked for neither.
Here such a refusal is restated as what the press does to the sensor, naming the load.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from taxel.transducers import CapacitiveTransducer, ReflectiveOpticalTransducer

if TYPE_CHECKING:
    from taxel.sensor._sensor import TactileSensor

__all__ = ["load_limit"]


def load_limit(
    sensor: TactileSensor, quantity: np.ndarray, load_name: str, load_text: str
) -> str | None:
    """Why the sensed `quantity` of a press is past the transducer's end; None if it is not.

    Parameters
    ----------
    sensor : TactileSensor
        The sensor pressed.
    quantity : numpy.ndarray
        The transducer's input at each taxel for the press.
    load_name : str
        The parameter that set the load (``normal_force`` or ``indentation``).
    load_text : str
        Its value with its unit, as the message shows it (``2 N``).

    Returns
    -------
    str or None
        The message, naming `load_name`.
    """
    transducer = sensor.transducer
    finite = quantity[np.isfinite(quantity)]
    if finite.size == 0:
        return None
    if isinstance(transducer, ReflectiveOpticalTransducer):
        moved = float(finite.max())
        gap = transducer.unloaded_gap
        if moved < gap:
            return None
        return (
            f"pressing with {load_text} closes {sensor.name}'s {gap * 1e3:.3g} mm gap (the "
            f"cover would move {moved * 1e3:.3g} mm): `{load_name}` must be smaller"
        )
    if isinstance(transducer, CapacitiveTransducer):
        strain = float(finite.min())
        if strain > -1:
            return None
        return (
            f"pressing with {load_text} squeezes {sensor.name}'s {transducer.gap * 1e3:.3g} mm "
            f"dielectric flat (it would be compressed by {-strain * 100:.4g} % of its "
            f"thickness, and 100 % closes the gap): `{load_name}` must be smaller"
        )
    return None
