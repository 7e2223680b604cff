"""What the features take from a sensor description, when they are given one.

Features work on a bare taxel pitch, on a rectangular grid; given a sensor (a
`taxel.sensor.TactileSensor`, or any object with ``taxel_pitch``, ``cover.depth`` and the
sensor's ``fields`` and ``sensed_quantity``), they also use its cover: how deep the sensing
plane lies, and how wide the cover spreads a point load at that depth; and its layout: a
hexagonal array's frame is resampled onto the rectangular grid first.
"""

from __future__ import annotations

import math
import weakref
from typing import Any

import numpy as np

from taxel._validation import (
    as_finite_array,
    check_broadcast,
    check_grid_shape,
    check_positive,
)

__all__ = [
    "TAIL_DEPTHS",
    "check_image_shape",
    "cover_blur",
    "cover_depth",
    "depths_in_taxels_of",
    "hexagonal_resampled",
    "pitch_pair",
    "raw_falls_with_pressure",
    "require_square_taxels",
    "sensor_coordinates",
    "sensor_noise",
]

# A contact's load is felt this many cover depths around it (2 % of a point load's beyond)
TAIL_DEPTHS = 3.5
_HALO_TAXELS = 2  # ... and at least this far: the smoothing's reach

_BLUR_CACHE: dict[Any, float] = {}
_NOISE_CACHE: weakref.WeakKeyDictionary[Any, float] = weakref.WeakKeyDictionary()
# `sensor_noise` pools the residuals of this many taxels at least (one 128 x 128 frame,
# 64 frames of a 4 x 4 array) and reads at most this many frames
_NOISE_RESIDUALS = 4096
_NOISE_FRAMES = 64
# Row and column pitches this close count as square for the measures taken in taxels
# (a 1 % stretch turns a 45 deg line by 0.3 deg)
_SQUARE_WITHIN = 0.01


def depths_in_taxels_of(depth: float, mean_pitch: float, depths: float) -> float:
    """`depths` cover depths of `depth` [m] in taxels of `mean_pitch` [m], at least 2.

    Without a cover (`depth` 0), the smoothing's reach, `_HALO_TAXELS`.
    """
    return max(_HALO_TAXELS, depths * depth / mean_pitch)


def cover_depth(sensor_or_pitch: Any) -> float | None:
    """Depth of the sensing plane under the surface [m], when a sensor description gives it."""
    depth = getattr(getattr(sensor_or_pitch, "cover", None), "depth", None)
    return float(depth) if isinstance(depth, int | float) and depth > 0 else None


def raw_falls_with_pressure(sensor_or_pitch: Any) -> bool:
    """Whether a sensor's raw reading falls as the pressure rises (a PVDF array's does).

    Read off the sensor (``reading_falls_with_pressure`` of a `taxel.sensor.TactileSensor`);
    False for a bare pitch.
    """
    return getattr(sensor_or_pitch, "reading_falls_with_pressure", False) is True


