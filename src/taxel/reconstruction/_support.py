r"""Non-negative least squares on the support of a regularized estimate (two stages).

A contact presses on a small part of the array. Over the whole map, the noise of every
unloaded taxel adds to the total force (its error grows like sigma p^2 sqrt(N)) and pulls
the centroid towards the middle; non-negativity alone keeps the positive half of that
noise. Knowing where the load is removes it:

1. the regularized estimate x1 (Tikhonov of the given order, lambda by the given rule);
2. its support S: the cells where x1 exceeds kappa times its own noise std, with the
   universal threshold kappa = sqrt(2 ln n) of n cells (D. L. Donoho and I. M. Johnstone,
   Biometrika 81, 1994), above which pure noise rises on no cell with high probability;
3. min |A x - b|^2 + lambda2^2 c |x|^2 over x >= 0 that vanish outside S, with lambda2 by
   GCV on the restricted problem, which has far fewer unknowns than readings and is then
   nearly well-posed (GCV's home ground); the quadratic program is solved exactly by the
   primal-dual active-set method (M. Hintermueller, K. Ito and K. Kunisch, SIAM J. Optim.
   13, 2003), started from the signs of the unconstrained solution;
4. the support found in 2 is as wide as the blur of x1, much wider than a point load:
   its rim cells where the restricted (unconstrained) estimate stays below twice its own
   std are peeled off and 3 is repeated, as long as the smaller support has the lower GCV
   score, i.e. predicts the readings as well with fewer unknowns (at most `refinements`
   times). The rim only: inside an extended contact single cells are not significant on
   their own, yet the contact is;
5. a support of several connected components keeps only those whose total load in the
   restricted ridge estimate exceeds kappa times its std. A lone noise cell that passed
   step 2 (about one frame in ten on 128 x 128 cells: the universal threshold bounds the
   chance of any false cell only slowly, ~ 1/(2 sqrt(pi ln n))) is far weaker there,
   because the restricted fit is a matched filter while the noise that lifted the cell
   in x1 is only partly correlated with it; a real contact gains. Far from the contact,
   such a cell moves the centroid by its share of the force times its distance.

The restricted normal matrix A_S^T A_S is gathered from the kernel of A^T A (fast
reflective model on the taxel grid), taken from the dense matrix (small grids), or built
column by column otherwise. When the support holds more than `max_cells` cells, or the
restricted fit would spend more than half of the readings' degrees of freedom, the load
is not compact and the result is that of the "nonneg" method at lambda1.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import ndimage

from taxel._validation import check_positive
from taxel.reconstruction._admm import ADMMSolver
from taxel.reconstruction._frames import one_frame, parse_regularization
from taxel.reconstruction._model import reflect_normal_block, reflect_normal_kernel
from taxel.reconstruction._restricted import component_scores, restricted_fit
from taxel.reconstruction._result import ReconstructionResult
from taxel.reconstruction._spectral import DenseSpectrum
from taxel.reconstruction._tikhonov import TikhonovSolver

__all__ = ["SupportSolver"]

_CHUNK = 64  # unit loads per batch when A_S^T A_S is built column by column
_RIM_SIGNIFICANCE = 2.0  # rim cells below twice their std are peeled off the support


class SupportSolver:
    """Non-negative pressure restricted to the support of a regularized estimate.

    Parameters
    ----------
    sensor : ForwardModelSpec or str or object with ``forward_model_spec()``
        The sensor.
    order : {0, 1, 2}, default 0
        Penalty order of the first (support-finding) stage; the second stage's penalty is
        the identity on the support.
    boundary, representation : str
        See `forward_operator`.
    threshold : float, optional
        kappa, in units of the first estimate's noise std per cell; default
        sqrt(2 ln n) for n load cells.
    max_cells : int, default 2048
        Largest support solved as a compact load (module docstring).
    refinements : int, default 8
        Most rims peeled off the first support (module docstring, step 4); 0 keeps it.

    Notes
    -----
    See the module docstring. Meant for contacts: loads that leave most of the array
    unloaded. For a field spread over the whole array use "tikhonov" of order 1.

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.reconstruction import forward_model_preset
    >>> spec = forward_model_preset("resistive16", shape=(12, 12))
    >>> solver = SupportSolver(spec)
    >>> truth = np.zeros((12, 12)); truth[5:7, 4:7] = 80e3
    >>> frame = solver.operator.apply(truth)
    >>> frame += np.random.default_rng(0).normal(0.0, 2e3, frame.shape)
    >>> result = solver.solve(frame)
    >>> print(f"{result.normal_force:.3f} N of {truth.sum() * 4e-6:.3f} N")
    1.939 N of 1.920 N
    >>> int(result.support.sum()), bool(result.pressure.min() >= 0)
    (6, True)
    """

    def __init__(
        self,
        sensor: Any,
        *,
        order: int = 0,
        boundary: str = "auto",
        representation: str = "auto",
        threshold: float | None = None,
        max_cells: int = 2048,
        refinements: int = 8,
    ) -> None:
        self.linear = TikhonovSolver(
            sensor, order=order, boundary=boundary, representation=representation
        )
        self.spec = self.linear.spec
        self.operator = self.linear.operator
        self.spectrum = self.linear.spectrum
        self.order = self.linear.order
        cells = self.spec.load_shape[0] * self.spec.load_shape[1]
        self.threshold = (
            float(np.sqrt(2 * np.log(cells)))
            if threshold is None
            else check_positive("threshold", threshold)
        )
        if int(max_cells) < 1:
            raise ValueError(f"`max_cells` must be >= 1, got {max_cells!r}")
        self.max_cells = int(max_cells)
        if int(refinements) < 0:
            raise ValueError(f"`refinements` must be >= 0, got {refinements!r}")
        self.refinements = int(refinements)
        self._normal_kernel: np.ndarray | None = None
        self._fallback: ADMMSolver | None = None

    @property
    def method(self) -> str:
        """The method's name, "support"."""
        return "support"

    def support_of(self, estimate: ReconstructionResult, noise_level: float) -> np.ndarray:
        """Cells where a first-stage estimate exceeds `threshold` times its noise std.

        `noise_level` is the std of the reading noise behind the estimate (one frame).
        """
        factors = self.linear.filter_factors(np.atleast_1d(estimate.regularization))[0]
        std = noise_level * np.sqrt(self.spectrum.cell_variance(factors))
        return estimate.pressure > self.threshold * std

    def _normal_block(self, cells: np.ndarray, live: np.ndarray) -> np.ndarray:
        """A_S^T A_S over the live readings, for the load cells `cells` (flat indices)."""
        if isinstance(self.spectrum, DenseSpectrum):
            columns = self.spectrum._matrix[:, cells]
            return columns.T @ columns
        if self.spec.oversampling == 1 and live.all():
            if self._normal_kernel is None:
                self._normal_kernel = reflect_normal_kernel(self.spec)
            rows, cols = np.divmod(cells, self.spec.load_shape[1])
            return reflect_normal_block(self._normal_kernel, rows, cols)
        shape = self.spec.load_shape
        block = np.empty((cells.size, cells.size))
        for start in range(0, cells.size, _CHUNK):
            chosen = cells[start : start + _CHUNK]
            unit: np.ndarray = np.zeros((chosen.size, shape[0] * shape[1]))
            unit[np.arange(chosen.size), chosen] = 1.0
            unit = unit.reshape(chosen.size, *shape)
            image = self.operator.adjoint(live * self.operator.apply(unit))
            block[start : start + chosen.size] = image.reshape(chosen.size, -1)[:, cells]
        return 0.5 * (block + block.T)

    def solve(
        self,
        frame: Any,
        *,
        regularization: float | str = "discrepancy",
        noise_level: float | None = None,
        tau: float = 1.0,
    ) -> ReconstructionResult:
        """Recover non-negative pressure on the support of a first estimate, one frame.

        Parameters as `TikhonovSolver.solve`; they govern the first stage, whose lambda
        the result holds as `first_regularization` (chosen by its `rule`). The returned
        `regularization` is lambda2 of the second stage (relative units, identity
        penalty, chosen by GCV; lambda1 when the support is too large and the
        non-negative solve at lambda1 stands in, `support` None then; 0 when no cell is
        found pressed), and `support` the cells allowed to carry load.
        """
        frame = one_frame(frame, self.spec, "support")
        rule, _ = parse_regularization(regularization)
        first = self.linear.solve(
            frame, regularization=regularization, noise_level=noise_level, tau=tau
        )
        noise = first.noise_level
        if noise is None:  # a given lambda, GCV or the L-curve: the noise is still needed
            noise = self.linear.estimate_noise_level(frame)
        support = self.support_of(first, float(noise))
        cells = np.flatnonzero(support.ravel())
        lam1 = float(first.regularization)
        stage = f"support of {cells.size} cells from Tikhonov order {self.order} at lambda "
        stage += f"{lam1:.3g} ({rule}{', at its bound' if first.at_bound else ''})"
        if cells.size == 0:
            return self._result(
                frame, first, np.zeros(self.spec.load_shape), 0.0, support, stage, 0
            )
        if cells.size > self.max_cells:
            return self._nonneg(frame, first, f"{stage}: more than {self.max_cells} cells")
        live = self.spec.live_taxels
        readings = np.where(live, frame, 0.0)
        normal = self._normal_block(cells, live)
        rhs = self.operator.adjoint(readings).ravel()[cells]
        energy, count = float(np.sum(readings**2)), int(live.sum())
        kept = np.ones(cells.size, dtype=bool)
        fit = restricted_fit(normal, rhs, energy, count)
        if fit is None:
            return self._nonneg(frame, first, f"{stage}: too many degrees of freedom")
        rounds = 0
        while rounds < self.refinements:
            # the restricted estimate is sharper than the first: peel the rim cells it does
            # not find significant, if the smaller support predicts the readings at least
            # as well (a lower GCV score: a choice between two models)
            significant = fit[0] > _RIM_SIGNIFICANCE * float(noise) * fit[2]
            mask = np.zeros(self.spec.load_shape, dtype=bool)
            mask.ravel()[cells[kept]] = True
            rim = mask & ~ndimage.binary_erosion(mask, border_value=0)
            drop = ~significant & rim.ravel()[cells[kept]]
            if not drop.any() or drop.all():
                break
            smaller = kept.copy()
            smaller[np.flatnonzero(kept)[drop]] = False
            refined = restricted_fit(normal[np.ix_(smaller, smaller)], rhs[smaller], energy, count)
            if refined is None or refined[3] > fit[3]:
                break
            kept, fit = smaller, refined
            rounds += 1
        kept, fit, dropped = self._drop_components(
            cells, kept, fit, normal, rhs, energy, count, noise
        )
        values, weight, _, _, iterations, converged = fit
        pressure = np.zeros(self.spec.load_shape)
        pressure.ravel()[cells[kept]] = values
        support = np.zeros(self.spec.load_shape, dtype=bool)
        support.ravel()[cells[kept]] = True
        lam2 = float(np.sqrt(weight / self.spectrum.scale))
        message = f"{stage}, {int(kept.sum())} after {rounds} refinement(s)"
        message += f" and {dropped} lone component(s) dropped" if dropped else ""
        message += f"; lambda {lam2:.3g} "
        message += f"on it (GCV); non-negative in {iterations} "
        message += "active-set steps" if converged else "steps, finished by NNLS"
        return self._result(frame, first, pressure, lam2, support, message, iterations, converged)

    def _drop_components(self, cells, kept, fit, normal, rhs, energy, count, noise):
        """Step 5 of the module docstring: (kept, fit, number of components dropped)."""
        mask = np.zeros(self.spec.load_shape, dtype=bool)
        mask.ravel()[cells[kept]] = True
        labels, found = ndimage.label(mask, structure=np.ones((3, 3)))
        if found < 2:
            return kept, fit, 0
        own = labels.ravel()[cells[kept]]
        inner = np.ix_(kept, kept)
        scores = component_scores(normal[inner], rhs[kept], fit[1], own)
        weak = scores <= self.threshold * float(noise)
        if not weak.any() or weak.all():
            return kept, fit, 0
        smaller = kept.copy()
        smaller[np.flatnonzero(kept)[np.isin(own, np.flatnonzero(weak) + 1)]] = False
        refined = restricted_fit(normal[np.ix_(smaller, smaller)], rhs[smaller], energy, count)
        if refined is None:
            return kept, fit, 0
        return smaller, refined, int(weak.sum())

    def _nonneg(self, frame: np.ndarray, first: ReconstructionResult, why: str):
        if self._fallback is None:
            self._fallback = ADMMSolver(
                self.spec,
                method="nonneg",
                order=self.order,
                boundary=self.operator.boundary,
                representation=self.operator.representation,
            )
        state = self._fallback.run(frame, float(first.regularization))
        converged = (
            state.primal < self._fallback.tolerance and state.dual < self._fallback.tolerance
        )
        return self._result(
            frame,
            first,
            state.z[-1],
            float(first.regularization),
            None,
            f"{why}; the non-negative solve at lambda1 instead",
            state.iteration,
            converged,
        )

    def _result(
        self,
        frame: np.ndarray,
        first: ReconstructionResult,
        pressure: np.ndarray,
        lam: float,
        support: np.ndarray | None,
        message: str,
        iterations: int,
        converged: bool = True,
    ) -> ReconstructionResult:
        misfit = (self.operator.apply(pressure) - frame)[self.spec.live_taxels]
        return ReconstructionResult(
            pressure=pressure,
            regularization=lam,
            rule=first.rule,
            method=self.method,
            order=self.order,
            residual_norm=float(np.linalg.norm(misfit)),
            solution_norm=float(np.linalg.norm(pressure)),
            noise_level=first.noise_level,
            curve=first.curve,
            spacing=self.spec.load_pitch,
            converged=converged,
            n_iterations=iterations,
            residual=0.0,
            message=message,
            support=support,
            first_regularization=float(first.regularization),
            at_bound=first.at_bound,
        )
