"""Planarity of the contact area and the normal of the contact plane (Ellis seed, section 2)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, Unpack

import cv2
import numpy as np

from taxel._validation import as_finite_array, shown_apart
from taxel.features._image import Preparation, Prepared, prepare
from taxel.features._record import record
from taxel.features._window import contact_area, contact_hull, contact_window

__all__ = ["ContactPlane", "checked_depth", "contact_plane", "plane_core"]

# A cover's indentation is millimetres; beyond a metre a depth map is in other units (and
# its squares overflow in the plane fit).
_DEEPEST = 1.0  # [m]

_ERODE = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (5, 5))


@record
class ContactPlane:
    """How planar the contact is, and the normal of its plane when depth is known.

    Attributes
    ----------
    planarity : float
        ``uniformity * fill`` in [0, 1]: 1 for a flat face pressed evenly over a convex area.
    uniformity : float
        ``1 - std / mean`` of the signal above baseline over the contact's interior (the
        contact eroded by 2 taxels, so the rim's blur and edge peaks do not count),
        clipped to [0, 1].
    fill : float
        Contact area over the area of its convex hull [-].
    normal : (float, float, float) or None
        Unit normal of the plane fitted to the indented surface, in the sensor frame,
        pointing away from the sensor (+z side); None without a depth map.
    tilt_rad : float or None
        Angle between `normal` and the sensor's +z [rad].
    rms_m : float or None
        RMS distance of the indented surface from the fitted plane [m].
    """

    planarity: float
    uniformity: float
    fill: float
    normal: tuple[float, float, float] | None
    tilt_rad: float | None
    rms_m: float | None


def plane_core(
    prepared: Prepared,
    depth: np.ndarray | None = None,
    *,
    contours: Sequence[np.ndarray] | None = None,
) -> ContactPlane:
    """Planarity and normal of a prepared image (internal core of `contact_plane`).

    `contours`: the contact's outlines, if already found (their hull is the contact's).
    """
    if not prepared.present:
        return ContactPlane(0.0, 0.0, 0.0, None, None, None)
    # the erosion reaches 2 taxels: on the contact's window grown by 2, it is the whole
    # image's erosion there (and 0 elsewhere)
    grown = contact_window(prepared, 2)
    r0, c0 = grown[0].start, grown[1].start
    mask = prepared.mask[grown]
    interior = cv2.erode(mask, _ERODE)
    if not cv2.countNonZero(interior):
        interior = mask
    mean, deviation = cv2.meanStdDev(prepared.smooth[grown], mask=interior)
    above = float(mean[0, 0]) - prepared.baseline
    spread = float(deviation[0, 0])
    uniformity = min(max(1.0 - spread / above, 0.0), 1.0) if above > 0 else 0.0
    if contours is None:
        contours = list(
            cv2.findContours(mask, cv2.RETR_LIST, cv2.CHAIN_APPROX_NONE, offset=(c0, r0))[0]
        )
    hull = contact_hull(prepared, contours)
    hull_area = float(cv2.contourArea(hull)) if hull is not None else 0.0
    perimeter = cv2.arcLength(hull, True) if hull is not None else 0.0
    # a taxel is a unit square: the hull through taxel centres misses half a taxel all round
    area = float(contact_area(prepared))
    fill = min(area / (hull_area + 0.5 * perimeter + 1), 1.0)
    normal = tilt = rms = None
    if depth is not None:
        rows, cols = np.nonzero(interior)  # the rim's taxels are half in contact
        if rows.size >= 3:
            rows += r0
            cols += c0
            shape = prepared.mask.shape
            x = (cols - (shape[1] - 1) / 2) * prepared.pitch[1]
            y = (rows - (shape[0] - 1) / 2) * prepared.pitch[0]
            z = -depth[rows, cols]  # depth is into the cover, along -z of the sensor frame
            design = np.column_stack((x, y, np.ones_like(x)))
            (a, b, c), *_ = np.linalg.lstsq(design, z, rcond=None)
            norm = math.sqrt(a * a + b * b + 1.0)
            normal = (float(-a / norm), float(-b / norm), float(1.0 / norm))
            tilt = math.acos(min(1.0 / norm, 1.0))
            residual = (z - (a * x + b * y + c)) / norm
            rms = float(math.sqrt(float(np.einsum("i,i->", residual, residual)) / residual.size))
    return ContactPlane(uniformity * fill, uniformity, fill, normal, tilt, rms)


def contact_plane(
    image: Any,
    sensor_or_pitch: Any,
    *,
    depth: Any = None,
    **preparation: Unpack[Preparation],
) -> ContactPlane:
    """Planarity of the contact area and, given depth, the normal of the contact plane.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m].
    depth : array_like, shape (rows, cols), optional
        Indentation of the cover's surface at each taxel [m], positive into the cover
        (the mechanics convention), from a sensor that measures displacement or depth.
    **preparation
        `calibrated`, `smoothing`, `baseline`, `defects`, `noise` and `reference`, passed
        on to `prepare` with its defaults (so that this agrees with `extract`).

    Returns
    -------
    ContactPlane

    Notes
    -----
    Planarity (how uniform the contact is over its extent) multiplies the uniformity of
    the signal over the contact's interior by how fully the contact fills its convex hull:
    a flat face pressed evenly scores near 1; a dome, a ring or a texture scores less. The
    plane ``z = a x + b y + c`` is fitted by least squares to the indented surface
    ``z = -depth`` over the contact's interior; its normal is ``(-a, -b, 1) / |(-a, -b, 1)|``.

    Examples
    --------
    >>> y, x = (np.mgrid[:32, :32] - 15.5) * 1e-3
    >>> face = (np.hypot(x, y) < 10e-3).astype(float)
    >>> tilted = np.where(face > 0, 1e-3 + 0.1 * x, 0.0)  # deeper at +x
    >>> plane = contact_plane(face, 1e-3, depth=tilted)
    >>> round(plane.planarity, 2), [round(v, 3) for v in plane.normal]
    (0.93, [0.1, 0.0, 0.995])
    """
    prepared = prepare(image, sensor_or_pitch, **preparation)
    return plane_core(prepared, checked_depth(depth, prepared.image.shape))


def checked_depth(depth: Any, shape: tuple[int, ...]) -> np.ndarray | None:
    """`depth` checked: finite, of the image's `shape`, within +-`_DEEPEST` m (internal)."""
    if depth is None:
        return None
    array = as_finite_array("depth", depth, ndim=2)
    if array.shape != shape:
        raise ValueError(f"`depth` must have the image's shape {shape}, got {array.shape}")
    deepest = float(np.max(np.abs(array)))
    if deepest > _DEEPEST:
        raise ValueError(
            f"`depth` is an indentation in metres and must lie within +-{_DEEPEST:g} m, "
            f"got {shown_apart(deepest, _DEEPEST)}"
        )
    return array
