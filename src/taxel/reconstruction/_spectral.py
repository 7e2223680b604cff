r"""Spectral factorizations of the regularized problem, built once per sensor and penalty.

Tikhonov regularization of any order, min |A x - b|^2 + lambda^2 c |L x|^2, reduces to
independent scalar problems on "generalized modes" with eigenvalues g_i: the filter factor
is f_i = g_i / (g_i + lambda^2) and the solution is a fixed linear synthesis of f_i beta_i.

Fast (reflective model, DCT): fine DCT mode j reaches one coarse mode mu with weight s_j;
per coarse mode the problem is min (s - beta)^2 + w s^2 / g with g = sum_j s_j^2 / l_j
(l_j the penalty eigenvalue), and y_j = s s_j / (l_j g). Dense (any model, small grids):
with c = A 1 the image of the penalty's null space (constants) and A~ = (I - c c^T/|c|^2) A,
the SVD of the standard form A~ M^(+1/2) = U diag(sqrt g) V^T gives the same form
(M^(+1/2) applied by DCT).
Here c = |A|^2 / |L|^2 makes lambda dimensionless: lambda = 1 weighs the penalty like the
largest singular value of the data term.
"""

from __future__ import annotations

import numpy as np
from scipy import fft, linalg

from taxel.reconstruction._mirror import mirror_blocks
from taxel.reconstruction._model import dense_penalty, fold_1d, penalty_eigenvalues
from taxel.reconstruction._operator import SensorOperator

__all__ = ["DenseSpectrum", "FastSpectrum", "Spectrum", "build_spectrum"]


def _dct(values: np.ndarray) -> np.ndarray:
    return fft.dctn(values, norm="ortho", axes=(-2, -1), workers=1)


def _idct(values: np.ndarray) -> np.ndarray:
    return fft.idctn(values, norm="ortho", axes=(-2, -1), workers=1)


def _slots(index: np.ndarray, coarse: int) -> list[np.ndarray]:
    """Fine modes folding onto each coarse mode, one (coarse,) array per slot (-1: none)."""
    slots: list[np.ndarray] = []
    for fine, target in enumerate(index):
        if target < 0:
            continue
        for slot in slots:
            if slot[target] < 0:
                slot[target] = fine
                break
        else:
            slots.append(np.full(coarse, -1))
            slots[-1][target] = fine
    return slots


def _dct_basis(size: int) -> np.ndarray:
    """Orthonormal DCT-II basis, shape (size, size): column m is mode m over the cells."""
    return fft.idct(np.eye(size), norm="ortho", axis=0, workers=1)


def _slot_matrix(basis: np.ndarray, slot: np.ndarray) -> np.ndarray:
    """(cells, coarse): the fine mode of `slot` over the cells, 0 where the slot is empty."""
    return np.where(slot[None, :] >= 0, basis[:, np.maximum(slot, 0)], 0.0)


