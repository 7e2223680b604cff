"""Where the contact lies in a prepared image: its box and windows, and its area (internal).

Features read sums, counts and extremes over the contact in the window that holds it
rather than over the whole image; each is computed once and kept in ``prepared.memo``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import cv2
import numpy as np

from taxel.features._image import Prepared
from taxel.features._sensor import TAIL_DEPTHS, depths_in_taxels_of

__all__ = [
    "WHOLE_IMAGE",
    "catchment_reach",
    "contact_area",
    "contact_box",
    "contact_hull",
    "contact_window",
    "depths_in_taxels",
]

# Images of at most this many taxels are read whole (see `contact_window`).
WHOLE_IMAGE = 32 * 32


def catchment_reach(prepared: Prepared) -> int:
    """How far [taxels] around a contact its load is felt: 3.5 cover depths, at least 2.

    A point load's stress at depth d spreads as Boussinesq's sigma_z, of which the part
    beyond a radius R is (1 + R^2 / d^2)^(-3/2): 2 % at R = 3.5 d. Without a cover (a bare
    pitch, a pressure map) the smoothing's reach, 2 taxels.
    """
    return math.ceil(depths_in_taxels(prepared, TAIL_DEPTHS) - 1e-9)


def depths_in_taxels(prepared: Prepared, depths: float) -> float:
    """`depths` cover depths in taxels, at least 2 (without a cover, that)."""
    return depths_in_taxels_of(prepared.cover_depth, prepared.mean_pitch, depths)


def contact_area(prepared: Prepared) -> int:
    """Number of contact taxels (internal; the binary moments' m00 when they are known)."""
    moments = prepared.memo.get("moments")
    if moments is not None:
        return int(moments[0]["m00"])
    rows, cols = contact_window(prepared)
    return cv2.countNonZero(prepared.mask[rows, cols])


def contact_box(prepared: Prepared) -> tuple[int, int, int, int]:
    """(left, top, width, height) of the contact mask (internal; kept in ``prepared.memo``).

    A region's extreme taxels lie on its outer outline: with one outline at hand, the
    box of its points is the mask's, at a fraction of the cost of reading the whole mask.
    """
    box = prepared.memo.get("box")
    if box is None:
        outlines = prepared.outlines
        source = outlines[0] if outlines is not None and len(outlines) == 1 else prepared.mask
        left, top, width, height = cv2.boundingRect(source)
        box = prepared.memo["box"] = (left, top, width, height)
    return box


def contact_window(prepared: Prepared, margin: int = 0) -> tuple[slice, slice]:
    """Rows and columns that hold every contact taxel (internal; kept in ``prepared.memo``).

    The rows of the contact's bounding box grown by `margin` taxels (within the image),
    across the whole width: sums, counts, extremes and filters of that reach over the
    contact can be computed there alone, on memory in one piece (NumPy works row by row
    on a narrower window, which costs more than the taxels it saves). The whole image when
    it is small (up to 32 x 32), where cropping costs more than it saves.
    """
    window = prepared.memo.get(("window", margin))
    if window is None:
        rows, cols = prepared.mask.shape
        if prepared.mask.size <= WHOLE_IMAGE:
            window = (slice(0, rows), slice(0, cols))
        else:
            _, top, _, height = contact_box(prepared)
            window = (
                slice(max(top - margin, 0), min(top + height + margin, rows)),
                slice(0, cols),
            )
        prepared.memo[("window", margin)] = window
    return window


def contact_hull(prepared: Prepared, contours: Sequence[np.ndarray]) -> np.ndarray | None:
    """Convex hull of the contact's taxel centres (internal; kept in ``prepared.memo``).

    `contours`: the contact's outlines (`outline_contours`); the hull of their points is
    that of every contact taxel. None with fewer than 3 outline points.
    """
    if "hull" not in prepared.memo:
        if len(contours) == 1:
            points = contours[0]
        else:
            points = np.concatenate(contours) if contours else np.zeros((0, 1, 2), np.int32)
        prepared.memo["hull"] = cv2.convexHull(points) if points.shape[0] >= 3 else None
    return prepared.memo["hull"]
