"""Linear operators on a grid of surface cells: pressure -> surface displacement or strain.

A `ConvolutionOperator` applies a translation-invariant influence kernel by FFT, either
periodically or, by default, as an exact linear convolution on a zero-padded grid (the
DC-FFT method of Liu, Wang & Liu, Wear 243, 2000). Every operator has its adjoint, and
small ones can be turned into a dense matrix.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import fft

from taxel._validation import (
    as_finite_array,
    check_flag,
    check_grid_shape,
    check_instance,
    check_positive,
)
from taxel.mechanics._kernels import depth_kernel, displacement_kernel, offsets
from taxel.mechanics._materials import ElasticMaterial
from taxel.mechanics._transfer import (
    halfspace_displacement_transfer,
    halfspace_strain_transfer,
    halfspace_stress_transfer,
    layer_displacement_transfer,
    layer_strain_transfer,
    layer_stress_transfer,
)

__all__ = [
    "MIN_SPACING",
    "ConvolutionOperator",
    "as_shape",
    "as_spacing",
    "depth_strain_operator",
    "depth_stress_operator",
    "surface_displacement_operator",
]


MIN_SPACING = 1e-9
"""Smallest grid spacing accepted [m]: below a nanometre continuum mechanics does not apply."""


def as_spacing(spacing: Any) -> tuple[float, float]:
    """Return (row spacing dy, column spacing dx) [m] from a scalar or a pair."""
    if spacing is None or isinstance(spacing, str | bool | np.bool_):
        raise TypeError(f"`spacing` must be a number or a (dy, dx) pair, got {spacing!r}")
    values = np.atleast_1d(as_finite_array("spacing", spacing))
    if values.ndim != 1 or values.size not in (1, 2):
        raise ValueError(f"`spacing` must be a number or a (dy, dx) pair, got {spacing!r}")
    dy, dx = (values[0], values[0]) if values.size == 1 else (values[0], values[1])
    for step in (dy, dx):
        if check_positive("spacing", step) < MIN_SPACING:
            raise ValueError(f"`spacing` must be >= {MIN_SPACING:g} m, got {step:g}")
    return float(dy), float(dx)


def as_shape(shape: Any) -> tuple[int, int]:
    """Return (rows, cols) from a pair of whole numbers >= 1, or raise naming `shape`."""
    return check_grid_shape("shape", shape)


class ConvolutionOperator:
    """A translation-invariant linear map between fields on one grid, applied by FFT.

    Parameters
    ----------
    spectrum : numpy.ndarray
        ``rfft2`` of the influence kernel laid out on the FFT grid (wrapped offsets).
    shape : tuple of int
        (rows, cols) of the fields.
    spacing : tuple of float
        (dy, dx) cell size [m].
    periodic : bool
        True for a periodic (circular) convolution on `shape`; False for a linear one.
    kernel : numpy.ndarray, optional
        The real-space influence kernel on offsets -(n-1)..(n-1), kept for `to_matrix`.

    Notes
    -----
    Fields may carry leading batch axes: ``apply`` works on shape (..., rows, cols).
    """

    def __init__(
        self,
        spectrum: np.ndarray,
        shape: tuple[int, int],
        spacing: tuple[float, float],
        *,
        periodic: bool,
        kernel: np.ndarray | None = None,
    ) -> None:
        self.shape = shape
        self.spacing = spacing
        self.periodic = periodic
        self.fft_shape = shape if periodic else (spectrum.shape[0], 2 * (spectrum.shape[1] - 1))
        self._spectrum = spectrum
        self._conjugate = np.conj(spectrum)
        self.kernel = kernel

    def __repr__(self) -> str:
        kind = "periodic" if self.periodic else "zero-padded"
        return f"ConvolutionOperator(shape={self.shape}, {kind})"

    def _check(self, values: Any) -> np.ndarray:
        array = as_finite_array("values", values)
        if array.shape[-2:] != self.shape:
            raise ValueError(
                f"`values` must end with the grid shape {self.shape}, got {array.shape}"
            )
        return array

    def _convolve(self, values: np.ndarray, spectrum: np.ndarray) -> np.ndarray:
        transformed = fft.rfft2(values, s=self.fft_shape, axes=(-2, -1))
        transformed *= spectrum
        result = fft.irfft2(transformed, s=self.fft_shape, axes=(-2, -1))
        return result[..., : self.shape[0], : self.shape[1]]

    def apply(self, values: Any) -> np.ndarray:
        """Apply the operator to a field (or a batch of fields) of shape (..., rows, cols)."""
        return self._convolve(self._check(values), self._spectrum)

    def adjoint(self, values: Any) -> np.ndarray:
        """Apply the adjoint (the correlation with the same kernel)."""
        return self._convolve(self._check(values), self._conjugate)

    def __matmul__(self, values: Any) -> np.ndarray:
        return self.apply(values)

    def to_matrix(self) -> np.ndarray:
        """The operator as a dense (rows*cols, rows*cols) matrix, row-major cell order."""
        rows, cols = self.shape
        if rows * cols > 4096:
            raise ValueError(f"`to_matrix` is for small grids (<= 4096 cells), got {self.shape}")
        identity = np.eye(rows * cols).reshape(rows * cols, rows, cols)
        return self.apply(identity).reshape(rows * cols, rows * cols).T


def _embed(kernel: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Place a kernel on offsets -(n-1)..(n-1) into a wrapped FFT grid; return its rfft2."""
    rows, cols = shape
    # the last axis must be even: the operator recovers its length as 2 * (bins - 1)
    fft_rows, fft_cols = fft.next_fast_len(2 * rows - 1), fft.next_fast_len(2 * cols - 1, True)
    while fft_cols % 2:
        fft_cols = fft.next_fast_len(fft_cols + 1, True)
    padded = np.zeros((fft_rows, fft_cols))
    row_index = np.arange(-(rows - 1), rows) % fft_rows
    col_index = np.arange(-(cols - 1), cols) % fft_cols
    padded[np.ix_(row_index, col_index)] = kernel
    return fft.rfft2(padded)


