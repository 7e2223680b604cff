"""Basins: the non-contact regions of a contact at several levels, that may hold a gap.

Helper of `taxel.features._gaps`: the outer outlines of the non-contact regions at three
levels of the smoothed image (50 % and 25 % of the contrast, then the contact threshold),
with cheap tests on each outline alone.

The outlines are traced in the contact's box grown by 1 taxel when that gives the same
basins, which is the usual case (see `_window`): every taxel above the level lies in the
box, so the grown box's ring (where it is not the array's border) is non-contact and joined
to the rest of the array; a region reaching the ring continues out of the box, along the
array's border. Such a region meets the border over a whole side of the array and more,
too long a run for a slot's end, so it is never a basin: in the box it is dropped, and
every other region lies in the box whole, so its outline is the same there.
"""

from __future__ import annotations

import math

import cv2
import numpy as np

from taxel.features._image import WHOLE_IMAGE, Prepared, contact_box

__all__ = ["MIN_GAP_AREA", "SLOT_BORDER_WIDTHS", "SLOT_ELONGATION", "basins"]

# Levels, besides the contact threshold, at which basins are searched [fraction of contrast].
_LEVELS = (0.25, 0.5)
# Smallest gap considered: a disk of one taxel's radius at the half level [taxels^2].
MIN_GAP_AREA = math.pi
# A slot is at least 2.5 times as long as it is wide (shorter: a hole or a notch) and runs
# off the array only at its ends (border taxels <= 2.5 widths).
SLOT_ELONGATION = 2.5
SLOT_BORDER_WIDTHS = 2.5
# At most this many basins are measured per level, largest first (a texture has hundreds of
# tiny ones; the gaps an object's shape makes are among the largest).
_MAX_BASINS = 24


def _shortest_frame_run(box: tuple[int, int, int, int], shape: tuple[int, int]) -> int:
    """Fewest border taxels in a row that a region out of `box` (x, y, w, h) can touch.

    The taxels of the array's border outside the box make runs along the border, between
    the stretches the box covers; each region of the array outside the box holds one run
    whole (all of the border it touches). Returns the shortest run's length (the whole
    border when the box touches none of it).
    """
    rows, cols = shape
    x0, y0, width, height = box
    x1, y1 = x0 + width - 1, y0 + height - 1  # last column and row of the box
    # the border as positions 0 .. perimeter - 1, clockwise from the top-left taxel
    perimeter = 2 * (rows - 1) + 2 * (cols - 1)
    right, bottom, left = cols - 1, cols - 1 + rows - 1, 2 * (cols - 1) + rows - 1
    covered = []  # the box's stretches of the border, as (first, last) positions
    if y0 == 0:
        covered.append((x0, x1))
    if x1 == cols - 1:
        covered.append((right + y0, right + y1))
    if y1 == rows - 1:
        covered.append((bottom + (cols - 1 - x1), bottom + (cols - 1 - x0)))
    if x0 == 0:
        covered.append((left + (rows - 1 - y1), left + (rows - 1 - y0)))
    if not covered:
        return perimeter
    covered.sort()
    # gaps between consecutive stretches, around the border (a stretch may pass position 0)
    shortest = perimeter
    reach = covered[0][1]
    for first, last in covered[1:]:
        if first > reach + 1:
            shortest = min(shortest, first - reach - 1)
        reach = max(reach, last)
    wrap = covered[0][0] + perimeter - reach - 1  # from the last stretch round to the first
    if wrap > 0:
        shortest = min(shortest, wrap)
    return shortest


def _window(prepared: Prepared, limit: float) -> tuple[slice, slice] | None:
    """The contact's box grown by 1 (within the array), when basins may be traced there.

    None when they may not, or need not (a small image is traced whole, and so is a box
    that fills the array). A region out of the box meets the border over at least
    `_shortest_frame_run` taxels; more than sqrt(2.5 limit) + 2 (plus a taxel against
    rounding) is more than a slot's end of at most half the array (area <= limit) can
    meet: then no such region is a basin.
    """
    rows, cols = prepared.image.shape
    box = contact_box(prepared)
    x0, y0, width, height = box
    if rows * cols <= WHOLE_IMAGE or width * height >= (rows - 2) * (cols - 2):
        return None
    if _shortest_frame_run(box, (rows, cols)) <= math.sqrt(SLOT_ELONGATION * limit) + 3:
        return None
    return (
        slice(max(y0 - 1, 0), min(y0 + height + 1, rows)),
        slice(max(x0 - 1, 0), min(x0 + width + 1, cols)),
    )


