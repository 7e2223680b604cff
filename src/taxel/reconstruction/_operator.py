"""The forward operator of a sensor: pressure on the load grid -> calibrated readings."""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import fft

from taxel._validation import as_finite_array, check_choice
from taxel.reconstruction._model import (
    block_average,
    block_spread,
    reading_kernel,
    reflect_eigenvalues,
    reflect_matrix,
    zero_matrix,
)
from taxel.reconstruction._spec import ForwardModelSpec, as_forward_model_spec

__all__ = ["BOUNDARIES", "REPRESENTATIONS", "SensorOperator", "forward_operator"]

BOUNDARIES: tuple[str, ...] = ("auto", "zero", "reflect")
REPRESENTATIONS: tuple[str, ...] = ("auto", "dense", "fast")
# dense matrices up to this many load cells (a 16 x 16 array at oversampling 4)
DENSE_LIMIT = 4096


class SensorOperator:
    """A sensor's linear forward model, with its adjoint.

    Build it with `forward_operator`. ``apply`` maps pressure [Pa] on the load grid, shape
    (..., *load_shape), to readings on the taxel grid, shape (..., *shape); ``adjoint`` maps
    back. Leading batch axes are allowed.

    Attributes
    ----------
    spec : ForwardModelSpec
    boundary : {"zero", "reflect"}
    representation : {"dense", "fast"}
    input_shape, output_shape : tuple of int
    """

    def __init__(self, spec: ForwardModelSpec, boundary: str, representation: str) -> None:
        self.spec = spec
        self.boundary = boundary
        self.representation = representation
        self.input_shape = spec.load_shape
        self.output_shape = spec.shape
        self._matrix: np.ndarray | None = None
        self._eigenvalues: np.ndarray | None = None
        self._spectrum: np.ndarray | None = None
        if representation == "dense":
            self._matrix = reflect_matrix(spec) if boundary == "reflect" else zero_matrix(spec)
        elif boundary == "reflect":
            self._eigenvalues = reflect_eigenvalues(spec)
        else:
            self._fft_shape, self._spectrum = _zero_padded_spectrum(spec)

    def __repr__(self) -> str:
        return (
            f"SensorOperator({self.input_shape} -> {self.output_shape}, "
            f"boundary={self.boundary!r}, representation={self.representation!r})"
        )

    def _check(self, name: str, values: Any, shape: tuple[int, int]) -> np.ndarray:
        array = as_finite_array(name, values)
        if array.shape[-2:] != shape:
            raise ValueError(f"`{name}` must end with the shape {shape}, got {array.shape}")
        return array

    def _fine(self, pressure: np.ndarray) -> np.ndarray:
        """The reading field on the fine grid (before block averaging); symmetric map."""
        if self._eigenvalues is not None:
            coefficients = fft.dctn(pressure, norm="ortho", axes=(-2, -1), workers=1)
            coefficients *= self._eigenvalues
            return fft.idctn(coefficients, norm="ortho", axes=(-2, -1), workers=1)
        rows, cols = self.input_shape
        transformed = fft.rfft2(pressure, s=self._fft_shape, axes=(-2, -1), workers=1)
        transformed *= self._spectrum
        result = fft.irfft2(transformed, s=self._fft_shape, axes=(-2, -1), workers=1)
        return result[..., :rows, :cols]

    def apply(self, pressure: Any) -> np.ndarray:
        """Readings for a pressure field (or batch) on the load grid."""
        pressure = self._check("pressure", pressure, self.input_shape)
        if self._matrix is not None:
            flat = pressure.reshape(*pressure.shape[:-2], -1)
            return (flat @ self._matrix.T).reshape(*pressure.shape[:-2], *self.output_shape)
        return block_average(self._fine(pressure), self.spec.oversampling)

    def adjoint(self, readings: Any) -> np.ndarray:
        """The adjoint map, readings -> load grid."""
        readings = self._check("readings", readings, self.output_shape)
        if self._matrix is not None:
            flat = readings.reshape(*readings.shape[:-2], -1)
            return (flat @ self._matrix).reshape(*readings.shape[:-2], *self.input_shape)
        return self._fine(block_spread(readings, self.spec.oversampling))

    def __matmul__(self, pressure: Any) -> np.ndarray:
        return self.apply(pressure)

    def to_matrix(self) -> np.ndarray:
        """The operator as a dense (taxels, load cells) matrix, row-major cell order."""
        if self._matrix is not None:
            return self._matrix.copy()
        count = self.input_shape[0] * self.input_shape[1]
        if count > DENSE_LIMIT:
            raise ValueError(
                f"`to_matrix` is for small grids (<= {DENSE_LIMIT} load cells), got {count}"
            )
        identity = np.eye(count).reshape(count, *self.input_shape)
        return self.apply(identity).reshape(count, -1).T

    @property
    def eigenvalues(self) -> np.ndarray | None:
        """DCT-II eigenvalues on the fine grid (fast reflective operators only)."""
        return self._eigenvalues


