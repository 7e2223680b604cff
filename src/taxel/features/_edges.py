"""Canny edges of a tactile image (Ellis seed, section 2.1) and their segments.

OpenCV's Canny is used because it takes tens of microseconds on a 128x128 image against
milliseconds for scikit-image's (see the README's dependency table), and the whole feature
set has a 1 ms budget.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Unpack

import cv2
import numpy as np

from taxel.features._image import Preparation, Prepared, prepare

__all__ = ["Edges", "detect_edges", "edges_core"]

# Canny thresholds on the clipped image scaled to 0..255, in units of OpenCV's 3x3 Sobel
# magnitude (L2). A step of full contrast blurred by sigma 1-1.5 taxels gives 550-800; noise
# at 5 % of full scale after smoothing gives under 40. 60 / 150 keep every real outline,
# including the weak shoulder of a Hertzian edge, and no noise.
_CANNY_LOW = 60.0
_CANNY_HIGH = 150.0
_NOISE_SOBEL = 20.0
_CANNY_CAP = 350.0
# Edges are kept within this many taxels of the contact's outline, or within the cover's
# blur when the sensor is known: the mask's outline lies at the low threshold, and a rim
# blurred by the cover has its steepest gradient (Canny's ridge) up to a blur's width
# inside it (on vhdta128, 3 taxels: a washer's rims came in 10-11 pieces at 2, 2 at 3).
_OUTLINE_REACH = 2
# A segment shorter than this many taxels is a speck, not an edge.
_MIN_SEGMENT = 4


@lru_cache(maxsize=8)
def _outline_kernel(reach: int) -> np.ndarray:
    """The disk that makes the band within `reach` taxels of an outline (cached)."""
    kernel = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * reach + 1, 2 * reach + 1))
    kernel.setflags(write=False)
    return kernel


@dataclass(frozen=True)
class Edges:
    """Edge taxels of a tactile image.

    Attributes
    ----------
    edge_mask : numpy.ndarray of bool, shape (rows, cols)
        Canny edge taxels (segments shorter than 4 taxels removed).
    n_edges : int
        Number of connected edge segments (8-neighbours).
    rows, cols : numpy.ndarray of int
        Indices of the edge taxels.
    points_m : numpy.ndarray, shape (n, 2)
        The same taxels as (x, y) in the sensor frame [m].
    """

    edge_mask: np.ndarray
    n_edges: int
    rows: np.ndarray
    cols: np.ndarray
    points_m: np.ndarray


def edges_core(prepared: Prepared) -> Edges:
    """Canny edges of a prepared image (internal core of `detect_edges`)."""
    shape = prepared.image.shape
    if not prepared.present:
        empty = np.zeros(0, np.intp)
        return Edges(np.zeros(shape, bool), 0, empty, empty, np.zeros((0, 2)))
    # clip at the lower quartile of the contact: the singular rim of a flat punch, the peaks
    # of a texture and the noise on a face then stay inside the contact instead of drawing
    # inner edges; clip below at the low contact threshold, so that background noise is flat
    inside = prepared.smooth[prepared.mask.view(bool)]
    level = float(np.partition(inside, inside.size // 4)[inside.size // 4])
    floor = min(prepared.low, level - 1e-6 * max(abs(level), 1.0))
    span = max(level - floor, 1e-30)
    scaled = (prepared.smooth - floor) * (255.0 / span)
    image8 = np.clip(scaled, 0, 255).astype(np.uint8)
    # the Sobel magnitude of smoothed white noise stays under ~18 times its sigma at the
    # 99.99th percentile; thresholds follow the noise left between the clip levels, capped
    # below the ~540 that a full-contrast step blurred by 1.5 taxels gives
    noise = _NOISE_SOBEL * prepared.noise * 255.0 / span
    high = min(max(_CANNY_HIGH, noise), _CANNY_CAP)
    edges: np.ndarray = cv2.Canny(
        image8, min(max(_CANNY_LOW, noise / 2), high / 2), high, L2gradient=True
    )
    # keep edges near the contact's outline (see `_OUTLINE_REACH`): an edge is where contact
    # starts or stops, not a ripple of pressure inside a face (texture is measured apart)
    reach = max(_OUTLINE_REACH, math.ceil(prepared.blur / prepared.mean_pitch - 1e-9))
    outline = cv2.morphologyEx(prepared.mask, cv2.MORPH_GRADIENT, _outline_kernel(reach))
    edges &= outline * np.uint8(255)
    count, labels, stats, _ = cv2.connectedComponentsWithStats(edges, connectivity=8)
    sizes = stats[:, cv2.CC_STAT_AREA]
    keep = sizes >= _MIN_SEGMENT
    keep[0] = False
    edge_mask = keep[labels]
    rows, cols = np.nonzero(edge_mask)
    row_pitch, col_pitch = prepared.pitch
    points = np.column_stack(
        ((cols - (shape[1] - 1) / 2) * col_pitch, (rows - (shape[0] - 1) / 2) * row_pitch)
    )
    return Edges(edge_mask, int(keep.sum()), rows, cols, points)


def detect_edges(image: Any, sensor_or_pitch: Any, **preparation: Unpack[Preparation]) -> Edges:
    """Canny edges of a tactile image and the number of edge segments.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m].
    **preparation
        `calibrated`, `smoothing` (the Gaussian sigma [taxels] applied before the
        gradient: Canny's own smoothing), `baseline`, `defects`, `noise` and `reference`,
        passed on to `prepare` with its defaults (so that this agrees with `extract`).

    Returns
    -------
    Edges

    Notes
    -----
    The smoothed image is scaled so that the low contact threshold maps to 0 and the lower
    quartile of the contact's levels to 255, clipped, and passed to OpenCV's Canny (3x3
    Sobel, L2 magnitude, hysteresis 60/150, raised with the noise up to 175/350). The
    clipping removes the inner edges that singular pressure peaks (flat-punch rims,
    texture) would otherwise draw, so the edges outline the contact. Edges are kept within
    2 taxels of the contact's outline, or within the cover's blur when `sensor_or_pitch` is
    a sensor (the steepest gradient of a blurred rim lies that far inside the outline).

    Examples
    --------
    >>> image = np.zeros((32, 32)); image[8:24, 8:24] = 1.0
    >>> edges = detect_edges(image, 1e-3)
    >>> edges.n_edges  # one closed outline
    1
    """
    return edges_core(prepare(image, sensor_or_pitch, **preparation))