def _outside(
    prepared: Prepared, level: float, window: tuple[slice, slice] | None
) -> tuple[np.ndarray, bool]:
    """The non-contact taxels at `level` (uint8), and whether they are those of `window`.

    In `window` when every taxel above the level lies in the contact's box, else in the
    whole array.
    """
    # `smooth < level` in one comparison; at the contact threshold, the mask's complement
    if level == prepared.low:
        return (1 - prepared.mask, False) if window is None else (1 - prepared.mask[window], True)
    if window is None or prepared.left_out >= level:
        return (prepared.smooth < level).view(np.uint8), False
    return (prepared.smooth[window] < level).view(np.uint8), True


def basins(prepared: Prepared) -> list[tuple[np.ndarray, float]]:
    """Outer outlines of the non-contact regions that may hold a gap, with their level.

    Highest level first. Cheap tests on the outline alone come first: a basin must hold
    at least a taxel's disk, and the disk of the cover's blur (a narrower gap is filled in
    by the blur and cannot dip to half its surroundings), and at most half the array
    (more is the free space around a contact); one that reaches the array's border can
    only be a slot running off it at its ends: long (>= 2.5 widths) and meeting the
    border over no more than 2.5 widths.
    """
    rows, cols = prepared.image.shape
    limit = 0.5 * rows * cols
    smallest = max(MIN_GAP_AREA, math.pi * (0.5 * prepared.blur / prepared.mean_pitch) ** 2)
    found = []
    levels = [
        prepared.baseline + f * prepared.contrast
        for f in sorted(_LEVELS, reverse=True)
        if prepared.baseline + f * prepared.contrast > prepared.low
    ] + [prepared.low]
    window = _window(prepared, limit)
    x0, y0, width, height = contact_box(prepared)
    for level in levels:
        outside, boxed = _outside(prepared, level, window)
        origin = (window[1].start, window[0].start) if boxed and window else (0, 0)
        # two-level hierarchy: every region's outer outline is at the top, however nested
        contours, hierarchy = cv2.findContours(
            outside, cv2.RETR_CCOMP, cv2.CHAIN_APPROX_NONE, offset=origin
        )
        sized = []
        parents = hierarchy[0][:, 3].tolist() if contours else []
        for contour, parent in zip(contours, parents, strict=True):
            points = contour.shape[0]
            if parent >= 0 or points < 3:
                continue
            left, top, box_width, box_height = cv2.boundingRect(contour)
            if boxed and (
                left < x0
                or top < y0
                or left + box_width > x0 + width
                or top + box_height > y0 + height
            ):
                continue  # out of the contact's box: never a basin (see the module notes)
            # the outline runs through the outer taxels' centres: add half a taxel all round
            # (`contourArea` is the moments' m00, without building them all)
            area = cv2.contourArea(contour) + 0.5 * points
            if area < smallest or area > limit:
                continue
            if left == 0 or top == 0 or left + box_width == cols or top + box_height == rows:
                moments = cv2.moments(contour)
                count = max(moments["m00"], 1e-9)
                var_x, var_y = moments["mu20"] / count, moments["mu02"] / count
                spread = math.hypot((var_x - var_y) / 2, moments["mu11"] / count)
                length = math.sqrt(12.0 * ((var_x + var_y) / 2 + spread)) + 1.0
                breadth = area / length
                if length < SLOT_ELONGATION * breadth:
                    continue
                # outline points on the array's border: all but those strictly inside it
                run = points - cv2.countNonZero(cv2.inRange(contour, (1, 1), (cols - 2, rows - 2)))
                if run > SLOT_BORDER_WIDTHS * breadth + 2:
                    continue
            sized.append((area, contour))
        sized.sort(key=lambda item: -item[0])
        found += [(contour, level) for _, contour in sized[:_MAX_BASINS]]
    return found
