"""Uneven lighting of a raw frame: the background's tilt, taken out before segmentation (internal).

A camera's frame is seldom evenly lit: stray light and vignetting add a slow ramp to the
background. The contact is cut at a level a few noise sigmas above the background's
minimum, so a ramp of that size lets the contact run on into the lit side: on the
features benchmark's vhdta128 frames a ramp of 4 grey levels across the array put line
contacts, washers and cans 8-24 taxels off. `background_tilt` fits a plane to the
background (the frame's smoothed image away from every taxel above that level, read on
a coarse grid) and returns its tilt when the tilt is significant and large enough to
move the cut. A tare (`reference`) measures the lighting exactly; this is for frames
without one. A texture or plate over most of the array leaves too little background to
fit, and a tilt hidden under the contact cannot be seen: both are left as they are.
"""

from __future__ import annotations

import math

import cv2
import numpy as np

__all__ = ["background_tilt", "fit_plane", "plane_image"]

# Read the smoothed image on a grid of about this many points a side
_GRID = 32
# Fit the plane only to at least this many background points, and this share of the grid:
# a texture or screen over most of the array leaves a band of background lit faintly by it
# (on the features benchmark, 8-10 % of the grid; a tilt read there put screens 1-5
# taxels off), while a ramp of 4 grey levels across leaves 17 % or more around an edge
_LEAST_POINTS = 64
_LEAST_SHARE = 0.15
# Points further than this many noise sigmas from the fitted plane are left out (a speck,
# a defect, a contact's faint tail)
_CLIP = 5.0
# The background lies on the plane when it spreads about it within this many noise sigmas
# (on the features benchmark's vhdta128 frames under a ramp, 0.97-1.21; a screen's faint
# light over 17 % of the grid, 1.41)
_FLAT = 1.3
# A tilt within this many of its standard errors is noise
_SIGNIFICANT = 3.0
# ... and one whose rise across the array is under this fraction of the cut's height above
# the baseline does not move the cut. Read away from the seeds (when too little of the
# array lies away from the cut), a tilt must be what lifted the array over the cut: taken
# out, it leaves `_LEAST_SHARE` of the grid away from the cut again. A screen's faint light
# so read rose by 1.5 and 5.5 grey levels, under cuts of 5.7 and 8.8, and put it 1.6 and
# 3.7 taxels off; taken out, it left 41 and 92 of the 154 points needed. (A rise of the
# whole cut's height was asked before, which left a ramp of 4 grey levels under an edge's
# cut of 8 in: on the features benchmark, 3 of 60 line contacts read as arcs or a face,
# 14-26 taxels off)
_MOVES_CUT = 0.25
# A first fit to every background point, outliers and all, that rises by under this share
# of the needed rise ends the search
_FIRST_LOOK = 0.5


def _away(coarse: np.ndarray, cut: float, reach: int) -> np.ndarray:
    """1 (uint8) on the points of `coarse` over `reach` points from any at `cut` or above."""
    square = np.ones((2 * reach + 1, 2 * reach + 1), np.uint8)
    near = cv2.dilate((coarse >= np.float32(cut)).view(np.uint8), square)
    return 1 - near


def _first_slopes(coarse: np.ndarray, away: np.ndarray) -> tuple[float, float]:
    """Slopes (per point down, across) of the plane through `coarse` where `away` is 1.

    By the moments of the points and of their values: a few calls, against a dozen for
    the points' own fit (the usual frame, evenly lit, ends here).
    """
    points = cv2.moments(away, True)
    values = cv2.moments(coarse * away)
    count = points["m00"]
    # central sums: of x x, x y, y y over the points, and of x v, y v
    xx, xy, yy = points["mu20"], points["mu11"], points["mu02"]
    xv = values["m10"] - points["m10"] / count * values["m00"]
    yv = values["m01"] - points["m01"] / count * values["m00"]
    determinant = xx * yy - xy * xy
    if not determinant > 0:
        return 0.0, 0.0
    return (xx * yv - xy * xv) / determinant, (yy * xv - xy * yv) / determinant


def fit_plane(design: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, float, np.ndarray]:
    """Least-squares plane through `values`: coefficients, residual variance, standard errors.

    `design` holds the rows 1, row, column of 3 or more points (better centred: the fit is
    then well conditioned); a direction the points do not span gets a zero coefficient of
    zero error (SVD least squares, errors by a pseudo-inverse).
    """
    coefficients = np.linalg.lstsq(design.T, values, rcond=None)[0]
    inverse = np.linalg.pinv(design @ design.T)
    residuals = values - coefficients @ design
    variance = float(residuals @ residuals) / max(values.size - 3, 1)
    return coefficients, variance, np.sqrt(np.maximum(variance * np.diag(inverse), 0.0))