def _wavenumbers(shape: tuple[int, int], spacing: tuple[float, float]) -> tuple[np.ndarray, ...]:
    """|k|, k_y, k_x [rad/m] on the rfft2 grid of a periodic field."""
    ky = 2 * np.pi * fft.fftfreq(shape[0], spacing[0])[:, None]
    kx = 2 * np.pi * fft.rfftfreq(shape[1], spacing[1])[None, :]
    return np.hypot(ky, kx), ky, kx


def _cell_factor(ky: np.ndarray, kx: np.ndarray, spacing: tuple[float, float]) -> np.ndarray:
    """Fourier transform of the unit cell's indicator over its area (the box factor)."""
    return np.sinc(ky * spacing[0] / (2 * np.pi)) * np.sinc(kx * spacing[1] / (2 * np.pi))


def surface_displacement_operator(
    shape: Any,
    spacing: Any,
    material: ElasticMaterial,
    *,
    periodic: bool = False,
    thickness: float | None = None,
) -> ConvolutionOperator:
    """Pressure on each cell [Pa] -> normal surface displacement at cell centres [m].

    Parameters
    ----------
    shape : tuple of int
        (rows, cols) of the grid.
    spacing : float or tuple of float
        Cell size, or (dy, dx) [m].
    material : ElasticMaterial
        The cover.
    periodic : bool, default False
        False: exact linear convolution with Love's cell-integrated kernel (zero-padded FFT).
        True: periodic, from the transfer function times the cell's box factor; the mean
        displacement of a periodic half-space is undefined and is set to zero.
    thickness : float, optional
        Thickness of a cover bonded to a rigid base [m]; None for a half-space.

    Returns
    -------
    ConvolutionOperator

    Examples
    --------
    >>> import numpy as np
    >>> op = surface_displacement_operator((8, 8), 1e-3, ElasticMaterial(1e6, 0.5))
    >>> x, y = np.random.default_rng(0).random((2, 8, 8))
    >>> bool(np.isclose(np.vdot(op.apply(x), y), np.vdot(x, op.adjoint(y))))
    True
    """
    shape = as_shape(shape)
    spacing = as_spacing(spacing)
    if thickness is not None:
        thickness = check_positive("thickness", thickness)
    check_instance("material", material, ElasticMaterial)
    # a truthy string such as "no" picked the periodic operator
    if check_flag("periodic", periodic):
        magnitude, ky, kx = _wavenumbers(shape, spacing)
        if thickness is None:
            with np.errstate(divide="ignore"):
                transfer = halfspace_displacement_transfer(magnitude, material)
            transfer[0, 0] = 0.0
        else:
            transfer = layer_displacement_transfer(magnitude, thickness, material)
        return ConvolutionOperator(
            transfer * _cell_factor(ky, kx, spacing), shape, spacing, periodic=True
        )
    y = offsets(shape[0], spacing[0])[:, None]
    x = offsets(shape[1], spacing[1])[None, :]
    kernel = displacement_kernel(y, x, spacing, material, thickness=thickness)
    return ConvolutionOperator(
        _embed(kernel, shape), shape, spacing, periodic=False, kernel=kernel
    )


