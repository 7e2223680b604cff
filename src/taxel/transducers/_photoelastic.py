"""Photoelastic taxels (Figure 25.12): a reflective circular polariscope and its fringes.

Stress makes the layer birefringent; light crossing it twice (in, off the mirror, out) picks
up a phase difference between its two polarisations proportional to the principal stress
difference in the plane normal to the light (the stress-optic law). Between crossed (dark
field) or parallel (light field) circular polarisers the intensity is sin^2 or cos^2 of half
that phase: fringes, independent of the principal directions. Recovering the load from the
fringes is done here in the two ways the literature uses: fringe counting (unwrapping the
phase along a path on which it grows monotonically) and a least-squares fit of one load
parameter to the whole intensity map.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from scipy import optimize

from taxel._validation import as_finite_array, check_choice, check_positive

__all__ = [
    "PhotoelasticFit",
    "PhotoelasticTransducer",
    "fit_load_scale",
    "photoelastic_retardation",
    "polariscope_intensity",
    "principal_stress_difference",
    "unwrap_retardation",
]

_FIELDS = ("dark", "light")


def principal_stress_difference(stress_a: Any, stress_b: Any, shear_stress: Any) -> np.ndarray:
    r"""sigma_1 - sigma_2 of an in-plane stress state, from its components [Pa].

    Parameters
    ----------
    stress_a, stress_b : array_like
        The two normal stresses in the plane normal to the light [Pa].
    shear_stress : array_like
        The shear stress in that plane [Pa].

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
    return np.hypot(a - b, 2.0 * shear)


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
    if int(passes) != passes or passes < 1:
        raise ValueError(f"`passes` must be a positive integer, got {passes!r}")
    return int(passes) * 2.0 * np.pi * layer_thickness * coefficient * difference / wavelength


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
    check_choice("field", field, _FIELDS)
    source_intensity = check_positive("source_intensity", source_intensity)
    wave = np.sin(delta / 2.0) if field == "dark" else np.cos(delta / 2.0)
    return source_intensity * wave**2


def unwrap_retardation(
    intensity: Any, *, field: str = "dark", source_intensity: float = 1.0, tolerance: float = 0.0
) -> np.ndarray:
    r"""Retardation along a path from intensities, by fringe counting [rad].

    Parameters
    ----------
    intensity : array_like, shape (..., n_samples)
        Intensities along a path (last axis) on which delta starts below the first dark
        fringe order's half (delta_0 < pi) and never decreases. Along the load's line of
        action, from deep in the layer towards the load, is such a path.
    field, source_intensity
        The polariscope, as in `polariscope_intensity`.
    tolerance : float, default 0.0
        How far [rad] a noisy sample may fall below its predecessor and still count as
        "not decreasing".

    Returns
    -------
    numpy.ndarray, shape (..., n_samples)
        delta [rad]. Needs at least a few samples per fringe.

    Notes
    -----
    The intensity gives :math:`\psi = 2\arcsin\sqrt{I/I_0} \in [0, \pi]` (dark field), and
    delta is one of :math:`2\pi m \pm \psi`. Walking along the path, each sample takes the
    candidate that is not below the previous value and is nearest the linear prediction
    from the two before it: a half fringe is counted each time psi turns back at 0 or pi,
    even when two samples straddle the turn.

    Examples
    --------
    >>> delta = np.linspace(0.1, 9.0, 200)
    >>> bool(np.allclose(unwrap_retardation(polariscope_intensity(delta)), delta))
    True
    """
    values = as_finite_array("intensity", intensity)
    if values.ndim == 0:
        raise ValueError("`intensity` must be a path (samples along the last axis), got 0-D")
    check_choice("field", field, _FIELDS)
    source_intensity = check_positive("source_intensity", source_intensity)
    tolerance = check_positive("tolerance", tolerance, allow_zero=True)
    root = np.sqrt(np.clip(values / source_intensity, 0.0, 1.0))
    folded = 2.0 * (np.arcsin(root) if field == "dark" else np.arccos(root))
    result = np.empty_like(folded)
    result[..., 0] = folded[..., 0]
    for k in range(1, folded.shape[-1]):
        previous, psi = result[..., k - 1], folded[..., k]
        slope = np.maximum(previous - result[..., k - 2], 0.0) if k > 1 else 0.0
        predicted = previous + slope
        turn = np.floor(previous / (2 * np.pi))
        best = np.full(previous.shape, np.inf)
        for m in (turn, turn + 1):
            for candidate in (2 * np.pi * m - psi, 2 * np.pi * m + psi):
                allowed = candidate >= previous - tolerance
                closer = np.abs(candidate - predicted) < np.abs(best - predicted)
                best = np.where(allowed & closer, candidate, best)
        result[..., k] = best
    return result


