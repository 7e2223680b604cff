"""The Gaussian smoothing every feature applies (internal)."""

from __future__ import annotations

import math
from functools import lru_cache

import cv2
import numpy as np

__all__ = ["gaussian_blur"]


@lru_cache(maxsize=16)
def _gaussian_kernel(sigma: float) -> np.ndarray:
    """The float32 Gaussian kernel of `gaussian_blur` (cached)."""
    reach = 2 * math.ceil(3 * sigma) + 1  # 3 sigma each way: 99.7 % of the weight
    kernel = cv2.getGaussianKernel(reach, sigma, cv2.CV_32F)
    kernel.setflags(write=False)  # shared by every call
    return kernel


def gaussian_blur(image: np.ndarray, sigma: float) -> np.ndarray:
    """``cv2.GaussianBlur`` of a float32 image over 3 sigma each way, mirrored at the edges.

    The separable filter GaussianBlur builds and applies to a float32 image, with its
    kernel made once per sigma instead of on every call (`tests/features/test_features.py`
    checks that both give the same values).
    """
    kernel = _gaussian_kernel(sigma)
    return cv2.sepFilter2D(image, -1, kernel, kernel, borderType=cv2.BORDER_REFLECT)
