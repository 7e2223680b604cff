"""Smoothing a frame to its rest level, past dead taxels (internal).

The contact is cut a few noise sigmas above the smoothed image's lowest level, the level of
the taxels at rest. A dead taxel (a camera's dark pixel, an open sensing cell) reads far
below rest, and smoothing spreads it into a dip; near a corner, where the smoothing mirrors
the image and removing narrow bright defects (an opening) widens a dark taxel next to the
border into a 2 x 2 block, the dip reached far below every taxel at rest, and the contact,
cut a few sigmas above it, took in the whole array. On every 9th frame of the features
benchmark's vhdta128 set, given a bare pitch, one dead taxel at or next to a corner or at
an edge's middle changed the contact type or made the whole array contact in 79 of 560
cases; given the sensor, a dead pixel at or next to a corner put an edge, a punch and a can
8-35 taxels off (now the edge and the punch within 0.05 taxel of the frame without it).

A dead taxel is one that reads `_DEAD_SIGMAS` noise sigmas below the median of its
neighbours (8, or fewer on the border), none of which does, as a spike (its neighbours
spread within those sigmas, or less than it drops below the lowest of them), and
`_BELOW_REST` sigmas below the lowest level of the rest of the array (the cover spreads any
load over several taxels, so no contact makes one; a patch of taxels at rest among pressed
ones has low neighbours, a face's corner at rest under a cover rises through its
neighbours, and a taxel at rest in a hole one taxel wide reads as the background does).
Only the taxels near the smoothed image's lowest place are looked at, where a dead taxel
would set the rest level: one found is read as that median, and the frame smoothed again
(up to `_MOST_DEAD` times); only on arrays 32 taxels a side or more, where enough of the
array lies beyond a dip. A dead taxel at one of 7 places (4 on the border, 1 next to a
corner, 2 inside) of every 9th benchmark frame changed the type in 80 of 784 cases given a
bare pitch and in 132 given the sensor, and moved the centroid by over 0.5 taxel in 271 and
155; with this, 10 and 14 change type, 35 and 20 move; no frame of the benchmark itself
changes. Not found: two or more dead taxels side by side; one beside bright taxels (a
glass's scratches widen its neighbours' spread: a can with a dead pixel in the very corner
still reads as a face 16 taxels off); one darker than noise alone by under 6 sigmas (a
4-sigma noise pixel next to a corner still makes a can's whole frame contact in 2 of 40
draws at 4.7 % noise, through the opening's 2 x 2 block). (A first version passed over any
dip under 12 taxels deep and 2.5 sigmas below the next place; a review found it took a
plate's few corner taxels at rest for a dip and emptied the contact.)
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import cv2
import numpy as np

from taxel.features._blur import gaussian_blur

__all__ = ["smoothed"]

# A taxel this many noise sigmas below the median of its neighbours, none so low, is dead
_DEAD_SIGMAS = 6.0
# ... and at least this many below the rest of the array's lowest smoothed level (a taxel
# at rest in a hole one taxel wide reads as the background does)
_BELOW_REST = 2.0
# Taxels looked at around the smoothed image's lowest place (the dip of a dead taxel next to
# a corner has its lowest place one taxel off it)
_LOOK = 2
# Dead taxels are looked for on arrays at least this many taxels a side
_SMALLEST = 32
# Dead taxels read as their neighbours at most (each needs the frame smoothed again)
_MOST_DEAD = 3
# Bright defects narrower than 3 taxels are removed by an opening of this square
_DEFECT_KERNEL = np.ones((3, 3), np.uint8)
_NEIGHBOURS = np.array([[1, 1, 1], [1, 0, 1], [1, 1, 1]], np.uint8)


def _dead_near(
    values: np.ndarray, at: Sequence[int], limit: float
) -> tuple[list[int], list[int], list[float]] | None:
    """Rows, columns and neighbours' medians of the dead taxels near `at` (x, y), or None."""
    rows, cols = values.shape
    x, y = at
    # the taxels within `_LOOK` of `at`, with their neighbours (the array's own border:
    # the dilation leaves out what lies beyond it)
    r0, r1 = max(y - _LOOK - 1, 0), min(y + _LOOK + 2, rows)
    c0, c1 = max(x - _LOOK - 1, 0), min(x + _LOOK + 2, cols)
    patch = values[r0:r1, c0:c1]
    lowest, highest = cv2.minMaxLoc(patch)[:2]
    if lowest >= highest - limit:
        return None  # (the usual case: no taxel of the patch so far below another)
    # a dead taxel lies below its highest neighbour too, which few taxels do by as much
    maybe = patch < cv2.dilate(patch, _NEIGHBOURS) - np.float32(limit)
    # only the taxels whose neighbours all lie in the patch, or beyond the array
    maybe[: max(y - _LOOK - r0, 0)] = False
    maybe[y + _LOOK + 1 - r0 :] = False
    maybe[:, : max(x - _LOOK - c0, 0)] = False
    maybe[:, x + _LOOK + 1 - c0 :] = False
    found: tuple[list[int], list[int], list[float]] = ([], [], [])
    for row, col in zip(*np.nonzero(maybe), strict=True):
        r, c = row + r0, col + c0
        value = float(values[r, c])
        around = values[max(r - 1, 0) : r + 2, max(c - 1, 0) : c + 2].ravel().tolist()
        around.remove(value)  # (the taxel itself, once)
        middle = float(np.median(around))
        floor, spread = min(around), max(around) - min(around)
        # alone so low, and a spike: a patch of taxels at rest among pressed ones has low
        # neighbours, and the corner of one under a cover rises through its neighbours, which
        # then spread further than noise does and than it drops below the lowest of them
        spike = spread <= limit or floor - value > spread
        if value < middle - limit and floor >= middle - limit and spike:
            found[0].append(int(r))
            found[1].append(int(c))
            found[2].append(middle)
    return found if found[0] else None


