"""Holes and slots of one image (public functions), and the seed's diameter test.

The gap test itself (basins, their depth and shape) is in `taxel.features._gaps`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any, Unpack

import cv2
import numpy as np

from taxel.features._contact import contact_regions
from taxel.features._fitting import CircleFit, taubin_circle
from taxel.features._gaps import Hole, HoleReport, Slot, SlotReport
from taxel.features._image import Preparation, Prepared, prepare
from taxel.features._sensor import require_square_taxels
from taxel.features._textured import textured_gaps
from taxel.features._window import contact_hull

__all__ = [
    "detect_holes",
    "detect_slots",
    "diameter_test",
    "outline_contours",
    "outline_taxels",
]

# Diameters sampled by the seed's hole test and their extent beyond the fitted radius.
_DIAMETERS = 16
_DIAMETER_REACH = 2.0
# the diameters' directions: cosines (x, along columns) above sines (y, along rows)
_DIRECTIONS = np.concatenate(
    (
        np.cos(np.arange(_DIAMETERS) * (math.pi / _DIAMETERS)),
        np.sin(np.arange(_DIAMETERS) * (math.pi / _DIAMETERS)),
    )
)[:, None]
_DIRECTIONS.flags.writeable = False
# How far outside the contact's convex hull the fitted centre may lie and a diameter still
# meet the contact on both sides of it [taxels]: the sample read as the centre lies up to
# half a step from it, and a sample reads the taxel it rounds to, up to sqrt(2) / 2 off
# the diameter (1.21; with a margin).
_CENTRE_OFF_HULL = 1.5


def diameter_test(
    prepared: Prepared,
    cols: np.ndarray,
    rows: np.ndarray,
    circle: CircleFit | None = None,
    *,
    contours: Sequence[np.ndarray] | None = None,
) -> bool:
    """The seed's hole test on a prepared image and its outline taxels (internal core).

    Fits a circle to the outline (Taubin's, as `circle_fit_algebraic`; or takes `circle`,
    fitted to it in taxel units) and walks 16 diameters of it across 2 radii each way
    (the fit to both rims of a washer lies between them): a hole is present when some
    diameter crosses the contact's outline 4 times, twice on each side of the fitted
    centre (object rim, hole rim), with the centre off contact. Crossings are counted on
    the contact mask, which a sampled line cannot slip through at a diagonal. `contours`:
    the outlines `cols` and `rows` come from, if at hand (for the contact's hull).
    """
    if rows.size < 8:
        return False
    if circle is not None:
        centre_c, centre_r = circle.center_m
        radius = circle.radius_m
    else:
        # the circle alone: its RMS is not needed here
        fitted = taubin_circle(cols.astype(float), rows.astype(float))
        if fitted is None:
            return False
        centre_c, centre_r, radius = fitted
    shape = prepared.mask.shape
    if not math.isfinite(radius) or radius < 2 or radius > 2 * max(shape):
        return False
    # a diameter crossing the outline twice on each side meets the contact on both sides
    # of the centre, so the centre lies in the contact's hull (up to the sampling): an arc
    # of less than half a circle, whose centre lies beyond its chord, has no such diameter
    if contours is None:
        contours = outline_contours(prepared)
    hull = contact_hull(prepared, contours)
    if hull is not None and hull.shape[0] >= 3:
        inside = cv2.pointPolygonTest(hull, (float(centre_c), float(centre_r)), True)
        if inside < -_CENTRE_OFF_HULL:
            return False
    # one taxel per step: the contact's walls are at least 2 taxels thick after smoothing;
    # the steps run symmetrically about the centre, which is one of them, so a mirrored
    # image gives the mirrored samples
    reach = math.floor(_DIAMETER_REACH * radius)
    steps = np.arange(-reach, reach + 1, dtype=float)
    # the samples' columns (first 16 rows) and rows (last 16), rounded to taxels
    at = _DIRECTIONS * steps
    at[:_DIAMETERS] += centre_c
    at[_DIAMETERS:] += centre_r
    at = np.rint(at, out=at).astype(np.float32)
    # the nearest taxel of each sample, 0 off the array: a remap with whole-number maps
    # (exact in float32) reads them in one call
    touched = cv2.remap(
        prepared.mask,
        at[:_DIAMETERS],
        at[_DIAMETERS:],
        cv2.INTER_NEAREST,
        borderMode=cv2.BORDER_CONSTANT,
        borderValue=0,
    )
    # the mask holds 0 and 1: a crossing is where a sample differs from the next one
    crossed = cv2.bitwise_xor(touched[:, 1:], touched[:, :-1])
    middle = steps.size // 2
    before = cv2.reduce(crossed[:, :middle], 1, cv2.REDUCE_SUM, dtype=cv2.CV_32S).ravel()
    after = cv2.reduce(crossed[:, middle:], 1, cv2.REDUCE_SUM, dtype=cv2.CV_32S).ravel()
    # (16 diameters: read as plain numbers)
    return any(
        first_half == 2 and second_half == 2 and centre == 0
        for first_half, second_half, centre in zip(
            before.tolist(), after.tolist(), touched[:, middle].tolist(), strict=True
        )
    )


def outline_contours(prepared: Prepared) -> tuple[np.ndarray, ...]:
    """The contact's outlines (outer boundaries and hole walls, every taxel; internal)."""
    if not prepared.present:
        return ()
    if prepared.outlines is not None:
        return tuple(prepared.outlines)
    return tuple(cv2.findContours(prepared.mask, cv2.RETR_LIST, cv2.CHAIN_APPROX_NONE)[0])


def outline_taxels(
    prepared: Prepared, contours: Sequence[np.ndarray] | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """(cols, rows) of the taxels on the outlines of the contact mask (internal)."""
    if contours is None:
        contours, _ = cv2.findContours(prepared.mask, cv2.RETR_LIST, cv2.CHAIN_APPROX_NONE)
    if not contours:
        empty = np.zeros(0, np.intp)
        return empty, empty
    points = (contours[0] if len(contours) == 1 else np.concatenate(contours))[:, 0, :]
    return points[:, 0], points[:, 1]


def _gaps(prepared: Prepared) -> tuple[list[Hole], list[Slot]]:
    """Holes and slots of a prepared image, told whether it is a texture as `extract` is."""
    # a texture's basins are holes only when they make a perforated sheet, and never slots;
    # its regions' areas are all that tells it (not their centres: no read-back)
    regions = contact_regions(replace(prepared, read_back=None))
    holes, slots, _ = textured_gaps(prepared, regions)[2]
    return holes, slots


def detect_holes(
    image: Any, sensor_or_pitch: Any, **preparation: Unpack[Preparation]
) -> HoleReport:
    """Holes in the contact, by the gap test and by the seed's diameter test.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m], or a sensor description.
    **preparation
        `calibrated`, `smoothing`, `baseline`, `defects`, `noise` and `reference`, passed
        on to `prepare` with its defaults (so that this agrees with `extract`).

    Returns
    -------
    HoleReport

    Notes
    -----
    Gap test (decides `present`): a basin of the smoothed image enclosed by contact (it
    does not reach the array's border) is a hole when its bottom lies below half the
    level of the contact around it (the object has no material there), and, measured at
    that half level, it is at least one taxel in inradius and round (axes within 2:1, area
    at most 1.9 times its inscribed disk). Its radius is that of the disk of its area at
    the half level. A hole cut by the array's border is not reported.

    Diameter test (the seed's, reported as `diameter_test`): fit a circle to the contact's
    outline; a hole exists if a diameter of it crosses the outline four times. It assumes
    a round object (a washer) and says no for a hole in a plate larger than the array.

    Examples
    --------
    >>> y, x = np.mgrid[:64, :64] - 31.5
    >>> washer = ((np.hypot(x, y) < 24) & (np.hypot(x, y) > 10)).astype(float)
    >>> report = detect_holes(washer, 0.5e-3)
    >>> report.count, report.diameter_test, round(report.items[0].radius_m * 1e3, 1)
    (1, True, 5.0)
    """
    prepared = prepare(image, sensor_or_pitch, **preparation)
    require_square_taxels(prepared.pitch, "the hole tests", prepared.hexagonal)
    holes, _ = _gaps(prepared)
    contours = outline_contours(prepared)
    test = diameter_test(prepared, *outline_taxels(prepared, contours), contours=contours)
    return HoleReport(bool(holes), len(holes), tuple(holes), test)


def detect_slots(
    image: Any, sensor_or_pitch: Any, **preparation: Unpack[Preparation]
) -> SlotReport:
    """Slots in the contact: long gaps with parallel walls.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m], or a sensor description.
    **preparation
        `calibrated`, `smoothing`, `baseline`, `defects`, `noise` and `reference`, passed
        on to `prepare` with its defaults (so that this agrees with `extract`).

    Returns
    -------
    SlotReport

    Notes
    -----
    A basin deeper than half its surroundings (see `detect_holes`) is a slot when it is
    at least 2.5 times as long as wide, its walls are parallel (area at least 0.6 of
    length times its widest span) and, if it reaches the array's border, it does so only
    at its ends. Length is sqrt(12) times the standard deviation along the long axis
    (exact for a rectangle); width is area over length, both at half the surrounding level.
    A texture's basins are no slots: a contact of 3 or more sizeable regions, or with 3 or
    more high points (`texture_measures`) besides up to 4 on the rim of its one slot, which
    are that slot's sharp corners, as `extract` judges it.

    Examples
    --------
    >>> plate = np.ones((64, 64)); plate[28:36, 8:56] = 0.0  # 8 x 48 taxel slot
    >>> slot = detect_slots(plate, 1e-3).items[0]
    >>> round(slot.width_m * 1e3), round(slot.length_m * 1e3), round(float(slot.angle_rad), 3)
    (8, 48, 0.0)
    """
    prepared = prepare(image, sensor_or_pitch, **preparation)
    _, slots = _gaps(prepared)
    return SlotReport(bool(slots), len(slots), tuple(slots))