class Spectrum:
    """Common interface of the factorizations (see the module docstring).

    Attributes
    ----------
    g : numpy.ndarray, shape (r,)
        Normalized generalized eigenvalues of the reachable modes (max 1 for order 0).
    n_free : int
        Unpenalized directions (the mean, for orders 1 and 2): their filter factor is 1.
    count : int
        Number of readings in the fit (live taxels).
    scale : float
        c, so that the penalty is lambda^2 c |L x|^2.
    exact_mask : bool
        False when dead taxels exist but the factorization is of the full array (fast);
        solvers then handle dead taxels iteratively.
    """

    g: np.ndarray
    n_free: int
    count: int
    scale: float
    exact_mask: bool
    load_shape: tuple[int, int]

    norm_squared: float
    penalty: np.ndarray

    def apply_penalty(self, values: np.ndarray) -> np.ndarray:
        """M x = L^T L x on the load grid (Neumann boundaries, diagonal in the DCT)."""
        return _idct(_dct(values) * self.penalty)

    def analyze(self, frames: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(beta (B, r), free (B, n_free), unreachable energy (B,)) of frames (B, rows, cols)."""
        raise NotImplementedError

    def synthesize(
        self, filtered: np.ndarray, free: np.ndarray, out: np.ndarray | None = None
    ) -> np.ndarray:
        """Pressure (B, *load_shape) from filtered coefficients f * beta and the free part.

        Written into `out` (B, *load_shape) when given.
        """
        raise NotImplementedError

    def shifted_solve(self, rhs: np.ndarray, alpha: float, beta: float) -> np.ndarray:
        """Solve (A^T A + alpha M + beta I) x = rhs on the load grid (M = L^T L)."""
        raise NotImplementedError

    def cell_variance(self, factors: np.ndarray) -> np.ndarray:
        """Variance of each load cell of the solution with filter `factors` (r,).

        Per unit variance of white reading noise, shape load_shape.
        """
        raise NotImplementedError


class FastSpectrum(Spectrum):
    """DCT-diagonal factorization of the reflective model (any oversampling)."""

    def __init__(self, operator: SensorOperator, order: int) -> None:
        spec = operator.spec
        k = spec.oversampling
        rows, cols = spec.shape
        self.load_shape = spec.load_shape
        self.order = order
        self.count = rows * cols
        self.exact_mask = not spec.dead_taxels
        self._k = k
        row_index, row_weight = fold_1d(rows, k)
        col_index, col_weight = fold_1d(cols, k)
        self._row_slots, self._col_slots = _slots(row_index, rows), _slots(col_index, cols)
        weight = row_weight[:, None] * col_weight[None, :] * operator.eigenvalues
        valid = (row_index[:, None] >= 0) & (col_index[None, :] >= 0)
        group = np.where(valid, row_index[:, None] * cols + col_index[None, :], 0)
        penalty = penalty_eigenvalues(self.load_shape, order)
        self._weight, self._group, self.penalty = weight, group, penalty
        self._group_flat = group.ravel()
        self._members_of_mean = np.flatnonzero((group.ravel() == 0) & valid.ravel())
        norm_a = np.bincount(self._group_flat, (weight**2).ravel(), minlength=rows * cols)
        self.norm_squared = float(norm_a.max())
        self.scale = self.norm_squared / float(penalty.max())
        free = (penalty == 0) & valid  # only the constant fine mode, which reaches mode 0
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(free | ~valid, 0.0, weight**2 / penalty)
        g_real = np.bincount(self._group_flat, ratio.ravel(), minlength=rows * cols)
        self.n_free = int(free.any())
        self._g_real = g_real
        self.g = g_real[self.n_free :] / self.scale
        with np.errstate(divide="ignore", invalid="ignore"):
            expansion = weight / (penalty * g_real[group])
        expansion = np.where(valid & ~free & np.isfinite(expansion), expansion, 0.0)
        if self.n_free:  # the mean's group: only the constant mode carries it, unpenalized
            expansion = np.where(group == 0, 0.0, expansion)
            expansion = np.where(free, 1.0 / np.where(free, weight, 1.0), expansion)
        self._expansion = expansion
        self._factor_cache: dict[tuple[float, float], np.ndarray] = {}

    def analyze(self, frames: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        coefficients = _dct(frames).reshape(frames.shape[0], -1)
        free = coefficients[:, : self.n_free]
        return coefficients[:, self.n_free :], free, np.zeros(frames.shape[0])

    def synthesize(
        self, filtered: np.ndarray, free: np.ndarray, out: np.ndarray | None = None
    ) -> np.ndarray:
        batch = filtered.shape[0]
        full = np.concatenate([free, filtered], axis=1) if self.n_free else filtered
        if self._k == 1:
            fine = full.reshape(batch, *self.load_shape) * self._expansion
        else:
            fine = full[:, self._group_flat].reshape(batch, *self.load_shape) * self._expansion
        if out is None:
            return _idct(fine)
        out[...] = _idct(fine)
        return out

    def cell_variance(self, factors: np.ndarray) -> np.ndarray:
        # x(i, j) = sum over coarse modes mu of f_mu beta_mu s_mu(i, j), with independent unit
        # beta_mu and s_mu the sum of the fine modes folding onto mu: var = sum_mu s_mu^2.
        # A fine mode is a (row mode, column mode) pair, so s_mu^2 is separable for each
        # pair of row slots (a, a') and column slots (b, b'). Near the edges the cosines of
        # the low modes do not average out: a corner cell has up to 4 times the mean variance.
        full = np.concatenate([np.ones(self.n_free), factors])
        amplitude = self._expansion * full[self._group]
        row_basis = _dct_basis(self.load_shape[0])
        col_basis = _dct_basis(self.load_shape[1])
        rows = [_slot_matrix(row_basis, slot) for slot in self._row_slots]
        cols = [_slot_matrix(col_basis, slot) for slot in self._col_slots]
        parts = [
            np.where((rs[:, None] >= 0) & (cs[None, :] >= 0), amplitude[rs][:, cs], 0.0)
            for rs in self._row_slots
            for cs in self._col_slots
        ]
        pairs = [(a, b) for a in range(len(rows)) for b in range(len(cols))]
        variance = np.zeros(self.load_shape)
        for first, (a, b) in enumerate(pairs):
            for second, (c, d) in enumerate(pairs):
                inner = (parts[first] * parts[second]) @ (cols[b] * cols[d]).T
                variance += (rows[a] * rows[c]) @ inner
        return variance

    def shifted_solve(self, rhs: np.ndarray, alpha: float, beta: float) -> np.ndarray:
        transformed = _dct(rhs)
        diagonal = alpha * self.penalty + beta
        weight = self._weight
        if self._k == 1:
            return _idct(transformed / (weight**2 + diagonal))
        # Sherman-Morrison per coarse group: (s s^T + D)^-1 r
        with np.errstate(divide="ignore", invalid="ignore"):
            scaled = np.where(diagonal > 0, weight / diagonal, 0.0)
            inverse = np.where(diagonal > 0, 1.0 / diagonal, 0.0)
        count = self._g_real.size
        projection = np.bincount(self._group_flat, (scaled * transformed).ravel(), count)
        energy = np.bincount(self._group_flat, (scaled * weight).ravel(), count)
        correction = projection / (1.0 + energy)
        result = inverse * transformed - scaled * correction[self._group]
        # the group of the mean may hold a zero of D: solve it directly (at most k^2 modes)
        members = self._members_of_mean
        s = weight.ravel()[members]
        system = np.outer(s, s) + np.diag(diagonal.ravel()[members])
        flat = result.reshape(-1)
        flat[members] = np.linalg.lstsq(system, transformed.ravel()[members], rcond=None)[0]
        return _idct(result)


class DenseSpectrum(Spectrum):
    """Eigen-factorization of a dense operator (any boundary model; dead taxels removed).

    An array with every taxel live, even sizes and a mirror-symmetric operator (the
    presets) is factorized and applied in its four mirror parts (module `_mirror`): the
    same modes, found and applied in a quarter of the dense products.
    """

    def __init__(self, operator: SensorOperator, order: int) -> None:
        spec = operator.spec
        self.load_shape = spec.load_shape
        self.order = order
        self._live = spec.live_taxels.ravel()
        full = operator.to_matrix()
        matrix = full[self._live]
        self._matrix = matrix
        self.count = int(matrix.shape[0])
        self.exact_mask = True
        penalty = penalty_eigenvalues(self.load_shape, order)
        self.penalty = penalty
        # |A| of the whole array: lambda means the same with or without dead taxels
        self.norm_squared = float(np.linalg.eigvalsh(full @ full.T)[-1])
        self.scale = self.norm_squared / float(penalty.max())
        cells = matrix.shape[1]
        if order == 0:
            self.n_free = 0
            reduced = matrix
            self._free_basis = np.zeros((cells, 0))
            self._image_of_mean = np.zeros((self.count, 0))
        else:
            self.n_free = 1
            mean = np.full(cells, 1.0 / np.sqrt(cells))
            image = matrix @ mean
            norm = float(np.linalg.norm(image))
            unit = image / norm
            reduced = matrix - np.outer(unit, unit @ matrix)
            self._free_basis = (mean / norm)[:, None]
            self._image_of_mean = unit[:, None]
        # standard form K = A~ M^(+1/2): its SVD keeps relative accuracy in sqrt(g), where an
        # eigen-decomposition of A~ M^+ A~^T would lose the small g below eps * g_max
        standard = self._penalty_power(reduced.T, -0.5).T if order else reduced
        self._all_live = bool(self._live.all())
        split = mirror_blocks(standard, spec.shape, self.load_shape) if self._all_live else None
        if split is None:
            vectors, singular, right = np.linalg.svd(standard, full_matrices=False)
            self._mirror = None
        else:
            vectors, singular, right, self._mirror = split
        keep = singular > singular.max() * max(standard.shape) * np.finfo(float).eps
        singular, vectors, right = singular[keep], vectors[:, keep], right[keep]
        expansion = right.T / singular
        if order:
            expansion = self._penalty_power(expansion, -0.5)
            # y -> y + (mean) a, with a fitting what A y leaves of b along A 1
            expansion -= self._free_basis @ (self._image_of_mean.T @ (matrix @ expansion))
        self._vectors, self._expansion = vectors, expansion
        # the expansion and the free direction side by side: one product synthesizes both
        self._synthesis = np.ascontiguousarray(np.hstack([expansion, self._free_basis]).T)
        if self._mirror is not None:
            self._mirror.keep(keep)
            self._mirror.prepare(vectors, self._synthesis, self._image_of_mean, self.load_shape)
        self.g = singular**2 / self.scale
        self._factor_cache: dict[tuple[float, float], tuple] = {}

    def _penalty_power(self, columns: np.ndarray, power: float) -> np.ndarray:
        """(M^+)^(-power) applied to each column (load-grid vectors), through the DCT."""
        cube = columns.T.reshape(-1, *self.load_shape)
        with np.errstate(divide="ignore"):
            factor = np.where(self.penalty > 0, np.abs(self.penalty) ** power, 0.0)
        return _idct(_dct(cube) * factor).reshape(cube.shape[0], -1).T

    def live(self, frames: np.ndarray) -> np.ndarray:
        """The live readings of frames (B, rows, cols) as (B, count)."""
        flat = frames.reshape(frames.shape[0], -1)
        return flat if self._all_live else flat[:, self._live]

    def analyze(self, frames: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        data = self.live(frames)
        if self._mirror is None:
            beta, free = data @ self._vectors, data @ self._image_of_mean
        else:
            beta, free = self._mirror.analyze(frames)
        if beta.shape[1] + self.n_free >= self.count:  # the modes span every reading
            return beta, free, np.zeros(data.shape[0])
        rest = np.einsum("ij,ij->i", data, data) - np.einsum("ij,ij->i", beta, beta)
        rest -= np.einsum("ij,ij->i", free, free)
        return beta, free, np.maximum(rest, 0.0)

    def synthesize(
        self, filtered: np.ndarray, free: np.ndarray, out: np.ndarray | None = None
    ) -> np.ndarray:
        if self._mirror is not None:
            return self._mirror.synthesize(filtered, free, out)
        coefficients = np.concatenate([filtered, free], axis=1) if self.n_free else filtered
        flat = None if out is None else out.reshape(filtered.shape[0], -1)
        flat = np.matmul(coefficients, self._synthesis, out=flat)
        return flat.reshape(filtered.shape[0], *self.load_shape)

    def cell_variance(self, factors: np.ndarray) -> np.ndarray:
        # beta = U^T b and the free part (along A 1, orthogonal to U) are independent
        variance = self._expansion**2 @ factors**2 + (self._free_basis**2).sum(axis=1)
        return variance.reshape(self.load_shape)

    def shifted_solve(self, rhs: np.ndarray, alpha: float, beta: float) -> np.ndarray:
        key = (float(alpha), float(beta))
        if key not in self._factor_cache:
            if len(self._factor_cache) > 4:
                self._factor_cache.clear()
            system = self._matrix.T @ self._matrix + beta * np.eye(self._matrix.shape[1])
            if alpha:
                system += alpha * dense_penalty(self.load_shape, self.order)
            self._factor_cache[key] = linalg.cho_factor(system)
        solution = linalg.cho_solve(self._factor_cache[key], rhs.reshape(-1))
        return solution.reshape(self.load_shape)

    def normal_rhs(self, frames: np.ndarray) -> np.ndarray:
        """A_live^T b for one frame (rows, cols)."""
        return (self.live(frames[None])[0] @ self._matrix).reshape(self.load_shape)


def build_spectrum(operator: SensorOperator, order: int) -> Spectrum:
    """The factorization matching an operator's representation."""
    if operator.representation == "dense":
        return DenseSpectrum(operator, order)
    if operator.boundary != "reflect":
        raise ValueError(
            "`boundary` 'zero' has no fast factorization; use representation='dense' "
            "(small grids) or boundary='reflect'"
        )
    return FastSpectrum(operator, order)
