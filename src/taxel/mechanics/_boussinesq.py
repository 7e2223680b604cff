r"""Three-dimensional half-space closed forms: Boussinesq's point load and loaded rectangles.

The uniformly loaded rectangle gives the strain at depth and (Love) the surface displacement.

Conventions as in the rest of `taxel.mechanics`: depth and displacement are positive into
the layer, compressive load positive, strain positive in tension. Sources: K. L. Johnson,
*Contact Mechanics* (1985), section 3.2; Love (1929) for the rectangle.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel._validation import (
    as_finite_array,
    check_broadcast,
    check_finite,
    check_instance,
    check_positive,
)
from taxel.mechanics._materials import ElasticMaterial

__all__ = [
    "point_load_displacement",
    "point_load_strain",
    "point_load_stress",
    "rectangle_displacement",
    "rectangle_strain",
    "rectangle_stress",
]


def point_load_displacement(
    radius: Any, depth: Any, normal_force: float, material: ElasticMaterial
) -> np.ndarray:
    r"""Vertical displacement under a point load on a half-space (Boussinesq) [m].

    Parameters
    ----------
    radius : array_like
        Horizontal distance r from the load [m].
    depth : array_like
        Depth z below the surface [m], >= 0; 0 gives the surface displacement.
    normal_force : float
        The point load P [N], positive pushing into the half-space.
    material : ElasticMaterial
        The half-space.

    Returns
    -------
    numpy.ndarray
        u_z [m], positive into the half-space; inf at the load point itself.

    Notes
    -----
    .. math:: u_z = \frac{P (1+\nu)}{2 \pi E}\left[\frac{2(1-\nu)}{\rho}
              + \frac{z^2}{\rho^3}\right], \qquad \rho^2 = r^2 + z^2

    which at the surface is :math:`P (1-\nu^2)/(\pi E r)`.

    Examples
    --------
    >>> cover = ElasticMaterial(1e6, 0.5)
    >>> print(f"{float(point_load_displacement(1e-3, 0.0, 1.0, cover)):.6e}")
    2.387324e-04
    """
    radius = np.abs(as_finite_array("radius", radius))
    depth = as_finite_array("depth", depth)
    check_broadcast(("radius", "depth"), radius, depth)
    if np.any(depth < 0):
        raise ValueError(f"`depth` must be >= 0, got {float(np.min(depth)):g}")
    force = check_finite("normal_force", normal_force)
    check_instance("material", material, ElasticMaterial)
    nu, modulus = material.poisson_ratio, material.youngs_modulus
    rho = np.hypot(radius, depth)
    with np.errstate(divide="ignore", invalid="ignore"):
        value = force * (1 + nu) / (2 * np.pi * modulus) * (2 * (1 - nu) / rho + depth**2 / rho**3)
    return np.where(rho > 0, value, np.inf)


def point_load_stress(radius: Any, depth: Any, normal_force: float) -> np.ndarray:
    r"""Normal stress sigma_z under a point load on a half-space (Boussinesq) [Pa].

    Independent of the material. Negative (compressive) for a load pushing in.

    Notes
    -----
    .. math:: \sigma_z = -\frac{3 P z^3}{2 \pi \rho^5}

    Examples
    --------
    >>> print(f"{float(point_load_stress(0.0, 1e-3, 1.0)):.6e}")
    -4.774648e+05
    """
    radius = np.abs(as_finite_array("radius", radius))
    depth = as_finite_array("depth", depth)
    check_broadcast(("radius", "depth"), radius, depth)
    if np.any(depth <= 0):
        raise ValueError(f"`depth` must be > 0, got {float(np.min(depth)):g}")
    force = check_finite("normal_force", normal_force)
    rho = np.hypot(radius, depth)
    return -3.0 * force * depth**3 / (2.0 * np.pi * rho**5)


def point_load_strain(
    radius: Any, depth: float, normal_force: float, material: ElasticMaterial
) -> np.ndarray:
    r"""Normal strain eps_z at depth d under a point load on a half-space [-].

    Parameters
    ----------
    radius : array_like
        Horizontal distance from the load [m].
    depth : float
        Depth d of the sensing elements [m], > 0.
    normal_force : float
        Point load P [N].
    material : ElasticMaterial
        The half-space.

    Returns
    -------
    numpy.ndarray
        eps_z [-], negative (compressed) under the load.

    Notes
    -----
    .. math:: \varepsilon_z(r, d) = \frac{P(1+\nu)}{2\pi E}
              \left[\frac{2\nu d}{\rho^3} - \frac{3 d^3}{\rho^5}\right]

    On the axis this is :math:`-P(1+\nu)(3-2\nu)/(2\pi E d^2)`.

    Examples
    --------
    >>> cover = ElasticMaterial(1e6, 0.5)
    >>> print(f"{float(point_load_strain(0.0, 1e-3, 1.0, cover)):.6e}")
    -4.774648e-01
    """
    radius = as_finite_array("radius", radius)
    depth = check_positive("depth", depth)
    force = check_finite("normal_force", normal_force)
    check_instance("material", material, ElasticMaterial)
    nu, modulus = material.poisson_ratio, material.youngs_modulus
    rho = np.hypot(radius, depth)
    return (
        force
        * (1 + nu)
        / (2 * np.pi * modulus)
        * (2 * nu * depth / rho**3 - 3 * depth**3 / rho**5)
    )


def _bounds(bounds: Any) -> tuple[float, float, float, float]:
    """The rectangle (x1, x2, y1, y2) [m] as finite floats, or raise naming `bounds`."""
    try:
        values = tuple(bounds)
    except TypeError:
        raise TypeError(f"`bounds` must be (x1, x2, y1, y2), got {bounds!r}") from None
    if len(values) != 4:
        raise ValueError(f"`bounds` must be (x1, x2, y1, y2), got {bounds!r}")
    x1, x2, y1, y2 = (check_finite("bounds", value) for value in values)
    return x1, x2, y1, y2


def _rectangle_strain_corner(x: np.ndarray, y: np.ndarray, depth: float, nu: float) -> np.ndarray:
    """F(X, Y) of the rectangle formula: the corner term of the strain integral."""
    big_r = np.sqrt(x**2 + y**2 + depth**2)
    return (2 * nu - 1) * np.arctan2(x * y, depth * big_r) - (x * y * depth / big_r) * (
        1.0 / (x**2 + depth**2) + 1.0 / (y**2 + depth**2)
    )


def rectangle_strain(
    x: Any,
    y: Any,
    bounds: tuple[float, float, float, float],
    depth: float,
    material: ElasticMaterial,
    *,
    pressure: float = 1.0,
) -> np.ndarray:
    r"""Strain eps_z at depth d under a uniformly loaded rectangle on a half-space [-].

    Parameters
    ----------
    x, y : array_like
        Horizontal position of the field points [m] (broadcast together).
    bounds : tuple of float
        The loaded rectangle (x1, x2, y1, y2) [m], x1 < x2, y1 < y2.
    depth : float
        Depth d of the field points [m], > 0.
    material : ElasticMaterial
        The half-space.
    pressure : float, default 1.0
        Uniform pressure p on the rectangle [Pa]; the default gives strain per pascal.

    Returns
    -------
    numpy.ndarray
        eps_z [-]: the exact integral of `point_load_strain` over the rectangle.

    Notes
    -----
    .. math:: \varepsilon_z = \frac{p (1+\nu)}{2\pi E}\left[F(x-x_1, y-y_1) - F(x-x_2, y-y_1)
              - F(x-x_1, y-y_2) + F(x-x_2, y-y_2)\right]

    with :math:`F(X, Y) = (2\nu-1)\,\mathrm{atan2}(XY, dR) - \frac{XYd}{R}\left[\frac{1}{X^2+d^2}
    + \frac{1}{Y^2+d^2}\right]` and :math:`R^2 = X^2 + Y^2 + d^2`. This is the influence
    coefficient of one taxel-sized load element, used instead of point collocation.

    Examples
    --------
    >>> cover = ElasticMaterial(1e6, 0.3)
    >>> huge = (-1.0, 1.0, -1.0, 1.0)  # tends to -(1+nu)(1-2nu)/E per Pa
    >>> print(f"{float(rectangle_strain(0.0, 0.0, huge, 1e-3, cover)):.4e}")
    -5.2070e-07
    """
    x = as_finite_array("x", x)
    y = as_finite_array("y", y)
    check_broadcast(("x", "y"), x, y)
    x1, x2, y1, y2 = _bounds(bounds)
    if not (x1 < x2 and y1 < y2):
        raise ValueError(f"`bounds` must satisfy x1 < x2 and y1 < y2, got {bounds}")
    depth = check_positive("depth", depth)
    pressure = check_finite("pressure", pressure)
    check_instance("material", material, ElasticMaterial)
    nu = material.poisson_ratio
    corner = _rectangle_strain_corner
    total = (
        corner(x - x1, y - y1, depth, nu)
        - corner(x - x2, y - y1, depth, nu)
        - corner(x - x1, y - y2, depth, nu)
        + corner(x - x2, y - y2, depth, nu)
    )
    return pressure * (1 + nu) / (2 * np.pi * material.youngs_modulus) * total


def _rectangle_stress_corner(x: np.ndarray, y: np.ndarray, depth: float) -> np.ndarray:
    """Corner term of the rectangle stress integral."""
    big_r = np.sqrt(x**2 + y**2 + depth**2)
    return np.arctan2(x * y, depth * big_r) + (x * y * depth / big_r) * (
        1.0 / (x**2 + depth**2) + 1.0 / (y**2 + depth**2)
    )


def rectangle_stress(
    x: Any,
    y: Any,
    bounds: tuple[float, float, float, float],
    depth: float,
    *,
    pressure: float = 1.0,
) -> np.ndarray:
    r"""Normal stress sigma_z at depth d under a uniformly loaded rectangle on a half-space [Pa].

    Independent of the material. This is what a stress-sensing cell (a piezoresistive or
    piezoelectric element, or the dielectric of a capacitive cell) under the cover feels.

    Parameters
    ----------
    x, y : array_like
        Horizontal position of the field points [m].
    bounds : tuple of float
        The loaded rectangle (x1, x2, y1, y2) [m].
    depth : float
        Depth d [m], > 0.
    pressure : float, default 1.0
        Uniform pressure on the rectangle [Pa].

    Returns
    -------
    numpy.ndarray
        sigma_z [Pa], negative (compressive) under a pressing load.

    Notes
    -----
    The integral of Boussinesq's :math:`-3 P z^3 / (2\pi\rho^5)` over the rectangle:

    .. math:: \sigma_z = -\frac{p}{2\pi}\left[S(x-x_1, y-y_1) - S(x-x_2, y-y_1)
              - S(x-x_1, y-y_2) + S(x-x_2, y-y_2)\right]

    with :math:`S(X, Y) = \mathrm{atan2}(XY, dR) + \frac{XYd}{R}\left[\frac{1}{X^2+d^2}
    + \frac{1}{Y^2+d^2}\right]` (the classical Holl/Newmark corner formula).

    Examples
    --------
    >>> huge = (-1.0, 1.0, -1.0, 1.0)  # a uniform load is transmitted undiminished
    >>> print(f"{float(rectangle_stress(0.0, 0.0, huge, 1e-3)):.6f}")
    -1.000000
    """
    x = as_finite_array("x", x)
    y = as_finite_array("y", y)
    check_broadcast(("x", "y"), x, y)
    x1, x2, y1, y2 = _bounds(bounds)
    if not (x1 < x2 and y1 < y2):
        raise ValueError(f"`bounds` must satisfy x1 < x2 and y1 < y2, got {bounds}")
    depth = check_positive("depth", depth)
    pressure = check_finite("pressure", pressure)
    corner = _rectangle_stress_corner
    total = (
        corner(x - x1, y - y1, depth)
        - corner(x - x2, y - y1, depth)
        - corner(x - x1, y - y2, depth)
        + corner(x - x2, y - y2, depth)
    )
    return -pressure / (2 * np.pi) * total


def _log_x_plus_hypot(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """ln(x + sqrt(x^2 + y^2)) without cancellation for x < 0 (y != 0)."""
    r = np.hypot(x, y)
    positive = x >= 0
    with np.errstate(divide="ignore"):
        direct = np.log(np.where(positive, x + r, 1.0))
        # x + r = y^2 / (r - x) for x < 0
        rewritten = 2 * np.log(np.abs(y)) - np.log(np.where(positive, 1.0, r - x))
    return np.where(positive, direct, rewritten)


def _love_corner(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """t(X, Y) = X ln(Y + r) + Y ln(X + r), with 0 ln 0 -> 0 on edges and corners."""
    with np.errstate(invalid="ignore"):
        first = np.where(x == 0, 0.0, x * _log_x_plus_hypot(y, x))
        second = np.where(y == 0, 0.0, y * _log_x_plus_hypot(x, y))
    return first + second


def rectangle_displacement(
    x: Any,
    y: Any,
    half_width: float,
    half_height: float,
    material: ElasticMaterial,
    *,
    pressure: float = 1.0,
) -> np.ndarray:
    r"""Surface displacement of a half-space under a uniformly loaded rectangle (Love) [m].

    Parameters
    ----------
    x, y : array_like
        Surface position relative to the rectangle's centre [m].
    half_width, half_height : float
        Half-sizes a (along x) and b (along y) of the rectangle [m], > 0.
    material : ElasticMaterial
        The half-space.
    pressure : float, default 1.0
        Uniform pressure [Pa]; the default gives displacement per pascal.

    Returns
    -------
    numpy.ndarray
        u_z [m], positive into the half-space. Finite everywhere, including edges and corners.

    Notes
    -----
    .. math:: u_z = \frac{(1-\nu^2) p}{\pi E}\left[t(x+a, y+b) - t(x+a, y-b)
              - t(x-a, y+b) + t(x-a, y-b)\right]

    with :math:`t(X, Y) = X \ln(Y + r) + Y \ln(X + r)`, :math:`r^2 = X^2 + Y^2`. The
    logarithms are evaluated without cancellation, and :math:`0 \ln 0 = 0`.

    Examples
    --------
    >>> cover = ElasticMaterial(1e6, 0.5)
    >>> centre = rectangle_displacement(0.0, 0.0, 1e-3, 1e-3, cover)
    >>> corner = rectangle_displacement(1e-3, 1e-3, 1e-3, 1e-3, cover)
    >>> print(f"{float(corner / centre):.12f}")  # exactly one half for a square
    0.500000000000
    """
    x = as_finite_array("x", x)
    y = as_finite_array("y", y)
    check_broadcast(("x", "y"), x, y)
    a = check_positive("half_width", half_width)
    b = check_positive("half_height", half_height)
    pressure = check_finite("pressure", pressure)
    check_instance("material", material, ElasticMaterial)
    t = _love_corner
    total = t(x + a, y + b) - t(x + a, y - b) - t(x - a, y + b) + t(x - a, y - b)
    return (1 - material.poisson_ratio**2) * pressure / (np.pi * material.youngs_modulus) * total
