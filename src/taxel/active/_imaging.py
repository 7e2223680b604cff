"""The sensors the active procedures can use: arrays whose frames are tactile images."""

from __future__ import annotations

from typing import Any

from taxel.sensor import TactileSensor, as_sensor
from taxel.transducers import MicrobendTransducer

__all__ = ["imaging_sensor"]


def imaging_sensor(sensor: Any) -> TactileSensor:
    """`taxel.sensor.as_sensor`, refusing a sensor whose frames are no image (internal).

    Every procedure reads contact features from the frames as images. A microbend array
    reads one signal per fibre (rows + columns), from which no image can be formed.
    """
    chosen = as_sensor(sensor)
    if isinstance(chosen.transducer, MicrobendTransducer):
        rows, cols = chosen.shape
        raise ValueError(
            f"`sensor` {chosen.name!r} reads one signal per fibre ({rows} + {cols}), not a "
            "tactile image; the active procedures need an imaging array"
        )
    return chosen
