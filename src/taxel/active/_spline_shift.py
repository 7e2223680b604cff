"""Re-sampling one reference image at many shifts, its spline coefficients computed once.

The slip registration shifts the same reference image up to 4 times a frame, and
`scipy.ndimage.shift` pads and spline-filters the image again at every call: four fifths of
its time on a 16 x 16 frame. `spline_shifter` does that once and then calls the
interpolation kernel `ndimage.shift` itself calls, with the same arguments, so the images
are the same to the last bit. That kernel is private to SciPy: the shifter checks itself
against `ndimage.shift` when made, and falls back to `ndimage.shift` if it ever differs.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy import ndimage

__all__ = ["spline_shifter"]

_PROBES = ((0.0, 0.0), (0.37, -1.21), (-2.5, 0.004), (14.2, -13.7))  # [taxels]


def _slow(reference: np.ndarray) -> Callable[[float, float], np.ndarray]:
    def shifted(rows: float, cols: float) -> np.ndarray:
        return ndimage.shift(reference, (rows, cols), order=3, mode="nearest")

    return shifted


def spline_shifter(reference: np.ndarray) -> Callable[[float, float], np.ndarray]:
    """`ndimage.shift` of `reference` (cubic, mode 'nearest') as a function of the shift.

    The function takes (rows, cols) [taxels] and gives ``ndimage.shift(reference,
    (rows, cols), order=3, mode="nearest")``, the same numbers at a fifth of the cost.
    """
    reference = np.asarray(reference, dtype=np.float64)
    slow = _slow(reference)
    try:
        from scipy.ndimage import _nd_image, _ni_support  # the kernel behind ndimage.shift

        npad = 12  # ndimage pads by 12 before filtering for mode 'nearest'
        padded = np.pad(reference, npad, mode="edge")
        filtered = ndimage.spline_filter(padded, 3, output=np.float64, mode="nearest")
        mode = _ni_support._extend_mode_to_code("nearest")

        def shifted(rows: float, cols: float) -> np.ndarray:
            output = np.zeros(reference.shape)
            offset = np.array([-rows, -cols], dtype=np.float64)
            _nd_image.zoom_shift(filtered, None, offset, output, 3, mode, 0.0, npad, False)
            return output

        if all(np.array_equal(shifted(*probe), slow(*probe)) for probe in _PROBES):
            return shifted
    except Exception:  # any change in SciPy's private kernel: the slow path
        pass
    return slow
