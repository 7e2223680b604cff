"""The image a feature function is given: validated once, as float32 (internal)."""

from __future__ import annotations

import math
from typing import Any

import cv2
import numpy as np

from taxel._validation import shown_apart

__all__ = ["LARGEST_VALUE", "as_image", "check_size"]

# The features compute in float32 (which ends at 3.4e38): values up to 1e15 keep their
# squares and sums finite, and no tactile image comes near it (1e15 Pa is a petapascal).
LARGEST_VALUE = 1e15


def as_image(image: Any, name: str = "image") -> np.ndarray:
    """Validate a 2-D numeric image (the parameter `name`) and return it as float32."""
    if isinstance(image, np.ma.MaskedArray):
        # np.asarray would drop the mask and read the values under it
        raise TypeError(
            f"`{name}` is a masked array: fill its masked taxels first (`{name}.filled(...)`)"
        )
    try:
        array = np.asarray(image)
    except ValueError as error:  # a ragged nested list
        raise ValueError(f"`{name}` must be a 2-D array of numbers: {error}") from None
    kind = array.dtype.kind
    if kind not in "biuf":
        raise TypeError(f"`{name}` must be numeric, got dtype {array.dtype}")
    if not array.dtype.isnative:  # big-endian data (OpenCV reads the bytes as native)
        array = array.astype(array.dtype.newbyteorder("="))
    if array.ndim != 2:
        raise ValueError(f"`{name}` must be 2-D (rows, cols), got shape {array.shape}")
    if min(array.shape) < 3:
        raise ValueError(f"`{name}` must be at least 3x3 taxels, got shape {array.shape}")
    if (kind == "f" and array.dtype.itemsize >= 4) or array.dtype.itemsize == 8:
        check_size(array, name)  # (smaller types cannot reach the limit)
    image32 = np.ascontiguousarray(array, dtype=np.float32)
    # integers are finite; a float image is when its sum is (one pass instead of two;
    # OpenCV's sum, in double, costs less than NumPy's wrapper and cast)
    if kind == "f" and not math.isfinite(cv2.sumElems(image32)[0]):
        bad = int(image32.size - np.count_nonzero(np.isfinite(image32)))
        raise ValueError(f"`{name}` must be finite everywhere, got {bad} NaN or inf value(s)")
    return image32


def check_size(array: np.ndarray, name: str) -> None:
    """Raise when a value of `array` (the parameter `name`) lies beyond +-`LARGEST_VALUE`."""
    if array.dtype.kind == "f" and array.dtype.itemsize <= 8:
        low, high = cv2.minMaxLoc(np.ascontiguousarray(array))[:2]  # (one pass, no warning)
    else:  # 64-bit integers as Python integers (abs of the lowest int64 overflows), long double
        low, high = array.min().item(), array.max().item()
    largest = max(-low, high)
    if largest > LARGEST_VALUE:
        finite = np.isfinite(array)
        if not finite.all():  # an inf, or NaN beside a large value
            bad = int(array.size - np.count_nonzero(finite))
            raise ValueError(f"`{name}` must be finite everywhere, got {bad} NaN or inf value(s)")
        raise ValueError(
            f"`{name}` values must lie within +-{LARGEST_VALUE:.0e} (the features compute in "
            f"float32), got a value of magnitude {shown_apart(float(largest), LARGEST_VALUE)}"
        )
