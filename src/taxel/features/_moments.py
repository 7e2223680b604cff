"""Moments of a binary region measured on a crop, as if measured on the whole image (internal).

``cv2.moments(image, binaryImage=True)`` scans every taxel of the image; a contact often
covers a small part of it. The raw moments of a binary image are integers, which OpenCV
sums exactly (in integers per 32 x 32 tile, then in doubles far below 2^53), so the raw
moments of the whole image follow exactly from those of a crop holding the region; the
central moments are then formed from them with OpenCV's own formulas, in the same order,
and come out bit for bit the same as OpenCV's on the whole image (which matters: their
rounding depends on where the origin lies).

The crop holds 0 and 1, so its plain moments are its binary moments: OpenCV's binary mode
first converts the image, which doubles the cost, and its plain mode on 8-bit images forms
the central moments its own way; so the raw moments are taken in plain mode and the
central moments always formed here, as the binary mode forms them.
"""

from __future__ import annotations

import sys

import cv2
import numpy as np

__all__ = ["binary_moments"]

_EPSILON = sys.float_info.epsilon  # DBL_EPSILON, OpenCV's test of an empty region


def binary_moments(crop: np.ndarray, row0: int = 0, col0: int = 0) -> dict[str, float]:
    """Binary moments of a region that lies within `crop`, in the frame of a larger image.

    Parameters
    ----------
    crop : numpy.ndarray (uint8), shape (rows, cols)
        1 on the region, 0 elsewhere; the larger image is zero outside the crop.
    row0, col0 : int
        Where the crop's first taxel sits in the larger image.

    Returns
    -------
    dict
        m00, m10, m01, m20, m11, m02, mu20, mu11, mu02, as ``cv2.moments(image,
        binaryImage=True)`` of the larger image gives them, bit for bit.
    """
    raw = cv2.moments(crop)  # 0/1: the binary moments (see the module notes)
    # exact integer shifts of the origin: x -> x + col0, y -> y + row0
    n, sx, sy = int(raw["m00"]), int(raw["m10"]), int(raw["m01"])
    sxx, sxy, syy = int(raw["m20"]), int(raw["m11"]), int(raw["m02"])
    m00 = float(n)
    m10 = float(sx + col0 * n)
    m01 = float(sy + row0 * n)
    m20 = float(sxx + (2 * sx + col0 * n) * col0)
    m11 = float(sxy + col0 * sy + row0 * sx + col0 * row0 * n)
    m02 = float(syy + (2 * sy + row0 * n) * row0)
    # OpenCV's completeMomentState
    cx = cy = 0.0
    if abs(m00) > _EPSILON:
        inverse = 1.0 / m00
        cx, cy = m10 * inverse, m01 * inverse
    return {
        "m00": m00, "m10": m10, "m01": m01, "m20": m20, "m11": m11, "m02": m02,
        "mu20": m20 - m10 * cx, "mu11": m11 - m10 * cy, "mu02": m02 - m01 * cy,
    }  # fmt: skip
