"""What the features take from a sensor description, when they are given one.

Features work on a bare taxel pitch; given a sensor (a `taxel.sensor.TactileSensor`, or
any object with ``taxel_pitch``, ``cover.depth`` and the sensor's ``fields`` and
``sensed_quantity``), they also use its cover: how deep the sensing plane lies, and how
wide the cover spreads a point load at that depth.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["cover_blur", "cover_depth"]

_BLUR_CACHE: dict[Any, float] = {}


def cover_depth(sensor_or_pitch: Any) -> float | None:
    """Depth of the sensing plane under the surface [m], when a sensor description gives it."""
    depth = getattr(getattr(sensor_or_pitch, "cover", None), "depth", None)
    return float(depth) if isinstance(depth, int | float) and depth > 0 else None


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
    key = (cover, grid.shape, grid.spacing, sensor_or_pitch.taxel_pitch)
    width = _BLUR_CACHE.get(key)
    if width is None:
        pressure = np.zeros(grid.shape)
        pressure[grid.shape[0] // 2, grid.shape[1] // 2] = 1e5
        response = np.abs(np.asarray(sensed(pressure, fields(pressure)), dtype=float))
        row = response[int(np.argmax(response.max(axis=1)))]
        width = float(np.count_nonzero(row >= 0.5 * row.max())) * sensor_or_pitch.taxel_pitch[1]
        _BLUR_CACHE[key] = width
    return width
