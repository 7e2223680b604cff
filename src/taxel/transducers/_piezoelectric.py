"""Piezoelectric (PVF2/PVDF) taxels: eqs. 25.14-25.18 and the two amplifiers of the chapter.

The film under a normal stress sigma (along its poling axis 3) frees a charge Q = d33 A sigma
(eq. 25.16). A charge amplifier (Figure 25.6b) turns it into V_o = -Q / C_f (eq. 25.17); the
resistor R_f in parallel with C_f, or a switch that periodically discharges C_f, makes it a
first-order high-pass with tau = R_f C_f, so a static load fades. A current-to-voltage
converter (Figure 25.7) gives V_o = A R_f d33 dsigma/dt (eq. 25.18), for vibration and slip.

Time runs along the last axis of every array; ``stress`` is positive in tension (a press
gives sigma < 0) and is taken to be ``initial_stress`` before the first sample. The
simulations are exact for stress that is piecewise linear between samples, and each has an
exact inverse.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from scipy import signal as sps

from taxel._validation import as_finite_array, check_choice, check_finite, check_positive
from taxel.transducers._capacitive import VACUUM_PERMITTIVITY

__all__ = [
    "PVDF_D33",
    "PVDF_RELATIVE_PERMITTIVITY",
    "PiezoelectricTransducer",
    "charge_amplifier_output",
    "charge_amplifier_stress",
    "current_amplifier_output",
    "current_amplifier_stress",
    "piezoelectric_charge",
    "piezoelectric_voltage",
]

PVDF_D33 = -33e-12
"""Typical d33 of poled PVDF film [C/N] (manufacturers' film data sheets quote -33 pC/N)."""

PVDF_RELATIVE_PERMITTIVITY = 12.0
"""Typical relative permittivity of PVDF film [-] (data sheets quote 12 to 13)."""


def piezoelectric_charge(stress: Any, *, area: float, d33: float = PVDF_D33) -> np.ndarray:
    """Charge freed on the electrodes by a normal stress, eq. 25.16 [C].

    Parameters
    ----------
    stress : array_like
        Normal stress sigma along the poling axis [Pa], positive in tension.
    area : float
        Electrode area A [m^2], > 0.
    d33 : float, default PVDF_D33
        Longitudinal piezoelectric coefficient [C/N], non-zero.

    Returns
    -------
    numpy.ndarray
        Q = d33 A sigma [C].

    Examples
    --------
    >>> float(piezoelectric_charge(-1e4, area=1e-6))  # 10 kPa press on 1 mm^2 of PVDF
    3.3e-13
    """
    stress = as_finite_array("stress", stress)
    area = check_positive("area", area)
    return _check_d33(d33) * area * stress


def piezoelectric_voltage(
    stress: Any,
    *,
    thickness: float,
    d33: float = PVDF_D33,
    relative_permittivity: float = PVDF_RELATIVE_PERMITTIVITY,
) -> np.ndarray:
    r"""Open-circuit voltage across the film, eq. 25.14 [V].

    Parameters
    ----------
    stress : array_like
        Normal stress sigma [Pa], positive in tension.
    thickness : float
        Film thickness h [m], > 0.
    d33 : float, default PVDF_D33
        [C/N].
    relative_permittivity : float, default PVDF_RELATIVE_PERMITTIVITY
        epsilon / epsilon_0 of the film [-], > 0.

    Returns
    -------
    numpy.ndarray
        V = d33 h sigma / epsilon [V]; equal to Q / C with C = epsilon A / h (eq. 25.15).

    Examples
    --------
    >>> float(piezoelectric_voltage(-1e4, thickness=28e-6))  # 28 um film, 10 kPa
    0.0869...
    """
    stress = as_finite_array("stress", stress)
    thickness = check_positive("thickness", thickness)
    relative_permittivity = check_positive("relative_permittivity", relative_permittivity)
    permittivity = relative_permittivity * VACUUM_PERMITTIVITY
    return _check_d33(d33) * thickness * stress / permittivity


def _check_d33(d33: float) -> float:
    d33 = check_finite("d33", d33)
    if d33 == 0:
        raise ValueError("`d33` must be non-zero, got 0")
    return d33


def _check_series(stress: Any, time_step: float) -> tuple[np.ndarray, float]:
    stress = as_finite_array("stress", stress)
    if stress.ndim == 0:
        raise ValueError("`stress` must be a time series (time along the last axis), got 0-D")
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
    if int(reset_interval) != reset_interval or reset_interval < 1:
        raise ValueError(f"`reset_interval` must be a positive integer, got {reset_interval!r}")
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
    >>> np.round(v, 6).tolist()
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


_AMPLIFIERS = ("charge", "current")


@dataclass(frozen=True)
class PiezoelectricTransducer:
    """A PVDF film taxel with its amplifier (Figures 25.6 and 25.7).

    Senses the normal ``stress`` sigma on the film [Pa], positive in tension, as a time
    series along the last axis; the signal is the amplifier output V_o [V]. Both `respond`
    and `invert` need the keyword ``time_step`` [s]. Only changes are seen: the quantity
    before the first sample is taken as zero.

    Parameters
    ----------
    area : float, default 1e-6
        Electrode area A [m^2].
    thickness : float, default 28e-6
        Film thickness h [m] (28 um is a common PVDF film).
    d33 : float, default PVDF_D33
        [C/N].
    relative_permittivity : float, default PVDF_RELATIVE_PERMITTIVITY
        [-], for the open-circuit voltage `open_circuit_voltage`.
    amplifier : {'charge', 'current'}
        Charge amplifier (eq. 25.17) or current-to-voltage converter (eq. 25.18).
    feedback_capacitance : float, default 1e-11
        C_f of the charge amplifier [F].
    feedback_resistance : float, default 1e10
        R_f [Ohm]: the leak across C_f (charge mode, tau = R_f C_f = 0.1 s by default; inf
        for none) or the transimpedance (current mode, finite).
    reset_interval : int, optional
        Charge mode: discharge C_f every this many samples.

    Examples
    --------
    >>> film = PiezoelectricTransducer()
    >>> press = np.r_[np.linspace(0.0, -1e4, 11), np.full(40, -1e4)]
    >>> v = film.respond(press, time_step=1e-2)  # 0.1 s ramp, then held for 0.4 s
    >>> round(float(v[10]), 4), round(float(v[-1] / v[10]), 4)  # the held load fades
    (-0.0209, 0.0183)
    >>> bool(np.allclose(film.invert(v, time_step=1e-2), press))
    True
    """

    quantity: ClassVar[str] = "stress"
    quantity_unit: ClassVar[str] = "Pa"
    signal_unit: ClassVar[str] = "V"

    area: float = 1e-6
    thickness: float = 28e-6
    d33: float = PVDF_D33
    relative_permittivity: float = PVDF_RELATIVE_PERMITTIVITY
    amplifier: str = "charge"
    feedback_capacitance: float = 1e-11
    feedback_resistance: float = 1e10
    reset_interval: int | None = None

    def __post_init__(self) -> None:
        for name in ("area", "thickness", "relative_permittivity", "feedback_capacitance"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        object.__setattr__(self, "feedback_resistance", _check_leak(self.feedback_resistance))
        object.__setattr__(self, "d33", _check_d33(self.d33))
        check_choice("amplifier", self.amplifier, _AMPLIFIERS)
        if self.amplifier == "current":
            check_positive("feedback_resistance", self.feedback_resistance)
        object.__setattr__(self, "reset_interval", _check_reset(self.reset_interval))

    @property
    def time_constant(self) -> float:
        """Tau = R_f C_f of the charge amplifier [s]."""
        return self.feedback_resistance * self.feedback_capacitance

    def open_circuit_voltage(self, stress: Any) -> np.ndarray:
        """V = d33 h sigma / epsilon across the bare film [V] (eq. 25.14)."""
        return piezoelectric_voltage(
            stress,
            thickness=self.thickness,
            d33=self.d33,
            relative_permittivity=self.relative_permittivity,
        )

    def _options(self) -> dict[str, Any]:
        if self.amplifier == "current":
            return {
                "area": self.area,
                "feedback_resistance": check_positive(
                    "feedback_resistance", self.feedback_resistance
                ),
            }
        return {
            "area": self.area,
            "feedback_capacitance": self.feedback_capacitance,
            "feedback_resistance": self.feedback_resistance,
            "reset_interval": self.reset_interval,
        }

    def respond(self, stress: Any, /, *, time_step: float) -> np.ndarray:
        """Amplifier output [V] for a stress series [Pa] sampled every `time_step` [s]."""
        simulate = (
            current_amplifier_output if self.amplifier == "current" else charge_amplifier_output
        )
        return simulate(stress, time_step, d33=self.d33, **self._options())

    def invert(self, signal: Any, /, *, time_step: float) -> np.ndarray:
        """Stress series [Pa] from the amplifier output [V], starting from zero stress."""
        recover = (
            current_amplifier_stress if self.amplifier == "current" else charge_amplifier_stress
        )
        return recover(signal, time_step, d33=self.d33, **self._options())
