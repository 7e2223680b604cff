"""The sensors the active procedures can use: arrays whose frames are tactile images."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy import ndimage

from taxel.features import Prepared
from taxel.sensor import TactileSensor, as_sensor, reading_step
from taxel.transducers import MicrobendTransducer

__all__ = ["background_level", "frame_noise", "imaging_sensor"]

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


def background_level(prepared: Prepared, sensor: TactileSensor) -> float | None:
    """A frame's no-contact level: the median of its smoothed image away from the contact.

    For `taxel.features.prepare`'s `baseline`, in the frame's raw units (internal).
    `prepare` takes by default the minimum of the smoothed image, which lies 3-4 noise
    sigmas under the background's mean in a noisy frame, an offset b. Its contact outline,
    at the larger of 8 sigmas and 12 % of the contrast over that minimum, then lies ~4
    sigmas above the background while the noise sets it, but at 12 % of the contrast less
    0.88 b once the contrast does: a smaller fraction of a faint image's contrast than of a
    bright one's, further out in the cover's blur. A light press then shows a larger
    imprint than a firm one of the same object. Over the background itself the outline's
    fraction of the contrast never grows with the contrast, and presses of one object
    compare.

    The background is what lies more than twice the cover's blur (the half-maximum width
    of its point response; 3 taxels when unknown) beyond the contact, or the whole image
    when it shows none. None when fewer than 36 taxels remain (the contact covers the
    array): the minimum is then the best guess.
    """
    mask = prepared.mask.view(bool)
    if mask.any():
        pitch = min(prepared.pitch)
        reach = max(math.ceil(2.0 * prepared.blur / pitch), 1) if prepared.blur > 0 else 3
        mask = ndimage.binary_dilation(mask, np.ones((3, 3), bool), iterations=reach)
    background = prepared.smooth[~mask]
    if background.size < _SMALLEST_INTERIOR:
        return None
    level = float(np.median(background))
    # `prepare` turns over the frames of a sensor whose reading falls with pressure
    return -level if sensor.reading_falls_with_pressure else level