def _zero_padded_spectrum(spec: ForwardModelSpec) -> tuple[tuple[int, int], np.ndarray]:
    """rfft2 of the kernel on offsets -(N-1)..(N-1), wrapped into a padded FFT grid."""
    rows, cols = spec.load_shape
    kernel = reading_kernel(spec)[rows : 3 * rows - 1, cols : 3 * cols - 1]
    shape = (fft.next_fast_len(2 * rows - 1, True), fft.next_fast_len(2 * cols - 1, True))
    padded = np.zeros(shape)
    row_index = np.arange(-(rows - 1), rows) % shape[0]
    col_index = np.arange(-(cols - 1), cols) % shape[1]
    padded[np.ix_(row_index, col_index)] = kernel
    return shape, fft.rfft2(padded, workers=1)


def resolve_layout(spec: ForwardModelSpec, boundary: str, representation: str) -> tuple[str, str]:
    """Turn "auto" choices into concrete ones: small grids dense and exact, large fast."""
    check_choice("boundary", boundary, BOUNDARIES)
    check_choice("representation", representation, REPRESENTATIONS)
    cells = spec.load_shape[0] * spec.load_shape[1]
    if representation == "auto":
        representation = "dense" if cells <= DENSE_LIMIT else "fast"
    if representation == "dense" and cells > 4 * DENSE_LIMIT:
        raise ValueError(
            f"`representation` 'dense' is for grids of <= {4 * DENSE_LIMIT} load cells, "
            f"got {cells}"
        )
    if boundary == "auto":
        boundary = "zero" if representation == "dense" else "reflect"
    return boundary, representation


def forward_operator(
    sensor: Any, *, boundary: str = "auto", representation: str = "auto"
) -> SensorOperator:
    """The forward operator of a sensor (a `ForwardModelSpec`, preset name or sensor object).

    Parameters
    ----------
    sensor : ForwardModelSpec or str or object with ``forward_model_spec()``
        The sensor.
    boundary : {"auto", "zero", "reflect"}, default "auto"
        "zero": no load outside the array (the true model, exact linear convolution).
        "reflect": loads mirrored about the edges (DCT-diagonal). "auto": zero for dense
        operators, reflect for fast ones.
    representation : {"auto", "dense", "fast"}, default "auto"
        "dense": an explicit matrix; "fast": DCT (reflect) or zero-padded FFT (zero).
        "auto": dense up to 4096 load cells, fast above.

    Returns
    -------
    SensorOperator

    Notes
    -----
    Readings are zeta = T F (eq. 25.5 of the chapter seed) in two dimensions: T is the
    cell-integrated kernel of the cover (Boussinesq/Love, or the bonded layer), followed by
    block averaging over each taxel's cell when the load grid is finer than the taxel grid.
    Dense and fast representations of one boundary model are the same map.

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.reconstruction import forward_model_preset
    >>> spec = forward_model_preset("resistive16", shape=(6, 6))
    >>> dense = forward_operator(spec, boundary="reflect", representation="dense")
    >>> fast = forward_operator(spec, boundary="reflect", representation="fast")
    >>> pressure = np.random.default_rng(0).random((6, 6))
    >>> bool(np.allclose(dense.apply(pressure), fast.apply(pressure)))
    True
    >>> readings = fast.apply(np.full((6, 6), 1e4))  # a uniform load reads itself
    >>> print(f"{readings.min() / 1e4:.3f} {readings.max() / 1e4:.3f}")
    1.000 1.000
    """
    spec = as_forward_model_spec(sensor)
    boundary, representation = resolve_layout(spec, boundary, representation)
    return SensorOperator(spec, boundary, representation)
