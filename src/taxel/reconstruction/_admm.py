r"""Non-negative pressure and total variation, by the alternating direction method (ADMM).

Compressive contact cannot pull, so p >= 0; sharp-edged contacts (a punch, an edge) are
recovered better by a total-variation penalty than by a quadratic one. Both problems are
split so that the only linear solve is (A^T A + alpha M + rho I) x = r, which the sensor's
factorization does in one pair of DCTs (large grids) or one Cholesky solve (small grids):

nonneg:  min 1/2 |A x - b|^2 + 1/2 lambda^2 c |L x|^2  s.t. x >= 0         (split x = z)
tv:      min 1/2 |A x - b|^2 + mu |A|^2 sum_i |(D x)_i|  s.t. x >= 0     (split D x, x)

with D the forward differences (Neumann), so D^T D is the order-1 penalty M. The penalty
parameter rho adapts by residual balancing (S. Boyd et al., Found. Trends Mach. Learn. 3,
2011, sec. 3.4.1). Dead taxels on a full-array factorization are handled by
majorization: at each step they are given the model's current prediction.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from taxel._validation import check_positive, check_progress
from taxel.reconstruction._frames import one_frame, parse_regularization
from taxel.reconstruction._result import ReconstructionResult
from taxel.reconstruction._spectral import DenseSpectrum
from taxel.reconstruction._tikhonov import TikhonovSolver

__all__ = ["ADMMSolver", "ADMMState"]

_ADAPT_EVERY = 10
_MAX_ADAPTATIONS = 6
_SECANT_RUNS = 10  # tv: the most values of mu tried in the search for the target residual


def gradient(x: np.ndarray) -> np.ndarray:
    """Forward differences along rows and columns (2, rows, cols), zero at the far edge."""
    result = np.zeros((2, *x.shape))
    result[0, :-1, :] = x[1:, :] - x[:-1, :]
    result[1, :, :-1] = x[:, 1:] - x[:, :-1]
    return result


def gradient_adjoint(field: np.ndarray) -> np.ndarray:
    """D^T of `gradient` (minus the divergence)."""
    rows, cols = field[0], field[1]
    result = np.zeros(field.shape[1:])
    result[:-1, :] -= rows[:-1, :]
    result[1:, :] += rows[:-1, :]
    result[:, :-1] -= cols[:, :-1]
    result[:, 1:] += cols[:, :-1]
    return result


def total_variation(x: np.ndarray) -> float:
    """Isotropic total variation sum_i |(D x)_i| (cell units)."""
    return float(np.sqrt((gradient(x) ** 2).sum(axis=0)).sum())


@dataclass
class ADMMState:
    """The iterate of an ADMM run (mutable; `ADMMSolver.step` advances it)."""

    x: np.ndarray
    z: np.ndarray
    u: np.ndarray
    rho: float
    iteration: int = 0
    primal: float = np.inf
    dual: float = np.inf
    adaptations: int = 0


class _Counter:
    """The iterations of every run of one solve, told to ``progress(done, total)``."""

    def __init__(self, progress: Callable[[int, int], object], total: int) -> None:
        self.progress, self.total, self.done = progress, total, 0

    def __call__(self, state: ADMMState) -> None:
        self.done += 1
        self.progress(self.done, self.total)

    def wrap(self, callback: Callable[[ADMMState], object] | None) -> Callable[..., None]:
        """A callback that counts, then calls `callback` (if any)."""
        if callback is None:
            return self
        inner = callback

        def both(state: ADMMState) -> None:
            self(state)
            inner(state)

        return both

    def finish(self) -> None:
        """Report the whole budget done (a solve that ended early)."""
        if self.done < self.total:
            self.done = self.total
            self.progress(self.total, self.total)


class ADMMSolver:
    """Non-negative Tikhonov ("nonneg") or non-negative total variation ("tv") for a sensor.

    Parameters
    ----------
    sensor : ForwardModelSpec or str or object with ``forward_model_spec()``
        The sensor.
    method : {"nonneg", "tv"}, default "nonneg"
        The problem (module docstring).
    order : {0, 1, 2}, default 0
        Penalty order of "nonneg" (TV uses order-1 structure internally).
    boundary, representation : str
        See `forward_operator`.
    tolerance : float, default 1e-4
        Relative primal and dual residuals at which iteration stops.
    max_iterations : int, default 1000
        Budget per solve.

    Notes
    -----
    Two tiers (PyLops style): ``setup`` / ``step`` / ``run`` for one parameter value, with
    a callback; ``solve`` chooses the parameter and runs. For "nonneg" the rule (GCV, L-curve,
    discrepancy) picks lambda on the linear Tikhonov problem of the same order, then the
    constrained problem is solved at that lambda. For "tv" the rule fixes the target
    residual (discrepancy: tau sigma sqrt(m); GCV and L-curve: the residual of the order-1
    Tikhonov solution at their lambda) and mu is found by secant steps on log mu.

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.reconstruction import forward_model_preset
    >>> spec = forward_model_preset("resistive16", shape=(8, 8))
    >>> solver = ADMMSolver(spec, method="nonneg")
    >>> truth = np.zeros((8, 8)); truth[2:4, 5:7] = 40e3
    >>> result = solver.solve(solver.operator.apply(truth), regularization=1e-3)
    >>> bool(result.pressure.min() >= 0), result.converged
    (True, True)
    >>> print(f"{np.abs(result.pressure - truth).max() / 40e3:.2f}")
    0.00
    """

    def __init__(
        self,
        sensor: Any,
        *,
        method: str = "nonneg",
        order: int = 0,
        boundary: str = "auto",
        representation: str = "auto",
        tolerance: float = 1e-4,
        max_iterations: int = 1000,
    ) -> None:
        if method not in ("nonneg", "tv"):
            raise ValueError(f"`method` must be one of nonneg, tv; got {method!r}")
        self.method = method
        self.linear = TikhonovSolver(
            sensor,
            order=1 if method == "tv" else order,
            boundary=boundary,
            representation=representation,
        )
        self.spec = self.linear.spec
        self.operator = self.linear.operator
        self.spectrum = self.linear.spectrum
        self.order = self.linear.order
        self.tolerance = check_positive("tolerance", tolerance)
        if int(max_iterations) < 1:
            raise ValueError(f"`max_iterations` must be >= 1, got {max_iterations!r}")
        self.max_iterations = int(max_iterations)
        self._live = self.spec.live_taxels
        self._frame = np.zeros(self.spec.shape)
        self._weight = 0.0
        self._companion: ADMMSolver | None = None

    # -- one parameter value: setup / step / run --------------------------------------------
    def setup(self, frame: np.ndarray, parameter: float, initial: ADMMState | None = None):
        """Prepare a run on one validated frame with lambda (nonneg) or mu [Pa] (tv)."""
        self._frame = frame
        norm_squared = self.spectrum.norm_squared
        if self.method == "nonneg":
            self._weight = parameter**2 * self.spectrum.scale
            rho = max(parameter, 1e-4) * norm_squared
        else:
            self._weight = parameter * norm_squared
            rho = 0.05 * norm_squared
        shape = self.spec.load_shape
        parts = 3 if self.method == "tv" else 1
        if initial is not None:
            state = ADMMState(initial.x.copy(), initial.z.copy(), initial.u.copy(), initial.rho)
        else:
            zeros = np.zeros((parts, *shape))
            state = ADMMState(np.zeros(shape), zeros, zeros.copy(), rho)
        return state

    def _data_rhs(self, x: np.ndarray) -> np.ndarray:
        if isinstance(self.spectrum, DenseSpectrum):
            return self.spectrum.normal_rhs(self._frame)
        frame = self._frame
        if not self.spectrum.exact_mask:  # majorize: dead taxels read the current model
            frame = np.where(self._live, frame, self.operator.apply(x))
        return self.operator.adjoint(frame)

    def _split(self, x: np.ndarray) -> np.ndarray:
        if self.method == "nonneg":
            return x[None]
        return np.concatenate([gradient(x), x[None]])

    def _split_adjoint(self, parts: np.ndarray) -> np.ndarray:
        if self.method == "nonneg":
            return parts[0]
        return gradient_adjoint(parts[:2]) + parts[2]

    def step(self, state: ADMMState) -> ADMMState:
        """One ADMM iteration (x-update, z-update, dual update, rho adaptation)."""
        rho = state.rho
        rhs = self._data_rhs(state.x) + rho * self._split_adjoint(state.z - state.u)
        if self.method == "nonneg":
            state.x = self.spectrum.shifted_solve(rhs, self._weight, rho)
        else:
            state.x = self.spectrum.shifted_solve(rhs, rho, rho)
        split = self._split(state.x)
        previous = state.z
        target = split + state.u
        z = np.empty_like(target)
        if self.method == "tv":
            magnitude = np.sqrt(target[0] ** 2 + target[1] ** 2)
            # 1 - (weight / rho) / magnitude, at least 0, written so that it cannot overflow
            # (the numerator is never larger than the magnitude, and 0 where that is 0)
            shrink = np.maximum(magnitude - self._weight / rho, 0.0)
            shrink /= np.maximum(magnitude, 1e-300)
            z[:2] = target[:2] * shrink
        z[-1] = np.maximum(target[-1], 0.0)
        state.z = z
        state.u = state.u + split - z
        state.iteration += 1
        scale = max(float(np.linalg.norm(split)), float(np.linalg.norm(z)), 1e-300)
        state.primal = float(np.linalg.norm(split - z)) / scale
        dual = rho * self._split_adjoint(z - previous)
        state.dual = float(np.linalg.norm(dual)) / max(
            float(np.linalg.norm(rho * self._split_adjoint(state.u))), 1e-300
        )
        if state.iteration % _ADAPT_EVERY == 0 and state.adaptations < _MAX_ADAPTATIONS:
            factor = 1.0
            if state.primal > 10 * state.dual:
                factor = 2.0
            elif state.dual > 10 * state.primal:
                factor = 0.5
            if factor != 1.0:
                state.rho *= factor
                state.u /= factor
                state.adaptations += 1
        return state

    def run(self, frame: np.ndarray, parameter: float, *, initial=None, callback=None):
        """Iterate to convergence for one parameter value; returns the final state."""
        state = self.setup(frame, parameter, initial)
        for _ in range(self.max_iterations):
            self.step(state)
            if callback is not None:
                callback(state)
            if state.primal < self.tolerance and state.dual < self.tolerance:
                break
        return state

    # -- the parameter rule and the result ---------------------------------------------------
    def _residual(self, frame: np.ndarray, x: np.ndarray) -> float:
        return float(np.linalg.norm((self.operator.apply(x) - frame)[self._live]))

    def _target_residual(self, frame, rule: str, linear, tau: float, tick=None) -> float:
        """The data fit TV must reach: tau sigma sqrt(m), or that of nonneg at the rule's lambda.

        A linear solution may fit the noise below zero pressure, which no non-negative
        solution can, so GCV and L-curve targets come from the non-negative order-1 solve.
        """
        if rule == "discrepancy":
            return tau * float(linear.noise_level) * np.sqrt(self.spectrum.count)
        if self._companion is None:
            self._companion = ADMMSolver(
                self.spec,
                method="nonneg",
                order=1,
                boundary=self.operator.boundary,
                representation=self.operator.representation,
                tolerance=self.tolerance,
                max_iterations=self.max_iterations,
            )
        state = self._companion.run(frame, float(linear.regularization), callback=tick)
        return self._residual(frame, state.z[-1])

    def _solve_tv(self, frame, target: float, initial_guess: float, callback):
        """The mu with |A x_mu - b| = target, by secant steps on (log mu, log residual).

        Returns mu, its state, and whether the search missed: no step came within 2 % of
        the target and none bracketed it (the target lies beyond every residual tried).
        """
        history: list[tuple[float, float, ADMMState]] = []
        log_mu, state = np.log(initial_guess), None
        target = max(target, 1e-300)  # no noise at all (an all-zero frame)
        for _ in range(_SECANT_RUNS):
            state = self.run(frame, float(np.exp(log_mu)), initial=state, callback=callback)
            log_r = np.log(max(self._residual(frame, state.x), 1e-300))
            history.append((log_mu, log_r, state))
            if abs(log_r - np.log(target)) < 0.02:
                break
            below = [h for h in history if h[1] < np.log(target)]
            above = [h for h in history if h[1] >= np.log(target)]
            if below and above:
                low, high = max(below, key=lambda h: h[0]), min(above, key=lambda h: h[0])
                slope = (high[1] - low[1]) / (high[0] - low[0]) if high[0] != low[0] else 0
                if slope > 0:
                    log_mu = low[0] + (np.log(target) - low[1]) / slope
                else:
                    log_mu = 0.5 * (low[0] + high[0])
            else:
                log_mu += 1.5 if not above else -1.5
        best = min(history, key=lambda h: abs(h[1] - np.log(target)))
        bracketed = min(h[1] for h in history) < np.log(target) <= max(h[1] for h in history)
        missed = bool(abs(best[1] - np.log(target)) >= 0.02 and not bracketed)
        return float(np.exp(best[0])), best[2], missed

    def solve(
        self,
        frame: Any,
        *,
        regularization: float | str = "discrepancy",
        noise_level: float | None = None,
        tau: float = 1.0,
        callback=None,
        progress: Callable[[int, int], object] | None = None,
    ) -> ReconstructionResult:
        """Recover non-negative pressure from one frame (rows, cols).

        Parameters as `TikhonovSolver.solve`; for "tv" a numeric `regularization` is mu
        [Pa], the weight of the total variation relative to |A|^2. `callback(state)` is
        called after each iteration at the chosen parameter (and at each mu tried);
        `progress(done, total)` after each iteration of every run, with ``total`` the budget
        of the whole solve (`max_iterations` per run; tv's search for mu makes up to 10 runs,
        11 with gcv or lcurve) and ``done = total`` last.

        Examples
        --------
        >>> import numpy as np
        >>> from taxel.reconstruction import forward_model_preset
        >>> solver = ADMMSolver(forward_model_preset("resistive16", shape=(8, 8)), method="tv")
        >>> truth = np.zeros((8, 8)); truth[2:5, 3:6] = 40e3
        >>> calls = []
        >>> result = solver.solve(
        ...     solver.operator.apply(truth), regularization=100.0,
        ...     progress=lambda done, total: calls.append((done, total)),
        ... )
        >>> calls[0], calls[-1], len(calls) == result.n_iterations + 1
        ((1, 1000), (1000, 1000), True)
        """
        frame = one_frame(frame, self.spec, self.method)
        rule, value = parse_regularization(regularization)
        tick = None
        if progress is not None:
            check_progress(progress)
            runs = 1
            if self.method == "tv" and rule != "given":
                runs = _SECANT_RUNS + (rule != "discrepancy")  # gcv, lcurve: a nonneg run
            tick = _Counter(progress, runs * self.max_iterations)
            callback = tick.wrap(callback)
        linear = self.linear.solve(
            frame, regularization=regularization, noise_level=noise_level, tau=tau
        )
        noise = linear.noise_level
        missed = False  # tv: the search for mu did not reach its target
        if self.method == "nonneg":
            parameter = float(linear.regularization)
            state = self.run(frame, parameter, callback=callback)
            seminorm = float(np.sqrt(np.vdot(state.z[0], self.spectrum.apply_penalty(state.z[0]))))
        else:
            if rule == "given":
                assert value is not None  # a given rule always comes with its number
                parameter = float(value)
                state = self.run(frame, parameter, callback=callback)
            else:
                target = self._target_residual(frame, rule, linear, tau, tick)
                guess = 0.05 * max(float(np.abs(frame).max()), 1e-300)
                if self.spec.quantity != "stress":
                    guess = 0.05 * float(np.abs(linear.pressure).max()) + 1e-300
                parameter, state, missed = self._solve_tv(frame, target, guess, callback)
            seminorm = total_variation(state.z[-1])
        if tick is not None:
            tick.finish()
        pressure, tv = state.z[-1], self.method == "tv"
        converged = state.primal < self.tolerance and state.dual < self.tolerance
        message = (
            f"converged in {state.iteration} iterations"
            if converged
            else f"not converged after {state.iteration} iterations"
        )
        residual_norm = self._residual(frame, pressure)
        if missed:
            message += (
                f"; the {rule} rule found no mu with its target residual: held at "
                f"{parameter:.3g}, residual {residual_norm:.3g}, target {target:.3g}"
            )
        return ReconstructionResult(
            pressure=pressure,
            regularization=parameter,
            rule=rule,
            method=self.method,
            order=self.order,
            residual_norm=residual_norm,
            solution_norm=seminorm,
            noise_level=noise,
            curve=linear.curve,
            spacing=self.spec.load_pitch,
            converged=converged,
            n_iterations=state.iteration,
            residual=max(state.primal, state.dual),
            # nonneg: what the linear solve said of its lambda (a bound), after its own
            message=message + ("" if tv else linear.message.removeprefix("direct solve")),
            at_bound=missed if tv else linear.at_bound,
        )
