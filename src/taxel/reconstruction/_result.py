"""The result of a reconstruction: a named, frozen object (SciPy style), never a tuple."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from taxel.reconstruction._choice import ParameterCurve

__all__ = ["ReconstructionResult", "bound_message"]

# why each rule ends at the upper, lower end of its range of lambda
_WHY = {
    "discrepancy": (
        "no residual reaches tau sigma sqrt(m) (the noise level is as large as the readings)",
        "every residual exceeds tau sigma sqrt(m) (the noise level is below the misfit "
        "that no lambda removes)",
    ),
    "gcv": ("the GCV function is least there",) * 2,
    "lcurve": ("the L-curve has no corner inside",) * 2,
}


def bound_message(
    rule: str,
    regularization: np.ndarray,
    at_bound: np.ndarray,
    searched: tuple[float, float],
    *,
    solve: str = "direct solve",
) -> str:
    """`solve`, and when the rule took an end of its range of lambda, which and why.

    `regularization` and `at_bound` are per frame (B,), `searched` the smallest and largest
    lambda the rule could choose (`ParameterScan.searched`).
    """
    if not np.any(at_bound):
        return solve
    low, high = searched
    chosen = np.asarray(regularization)[np.asarray(at_bound)]
    ends = [(end, why) for end, why in zip((high, low), _WHY[rule], strict=True)]
    parts = []
    for (end, why), name in zip(ends, ("largest", "smallest"), strict=True):
        # (np.isclose, the same test, costs ~20 us a call: a tenth of a frame's solve)
        count = int(np.count_nonzero(np.abs(chosen - end) <= 1e-8 + 1e-9 * abs(end)))
        if count:
            frames = "" if at_bound.size == 1 else f" in {count} of {at_bound.size} frames"
            parts.append(f"lambda held at the {name} of its range, {end:.3g}{frames}, as {why}")
    return (
        f"{solve}; the {rule} rule found no lambda inside [{low:.3g}, {high:.3g}]: "
        + "; ".join(parts)
    )


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
        weight mu [Pa] of the total variation. For method "support", the lambda of its
        second stage (the ridge on the support, chosen by GCV; see `SupportSolver.solve`).
    rule : str
        How lambda was chosen: "gcv", "lcurve", "discrepancy", or "given"; for method
        "support", how `first_regularization` was.
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
    first_regularization : float or None
        Method "support": the lambda of its first stage (the Tikhonov estimate whose
        support is fitted), given or chosen by `rule`; None for the other methods.
    at_bound : bool or numpy.ndarray of bool
        Whether `rule` found no lambda inside its range and took the range's end (per frame
        for a batch; the first stage's for method "support"); `message` says which. The
        discrepancy principle does when no lambda's residual reaches tau sigma sqrt(m): a
        noise level as large as the readings' own part that the penalty does not smooth
        away; lambda is then the largest of the range, which leaves about 1 % of every mode
        the penalty acts on. False for a given lambda. For method "tv", whose search for
        mu is not on a grid: True when the search ended without reaching its target
        residual or bracketing it (the message gives the mu, residual and target).
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
    first_regularization: float | None = None
    at_bound: bool | np.ndarray = False

    @property
    def normal_force(self) -> float | np.ndarray:
        """Total force sum(p) dA [N] (per frame for a batch)."""
        total = self.pressure.sum(axis=(-2, -1)) * self.spacing**2
        return float(total) if np.ndim(total) == 0 else total

    @property
    def centroid_m(self) -> tuple[float, float] | np.ndarray:
        """Centre of pressure (x, y) in the sensor frame [m] (per frame for a batch).

        The load grid is centred on the array (as `taxel.sensor.LoadGrid.coordinates`).
        NaN where the total force is not positive, or where the centre falls off the load
        grid: a load that presses everywhere has its centre within the contact, so a centre
        off the grid is that of a signed map whose net force is a small difference of large
        ones (noise, or a field pulling as much as it pushes), and means nothing. Every cell
        weighs in with its signed pressure, so the noise of the unloaded cells of a Tikhonov
        or TSVD map moves it; methods "support" and "nonneg" keep the load on the contact.

        Returns
        -------
        (float, float) or numpy.ndarray, shape (..., 2)

        Examples
        --------
        >>> pressure = np.zeros((5, 5))
        >>> pressure[1, 3] = 2e5  # row 1, column 3: x = +1 cell, y = -1 cell
        >>> result = ReconstructionResult(pressure, 0.0, "given", "naive", 0, 0.0, 0.0,
        ...                               None, None, spacing=1e-3)
        >>> [round(v * 1e3, 6) for v in result.centroid_m]
        [1.0, -1.0]
        """
        pressure = self.pressure
        rows, cols = pressure.shape[-2:]
        x = (np.arange(cols) - (cols - 1) / 2) * self.spacing
        y = (np.arange(rows) - (rows - 1) / 2) * self.spacing
        total = pressure.sum(axis=(-2, -1))
        positive = total > 0
        safe = np.where(positive, total, 1.0)
        centre = np.stack(
            [pressure.sum(axis=-2) @ x / safe, pressure.sum(axis=-1) @ y / safe], axis=-1
        )
        half_width = np.array([cols / 2, rows / 2]) * self.spacing  # the grid's edges
        on_grid = (np.abs(centre) <= half_width).all(axis=-1)
        centre = np.where((positive & on_grid)[..., None], centre, np.nan)
        if centre.ndim == 1:
            return float(centre[0]), float(centre[1])
        return centre
