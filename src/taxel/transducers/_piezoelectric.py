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

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from taxel._validation import check_choice, check_positive
from taxel.transducers._piezo_amplifiers import (
    _check_leak,
    _check_reset,
    charge_amplifier_output,
    charge_amplifier_stress,
    current_amplifier_output,
    current_amplifier_stress,
)
from taxel.transducers._piezo_film import (
    PVDF_D33,
    PVDF_RELATIVE_PERMITTIVITY,
    _check_d33,
    piezoelectric_voltage,
)

__all__ = ["PiezoelectricTransducer"]

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
    film_thickness : float, default 28e-6
        Thickness h of the film [m] (28 um is a common PVDF film).
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
    film_thickness: float = 28e-6
    d33: float = PVDF_D33
    relative_permittivity: float = PVDF_RELATIVE_PERMITTIVITY
    amplifier: str = "charge"
    feedback_capacitance: float = 1e-11
    feedback_resistance: float = 1e10
    reset_interval: int | None = None

    def __post_init__(self) -> None:
        for name in ("area", "film_thickness", "relative_permittivity", "feedback_capacitance"):
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
            film_thickness=self.film_thickness,
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
