"""One-call reconstruction, with the solvers cached per sensor (built once, reused)."""

from __future__ import annotations

from collections.abc import Callable
from functools import lru_cache
from typing import Any, cast

from taxel._validation import check_choice, check_progress
from taxel.reconstruction._admm import ADMMSolver
from taxel.reconstruction._result import ReconstructionResult
from taxel.reconstruction._spec import (
    ForwardModelSpec,
    as_forward_model_spec,
    with_dead_taxels,
)
from taxel.reconstruction._support import SupportSolver
from taxel.reconstruction._tikhonov import TikhonovSolver, check_order

__all__ = ["METHODS", "estimate_noise_level", "naive_inverse", "reconstruct", "solver_for"]

METHODS: tuple[str, ...] = ("tikhonov", "tsvd", "nonneg", "tv", "support")


@lru_cache(maxsize=16)
def _cached(
    spec: ForwardModelSpec, method: str, order: int, boundary: str, representation: str
) -> TikhonovSolver | ADMMSolver | SupportSolver:
    if method == "support":
        return SupportSolver(spec, order=order, boundary=boundary, representation=representation)
    if method in ("tikhonov", "tsvd"):
        return TikhonovSolver(
            spec,
            order=order,
            truncated=method == "tsvd",
            boundary=boundary,
            representation=representation,
        )
    return ADMMSolver(
        spec, method=method, order=order, boundary=boundary, representation=representation
    )


def solver_for(
    sensor: Any,
    *,
    method: str = "tikhonov",
    order: int = 0,
    boundary: str = "auto",
    representation: str = "auto",
    dead_taxels: Any = None,
) -> TikhonovSolver | ADMMSolver | SupportSolver:
    """The solver of a sensor, built on first use and cached (16 most recent).

    `dead_taxels` (a boolean mask or (row, col) pairs, such as ``~calibration.valid``) are
    left out of the fit, beside those the sensor's spec already marks dead; a solver is
    built and cached for each set of dead taxels.

    Examples
    --------
    >>> first = solver_for("resistive16", method="tikhonov", order=1)
    >>> first is solver_for("resistive16", method="tikhonov", order=1)
    True
    >>> solver_for("resistive16", dead_taxels=[(0, 3)]).spec.dead_taxels
    ((0, 3),)
    """
    spec = with_dead_taxels(as_forward_model_spec(sensor), dead_taxels)
    check_choice("method", method, METHODS)
    order = check_order(order)
    if method == "tv":
        order = 1
    return _cached(spec, method, order, boundary, representation)


