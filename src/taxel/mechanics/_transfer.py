r"""Fourier transfer functions of the cover: half-space and a layer bonded to a rigid base.

A normal surface pressure :math:`\hat p(\mathbf{q})` produces the surface displacement
:math:`\hat u = U(q)\,\hat p` and the strain at depth :math:`\hat\varepsilon_z = H(q)\,\hat p`,
with :math:`q = |\mathbf{q}|` [rad/m]. The same functions hold in plane strain (one
wavenumber) and in three dimensions (a normal load is axisymmetric in the wavevector plane).

The layer of thickness h is bonded to a rigid base at depth h and loaded by a normal
pressure with no shear at its top surface. Its transfer functions were derived from Navier's
equations with the general solution :math:`(A + Bz)e^{-qz} + (C + Dz)e^{q(z-h)}` and written
with decaying exponentials only, so they are stable for every q h.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_instance, check_positive
from taxel.mechanics._materials import ElasticMaterial

__all__ = [
    "halfspace_displacement_transfer",
    "halfspace_strain_transfer",
    "halfspace_stress_transfer",
    "layer_displacement_transfer",
    "layer_strain_transfer",
    "layer_stress_transfer",
]

# below this q h the layer formulas lose digits to cancellation; use the series instead
_SMALL_QH = 1e-4


def _wavenumber(q: Any) -> np.ndarray:
    q = as_finite_array("wavenumber", q)
    if np.any(q < 0):
        raise ValueError(f"`wavenumber` must be >= 0, got {float(np.min(q)):g}")
    return q


def halfspace_displacement_transfer(wavenumber: Any, material: ElasticMaterial) -> np.ndarray:
    r"""Surface displacement per unit pressure of a half-space, U(q) = 2 / (E* q) [m/Pa · m].

    Parameters
    ----------
    wavenumber : array_like
        q >= 0 [rad/m]. U is infinite at q = 0 (a uniform load on a half-space sinks
        without bound); callers choose what the mean displacement means.
    material : ElasticMaterial
        The half-space.

    Returns
    -------
    numpy.ndarray
        U(q) [m^3/N]: multiply the Fourier transform of the pressure by it.

    Examples
    --------
    >>> print(f"{float(halfspace_displacement_transfer(1e3, ElasticMaterial(1e6, 0.5))):.4e}")
    1.5000e-09
    """
    q = _wavenumber(wavenumber)
    check_instance("material", material, ElasticMaterial)
    with np.errstate(divide="ignore"):
        return 2.0 / (material.plane_strain_modulus * q)


def halfspace_strain_transfer(
    wavenumber: Any, depth: float, material: ElasticMaterial
) -> np.ndarray:
    r"""Strain eps_z at depth d per unit pressure of a half-space [1/Pa].

    Notes
    -----
    .. math:: H(q) = -\frac{1+\nu}{E}(1 - 2\nu + q d)\,e^{-q d}

    H(0) = -(1+nu)(1-2nu)/E is the strain under a uniform load; it vanishes for nu = 0.5,
    so an incompressible cover makes total force nearly unobservable from eps_z taxels.

    Examples
    --------
    >>> cover = ElasticMaterial(1e6, 0.5)
    >>> print(f"{float(halfspace_strain_transfer(0.0, 1e-3, cover)):.1f}")
    -0.0
    """
    q = _wavenumber(wavenumber)
    check_instance("material", material, ElasticMaterial)
    depth = check_positive("depth", depth)
    nu = material.poisson_ratio
    qd = q * depth
    return -(1 + nu) / material.youngs_modulus * (1 - 2 * nu + qd) * np.exp(-qd)


def halfspace_stress_transfer(wavenumber: Any, depth: float) -> np.ndarray:
    r"""Normal stress sigma_z at depth d per unit surface pressure of a half-space [-].

    Notes
    -----
    .. math:: S(q) = -(1 + q d)\,e^{-q d}

    independent of the material; S(0) = -1: a uniform load reaches every depth undiminished.

    Examples
    --------
    >>> float(halfspace_stress_transfer(0.0, 1e-3))
    -1.0
    """
    q = _wavenumber(wavenumber)
    depth = check_positive("depth", depth)
    qd = q * depth
    return -(1 + qd) * np.exp(-qd)


def _kappa(material: ElasticMaterial) -> float:
    """Kolosov's constant for plane strain, 3 - 4 nu."""
    return 3.0 - 4.0 * material.poisson_ratio


