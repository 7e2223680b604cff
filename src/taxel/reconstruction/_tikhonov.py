"""Tikhonov regularization (orders 0, 1, 2), truncated SVD and the naive inverse."""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import ndimage

from taxel._validation import check_positive
from taxel.reconstruction._choice import ParameterCurve, ParameterScan, join_curves
from taxel.reconstruction._frames import as_frames, parse_regularization, restore_batch
from taxel.reconstruction._noise import (
    combined_noise,
    difference_blocks,
    high_frequency_noise,
    spectral_noise,
)
from taxel.reconstruction._operator import forward_operator
from taxel.reconstruction._result import ReconstructionResult, bound_message
from taxel.reconstruction._spec import as_forward_model_spec
from taxel.reconstruction._spectral import build_spectrum

__all__ = ["TikhonovSolver", "check_order", "estimate_noise"]

# dead taxels on a fast (full-array) factorization: imputation sweeps, then exact PCG
_SWEEPS = 3
_PCG_TOLERANCE = 1e-12
_PCG_ITERATIONS = 200
_NOISE_MODES = 4096
_CHUNK_BYTES = 1 << 18  # readings per chunk of a batch (`_solve_spectral`)
_GIVEN_KEPT = 16  # filter factors kept for this many given lambdas
_CURVES_KEPT = 8  # batches of at most this many frames keep their L-curves (for plots)


def check_order(order: Any) -> int:
    """The Tikhonov order as an int in {0, 1, 2}, or a ValueError naming `order`."""
    if order not in (0, 1, 2) or isinstance(order, bool):
        raise ValueError(f"`order` must be 0, 1 or 2, got {order!r}")
    return int(order)


def estimate_noise(curve: ParameterCurve, trace: np.ndarray, count: int) -> np.ndarray:
    """Noise std per frame from the GCV fit: sqrt(|r|^2 / (m - trace)) at the GCV minimum.

    Wahba's estimator (G. Wahba, *Spline Models for Observational Data*, SIAM 1990, eq. 4.7.1).
    It fails when the load grid has more cells than there are readings (oversampling): the
    GCV fit then absorbs most of the noise. The discrepancy principle therefore uses
    `TikhonovSolver.estimate_noise_level` instead; this function is kept for comparison.
    """
    index = np.argmin(curve.gcv, axis=-1)
    residual = np.take_along_axis(curve.residual_norm, index[:, None], axis=-1)[:, 0]
    return residual / np.sqrt(np.maximum(count - trace[index], 1.0))


