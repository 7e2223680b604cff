"""The PVF2 (PVDF) film itself: charge and open-circuit voltage under stress, eqs. 25.14-25.16."""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_finite, check_positive
from taxel.transducers._capacitive import VACUUM_PERMITTIVITY

__all__ = [
    "PVDF_D33",
    "PVDF_RELATIVE_PERMITTIVITY",
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
    film_thickness: float,
    d33: float = PVDF_D33,
    relative_permittivity: float = PVDF_RELATIVE_PERMITTIVITY,
) -> np.ndarray:
    r"""Open-circuit voltage across the film, eq. 25.14 [V].

    Parameters
    ----------
    stress : array_like
        Normal stress sigma [Pa], positive in tension.
    film_thickness : float
        Thickness h of the film [m], > 0.
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
    >>> float(piezoelectric_voltage(-1e4, film_thickness=28e-6))  # 28 um film, 10 kPa
    0.0869...
    """
    stress = as_finite_array("stress", stress)
    film_thickness = check_positive("film_thickness", film_thickness)
    relative_permittivity = check_positive("relative_permittivity", relative_permittivity)
    permittivity = relative_permittivity * VACUUM_PERMITTIVITY
    return _check_d33(d33) * film_thickness * stress / permittivity


def _check_d33(d33: float) -> float:
    d33 = check_finite("d33", d33)
    if d33 == 0:
        raise ValueError("`d33` must be non-zero, got 0")
    return d33
