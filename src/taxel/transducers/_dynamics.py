"""Time-dependent non-idealities: hysteresis, first-order lag, creep, drift, temperature.

Time runs along the last axis; every function is the identity when its strength is zero.
The state before the first sample is stated by an ``initial_value`` argument (0 by default: a
relaxed, unloaded taxel), never guessed.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_finite, check_integer, check_positive
from taxel.transducers._common import as_generator

__all__ = [
    "add_drift",
    "creep",
    "first_order_lag",
    "play_hysteresis",
    "temperature_dependence",
]


def _series(name: str, value: Any) -> np.ndarray:
    array = as_finite_array(name, value)
    if array.ndim == 0:
        raise ValueError(f"`{name}` must be a time series (time along the last axis), got 0-D")
    return array


def play_hysteresis(
    signal: Any, *, loop_width: float = 0.0, n_operators: int = 1, initial_value: float = 0.0
) -> np.ndarray:
    r"""Rate-independent hysteresis: a play operator, or a Prandtl-Ishlinskii sum of them.

    Parameters
    ----------
    signal : array_like, shape (..., n_samples)
        Input series [signal unit].
    loop_width : float, default 0.0
        w, the vertical width of a major loop [signal unit], >= 0: on a sweep that runs
        past each turning point by more than w, the rising branch lies w/2 below the input
        and the falling one w/2 above it.
    n_operators : int, default 1
        1 gives the single play (backlash) operator, with sharp corners at reversals; more
        give a Prandtl-Ishlinskii operator of plays with widths 2 w i / (n + 1),
        i = 1..n, equal weights, whose loops have rounded corners and the same major width.
    initial_value : float, default 0.0
        Input and output before the first sample.

    Returns
    -------
    numpy.ndarray
        :math:`y_k = \min(\max(y_{k-1}, x_k - r), x_k + r)` with r = w/2 for each play,
        averaged over the plays.

    Examples
    --------
    >>> x = np.array([0.0, 1.0, 2.0, 1.0, 0.0, 1.0, 2.0])
    >>> play_hysteresis(x, loop_width=1.0).tolist()
    [0.0, 0.5, 1.5, 1.5, 0.5, 0.5, 1.5]
    """
    x = _series("signal", signal)
    loop_width = check_positive("loop_width", loop_width, allow_zero=True)
    n_operators = check_integer("n_operators", n_operators)
    initial_value = check_finite("initial_value", initial_value)
    if loop_width == 0:
        return x.copy()
    count = int(n_operators)
    radii = (
        loop_width * np.arange(1, count + 1) / (count + 1)
        if count > 1
        else np.array([loop_width / 2])
    )
    state = np.full((count, *x.shape[:-1]), initial_value)
    radii = radii.reshape((count,) + (1,) * (x.ndim - 1))
    out = np.empty_like(x)
    for k in range(x.shape[-1]):
        state = np.clip(state, x[..., k] - radii, x[..., k] + radii)
        out[..., k] = state.mean(axis=0)
    return out


def first_order_lag(
    signal: Any, time_step: float, *, time_constant: float, initial_value: float = 0.0
) -> np.ndarray:
    r"""A first-order low-pass, tau dy/dt + y = x, exact for piecewise-linear input.

    Parameters
    ----------
    signal : array_like, shape (..., n_samples)
        Input x [signal unit].
    time_step : float
        Sampling interval [s], > 0.
    time_constant : float
        tau [s], >= 0; 0 returns the input.
    initial_value : float, default 0.0
        x and y before the first sample (settled).

    Returns
    -------
    numpy.ndarray
        :math:`y_k = a y_{k-1} + (g - a) x_{k-1} + (1 - g) x_k`, with
        :math:`a = e^{-\Delta t/\tau}` and :math:`g = (\tau/\Delta t)(1 - a)`.

    Examples
    --------
    >>> y = first_order_lag(np.ones(4), 1.0, time_constant=1.0)
    >>> np.round(y, 4).tolist()  # ramp to 1 within the first step, then e^-t
    [0.3679, 0.7675, 0.9145, 0.9685]
    """
    x = _series("signal", signal)
    time_step = check_positive("time_step", time_step)
    time_constant = check_positive("time_constant", time_constant, allow_zero=True)
    initial_value = check_finite("initial_value", initial_value)
    if time_constant == 0:
        return x.copy()
    decay = math.exp(-time_step / time_constant)
    gain = -math.expm1(-time_step / time_constant) * time_constant / time_step
    before = np.full((*x.shape[:-1], 1), initial_value)
    extended = np.concatenate([before, x], axis=-1)
    # lfilter's state ahead of sample n is b1 x[n-1] + a y[n-1]; settled at `initial_value` it is
    # (g - a + a) initial_value, which makes the prepended sample come out as `initial_value` too.
    state = np.full((*x.shape[:-1], 1), gain * initial_value)
    from scipy import signal as sps  # here: it takes ~1 s to import (see taxel.cli)

    out, _ = sps.lfilter([1.0 - gain, gain - decay], [1.0, -decay], extended, axis=-1, zi=state)
    return out[..., 1:]


def creep(
    signal: Any,
    time_step: float,
    *,
    creep_fraction: float = 0.0,
    time_constant: float = 1.0,
    initial_value: float = 0.0,
) -> np.ndarray:
    r"""Creep of a viscoelastic cover: a held load reads more and more, up to (1 + f) times.

    Parameters
    ----------
    signal : array_like, shape (..., n_samples)
        The instantaneous (elastic) response [signal unit].
    time_step : float
        Sampling interval [s], > 0.
    creep_fraction : float, default 0.0
        f, the creep that builds up under a held load as a fraction of the elastic part
        [-], >= 0 (a few percent to tens of percent for elastomers).
    time_constant : float, default 1.0
        tau of the creep [s], > 0.
    initial_value : float, default 0.0
        Signal before the first sample, settled.

    Returns
    -------
    numpy.ndarray
        :math:`y = x + f\,\mathrm{lag}_\tau(x)`: the step response
        :math:`x (1 + f (1 - e^{-t/\tau}))` of a standard linear solid under a held load,
        which recovers the same way on unloading.

    Examples
    --------
    >>> y = creep(np.ones(5), 1.0, creep_fraction=0.1, time_constant=2.0)
    >>> np.round(y, 4).tolist()
    [1.0213, 1.0523, 1.0711, 1.0824, 1.0893]
    """
    x = _series("signal", signal)
    creep_fraction = check_positive("creep_fraction", creep_fraction, allow_zero=True)
    time_constant = check_positive("time_constant", time_constant)
    if creep_fraction == 0:
        return x.copy()
    lag = first_order_lag(x, time_step, time_constant=time_constant, initial_value=initial_value)
    return x + creep_fraction * lag


def add_drift(
    signal: Any,
    time_step: float,
    *,
    rate: float = 0.0,
    random_walk: float = 0.0,
    rng: Any = None,
) -> np.ndarray:
    r"""Slow baseline drift: a linear trend plus a random walk, starting from zero.

    Parameters
    ----------
    signal : array_like, shape (..., n_samples)
        Input [signal unit].
    time_step : float
        Sampling interval [s], > 0.
    rate : float, default 0.0
        Linear drift [signal unit / s].
    random_walk : float, default 0.0
        Random-walk intensity [signal unit / sqrt(s)], >= 0: after t seconds the baseline
        has wandered by random_walk sqrt(t) rms. Independent for every taxel.
    rng : numpy.random.Generator or int
        Required when `random_walk` > 0.

    Returns
    -------
    numpy.ndarray
        :math:`y_k = x_k + r t_k + \sum_{i \le k} \sigma \sqrt{\Delta t}\, n_i`,
        :math:`t_k = k \Delta t`.

    Examples
    --------
    >>> np.round(add_drift(np.zeros(4), 0.5, rate=0.2), 12).tolist()
    [0.0, 0.1, 0.2, 0.3]
    """
    x = _series("signal", signal)
    time_step = check_positive("time_step", time_step)
    rate = check_finite("rate", rate)
    random_walk = check_positive("random_walk", random_walk, allow_zero=True)
    y = x + rate * time_step * np.arange(x.shape[-1])
    if random_walk > 0:
        if rng is None:
            raise TypeError("`rng` is required when the effect is on (a Generator or an int seed)")
        steps = as_generator("rng", rng).standard_normal(x.shape) * random_walk
        steps[..., 0] = 0.0
        y = y + np.cumsum(steps, axis=-1) * math.sqrt(time_step)
    return y


def temperature_dependence(
    signal: Any,
    temperature: Any,
    *,
    reference_temperature: float = 293.15,
    gain_coefficient: float = 0.0,
    offset_coefficient: float = 0.0,
) -> np.ndarray:
    r"""Linear temperature dependence of a taxel's sensitivity and zero.

    Parameters
    ----------
    signal : array_like
        Output at the reference temperature [signal unit].
    temperature : float or array_like
        Temperature [K], > 0; broadcasts against `signal` (one value, a map or a series).
    reference_temperature : float, default 293.15
        T_0 [K], > 0.
    gain_coefficient : float, default 0.0
        alpha, relative change of sensitivity per kelvin [1/K].
    offset_coefficient : float, default 0.0
        beta, zero shift per kelvin [signal unit / K].

    Returns
    -------
    numpy.ndarray
        :math:`y = x (1 + \alpha (T - T_0)) + \beta (T - T_0)`.

    Examples
    --------
    >>> temperature_dependence(1.0, 303.15, gain_coefficient=-2e-3,
    ...                        offset_coefficient=0.01).round(6).tolist()
    1.08
    """
    x = as_finite_array("signal", signal)
    temperature = as_finite_array("temperature", temperature)
    if np.any(temperature <= 0):
        raise ValueError(f"`temperature` must be > 0 K, got {float(np.min(temperature)):g}")
    reference = check_positive("reference_temperature", reference_temperature)
    alpha = check_finite("gain_coefficient", gain_coefficient)
    beta = check_finite("offset_coefficient", offset_coefficient)
    rise = temperature - reference
    return x * (1.0 + alpha * rise) + beta * rise
