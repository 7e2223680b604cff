"""Basins: the non-contact regions of a contact at several levels, that may hold a gap.

Helper of `taxel.features._gaps`: the outer outlines of the non-contact regions at three
levels of the smoothed image (50 % and 25 % of the contrast, then the contact threshold),
with cheap tests on each outline alone.

Regions reaching out of the contact's box are dropped unseen when they cannot be basins,
which is the usual case (see `_window`): every taxel above the level lies in the box, and
a region out of the box meets the array's border over a whole side of the array and more,
too long a run for a slot's end. On a large array the outlines are then traced in the box
grown by 1 taxel alone: every region reaching out of the box passes through that ring of
taxels (where it is not the array's border), so each of its pieces in the grown box
reaches out of the box too and is dropped, and every other region lies in the box whole,
so its outline is the same there (and the outlines come in the same raster order).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import cv2
import numpy as np

from taxel.features._image import Prepared
from taxel.features._window import WHOLE_IMAGE, contact_box

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
    """The contact's box grown by 1 (within the array), if regions out of it are no basins.

    A region out of the box meets the border over at least `_shortest_frame_run` taxels;
    more than sqrt(2.5 limit) + 2 (plus a taxel against rounding) is more than a slot's
    end of at most half the array (area <= limit) can meet: then no such region is a
    basin. None otherwise. (The outlines are traced in a copy of the window, so a narrow
    one saves the tracing its taxels.)
    """
    rows, cols = prepared.image.shape
    box = contact_box(prepared)
    if _shortest_frame_run(box, (rows, cols)) <= math.sqrt(SLOT_ELONGATION * limit) + 3:
        return None
    x0, y0, width, height = box
    return (
        slice(max(y0 - 1, 0), min(y0 + height + 1, rows)),
        slice(max(x0 - 1, 0), min(x0 + width + 1, cols)),
    )


def _out_of(rect: Sequence[int], box: Sequence[int]) -> bool:
    """Whether the bounding box `rect` reaches out of `box` (both x, y, width, height)."""
    left, top, width, height = rect
    x0, y0, box_width, box_height = box
    return left < x0 or top < y0 or left + width > x0 + box_width or top + height > y0 + box_height


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
    box = contact_box(prepared)
    # a large array is traced in the window alone (a small one, or a window that is the
    # whole array, saves nothing)
    crop = None
    if (
        window is not None
        and rows * cols > WHOLE_IMAGE
        and (window[0].stop - window[0].start) * (window[1].stop - window[1].start) < rows * cols
    ):
        crop = window
    for level in levels:
        # regions out of the box are no basins when every taxel above the level is in it
        boxed = window is not None and (level == prepared.low or prepared.left_out < level)
        cut = crop if boxed else None
        # `smooth < level` in one comparison; at the contact threshold, the mask's complement
        if level == prepared.low:
            outside = 1 - (prepared.mask if cut is None else prepared.mask[cut])
        else:
            smooth = prepared.smooth if cut is None else prepared.smooth[cut]
            outside = (smooth < level).view(np.uint8)
        origin = (0, 0) if cut is None else (cut[1].start, cut[0].start)
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
            # the outline runs through the outer taxels' centres: half a taxel is added all
            # round its area, so an outline of 2 `smallest` points or more is never too
            # small, and its box is tested first: that drops the usual long outline out of
            # the box (the region around the contact) without its area. A short outline,
            # mostly a speck, is dropped by its area first.
            rect = None
            if boxed and 0.5 * points >= smallest:
                rect = cv2.boundingRect(contour)
                if _out_of(rect, box):
                    continue
            # (`contourArea` is the moments' m00, without building them all)
            area = cv2.contourArea(contour) + 0.5 * points
            if area < smallest or area > limit:
                continue
            left, top, box_width, box_height = rect or cv2.boundingRect(contour)
            if boxed and rect is None and _out_of((left, top, box_width, box_height), box):
                continue  # out of the contact's box: never a basin (see the module notes)
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
