r"""The pieces of a sensor's forward model: kernel, boundary models, DCT structure, penalties.

Two boundary models are offered, and each has a dense and a fast representation that are
the same linear map (they agree to rounding):

``"zero"``
    The true model: no load outside the array, exact linear convolution of the
    cell-integrated kernel (dense matrix, or zero-padded FFT).
``"reflect"``
    Loads mirrored about the array edges (half-sample symmetric extension), the kernel
    periodized with period 2N. It is diagonalised by the DCT-II, which makes large grids fast.
    Its error is confined to loads within about two depths of an edge, where the mirror
    images add phantom readings; the benchmark measures it.

Block averaging (oversampling k) maps fine DCT mode m to coarse mode mu with a known weight
(the 1-D fold below), so the whole operator A = (block average) K is "DCT-sparse": each fine
mode reaches exactly one coarse mode, and A A^T is diagonal in the coarse DCT basis.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy import fft

from taxel.mechanics import (
    ElasticMaterial,
    depth_strain_operator,
    depth_stress_operator,
    surface_displacement_operator,
)
from taxel.reconstruction._spec import ForwardModelSpec

__all__ = [
    "block_average",
    "block_spread",
    "dense_penalty",
    "fold_1d",
    "penalty_eigenvalues",
    "reading_kernel",
    "reflect_eigenvalues",
    "reflect_matrix",
    "reflect_normal_block",
    "reflect_normal_kernel",
    "zero_matrix",
]


@lru_cache(maxsize=8)
def _kernel(
    quantity: str,
    shape: tuple[int, int],
    pitch: float,
    depth: float,
    material: ElasticMaterial,
    thickness: float | None,
) -> np.ndarray:
    if quantity == "stress":
        operator = depth_stress_operator(shape, pitch, depth, material, thickness=thickness)
    elif quantity == "strain":
        operator = depth_strain_operator(shape, pitch, depth, material, thickness=thickness)
    else:
        operator = surface_displacement_operator(shape, pitch, material, thickness=thickness)
    assert operator.kernel is not None  # a zero-padded operator keeps its real-space kernel
    # calibrated stress reading: -sigma_z, positive under load
    kernel = -operator.kernel if quantity == "stress" else operator.kernel
    kernel.setflags(write=False)
    return kernel


def reading_kernel(spec: ForwardModelSpec) -> np.ndarray:
    """Reading at a fine cell centre per unit pressure on the fine cell at offset 0.

    Returns the exact cell-integrated kernel on offsets -(2N-1)..(2N-1) per axis (N the
    load-grid size), enough for both boundary models. Cached per configuration.
    """
    rows, cols = spec.load_shape
    return _kernel(
        spec.quantity,
        (2 * rows, 2 * cols),
        spec.load_pitch,
        spec.depth,
        spec.material,
        spec.thickness,
    )


def _periodize(kernel: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Wrap a kernel on offsets -(2N-1)..(2N-1) onto the period 2N, per axis."""
    rows, cols = shape
    result = np.zeros((2 * rows, 2 * cols))
    row_index = np.arange(-(2 * rows - 1), 2 * rows) % (2 * rows)
    col_index = np.arange(-(2 * cols - 1), 2 * cols) % (2 * cols)
    partial = np.zeros((2 * rows, kernel.shape[1]))
    np.add.at(partial, row_index, kernel)
    np.add.at(result.T, col_index, partial.T)
    return result


def reflect_eigenvalues(spec: ForwardModelSpec) -> np.ndarray:
    """DCT-II eigenvalues of the reflective-boundary model on the fine load grid.

    kappa[m1, m2] = sum_t k_per(t) cos(pi m1 t1 / N1) cos(pi m2 t2 / N2), with k_per the
    kernel periodized with period 2N (the FFT of length 2N of a symmetric kernel is real).
    """
    periodic = _periodize(reading_kernel(spec), spec.load_shape)
    rows, cols = spec.load_shape
    return np.real(fft.fft2(periodic))[:rows, :cols]


def fold_1d(coarse: int, factor: int) -> tuple[np.ndarray, np.ndarray]:
    r"""Where each fine DCT mode lands after k-fold block averaging, and with what weight.

    Parameters
    ----------
    coarse : int
        Coarse size N.
    factor : int
        Oversampling k; the fine size is k N.

    Returns
    -------
    index : numpy.ndarray of int, shape (k N,)
        Coarse mode mu reached by each fine mode m, or -1 when the weight is zero.
    weight : numpy.ndarray, shape (k N,)
        w with B phi_m = w psi_mu for the orthonormal DCT-II bases phi (fine), psi (coarse).

    Notes
    -----
    The block average of cos(pi m (i + 1/2) / (k N)) over k fine cells is
    cos(pi m (j + 1/2) / N) D_k(theta) / k with the Dirichlet factor
    :math:`D_k(\theta) = \sin(k\theta/2)/\sin(\theta/2)`, theta = pi m / (k N); the cosine
    aliases to mode mu = m mod 2N (or 2N - that) with a sign.
    """
    fine = coarse * factor
    m = np.arange(fine)
    q, r = np.divmod(m, 2 * coarse)
    sign = np.where(q % 2 == 0, 1.0, -1.0)
    index = np.where(r < coarse, r, 2 * coarse - r)
    sign = np.where(r < coarse, sign, -sign)
    theta = np.pi * m / fine
    with np.errstate(invalid="ignore", divide="ignore"):
        dirichlet = np.where(m == 0, factor, np.sin(factor * theta / 2) / np.sin(theta / 2))
    scale_fine = np.where(m == 0, 1 / np.sqrt(2), 1.0)
    scale_coarse = np.where(index == 0, 1 / np.sqrt(2), 1.0)
    weight = sign * scale_fine / scale_coarse * dirichlet / factor / np.sqrt(factor)
    zero = r == coarse
    return np.where(zero, -1, index), np.where(zero, 0.0, weight)


