"""The average cross-section of a line contact, taken normal to its fitted line."""

from __future__ import annotations

import numpy as np

from taxel.features import LineFit, sensor_coordinates

__all__ = ["line_cross_section"]


def line_cross_section(
    image: np.ndarray, line: LineFit, pitch: float, *, half_width: float, bins: int = 41
) -> tuple[np.ndarray, np.ndarray]:
    """Mean image value against signed distance from a fitted line.

    Parameters
    ----------
    image : numpy.ndarray
        The tactile image (background removed or not).
    line : LineFit
        The fitted line (sensor-frame angle and offset, metres).
    pitch : float
        Taxel pitch [m].
    half_width : float
        How far either side of the line to go [m].
    bins : int
        Number of distance bins.

    Returns
    -------
    distance, profile : numpy.ndarray
        Bin centres [m] and the mean image value in each bin.
    """
    row_index, col_index = np.indices(image.shape)
    x, y = sensor_coordinates(row_index.ravel(), col_index.ravel(), image.shape, pitch)
    normal = np.array([-np.sin(line.angle_rad), np.cos(line.angle_rad)])
    signed = x * normal[0] + y * normal[1] - line.offset_m
    edges = np.linspace(-half_width, half_width, bins + 1)
    index = np.digitize(signed, edges) - 1
    inside = (index >= 0) & (index < bins)
    totals = np.bincount(index[inside], weights=image.ravel()[inside], minlength=bins)
    counts = np.bincount(index[inside], minlength=bins)
    profile = np.where(counts > 0, totals / np.maximum(counts, 1), np.nan)
    return (edges[:-1] + edges[1:]) / 2, profile
