"""Capacitive taxels: parallel plates over an elastomer, read by the detector of eqs. 25.7-25.13.

Each cell is the crossing of a row and a column strip (Figure 25.5). Its capacitance follows
the gap (eqs. 25.9, 25.11); a tangential load slides one plate over the other and shrinks
the overlap; stray capacitance in parallel with the cell dilutes the change; temperature
changes both the permittivity and, by thermal expansion, the unloaded gap. The detector is
the RC divider of Figure 25.5(c).

Sign convention: ``strain`` is the normal strain eps_z of the dielectric [-], negative in
compression, so the gap is h = h0 (1 + eps_z). The chapter's zeta_z = dh/h0 (eq. 25.12) is
-eps_z.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from taxel._validation import (
    as_finite_array,
    check_broadcast,
    check_choice,
    check_finite,
    check_positive,
)
from taxel.transducers._capacitive_detector import (
    capacitance_from_detector_voltage,
    detector_voltage,
    strain_from_detector_voltage,
)

__all__ = ["VACUUM_PERMITTIVITY", "CapacitiveTransducer", "plate_capacitance"]

VACUUM_PERMITTIVITY = 8.8541878128e-12
"""epsilon_0 [F/m] (CODATA 2018)."""


def plate_capacitance(
    gap: Any,
    *,
    plate_width: float,
    plate_length: float,
    permittivity: Any,
    shear_offset: Any = 0.0,
) -> np.ndarray:
    r"""Capacitance of a parallel-plate cell, eqs. 25.9 and 25.11 with sliding plates [F].

    Parameters
    ----------
    gap : array_like
        Distance h between the plates [m], > 0 (h0 unloaded, h0 - dh under load).
    plate_width, plate_length : float
        w and l of the plates [m], > 0. Shear slides the plates along l.
    permittivity : float or array_like
        epsilon of the dielectric [F/m], > 0 (epsilon_r times `VACUUM_PERMITTIVITY`).
    shear_offset : float or array_like, default 0.0
        Tangential offset dx of the top plate along l [m], |dx| <= l. `gap`,
        `permittivity` and `shear_offset` broadcast together.

    Returns
    -------
    numpy.ndarray
        C = epsilon w (l - |dx|) / h [F]; fringing fields are neglected, as in the chapter.

    Notes
    -----
    Eq. 25.9, :math:`C^0_{ij} = \epsilon w l / h_0`, and eq. 25.11,
    :math:`C_{ij} = \epsilon w l / (h_0 - \Delta h)`. The chapter remarks (after eq. 25.13)
    that a tangential force offsets the plates and changes the effective area; here the
    overlap is w (l - |dx|) for equal plates.

    Examples
    --------
    >>> c0 = plate_capacitance(1e-4, plate_width=1e-3, plate_length=1e-3,
    ...                        permittivity=3 * VACUUM_PERMITTIVITY)
    >>> print(f"{float(c0):.4e}")
    2.6563e-13
    >>> c = plate_capacitance(0.9e-4, plate_width=1e-3, plate_length=1e-3,
    ...                       permittivity=3 * VACUUM_PERMITTIVITY)
    >>> float(c / c0)  # 10 % compression: C grows by 1/0.9
    1.1111...
    """
    gap = as_finite_array("gap", gap)
    if np.any(gap <= 0):
        raise ValueError(f"`gap` must be > 0, got {float(np.min(gap)):g}")
    plate_width = check_positive("plate_width", plate_width)
    plate_length = check_positive("plate_length", plate_length)
    permittivity = as_finite_array("permittivity", permittivity)
    if np.any(permittivity <= 0):
        raise ValueError(f"`permittivity` must be > 0, got {float(np.min(permittivity)):g}")
    offset = np.abs(as_finite_array("shear_offset", shear_offset))
    if np.any(offset > plate_length):
        raise ValueError(
            f"`shear_offset` must satisfy |dx| <= plate_length = {plate_length:g}, "
            f"got {float(np.max(offset)):g}"
        )
    try:
        return permittivity * plate_width * (plate_length - offset) / gap
    except ValueError:  # checked only on failure: the sensor's read calls this every frame
        check_broadcast(("gap", "permittivity", "shear_offset"), gap, permittivity, offset)
        raise


_METHODS = ("exact", "chapter")


@dataclass(frozen=True)
class CapacitiveTransducer:
    """A capacitive taxel of Figure 25.5 with its detector, stray capacitance and temperature.

    Senses the normal ``strain`` eps_z of the dielectric layer [-] (negative in compression;
    gap h = h0 (1 + eps_z)); the signal is |V_d| [V]. Temperature effects are off by default.

    Parameters
    ----------
    plate_width, plate_length : float, default 1e-3
        w, l [m].
    gap : float, default 1e-4
        h0, the unloaded gap at the reference temperature [m].
    relative_permittivity : float, default 3.0
        epsilon_r of the dielectric at the reference temperature [-] (about 3 for silicone).
    detector_resistance : float, default 1e6
        R_d [Ohm].
    detector_capacitance : float, default 1e-10
        C_d [F]; made large on purpose (cable), as the chapter advises.
    angular_frequency : float, default 2 pi 1e5
        omega of the source [rad/s].
    source_voltage : float, default 5.0
        |V_s| [V].
    stray_capacitance : float, default 0.0
        Capacitance in parallel with the cell that does not change with load [F] (fringing,
        the overlap of the selected strips with their neighbours).
    reference_temperature : float, default 293.15
        T0 [K], where the nominal values hold.
    permittivity_temperature_coefficient : float, default 0.0
        (1/epsilon) d epsilon / dT [1/K].
    gap_temperature_coefficient : float, default 0.0
        Linear thermal expansion of the dielectric, (1/h0) dh0/dT [1/K].

    Examples
    --------
    >>> cell = CapacitiveTransducer()
    >>> v = cell.respond([-0.05, -0.2])
    >>> np.round(cell.invert(v), 12).tolist()
    [-0.05, -0.2]
    >>> np.round(cell.invert(v, method="chapter"), 4).tolist()  # eq. 25.13 reads low
    [-0.0499, -0.1995]
    """

    quantity: ClassVar[str] = "strain"
    quantity_unit: ClassVar[str] = "-"
    signal_unit: ClassVar[str] = "V"

    plate_width: float = 1e-3
    plate_length: float = 1e-3
    gap: float = 1e-4
    relative_permittivity: float = 3.0
    detector_resistance: float = 1e6
    detector_capacitance: float = 1e-10
    angular_frequency: float = 2 * np.pi * 1e5
    source_voltage: float = 5.0
    stray_capacitance: float = 0.0
    reference_temperature: float = 293.15
    permittivity_temperature_coefficient: float = 0.0
    gap_temperature_coefficient: float = 0.0

    def __post_init__(self) -> None:
        for name in (
            "plate_width",
            "plate_length",
            "gap",
            "relative_permittivity",
            "detector_resistance",
            "detector_capacitance",
            "angular_frequency",
            "source_voltage",
            "reference_temperature",
        ):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        object.__setattr__(
            self,
            "stray_capacitance",
            check_positive("stray_capacitance", self.stray_capacitance, allow_zero=True),
        )
        for name in ("permittivity_temperature_coefficient", "gap_temperature_coefficient"):
            object.__setattr__(self, name, check_finite(name, getattr(self, name)))

    def _detector(self) -> dict[str, Any]:
        return {
            "detector_resistance": self.detector_resistance,
            "detector_capacitance": self.detector_capacitance,
            "angular_frequency": self.angular_frequency,
            "source_voltage": self.source_voltage,
        }

    def _thermal(self, temperature: Any) -> tuple[np.ndarray, np.ndarray]:
        """Permittivity [F/m] and unloaded gap [m] at `temperature` [K]."""
        if temperature is None:
            temperature = self.reference_temperature
        temperature = as_finite_array("temperature", temperature)
        if np.any(temperature <= 0):
            raise ValueError(f"`temperature` must be > 0 K, got {float(np.min(temperature)):g}")
        rise = temperature - self.reference_temperature
        permittivity = (
            self.relative_permittivity
            * VACUUM_PERMITTIVITY
            * (1.0 + self.permittivity_temperature_coefficient * rise)
        )
        return permittivity, self.gap * (1.0 + self.gap_temperature_coefficient * rise)

    def capacitance(
        self, strain: Any, *, shear_offset: Any = 0.0, temperature: Any = None
    ) -> np.ndarray:
        """Cell plus stray capacitance [F] at `strain` [-], offset [m], temperature [K]."""
        strain = as_finite_array("strain", strain)
        if np.any(strain <= -1):
            raise ValueError(f"`strain` must be > -1, got {float(np.min(strain)):g}")
        permittivity, gap = self._thermal(temperature)
        try:
            cell = plate_capacitance(
                gap * (1.0 + strain),
                plate_width=self.plate_width,
                plate_length=self.plate_length,
                permittivity=permittivity,
                shear_offset=shear_offset,
            )
        except ValueError:  # name what was given, not the plate law's own parameters
            offset = as_finite_array("shear_offset", shear_offset)
            check_broadcast(("strain", "shear_offset", "temperature"), strain, offset, gap)
            raise
        return cell + self.stray_capacitance

    def respond(
        self, strain: Any, /, *, shear_offset: Any = 0.0, temperature: Any = None
    ) -> np.ndarray:
        """|V_d| [V] (eq. 25.7) for the dielectric's `strain` [-].

        `shear_offset` [m] slides the plates; `temperature` [K] defaults to the reference.
        """
        capacitance = self.capacitance(strain, shear_offset=shear_offset, temperature=temperature)
        return detector_voltage(capacitance, **self._detector())

    def invert(
        self, signal: Any, /, *, method: str = "exact", temperature: Any = None
    ) -> np.ndarray:
        """Strain eps_z [-] from |V_d| [V].

        ``method='exact'`` inverts eq. 25.7 and the plate law, subtracting the known stray
        capacitance, assuming no shear and the given `temperature` (default: reference).
        ``method='chapter'`` is eq. 25.13 against the unloaded |V_d0| at that temperature,
        as a practitioner would compute it.
        """
        check_choice("method", method, _METHODS)
        if method == "chapter":
            unloaded = self.respond(0.0, temperature=temperature)
            return strain_from_detector_voltage(signal, unloaded)
        total = capacitance_from_detector_voltage(signal, **self._detector())
        permittivity, gap = self._thermal(temperature)
        cell = total - self.stray_capacitance
        with np.errstate(divide="ignore"):
            height = permittivity * self.plate_width * self.plate_length / cell
        return np.where(cell > 0, height / gap - 1.0, np.inf)
