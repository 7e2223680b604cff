r"""The reading noise of a frame, estimated from the frame itself (for the discrepancy principle).

Two robust estimates, each of which the load can only inflate:

spectral
    The readings' coefficients beta_i on the orthonormal modes of the forward model are
    signal plus white noise of the same std sigma. The half of the modes that the cover
    passes least (smallest g_i) carry almost no signal when the cover is thick against the
    pitch (vhdta128: d = 3.9 pitches), so sigma^2 = median(beta_i^2) / 0.4549 there
    (the median of chi-square with one degree of freedom). Sharp loads on a thin cover
    (resistive16: d = 0.75 pitch) put signal in every mode and inflate it.
high-frequency
    The finest diagonal differences (b[i, j] - b[i+1, j] - b[i, j+1] + b[i+1, j+1]) / 2 have
    the std sigma of the noise and no response to constants or linear trends; a load adds
    to them only near its edges, a minority of the array for a contact, so their median
    absolute value gives sigma (the finest-scale estimator of D. L. Donoho and
    I. M. Johnstone, Biometrika 81, 1994, on an undecimated grid). Loads that cover most
    of the array with curvature inflate it.

The estimate is the smaller of the two (an estimate that is exactly zero, as quantized
readings of an unloaded array may give, is ignored).
"""

from __future__ import annotations

import numpy as np

__all__ = ["combined_noise", "high_frequency_noise", "spectral_noise"]

# median of chi-square with one degree of freedom: median(x^2) = 0.4549 sigma^2 for N(0, sigma^2)
_CHI2_MEDIAN = 0.454936423119572


def spectral_noise(beta: np.ndarray, modes: np.ndarray) -> np.ndarray:
    """The noise std per frame from the coefficients beta (B, r) on the least-passed `modes`."""
    if modes.size == 0:
        return np.full(beta.shape[0], np.inf)
    return np.sqrt(np.median(beta[:, modes] ** 2, axis=1) / _CHI2_MEDIAN)


def high_frequency_noise(frames: np.ndarray, live: np.ndarray) -> np.ndarray:
    """The noise std per frame (B, rows, cols) from diagonal differences of live 2 x 2 blocks."""
    difference = (
        frames[:, :-1, :-1] - frames[:, 1:, :-1] - frames[:, :-1, 1:] + frames[:, 1:, 1:]
    ) / 2
    usable = live[:-1, :-1] & live[1:, :-1] & live[:-1, 1:] & live[1:, 1:]
    if not usable.any():
        return np.full(frames.shape[0], np.inf)
    values = difference[:, usable]
    return np.sqrt(np.median(values**2, axis=1) / _CHI2_MEDIAN)


def combined_noise(*estimates: np.ndarray) -> np.ndarray:
    """The smallest positive, finite estimate per frame (0 if none is)."""
    stacked = np.stack(estimates)
    usable = np.where((stacked > 0) & np.isfinite(stacked), stacked, np.inf)
    result = usable.min(axis=0)
    return np.where(np.isfinite(result), result, 0.0)
