"""A raw frame read back to pressure through its sensor's known response (internal).

An image's grey levels are not pressure: an FTIR camera's follow the real contact area,
which saturates (Persson's erf law), so that the highest pressures weigh too little in the
image, and its glass's scratches add light no contact makes. Given a sensor whose raw
frame its transducer reads back to pressure (`read_back`), the contact's centre of
pressure is taken from that pressure instead (`taxel.features._pressure_centre`). That
pressure is the one the cover carries down to the glass, the sensor's forward model's
reading (`forward_model`), which tells what the cover spreads beyond the array's edges.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import cv2
import numpy as np
from scipy import special

from taxel.reconstruction import ForwardModelSpec, as_forward_model_spec
from taxel.sensor import TactileSensor
from taxel.transducers import FtirTransducer

__all__ = [
    "ROUNDING",
    "ReadBack",
    "forward_model",
    "grey_level_pressure",
    "grey_noise",
    "light_image",
    "light_pressure",
    "read_back",
    "signed_pressure",
]

# The noise of an integer grey level at least: its rounding's [DN]
ROUNDING = 1.0 / math.sqrt(12.0)


@dataclass(frozen=True, eq=False)
class ReadBack:
    """A raw FTIR frame and the transducer that reads it back to pressure.

    Attributes
    ----------
    transducer : FtirTransducer
        A textured one (its grey level carries pressure).
    frame : numpy.ndarray
        The raw camera frame [DN], as given.
    tare : numpy.ndarray or None
        The sensor's unloaded frame (or a mean of several) [DN], when the frame was tared:
        the frame's unloaded level, in place of the model's dark level and scratches.
    sensor : object or None
        The sensor the frame came from, whose forward model (`forward_model`) reads the
        pressure at the glass.
    """

    transducer: FtirTransducer
    frame: np.ndarray
    tare: np.ndarray | None = None
    sensor: Any = None


def read_back(
    sensor_or_pitch: Any,
    frame: np.ndarray,
    *,
    calibrated: bool,
    tare: np.ndarray | None = None,
) -> ReadBack | None:
    """The frame's read-back, when the sensor's raw output is its transducer's own signal.

    Only for a textured FTIR transducer behind an ideal readout, on a raw frame of the
    sensor's shape that was not calibrated, tared or not by `tare` (its unloaded frame);
    None otherwise, and the features weigh the image.
    """
    transducer = getattr(sensor_or_pitch, "transducer", None)
    readout = getattr(sensor_or_pitch, "readout", None)
    if (
        calibrated
        or not isinstance(transducer, FtirTransducer)
        or not transducer.textured
        or getattr(readout, "is_identity", False) is not True
        or _shape_of(sensor_or_pitch) != frame.shape
    ):
        return None
    return ReadBack(transducer, frame, tare, sensor_or_pitch)


def forward_model(read: ReadBack) -> ForwardModelSpec | None:
    """The sensor's forward model, when its readings are the read-back's pressure.

    That is when the sensor has a forward model of one reading per taxel, of the frame's
    shape and the sensor's pitch, whose reading is the pressure felt at the cover's depth
    (``"stress"``); None otherwise. A `TactileSensor`'s is kept for the sensors seen last
    (the model costs ~25 us to build); another sensor's is asked for each time, as it may
    have changed.
    """
    if isinstance(read.sensor, TactileSensor):
        return _kept_model_of(read.sensor, read.frame.shape)
    return _model_of(read.sensor, read.frame.shape)


def _model_of(sensor: Any, shape: tuple[int, ...]) -> ForwardModelSpec | None:
    try:
        model = as_forward_model_spec(sensor)
    except (TypeError, ValueError, NotImplementedError):  # no forward model of this kind
        return None
    pitch = getattr(sensor, "taxel_pitch", None)
    if pitch is not None and not np.allclose(pitch, model.taxel_pitch, rtol=1e-6, atol=0.0):
        return None
    return model if model.shape == shape and model.quantity == "stress" else None


_kept_model_of = functools.lru_cache(maxsize=8)(_model_of)


def _shape_of(sensor: Any) -> tuple[int, ...] | None:
    """A sensor's ``shape`` as a tuple of ints (a duck-typed one may give an array), or None."""
    try:
        return tuple(int(n) for n in sensor.shape)
    except (AttributeError, TypeError, ValueError):
        return None


@functools.lru_cache(maxsize=8)
def _level_table(transducer: FtirTransducer, levels: int) -> np.ndarray:
    """Signed pressure [Pa] of each grey level 0..levels - 1, scratches aside (float32)."""
    grey = np.arange(float(levels))[None]
    table = transducer.invert(grey, subtract_scratches=False, keep_sign=True)[0]
    return table.astype(np.float32)


