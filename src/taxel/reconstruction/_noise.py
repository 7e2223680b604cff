r"""The reading noise of a frame, estimated from the frame itself (for the discrepancy principle).

Two robust estimates, each of which the load can only inflate:

spectral
    The readings' coefficients beta_i on the orthonormal modes of the forward model are
    signal plus white noise of the same std sigma. The half of the modes that the cover
    passes least (smallest g_i) carry almost no signal when the cover is thick against the
    pitch (vhdta128: d = 3.9 pitches), so sigma^2 = median(beta_i^2) / 0.4549 there
    (at most the 4096 least-passed modes are used)
    (the median of chi-square with one degree of freedom). Sharp loads on a thin cover
    (resistive16: d = 0.75 pitch) put signal in every mode and inflate it.
high-frequency
    The finest diagonal differences (b[i, j] - b[i+1, j] - b[i, j+1] + b[i+1, j+1]) / 2 have
    the std sigma of the noise and no response to constants or linear trends; a load adds
    to them only near its edges, a minority of the array for a contact, so their median
    absolute value gives sigma (the finest-scale estimator of D. L. Donoho and
    I. M. Johnstone, Biometrika 81, 1994: disjoint blocks on large arrays, every
    overlapping block on small ones). Loads that cover most of the array with curvature
    inflate it.

The estimate is the smaller of the two (an estimate that is exactly zero, as quantized
readings of an unloaded array may give, is ignored).
"""

from __future__ import annotations

import numpy as np

__all__ = ["combined_noise", "difference_blocks", "high_frequency_noise", "spectral_noise"]

# median of chi-square with one degree of freedom: median(x^2) = 0.4549 sigma^2 for N(0, sigma^2)
_CHI2_MEDIAN = 0.454936423119572
# disjoint 2 x 2 blocks are used when there are at least this many (else overlapping ones)
_DISJOINT_ENOUGH = 1024
# rows of up to this many values are sorted for their median: quicker than partitioning
# (1000 rows of 127: 0.28 against 0.35 ms; one row of 4096: 22 against 10 us)
_SORTED_BELOW = 512


def _median_of_squares(values: np.ndarray) -> np.ndarray:
    """Median of values^2 along the last axis (the upper one for an even count)."""
    middle = values.shape[-1] // 2
    if values.shape[-1] <= _SORTED_BELOW:  # (the same value: a short row sorts quicker)
        return np.sort(values**2, axis=-1)[..., middle]
    return np.partition(values**2, middle, axis=-1)[..., middle]


def spectral_noise(beta: np.ndarray, modes: np.ndarray) -> np.ndarray:
    """The noise std per frame from the coefficients beta (B, r) on the least-passed `modes`."""
    if modes.size == 0:
        return np.full(beta.shape[0], np.inf)
    return np.sqrt(_median_of_squares(beta[:, modes]) / _CHI2_MEDIAN)


def _blocks(array: np.ndarray, disjoint: bool, row: int, col: int) -> np.ndarray:
    """Corner (row, col) of every 2 x 2 block of the last two axes (disjoint or all)."""
    rows, cols = array.shape[-2:]
    if disjoint:
        return array[..., row : row + 2 * (rows // 2) - 1 : 2, col : col + 2 * (cols // 2) - 1 : 2]
    return array[..., row : row + rows - 1, col : col + cols - 1]


def difference_blocks(live: np.ndarray) -> tuple[bool, np.ndarray]:
    """(disjoint, usable): which 2 x 2 blocks `high_frequency_noise` uses for a live mask.

    Large arrays use the disjoint blocks (independent differences, the decimated finest
    scale); small ones, where those would be too few, every overlapping block. A block
    is usable when its four taxels are live.
    """
    rows, cols = live.shape
    disjoint = (rows // 2) * (cols // 2) >= _DISJOINT_ENOUGH
    corners = [_blocks(live, disjoint, r, c) for r, c in ((0, 0), (1, 0), (0, 1), (1, 1))]
    return disjoint, np.logical_and.reduce(corners).ravel()


def high_frequency_noise(
    frames: np.ndarray, live: np.ndarray, blocks: tuple[bool, np.ndarray] | None = None
) -> np.ndarray:
    """The noise std per frame (B, rows, cols) from diagonal differences of live 2 x 2 blocks.

    `blocks` is ``difference_blocks(live)``, computed here when not given.
    """
    disjoint, usable = difference_blocks(live) if blocks is None else blocks
    if not usable.any():
        return np.full(frames.shape[0], np.inf)
    difference = (
        _blocks(frames, disjoint, 0, 0)
        - _blocks(frames, disjoint, 1, 0)
        - _blocks(frames, disjoint, 0, 1)
        + _blocks(frames, disjoint, 1, 1)
    )
    flat = difference.reshape(frames.shape[0], -1)
    values = flat if usable.all() else flat[:, usable]
    # the differences are twice the noise-std variables: (b - b - b + b) / 2
    return np.sqrt(_median_of_squares(values) / (4 * _CHI2_MEDIAN))


def combined_noise(*estimates: np.ndarray) -> np.ndarray:
    """The smallest positive, finite estimate per frame (0 if none is)."""
    result = np.full(np.shape(estimates[0]), np.inf)
    for estimate in estimates:
        result = np.where((estimate > 0) & (estimate < result), estimate, result)
    return np.where(np.isfinite(result), result, 0.0)
