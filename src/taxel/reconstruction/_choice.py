r"""Choice of the regularization parameter: GCV, the L-curve corner, the discrepancy principle.

All three work on the spectral form of the problem (`_spectral`): with filter factors
f_i(lambda), residual rho = sum (1 - f_i)^2 beta_i^2 (+ what no mode reaches), seminorm
eta = sum f_i^2 beta_i^2 / g_i and trace t = sum f_i (+ unpenalized directions), every curve
is a weighted sum of beta_i^2 whose weights depend only on g. The weights are tabulated once
per sensor on a grid of lambda; a frame then costs one matrix-vector product. Above 2048
modes the beta_i^2 are summed in bins of g 1/100 decade wide (g varies by 2.3 % in a bin).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from taxel._validation import as_finite_array, check_broadcast

__all__ = ["RULES", "ParameterCurve", "ParameterScan", "lcurve_curvature"]

RULES: tuple[str, ...] = ("gcv", "lcurve", "discrepancy")
_EXACT_LIMIT = 2048
_BINS_PER_DECADE = 100


@dataclass(frozen=True)
class ParameterCurve:
    """The curves a parameter rule looked at, on a grid of lambda (for plotting).

    Attributes
    ----------
    regularization : numpy.ndarray, shape (n,)
        The lambda grid (relative units, see `TikhonovSolver`).
    residual_norm : numpy.ndarray, shape (..., n)
        |A x - b| over the live taxels, in reading units.
    gcv : numpy.ndarray, shape (..., n)
        The GCV function m |r|^2 / (m - trace)^2.
    solution_norm : numpy.ndarray, shape (..., n)
        |L x|, the penalty seminorm [Pa per cell^order] (computed when first read; NaN for
        a batch of more than 8 frames, unless its rule was the L-curve).
    curvature : numpy.ndarray, shape (..., n)
        Curvature of the L-curve (log |r|, log |L x|); the corner is its maximum (computed
        when first read).
    """

    regularization: np.ndarray = field(repr=False)
    residual_norm: np.ndarray = field(repr=False)
    gcv: np.ndarray = field(repr=False)
    # () -> (solution_norm, curvature): only plots and the L-curve rule need them
    lcurve: Callable[[], tuple[np.ndarray, np.ndarray]] = field(repr=False, compare=False)

    @cached_property
    def _lcurve_values(self) -> tuple[np.ndarray, np.ndarray]:
        return self.lcurve()

    @property
    def solution_norm(self) -> np.ndarray:
        """|L x| on the grid, shape (..., n)."""
        return self._lcurve_values[0]

    @property
    def curvature(self) -> np.ndarray:
        """Curvature of the L-curve on the grid, shape (..., n)."""
        return self._lcurve_values[1]

    def frame(self, index: int) -> ParameterCurve:
        """The curves of one frame of a batch."""
        return ParameterCurve(
            self.regularization,
            self.residual_norm[index],
            self.gcv[index],
            _FrameOf(self, index),
        )


def join_curves(curves: list[ParameterCurve]) -> ParameterCurve:
    """The curves of consecutive parts of a batch as one batch's."""
    return ParameterCurve(
        curves[0].regularization,
        np.concatenate([c.residual_norm for c in curves]),
        np.concatenate([c.gcv for c in curves]),
        _Joined(curves),
    )


class _Joined:
    """The L-curves of consecutive parts of a batch, joined when first asked for."""

    def __init__(self, curves: list[ParameterCurve]) -> None:
        self.curves = curves

    def __call__(self) -> tuple[np.ndarray, np.ndarray]:
        return (
            np.concatenate([c.solution_norm for c in self.curves]),
            np.concatenate([c.curvature for c in self.curves]),
        )


class _FrameOf:
    """One frame's L-curve, taken from its batch's when first asked for."""

    def __init__(self, batch: ParameterCurve, index: int) -> None:
        self.batch, self.index = batch, index

    def __call__(self) -> tuple[np.ndarray, np.ndarray]:
        return self.batch.solution_norm[self.index], self.batch.curvature[self.index]


class _Missing:
    """No L-curve (NaN), for batches that did not keep what it needs."""

    def __init__(self, shape: tuple[int, ...]) -> None:
        self.shape = shape

    def __call__(self) -> tuple[np.ndarray, np.ndarray]:
        return np.full(self.shape, np.nan), np.full(self.shape, np.nan)


class _LCurve:
    """The seminorm and L-curve curvature of frames, computed when first asked for."""

    def __init__(self, scan: ParameterScan, data: np.ndarray, residual: np.ndarray) -> None:
        self.scan, self.data, self.residual = scan, data, residual

    def __call__(self) -> tuple[np.ndarray, np.ndarray]:
        return self.scan.lcurve(self.data, self.residual)


