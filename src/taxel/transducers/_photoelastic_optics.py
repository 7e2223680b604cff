"""The optics of photoelastic taxels (Figure 25.12): the stress-optic law and the polariscope.

Stress makes the layer birefringent; light crossing it twice (in, off the mirror, out) picks
up a phase difference between its two polarisations proportional to the principal stress
difference in the plane normal to the light (the stress-optic law). Between crossed (dark
field) or parallel (light field) circular polarisers the intensity is sin^2 or cos^2 of half
that phase: fringes, independent of the principal directions. The transducer itself is in
`_photoelastic`, the recovery of load from fringes in `_photoelastic_recovery`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel._validation import (
    as_finite_array,
    check_broadcast,
    check_choice,
    check_integer,
    check_positive,
)

__all__ = [
    "FIELDS",
    "photoelastic_retardation",
    "polariscope_intensity",
    "principal_stress_difference",
]

FIELDS = ("dark", "light")


def principal_stress_difference(stress_a: Any, stress_b: Any, shear_stress: Any) -> np.ndarray:
    r"""sigma_1 - sigma_2 of an in-plane stress state, from its components [Pa].

    Parameters
    ----------
    stress_a, stress_b : array_like
        The two normal stresses in the plane normal to the light [Pa].
    shear_stress : array_like
        The shear stress in that plane [Pa] (the three broadcast together).

    Returns
    -------
    numpy.ndarray
        :math:`\sqrt{(\sigma_a - \sigma_b)^2 + 4 \tau_{ab}^2}` [Pa], >= 0.

    Examples
    --------
    >>> float(principal_stress_difference(3.0, -1.0, 0.0))
    4.0
    >>> float(principal_stress_difference(0.0, 0.0, 2.0))  # pure shear
    4.0
    """
    a = as_finite_array("stress_a", stress_a)
    b = as_finite_array("stress_b", stress_b)
    shear = as_finite_array("shear_stress", shear_stress)
    try:
        return np.hypot(a - b, 2.0 * shear)
    except ValueError:  # checked only on failure, as the arithmetic costs less than a check
        check_broadcast(("stress_a", "stress_b", "shear_stress"), a, b, shear)
        raise


def photoelastic_retardation(
    stress_difference: Any,
    *,
    layer_thickness: float,
    stress_optic_coefficient: float,
    wavelength: float,
    passes: int = 2,
) -> np.ndarray:
    r"""Phase difference delta between the two polarisations leaving the layer [rad].

    Parameters
    ----------
    stress_difference : array_like
        sigma_1 - sigma_2 in the plane normal to the light [Pa], >= 0.
    layer_thickness : float
        Thickness t of the photoelastic layer [m], > 0.
    stress_optic_coefficient : float
        C [1/Pa], > 0 (1 brewster = 1e-12 /Pa; polycarbonate is about 7.8e-11 /Pa).
    wavelength : float
        lambda of the light in vacuum [m], > 0.
    passes : int, default 2
        Times the light crosses the layer: 2 for the reflective transducer of Figure 25.12.

    Returns
    -------
    numpy.ndarray
        :math:`\delta = n_{pass} \cdot 2\pi t C (\sigma_1 - \sigma_2) / \lambda` [rad];
        the fringe order is :math:`N = \delta / 2\pi`.

    Examples
    --------
    >>> d = photoelastic_retardation(1e6, layer_thickness=2e-3, stress_optic_coefficient=7.8e-11,
    ...                              wavelength=550e-9)
    >>> round(float(d / (2 * np.pi)), 4)  # fringe order at 1 MPa
    0.5673
    """
    difference = as_finite_array("stress_difference", stress_difference)
    if np.any(difference < 0):
        raise ValueError(f"`stress_difference` must be >= 0, got {float(np.min(difference)):g}")
    layer_thickness = check_positive("layer_thickness", layer_thickness)
    coefficient = check_positive("stress_optic_coefficient", stress_optic_coefficient)
    wavelength = check_positive("wavelength", wavelength)
    passes = check_integer("passes", passes)
    return passes * 2.0 * np.pi * layer_thickness * coefficient * difference / wavelength


def polariscope_intensity(
    retardation: Any, *, field: str = "dark", source_intensity: float = 1.0
) -> np.ndarray:
    r"""Intensity leaving a circular polariscope [same unit as `source_intensity`].

    Parameters
    ----------
    retardation : array_like
        delta [rad].
    field : {'dark', 'light'}
        Crossed (dark field: black where unstressed) or parallel analyser.
    source_intensity : float, default 1.0
        I_0, the intensity with the analyser aligned to the light [W/m^2], > 0.

    Returns
    -------
    numpy.ndarray
        :math:`I_0 \sin^2(\delta/2)` (dark) or :math:`I_0 \cos^2(\delta/2)` (light).

    Examples
    --------
    >>> np.round(polariscope_intensity([0.0, np.pi / 2, np.pi, 2 * np.pi]), 3).tolist()
    [0.0, 0.5, 1.0, 0.0]
    """
    delta = as_finite_array("retardation", retardation)
    check_choice("field", field, FIELDS)
    source_intensity = check_positive("source_intensity", source_intensity)
    wave = np.sin(delta / 2.0) if field == "dark" else np.cos(delta / 2.0)
    return source_intensity * wave**2
