"""Monotone fitting: isotonic regression and the inverse of a monotone cubic, vectorised."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from scipy.interpolate import PchipInterpolator

__all__ = ["invert_pchip", "isotonic_increasing"]

BISECTIONS = 40  # halves a segment to 1e-12 of its width


def isotonic_increasing(values: np.ndarray) -> np.ndarray:
    """Least-squares non-decreasing fit along axis 0 (equal weights), column by column.

    Uses the min-max formula of isotonic regression,
    ``fit[i] = max_{j <= i} min_{k >= i} mean(values[j:k + 1])``, exact and vectorised.

    Examples
    --------
    >>> isotonic_increasing(np.array([[1.0], [3.0], [2.0], [4.0]])).ravel().tolist()
    [1.0, 2.5, 2.5, 4.0]
    """
    n = values.shape[0]
    result = values.reshape(n, -1).astype(float)  # a copy
    crossing = np.flatnonzero(np.any(np.diff(result, axis=0) < 0, axis=0))
    flat = result[:, crossing]  # only columns that are not monotonic already need a fit
    fitted = np.empty_like(flat)
    j = np.arange(n)[:, None]
    k = np.arange(n)[None, :]
    upper = k >= j
    counts = np.where(upper, k - j + 1, 1)[..., None]
    step = max(1, 2**22 // (n * n))  # columns per chunk: about 32 MB of temporaries
    for start in range(0, flat.shape[1], step):
        chunk = flat[:, start : start + step]
        sums = np.concatenate([np.zeros((1, chunk.shape[1])), np.cumsum(chunk, axis=0)])
        means = (sums[None, 1:, :] - sums[:-1, None, :]) / counts  # [j, k]: mean of j..k
        means = np.where(upper[..., None], means, np.inf)
        lowest = np.minimum.accumulate(means[:, ::-1], axis=1)[:, ::-1]  # min over k >= i
        lowest = np.where(upper[..., None], lowest, -np.inf)  # only j <= i
        fitted[:, start : start + step] = lowest.max(axis=0)
    result[:, crossing] = fitted
    return result.reshape(values.shape)


def invert_pchip(
    response: PchipInterpolator, pressures: np.ndarray, knots: np.ndarray, x: np.ndarray
) -> np.ndarray:
    """Per taxel t, the pressure at which the non-decreasing response reads x[:, t]."""
    frames, taxels = x.shape
    columns = np.broadcast_to(np.arange(taxels), x.shape)
    below = (knots[None] < x[:, None]).sum(axis=1)  # (frames, taxels): first knot >= x
    at_most = (knots[None] <= x[:, None]).sum(axis=1) - 1  # last knot <= x
    on_knot = below <= at_most  # x equals the knots below..at_most (a flat run, or one knot)
    middle = 0.5 * (pressures[np.minimum(below, len(pressures) - 1)] + pressures[at_most])
    segment = np.clip(at_most, 0, len(pressures) - 2)
    coefficients = response.c[:, segment, columns]  # (4, frames, taxels)
    low = np.zeros(x.shape)
    high = (pressures[segment + 1] - pressures[segment]).astype(float)
    for _ in range(BISECTIONS):
        mid = 0.5 * (low + high)
        value = ((coefficients[0] * mid + coefficients[1]) * mid + coefficients[2]) * mid
        value = value + coefficients[3]
        below_target = value < x
        low = np.where(below_target, mid, low)
        high = np.where(below_target, high, mid)
    inside = pressures[segment] + 0.5 * (low + high)
    return np.where(on_knot, middle, inside)
