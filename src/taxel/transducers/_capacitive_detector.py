"""The detector of a capacitive matrix (Figure 25.5c) and the chapter's strain readout.

Eqs. 25.7 and 25.8 give the detector voltage for the selected crossing, eq. 25.13 the strain
from the loaded and unloaded voltages; the exact inverse of eq. 25.7 is here too.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_broadcast, check_positive

__all__ = [
    "capacitance_from_detector_voltage",
    "detector_voltage",
    "strain_from_detector_voltage",
]


def _check_detector(
    detector_resistance: float, detector_capacitance: float, angular_frequency: float
) -> tuple[float, float, float]:
    return (
        check_positive("detector_resistance", detector_resistance),
        check_positive("detector_capacitance", detector_capacitance),
        check_positive("angular_frequency", angular_frequency),
    )


def detector_voltage(
    capacitance: Any,
    *,
    detector_resistance: float,
    detector_capacitance: float,
    angular_frequency: float,
    source_voltage: float,
    approximate: bool = False,
) -> np.ndarray:
    r"""Magnitude of the voltage at the detector input, eq. 25.7 (or 25.8) [V].

    Parameters
    ----------
    capacitance : array_like
        C_ij, the selected cell plus any stray capacitance in parallel with it [F], >= 0.
    detector_resistance : float
        R_d, the detector's input resistance [Ohm], > 0.
    detector_capacitance : float
        C_d, the stray capacitance to ground at the detector: amplifier input, cable and the
        unselected (grounded) lines [F], > 0.
    angular_frequency : float
        omega of the sinusoidal source [rad/s], > 0.
    source_voltage : float
        |V_s| [V], > 0.
    approximate : bool, default False
        Use eq. 25.8, |V_d| = (C_ij / C_d) |V_s|, valid for C_d >> C_ij and large omega.

    Returns
    -------
    numpy.ndarray
        |V_d| [V].

    Notes
    -----
    Eq. 25.7 of the seed chapter, the divider of C_ij against R_d || C_d:

    .. math:: |V_d| = \frac{C_{ij} R_d \omega}{\sqrt{1 + [\omega R_d (C_{ij} + C_d)]^2}} |V_s|

    For :math:`\omega R_d (C_{ij} + C_d) \gg 1` it tends to
    :math:`C_{ij} / (C_{ij} + C_d) |V_s|`, and to eq. 25.8 when also :math:`C_d \gg C_{ij}`.

    Examples
    --------
    >>> kw = dict(detector_resistance=1e6, detector_capacitance=1e-10,
    ...           angular_frequency=2 * np.pi * 1e5, source_voltage=5.0)
    >>> exact = detector_voltage(1e-12, **kw)
    >>> approx = detector_voltage(1e-12, approximate=True, **kw)
    >>> print(f"{float(exact):.5f} {float(approx):.5f}")
    0.04950 0.05000
    """
    capacitance = as_finite_array("capacitance", capacitance)
    if np.any(capacitance < 0):
        raise ValueError(f"`capacitance` must be >= 0, got {float(np.min(capacitance)):g}")
    resistance, stray, omega = _check_detector(
        detector_resistance, detector_capacitance, angular_frequency
    )
    source_voltage = check_positive("source_voltage", source_voltage)
    if approximate:
        return capacitance / stray * source_voltage
    x = omega * resistance
    return x * capacitance / np.sqrt(1.0 + (x * (capacitance + stray)) ** 2) * source_voltage


def capacitance_from_detector_voltage(
    voltage: Any,
    *,
    detector_resistance: float,
    detector_capacitance: float,
    angular_frequency: float,
    source_voltage: float,
    approximate: bool = False,
) -> np.ndarray:
    r"""C_ij from |V_d|: eq. 25.7 (or 25.8) solved for the capacitance [F].

    Parameters
    ----------
    voltage : array_like
        |V_d| [V], in [0, |V_s|).
    detector_resistance, detector_capacitance, angular_frequency, source_voltage, approximate
        The detector, as in `detector_voltage`.

    Returns
    -------
    numpy.ndarray
        C_ij [F].

    Notes
    -----
    With :math:`a = |V_d| / |V_s|` and :math:`x = \omega R_d`, squaring eq. 25.7 gives a
    quadratic in C whose non-negative root is

    .. math:: C = \frac{a \left[a x C_d + \sqrt{1 + x^2 C_d^2 - a^2}\right]}{(1 - a^2) x}

    Examples
    --------
    >>> kw = dict(detector_resistance=1e6, detector_capacitance=1e-10,
    ...           angular_frequency=2 * np.pi * 1e5, source_voltage=5.0)
    >>> v = detector_voltage(1e-12, **kw)
    >>> print(f"{float(capacitance_from_detector_voltage(v, **kw)):.6e}")
    1.000000e-12
    """
    voltage = as_finite_array("voltage", voltage)
    resistance, stray, omega = _check_detector(
        detector_resistance, detector_capacitance, angular_frequency
    )
    source_voltage = check_positive("source_voltage", source_voltage)
    ratio = voltage / source_voltage
    if np.any((ratio < 0) | (ratio >= 1)):
        bad = float(voltage.flat[np.argmax((ratio < 0) | (ratio >= 1))])
        raise ValueError(f"`voltage` must lie in [0, {source_voltage:g}) V, got {bad:g}")
    if approximate:
        return ratio * stray
    x = omega * resistance
    root = np.sqrt(1.0 + (x * stray) ** 2 - ratio**2)
    return ratio * (ratio * x * stray + root) / ((1.0 - ratio**2) * x)


def strain_from_detector_voltage(voltage: Any, unloaded_voltage: Any) -> np.ndarray:
    r"""Normal strain of the dielectric from |V_d| and |V_d0|, eq. 25.13 [-].

    Parameters
    ----------
    voltage : array_like
        |V_d| under load [V], > 0.
    unloaded_voltage : array_like
        |V_d0| with no load [V], > 0 (broadcasts against `voltage`).

    Returns
    -------
    numpy.ndarray
        eps_z = -(|V_d| - |V_d0|) / |V_d| [-], negative in compression.

    Notes
    -----
    Eq. 25.13 of the seed chapter:

    .. math:: \frac{|V_d| - |V_{d0}|}{|V_d|} = 1 - \frac{C^0_{ij}}{C_{ij}}
              = \frac{\Delta h}{h_0} \cong \zeta_z

    The chain is exact when eq. 25.8 holds (engineering strain dh/h0, no small-strain
    step); what makes it approximate is eq. 25.8 itself. Under eq. 25.7 at high omega,
    |V_d| is proportional to C / (C + C_d), and the estimate becomes
    (dh/h0) C_d / (C0 + C_d): its error grows in proportion to the strain. Stray capacitance
    C_s in parallel with the cell scales it by a further C0 / (C0 + C_s). Normalising by
    |V_d0| instead of |V_d| would give dh / (h0 - dh), wrong already at second order.
    The minus sign turns the chapter's compression-positive zeta_z into our eps_z.

    Examples
    --------
    >>> round(float(strain_from_detector_voltage(0.0125, 0.01)), 12)  # C grew by 1.25: dh/h0 = 0.2
    -0.2
    """
    voltage = as_finite_array("voltage", voltage)
    unloaded_voltage = as_finite_array("unloaded_voltage", unloaded_voltage)
    if np.any(voltage <= 0):
        raise ValueError(f"`voltage` must be > 0, got {float(np.min(voltage)):g}")
    if np.any(unloaded_voltage <= 0):
        raise ValueError(
            f"`unloaded_voltage` must be > 0, got {float(np.min(unloaded_voltage)):g}"
        )
    try:
        return -(voltage - unloaded_voltage) / voltage
    except ValueError:  # checked only on failure: inverting a frame needs no extra pass
        check_broadcast(("voltage", "unloaded_voltage"), voltage, unloaded_voltage)
        raise