def cover_blur(sensor_or_pitch: Any) -> float:
    """Half-maximum width [m] of what the sensor senses under a point load; 0 if unknown.

    Computed once per cover and grid with the sensor's own mechanics: one surface cell is
    loaded at the centre of the load grid and the sensed field is read at the taxels; the
    width counts the taxels of the central row at or above half the peak.
    """
    fields = getattr(sensor_or_pitch, "fields", None)
    sensed = getattr(sensor_or_pitch, "sensed_quantity", None)
    grid = getattr(sensor_or_pitch, "load_grid", None)
    cover = getattr(sensor_or_pitch, "cover", None)
    if fields is None or sensed is None or grid is None or cover is None:
        return 0.0
    pitch = pitch_pair(sensor_or_pitch)  # (a duck-typed sensor may give one number)
    key = (cover, grid.shape, grid.spacing, pitch)
    width = _BLUR_CACHE.get(key)
    if width is None:
        pressure = np.zeros(grid.shape)
        pressure[grid.shape[0] // 2, grid.shape[1] // 2] = 1e5
        response = np.abs(np.asarray(sensed(pressure, fields(pressure)), dtype=float))
        row = response[int(np.argmax(response.max(axis=1)))]
        width = float(np.count_nonzero(row >= 0.5 * row.max())) * pitch[1]
        _BLUR_CACHE[key] = width
    return width


def sensor_noise(sensor: Any) -> float:
    """Noise sigma of one taxel of the sensor's raw frames [raw units], as `prepare` sees it.

    Parameters
    ----------
    sensor : taxel.sensor.TactileSensor
        A sensor that reads frames (``frame_from_pressure``).

    Returns
    -------
    float
        The noise `prepare` would estimate from unloaded raw frames of the sensor, were
        they large enough: the readout's noise, its quantization and the unit's fixed
        pattern (gain and offset spread) together, which is what sets a raw frame's
        background apart from a contact.

    Notes
    -----
    Measured once per sensor (then cached) on unloaded frames drawn with a fixed seed
    (`_NOISE_RESIDUALS` taxels at least, at most `_NOISE_FRAMES` frames), by the estimator
    `prepare` applies to an image (the median absolute Laplacian residual) on all their
    residuals pooled: an image of 16 taxels, most of them under a contact, cannot give its
    own noise, but the sensor's frames can.

    Examples
    --------
    >>> from taxel.sensor import make_sensor
    >>> round(sensor_noise(make_sensor("capacitive4x4")), 1)  # 16-bit codes
    33.2
    """
    from taxel.features._noise import laplacian_residual, noise_from_residual

    if not callable(getattr(sensor, "frame_from_pressure", None)):
        raise TypeError(
            f"`sensor` must be a sensor that reads frames (a taxel.sensor.TactileSensor), "
            f"got {type(sensor).__name__}"
        )
    cached = _NOISE_CACHE.get(sensor)
    if cached is not None:
        return cached
    rows, cols = sensor.shape
    count = min(_NOISE_FRAMES, math.ceil(_NOISE_RESIDUALS / max((rows - 2) * (cols - 2), 1)))
    rest = np.zeros(sensor.load_grid.shape)
    rng = np.random.default_rng(0)
    residuals = []
    quantum = 0.0
    for _ in range(count):
        given = np.asarray(sensor.frame_from_pressure(rest, rng=rng).raw)
        raw = given.astype(np.float32)
        if raw.ndim != 2:
            raise ValueError(
                f"`sensor` must read raw frames that are images, got frames of shape "
                f"{raw.shape}"
            )
        resampled = hexagonal_resampled(raw, sensor)
        if given.dtype.kind in "biu" and resampled is raw:  # residuals: multiples of 1/4
            quantum = 0.25
        residuals.append(laplacian_residual(resampled).ravel())
    noise = noise_from_residual(np.concatenate(residuals), quantum=quantum)
    _NOISE_CACHE[sensor] = noise
    return noise


# Below a nanometre no tactile array exists, and areas (pitch squared) underflow.
_SMALLEST_PITCH = 1e-9


def pitch_pair(sensor_or_pitch: Any) -> tuple[float, float]:
    """(row pitch, column pitch) [m] from a pitch, a pair, or an object with `taxel_pitch`.

    Parameters
    ----------
    sensor_or_pitch : float, (float, float) or object with a ``taxel_pitch`` attribute
        Centre-to-centre distance of the taxels [m]; a pair gives (row, column) pitches.

    Returns
    -------
    tuple of float

    Examples
    --------
    >>> pitch_pair(1e-3)
    (0.001, 0.001)
    >>> pitch_pair((1e-3, 2e-3))
    (0.001, 0.002)
    """
    value = getattr(sensor_or_pitch, "taxel_pitch", sensor_or_pitch)
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()  # what np.load gives for a saved number
    if isinstance(value, bool | np.bool_):
        raise TypeError(f"`sensor_or_pitch` must be a number in metres, got {value!r}")
    if isinstance(value, tuple | list | np.ndarray):
        if len(value) != 2:
            raise ValueError(
                f"`sensor_or_pitch` must be a pitch or a (row, column) pair, got {value!r}"
            )
        pair = (
            check_positive("sensor_or_pitch[0]", value[0]),
            check_positive("sensor_or_pitch[1]", value[1]),
        )
    else:
        if isinstance(value, str | bytes):
            raise TypeError(f"`sensor_or_pitch` must be a number in metres, got {value!r}")
        pitch = check_positive("sensor_or_pitch", value)
        pair = (pitch, pitch)
    for number in pair:
        if not _SMALLEST_PITCH <= number <= 1.0:
            raise ValueError(
                f"`sensor_or_pitch` must be a taxel pitch in metres (1 nm to 1 m), got {number:g}"
            )
    return pair


def require_square_taxels(pitch: tuple[float, float], what: str, hexagonal: bool) -> None:
    """Raise unless the row and column pitch agree to 1 % (`what` needs square taxels).

    The contact type, the line and circle fits and the hole tests measure the contact in
    taxels (distances, outlines, circles) and convert with one pitch: on oblong taxels a
    round hole is an ellipse and a line's angle is stretched. The contact's centroid,
    area, axes and force, the slots, the plane and the texture take any pitch. A
    `hexagonal` array's frame (resampled onto its rectangular grid, rows sqrt(3)/2 of
    its pitch apart) is let through: its measures in taxels are 15 % short across the
    rows, which turns a 45 deg line by up to 4 deg.
    """
    row, col = pitch
    if not hexagonal and abs(row / col - 1.0) > _SQUARE_WITHIN:
        raise ValueError(
            f"`sensor_or_pitch` must give square taxels for {what} (row and column pitch "
            f"within 1 %), got ({row:g}, {col:g}) m: resample the image to one pitch p "
            f"first (e.g. cv2.resize(image, None, fx={col:g} / p, fy={row:g} / p)); "
            "find_contact, detect_slots, contact_plane and texture_measures take any pitch"
        )


def check_image_shape(shape: tuple[int, ...], sensor_or_pitch: Any) -> None:
    """Raise when a sensor is given and the image is not one of its frames.

    The sensor's pitch and centre apply to its own frames only: an image of another shape
    (a crop, a pressure map on a finer load grid) needs its own pitch.
    """
    if not hasattr(sensor_or_pitch, "taxel_pitch"):
        return
    expected = getattr(sensor_or_pitch, "shape", None)
    if expected is not None and tuple(shape) != tuple(expected):
        raise ValueError(
            f"`image` must be a frame of the sensor, shape {tuple(expected)}, got "
            f"{tuple(shape)}; give the image's own pitch instead of the sensor"
        )


def sensor_coordinates(
    rows: Any, cols: Any, shape: tuple[int, int], sensor_or_pitch: Any
) -> tuple[np.ndarray, np.ndarray]:
    """Positions (x, y) [m] in the sensor frame of (fractional) taxel indices.

    Indices are on the rectangular grid every feature works on; `prepare` resamples a
    hexagonal array's frame onto it first (`ArrayGeometry.on_rectangular_grid`).

    Parameters
    ----------
    rows, cols : array_like
        Row and column indices; fractions are allowed (centroids, fitted centres).
    shape : (int, int)
        (rows, cols) of the image.
    sensor_or_pitch : float, pair or object with ``taxel_pitch``
        Taxel pitch [m].

    Returns
    -------
    x, y : numpy.ndarray
        ``x = (col - (cols - 1) / 2) p_col``, ``y = (row - (rows - 1) / 2) p_row`` [m].

    Examples
    --------
    >>> x, y = sensor_coordinates(0, 3, (4, 4), 1e-3)
    >>> float(x), float(y)
    (0.0015, -0.0015)
    """
    row_pitch, col_pitch = pitch_pair(sensor_or_pitch)
    n_rows, n_cols = check_grid_shape("shape", shape)
    rows, cols = as_finite_array("rows", rows), as_finite_array("cols", cols)
    check_broadcast(("rows", "cols"), rows, cols)
    return (cols - (n_cols - 1) / 2) * col_pitch, (rows - (n_rows - 1) / 2) * row_pitch


def hexagonal_resampled(values: np.ndarray, sensor_or_pitch: Any) -> np.ndarray:
    """A frame of a hexagonal array, resampled onto the rectangular grid all features assume.

    Taxels of a hexagonal (triangular) array sit p/4 off the rectangular grid, alternately
    left and right; only a frame of the array's own shape is resampled (a pressure map on a
    load grid is already rectangular).
    """
    geometry = getattr(sensor_or_pitch, "geometry", sensor_or_pitch)
    if getattr(geometry, "layout", None) != "hexagonal" or values.shape != geometry.shape:
        return values
    return geometry.on_rectangular_grid(values).astype(np.float32)
