"""The features of one tactile image drawn on it (the seed's figures 3B-5B)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["plot_features"]


def plot_features(image: Any, features: Any, sensor_or_pitch: Any, *, ax: Any = None) -> Any:
    """Draw a tactile image with its edges, fitted line or circle, holes and slots.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        The tactile image the features came from.
    features : taxel.features.TactileFeatures
        From `taxel.features.extract`.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        The taxel pitch used for `features` [m].
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure is made when omitted.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.features import extract
    >>> y, x = np.mgrid[:48, :48]
    >>> washer = ((np.hypot(x - 24, y - 24) < 18) & (np.hypot(x - 24, y - 24) > 7)) * 1.0
    >>> figure = plot_features(washer, extract(washer, 1e-3), 1e-3)
    >>> figure.axes[0].get_title()
    'surface, 1 hole(s), 0 slot(s)'
    """
    from matplotlib.figure import Figure  # no pyplot: no GUI backend, no global state
    from matplotlib.patches import Circle

    from taxel.features import detect_edges, pitch_pair

    array = np.asarray(image, dtype=float)
    row_pitch, col_pitch = pitch_pair(sensor_or_pitch)
    rows, cols = array.shape

    def to_index(x: float, y: float) -> tuple[float, float]:
        return x / col_pitch + (cols - 1) / 2, y / row_pitch + (rows - 1) / 2

    if ax is None:
        figure = Figure(figsize=(5, 5))
        ax = figure.add_subplot()
    else:
        figure = ax.figure
    ax.imshow(array, cmap="gray", interpolation="nearest")
    edges = detect_edges(array, (row_pitch, col_pitch))
    ax.plot(edges.cols, edges.rows, "s", color="tab:orange", markersize=1.5, alpha=0.8)
    shape = features.shape
    if shape.contact_type == "line" and shape.line is not None:
        line = shape.line
        direction = np.array([math.cos(line.angle_rad), math.sin(line.angle_rad)])
        foot = line.offset_m * np.array([-direction[1], direction[0]])
        reach = math.hypot(rows * row_pitch, cols * col_pitch)
        ends = [to_index(*(foot + t * direction)) for t in (-reach, reach)]
        ax.plot([e[0] for e in ends], [e[1] for e in ends], "-", color="tab:cyan", lw=1.5)
    elif shape.contact_type == "arc" and shape.circle is not None:
        centre = to_index(*shape.circle.center_m)
        radius = shape.circle.radius_m / math.sqrt(row_pitch * col_pitch)
        ax.add_patch(Circle(centre, radius, fill=False, color="tab:cyan", lw=1.5))
    for hole in features.holes.items:
        radius = hole.radius_m / math.sqrt(row_pitch * col_pitch)
        centre = (hole.center_index[1], hole.center_index[0])
        ax.add_patch(Circle(centre, radius, fill=False, color="tab:red", lw=1.5))
    for slot in features.slots.items:
        direction = np.array([math.cos(slot.angle_rad), math.sin(slot.angle_rad)])
        normal = np.array([-direction[1], direction[0]])
        middle = np.array(slot.center_m)
        corners = [
            middle + a * slot.length_m / 2 * direction + b * slot.width_m / 2 * normal
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1), (-1, -1))
        ]
        points = [to_index(*c) for c in corners]
        ax.plot([p[0] for p in points], [p[1] for p in points], "-", color="tab:green", lw=1.5)
    if features.contact.present:
        row, col = features.contact.centroid_index
        ax.plot([col], [row], "+", color="tab:blue", markersize=10, mew=2)
    ax.set_xlim(-0.5, cols - 0.5)
    ax.set_ylim(rows - 0.5, -0.5)
    ax.set_title(
        f"{shape.contact_type}, {features.holes.count} hole(s), {features.slots.count} slot(s)"
    )
    ax.set_xlabel("column")
    ax.set_ylabel("row")
    return figure
