"""The two amplifiers of a piezoelectric taxel: charge (eq. 25.17) and current (eq. 25.18).

Time runs along the last axis of every array; ``stress`` is positive in tension (a press
gives sigma < 0) and is taken to be ``initial_stress`` before the first sample. The
simulations are exact for stress that is piecewise linear between samples, and each has an
exact inverse.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_finite, check_integer, check_positive
from taxel.transducers._piezo_film import PVDF_D33, _check_d33

__all__ = [
    "charge_amplifier_output",
    "charge_amplifier_stress",
    "current_amplifier_output",
    "current_amplifier_stress",
]


def _check_series(stress: Any, time_step: float) -> tuple[np.ndarray, float]:
    stress = as_finite_array("stress", stress)
    if stress.ndim == 0 or stress.shape[-1] == 0:
        raise ValueError(
            f"`stress` must be a time series (time along the last axis), got shape {stress.shape}"
        )
    return stress, check_positive("time_step", time_step)


def _filter_constants(
    time_step: float, feedback_resistance: float, feedback_capacitance: float
) -> tuple[float, float]:
    """Decay per step a and the gain g of a ramp of charge, for tau = R_f C_f."""
    tau = feedback_resistance * feedback_capacitance
    if math.isinf(tau):
        return 1.0, 1.0
    return math.exp(-time_step / tau), -math.expm1(-time_step / tau) * tau / time_step


def _check_leak(feedback_resistance: Any) -> float:
    """R_f across C_f: > 0, and +inf (no resistor) is allowed."""
    if isinstance(feedback_resistance, int | float) and feedback_resistance == math.inf:
        return math.inf
    return check_positive("feedback_resistance", feedback_resistance)


def _check_reset(reset_interval: int | None) -> int | None:
    if reset_interval is None:
        return None
    reset_interval = check_integer("reset_interval", reset_interval)
    return int(reset_interval)


def _segments(array: np.ndarray, reset_interval: int | None) -> tuple[np.ndarray, int]:
    """View the time axis as independent segments between resets (zero padded)."""
    length = array.shape[-1]
    size = length if reset_interval is None else reset_interval
    count = -(-length // size)
    padded = np.zeros((*array.shape[:-1], count * size))
    padded[..., :length] = array
    return padded.reshape(*array.shape[:-1], count, size), length


def charge_amplifier_output(
    stress: Any,
    time_step: float,
    *,
    area: float,
    feedback_capacitance: float,
    feedback_resistance: float = math.inf,
    reset_interval: int | None = None,
    d33: float = PVDF_D33,
    initial_stress: float = 0.0,
) -> np.ndarray:
    r"""Output of the charge amplifier of Figure 25.6(b) for a stress time series [V].

    Parameters
    ----------
    stress : array_like, shape (..., n_samples)
        Normal stress sigma [Pa], positive in tension; time along the last axis.
    time_step : float
        Sampling interval [s], > 0.
    area : float
        Electrode area A [m^2], > 0.
    feedback_capacitance : float
        C_f [F], > 0.
    feedback_resistance : float, default inf
        R_f in parallel with C_f [Ohm], > 0; inf means none (the ideal eq. 25.17).
    reset_interval : int, optional
        Discharge C_f after every `reset_interval` samples (the switch of Figure 25.6b).
    d33 : float, default PVDF_D33
        [C/N].
    initial_stress : float, default 0.0
        sigma before the first sample, with the amplifier settled [Pa].

    Returns
    -------
    numpy.ndarray, shape (..., n_samples)
        V_o [V].

    Notes
    -----
    Eq. 25.17, :math:`V_o = -Q / C_f`, with the leak of R_f:

    .. math:: \frac{dV_o}{dt} + \frac{V_o}{\tau} = -\frac{1}{C_f}\frac{dQ}{dt},
              \qquad \tau = R_f C_f,\quad Q = d_{33} A \sigma

    For Q linear over each step the update is exact:
    :math:`V_k = a V_{k-1} - g\,\Delta Q_k / C_f` with :math:`a = e^{-\Delta t/\tau}` and
    :math:`g = (\tau/\Delta t)(1 - a)`. A step of stress therefore decays as
    :math:`e^{-t/\tau}`: the reason the chapter says steady loads cannot be measured.

    Examples
    --------
    >>> step = np.full(6, -1e4)  # a 10 kPa press held from t = 0
    >>> v = charge_amplifier_output(step, 1e-3, area=1e-6, feedback_capacitance=1e-11,
    ...                             feedback_resistance=1e8)  # tau = 1 ms
    >>> np.round(v / v[0], 4).tolist()
    [1.0, 0.3679, 0.1353, 0.0498, 0.0183, 0.0067]
    """
    stress, time_step = _check_series(stress, time_step)
    area = check_positive("area", area)
    feedback_capacitance = check_positive("feedback_capacitance", feedback_capacitance)
    feedback_resistance = _check_leak(feedback_resistance)
    reset_interval = _check_reset(reset_interval)
    initial_stress = check_finite("initial_stress", initial_stress)
    charge = _check_d33(d33) * area * (stress - initial_stress)
    increments = np.diff(charge, axis=-1, prepend=0.0)
    decay, gain = _filter_constants(time_step, feedback_resistance, feedback_capacitance)
    segments, length = _segments(increments, reset_interval)
    from scipy import signal as sps  # here: it takes ~1 s to import (see taxel.cli)

    output = sps.lfilter([-gain / feedback_capacitance], [1.0, -decay], segments, axis=-1)
    return output.reshape(*stress.shape[:-1], -1)[..., :length]


def charge_amplifier_stress(
    output: Any,
    time_step: float,
    *,
    area: float,
    feedback_capacitance: float,
    feedback_resistance: float = math.inf,
    reset_interval: int | None = None,
    d33: float = PVDF_D33,
    initial_stress: float = 0.0,
) -> np.ndarray:
    """Stress series from the charge amplifier's output: the exact inverse of the recursion.

    Parameters
    ----------
    output : array_like, shape (..., n_samples)
        V_o [V]; time along the last axis.
    time_step, area, feedback_capacitance, feedback_resistance, reset_interval, d33
        The amplifier, as in `charge_amplifier_output`.
    initial_stress : float, default 0.0
        sigma before the first sample [Pa]: the one thing a charge amplifier cannot tell.

    Returns
    -------
    numpy.ndarray
        sigma [Pa]. Exact without noise; with noise, the division by g and the running sum
        make the error a random walk, which is why the chapter calls PVDF dynamic-only.

    Examples
    --------
    >>> kw = dict(area=1e-6, feedback_capacitance=1e-11, feedback_resistance=1e8)
    >>> stress = -1e4 * np.sin(np.linspace(0, np.pi, 7))
    >>> v = charge_amplifier_output(stress, 1e-3, **kw)
    >>> bool(np.allclose(charge_amplifier_stress(v, 1e-3, **kw), stress))
    True
    """
    output = as_finite_array("output", output)
    if output.ndim == 0:
        raise ValueError("`output` must be a time series (time along the last axis), got 0-D")
    time_step = check_positive("time_step", time_step)
    area = check_positive("area", area)
    feedback_capacitance = check_positive("feedback_capacitance", feedback_capacitance)
    feedback_resistance = _check_leak(feedback_resistance)
    reset_interval = _check_reset(reset_interval)
    initial_stress = check_finite("initial_stress", initial_stress)
    decay, gain = _filter_constants(time_step, feedback_resistance, feedback_capacitance)
    segments, length = _segments(output, reset_interval)
    previous = np.zeros_like(segments)
    previous[..., 1:] = segments[..., :-1]  # the state is zero after every reset
    increments = -feedback_capacitance * (segments - decay * previous) / gain
    increments = increments.reshape(*output.shape[:-1], -1)[..., :length]
    return initial_stress + np.cumsum(increments, axis=-1) / (_check_d33(d33) * area)


def current_amplifier_output(
    stress: Any,
    time_step: float,
    *,
    area: float,
    feedback_resistance: float,
    d33: float = PVDF_D33,
    initial_stress: float = 0.0,
) -> np.ndarray:
    r"""Output of the current-to-voltage converter of Figure 25.7, eq. 25.18 [V].

    Parameters
    ----------
    stress : array_like, shape (..., n_samples)
        sigma [Pa], positive in tension; time along the last axis.
    time_step : float
        Sampling interval [s], > 0.
    area : float
        A [m^2], > 0.
    feedback_resistance : float
        R_f [Ohm], > 0.
    d33 : float, default PVDF_D33
        [C/N].
    initial_stress : float, default 0.0
        sigma before the first sample [Pa].

    Returns
    -------
    numpy.ndarray
        V_o [V], the mean over each step of A R_f d33 dsigma/dt (a backward difference).

    Notes
    -----
    Eq. 25.18: :math:`V_o = R_f\, dQ/dt = A R_f d_{33}\, d\sigma/dt`. Only changes of
    stress show; a held load reads zero.

    Examples
    --------
    >>> ramp = np.array([0.0, -1e3, -2e3, -2e3])  # -1 MPa/s for 2 ms, then held
    >>> v = current_amplifier_output(ramp, 1e-3, area=1e-6, feedback_resistance=1e9)
    >>> (np.round(v, 6) + 0.0).tolist()  # (+ 0.0: no negative zeros)
    [0.0, 0.033, 0.033, 0.0]
    """
    stress, time_step = _check_series(stress, time_step)
    area = check_positive("area", area)
    feedback_resistance = check_positive("feedback_resistance", feedback_resistance)
    initial_stress = check_finite("initial_stress", initial_stress)
    rate = np.diff(stress, axis=-1, prepend=initial_stress) / time_step
    return area * feedback_resistance * _check_d33(d33) * rate


def current_amplifier_stress(
    output: Any,
    time_step: float,
    *,
    area: float,
    feedback_resistance: float,
    d33: float = PVDF_D33,
    initial_stress: float = 0.0,
) -> np.ndarray:
    """Stress series from the current-to-voltage output: the running integral of eq. 25.18 [Pa].

    Parameters
    ----------
    output : array_like, shape (..., n_samples)
        V_o [V].
    time_step, area, feedback_resistance, d33, initial_stress
        As in `current_amplifier_output`.

    Returns
    -------
    numpy.ndarray
        sigma [Pa].

    Examples
    --------
    >>> v = np.array([0.0, 0.033, 0.033, 0.0])
    >>> s = current_amplifier_stress(v, 1e-3, area=1e-6, feedback_resistance=1e9)
    >>> np.round(s).tolist()
    [0.0, -1000.0, -2000.0, -2000.0]
    """
    output = as_finite_array("output", output)
    if output.ndim == 0:
        raise ValueError("`output` must be a time series (time along the last axis), got 0-D")
    time_step = check_positive("time_step", time_step)
    area = check_positive("area", area)
    feedback_resistance = check_positive("feedback_resistance", feedback_resistance)
    initial_stress = check_finite("initial_stress", initial_stress)
    scale = time_step / (area * feedback_resistance * _check_d33(d33))
    return initial_stress + np.cumsum(output, axis=-1) * scale
