"""The result of a reconstruction: a named, frozen object (SciPy style), never a tuple."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from taxel.reconstruction._choice import ParameterCurve

__all__ = ["ReconstructionResult"]


@dataclass(frozen=True)
class ReconstructionResult:
    """A recovered pressure field (or a batch of them) and how it was obtained.

    Attributes
    ----------
    pressure : numpy.ndarray, shape (..., *load_shape)
        Recovered pressure on the load grid [Pa].
    regularization : float or numpy.ndarray
        The lambda used (per frame for a batch); relative units: lambda = 1 weighs the
        penalty like the largest singular value of the data term. For total variation, the
        weight mu [Pa] of the total variation.
    rule : str
        How lambda was chosen: "gcv", "lcurve", "discrepancy", or "given".
    method : str
        "tikhonov", "tsvd", "nonneg", "tv", "support" or "naive".
    order : int
        Tikhonov order of the penalty (0 identity, 1 gradient, 2 Laplacian).
    residual_norm : float or numpy.ndarray
        |A x - b| over the live taxels, in reading units.
    solution_norm : float or numpy.ndarray
        |L x| (the penalty seminorm; for TV the total variation) [Pa per cell^order].
    noise_level : float or numpy.ndarray or None
        The reading noise std used by the discrepancy principle (given or estimated).
    curve : ParameterCurve or None
        The GCV and L-curve data the rule looked at (None for a given lambda).
    spacing : float
        Load-grid cell size [m].
    converged : bool
        Whether an iterative solve met its tolerance (always True for direct solves).
    n_iterations : int
        Iterations of an iterative solve (0 for direct solves).
    residual : float
        The stopping quantity of an iterative solve (relative change; 0 for direct solves).
    message : str
        How the solve ended.
    support : numpy.ndarray of bool or None
        The load cells allowed to carry load (method "support"), else None.
    """

    pressure: np.ndarray = field(repr=False)
    regularization: float | np.ndarray
    rule: str
    method: str
    order: int
    residual_norm: float | np.ndarray
    solution_norm: float | np.ndarray
    noise_level: float | np.ndarray | None
    curve: ParameterCurve | None = field(repr=False)
    spacing: float
    converged: bool = True
    n_iterations: int = 0
    residual: float = 0.0
    message: str = "direct solve"
    support: np.ndarray | None = field(default=None, repr=False)

    @property
    def normal_force(self) -> float | np.ndarray:
        """Total force sum(p) dA [N] (per frame for a batch)."""
        total = self.pressure.sum(axis=(-2, -1)) * self.spacing**2
        return float(total) if np.ndim(total) == 0 else total
