"""The sensors the active procedures can use: arrays whose frames are tactile images."""

from __future__ import annotations

from typing import Any

from taxel.sensor import TactileSensor, as_sensor, reading_step
from taxel.transducers import MicrobendTransducer

__all__ = ["frame_noise", "imaging_sensor"]

# `taxel.features.prepare` estimates an image's noise from the median of its Laplacian
# residual over the interior (all but the border taxels), which holds while the contact
# curves fewer than half of them. An interior under 6 x 6 taxels (an array under 8 x 8)
# is mostly contact: on a 4 x 4 array a press fills the 2 x 2 interior and the "noise"
# is the contact itself, which then never clears 11 times it.
_SMALLEST_INTERIOR = 36


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


def frame_noise(sensor: TactileSensor) -> float | None:
    """The noise of a raw frame for `taxel.features.prepare`, on arrays too small to show it.

    None on arrays of 8 x 8 taxels or more, whose images give their own noise. On smaller
    ones, the sensor's reading step measured at rest (`taxel.sensor.reading_step`: the rms
    noise over 32 frames, at least one ADC level) [raw units], as a robot measures its
    sensor once before use (internal).
    """
    rows, cols = sensor.shape
    if (rows - 2) * (cols - 2) >= _SMALLEST_INTERIOR:
        return None
    return reading_step(sensor, rng=0).step
