"""Measures of the main contact region that the contact type is decided from (internal)."""

from __future__ import annotations

import math

import cv2
import numpy as np

from taxel.features._contact import Contact, region_moments, signal_moments
from taxel.features._fitting import (
    CircleFit,
    LineFit,
    fit_line_and_circle,
    line_circle_and_distances,
)
from taxel.features._image import Prepared
from taxel.features._moments import binary_moments
from taxel.features._outline import lobes
from taxel.features._window import contact_box, contact_window

__all__ = [
    "band_fits",
    "half_region",
    "region_measures",
    "signal_elongation",
    "three_lobes",
    "to_metres_circle",
    "to_metres_line",
]

# A saturated image is flat-topped: its top 10 % covers at least a third of its
# half-maximum area (a Gaussian's covers 15 %, a blurred dome's ~20-25 %).
_FLAT_TOP = 1.0 / 3.0
# A Gaussian's half-maximum width is 2 sqrt(2 ln 2) = 2.355 of its sigma.
_FWHM_PER_SIGMA = 2.0 * math.sqrt(2.0 * math.log(2.0))
# A band's taxels lie within half its thickness of its centre line or arc. Taxels farther
# than 0.75 thicknesses from the fitted curve (half a thickness, plus as much again for the
# first fit's own error) are a spur: the remains of a glass scratch or a noise ridge that
# joins the band where it crosses it, and pull the circle's radius by several per cent.
# They are left out and the band refitted, at most three times.
_SPUR_DISTANCE = 0.75
_SPUR_PASSES = 3
# Fewer taxels than this left on the curve: keep the fit of the whole region.
_SPUR_MIN_TAXELS = 10


def _main_region(prepared: Prepared, contact: Contact) -> np.ndarray:
    """The mask (uint8) of the largest region."""
    if prepared.n_regions == 1:
        return prepared.mask
    counts = np.bincount(prepared.labels.ravel(), minlength=prepared.n_regions + 1)
    counts[0] = 0
    return (prepared.labels == int(np.argmax(counts))).view(np.uint8)


def half_region(
    prepared: Prepared, main: np.ndarray
) -> tuple[np.ndarray, tuple[int, int], float, bool, dict]:
    """The main region above half its peak: mask, origin, major axis [taxels], flatness, moments.

    The region is taken on the unsmoothed image at half its own peak, so that the
    smoothing does not widen it; flatness is judged on the smoothed image, against noise.
    Its mask covers the contact's window (see `contact_window`), whose first taxel is at
    `origin` (column, row); the moments are the region's binary ones, as `cv2.moments`
    gives them on the whole image.
    """
    # everything is read in the contact's window: `main` is 0 outside it
    window = contact_window(prepared)
    # with one region, the contact's own peak, if `contact_regions` read it already
    peak = prepared.memo.get("peak") if main is prepared.mask else None
    image, smooth, main = prepared.image[window], prepared.smooth[window], main[window]
    top, left = window[0].start, window[1].start
    if peak is None:
        peak = cv2.minMaxLoc(image, main)[1]
    region = (image >= 0.5 * (prepared.baseline + peak)).view(np.uint8) & main
    # with one region, the smoothed image's peak is the contact's
    highest = prepared.peak if prepared.n_regions == 1 else cv2.minMaxLoc(smooth, main)[1]
    span = highest - prepared.baseline
    moments = binary_moments(region, top, left)
    count = moments["m00"]
    if count == 0:
        return region, (left, top), 0.0, False, moments
    half_area = cv2.countNonZero((smooth >= prepared.baseline + 0.5 * span).view(np.uint8) & main)
    top_area = cv2.countNonZero((smooth >= prepared.baseline + 0.9 * span).view(np.uint8) & main)
    var_y, var_x = moments["mu02"] / count + 1 / 12, moments["mu20"] / count + 1 / 12
    root = math.hypot((var_x - var_y) / 2, moments["mu11"] / count)
    flat = top_area >= _FLAT_TOP * max(half_area, 1)
    return region, (left, top), 4.0 * math.sqrt((var_x + var_y) / 2 + root), flat, moments


def signal_elongation(prepared: Prepared, main: np.ndarray) -> float:
    """Length over width of the region's unsmoothed signal, the cover's blur taken out.

    The signal's equivalent ellipse (its weighted second moments) is the pressure's
    convolved with the cover's response and sampled by the taxels, whose variances add:
    each axis loses the blur's (a Gaussian of the blur's half-maximum width) and a taxel's
    (1/12). What is left across is at least a taxel's own (1/12): the narrowest width the
    array tells. 0 when the region carries no signal.
    """
    moments = signal_moments(prepared, main)
    total = moments["m00"]
    if not total > 0:
        return 0.0
    xx, yy, xy = moments["mu20"] / total, moments["mu02"] / total, moments["mu11"] / total
    spread = math.hypot((xx - yy) / 2, xy)
    blurred = (prepared.blur / prepared.mean_pitch / _FWHM_PER_SIGMA) ** 2 + 1 / 12
    along = (xx + yy) / 2 + spread - blurred
    across = max((xx + yy) / 2 - spread - blurred, 1 / 12)
    return math.sqrt(max(along, 0.0) / across)