def lcurve_curvature(
    regularization: np.ndarray,
    residual: np.ndarray,
    seminorm: np.ndarray,
    seminorm_derivative: np.ndarray,
) -> np.ndarray:
    r"""Curvature of the L-curve (log |r|, log |L x|) of Tikhonov regularization.

    Parameters
    ----------
    regularization : array_like
        lambda.
    residual : array_like
        rho = |r|^2 at lambda.
    seminorm : array_like
        eta = |L x|^2 at lambda.
    seminorm_derivative : array_like
        d eta / d lambda = -(4 / lambda) sum (1 - f_i) f_i^2 beta_i^2 / g_i (< 0).

    Returns
    -------
    numpy.ndarray
        kappa, positive where the curve bends towards the origin (the corner).

    Notes
    -----
    With rho' = -lambda^2 eta' (a property of Tikhonov filters),

    .. math:: \kappa = -2\,\frac{\eta\rho}{\eta'}\,
              \frac{\lambda^2\eta'\rho + 2\lambda\eta\rho + \lambda^4\eta\eta'}
                   {(\lambda^4\eta^2 + \rho^2)^{3/2}}

    (P. C. Hansen, *Discrete Inverse Problems*, SIAM 2010, sec. 5.3, derived again here
    for the curve of log-norms and checked against finite differences in the tests).

    Examples
    --------
    A Picard-like spectrum with a noise floor of 1e-4: the corner sits near the noise.

    >>> import numpy as np
    >>> g = np.logspace(0, -12, 200)
    >>> beta2 = (np.sqrt(g) + 1e-4) ** 2
    >>> lam = np.logspace(-6, 0, 601)
    >>> f = g / (g + lam[:, None] ** 2)
    >>> rho = ((1 - f) ** 2 * beta2).sum(axis=1)
    >>> eta = (f**2 * beta2 / g).sum(axis=1)
    >>> deta = -(4 / lam) * ((1 - f) * f**2 * beta2 / g).sum(axis=1)
    >>> print(f"{lam[np.argmax(lcurve_curvature(lam, rho, eta, deta))]:.1e}")
    7.4e-05
    """
    names = ("regularization", "residual", "seminorm", "seminorm_derivative")
    arrays = [
        as_finite_array(name, value)
        for name, value in zip(
            names, (regularization, residual, seminorm, seminorm_derivative), strict=False
        )
    ]
    for name, array in zip(names, arrays, strict=False):
        if array.size == 0:
            raise ValueError(f"`{name}` must not be empty, got shape {array.shape}")
    check_broadcast(names, *arrays)
    return _curvature(*arrays)


def _curvature(lam: np.ndarray, rho: np.ndarray, eta: np.ndarray, deta: np.ndarray) -> np.ndarray:
    """`lcurve_curvature` without the checks; zero where it is not finite."""
    lam, rho, eta, deta = (np.asarray(v, dtype=float) for v in (lam, rho, eta, deta))
    with np.errstate(divide="ignore", invalid="ignore"):
        numerator = lam**2 * deta * rho + 2 * lam * eta * rho + lam**4 * eta * deta
        kappa = -2 * (eta * rho / deta) * numerator / (lam**4 * eta**2 + rho**2) ** 1.5
    return np.nan_to_num(kappa, nan=0.0, posinf=0.0, neginf=0.0)


def _parabola_vertices(x: np.ndarray, y: np.ndarray, index: np.ndarray) -> np.ndarray:
    """Vertex of the parabola through three grid points around each row's `index` (B,).

    x is uniform (n,), y holds one row per frame (B, n); at the grid's ends, or where the
    three points are collinear or not finite, the grid point itself.
    """
    rows = np.arange(y.shape[0])
    inner = np.clip(index, 1, x.size - 2)
    left, centre, right = y[rows, inner - 1], y[rows, inner], y[rows, inner + 1]
    with np.errstate(invalid="ignore", divide="ignore"):
        denominator = left - 2 * centre + right
        shift = 0.5 * (left - right) / denominator
    usable = (index == inner) & (denominator != 0) & np.isfinite(denominator)
    step = np.clip(np.where(usable, shift, 0.0), -1, 1)
    return x[index] + step * (x[1] - x[0])