def _layer_denominator(t: np.ndarray, kappa: float) -> np.ndarray:
    """Denominator kappa (1 + e^{-4t}) + (4 t^2 + 1 + kappa^2) e^{-2t}, with t = q h."""
    decay = np.exp(-2.0 * t)
    return kappa * (1.0 + decay**2) + (4.0 * t**2 + 1.0 + kappa**2) * decay


def layer_displacement_transfer(
    wavenumber: Any, thickness: float, material: ElasticMaterial
) -> np.ndarray:
    r"""Surface displacement per unit pressure of a layer bonded to a rigid base [m^3/N].

    Parameters
    ----------
    wavenumber : array_like
        q >= 0 [rad/m].
    thickness : float
        Layer thickness h [m], > 0.
    material : ElasticMaterial
        The layer.

    Returns
    -------
    numpy.ndarray
        U(q) [m^3/N]; finite at q = 0, where it is the oedometric h / M.

    Notes
    -----
    With :math:`t = q h` and :math:`\kappa = 3 - 4\nu`,

    .. math:: U(q) = \frac{2}{E^* q}\,
              \frac{\kappa (1 - e^{-4t}) - 4 t e^{-2t}}
                   {\kappa (1 + e^{-4t}) + (4t^2 + 1 + \kappa^2) e^{-2t}}

    which tends to the half-space 2/(E* q) as h grows and to h/M (M the constrained
    modulus) as q h -> 0: a thin bonded layer cannot expand sideways.

    Examples
    --------
    >>> cover = ElasticMaterial(1e6, 0.3)
    >>> thin = layer_displacement_transfer(0.0, 1e-3, cover)
    >>> print(f"{float(thin):.6e} {1e-3 / cover.constrained_modulus:.6e}")
    7.428571e-10 7.428571e-10
    """
    q = _wavenumber(wavenumber)
    check_instance("material", material, ElasticMaterial)
    h = check_positive("thickness", thickness)
    kappa = _kappa(material)
    t = q * h
    small = t < _SMALL_QH
    safe_t = np.where(small, 1.0, t)
    decay = np.exp(-2.0 * safe_t)
    numerator = kappa * (1.0 - decay**2) - 4.0 * safe_t * decay
    ratio = numerator / _layer_denominator(safe_t, kappa)
    full = 2.0 * h / (material.plane_strain_modulus * safe_t) * ratio
    incompressible = material.poisson_ratio == 0.5
    oedometric = 0.0 if incompressible else h / material.constrained_modulus
    return np.where(small, oedometric, full)