class TikhonovSolver:
    """Regularized least squares for one sensor, factorized once and reused frame after frame.

    Solves min |A x - b|^2 + lambda^2 c |L x|^2 over the live taxels, with L the identity
    (order 0), the gradient (1) or the Laplacian (2) on the load grid, and
    c = |A|^2 / |L|^2 so that lambda is dimensionless. With ``truncated=True`` the filter is
    that of the truncated (generalized) SVD: modes with g_i > lambda^2 are kept whole.

    Parameters
    ----------
    sensor : ForwardModelSpec or str or object with ``forward_model_spec()``
        The sensor.
    order : {0, 1, 2}, default 0
        Order of the penalty.
    truncated : bool, default False
        Truncated SVD instead of Tikhonov.
    boundary, representation : str
        See `forward_operator`.

    Notes
    -----
    Construction is the setup: operator, factorization and the tabulated parameter curves
    (`_spectral`, `_choice`). ``solve`` then costs two transforms and a few vector
    operations per frame; batches (..., rows, cols) are solved together, each frame with
    its own lambda.

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.reconstruction import forward_model_preset, forward_operator
    >>> spec = forward_model_preset("resistive16", shape=(8, 8))
    >>> solver = TikhonovSolver(spec, order=1)
    >>> truth = np.zeros((8, 8)); truth[3:5, 3:5] = 50e3
    >>> result = solver.solve(solver.operator.apply(truth), regularization=0.0)
    >>> bool(np.allclose(result.pressure, truth, atol=1e-6 * 50e3))
    True
    >>> result.rule, round(result.normal_force, 3)
    ('given', 0.8)
    """

    def __init__(
        self,
        sensor: Any,
        *,
        order: int = 0,
        truncated: bool = False,
        boundary: str = "auto",
        representation: str = "auto",
    ) -> None:
        self.spec = as_forward_model_spec(sensor)
        self.order = check_order(order)
        self.truncated = bool(truncated)
        self.operator = forward_operator(
            self.spec, boundary=boundary, representation=representation
        )
        self.spectrum = build_spectrum(self.operator, self.order)
        spectrum = self.spectrum
        self.scan = ParameterScan(
            spectrum.g, spectrum.n_free, spectrum.count, spectrum.scale, truncated=truncated
        )
        with np.errstate(divide="ignore"):
            self._inverse_g = np.where(spectrum.g > 0, 1 / spectrum.g, 0.0) / spectrum.scale
        # the half of the modes the cover passes least, at most 4096 of them: almost pure
        # noise (`_noise`); 4096 give sigma to about 2 %
        least = min(spectrum.g.size // 2, _NOISE_MODES)
        self._noise_modes = np.sort(np.argsort(spectrum.g, kind="stable")[:least])
        self._noise_blocks = difference_blocks(self.spec.live_taxels)
        self._given_factors: dict[float, np.ndarray] = {}  # (1, r) for a given lambda

    @property
    def method(self) -> str:
        """The method's name, "tsvd" or "tikhonov"."""
        return "tsvd" if self.truncated else "tikhonov"

    def _factors_of(self, value: float) -> np.ndarray:
        """f_i of one given lambda, (1, r), kept for the frames that follow.

        A loop at a fixed lambda then does not compute them frame after frame, nor a batch
        once per frame.
        """
        factors = self._given_factors.get(value)
        if factors is None:
            if len(self._given_factors) >= _GIVEN_KEPT:
                self._given_factors.clear()
            factors = self.filter_factors(np.array([value]))
            factors.flags.writeable = False
            self._given_factors[value] = factors
        return factors

    def filter_factors(self, regularization: np.ndarray) -> np.ndarray:
        """f_i(lambda) for each frame's lambda (B,) -> (B, r)."""
        lam2 = np.asarray(regularization, dtype=float)[:, None] ** 2
        g = self.spectrum.g[None, :]
        if self.truncated:
            return (g > lam2).astype(float)
        return g / (g + lam2)

    def solve(
        self,
        frame: Any,
        *,
        regularization: float | str = "discrepancy",
        noise_level: float | None = None,
        tau: float = 1.0,
    ) -> ReconstructionResult:
        """Recover pressure from one frame or a batch (..., rows, cols).

        Parameters
        ----------
        frame : array_like
            Calibrated readings. Values at dead taxels are ignored (NaN allowed there).
        regularization : float or {"gcv", "lcurve", "discrepancy"}, default "discrepancy"
            lambda from 0 (the naive, unregularized inverse) to `LARGEST_REGULARIZATION`
            (1e150), or the rule choosing it.
        noise_level : float, optional
            Reading noise std for the discrepancy principle, below the spec's
            `full_scale` reading; default the spec's, else estimated from each frame
            (`estimate_noise_level`).
        tau : float, default 1.0
            Safety factor of the discrepancy principle: |r| = tau sigma sqrt(m).

        Returns
        -------
        ReconstructionResult

        Notes
        -----
        The default rule is the discrepancy principle (V. A. Morozov, 1966): the largest
        lambda whose residual is as large as the noise, |A x - b| = tau sigma sqrt(m), with
        sigma estimated from the frame itself when neither `noise_level` nor the spec gives
        it. Across the reconstruction benchmark it comes within 1.25x of the best lambda
        far more often than GCV, which undersmooths smooth loads at order 0, or the
        L-curve (docs/benchmarks.md).
        """
        frames, batch = as_frames(frame, self.spec)
        rule, value = parse_regularization(regularization)
        tau = check_positive("tau", tau)
        if noise_level is not None:
            noise_level = self.spec.check_noise_level(noise_level)
        elif self.spec.noise_level is not None:
            noise_level = self.spec.noise_level
        if self.spectrum.exact_mask:
            parts = self._solve_spectral(frames, rule, value, noise_level, tau)
        else:
            parts = self._solve_masked(frames, rule, value, noise_level, tau)
        pressure, lam, residual, seminorm, noise, curve, bound = parts
        return ReconstructionResult(
            pressure=pressure.reshape(*batch, *self.spec.load_shape),
            regularization=restore_batch(lam, batch),
            rule=rule,
            method="naive" if rule == "given" and value == 0 else self.method,
            order=self.order,
            residual_norm=restore_batch(residual, batch),
            solution_norm=restore_batch(seminorm, batch),
            noise_level=None if noise is None else restore_batch(noise, batch),
            curve=curve.frame(0) if curve is not None and batch == () else curve,
            spacing=self.spec.load_pitch,
            message=bound_message(rule, lam, bound, self.scan.searched(rule)),
            at_bound=bool(bound[0]) if batch == () else bound.reshape(batch),
        )

    def estimate_noise_level(self, frame: Any) -> float | np.ndarray:
        """The reading noise std of a frame (or per frame of a batch), from the frame itself.

        Parameters
        ----------
        frame : array_like, shape (..., rows, cols)
            Calibrated readings (NaN allowed at dead taxels).

        Returns
        -------
        float or numpy.ndarray
            sigma [reading units], per frame for a batch.

        Notes
        -----
        The smaller of two robust estimates that a load can only inflate: the median of the
        squared coefficients on the half of the modes the cover passes least, and the median
        of the squared finest diagonal differences of the readings (module `_noise`).

        Examples
        --------
        >>> import numpy as np
        >>> solver = TikhonovSolver("vhdta128")
        >>> truth = np.zeros((128, 128)); truth[50:70, 40:60] = 100e3
        >>> frame = solver.operator.apply(truth)
        >>> frame += np.random.default_rng(0).normal(0.0, 4e3, frame.shape)
        >>> print(f"{solver.estimate_noise_level(frame):.0f} Pa (true 4000 Pa)")
        3977 Pa (true 4000 Pa)
        """
        frames, batch = as_frames(frame, self.spec)
        if not self.spectrum.exact_mask:
            frames = np.stack([self._impute(f) for f in frames])
        return restore_batch(self._noise(frames, self.spectrum.analyze(frames)[0]), batch)

    def _noise(self, frames: np.ndarray, beta: np.ndarray) -> np.ndarray:
        return combined_noise(
            spectral_noise(beta, self._noise_modes),
            high_frequency_noise(frames, self.spec.live_taxels, self._noise_blocks),
        )

    def _impute(self, frame: np.ndarray) -> np.ndarray:
        """Dead taxels filled with the mean of their live 3 x 3 neighbours."""
        live = self.spec.live_taxels
        weights = ndimage.uniform_filter(live.astype(float), 3, mode="nearest")
        smooth = ndimage.uniform_filter(frame * live, 3, mode="nearest")
        return np.where(live, frame, smooth / np.maximum(weights, 1e-12))

    def _solve_spectral(
        self,
        frames: np.ndarray,
        rule: str,
        value: float | None,
        noise_level: float | np.ndarray | None,
        tau: float,
    ) -> tuple:
        """A batch in chunks of about `_CHUNK_BYTES` of readings.

        Every temporary of a chunk is then small, and the memory it frees is reused by the
        next chunk instead of being handed back to the system and faulted in again, which
        on this machine cost more than the products themselves (a cold heap, 16 x 16
        frames in a batch of 1000: 3700 page faults a call, about 6 us a frame).
        """
        size = max(_CHUNK_BYTES // (8 * frames[0].size), 1)
        # a batch keeps its L-curves only when the rule needs them or it is a few frames
        keep = rule == "lcurve" or frames.shape[0] <= _CURVES_KEPT
        if frames.shape[0] <= size:
            return self._solve_chunk(frames, rule, value, noise_level, tau, keep)
        pressure = np.empty((frames.shape[0], *self.spec.load_shape))
        parts = [
            self._solve_chunk(
                frames[start : start + size],
                rule,
                value,
                noise_level,
                tau,
                keep,
                pressure[start : start + size],
            )
            for start in range(0, frames.shape[0], size)
        ]
        lam, residual, seminorm, bound = (
            np.concatenate([p[i] for p in parts]) for i in (1, 2, 3, 6)
        )
        noise = None if parts[0][4] is None else np.concatenate([p[4] for p in parts])
        curve = None if parts[0][5] is None else join_curves([p[5] for p in parts])
        return pressure, lam, residual, seminorm, noise, curve, bound

    def _solve_chunk(
        self,
        frames: np.ndarray,
        rule: str,
        value: float | None,
        noise_level: float | np.ndarray | None,
        tau: float,
        keep: bool,
        out: np.ndarray | None = None,
    ) -> tuple:
        spectrum = self.spectrum
        beta, free, rest = spectrum.analyze(frames)
        curve, noise = None, None
        bound = np.zeros(frames.shape[0], dtype=bool)
        if rule == "given":
            assert value is not None  # a given lambda has its value
            lam = np.full(frames.shape[0], value)
            factors = self._factors_of(value)
        else:
            curve = self.scan.curves(beta**2, rest, lcurve=keep)
            if rule == "discrepancy":
                if noise_level is None:
                    noise = self._noise(frames, beta)
                else:
                    noise = np.broadcast_to(np.asarray(noise_level, dtype=float), beta.shape[:1])
                    noise = noise.copy()
            lam, bound = self.scan.choose(rule, curve, None if noise is None else tau * noise)
            factors = self.filter_factors(lam)
        filtered = factors * beta
        pressure = spectrum.synthesize(filtered, free, out)
        misfit = beta - filtered
        residual = np.sqrt(np.einsum("ij,ij->i", misfit, misfit) + rest)
        seminorm = np.sqrt(np.einsum("ij,ij,j->i", filtered, filtered, self._inverse_g))
        return pressure, lam, residual, seminorm, noise, curve, bound

    def _solve_masked(
        self,
        frames: np.ndarray,
        rule: str,
        value: float | None,
        noise_level: float | None,
        tau: float,
    ) -> tuple:
        """Dead taxels on a full-array factorization: impute, choose lambda, then exact PCG.

        The parameter rule runs on the frame with dead taxels filled by the model's own
        prediction (three sweeps); the final solve at that lambda excludes them exactly,
        by conjugate gradients preconditioned with the full-array solve.
        """
        live = self.spec.live_taxels
        outputs = []
        for frame in frames:
            frame_noise: float | np.ndarray | None
            filled = self._impute(frame)
            if rule == "discrepancy" and noise_level is None:  # once, from the live readings
                frame_noise = self._noise(filled[None], self.spectrum.analyze(filled[None])[0])
            else:
                frame_noise = noise_level
            for _ in range(_SWEEPS):
                parts = self._solve_spectral(filled[None], rule, value, frame_noise, tau)
                filled = np.where(live, frame, self.operator.apply(parts[0][0]))
            lam = float(parts[1][0])
            pressure = self._pcg(frame, live, lam, parts[0][0])
            residual = np.linalg.norm((self.operator.apply(pressure) - frame)[live])
            seminorm = np.sqrt(np.vdot(pressure, self._penalty(pressure)))
            outputs.append((pressure, lam, residual, seminorm, parts[4], parts[5], parts[6][0]))
        pressure = np.stack([o[0] for o in outputs])
        lams, residuals, seminorms, bound = (
            np.array([o[i] for o in outputs]) for i in (1, 2, 3, 6)
        )
        noise = None if outputs[0][4] is None else np.concatenate([o[4] for o in outputs])
        curve = outputs[-1][5] if len(outputs) == 1 else None
        return pressure, lams, residuals, seminorms, noise, curve, bound

    def _penalty(self, pressure: np.ndarray) -> np.ndarray:
        return self.spectrum.apply_penalty(pressure)

    def _pcg(self, frame: np.ndarray, live: np.ndarray, lam: float, start: np.ndarray):
        operator, spectrum = self.operator, self.spectrum
        weight = max(lam**2, 1e-12) * spectrum.scale

        def normal(x: np.ndarray) -> np.ndarray:
            return operator.adjoint(live * operator.apply(x)) + weight * self._penalty(x)

        x = start.copy()
        rhs = operator.adjoint(live * frame)
        r = rhs - normal(x)
        z = spectrum.shifted_solve(r, weight, 0.0)
        direction = z.copy()
        rz = np.vdot(r, z)
        limit = _PCG_TOLERANCE * np.linalg.norm(rhs)
        for _ in range(_PCG_ITERATIONS):
            if np.linalg.norm(r) <= limit:
                break
            image = normal(direction)
            step = rz / np.vdot(direction, image)
            x += step * direction
            r -= step * image
            z = spectrum.shifted_solve(r, weight, 0.0)
            rz, previous = np.vdot(r, z), rz
            direction = z + (rz / previous) * direction
        return x