@functools.lru_cache(maxsize=4)
def _scratched(transducer: FtirTransducer, shape: tuple[int, int]) -> tuple[np.ndarray, ...]:
    """Flat indices of the pixels the glass's scratches brighten, and by how much [-]."""
    pattern = transducer.scratches(shape).ravel()
    where = np.flatnonzero(pattern)
    return where, pattern[where]


def _law(transducer: FtirTransducer, light: np.ndarray) -> np.ndarray:
    """Signed pressure [Pa] of a light fraction above the unloaded level [-] (the law)."""
    top = 1.0 - 0.5 / (transducer.bright_level - transducer.dark_level)
    scale = transducer.contact_modulus * transducer.rms_slope / math.sqrt(2.0)
    return scale * special.erfinv(np.clip(light, -top, top))


@functools.lru_cache(maxsize=8)
def _step_table(transducer: FtirTransducer, levels: int) -> np.ndarray:
    """Signed pressure [Pa] of each grey-level step -(levels - 1)..levels - 1 (float32)."""
    steps = np.arange(1.0 - levels, float(levels))
    span = transducer.bright_level - transducer.dark_level
    return _law(transducer, steps / span).astype(np.float32)


def signed_pressure(read: ReadBack) -> np.ndarray:
    """Pressure [Pa] of every pixel, negative below the unloaded level (float32).

    ``transducer.invert(frame, keep_sign=True)``; an unsigned 8- or 16-bit frame (in the
    machine's byte order) through a table of its levels, with only the scratched pixels
    (4 % of the glass) computed one by one, since scipy's erfinv costs ~20 ns a pixel;
    other frames through the law on every pixel. A tared frame's light is its step above
    the tare: through a table of the steps when both are integers of at most 16 bits.
    """
    transducer, frame, tare = read.transducer, read.frame, read.tare
    span = transducer.bright_level - transducer.dark_level
    if tare is not None:
        small = frame.itemsize <= 2 and tare.itemsize <= 2
        if small and frame.dtype.kind in "iu" and tare.dtype.kind in "iu":
            levels = 256 if frame.dtype.itemsize == 1 and tare.dtype.itemsize == 1 else 65536
            steps = frame.astype(np.int32) - tare.astype(np.int32) + (levels - 1)
            if steps.min() >= 0 and steps.max() < 2 * levels - 1:
                return _step_table(transducer, levels).take(steps)
        light = (frame.astype(np.float64) - tare) / span
        return _law(transducer, light).astype(np.float32)
    if frame.dtype == np.uint8:
        pressure = cv2.LUT(frame, _level_table(transducer, 256))
    elif frame.dtype == np.uint16:
        pressure = _level_table(transducer, 65536).take(frame)
    else:
        return transducer.invert(frame, keep_sign=True).astype(np.float32)
    if transducer.scratch_count:
        where, scratch = _scratched(transducer, frame.shape)
        light = (frame.ravel()[where] - transducer.dark_level) / span - scratch
        pressure.ravel()[where] = _law(transducer, light)
    return pressure


def light_image(read: ReadBack) -> np.ndarray:
    """Grey levels above the unloaded level [DN] of every pixel (float32).

    The unloaded level is the tare's, or the transducer's dark level and its glass's
    scratches.
    """
    transducer, frame, tare = read.transducer, read.frame, read.tare
    light = frame.astype(np.float32)
    if tare is not None:
        return light - tare.astype(np.float32)
    light -= np.float32(transducer.dark_level)
    if transducer.scratch_count:
        span = transducer.bright_level - transducer.dark_level
        light -= (span * transducer.scratches(frame.shape)).astype(np.float32)
    return light


def light_pressure(read: ReadBack, light: np.ndarray) -> np.ndarray:
    """Signed pressure [Pa] of grey levels above the unloaded level [DN] (the law)."""
    transducer = read.transducer
    return _law(transducer, light / (transducer.bright_level - transducer.dark_level))


def grey_level_pressure(read: ReadBack) -> float:
    """Pressure [Pa] of one grey level at the unloaded level (the law's slope there)."""
    transducer = read.transducer
    span = transducer.bright_level - transducer.dark_level
    # d erfinv / dx at 0 is sqrt(pi) / 2
    slope = transducer.contact_modulus * transducer.rms_slope / math.sqrt(2.0)
    return slope * math.sqrt(math.pi) / 2.0 / span


def grey_noise(read: ReadBack, noise: float) -> float:
    """A frame's noise [DN], an integer frame's taken as its rounding's at least."""
    return max(noise, ROUNDING) if read.frame.dtype.kind in "iu" else noise