def reconstruct(
    frame: Any,
    sensor: Any,
    *,
    method: str = "tikhonov",
    order: int = 0,
    regularization: float | str = "discrepancy",
    noise_level: float | None = None,
    tau: float = 1.0,
    boundary: str = "auto",
    representation: str = "auto",
    dead_taxels: Any = None,
    progress: Callable[[int, int], object] | None = None,
) -> ReconstructionResult:
    """Recover the pressure field behind one tactile frame (or a batch, for linear methods).

    Parameters
    ----------
    frame : array_like, shape (..., rows, cols)
        Calibrated readings (NaN allowed at dead taxels, which are left out of the fit).
    sensor : ForwardModelSpec or str or object with ``forward_model_spec()``
        The sensor (a preset name such as "vhdta128" or "resistive16").
    method : {"tikhonov", "tsvd", "nonneg", "tv", "support"}, default "tikhonov"
        Tikhonov, truncated SVD, non-negative Tikhonov, non-negative total variation, or
        non-negative least squares on the support of a Tikhonov estimate
        (`SupportSolver`: the most accurate force and centroid of a contact).
    order : {0, 1, 2}, default 0
        Penalty order (identity, gradient, Laplacian) of tikhonov, tsvd and nonneg, and
        of the first stage of support.
    regularization : float or {"gcv", "lcurve", "discrepancy"}, default "discrepancy"
        lambda >= 0 (relative units; 0 is the naive inverse), mu [Pa] for "tv", or a rule;
        a number is at most `LARGEST_REGULARIZATION` (1e150).
        The default, the discrepancy principle with the noise estimated from the frame,
        is the rule that comes closest to the best lambda in the benchmark.
    noise_level : float, optional
        Reading noise std for "discrepancy", below the sensor's full-scale reading
        (ValueError otherwise); default the sensor's, else estimated from the frame
        (`estimate_noise_level`).
    tau : float, default 1.0
        Safety factor of the discrepancy principle.
    boundary, representation : str
        See `forward_operator`.
    dead_taxels : array_like of bool, shape (rows, cols), or sequence of (row, col), optional
        Taxels to leave out of the fit (their readings may be NaN), beside those `sensor`
        marks dead: the taxels a calibration excluded are ``~calibration.valid`` (see
        `taxel.sensor.Calibration`), which `calibrated_readings` sets to NaN.
    progress : callable, optional
        Called as ``progress(done, total)`` by the iterative methods, nonneg and tv, after
        each iteration (see `ADMMSolver.solve`), ending at ``done = total``; the direct
        methods do not call it. None (the default) reports nothing.

    Returns
    -------
    ReconstructionResult

    Notes
    -----
    Solves the ill-posed zeta = T F (eq. 25.5 of the chapter seed) with regularization, as
    the chapter prescribes. Solvers are built once per sensor (`solver_for`).

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.reconstruction import forward_operator
    >>> truth = np.zeros((16, 16)); truth[6:9, 7:10] = 30e3
    >>> frame = forward_operator("resistive16").apply(truth)
    >>> frame += np.random.default_rng(0).normal(0.0, 0.002 * 200e3, frame.shape)
    >>> result = reconstruct(frame, "resistive16", order=1)
    >>> print(f"{result.normal_force:.2f} N of {truth.sum() * 4e-6:.2f} N")
    1.08 N of 1.08 N

    Total variation, with a progress callback (a command line draws a bar with it):

    >>> calls = []
    >>> result = reconstruct(
    ...     frame, "resistive16", method="tv",
    ...     progress=lambda done, total: calls.append((done, total)),
    ... )
    >>> calls[0], calls[-1]
    ((1, 10000), (10000, 10000))
    """
    solver = solver_for(
        sensor,
        method=method,
        order=order,
        boundary=boundary,
        representation=representation,
        dead_taxels=dead_taxels,
    )
    if isinstance(solver, ADMMSolver):
        return solver.solve(
            frame,
            regularization=regularization,
            noise_level=noise_level,
            tau=tau,
            progress=progress,
        )
    check_progress(progress)
    return solver.solve(frame, regularization=regularization, noise_level=noise_level, tau=tau)


def naive_inverse(frame: Any, sensor: Any, **options: Any) -> ReconstructionResult:
    """The unregularized least-squares inverse (lambda = 0), for demonstration only.

    Its error grows like the noise divided by the smallest singular value of the forward
    operator; see the reconstruction figure and tests.

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.reconstruction import forward_operator
    >>> truth = np.zeros((16, 16)); truth[6:9, 7:10] = 30e3
    >>> result = naive_inverse(forward_operator("resistive16").apply(truth), "resistive16")
    >>> result.method, bool(np.allclose(result.pressure, truth, atol=1e-6 * 30e3))
    ('naive', True)
    """
    return reconstruct(frame, sensor, method="tikhonov", order=0, regularization=0.0, **options)


def estimate_noise_level(frame: Any, sensor: Any) -> float | Any:
    """The reading noise std of a frame, estimated from the frame itself [reading units].

    What the default parameter rule (the discrepancy principle) uses when the noise level is
    not given; see `TikhonovSolver.estimate_noise_level`. Per frame for a batch.

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.reconstruction import forward_operator
    >>> truth = np.zeros((16, 16)); truth[6:9, 7:10] = 30e3
    >>> frame = forward_operator("resistive16").apply(truth)
    >>> frame += np.random.default_rng(1).normal(0.0, 2e3, frame.shape)
    >>> print(f"{estimate_noise_level(frame, 'resistive16'):.1e} Pa (true 2.0e+03 Pa)")
    1.9e+03 Pa (true 2.0e+03 Pa)
    """
    solver = cast(TikhonovSolver, solver_for(sensor, method="tikhonov", order=0))
    return solver.estimate_noise_level(frame)