def penalty_eigenvalues(shape: tuple[int, int], order: int) -> np.ndarray:
    """DCT-II eigenvalues of L^T L for the Tikhonov penalties, Neumann boundaries.

    order 0: L = I; order 1: L = forward differences along both axes (cell units), so
    L^T L is the Neumann Laplacian; order 2: L = that Laplacian, L^T L its square.
    """
    rows, cols = shape
    along_rows = 4 * np.sin(np.pi * np.arange(rows) / (2 * rows)) ** 2
    along_cols = 4 * np.sin(np.pi * np.arange(cols) / (2 * cols)) ** 2
    laplacian = along_rows[:, None] + along_cols[None, :]
    if order == 0:
        return np.ones(shape)
    return laplacian if order == 1 else laplacian**2


def _difference_matrix(count: int) -> np.ndarray:
    """(count - 1, count) forward differences."""
    return np.eye(count - 1, count, 1) - np.eye(count - 1, count)


def dense_penalty(shape: tuple[int, int], order: int) -> np.ndarray:
    """L^T L of `penalty_eigenvalues` as an explicit matrix (row-major cells)."""
    rows, cols = shape
    if order == 0:
        return np.eye(rows * cols)
    along_rows = np.kron(_difference_matrix(rows), np.eye(cols))
    along_cols = np.kron(np.eye(rows), _difference_matrix(cols))
    laplacian = along_rows.T @ along_rows + along_cols.T @ along_cols
    return laplacian if order == 1 else laplacian @ laplacian


def block_average(fine: np.ndarray, factor: int) -> np.ndarray:
    """Mean over k x k blocks of the last two axes."""
    if factor == 1:
        return fine
    *batch, rows, cols = fine.shape
    blocks = fine.reshape(*batch, rows // factor, factor, cols // factor, factor)
    return blocks.mean(axis=(-3, -1))


def block_spread(coarse: np.ndarray, factor: int) -> np.ndarray:
    """Adjoint of `block_average`: each value spread over its block, divided by k^2."""
    if factor == 1:
        return coarse
    spread = np.repeat(np.repeat(coarse, factor, axis=-2), factor, axis=-1)
    return spread / factor**2


def _rows_to_taxels(fine_matrix: np.ndarray, spec: ForwardModelSpec) -> np.ndarray:
    """Block-average the rows of a (fine cells, fine cells) matrix into taxel rows."""
    rows, cols = spec.load_shape
    cube = fine_matrix.T.reshape(rows * cols, rows, cols)
    return block_average(cube, spec.oversampling).reshape(rows * cols, -1).T


def zero_matrix(spec: ForwardModelSpec) -> np.ndarray:
    """Dense (taxels, load cells) matrix of the zero-boundary model (row-major)."""
    rows, cols = spec.load_shape
    kernel = reading_kernel(spec)
    i = np.arange(rows)
    j = np.arange(cols)
    row_offset = (i[:, None] - i[None, :]) + 2 * rows - 1  # (taxel row, load row)
    col_offset = (j[:, None] - j[None, :]) + 2 * cols - 1
    fine = kernel[row_offset[:, None, :, None], col_offset[None, :, None, :]]
    return _rows_to_taxels(fine.reshape(rows * cols, rows * cols), spec)


def reflect_matrix(spec: ForwardModelSpec) -> np.ndarray:
    """Dense matrix of the reflective model, summed over mirror images (independent of DCT)."""
    rows, cols = spec.load_shape
    periodic = _periodize(reading_kernel(spec), spec.load_shape)

    def images(count: int) -> list[np.ndarray]:
        i = np.arange(count)
        direct = (i[:, None] - i[None, :]) % (2 * count)
        mirror = (i[:, None] + i[None, :] + 1) % (2 * count)
        return [direct, mirror]

    fine = np.zeros((rows, cols, rows, cols))
    for row_index in images(rows):
        for col_index in images(cols):
            fine += periodic[row_index[:, None, :, None], col_index[None, :, None, :]]
    return _rows_to_taxels(fine.reshape(rows * cols, rows * cols), spec)


def reflect_normal_kernel(spec: ForwardModelSpec) -> np.ndarray:
    """The 2N-periodic kernel of K^T K for the reflective model on the load grid (k = 1).

    Reflective convolutions compose: K^T K = K K is the reflective convolution whose
    periodic kernel has the squared spectrum of K's.
    """
    spectrum = np.real(fft.fft2(_periodize(reading_kernel(spec), spec.load_shape)))
    return np.real(fft.ifft2(spectrum**2))


def reflect_normal_block(kernel: np.ndarray, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """Entries of a reflective convolution between the cells (rows[i], cols[i]) (n, n).

    The images of `reflect_matrix` (direct and mirrored, per axis), gathered for a few
    cells only: O(n^2) instead of the whole matrix.
    """
    period_rows, period_cols = kernel.shape
    flat = kernel.ravel()
    row_images = [
        (np.subtract.outer(rows, rows) % period_rows) * period_cols,
        (np.add.outer(rows, rows + 1) % period_rows) * period_cols,
    ]
    col_images = [
        np.subtract.outer(cols, cols) % period_cols,
        np.add.outer(cols, cols + 1) % period_cols,
    ]
    block = np.zeros((rows.size, rows.size))
    for row_index in row_images:
        for col_index in col_images:
            block += flat.take(row_index + col_index)
    return block
