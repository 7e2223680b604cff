"""Static non-idealities of a taxel array: noise, ADC, gain/offset spread, faults, crosstalk.

Each is a pure function that is the identity when its parameters are zero, so the sensor
layer can compose them and switch each off. Randomness comes only from an explicit `rng`
(a numpy Generator or an int seed). Per-taxel properties that must stay fixed from frame to
frame (gain, offset, faults) are drawn once into a frozen object and then applied.
Taxel arrays are the last axes of `signal`; leading axes (frames, time) broadcast.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import ndimage

from taxel._validation import (
    as_finite_array,
    check_count,
    check_finite,
    check_integer,
    check_positive,
    check_range,
)
from taxel.transducers._common import as_generator

__all__ = [
    "GainOffset",
    "TaxelFaults",
    "adc_codes",
    "adc_values",
    "add_noise",
    "draw_faults",
    "draw_gain_offset",
    "neighbour_crosstalk",
    "quantize",
]


def _as_shape(shape: Any) -> tuple[int, ...]:
    """An array shape of whole numbers >= 1 (any number of axes), or raise naming `shape`."""
    try:
        sizes = tuple(shape)
    except TypeError:
        raise ValueError(f"`shape` must be a sequence of sizes, got {shape!r}") from None
    return tuple(check_count("shape", size) for size in sizes)


def add_noise(
    signal: Any, *, additive: float = 0.0, multiplicative: float = 0.0, rng: Any = None
) -> np.ndarray:
    r"""White Gaussian noise, additive and proportional to the signal.

    Parameters
    ----------
    signal : array_like
        Clean signal [any unit].
    additive : float, default 0.0
        Standard deviation sigma_a of the additive part [signal unit], >= 0.
    multiplicative : float, default 0.0
        Relative standard deviation sigma_m of the proportional part [-], >= 0.
    rng : numpy.random.Generator or int
        Required when either part is on.

    Returns
    -------
    numpy.ndarray
        :math:`y = x (1 + \sigma_m n_1) + \sigma_a n_2`, n_1, n_2 independent N(0, 1).

    Examples
    --------
    >>> y = add_noise(np.full(100_000, 2.0), additive=0.1, multiplicative=0.05, rng=0)
    >>> round(float(y.std()), 2)  # sqrt(0.1^2 + (0.05 * 2)^2) = 0.1414
    0.14
    """
    x = as_finite_array("signal", signal)
    additive = check_positive("additive", additive, allow_zero=True)
    multiplicative = check_positive("multiplicative", multiplicative, allow_zero=True)
    if additive == 0 and multiplicative == 0:
        return x.copy()
    generator = _require_rng(rng)
    proportional = generator.standard_normal(x.shape) * multiplicative
    return x * (1.0 + proportional) + generator.standard_normal(x.shape) * additive


def _require_rng(rng: Any) -> np.random.Generator:
    if rng is None:
        raise TypeError("`rng` is required when the effect is on (a Generator or an int seed)")
    return as_generator("rng", rng)


def _adc(bits: Any, low: float, high: float) -> tuple[int, float, float]:
    bits = check_integer("bits", bits, 1, 24)
    low, high = check_finite("low", low), check_finite("high", high)
    if high <= low:
        raise ValueError(f"`high` must exceed low = {low:g}, got {high:g}")
    return int(bits), low, high


def adc_codes(signal: Any, *, bits: int, low: float, high: float) -> np.ndarray:
    """Output codes of an ideal, saturating ADC.

    Parameters
    ----------
    signal : array_like
        Input [signal unit].
    bits : int
        Resolution, 1 to 24.
    low, high : float
        Input range [signal unit]; inputs outside it clip to the end codes.

    Returns
    -------
    numpy.ndarray of int64
        floor((x - low) / LSB), clipped to [0, 2^bits - 1], LSB = (high - low) / 2^bits.

    Examples
    --------
    >>> adc_codes([-1.0, 0.0, 0.49, 0.5, 0.99, 5.0], bits=2, low=0.0, high=1.0).tolist()
    [0, 0, 1, 2, 3, 3]
    """
    x = as_finite_array("signal", signal)
    bits, low, high = _adc(bits, low, high)
    levels = 2**bits
    codes = np.floor((x - low) / (high - low) * levels)
    return np.clip(codes, 0, levels - 1).astype(np.int64)


def adc_values(codes: Any, *, bits: int, low: float, high: float) -> np.ndarray:
    """Mid-point of each code's input interval [signal unit]: what a code stands for.

    Parameters
    ----------
    codes : array_like of int
        ADC output codes, 0 to 2^bits - 1.
    bits, low, high
        The converter, as in `adc_codes`.

    Returns
    -------
    numpy.ndarray
        low + (code + 1/2) LSB.

    Examples
    --------
    >>> adc_values([0, 3], bits=2, low=0.0, high=1.0).tolist()
    [0.125, 0.875]
    """
    bits, low, high = _adc(bits, low, high)
    values = as_finite_array("codes", codes)
    if np.any((values < 0) | (values > 2**bits - 1) | (values != np.round(values))):
        raise ValueError(f"`codes` must be integers in 0..{2**bits - 1}")
    return low + (values + 0.5) * (high - low) / 2**bits


def quantize(signal: Any, *, bits: int, low: float, high: float) -> np.ndarray:
    """Signal after an ADC and back: quantized to the code mid-points and clipped [signal unit].

    Within [low, high] the error is at most half an LSB; outside, the signal saturates at
    the first or last mid-point.

    Examples
    --------
    >>> quantize([0.1, 0.3, 2.0], bits=3, low=0.0, high=1.0).tolist()
    [0.0625, 0.3125, 0.9375]
    """
    return adc_values(
        adc_codes(signal, bits=bits, low=low, high=high), bits=bits, low=low, high=high
    )


@dataclass(frozen=True)
class GainOffset:
    """Per-taxel gain and offset, drawn once by `draw_gain_offset`.

    Attributes
    ----------
    gain : numpy.ndarray
        Multiplicative gain of each taxel [-].
    offset : numpy.ndarray
        Additive offset of each taxel [signal unit].
    """

    gain: np.ndarray
    offset: np.ndarray

    def apply(self, signal: Any) -> np.ndarray:
        """Gain * x + offset, broadcasting over leading (frame) axes."""
        return self.gain * as_finite_array("signal", signal) + self.offset

    def remove(self, signal: Any) -> np.ndarray:
        """(y - offset) / gain: the two-point calibration that undoes `apply`."""
        return (as_finite_array("signal", signal) - self.offset) / self.gain


def draw_gain_offset(
    shape: tuple[int, ...],
    *,
    gain_spread: float = 0.0,
    offset_spread: float = 0.0,
    rng: Any = None,
) -> GainOffset:
    r"""Draw the fixed gain and offset of every taxel.

    Parameters
    ----------
    shape : tuple of int
        Shape of the taxel array.
    gain_spread : float, default 0.0
        s_g, about the relative standard deviation of the gain [-], >= 0.
    offset_spread : float, default 0.0
        Standard deviation of the offset [signal unit], >= 0.
    rng : numpy.random.Generator or int
        Required when either spread is non-zero.

    Returns
    -------
    GainOffset
        :math:`g = e^{s_g n_1}` (log-normal, so always positive, median 1) and
        :math:`o = s_o n_2`.

    Examples
    --------
    >>> spread = draw_gain_offset((64, 64), gain_spread=0.05, offset_spread=0.01, rng=1)
    >>> round(float(np.log(spread.gain).std()), 2), round(float(spread.offset.std()), 2)
    (0.05, 0.01)
    """
    shape = _as_shape(shape)
    gain_spread = check_positive("gain_spread", gain_spread, allow_zero=True)
    offset_spread = check_positive("offset_spread", offset_spread, allow_zero=True)
    if gain_spread == 0 and offset_spread == 0:
        return GainOffset(np.ones(shape), np.zeros(shape))
    generator = _require_rng(rng)
    gain = np.exp(generator.standard_normal(shape) * gain_spread)
    return GainOffset(gain, generator.standard_normal(shape) * offset_spread)


@dataclass(frozen=True)
class TaxelFaults:
    """Which taxels are dead, stuck or saturated, drawn once by `draw_faults`.

    Attributes
    ----------
    dead, stuck, saturated : numpy.ndarray of bool
        Disjoint masks over the taxel array.
    stuck_level : numpy.ndarray
        Where each stuck taxel is stuck, as a fraction of the output range [-] (0 elsewhere).
    """

    dead: np.ndarray
    stuck: np.ndarray
    saturated: np.ndarray
    stuck_level: np.ndarray

    def apply(self, signal: Any, *, low: float, high: float) -> np.ndarray:
        """Dead taxels read `low`, saturated ones `high`, stuck ones their fixed level."""
        low, high = check_finite("low", low), check_finite("high", high)
        y = as_finite_array("signal", signal)
        y = np.where(self.dead, low, y)
        y = np.where(self.saturated, high, y)
        return np.where(self.stuck, low + self.stuck_level * (high - low), y)

    @property
    def working(self) -> np.ndarray:
        """Mask of the taxels with no fault."""
        return ~(self.dead | self.stuck | self.saturated)


def draw_faults(
    shape: tuple[int, ...],
    *,
    dead: float = 0.0,
    stuck: float = 0.0,
    saturated: float = 0.0,
    rng: Any = None,
) -> TaxelFaults:
    """Choose the faulty taxels: exact counts, disjoint sets, random places.

    Parameters
    ----------
    shape : tuple of int
        Shape of the taxel array.
    dead, stuck, saturated : float, default 0.0
        Fraction of taxels with each fault [-], each in [0, 1], summing to at most 1; the
        count is the fraction times the number of taxels, rounded.
    rng : numpy.random.Generator or int
        Required when any fraction is non-zero.

    Returns
    -------
    TaxelFaults

    Examples
    --------
    >>> faults = draw_faults((10, 10), dead=0.03, stuck=0.02, saturated=0.01, rng=2)
    >>> int(faults.dead.sum()), int(faults.stuck.sum()), int(faults.saturated.sum())
    (3, 2, 1)
    """
    shape = _as_shape(shape)
    fractions = [
        check_range(name, value, 0.0, 1.0)
        for name, value in (("dead", dead), ("stuck", stuck), ("saturated", saturated))
    ]
    if sum(fractions) > 1.0:
        raise ValueError(f"`dead + stuck + saturated` must be <= 1, got {sum(fractions):g}")
    size = int(np.prod(shape))
    masks = [np.zeros(shape, dtype=bool) for _ in range(3)]
    level = np.zeros(shape)
    if sum(fractions) == 0:
        return TaxelFaults(masks[0], masks[1], masks[2], level)
    generator = _require_rng(rng)
    order = generator.permutation(size)
    start = 0
    for mask, fraction in zip(masks, fractions, strict=True):
        count = round(fraction * size)
        mask.flat[order[start : start + count]] = True
        start += count
    level[masks[1]] = generator.uniform(0.0, 1.0, int(masks[1].sum()))
    return TaxelFaults(masks[0], masks[1], masks[2], level)


def neighbour_crosstalk(
    image: Any, *, coupling: float = 0.0, diagonal_coupling: float = 0.0
) -> np.ndarray:
    r"""Leak of each taxel's signal into its neighbours, over the last two axes.

    Parameters
    ----------
    image : array_like, shape (..., rows, cols)
        Signal of each taxel.
    coupling : float, default 0.0
        c, the fraction of a taxel's signal that appears on each edge neighbour [-], in
        [0, 1).
    diagonal_coupling : float, default 0.0
        c_d, the same for corner neighbours [-], in [0, 1).

    Returns
    -------
    numpy.ndarray
        Convolution with [[c_d, c, c_d], [c, 1, c], [c_d, c, c_d]], zero outside the array.

    Notes
    -----
    The kernel is symmetric and the boundary is zero, so the operator is its own adjoint:
    the reconstruction layer can use it as both. Capacitive and resistive matrices couple
    mainly along rows and columns (c), optical ones through the cover in all directions.

    Examples
    --------
    >>> img = np.zeros((3, 3))
    >>> img[1, 1] = 1.0
    >>> neighbour_crosstalk(img, coupling=0.1, diagonal_coupling=0.02).tolist()
    [[0.02, 0.1, 0.02], [0.1, 1.0, 0.1], [0.02, 0.1, 0.02]]
    """
    x = as_finite_array("image", image)
    if x.ndim < 2:
        raise ValueError(f"`image` must be at least 2-D (rows, cols), got shape {x.shape}")
    coupling = check_range("coupling", coupling, 0.0, 1.0, high_inclusive=False)
    diagonal = check_range("diagonal_coupling", diagonal_coupling, 0.0, 1.0, high_inclusive=False)
    if coupling == 0 and diagonal == 0:
        return x.copy()
    kernel = np.array(
        [[diagonal, coupling, diagonal], [coupling, 1.0, coupling], [diagonal, coupling, diagonal]]
    )
    kernel = kernel.reshape((1,) * (x.ndim - 2) + (3, 3))
    return ndimage.convolve(x, kernel, mode="constant", cval=0.0)