def band_fits(
    prepared: Prepared, main: np.ndarray, thickness: float
) -> tuple[LineFit, CircleFit, float]:
    """Weighted centre line and circle of a band (taxel units), and its length [taxels].

    `thickness`: the band's thickness [taxels] (see `region_measures`); taxels farther
    from the fitted curve than `_SPUR_DISTANCE` thicknesses are left out (see there).
    """
    # the band's taxels in row-major order, as np.nonzero gives them, found in the
    # contact's window (`main` is 0 outside it; whole rows, so x needs no shift)
    window = contact_window(prepared)
    _, weighted = region_moments(prepared, main)  # the moments of the same weights
    main = main[window]
    points = cv2.findNonZero(main).reshape(-1, 2).T.astype(float, order="C")
    x, y = points[0], points[1]  # (indexed: unpacking an array costs more)
    y += window[0].start
    weight = prepared.smooth[window][main.view(bool)] - np.float32(prepared.baseline)
    np.maximum(weight, 1e-12, out=weight)
    weight = weight.astype(float)
    line, circle, squared = line_circle_and_distances(x, y, weight, weighted)
    reach = _SPUR_DISTANCE * thickness
    # the circle's squared distances are at hand: a band without spurs costs one look
    if squared is None or cv2.minMaxLoc(squared)[1] > reach * reach:
        line, circle, x, y = _without_spurs(x, y, weight, line, circle, reach)
    along = math.cos(line.angle_rad) * x
    along += math.sin(line.angle_rad) * y
    return line, circle, float(np.maximum.reduce(along) - np.minimum.reduce(along)) + 1.0


def _distance_from_fit(
    x: np.ndarray, y: np.ndarray, line: LineFit, circle: CircleFit
) -> np.ndarray:
    """Distance [taxels] of each point from the fitted circle, or the line without one."""
    if math.isfinite(circle.radius_m):
        # cv2.magnitude: a quarter of np.hypot's time, on a band's thousands of taxels
        magnitude = cv2.magnitude(x - circle.center_m[0], y - circle.center_m[1])
        distance: np.ndarray = np.asarray(magnitude, dtype=float).ravel()
        distance -= circle.radius_m
    else:
        distance = math.cos(line.angle_rad) * y
        distance -= math.sin(line.angle_rad) * x
        distance -= line.offset_m
    return np.abs(distance, out=distance)


def _without_spurs(
    x: np.ndarray,
    y: np.ndarray,
    weight: np.ndarray,
    line: LineFit,
    circle: CircleFit,
    reach: float,
) -> tuple[LineFit, CircleFit, np.ndarray, np.ndarray]:
    """The band's fits refitted without its points beyond `reach`, and the points kept.

    See `_SPUR_DISTANCE`; `reach` is that many band thicknesses [taxels].
    """
    kept = None
    for _ in range(_SPUR_PASSES):
        # every taxel is measured against each new fit: one cut by a poor first fit returns
        distance = _distance_from_fit(x, y, line, circle)
        if cv2.minMaxLoc(distance)[1] <= reach:
            break
        near = distance <= reach
        if np.count_nonzero(near) < _SPUR_MIN_TAXELS:
            break
        if kept is not None and np.array_equal(near, kept):
            break
        kept = near
        line, circle = fit_line_and_circle(x[near], y[near], weight[near])
    if kept is not None:
        x, y = x[kept], y[kept]
    return line, circle, x, y


def to_metres_line(fit: LineFit, prepared: Prepared) -> LineFit:
    """A line fitted in taxel indices, in the sensor frame [m] (square taxels assumed)."""
    rows, cols = prepared.image.shape
    pitch = prepared.mean_pitch
    cx, cy = (cols - 1) / 2, (rows - 1) / 2
    offset = fit.offset_m + math.sin(fit.angle_rad) * cx - math.cos(fit.angle_rad) * cy
    return LineFit(fit.angle_rad, offset * pitch, fit.rms_m * pitch, fit.n_points)


def to_metres_circle(fit: CircleFit, prepared: Prepared) -> CircleFit:
    rows, cols = prepared.image.shape
    pitch = prepared.mean_pitch
    if not math.isfinite(fit.radius_m):
        return fit
    centre = (
        (fit.center_m[0] - (cols - 1) / 2) * pitch,
        (fit.center_m[1] - (rows - 1) / 2) * pitch,
    )
    return CircleFit(centre, fit.radius_m * pitch, fit.rms_m * pitch, fit.n_points)


def region_measures(
    prepared: Prepared, contact: Contact
) -> tuple[np.ndarray, float, float, float]:
    """Main region mask, its thickness and area [taxels], and its concentration."""
    main = _main_region(prepared, contact)
    left, top, width, height = (
        contact_box(prepared) if main is prepared.mask else cv2.boundingRect(main)
    )
    box = main[max(top - 1, 0) : top + height + 1, max(left - 1, 0) : left + width + 1]
    inscribed = cv2.minMaxLoc(cv2.distanceTransform(box, cv2.DIST_L2, 3))[1]
    thickness = 2.0 * float(inscribed) + 1.0  # [taxels]; +1: taxel centres, not edges
    binary, weighted = region_moments(prepared, main)
    spread = (binary["mu20"] + binary["mu02"]) / max(binary["m00"], 1e-30)
    concentration = (weighted["mu20"] + weighted["mu02"]) / max(weighted["m00"], 1e-30)
    concentration = concentration / spread if spread > 0 else 0.0
    return main, thickness, float(binary["m00"]), float(concentration)


def three_lobes(
    prepared: Prepared,
    half: np.ndarray,
    moments: dict | None = None,
    origin: tuple[int, int] = (0, 0),
) -> float:
    """3rd harmonic of the outline of the main region above half its peak.

    `moments`: the region's binary moments, if already computed (see `half_region`);
    `origin`: where the first taxel of `half` lies in the image (column, row).
    """
    outlines, _ = cv2.findContours(half, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE, offset=origin)
    if not outlines:
        return 0.0
    if moments is None:
        moments = binary_moments(half, origin[1], origin[0])
    centre = (moments["m10"] / moments["m00"], moments["m01"] / moments["m00"])
    return lobes(max(outlines, key=len), centre, 3)
