"""The features of one tactile image drawn on it (the seed's figures 3B-5B)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Unpack

import numpy as np

if TYPE_CHECKING:
    from taxel.features import Preparation

__all__ = ["plot_features"]


def plot_features(
    image: Any,
    features: Any,
    sensor_or_pitch: Any,
    *,
    ax: Any = None,
    **preparation: Unpack[Preparation],
) -> Any:
    """Draw a tactile image with its edges, fitted line or circle, holes and slots.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        The tactile image the features came from (refused when the features locate their
        contact, holes or slots as on an image of another shape).
    features : taxel.features.TactileFeatures
        From `taxel.features.extract`.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        The taxel pitch, or the sensor, given to `extract` for `features`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure is made when omitted.
    **preparation
        The keywords `extract` was given (`calibrated`, `smoothing`, `baseline`,
        `defects`, `noise`, `reference`), so that the edges drawn are found as the
        features were; a `reference` is also subtracted from the image drawn.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    TypeError
        When `features` is not a `TactileFeatures` or `ax` not a matplotlib Axes.
    ValueError
        When `image` is not a 2-D image, or `features` are not of an image of its shape
        at this pitch.

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

    from taxel.features import detect_edges

    array, (row_pitch, col_pitch) = _checked(image, features, sensor_or_pitch, ax)
    rows, cols = array.shape
    # the image as given (integers keep their noise's steps), prepared as the features were
    edges = detect_edges(image, sensor_or_pitch, **preparation)
    reference = preparation.get("reference")
    if reference is not None:
        array = array - np.asarray(reference, dtype=float)

    def to_index(x: float, y: float) -> tuple[float, float]:
        return x / col_pitch + (cols - 1) / 2, y / row_pitch + (rows - 1) / 2

    if ax is None:
        figure = Figure(figsize=(5, 5))
        ax = figure.add_subplot()
    else:
        figure = ax.figure
    ax.imshow(array, cmap="gray", interpolation="nearest")
    ax.plot(
        edges.cols, edges.rows, "s", color="tab:orange", markersize=1.5, alpha=0.8, label="edges"
    )
    shape = features.shape
    if shape.contact_type == "line" and shape.line is not None:
        line = shape.line
        direction = np.array([math.cos(line.angle_rad), math.sin(line.angle_rad)])
        foot = line.offset_m * np.array([-direction[1], direction[0]])
        reach = math.hypot(rows * row_pitch, cols * col_pitch)
        ends = [to_index(*(foot + t * direction)) for t in (-reach, reach)]
        ends_x, ends_y = [e[0] for e in ends], [e[1] for e in ends]
        ax.plot(ends_x, ends_y, "-", color="tab:cyan", lw=1.5, label="fitted line")
    elif shape.contact_type == "arc" and shape.circle is not None:
        centre = to_index(*shape.circle.center_m)
        radius = shape.circle.radius_m / math.sqrt(row_pitch * col_pitch)
        ax.add_patch(
            Circle(centre, radius, fill=False, color="tab:cyan", lw=1.5, label="fitted circle")
        )
    for number, hole in enumerate(features.holes.items):
        radius = hole.radius_m / math.sqrt(row_pitch * col_pitch)
        centre = (hole.center_index[1], hole.center_index[0])
        label = "hole" if number == 0 else None
        ax.add_patch(Circle(centre, radius, fill=False, color="tab:red", lw=1.5, label=label))
    for number, slot in enumerate(features.slots.items):
        direction = np.array([math.cos(slot.angle_rad), math.sin(slot.angle_rad)])
        normal = np.array([-direction[1], direction[0]])
        middle = np.array(slot.center_m)
        corners = [
            middle + a * slot.length_m / 2 * direction + b * slot.width_m / 2 * normal
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1), (-1, -1))
        ]
        points = [to_index(*c) for c in corners]
        label = "slot" if number == 0 else None
        xs, ys = [p[0] for p in points], [p[1] for p in points]
        ax.plot(xs, ys, "-", color="tab:green", lw=1.5, label=label)
    if features.contact.present:
        row, col = features.contact.centroid_index
        ax.plot([col], [row], "+", color="tab:blue", markersize=10, mew=2, label="centroid")
    ax.set_xlim(-0.5, cols - 0.5)
    ax.set_ylim(rows - 0.5, -0.5)
    tared = "" if reference is None else " (reference subtracted)"
    ax.set_title(
        f"{shape.contact_type}, {features.holes.count} hole(s), {features.slots.count} "
        f"slot(s){tared}"
    )
    ax.set_xlabel(f"column [taxels of {col_pitch * 1e3:.3g} mm]")
    ax.set_ylabel(f"row [taxels of {row_pitch * 1e3:.3g} mm]")
    ax.legend(loc="lower right", fontsize="small", framealpha=0.8)
    return figure


# How far, in taxels, the shape implied by a feature's index and position may lie from the
# image's (float32 rounding of the positions, far below a taxel).
_SHAPE_TOLERANCE = 0.01


def _checked(
    image: Any, features: Any, sensor_or_pitch: Any, ax: Any
) -> tuple[np.ndarray, tuple[float, float]]:
    """The image as a float array and the (row, col) pitch, once every input is checked."""
    from matplotlib.axes import Axes

    from taxel._validation import as_finite_array, check_instance
    from taxel.features import TactileFeatures, pitch_pair
    from taxel.features._sensor import check_image_shape

    array = as_finite_array("image", image, ndim=2)
    check_instance("features", features, TactileFeatures)
    pitch = pitch_pair(sensor_or_pitch)
    check_image_shape(array.shape, sensor_or_pitch)
    if ax is not None:
        check_instance("ax", ax, Axes)
    _check_same_image(features, array.shape, pitch)
    return array, pitch


def _check_same_image(features: Any, shape: tuple[int, ...], pitch: tuple[float, float]) -> None:
    """Raise when `features` locate something as on an image of another shape (or pitch).

    The features do not record their image's shape, but each located item (the contact,
    its regions, holes and slots) has both a taxel index and a position in the sensor
    frame, ``x = (col - (cols - 1) / 2) p_col``: together they give the image's shape. An
    image without contact records nothing to compare, and is drawn as it is.
    """
    contact = features.contact
    located = [(region.centroid_index, region.centroid_m) for region in contact.regions]
    if contact.present and contact.centroid_index is not None and contact.centroid_m is not None:
        located.append((contact.centroid_index, contact.centroid_m))
    located += [(item.center_index, item.center_m) for item in features.holes.items]
    located += [(item.center_index, item.center_m) for item in features.slots.items]
    for (row, col), (x, y) in located:
        implied = (2 * (row - y / pitch[0]) + 1, 2 * (col - x / pitch[1]) + 1)
        if any(abs(a - b) > _SHAPE_TOLERANCE for a, b in zip(implied, shape, strict=True)):
            raise ValueError(
                f"`features` must be of `image` (shape {tuple(shape)}) at `sensor_or_pitch` "
                f"{pitch}, got features located as on an image of shape "
                f"({implied[0]:.4g}, {implied[1]:.4g}) at that pitch: another image, or "
                "another pitch"
            )
