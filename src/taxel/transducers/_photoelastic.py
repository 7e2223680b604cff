"""Photoelastic taxels (Figure 25.12): a reflective circular polariscope and its fringes.

Stress makes the layer birefringent; light crossing it twice (in, off the mirror, out) picks
up a phase difference between its two polarisations proportional to the principal stress
difference in the plane normal to the light (the stress-optic law). Between crossed (dark
field) or parallel (light field) circular polarisers the intensity is sin^2 or cos^2 of half
that phase: fringes, independent of the principal directions. Recovering the load from the
fringes is done in the two ways the literature uses (`_photoelastic_recovery`): fringe
counting (unwrapping the phase along a path on which it grows monotonically) and a
least-squares fit of one load parameter to the whole intensity map.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from taxel._validation import check_choice, check_positive
from taxel.transducers._photoelastic_optics import (
    FIELDS,
    photoelastic_retardation,
    polariscope_intensity,
)
from taxel.transducers._photoelastic_recovery import (
    PhotoelasticFit,
    fit_load_scale,
    unwrap_retardation,
)

__all__ = ["PhotoelasticTransducer"]


@dataclass(frozen=True)
class PhotoelasticTransducer:
    """A reflective photoelastic layer in a circular polariscope (Figure 25.12).

    Senses the ``stress_difference`` sigma_1 - sigma_2 in the plane normal to the light
    [Pa] (>= 0, one value per camera pixel); the signal is the intensity [W/m^2]. `invert`
    unwraps along the last axis, so it needs paths on which the stress difference grows
    from below half a fringe; `fit_load` fits one load parameter to a whole map.

    Parameters
    ----------
    layer_thickness : float, default 2e-3
        t [m].
    stress_optic_coefficient : float, default 7.8e-11
        C [1/Pa] (polycarbonate; soft urethanes are far more sensitive).
    wavelength : float, default 550e-9
        lambda [m].
    field : {'dark', 'light'}
        Polariscope arrangement.
    source_intensity : float, default 1.0
        I_0 [W/m^2].
    passes : int, default 2
        2 for the mirrored (reflective) layer.

    Examples
    --------
    >>> layer = PhotoelasticTransducer()
    >>> round(layer.fringe_stress / 1e6, 4)  # stress difference per fringe [MPa]
    1.7628
    >>> s = np.linspace(0.1e6, 8e6, 300)
    >>> bool(np.allclose(layer.invert(layer.respond(s)), s))
    True
    """

    quantity: ClassVar[str] = "stress_difference"
    quantity_unit: ClassVar[str] = "Pa"
    signal_unit: ClassVar[str] = "W/m^2"

    layer_thickness: float = 2e-3
    stress_optic_coefficient: float = 7.8e-11
    wavelength: float = 550e-9
    field: str = "dark"
    source_intensity: float = 1.0
    passes: int = 2

    def __post_init__(self) -> None:
        photoelastic_retardation(0.0, **self._optics())
        check_choice("field", self.field, FIELDS)
        object.__setattr__(
            self, "source_intensity", check_positive("source_intensity", self.source_intensity)
        )

    def _optics(self) -> dict[str, Any]:
        return {
            "layer_thickness": self.layer_thickness,
            "stress_optic_coefficient": self.stress_optic_coefficient,
            "wavelength": self.wavelength,
            "passes": self.passes,
        }

    @property
    def fringe_stress(self) -> float:
        """Stress difference per fringe order, lambda / (passes t C) [Pa]."""
        return self.wavelength / (
            self.passes * self.layer_thickness * self.stress_optic_coefficient
        )

    def respond(self, stress_difference: Any, /) -> np.ndarray:
        """Intensity [W/m^2] for a field of sigma_1 - sigma_2 [Pa]."""
        delta = photoelastic_retardation(stress_difference, **self._optics())
        return polariscope_intensity(
            delta, field=self.field, source_intensity=self.source_intensity
        )

    def invert(self, signal: Any, /, *, tolerance: float = 0.0) -> np.ndarray:
        """sigma_1 - sigma_2 [Pa] along paths (last axis) by fringe counting."""
        delta = unwrap_retardation(
            signal, field=self.field, source_intensity=self.source_intensity, tolerance=tolerance
        )
        return delta / (2 * np.pi) * self.fringe_stress

    def fit_load(
        self, signal: Any, unit_stress_difference: Any, *, max_load: float
    ) -> PhotoelasticFit:
        """Fit P in sigma_1 - sigma_2 = P * `unit_stress_difference` [Pa per load unit]."""
        unit = photoelastic_retardation(unit_stress_difference, **self._optics())
        return fit_load_scale(
            signal,
            unit,
            max_load=max_load,
            field=self.field,
            source_intensity=self.source_intensity,
        )
