"""Cached compliance operators of the contact: cover plus (optionally) an elastic indenter.

The contact solver works on a window around the contact. Its operator is the central part of
the full grid's kernel, so the expensive kernel (a bonded layer needs a Hankel transform) is
built once per configuration and windows are cut from it.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from taxel.mechanics._kernels import displacement_kernel, offsets
from taxel.mechanics._materials import ElasticMaterial
from taxel.mechanics._operators import (
    ConvolutionOperator,
    _embed,
    surface_displacement_operator,
)

__all__ = ["WindowToGrid", "cover_operator", "gap_operator", "window_to_grid"]


@lru_cache(maxsize=16)
def _gap_kernel(
    shape: tuple[int, int],
    spacing: tuple[float, float],
    cover: ElasticMaterial,
    indenter: ElasticMaterial | None,
    thickness: float | None,
) -> np.ndarray:
    """Displacement kernel of both bodies together on offsets -(n-1)..(n-1) [m/Pa]."""
    y = offsets(shape[0], spacing[0])[:, None]
    x = offsets(shape[1], spacing[1])[None, :]
    kernel = displacement_kernel(y, x, spacing, cover, thickness=thickness)
    if indenter is not None:
        # a half-space indenter: Love's kernel depends on (1 - nu^2)/E only
        equivalent = ElasticMaterial(indenter.plane_strain_modulus, 0.0)
        kernel = kernel + displacement_kernel(y, x, spacing, equivalent)
    kernel.setflags(write=False)
    return kernel


@lru_cache(maxsize=64)
def gap_operator(
    shape: tuple[int, int],
    spacing: tuple[float, float],
    cover: ElasticMaterial,
    indenter: ElasticMaterial | None = None,
    thickness: float | None = None,
    periodic: bool = False,
    window: tuple[int, int] | None = None,
) -> ConvolutionOperator:
    """Pressure -> change of gap (both bodies' normal displacement) on a grid or a window.

    `window` (rows, cols) cuts the operator of a sub-grid out of the full grid's kernel.
    """
    if periodic:
        operator = surface_displacement_operator(
            shape, spacing, cover, periodic=True, thickness=thickness
        )
        if indenter is not None:
            equivalent = ElasticMaterial(indenter.plane_strain_modulus, 0.0)
            extra = surface_displacement_operator(shape, spacing, equivalent, periodic=True)
            operator = ConvolutionOperator(
                operator._spectrum + extra._spectrum, shape, spacing, periodic=True
            )
        return operator
    full = _gap_kernel(shape, spacing, cover, indenter, thickness)
    rows, cols = window if window is not None else shape
    centre_row, centre_col = shape[0] - 1, shape[1] - 1
    kernel = full[
        centre_row - (rows - 1) : centre_row + rows, centre_col - (cols - 1) : centre_col + cols
    ]
    return ConvolutionOperator(
        _embed(kernel, (rows, cols)), (rows, cols), spacing, periodic=False, kernel=kernel
    )


@lru_cache(maxsize=16)
def cover_operator(
    shape: tuple[int, int],
    spacing: tuple[float, float],
    cover: ElasticMaterial,
    thickness: float | None = None,
    periodic: bool = False,
) -> ConvolutionOperator:
    """Pressure -> the cover's own surface displacement (cached)."""
    return surface_displacement_operator(
        shape, spacing, cover, periodic=periodic, thickness=thickness
    )


class WindowToGrid:
    """The gap operator from sources in a window to every cell of the full grid.

    The contact lies in a window; its effect on the whole grid is a linear convolution of a
    small source with the kernel, which needs an FFT only as large as the grid plus the
    window, not twice the grid.
    """

    def __init__(self, kernel: np.ndarray, shape: tuple[int, int], window: tuple[int, ...]):
        from scipy import fft

        rows, cols = shape
        top, left, height, width = window
        self.shape = shape
        self.window = (slice(top, top + height), slice(left, left + width))
        self.fft_shape = (
            fft.next_fast_len(rows + height - 1),
            fft.next_fast_len(cols + width - 1, True),
        )
        padded = np.zeros(self.fft_shape)
        # output cell i from source j (at top + j) sees kernel offset i - j - top
        row_steps = np.arange(-(height - 1), rows)
        col_steps = np.arange(-(width - 1), cols)
        centre_row, centre_col = rows - 1, cols - 1
        padded[np.ix_(row_steps % self.fft_shape[0], col_steps % self.fft_shape[1])] = kernel[
            np.ix_(centre_row + row_steps - top, centre_col + col_steps - left)
        ]
        self._spectrum = fft.rfft2(padded)

    def apply(self, source: np.ndarray) -> np.ndarray:
        """The full grid's response to `source` (the window's values)."""
        from scipy import fft

        transformed = fft.rfft2(source, s=self.fft_shape)
        transformed *= self._spectrum
        return fft.irfft2(transformed, s=self.fft_shape)[: self.shape[0], : self.shape[1]]


@lru_cache(maxsize=32)
def window_to_grid(
    shape: tuple[int, int],
    spacing: tuple[float, float],
    cover: ElasticMaterial,
    indenter: ElasticMaterial | None,
    thickness: float | None,
    window: tuple[int, int, int, int],
) -> WindowToGrid:
    """`WindowToGrid` for a window (top, left, height, width) of a grid (cached)."""
    return WindowToGrid(_gap_kernel(shape, spacing, cover, indenter, thickness), shape, window)
