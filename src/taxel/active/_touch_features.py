"""Rotation-invariant numbers from one touch, for matching objects against models.

Each touch's tactile frame goes through `taxel.features.extract`; the numbers kept do not
depend on where the contact lies on the pad or how it is turned, so that a touch of an
object at any pose can be compared with the touches of its model at canonical poses.
"""

from __future__ import annotations

import math

import numpy as np

from taxel.features import Prepared, TactileFeatures, fit_circle, sensor_coordinates

__all__ = ["TOUCH_FEATURES", "touch_vector"]

# name and meaning; lengths in mm, so that every feature is of order 1-100
TOUCH_FEATURES: dict[str, str] = {
    "present": "1 when the touch found contact, else 0",
    "log_area": "log10 of the contact area [mm^2]",
    "major_axis": "length of the contact's major axis [mm]",
    "minor_axis": "length of its minor axis [mm]",
    "thickness": "diameter of the largest disk inside the contact [mm]",
    "elongation": "length over thickness of the main region (at most 20)",
    "hole": "1 when a hole was found in the contact, else 0",
    "curvature": "1 / radius of the circle fitted to the outline [1/mm] (0: straight)",
    "circle_fit": "RMS distance of the outline from that circle over its radius",
    "concentration": "pressure-weighted over plain mean square radius of the contact",
    "edge_score": "evidence of a long narrow edge, 0 to 1",
    "corner_score": "evidence of a vertex, 0 to 1",
    "band_curvature": "1 / radius of the circle fitted to the main region's taxels [1/mm]",
}
_MAX_ELONGATION = 20.0


def _band_curvature(prepared: Prepared | None) -> float:
    """Curvature of the main contact region as a whole: an arc band bends, a strip not."""
    if prepared is None or not prepared.present:
        return math.nan
    counts = np.bincount(prepared.labels.ravel())
    counts[0] = 0
    rows, cols = np.nonzero(prepared.labels == int(np.argmax(counts)))
    if rows.size < 10:
        return math.nan
    x, y = sensor_coordinates(rows, cols, prepared.image.shape, prepared.pitch)
    radius = fit_circle(np.column_stack((x, y))).radius_m * 1e3
    return 1.0 / radius if radius > 0 else math.nan


def touch_vector(features: TactileFeatures | None, prepared: Prepared | None = None) -> np.ndarray:
    """The numbers of `TOUCH_FEATURES` for one touch; None or no contact gives 0 then NaN.

    Parameters
    ----------
    features : TactileFeatures or None
        `taxel.features.extract` of the touch's frame; None when nothing was touched.
    prepared : Prepared, optional
        `taxel.features.prepare` of the same frame, for the band curvature.

    Examples
    --------
    >>> touch_vector(None)[:2].tolist()
    [0.0, nan]
    """
    vector = np.full(len(TOUCH_FEATURES), np.nan)
    vector[0] = 0.0
    if features is None or not features.contact.present:
        return vector
    contact, shape = features.contact, features.shape
    circle = shape.circle
    radius = circle.radius_m * 1e3 if circle is not None else math.inf
    fit = circle.rms_m / circle.radius_m if circle is not None and radius < math.inf else 1.0
    vector[:] = [
        1.0,
        math.log10(max(contact.area_m2 * 1e6, 1e-3)),
        contact.major_axis_m * 1e3,
        contact.minor_axis_m * 1e3,
        shape.thickness_m * 1e3,
        min(shape.elongation, _MAX_ELONGATION),
        1.0 if features.holes.present else 0.0,
        1.0 / radius,
        min(fit, 1.0),
        shape.concentration,
        shape.edge_score,
        shape.corner_score,
        _band_curvature(prepared),
    ]
    return np.where(np.isfinite(vector), vector, np.nan)
