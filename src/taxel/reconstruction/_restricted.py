"""The restricted problem of the support method: ridge with GCV, then non-negative.

On a support S of few cells, min |A x - b|^2 + w |x|^2 over x >= 0 is a small quadratic
program in the normal matrix A_S^T A_S. `nonneg_quadratic` solves it exactly (primal-dual
active set); `restricted_fit` chooses w by GCV from one eigendecomposition; and
`component_scores` measures how significant the load of each piece of S is.
"""

from __future__ import annotations

import numpy as np
from scipy import linalg, optimize

__all__ = ["component_scores", "nonneg_quadratic", "restricted_fit"]

_GRID_POINTS = 240  # lambda2 grid, log-spaced over 14 decades below the largest eigenvalue


def nonneg_quadratic(
    matrix: np.ndarray, vector: np.ndarray, passive: np.ndarray, *, max_iterations: int = 50
) -> tuple[np.ndarray, int, bool]:
    """Minimize 1/2 y^T Q y - h^T y over y >= 0, Q symmetric positive definite.

    Primal-dual active set: solve on the passive set, then move every cell whose value is
    not positive out and every held cell whose multiplier Q y - h is negative in, until
    the sets repeat (the KKT conditions then hold). Lawson and Hanson's NNLS
    (`scipy.optimize.nnls`) finishes the rare cases that cycle.

    Returns
    -------
    y : numpy.ndarray
    iterations : int
    converged : bool
        False only if the fallback was needed.
    """
    passive = np.asarray(passive, dtype=bool).copy()
    scale = max(float(np.abs(vector).max()), 1e-300)
    for iteration in range(1, max_iterations + 1):
        y = np.zeros(vector.size)
        index = np.flatnonzero(passive)
        if index.size:
            y[index] = linalg.solve(
                matrix[np.ix_(index, index)], vector[index], assume_a="pos", check_finite=False
            )
        multiplier = matrix @ y - vector
        updated = np.where(passive, y > 0, multiplier < -1e-12 * scale)
        if np.array_equal(updated, passive):
            return y, iteration, True
        passive = updated
    factor = linalg.cholesky(matrix)
    y, _ = optimize.nnls(factor, linalg.solve_triangular(factor, vector, trans="T"))
    return y, max_iterations, False


def restricted_fit(normal: np.ndarray, rhs: np.ndarray, energy: float, count: int):
    """Ridge on a support with lambda by GCV, then non-negative.

    Returns (values, weight, std per cell per unit reading noise, GCV score, active-set
    steps, converged), or None when the GCV fit spends more than half of the readings'
    degrees of freedom.
    """
    eigenvalues, vectors = np.linalg.eigh(normal)
    eigenvalues = np.maximum(eigenvalues, 0.0)
    projected = vectors.T @ rhs
    top = max(float(eigenvalues[-1]), 1e-300)
    weights = np.logspace(np.log10(top) - 14, np.log10(top) + 2, _GRID_POINTS)[:, None]
    shrink = (eigenvalues + 2 * weights) / (eigenvalues + weights) ** 2
    residual = energy - np.sum(projected**2 * shrink, axis=1)
    trace = np.sum(eigenvalues / (eigenvalues + weights), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        gcv = np.where(count - trace > 0.5, count * residual / (count - trace) ** 2, np.inf)
    best = int(np.argmin(gcv))
    if trace[best] > count / 2:
        return None
    weight = float(weights[best, 0])
    unconstrained = vectors @ (projected / (eigenvalues + weight))
    # covariance of the unconstrained estimate: V diag(e / (e + w)^2) V^T per unit variance
    std = np.sqrt(vectors**2 @ (eigenvalues / (eigenvalues + weight) ** 2))
    system = normal + weight * np.eye(rhs.size)
    values, iterations, converged = nonneg_quadratic(system, rhs, unconstrained > 0)
    return values, weight, std, float(gcv[best]), iterations, converged


def component_scores(normal: np.ndarray, rhs: np.ndarray, weight: float, labels: np.ndarray):
    """Total of each labelled group of cells in the ridge estimate over its std.

    Per unit reading noise: z_j = 1_j^T x / sqrt(1_j^T Cov 1_j), Cov = V diag(e/(e+w)^2) V^T.
    """
    eigenvalues, vectors = np.linalg.eigh(normal)
    eigenvalues = np.maximum(eigenvalues, 0.0)
    estimate = vectors @ ((vectors.T @ rhs) / (eigenvalues + weight))
    indicators = (labels[:, None] == np.unique(labels)[None, :]).astype(float)
    spread = (vectors.T @ indicators) ** 2 * (eigenvalues / (eigenvalues + weight) ** 2)[:, None]
    return indicators.T @ estimate / np.sqrt(np.maximum(spread.sum(axis=0), 1e-300))
