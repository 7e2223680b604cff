"""Noise of a tactile image: the Laplacian residual and its robust sigma (internal).

The contact thresholds of `prepare` are counted in noise sigmas of the smoothed image. The
noise is measured on the image itself, as the median absolute value of the residual
``x - mean(4 neighbours)``, which cancels a locally linear signal (a contact's flanks) and
leaves white noise; a raw frame too small to measure it takes the sensor's (`sensor_noise`).
"""

from __future__ import annotations

import math
from typing import Any

import cv2
import numpy as np

from taxel._validation import check_range
from taxel.features._input import LARGEST_VALUE
from taxel.features._sensor import sensor_noise

__all__ = [
    "RESIDUAL_QUANTUM",
    "laplacian_residual",
    "noise_from_residual",
    "smoothing_gain",
    "taxel_noise",
]

# An image with fewer interior taxels cannot estimate its own noise (a contact covers most
# of a 4 x 4 array's 4); a raw frame of a known sensor then takes the sensor's noise.
_SMALL_IMAGE = 16
# MAD of a standard normal, and the noise gain of `x - mean of its 4 neighbours`.
_MAD = 1.4826
_LAPLACE_GAIN = math.sqrt(1.25)
_LAPLACE_KERNEL = np.array([[0, -0.25, 0], [-0.25, 1, -0.25], [0, -0.25, 0]], np.float32)
# The Laplacian residual of an integer image is a multiple of 1/4.
RESIDUAL_QUANTUM = 0.25


def laplacian_residual(image: np.ndarray, step: int = 1, *, whole: bool = False) -> np.ndarray:
    """``x - mean(4 neighbours)`` on the image's interior, on every `step`-th row.

    Shape (len(range(1, rows - 1, step)), cols - 2): rows 1, 1 + step, ... of the image.
    `whole`: the image holds integers of at most 16 bits; every partial sum is then an
    exact multiple of 1/4 in float32, so one filter over every row, adding in its own
    order, gives the same residual in a third of the time of the four sums on the rows.
    """
    end = image.shape[0] - 1
    if whole:
        return cv2.filter2D(image, -1, _LAPLACE_KERNEL)[1:end:step, 1:-1]
    around = image[0 : end - 1 : step, 1:-1] + image[2 : end + 1 : step, 1:-1]
    around += image[1:end:step, :-2]
    around += image[1:end:step, 2:]
    around *= np.float32(0.25)
    return np.subtract(image[1:end:step, 1:-1], around, out=around)


def noise_from_residual(residual: np.ndarray, *, quantum: float = 0.0) -> float:
    """Noise sigma from Laplacian residuals (any shape): 1.4826 MAD / sqrt(1.25).

    `quantum`: the residuals are multiples of it (1/4 of an integer image's step). The
    median of such values jumps from one multiple to the next (a noise of 0.58 steps reads
    as 0.33 or 0.66), so it is then taken as the median of grouped data: each multiple
    stands for the interval of width `quantum` around it, and the median is interpolated
    within its interval from the counts below and in it. On integer images with white noise
    of 0.7-4 steps (quantisation included) this is within 4 % of the truth; under 0.6 steps
    the residual is mostly zero and it reads low (0.43 for 0.57).
    """
    values = np.abs(residual).ravel()  # a new array: partitioned in place below
    if values.size == 0:
        return 0.0
    middle = values.size // 2
    values.partition(middle)
    median = float(values[middle])
    if quantum > 0:
        # values[:middle] are <= the median and values[middle + 1:] >= it
        below = int(np.count_nonzero(values[:middle] < median))
        tied = middle - below + 1 + int(np.count_nonzero(values[middle + 1 :] == median))
        start = max(median - 0.5 * quantum, 0.0)  # |residual| = 0 stands for [0, q / 2)
        width = median + 0.5 * quantum - start
        median = start + width * (0.5 * values.size - below) / tied
    return _MAD * median / _LAPLACE_GAIN


def noise_sigma(residual: np.ndarray, quantum: float) -> float:
    """Noise sigma of an image, from the median absolute deviation of a discrete Laplacian.

    ``x - mean(4 neighbours)`` cancels any locally linear signal (the flanks of a contact)
    and leaves white noise of sigma n as sqrt(1.25) n; its median absolute value is robust
    to the few taxels where the signal curves. On images over 64 x 64 the residual is taken
    on every other row and the median over every other column, which is as good (the
    noise is white) and costs a quarter.
    """
    if residual.shape[1] > 64:
        residual = residual[:, ::2]
    return noise_from_residual(residual, quantum=quantum)


def smoothing_gain(smoothing: float) -> float:
    """Noise sigma left by a Gaussian of sigma `smoothing` [taxels] on white noise of sigma 1."""
    if smoothing == 0:
        return 1.0
    # a 2-D Gaussian of sigma s has sum(g^2) = 1 / (4 pi s^2) (continuous limit)
    return min(1.0 / (2.0 * math.sqrt(math.pi) * smoothing), 1.0)


def taxel_noise(
    noise: Any,
    sensor_or_pitch: Any,
    calibrated: bool,
    residual: np.ndarray,
    interior: int,
    quantum: float,
) -> float:
    """The noise sigma of one taxel [image units]: as given, the sensor's, or estimated.

    `quantum`: the step the residual's values are multiples of, or 0 (`noise_from_residual`).

    By default (None) estimated from the image's Laplacian residual, unless the image
    has too few interior taxels for the estimate (`_SMALL_IMAGE`): then the sensor's own
    (`sensor_noise`), in pascals for a calibrated image (through the sensor's
    `flat_plate_gain`), when `sensor_or_pitch` is a sensor that reads frames; else a
    ValueError asks for `noise`.
    """
    if noise is None:
        small = interior < _SMALL_IMAGE
        reads_frames = callable(getattr(sensor_or_pitch, "frame_from_pressure", None))
        if small and reads_frames:
            if not calibrated:
                return sensor_noise(sensor_or_pitch)
            gain = abs(float(getattr(sensor_or_pitch, "flat_plate_gain", 0.0)))
            if gain > 0:
                return sensor_noise(sensor_or_pitch) / gain
        if small:
            # a contact would be most of the estimate: on a 4 x 4 array a ball's 2 x 2
            # press, a residual of 4000 counts under 30 of noise, buried itself
            raise ValueError(
                f"an image with {interior} interior taxel(s) cannot estimate its own noise (it "
                f"needs {_SMALL_IMAGE}): give `noise` (one taxel's noise sigma, in the image's "
                "units)" + ("" if reads_frames else " or a sensor description")
            )
        return noise_sigma(residual, quantum)
    if isinstance(noise, str):
        if noise != "sensor":
            raise ValueError(f"`noise` must be a number or 'sensor', got {noise!r}")
        if calibrated:
            raise ValueError(
                "`noise='sensor'` is the noise of the sensor's raw frames, not of a calibrated "
                "image: give its noise in the image's units, or leave it to be estimated"
            )
        if not callable(getattr(sensor_or_pitch, "frame_from_pressure", None)):
            raise TypeError(
                "`noise='sensor'` needs `sensor_or_pitch` to be a sensor that reads frames (a "
                f"taxel.sensor.TactileSensor), got {type(sensor_or_pitch).__name__}"
            )
        return sensor_noise(sensor_or_pitch)
    # (as the image's values: beyond, its squares overflow single precision)
    return check_range("noise", noise, 0.0, LARGEST_VALUE, low_inclusive=False)
