"""Load from photoelastic fringes: fringe counting along a path, and a one-parameter fit.

The intensity between circular polarisers is periodic in the retardation, so one reading
does not tell the fringe order. Counting fringes along a path on which the retardation grows
from below half a fringe recovers it; fitting one load scale to a whole intensity map, with
a grid search before the polish, does not need such a path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import optimize

from taxel._validation import as_finite_array, check_choice, check_positive
from taxel.transducers._photoelastic_optics import FIELDS, polariscope_intensity

__all__ = ["PhotoelasticFit", "fit_load_scale", "unwrap_retardation"]


def unwrap_retardation(
    intensity: Any, *, field: str = "dark", source_intensity: float = 1.0, tolerance: float = 0.0
) -> np.ndarray:
    r"""Retardation along a path from intensities, by fringe counting [rad].

    Parameters
    ----------
    intensity : array_like, shape (..., n_samples)
        Intensities along a path (last axis) on which delta starts below the first dark
        fringe order's half (delta_0 < pi) and never decreases. Along the load's line of
        action, from deep in the layer towards the load, is such a path.
    field, source_intensity
        The polariscope, as in `polariscope_intensity`.
    tolerance : float, default 0.0
        How far [rad] a noisy sample may fall below its predecessor and still count as
        "not decreasing".

    Returns
    -------
    numpy.ndarray, shape (..., n_samples)
        delta [rad]. Needs at least a few samples per fringe.

    Notes
    -----
    The intensity gives :math:`\psi = 2\arcsin\sqrt{I/I_0} \in [0, \pi]` (dark field), and
    delta is one of :math:`2\pi m \pm \psi`. Walking along the path, each sample takes the
    candidate that is not below the previous value and is nearest the linear prediction
    from the two before it: a half fringe is counted each time psi turns back at 0 or pi,
    even when two samples straddle the turn.

    Examples
    --------
    >>> delta = np.linspace(0.1, 9.0, 200)
    >>> bool(np.allclose(unwrap_retardation(polariscope_intensity(delta)), delta))
    True
    """
    values = as_finite_array("intensity", intensity)
    if values.ndim == 0 or values.shape[-1] == 0:
        raise ValueError(
            "`intensity` must be a path (samples along the last axis), "
            f"got shape {values.shape}"
        )
    check_choice("field", field, FIELDS)
    source_intensity = check_positive("source_intensity", source_intensity)
    tolerance = check_positive("tolerance", tolerance, allow_zero=True)
    root = np.sqrt(np.clip(values / source_intensity, 0.0, 1.0))
    folded = 2.0 * (np.arcsin(root) if field == "dark" else np.arccos(root))
    result = np.empty_like(folded)
    result[..., 0] = folded[..., 0]
    for k in range(1, folded.shape[-1]):
        previous, psi = result[..., k - 1], folded[..., k]
        slope = np.maximum(previous - result[..., k - 2], 0.0) if k > 1 else 0.0
        predicted = previous + slope
        turn = np.floor(previous / (2 * np.pi))
        best = np.full(previous.shape, np.inf)
        for m in (turn, turn + 1):
            for candidate in (2 * np.pi * m - psi, 2 * np.pi * m + psi):
                allowed = candidate >= previous - tolerance
                closer = np.abs(candidate - predicted) < np.abs(best - predicted)
                best = np.where(allowed & closer, candidate, best)
        result[..., k] = best
    return result


@dataclass(frozen=True)
class PhotoelasticFit:
    """Outcome of `fit_load_scale`.

    Attributes
    ----------
    load : float
        The best load parameter, in the unit of the model's scale.
    converged : bool
        Whether the local refinement met its tolerance.
    n_iterations : int
        Function evaluations of the refinement.
    residual : float
        Root-mean-square intensity misfit at `load`.
    message : str
        What happened, in words.
    """

    load: float
    converged: bool
    n_iterations: int
    residual: float
    message: str


def fit_load_scale(
    intensity: Any,
    unit_retardation: Any,
    *,
    max_load: float,
    field: str = "dark",
    source_intensity: float = 1.0,
) -> PhotoelasticFit:
    r"""Least-squares fit of one load parameter to a fringe map.

    Parameters
    ----------
    intensity : array_like
        Measured intensities (any shape).
    unit_retardation : array_like
        delta per unit load at the same pixels [rad per load unit]: stress fields are linear
        in the load, so delta(P) = P * unit_retardation.
    max_load : float
        Upper end of the search [load unit], > 0.
    field, source_intensity
        The polariscope, as in `polariscope_intensity`.

    Returns
    -------
    PhotoelasticFit
        The load minimising :math:`\sum (I_{model}(P) - I)^2`.

    Notes
    -----
    The misfit oscillates in P (every fringe is a local minimum), so a grid fine enough to
    move the fastest pixel by at most pi/8 per step finds the right valley first; bounded
    Brent refinement then polishes it.

    Examples
    --------
    >>> x = np.linspace(0.0, 1.0, 50)
    >>> unit = 2.0 + 30.0 * x**2  # rad per newton, say
    >>> fit = fit_load_scale(polariscope_intensity(0.37 * unit), unit, max_load=1.0)
    >>> fit.converged, round(fit.load, 6)
    (True, 0.37)
    """
    measured = as_finite_array("intensity", intensity)
    unit = as_finite_array("unit_retardation", unit_retardation)
    if measured.shape != unit.shape:
        raise ValueError(
            f"`unit_retardation` must have the shape of intensity {measured.shape}, "
            f"got {unit.shape}"
        )
    max_load = check_positive("max_load", max_load)
    check_choice("field", field, FIELDS)
    source_intensity = check_positive("source_intensity", source_intensity)
    measured, unit = measured.ravel(), unit.ravel()

    def misfit(load: Any) -> Any:
        model = polariscope_intensity(
            np.multiply.outer(np.atleast_1d(load), unit),
            field=field,
            source_intensity=source_intensity,
        )
        return np.mean((model - measured) ** 2, axis=-1)

    fastest = float(np.max(np.abs(unit))) if unit.size else 0.0
    count = int(min(max(math.ceil(8.0 * fastest * max_load / np.pi), 16), 200_000)) + 1
    grid = np.linspace(0.0, max_load, count)
    values = np.concatenate([misfit(chunk) for chunk in np.array_split(grid, -(-count // 256))])
    best = int(np.argmin(values))
    step = grid[1] - grid[0]
    low, high = max(0.0, grid[best] - step), min(max_load, grid[best] + step)
    polished = optimize.minimize_scalar(
        lambda p: float(misfit(p)[0]),
        bounds=(low, high),
        method="bounded",
        options={"xatol": 1e-12 * max_load},
    )
    load = float(polished.x)
    return PhotoelasticFit(
        load=load,
        converged=bool(polished.success),
        n_iterations=int(polished.nfev),
        residual=float(np.sqrt(misfit(load)[0])),
        message=str(polished.message),
    )
