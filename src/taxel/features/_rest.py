"""The unloaded level of a smoothed image, past dead taxels (internal).

The contact is cut a few noise sigmas above the smoothed image's lowest level, the level of
the taxels at rest. A dead taxel (a camera's dark pixel, an open sensing cell) reads far
below rest, and smoothing spreads it into a dip: near a corner, where the smoothing mirrors
the image, and where removing narrow bright defects (an opening) widens a dark taxel next
to the border into a 2 x 2 block, the dip reaches far below every taxel at rest, and the
contact, cut a few sigmas above that dip, took in the whole array. On every 9th frame of
the features benchmark's vhdta128 set, given a bare pitch, one dead taxel at or next to a
corner or at an edge's middle changed the contact type or made the whole array contact in
79 of 560 cases (4 now); given the sensor, a dead pixel at or next to a corner put an edge,
a punch and a can 8-35 taxels off (now within 0.05 taxel of the frame without it); and the
camera's noise alone, a dark pixel next to a corner, made a can's whole frame contact in 2
of 40 draws at 4.7 % noise (12 taxels off; now 0.4 at most). On the benchmark itself, 13 of
the 2576 frames change: a box corner now read as a corner, a box edge 1.29 -> 0.15 taxel
off.

A dip is told from the rest by its size: the lowest level is passed over when a place
away from it (beyond the smoothing's reach) lies `_SIGMAS` noise sigmas higher and at
most `_DIP_TAXELS` taxels lie below that; a patch of taxels at rest is larger, and noise
alone leaves its lowest places within a sigma or so of one another. A shallower dip is
left (inside the array, a dead taxel's is 1.4 sigmas deep at 1 % noise, and lowers the
cut by that). Only on arrays at least 4 times as wide as a dip's square (44 taxels for
the default smoothing).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import cv2
import numpy as np

__all__ = ["extremes"]

# A lowest place is a dip when the next place lies this many noise sigmas of the smoothed
# image higher, and at most this many taxels lie below it (a dead taxel's dip, at most a
# 2 x 2 block smoothed: the taxels within a few sigmas of its bottom)
_SIGMAS = 2.5
_DIP_TAXELS = 12
# Dead taxels passed over at most
_MOST_DIPS = 3
# Only on an array this many dips' squares wide: on a smaller one the square around a dip
# leaves too little of it, and a few taxels at rest in a corner (a plate over the rest)
# could pass for a dip
_ARRAY_SQUARES = 4


def extremes(smooth: np.ndarray, noise: float, sigma: float) -> tuple[float, float, Sequence[int]]:
    """The smoothed image's rest level (lowest but for dips), its peak and the peak's place.

    Parameters
    ----------
    smooth : numpy.ndarray
        The smoothed image (float32).
    noise : float
        Its noise sigma.
    sigma : float
        The smoothing's sigma [taxels]: a dip reaches 3 sigma around its taxel.

    Returns
    -------
    (float, float, (int, int))
        The rest level, the peak, the peak's (x, y), as ``cv2.minMaxLoc`` gives them.
    """
    lowest, peak, low_at, peak_at = cv2.minMaxLoc(smooth)
    margin = _SIGMAS * noise
    reach = math.ceil(3 * sigma) + 2  # the smoothing's reach, and a block's second taxel
    # (the usual frame: many taxels lie near the lowest, and this ends it)
    if (
        not margin > 0
        or min(smooth.shape) < _ARRAY_SQUARES * (2 * reach + 1)
        or cv2.countNonZero((smooth < lowest + margin).view(np.uint8)) > _DIP_TAXELS
    ):
        return lowest, peak, peak_at
    away = np.full(smooth.shape, 255, np.uint8)
    for _ in range(_MOST_DIPS):
        x, y = low_at
        away[max(y - reach, 0) : y + reach + 1, max(x - reach, 0) : x + reach + 1] = 0
        if not cv2.countNonZero(away):
            break
        level, _, at, _ = cv2.minMaxLoc(smooth, away)
        below = cv2.countNonZero((smooth < level - margin).view(np.uint8))
        if not (level - lowest > margin and below <= _DIP_TAXELS):
            break
        lowest, low_at = level, at
    return lowest, peak, peak_at