class ParameterScan:
    """Tabulated filter weights on a lambda grid, for one spectrum and one method.

    Parameters
    ----------
    g : numpy.ndarray
        Normalized generalized eigenvalues.
    n_free : int
        Unpenalized directions.
    count : int
        Readings in the fit.
    scale : float
        c of the penalty (to report |L x| in physical units).
    truncated : bool
        True for truncated SVD (f in {0, 1}), False for Tikhonov.
    points : int
        Grid size from the smallest lambda to 10; above 10 sqrt(max g) > 10 (penalties of
        order >= 1) the grid goes on at the same step to that lambda.
    """

    def __init__(
        self,
        g: np.ndarray,
        n_free: int,
        count: int,
        scale: float,
        *,
        truncated: bool = False,
        points: int = 120,
    ) -> None:
        self.count, self.n_free, self.scale, self.truncated = count, n_free, scale, truncated
        positive = g[g > 0]
        smallest = np.sqrt(max(float(positive.min()), 1e-20)) if positive.size else 1e-6
        low = min(smallest / 10, 1e-4)  # well-posed problems may want lambda << sqrt(g_min)
        self.log_grid = np.linspace(np.log10(low), 1.0, points)
        # and at the other end, lambda >> sqrt(g_max): every mode filtered away, the residual
        # within 2 % of its limit (an order >= 1 penalty passes smooth modes with g up to
        # 1e8; a grid ending at 10 left the discrepancy principle no root for a noise level
        # its limit admits); extended at the same step, so that the points below 10 stay
        highest = np.sqrt(float(g.max())) * 10 if g.size else 10.0
        step = self.log_grid[1] - self.log_grid[0]
        extra = max(int(np.ceil((np.log10(max(highest, 10.0)) - 1.0) / step - 1e-9)), 0)
        self.log_grid = np.r_[self.log_grid, 1.0 + step * np.arange(1, extra + 1)]
        points = self.log_grid.size
        self.grid = 10**self.log_grid
        self._first_meaningful = min(int(np.searchsorted(self.grid, smallest / 10)), points - 3)
        # where lambda passes sqrt(g_max) every mode is more than half filtered: the L-curve
        # has collapsed to its far end, and a corner there is the collapse, not the
        # transition from noise to smoothing (the grid below 10 is searched as it always was)
        largest = max(np.sqrt(float(g.max())) if g.size else 10.0, 10.0)
        self._last_meaningful = max(
            int(np.searchsorted(self.grid, largest, side="right")), self._first_meaningful + 3
        )
        self._bin: np.ndarray | None = None  # each mode's bin (None: a bin per mode)
        if g.size <= _EXACT_LIMIT:
            centres = g
        else:  # bins of equal width in log g, numbered from the smallest g
            logs = np.log10(np.maximum(g, 1e-300))
            _, self._bin = np.unique(np.floor(logs * _BINS_PER_DECADE), return_inverse=True)
            self._counts = np.bincount(self._bin)
            centres = np.bincount(self._bin, g) / self._counts
        lam2 = self.grid[:, None] ** 2
        with np.errstate(divide="ignore", invalid="ignore"):
            if truncated:
                f = (centres[None, :] > lam2).astype(float)
            else:
                f = centres[None, :] / (centres[None, :] + lam2)
            inverse_g = np.where(centres > 0, 1.0 / centres, 0.0)[None, :]
        self._residual_weight = (1 - f) ** 2
        self._seminorm_weight = f**2 * inverse_g
        self._derivative_weight = -(4 / self.grid[:, None]) * (1 - f) * f**2 * inverse_g
        mode_count = self._counts if self._bin is not None else np.ones(g.size)
        self.trace = (f * mode_count[None, :]).sum(axis=1) + n_free

    def _compress(self, beta2: np.ndarray) -> np.ndarray:
        """Squared coefficients (B, n) summed in each mode's bin: (B, bins).

        One `np.bincount` for the batch, frame j's bins shifted by j * bins (a gather of
        the modes in order of g and `np.add.reduceat` cost 2.5x as much on one frame).
        """
        if self._bin is None:
            return beta2
        count, bins = beta2.shape[0], self._counts.size
        keys = self._bin if count == 1 else (self._bin + bins * np.arange(count)[:, None])
        return np.bincount(keys.ravel(), beta2.ravel(), count * bins).reshape(count, bins)

    def curves(
        self, beta2: np.ndarray, rest: np.ndarray, *, lcurve: bool = True
    ) -> ParameterCurve:
        """Curves for frames with squared coefficients beta2 (B, r) and unreachable rest.

        The residual and GCV are computed here, which is all that GCV and the discrepancy
        principle need; the seminorm and the L-curve's curvature when first read. With
        ``lcurve=False`` they are NaN, and nothing is kept to compute them (large batches:
        what a curve keeps stays allocated as long as the result).
        """
        data = self._compress(beta2).T
        residual = (self._residual_weight @ data).T + rest[:, None]
        with np.errstate(divide="ignore", invalid="ignore"):
            gcv = self.count * residual / (self.count - self.trace) ** 2
        gcv = np.where(self.count - self.trace > 0.5, gcv, np.inf)
        later = _LCurve(self, data, residual) if lcurve else _Missing(residual.shape)
        return ParameterCurve(self.grid, np.sqrt(residual), gcv, later)

    def lcurve(self, data: np.ndarray, residual: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """|L x| and the L-curve's curvature (B, n) from compressed beta^2 (bins, B)."""
        seminorm = (self._seminorm_weight @ data).T
        if self.truncated:  # no derivative: curvature of the sampled curve
            x = 0.5 * np.log(np.maximum(residual, 1e-300))
            y = 0.5 * np.log(np.maximum(seminorm, 1e-300))
            dx, dy = np.gradient(x, axis=1), np.gradient(y, axis=1)
            ddx, ddy = np.gradient(dx, axis=1), np.gradient(dy, axis=1)
            with np.errstate(divide="ignore", invalid="ignore"):
                curvature = np.nan_to_num((dx * ddy - ddx * dy) / (dx**2 + dy**2) ** 1.5)
        else:
            derivative = (self._derivative_weight @ data).T
            curvature = _curvature(self.grid, residual, seminorm, derivative)
        return np.sqrt(seminorm / self.scale), curvature

    def choose(
        self, rule: str, curve: ParameterCurve, noise: np.ndarray | None
    ) -> tuple[np.ndarray, np.ndarray]:
        """(lambda, at_bound) of each frame (B,) by the rule; `noise`: noise std per frame.

        `at_bound` is True where the rule found no lambda inside the range it searches
        (`searched`) and took one of its ends: for the discrepancy principle, a residual
        that never reaches tau sigma sqrt(m) (the largest lambda) or exceeds it everywhere
        (the smallest); for GCV, a minimum at an end; for the L-curve, a curvature
        greatest at an end of its window (no corner inside).
        """
        if rule == "discrepancy":
            assert noise is not None
            # no noise at all (an all-zero frame): the smallest lambda on the grid
            target = np.log(np.maximum(np.asarray(noise) * np.sqrt(self.count), 1e-300))
            values = np.log(np.maximum(curve.residual_norm, 1e-300))
            logs, at_bound = _crossings(self.log_grid, values, target)
            return 10**logs, at_bound
        if rule == "gcv":
            # an all-zero frame has no residual at any lambda: then the smallest on the grid
            values = np.log(np.maximum(curve.gcv, 1e-300))
            index = np.argmin(values, axis=1)
        elif rule == "lcurve":
            values = curve.curvature.copy()
            values[:, [0, -1]] = -np.inf  # a corner is interior
            # well below the smallest mode's transition the curve collapses to a point: its
            # curvature there is rounding noise, not a corner
            values[:, : self._first_meaningful] = -np.inf
            values[:, self._last_meaningful :] = -np.inf
            index = np.argmax(values, axis=1)
            logs = _parabola_vertices(self.log_grid, values, index)
            # the curvature greatest at an end of the searched window: no corner inside it
            first, last = self._lcurve_window()
            return 10**logs, (index <= first) | (index >= last)
        else:
            raise ValueError(f"unknown rule {rule!r}")
        logs = _parabola_vertices(self.log_grid, values, index)
        return 10**logs, (index == 0) | (index == self.grid.size - 1)

    def _lcurve_window(self) -> tuple[int, int]:
        """First and last grid index where the L-curve's corner is sought."""
        return max(self._first_meaningful, 1), min(self._last_meaningful, self.grid.size - 1) - 1

    def searched(self, rule: str) -> tuple[float, float]:
        """The smallest and largest lambda `rule` can choose on this grid.

        The L-curve's corner is sought only between the smallest mode's transition and
        sqrt(g_max) (or 10): beyond them the curve has collapsed to its ends.
        """
        if rule == "lcurve":
            first, last = self._lcurve_window()
            return float(self.grid[first]), float(self.grid[last])
        return float(self.grid[0]), float(self.grid[-1])


def _crossings(x: np.ndarray, y: np.ndarray, target: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """First x where each non-decreasing row of y (B, n) reaches its target (B,).

    Linearly interpolated; x[0] if the row starts above it, x[-1] if it never gets there,
    which the second array (B,) marks True.
    """
    above = y >= target[:, None]
    index = np.argmax(above, axis=1)
    never = ~above.any(axis=1)
    rows = np.arange(y.shape[0])
    previous = np.maximum(index - 1, 0)
    y0, y1 = y[rows, previous], y[rows, index]
    with np.errstate(divide="ignore", invalid="ignore"):
        weight = np.where(y1 > y0, (target - y0) / (y1 - y0), 0.0)
    result = x[previous] + weight * (x[index] - x[previous])
    result = np.where(index == 0, x[0], result)
    starts_above = (index == 0) & ~never & (y[:, 0] > target)
    return np.where(never, x[-1], result), never | starts_above