def plane_image(level: tuple[float, float, float], shape: tuple[int, ...]) -> np.ndarray:
    """The image (float32) of `shape` of a plane: at the first taxel, per row, per column."""
    start, per_row, per_col = (np.float32(v) for v in level)
    rows = np.arange(shape[0], dtype=np.float32)[:, None]
    cols = np.arange(shape[1], dtype=np.float32)[None, :]
    return start + per_row * rows + per_col * cols


def _rise(slopes: np.ndarray, rows: int, cols: int) -> float:
    """How far a plane of `slopes` (per row, per column) rises across the array."""
    return float(abs(slopes[0]) * (rows - 1) + abs(slopes[1]) * (cols - 1))


def background_tilt(
    smooth: np.ndarray, low: float, high: float, level: float, noise: float, reach: float
) -> np.ndarray | None:
    """The background's tilt (float32, zero at the array's centre), or None when there is none.

    Parameters
    ----------
    smooth : numpy.ndarray, shape (rows, cols)
        The smoothed frame (float32).
    low, high : float
        The levels at which the contact is cut and its seeds are taken. The background
        lies away from every taxel above `low`; where a steep ramp lifts too much of the
        array over it, away from every taxel above `high`, and the tilt found there is kept
        only when, taken out, it leaves enough of the array away from the cut.
    level : float
        The baseline (the smoothed frame's minimum).
    noise : float
        The smoothed frame's noise sigma.
    reach : float
        How far around a contact its load is felt [taxels]: those taxels are no background.

    Returns
    -------
    numpy.ndarray or None
        The plane to subtract, of `smooth`'s shape.

    Examples
    --------
    >>> y, x = np.mgrid[:64, :64].astype(np.float32)
    >>> frame = 20.0 + 0.1 * x  # a ramp of 6.3 grey levels
    >>> frame[20:30, 20:30] += 50.0  # a contact
    >>> tilt = background_tilt(frame, 26.0, 38.0, 20.0, 0.5, 4.0)
    >>> [round(float(v), 2) for v in (tilt[0, 0], tilt[0, 63], tilt[63, 0])]
    [-3.15, 3.15, -3.15]
    """
    rows, cols = smooth.shape
    step = max(min(rows, cols) // _GRID, 1)
    coarse = smooth[::step, ::step]
    least = max(_LEAST_POINTS, _LEAST_SHARE * coarse.size)
    spread = math.ceil(reach / step)
    for cut in (low, high):  # (the cut found is read after the loop)
        away = _away(coarse, cut, spread)
        if cv2.countNonZero(away) >= least:
            break
    else:
        return None
    threshold = _MOVES_CUT * (low - level)
    first = _first_slopes(coarse, away)
    if _rise(np.divide(first, step), rows, cols) <= _FIRST_LOOK * threshold:
        return None  # (the usual case: no tilt that could matter)
    at_rows, at_cols = np.nonzero(away)
    values = coarse[at_rows, at_cols].astype(np.float64)
    middle = ((rows - 1) / 2, (cols - 1) / 2)
    design = np.stack(
        (np.ones(values.size), at_rows * step - middle[0], at_cols * step - middle[1])
    )
    coefficients, variance, errors = fit_plane(design, values)
    # again without the points off the plane (a speck, a defect, a contact's faint tail)
    inside = np.abs(values - coefficients @ design) <= _CLIP * max(noise, math.sqrt(variance))
    if np.count_nonzero(inside) < _LEAST_POINTS:
        return None
    coefficients, variance, errors = fit_plane(design[:, inside], values[inside])
    if not variance <= (_FLAT * noise) ** 2:
        return None
    slopes = np.where(np.abs(coefficients[1:]) > _SIGNIFICANT * errors[1:], coefficients[1:], 0.0)
    if _rise(slopes, rows, cols) <= threshold:
        return None
    start = -(slopes[0] * middle[0] + slopes[1] * middle[1])  # zero at the centre
    tilt = plane_image((start, slopes[0], slopes[1]), smooth.shape)
    if cut != low:  # read away from the seeds: is the tilt what lifted the array?
        level_free = coarse - tilt[::step, ::step]
        cleared = _away(level_free, float(level_free.min()) + (low - level), spread)
        if cv2.countNonZero(cleared) < least:
            return None
    return tilt