def _below_rest(
    dead: tuple[list[int], list[int], list[float]],
    values: np.ndarray,
    smooth: np.ndarray,
    at: Sequence[int],
    sigma: float,
    limit: float,
) -> tuple[list[int], list[int], list[float]] | None:
    """Those of the `dead` taxels that read `limit` below the rest of the array's lowest level.

    The rest of the array: beyond the reach of their dip (a square around `at`, the
    smoothed image's lowest place). A taxel at rest in a hole one taxel wide reads as the
    array's background does, a dead one far below it. None when none is left, or nothing
    lies beyond the square.
    """
    x, y = at
    reach = _LOOK + math.ceil(3 * sigma) + 1
    away = np.full(smooth.shape, 255, np.uint8)
    away[max(y - reach, 0) : y + reach + 1, max(x - reach, 0) : x + reach + 1] = 0
    if not cv2.countNonZero(away):
        return None
    rest = cv2.minMaxLoc(smooth, away)[0]
    kept = [
        k
        for k, (r, c) in enumerate(zip(dead[0], dead[1], strict=True))
        if values[r, c] < rest - limit
    ]
    if not kept:
        return None
    return [dead[0][k] for k in kept], [dead[1][k] for k in kept], [dead[2][k] for k in kept]


def smoothed(
    values: np.ndarray, sigma: float, noise: float, *, defects: bool
) -> tuple[np.ndarray, np.ndarray, float, float, Sequence[int]]:
    """The frame cleaned and smoothed, its rest level, its peak and the peak's place.

    Parameters
    ----------
    values : numpy.ndarray
        The frame (float32); not changed.
    sigma : float
        The Gaussian smoothing's sigma [taxels]; 0: none.
    noise : float
        One taxel's noise sigma (unsmoothed); 0 finds no dead taxel, and neither does an
        array under 32 taxels a side.
    defects : bool
        Remove bright defects narrower than 3 taxels (a 3 x 3 grey-level opening).

    Returns
    -------
    tuple
        The frame with its defects removed and its dead taxels read as their neighbours'
        median, that frame smoothed, its lowest level (the rest level), its peak and the
        peak's (x, y), as ``cv2.minMaxLoc`` gives them.
    """
    # (a small array has too little background beyond a dip to read its rest level from)
    limit = _DEAD_SIGMAS * noise if min(values.shape) >= _SMALLEST else 0.0
    for attempt in range(_MOST_DEAD + 1):
        cleaned = cv2.morphologyEx(values, cv2.MORPH_OPEN, _DEFECT_KERNEL) if defects else values
        smooth = gaussian_blur(cleaned, sigma) if sigma > 0 else cleaned
        lowest, peak, low_at, peak_at = cv2.minMaxLoc(smooth)
        dead = _dead_near(values, low_at, limit) if limit > 0 else None
        if dead is not None:
            dead = _below_rest(dead, values, smooth, low_at, sigma, _BELOW_REST * noise)
        if dead is None or attempt == _MOST_DEAD:
            break
        if attempt == 0:
            values = values.copy()  # (the caller's frame, or the user's array itself)
        values[dead[0], dead[1]] = dead[2]
    return cleaned, smooth, lowest, peak, peak_at
