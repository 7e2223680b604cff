"""Holes and slots: gaps in a contact that are bounded by the contact (Ellis seed, 2.1).

A *gap* is a connected set of non-contact taxels (4-neighbours, the dual of the contact's
8-neighbours). Gaps are measured at half the surrounding contact level, where a blurred
step crosses the true wall, so radius and width do not shrink with the blur.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import cv2
import numpy as np

from taxel.features._edges import Edges, edges_core
from taxel.features._fitting import circle_fit_core
from taxel.features._image import Prepared, prepare

__all__ = [
    "Hole",
    "HoleReport",
    "Slot",
    "SlotReport",
    "detect_holes",
    "detect_slots",
    "diameter_test",
    "gaps_core",
]

# Smallest gap considered [taxels]: below ~1 taxel of radius a hole is not resolved.
_MIN_GAP_AREA = 3
_MIN_HOLE_INRADIUS = 1.0
# A hole is round: its equivalent-ellipse axes within 2:1, and its area at most 1.9 times the
# largest inscribed disk (a disk gives ~1.2 on a grid; the irregular pores between the
# bumps of a texture give far more).
_HOLE_AXIS_RATIO = 0.5
_HOLE_FILL = 1.9
# A hole lies in a face: the contact around it is at least 0.3 hole radii thick. A thin ring
# around a wide gap is a rim (the top of a drink can), a curved edge rather than a face.
_HOLE_WALL = 0.3
# A slot is at least 2.5 times as long as it is wide (shorter: a hole or a notch), has
# parallel walls (area >= 0.6 of length times its widest span; a wedge-shaped gap gives
# ~0.5) and runs off the array only at its ends (border taxels <= 2.5 widths).
_SLOT_ELONGATION = 2.5
_SLOT_PARALLEL = 0.6
_SLOT_BORDER_WIDTHS = 2.5
# Diameters sampled by the seed's hole test and their extent beyond the fitted radius.
_DIAMETERS = 16
_DIAMETER_REACH = 2.0
_RING = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (7, 7))
_WALL = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (13, 13))


@dataclass(frozen=True)
class Hole:
    """A hole in the contact.

    Attributes
    ----------
    center_index : (float, float)
        Centre as (row, col) taxel indices.
    center_m : (float, float)
        Centre (x, y) in the sensor frame [m].
    radius_m : float
        Radius of the disk with the hole's area at half the surrounding level [m].
    """

    center_index: tuple[float, float]
    center_m: tuple[float, float]
    radius_m: float


@dataclass(frozen=True)
class Slot:
    """A slot: a long gap with parallel walls.

    Attributes
    ----------
    center_index, center_m : (float, float)
        Centre of the visible part (row, col) and (x, y) in the sensor frame [m].
    angle_rad : float
        Direction of the slot's long axis from +x towards +y, in [0, pi) [rad].
    width_m, length_m : float
        Width and visible length [m].
    truncated : bool
        The slot runs off the array, so its true length is at least `length_m`.
    """

    center_index: tuple[float, float]
    center_m: tuple[float, float]
    angle_rad: float
    width_m: float
    length_m: float
    truncated: bool


@dataclass(frozen=True)
class HoleReport:
    """Holes found by the gap test, and the seed's diameter test.

    Attributes
    ----------
    present : bool
        At least one hole by the gap test (enclosed, round, in a face).
    count : int
    items : tuple of Hole
    diameter_test : bool
        The seed's test: some diameter of the circle fitted to all edges crosses 4 edges.
    """

    present: bool
    count: int
    items: tuple[Hole, ...]
    diameter_test: bool


@dataclass(frozen=True)
class SlotReport:
    """Slots found in the contact.

    Attributes
    ----------
    present : bool
    count : int
    items : tuple of Slot
    """

    present: bool
    count: int
    items: tuple[Slot, ...]


def _to_metres(prepared: Prepared, row: float, col: float) -> tuple[float, float]:
    rows, cols = prepared.image.shape
    return (
        float((col - (cols - 1) / 2) * prepared.pitch[1]),
        float((row - (rows - 1) / 2) * prepared.pitch[0]),
    )


def _moments(rows: np.ndarray, cols: np.ndarray, pitch) -> tuple[float, float, float, float]:
    """Centroid (row, col), largest and smallest variance [m^2] and major-axis angle."""
    mean_r, mean_c = float(rows.mean()), float(cols.mean())
    dr, dc = (rows - mean_r) * pitch[0], (cols - mean_c) * pitch[1]
    var_y, var_x = float(dr @ dr) / rows.size, float(dc @ dc) / rows.size
    cov = float(dr @ dc) / rows.size
    half = (var_x + var_y) / 2
    root = math.hypot((var_x - var_y) / 2, cov)
    angle = (0.5 * math.atan2(2 * cov, var_x - var_y)) % math.pi
    return mean_r, mean_c, half + root + pitch[0] * pitch[1] / 12, angle


def gaps_core(prepared: Prepared) -> tuple[list[Hole], list[Slot], np.ndarray]:
    """Holes, slots, and the mask of the gaps they occupy (internal)."""
    shape = prepared.image.shape
    explained = np.zeros(shape, np.uint8)
    if not prepared.present:
        return [], [], explained
    gap = 1 - prepared.mask
    count, labels, stats, _ = cv2.connectedComponentsWithStats(gap, connectivity=4)
    if count <= 1:
        return [], [], explained
    gap_depth = cv2.distanceTransform(gap, cv2.DIST_L2, 3)
    contact_depth = cv2.distanceTransform(prepared.mask, cv2.DIST_L2, 3)
    holes: list[Hole] = []
    slots: list[Slot] = []
    row_pitch, col_pitch = prepared.pitch
    for index in range(1, count):
        left, top, width, height, area = stats[index]
        if area < _MIN_GAP_AREA:
            continue
        border = left == 0 or top == 0 or left + width == shape[1] or top + height == shape[0]
        if border and area > 0.5 * gap.size:
            continue  # the free space around a contact, not a gap in it
        margin = 6 + int(max(width, height)) // 2
        r0, r1 = max(top - margin, 0), min(top + height + margin, shape[0])
        c0, c1 = max(left - margin, 0), min(left + width + margin, shape[1])
        own = labels[r0:r1, c0:c1] == index
        inradius = float(gap_depth[r0:r1, c0:c1][own].max())
        # measure at half the surrounding contact level (see the module notes)
        grown = cv2.dilate(own.view(np.uint8), _RING).view(bool)
        window = prepared.smooth[r0:r1, c0:c1]
        # the wall's level is read up to 6 taxels out, past the blurred transition
        wall = cv2.dilate(own.view(np.uint8), _WALL).view(bool) & (prepared.mask[r0:r1, c0:c1] > 0)
        if not wall.any():
            continue
        level = float(np.percentile(window[wall], 90))
        half = prepared.baseline + 0.5 * (level - prepared.baseline)
        rows, cols = np.nonzero(grown & (window < half))
        if rows.size < _MIN_GAP_AREA:
            continue
        mean_r, mean_c, major_var, angle = _moments(rows + r0, cols + c0, prepared.pitch)
        gap_area = rows.size * row_pitch * col_pitch
        centre_m = _to_metres(prepared, mean_r, mean_c)
        pitch = math.sqrt(row_pitch * col_pitch)
        length = math.sqrt(12.0 * major_var)
        if not border and inradius >= _MIN_HOLE_INRADIUS:
            radius = math.sqrt(gap_area / math.pi)
            minor_var = max(
                float(np.var(rows)) * row_pitch**2 + float(np.var(cols)) * col_pitch**2
                - major_var + pitch**2 / 6,
                0.0,
            )  # fmt: skip
            round_enough = math.sqrt(minor_var / major_var) >= _HOLE_AXIS_RATIO
            filled = area / (math.pi * (inradius + 0.5) ** 2) <= _HOLE_FILL
            wall_thickness = 2.0 * float(contact_depth[r0:r1, c0:c1].max()) * pitch
            if round_enough and filled and wall_thickness >= _HOLE_WALL * radius:
                holes.append(Hole((mean_r, mean_c), centre_m, radius))
                explained[r0:r1, c0:c1][grown] = 1
                continue
        span = 2.0 * (inradius + 0.5) * pitch
        slot_width = gap_area / length
        if length < _SLOT_ELONGATION * slot_width or gap_area < _SLOT_PARALLEL * length * span:
            continue
        if border:
            on_border = int(
                own[0].sum() * (r0 == 0)
                + own[-1].sum() * (r1 == shape[0])
                + own[:, 0].sum() * (c0 == 0)
                + own[:, -1].sum() * (c1 == shape[1])
            )
            if on_border * pitch > _SLOT_BORDER_WIDTHS * slot_width:
                continue
        slots.append(Slot((mean_r, mean_c), centre_m, angle, slot_width, length, bool(border)))
        explained[r0:r1, c0:c1][grown] = 1
    return holes, slots, explained


def diameter_test(prepared: Prepared, edges: Edges) -> bool:
    """The seed's hole test on a prepared image and its edges (internal core).

    Fits a circle to all edge taxels and walks 16 diameters of it across 2 radii each
    way (the fit to both rims of a washer lies between them): a hole is present when
    some diameter crosses the contact's outline 4 times, twice on each side of the fitted
    centre (object rim, hole rim), with the centre off contact. Crossings are counted on the
    contact mask rather than on the thin Canny edges, which a sampled line can slip
    between at a diagonal.
    """
    if edges.rows.size < 8:
        return False
    fit = circle_fit_core(edges.cols.astype(float), edges.rows.astype(float))
    shape = prepared.mask.shape
    if not math.isfinite(fit.radius_m) or fit.radius_m < 2 or fit.radius_m > 2 * max(shape):
        return False
    centre_c, centre_r = fit.center_m
    steps = np.arange(-_DIAMETER_REACH * fit.radius_m, _DIAMETER_REACH * fit.radius_m, 0.5)
    angles = np.arange(_DIAMETERS) * (math.pi / _DIAMETERS)
    cols = np.rint(centre_c + np.cos(angles)[:, None] * steps).astype(int)
    rows = np.rint(centre_r + np.sin(angles)[:, None] * steps).astype(int)
    inside = (rows >= 0) & (rows < shape[0]) & (cols >= 0) & (cols < shape[1])
    touched = np.zeros(rows.shape, bool)
    touched[inside] = prepared.mask[rows[inside], cols[inside]] > 0
    middle = steps.size // 2
    before = np.count_nonzero(np.diff(touched[:, : middle + 1], axis=1), axis=1)
    after = np.count_nonzero(np.diff(touched[:, middle:], axis=1), axis=1)
    return bool(np.any((before == 2) & (after == 2) & ~touched[:, middle]))


def detect_holes(image: Any, sensor_or_pitch: Any, *, smoothing: float = 1.0) -> HoleReport:
    """Holes in the contact, by the gap test and by the seed's diameter test.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m].
    smoothing : float, default 1.0
        Gaussian sigma [taxels].

    Returns
    -------
    HoleReport

    Notes
    -----
    Gap test (decides `present`): a gap is a hole when it is enclosed by contact (it does
    not reach the array's border), at least one taxel in inradius, round (axes within 2:1,
    area at most 1.9 times its inscribed disk) and lies in a face (the surrounding contact
    is at least 0.3 hole radii thick). Its radius comes from its area at half the
    surrounding contact level. A hole cut by the array's border is not reported.

    Diameter test (the seed's, reported as `diameter_test`): fit a circle to all edges; a
    hole exists if a diameter of it crosses four edges. It assumes a round object (a
    washer) and says no for a hole in a plate larger than the array.

    Examples
    --------
    >>> y, x = np.mgrid[:64, :64] - 31.5
    >>> washer = ((np.hypot(x, y) < 24) & (np.hypot(x, y) > 10)).astype(float)
    >>> report = detect_holes(washer, 0.5e-3)
    >>> report.count, report.diameter_test, round(report.items[0].radius_m * 1e3, 1)
    (1, True, 5.0)
    """
    prepared = prepare(image, sensor_or_pitch, smoothing=smoothing)
    holes, _, _ = gaps_core(prepared)
    edges = edges_core(prepared)
    return HoleReport(bool(holes), len(holes), tuple(holes), diameter_test(prepared, edges))


def detect_slots(image: Any, sensor_or_pitch: Any, *, smoothing: float = 1.0) -> SlotReport:
    """Slots in the contact: long gaps with parallel walls.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m].
    smoothing : float, default 1.0
        Gaussian sigma [taxels].

    Returns
    -------
    SlotReport

    Notes
    -----
    A gap is a slot when it is at least 2.5 times as long as wide, its walls are parallel
    (area at least 0.6 of length times its widest span) and, if it reaches the array's
    border, it does so only at its ends. Length is sqrt(12) times the standard deviation
    along the long axis (exact for a rectangle); width is area over length, both measured
    at half the surrounding contact level.

    Examples
    --------
    >>> plate = np.ones((64, 64)); plate[28:36, 8:56] = 0.0  # 8 x 48 taxel slot
    >>> slot = detect_slots(plate, 1e-3).items[0]
    >>> round(slot.width_m * 1e3), round(slot.length_m * 1e3), round(float(slot.angle_rad), 3)
    (8, 48, 0.0)
    """
    prepared = prepare(image, sensor_or_pitch, smoothing=smoothing)
    _, slots, _ = gaps_core(prepared)
    return SlotReport(bool(slots), len(slots), tuple(slots))
