"""Holes and slots: gaps in a contact that are bounded by the contact (Ellis seed, 2.1).

Where an object has no material (a hole, a slot), the surface pressure is zero; under the
cover the pressure at the sensing depth dips there, to a fraction of the surrounding level
that falls as the gap widens compared with the depth (to ~0.2-0.3 for a gap 3-4 depths
across). A shallow dimple of the pressure, by contrast, comes from a face that is only
less pressed there. So a *gap* is a dark basin enclosed by contact, most of it pressing
clearly (at the contact's seed level, see `prepare`), whose bottom lies below half the
level of the contact around it, and it is measured at that half level, where a
blurred step crosses the true wall, so radius and width do not shrink with the blur.

Basins are found as the outer outlines of the non-contact regions at three levels of the
smoothed image (50 % and 25 % of the contrast, then the contact threshold), so that a hole
in a dome-shaped contact (a gently convex plate) is enclosed at some level even where its
surroundings press less than the contact's peak. The highest level is tried first: a slot
whose floor is not equally deep all along is one basin there, and the pieces it may break
into at lower levels are then already explained. A gap refused there as too near the
array's border explains the smaller basins of its floor in the same way.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import cast

import cv2
import numpy as np

from taxel.features._basins import MIN_GAP_AREA, SLOT_BORDER_WIDTHS, SLOT_ELONGATION, basins
from taxel.features._image import K_HIGH, Prepared
from taxel.features._moments import binary_moments
from taxel.features._record import record

__all__ = ["Hole", "HoleReport", "Slot", "SlotReport", "gaps_core"]

# A basin holds a gap when its bottom lies below this fraction of the surrounding level.
_DIP = 0.5
# A gap lies in a face: at least half the ring 2-6 taxels around it presses as clearly as a
# contact's seed (`prepared.high`, see `prepare`), or at or above the gap's own half level
# (where a blurred step crosses its true wall) and the noise floor of a seed (K_HIGH
# sigmas). Judged against the gap's own wall, a plate pressing less toward the array's
# border still makes a face around its hole; a narrow ridge (a can's rim, a box edge)
# leaves most of the ring off the contact either way; and in the noisy fringe of a weak
# contact, where noise alone can enclose a dark patch, the ring clears neither. In a
# texture every valley is ringed by bumps at their own level: there only the seed's level
# makes a face.
_FACE = 0.5
# A hole is round: its equivalent-ellipse axes within 2:1, and its area at most 1.9 times the
# largest inscribed disk (a disk gives ~1.2 on a grid; the irregular valleys between the
# bumps of a texture give far more).
_HOLE_AXIS_RATIO = 0.5
_HOLE_FILL = 1.9
# A slot is at least 2.5 times as long as it is wide and runs off the array only at its
# ends (see `taxel.features._basins`), and has parallel walls (area >= 0.6 of length times
# its widest span; a wedge-shaped gap gives ~0.5).
_SLOT_PARALLEL = 0.6
# In a texture (many separate high points) the dark basins between them are the valleys of
# the surface, not missing material; they are holes only when they make a perforated sheet:
# 3 or more holes of equal size (radii within 15 %, as punched) in an evenly pressed sheet
# (around the median hole, the 10th percentile of the contact level >= half its 90th).
_SHEET_HOLES = 3
_SHEET_SPREAD = 0.15
_SHEET_EVENNESS = 0.5
# A sheet's holes are punched on a grid, each beside its neighbours: the 3 or more holes
# must each have another within 3 of their mean diameters, centre to centre (a web at most
# twice as wide as a hole, 9 % open area on a square grid; perforated sheets have more,
# and a sheet seen in part may lack a hole, which puts a neighbour 2 pitches away). The
# valleys of a texture that pass for holes lie scattered, farther apart.
_SHEET_PITCH = 3.0
# A hole must be seen all round: a gap closer to the array's border than the cover is deep
# (and than 2 taxels) cannot be told from a notch, since its wall on that side is blurred
# into the array's edge.
_BORDER_TAXELS = 2.0
_GROW = np.ones((7, 7), np.uint8)
# A gap too near the border to be judged (see `_BORDER_TAXELS`) is still a gap: a basin it
# holds at a lower level is read again, but it is that gap only if it reads as large as
# it (at least half its area: the half level's reading does not depend on the level the
# basin was found at). A smaller reading is the gap's floor, whose ring lies on the gap's
# own flanks, lower than the contact around it: read alone, it seems a small hole clear
# of the border.
_SAME_GAP = 0.5
# A basin's wall is read up to this many taxels from it.
_REACH = 6


@record
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


@record
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


@record
class HoleReport:
    """Holes found by the gap test, and the seed's diameter test.

    Attributes
    ----------
    present : bool
        At least one hole by the gap test (enclosed, deep, round, resolved).
    count : int
    items : tuple of Hole
    diameter_test : bool
        The seed's test: some diameter of the circle fitted to the contact's outline
        crosses it 4 times.
    """

    present: bool
    count: int
    items: tuple[Hole, ...]
    diameter_test: bool


@record
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


def _reaches_border(box: Sequence[int], r0: int, c0: int, shape: tuple[int, int]) -> bool:
    """Whether a region touches the array's border, from its bounding box in a window.

    `box` is the region's (left, top, width, height) in the window whose corner is at
    row `r0`, column `c0` of the array (an empty region has width 0).
    """
    left, top, width, height = box
    return width > 0 and (
        r0 + top == 0
        or c0 + left == 0
        or r0 + top + height == shape[0]
        or c0 + left + width == shape[1]
    )


def _moments_of_old(
    region: np.ndarray,
    bounds: tuple[int, int, int, int],
    contour: np.ndarray,
    shape: tuple[int, int],
) -> tuple[dict, int, int]:
    """Moments of a window's region, taken in the gap test's original, wider window.

    The region, in the window of rows r0:r1 and columns c0:c1 (`bounds`), is measured as
    if placed in the window the gap test was written with (margin 6 taxels plus half the
    basin's size): the moments' rounding depends on their origin, so the results stay the
    same bit for bit. Returns the moments and the wider window's corner (row, column).
    """
    r0, _, c0, _ = bounds
    left, top, width, height = cv2.boundingRect(contour)
    margin = _REACH + max(width, height) // 2
    wide_r0, wide_c0 = max(top - margin, 0), max(left - margin, 0)
    return binary_moments(region, r0 - wide_r0, c0 - wide_c0), wide_r0, wide_c0


def _clearance(box: Sequence[int], r0: int, c0: int, shape: tuple[int, int]) -> int:
    """Taxels between a region and the array's border (0 if it touches it).

    `box` is the region's (left, top, width, height) in the window whose corner is at
    row `r0`, column `c0` of the array.
    """
    left, top, width, height = box
    rows, cols = shape
    return min(c0 + left, r0 + top, cols - c0 - left - width, rows - r0 - top - height)


def _half_levels(window: np.ndarray, wall: np.ndarray, baseline: float, half: float) -> np.ndarray:
    """The half level at each taxel of a window, following the trend of the wall around it.

    A blurred step crosses half of its *own* height at the true wall. When the contact
    around a gap falls from one side to the other (a gently convex plate, or a face
    pressing less toward the array's edge, beyond which the cover bears no load), half the
    level of the whole wall lies too high on the weak side, and the gap seems to reach
    toward it. So the half level `half` (of the whole wall) is scaled by the plane fitted
    through the wall (least squares on the `wall` taxels, above `baseline`) over the wall's
    mean: a plane follows the slow fall-off of the face, not the texture or noise of the
    wall. Returns the levels as a (rows, 1) + (1, cols) broadcast sum.
    """
    mask = wall.view(np.uint8)
    moments = cv2.moments(mask, binaryImage=True)
    raised = cv2.moments(np.multiply(window - np.float32(baseline), mask, dtype=np.float32))
    count, total = moments["m00"], raised["m00"]
    centre_c, centre_r = moments["m10"] / count, moments["m01"] / count
    # the plane's slopes from the normal equations, about the wall's centroid
    along_c = raised["m10"] - centre_c * total
    along_r = raised["m01"] - centre_r * total
    xx, xy, yy = moments["mu20"], moments["mu11"], moments["mu02"]
    det = xx * yy - xy * xy
    slope_c = (yy * along_c - xy * along_r) / det if det > 0 else 0.0
    slope_r = (xx * along_r - xy * along_c) / det if det > 0 else 0.0
    # half level = baseline + (half - baseline) * plane / mean, mean = total / count
    factor = (half - baseline) * count / max(total, 1e-30)
    rows, cols = window.shape
    by_col = (np.arange(cols, dtype=np.float32) - np.float32(centre_c)) * np.float32(
        factor * slope_c
    )
    by_row = (np.arange(rows, dtype=np.float32) - np.float32(centre_r)) * np.float32(
        factor * slope_r
    ) + np.float32(half)
    return by_row[:, None] + by_col[None, :]


def _measure(
    prepared: Prepared, contour: np.ndarray, level: float, textured: bool
) -> tuple[Hole | Slot | bool, tuple[slice, slice], np.ndarray, float] | None:
    """Decide whether one basin holds a hole or a slot, and measure it.

    `textured`: the contact is a texture (see `_FACE`). Returns None when the basin holds
    no gap; else the hole or slot, or else whether the gap was refused as too near the
    array's border only (True; False for a gap of no hole's or slot's shape), with where it
    was read, the gap's region there and the evenness of its wall.
    """
    shape = prepared.image.shape
    left, top, width, height = cv2.boundingRect(contour)
    # everything below is read within 6 taxels of the basin (the wall's ring): a window
    # that wide around it holds it all (distances to the basin do not depend on the
    # window, as long as it holds the basin)
    r0, r1 = max(top - _REACH, 0), min(top + height + _REACH, shape[0])
    c0, c1 = max(left - _REACH, 0), min(left + width + _REACH, shape[1])
    window = prepared.smooth[r0:r1, c0:c1]
    own = np.zeros(window.shape, np.uint8)
    cv2.drawContours(own, [contour], -1, 1, thickness=-1, offset=(-c0, -r0))
    bottom = cv2.minMaxLoc(window, own)[0]
    # distance of every window taxel from the basin: the wall is read 2-6 taxels out,
    # past the blurred transition, and the gap grown up to 3 taxels to the half level
    away = cv2.distanceTransform(1 - own, cv2.DIST_L2, 3)
    ring = (away > 2.0) & (away <= float(_REACH))
    wall = ring & (window >= level)
    if not np.count_nonzero(wall):
        return None
    ring_size = cv2.countNonZero(ring.view(np.uint8))
    seeded = (
        cv2.countNonZero((ring & (window >= prepared.high)).view(np.uint8)) >= _FACE * ring_size
    )
    if textured and not seeded:
        return None  # no face around it: the valleys of a texture
    values = window[wall]
    tenth, ninetieth = (values.size - 1) // 10, (values.size - 1) * 9 // 10
    values.partition((tenth, ninetieth))  # in place: `values` is a copy already
    surround = float(values[ninetieth])
    evenness = (float(values[tenth]) - prepared.baseline) / max(
        surround - prepared.baseline, 1e-30
    )
    half = prepared.baseline + _DIP * (surround - prepared.baseline)
    if not seeded:  # (not textured) a face at the gap's own level, clear of the noise?
        face = max(half, prepared.baseline + K_HIGH * prepared.noise)
        if cv2.countNonZero((ring & (window >= face)).view(np.uint8)) < _FACE * ring_size:
            return None  # no face around it (a ridge, a noisy fringe)
    if bottom > half:
        return None  # a dimple of the pressure, not a gap in the contact
    near = away <= 3.0
    region = (near & (window < half)).view(np.uint8)
    box = cv2.boundingRect(region)
    row_pitch, col_pitch = prepared.pitch
    pitch = math.sqrt(row_pitch * col_pitch)
    edge = max(_BORDER_TAXELS, prepared.cover_depth / pitch)
    if _clearance(box, r0, c0, shape) < edge:
        # near the array's edge, where the face may press less: read the gap at the half
        # level of its wall's trend (see `_half_levels`)
        levels = _half_levels(window, wall, prepared.baseline, half)
        region = (near & (window < levels)).view(np.uint8)
        box = cv2.boundingRect(region)
    # (the filled outline's bounding box is the outline's)
    if _reaches_border(box, r0, c0, shape) and not _reaches_border(
        (left - c0, top - r0, width, height), r0, c0, shape
    ):
        # the face itself falls below the half level toward the array's edge (a pad
        # presses less at its rim): measure the gap where it is enclosed instead
        region = own & (window < half).view(np.uint8)
        box = cv2.boundingRect(region)
    moments, origin_r, origin_c = _moments_of_old(region, (r0, r1, c0, c1), contour, shape)
    area = moments["m00"]
    where = (slice(r0, r1), slice(c0, c1))
    if area < MIN_GAP_AREA:
        return False, where, region, evenness
    mean_r, mean_c = moments["m01"] / area + origin_r, moments["m10"] / area + origin_c
    var_y = (moments["mu02"] / area + 1 / 12) * row_pitch**2
    var_x = (moments["mu20"] / area + 1 / 12) * col_pitch**2
    cov = moments["mu11"] / area * row_pitch * col_pitch
    root = math.hypot((var_x - var_y) / 2, cov)
    major, minor = (var_x + var_y) / 2 + root, max((var_x + var_y) / 2 - root, 0.0)
    angle = (0.5 * math.atan2(2 * cov, var_x - var_y)) % math.pi
    rows, cols = shape
    centre_m = (
        float((mean_c - (cols - 1) / 2) * col_pitch),
        float((mean_r - (rows - 1) / 2) * row_pitch),
    )
    gap_area = area * row_pitch * col_pitch
    inradius = cv2.minMaxLoc(cv2.distanceTransform(region, cv2.DIST_L2, 3))[1]
    border = _reaches_border(box, r0, c0, shape)
    if not border and _clearance(box, r0, c0, shape) >= edge:
        round_enough = math.sqrt(minor / major) >= _HOLE_AXIS_RATIO
        filled = area / (math.pi * (inradius + 0.5) ** 2) <= _HOLE_FILL
        if round_enough and filled and inradius >= 1.0:
            hole = Hole((mean_r, mean_c), centre_m, math.sqrt(gap_area / math.pi))
            return hole, where, region, evenness
    length = math.sqrt(12.0 * major)
    slot_width = gap_area / length
    span = 2.0 * (inradius + 0.5) * pitch
    if length < SLOT_ELONGATION * slot_width or gap_area < _SLOT_PARALLEL * length * span:
        return border or _clearance(box, r0, c0, shape) < edge, where, region, evenness
    if border:
        on_border = int(
            region[0].sum() * (r0 == 0)
            + region[-1].sum() * (r1 == rows)
            + region[:, 0].sum() * (c0 == 0)
            + region[:, -1].sum() * (c1 == cols)
        )
        if on_border * pitch > SLOT_BORDER_WIDTHS * slot_width:
            return False, where, region, evenness
    slot = Slot((mean_r, mean_c), centre_m, angle, slot_width, length, bool(border))
    return slot, where, region, evenness


def _perforated(holes: list[Hole], evenness: list[float]) -> bool:
    """Whether the holes of a texture make a perforated sheet (see the module constants)."""
    if len(holes) < _SHEET_HOLES:
        return False
    radii = np.array([hole.radius_m for hole in holes])
    centres = np.array([hole.center_m for hole in holes])
    apart = np.hypot(*(centres[:, None, :] - centres[None, :, :]).transpose(2, 0, 1))
    np.fill_diagonal(apart, np.inf)
    beside = apart.min(axis=1) <= _SHEET_PITCH * 2.0 * float(radii.mean())
    if np.count_nonzero(beside) < _SHEET_HOLES:
        return False
    middle = len(holes) // 2
    even = float(np.partition(np.array(evenness), middle)[middle])
    return float(radii.std()) <= _SHEET_SPREAD * float(radii.mean()) and even >= _SHEET_EVENNESS


# holes, slots, and the mask of the gaps they occupy (None without a gap)
GapsFound = tuple[list[Hole], list[Slot], np.ndarray | None]


def gaps_core(prepared: Prepared, *, textured: bool = False) -> GapsFound:
    """Holes, slots, and the mask of the gaps they occupy (internal).

    `textured`: the contact is a texture (see `_textured.judged_gaps`); its basins are then
    holes only when they make a perforated sheet, and never slots. The mask (uint8) is
    None when no gap was found (most contacts: it is made with the first gap).
    """
    explained: np.ndarray | None = None
    holes: list[Hole] = []
    slots: list[Slot] = []
    evenness: list[float] = []
    if not prepared.present:
        return holes, slots, explained
    # the gaps refused as too near the border (numbered from 1), once there is one, and
    # their areas (see `_SAME_GAP`)
    refused: np.ndarray | None = None
    refused_areas = [0.0]
    for contour, level in basins(prepared):
        within = 0  # the refused gap the basin lies in, if any
        if explained is not None or refused is not None:  # one explained higher up is done
            moments = cv2.moments(contour)
            if moments["m00"] > 0:
                col, row = moments["m10"] / moments["m00"], moments["m01"] / moments["m00"]
                at = int(round(row)), int(round(col))
                if explained is not None and explained[at]:
                    continue
                if refused is not None:
                    within = int(refused[at])
        measured = _measure(prepared, contour, level, textured)
        if measured is None:
            continue
        found, where, region, even = measured
        if within and cv2.countNonZero(region) < _SAME_GAP * refused_areas[within]:
            continue  # the floor of a gap refused at a higher level
        if isinstance(found, bool):
            if found:  # too near the border: keep it, for the basins it holds
                if refused is None:
                    refused = np.zeros(prepared.image.shape, np.int32)
                refused[where][cv2.dilate(region, _GROW) > 0] = len(refused_areas)
                refused_areas.append(float(cv2.countNonZero(region)))
            continue
        if isinstance(found, Hole):
            holes.append(found)
            evenness.append(even)
        elif not textured:
            slots.append(found)
        if explained is None:
            explained = np.zeros(prepared.image.shape, np.uint8)
        explained[where] |= cast(np.ndarray, cv2.dilate(region, _GROW))  # uint8, as region
    if textured and not _perforated(holes, evenness):
        holes = []
    return holes, slots, explained