def _depth_operator(
    quantity: str,
    shape: Any,
    spacing: Any,
    depth: float,
    material: ElasticMaterial,
    periodic: bool,
    thickness: float | None,
) -> ConvolutionOperator:
    """Shared construction of the operators to a quantity at depth (strain or stress)."""
    shape = as_shape(shape)
    spacing = as_spacing(spacing)
    depth = check_positive("depth", depth)
    if thickness is not None:
        thickness = check_positive("thickness", thickness)
        if depth > thickness:
            raise ValueError(f"`depth` must be <= `thickness` ({thickness:g} m), got {depth:g}")
    check_instance("material", material, ElasticMaterial)
    if check_flag("periodic", periodic):
        magnitude, ky, kx = _wavenumbers(shape, spacing)
        if quantity == "strain":
            transfer = (
                halfspace_strain_transfer(magnitude, depth, material)
                if thickness is None
                else layer_strain_transfer(magnitude, depth, thickness, material)
            )
        else:
            transfer = (
                halfspace_stress_transfer(magnitude, depth)
                if thickness is None
                else layer_stress_transfer(magnitude, depth, thickness, material)
            )
        return ConvolutionOperator(
            transfer * _cell_factor(ky, kx, spacing), shape, spacing, periodic=True
        )
    y = offsets(shape[0], spacing[0])[:, None]
    x = offsets(shape[1], spacing[1])[None, :]
    kernel = depth_kernel(quantity, y, x, spacing, depth, material, thickness=thickness)
    return ConvolutionOperator(
        _embed(kernel, shape), shape, spacing, periodic=False, kernel=kernel
    )


def depth_strain_operator(
    shape: Any,
    spacing: Any,
    depth: float,
    material: ElasticMaterial,
    *,
    periodic: bool = False,
    thickness: float | None = None,
) -> ConvolutionOperator:
    """Pressure on each cell [Pa] -> normal strain eps_z at depth under cell centres [-].

    Parameters
    ----------
    shape : tuple of int
        (rows, cols) of the grid.
    spacing : float or tuple of float
        Cell size, or (dy, dx) [m].
    depth : float
        Depth d of the sensing elements [m], > 0 (and <= `thickness` for a layer).
    material : ElasticMaterial
        The cover.
    periodic : bool, default False
        False: exact linear convolution with the rectangle-strain kernel. True: periodic,
        from the transfer function times the cell's box factor.
    thickness : float, optional
        Thickness of a cover bonded to a rigid base [m]; None for a half-space.

    Returns
    -------
    ConvolutionOperator

    Examples
    --------
    >>> import numpy as np
    >>> op = depth_strain_operator((16, 16), 0.5e-3, 1e-3, ElasticMaterial(1e6, 0.3))
    >>> strain = op.apply(np.full((16, 16), 1e4))  # 10 kPa everywhere
    >>> bool(strain[8, 8] < 0)  # compressed under the load
    True
    """
    return _depth_operator("strain", shape, spacing, depth, material, periodic, thickness)


def depth_stress_operator(
    shape: Any,
    spacing: Any,
    depth: float,
    material: ElasticMaterial,
    *,
    periodic: bool = False,
    thickness: float | None = None,
) -> ConvolutionOperator:
    """Pressure on each cell [Pa] -> normal stress sigma_z at depth under cell centres [Pa].

    What stress-sensing cells (piezoresistive, piezoelectric, the dielectric of a capacitive
    cell) under the cover feel. Parameters as `depth_strain_operator`; for a half-space the
    result does not depend on the material.

    Examples
    --------
    >>> import numpy as np
    >>> op = depth_stress_operator((16, 16), 0.5e-3, 1e-3, ElasticMaterial(1e6, 0.5),
    ...                            periodic=True)
    >>> float(op.apply(np.full((16, 16), 1e4))[8, 8])  # uniform load: sigma_z = -p
    -10000.0
    """
    return _depth_operator("stress", shape, spacing, depth, material, periodic, thickness)