@dataclass(frozen=True)
class PhotoelasticFit:
    """Outcome of `fit_load_scale`.

    Attributes
    ----------
    load : float
        The best load parameter, in the unit of the model's scale.
    converged : bool
        Whether the local refinement met its tolerance.
    n_iterations : int
        Function evaluations of the refinement.
    residual : float
        Root-mean-square intensity misfit at `load`.
    message : str
        What happened, in words.
    """

    load: float
    converged: bool
    n_iterations: int
    residual: float
    message: str


def fit_load_scale(
    intensity: Any,
    unit_retardation: Any,
    *,
    max_load: float,
    field: str = "dark",
    source_intensity: float = 1.0,
) -> PhotoelasticFit:
    r"""Least-squares fit of one load parameter to a fringe map.

    Parameters
    ----------
    intensity : array_like
        Measured intensities (any shape).
    unit_retardation : array_like
        delta per unit load at the same pixels [rad per load unit]: stress fields are linear
        in the load, so delta(P) = P * unit_retardation.
    max_load : float
        Upper end of the search [load unit], > 0.
    field, source_intensity
        The polariscope, as in `polariscope_intensity`.

    Returns
    -------
    PhotoelasticFit
        The load minimising :math:`\sum (I_{model}(P) - I)^2`.

    Notes
    -----
    The misfit oscillates in P (every fringe is a local minimum), so a grid fine enough to
    move the fastest pixel by at most pi/8 per step finds the right valley first; bounded
    Brent refinement then polishes it.

    Examples
    --------
    >>> x = np.linspace(0.0, 1.0, 50)
    >>> unit = 2.0 + 30.0 * x**2  # rad per newton, say
    >>> fit = fit_load_scale(polariscope_intensity(0.37 * unit), unit, max_load=1.0)
    >>> fit.converged, round(fit.load, 6)
    (True, 0.37)
    """
    measured = as_finite_array("intensity", intensity)
    unit = as_finite_array("unit_retardation", unit_retardation)
    if measured.shape != unit.shape:
        raise ValueError(
            f"`unit_retardation` must have the shape of intensity {measured.shape}, "
            f"got {unit.shape}"
        )
    max_load = check_positive("max_load", max_load)
    check_choice("field", field, _FIELDS)
    source_intensity = check_positive("source_intensity", source_intensity)
    measured, unit = measured.ravel(), unit.ravel()

    def misfit(load: Any) -> Any:
        model = polariscope_intensity(
            np.multiply.outer(np.atleast_1d(load), unit),
            field=field,
            source_intensity=source_intensity,
        )
        return np.mean((model - measured) ** 2, axis=-1)

    fastest = float(np.max(np.abs(unit))) if unit.size else 0.0
    count = int(min(max(math.ceil(8.0 * fastest * max_load / np.pi), 16), 200_000)) + 1
    grid = np.linspace(0.0, max_load, count)
    values = np.concatenate([misfit(chunk) for chunk in np.array_split(grid, -(-count // 256))])
    best = int(np.argmin(values))
    step = grid[1] - grid[0]
    low, high = max(0.0, grid[best] - step), min(max_load, grid[best] + step)
    polished = optimize.minimize_scalar(
        lambda p: float(misfit(p)[0]),
        bounds=(low, high),
        method="bounded",
        options={"xatol": 1e-12 * max_load},
    )
    load = float(polished.x)
    return PhotoelasticFit(
        load=load,
        converged=bool(polished.success),
        n_iterations=int(polished.nfev),
        residual=float(np.sqrt(misfit(load)[0])),
        message=str(polished.message),
    )


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
        check_choice("field", self.field, _FIELDS)
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