def layer_strain_transfer(
    wavenumber: Any, depth: float, thickness: float, material: ElasticMaterial
) -> np.ndarray:
    r"""Strain eps_z at depth d per unit pressure in a layer bonded to a rigid base [1/Pa].

    Parameters
    ----------
    wavenumber : array_like
        q >= 0 [rad/m].
    depth : float
        Depth d of the sensing elements [m], 0 < d <= h.
    thickness : float
        Layer thickness h [m].
    material : ElasticMaterial
        The layer.

    Returns
    -------
    numpy.ndarray
        H(q) [1/Pa]; H(0) = -1/M, the oedometric strain.

    Notes
    -----
    With :math:`s = q d`, :math:`t = q h`, :math:`\kappa = 3 - 4\nu` and D the denominator of
    `layer_displacement_transfer`,

    .. math:: H = \frac{1+\nu}{E\,D}\Big[-\kappa(1-2\nu+s)e^{-s}
              + c_1 e^{-(2t-s)} + c_2 e^{-(2t+s)} + \kappa(s+2\nu-1)e^{-(4t-s)}\Big]

    .. math:: c_{1,2} = -8\nu^2 \pm 4\nu t + 14\nu + 2 s t \pm s - 2t^2 \mp 2t - 5

    Every exponent is <= 0 because d <= h. As h grows, H tends to the half-space
    :math:`-(1+\nu)(1-2\nu+s)e^{-s}/E`.

    Examples
    --------
    >>> cover = ElasticMaterial(1e6, 0.3)
    >>> value = layer_strain_transfer(0.0, 0.5e-3, 1e-3, cover)
    >>> print(f"{float(value):.6e} {-1 / cover.constrained_modulus:.6e}")
    -7.428571e-07 -7.428571e-07
    """
    q = _wavenumber(wavenumber)
    check_instance("material", material, ElasticMaterial)
    h = check_positive("thickness", thickness)
    d = check_positive("depth", depth)
    if d > h:
        raise ValueError(f"`depth` must be <= `thickness` ({h:g} m), got {d:g}")
    nu, kappa = material.poisson_ratio, _kappa(material)
    s, t = q * d, q * h
    c1 = -8 * nu**2 + 4 * nu * t + 14 * nu + 2 * s * t + s - 2 * t**2 - 2 * t - 5
    c2 = -8 * nu**2 - 4 * nu * t + 14 * nu + 2 * s * t - s - 2 * t**2 + 2 * t - 5
    bracket = (
        -kappa * (1 - 2 * nu + s) * np.exp(-s)
        + c1 * np.exp(-(2 * t - s))
        + c2 * np.exp(-(2 * t + s))
        + kappa * (s + 2 * nu - 1) * np.exp(-(4 * t - s))
    )
    return (1 + nu) / (material.youngs_modulus * _layer_denominator(t, kappa)) * bracket


def layer_stress_transfer(
    wavenumber: Any, depth: float, thickness: float, material: ElasticMaterial
) -> np.ndarray:
    r"""Normal stress sigma_z at depth d per unit pressure in a layer bonded to a rigid base [-].

    Parameters
    ----------
    wavenumber : array_like
        q >= 0 [rad/m].
    depth : float
        Depth d [m], 0 < d <= h.
    thickness : float
        Layer thickness h [m].
    material : ElasticMaterial
        The layer (only nu matters).

    Returns
    -------
    numpy.ndarray
        S(q) [-]; S(0) = -1.

    Notes
    -----
    With :math:`s = q d`, :math:`t = q h`, :math:`\kappa = 3 - 4\nu` and D the denominator of
    `layer_displacement_transfer`,

    .. math:: S = \frac{1}{D}\Big[-\kappa(1+s)e^{-s} + c_1 e^{-(2t-s)} + c_2 e^{-(2t+s)}
              + \kappa(s-1)e^{-(4t-s)}\Big]

    .. math:: c_{1,2} = -8\nu^2 + 12\nu + 2 s t \pm s - 2t^2 \mp 2t - 5

    Examples
    --------
    >>> cover = ElasticMaterial(1e6, 0.3)
    >>> print(f"{float(layer_stress_transfer(0.0, 0.5e-3, 1e-3, cover)):.6f}")
    -1.000000
    """
    q = _wavenumber(wavenumber)
    check_instance("material", material, ElasticMaterial)
    h = check_positive("thickness", thickness)
    d = check_positive("depth", depth)
    if d > h:
        raise ValueError(f"`depth` must be <= `thickness` ({h:g} m), got {d:g}")
    nu, kappa = material.poisson_ratio, _kappa(material)
    s, t = q * d, q * h
    c1 = -8 * nu**2 + 12 * nu + 2 * s * t + s - 2 * t**2 - 2 * t - 5
    c2 = -8 * nu**2 + 12 * nu + 2 * s * t - s - 2 * t**2 + 2 * t - 5
    bracket = (
        -kappa * (1 + s) * np.exp(-s)
        + c1 * np.exp(-(2 * t - s))
        + c2 * np.exp(-(2 * t + s))
        + kappa * (s - 1) * np.exp(-(4 * t - s))
    )
    return bracket / _layer_denominator(t, kappa)
