"""The chapter's one-dimensional (plane strain) model of the cover, eqs. 25.1-25.5.

A line load on an elastic half-space (Flamant's problem) gives, at depth d under the
surface, the normal strain h_z (eq. 25.2), and at the surface the displacement k
(eq. 25.4). Discretising eq. 25.1 with a piecewise-constant load gives zeta = T F
(eq. 25.5); the entries of T here are the exact integrals of h_z over each load element,
because point collocation errs by 20-28 % when the pitch equals the depth.

Sign convention: z points into the layer, a compressive load is positive and strain is
positive in tension, so a taxel under a load reads a negative strain.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel._validation import (
    as_finite_array,
    check_broadcast,
    check_choice,
    check_instance,
    check_positive,
)
from taxel.mechanics._materials import ElasticMaterial

__all__ = [
    "line_load_displacement",
    "line_load_strain",
    "plane_strain_displacement_matrix",
    "plane_strain_strain_matrix",
    "strip_load_strain",
]

_DIRECTIONS = ("normal", "tangential")


def line_load_strain(
    x: Any, depth: float, material: ElasticMaterial, *, direction: str = "normal"
) -> np.ndarray:
    r"""Normal strain eps_z at depth d per unit line load, h_z of eq. 25.2 [1/(N/m)].

    Parameters
    ----------
    x : array_like
        Horizontal offset between the field point and the load [m].
    depth : float
        Depth d of the sensing elements [m], > 0.
    material : ElasticMaterial
        The cover.
    direction : {'normal', 'tangential'}
        A normal line load (pushing into the layer) or a tangential one (acting along +x).

    Returns
    -------
    numpy.ndarray
        Strain per unit load [m/N]; multiply by the load P [N/m] to get eps_z [-].

    Notes
    -----
    Normal load (eq. 25.2 of the seed chapter; the printed "pi r E" is pi E):

    .. math:: h_z(x) = -\frac{2 d (1+\nu) [d^2 (1-\nu) - \nu x^2]}{\pi E (x^2+d^2)^2}

    Tangential load Q along +x (Flamant, Johnson eq. 2.19, plane strain Hooke's law):

    .. math:: h_x(x) = -\frac{2 x (1+\nu) [d^2 (1-\nu) - \nu x^2]}{\pi E (x^2+d^2)^2}

    Examples
    --------
    >>> from taxel.mechanics import ElasticMaterial
    >>> cover = ElasticMaterial(1e6, 0.3)
    >>> float(100 * line_load_strain(0.0, 2e-3, cover))  # P = 100 N/m
    -0.028966199...
    """
    x = as_finite_array("x", x)
    depth = check_positive("depth", depth)
    check_instance("material", material, ElasticMaterial)
    check_choice("direction", direction, _DIRECTIONS)
    nu, modulus = material.poisson_ratio, material.youngs_modulus
    lever = depth if direction == "normal" else x
    return (
        -2.0
        * lever
        * (1.0 + nu)
        * (depth**2 * (1.0 - nu) - nu * x**2)
        / (np.pi * modulus * (x**2 + depth**2) ** 2)
    )


def _strain_antiderivative(
    s: np.ndarray, depth: float, material: ElasticMaterial, direction: str
) -> np.ndarray:
    """G(s) with dG/ds = line_load_strain(s): the element integral is a difference of G."""
    nu, modulus = material.poisson_ratio, material.youngs_modulus
    scale = (1.0 + nu) / (np.pi * modulus)
    if direction == "normal":
        return -scale * (depth * s / (s**2 + depth**2) + (1.0 - 2.0 * nu) * np.arctan(s / depth))
    return scale * (depth**2 / (s**2 + depth**2) + nu * np.log1p((s / depth) ** 2))


def strip_load_strain(
    x: Any,
    depth: float,
    width: Any,
    material: ElasticMaterial,
    *,
    direction: str = "normal",
) -> np.ndarray:
    r"""Strain eps_z at depth d under a uniform unit pressure on a strip of given width [1/Pa].

    Parameters
    ----------
    x : array_like
        Offset of the field point from the strip's centre [m].
    depth : float
        Depth of the sensing elements [m], > 0.
    width : float or array_like
        Width of the loaded strip [m], > 0 (broadcasts against `x`).
    material : ElasticMaterial
        The cover.
    direction : {'normal', 'tangential'}
        Direction of the surface traction.

    Returns
    -------
    numpy.ndarray
        eps_z per unit pressure [1/Pa]: the exact integral of `line_load_strain` over the strip.

    Notes
    -----
    With the antiderivatives

    .. math:: G_z(s) = -\frac{1+\nu}{\pi E}\left[\frac{d s}{s^2+d^2}
              + (1-2\nu)\arctan\frac{s}{d}\right],\qquad
              G_x(s) = \frac{1+\nu}{\pi E}\left[\frac{d^2}{s^2+d^2}
              + \nu \ln\left(1 + \frac{s^2}{d^2}\right)\right]

    a strip of width w centred at 0 gives eps_z(x) = p [G(x + w/2) - G(x - w/2)].

    Examples
    --------
    >>> from taxel.mechanics import ElasticMaterial
    >>> cover = ElasticMaterial(1e6, 0.3)
    >>> # a strip much wider than the depth tends to -(1+nu)(1-2nu)/E = -5.2e-07 per Pa
    >>> print(f"{float(strip_load_strain(0.0, 1e-3, 1.0, cover)):.4e}")
    -5.2099e-07
    """
    x = as_finite_array("x", x)
    depth = check_positive("depth", depth)
    width = as_finite_array("width", width)
    if np.any(width <= 0):
        raise ValueError(f"`width` must be > 0, got {float(np.min(width)):g}")
    check_broadcast(("x", "width"), x, width)
    check_instance("material", material, ElasticMaterial)
    check_choice("direction", direction, _DIRECTIONS)
    upper = _strain_antiderivative(x + width / 2, depth, material, direction)
    lower = _strain_antiderivative(x - width / 2, depth, material, direction)
    return upper - lower


def line_load_displacement(
    x: Any, material: ElasticMaterial, *, reference_distance: float = 1.0
) -> np.ndarray:
    r"""Surface displacement per unit line load, k of eq. 25.4 [m/(N/m)].

    Parameters
    ----------
    x : array_like
        Offset from the load [m]; x = 0 is the logarithmic singularity and gives inf.
    material : ElasticMaterial
        The cover.
    reference_distance : float, default 1.0
        x_a of eq. 25.4 [m], where the displacement is taken as zero. In plane strain only
        differences of displacement are defined: x_a shifts every value by a constant.

    Returns
    -------
    numpy.ndarray
        Displacement into the layer per unit load [m^2/N].

    Notes
    -----
    .. math:: k(x) = -\frac{2 (1-\nu^2)}{\pi E} \ln\left|\frac{x}{x_a}\right|

    Examples
    --------
    >>> from taxel.mechanics import ElasticMaterial
    >>> cover = ElasticMaterial(1e6, 0.0)
    >>> float(line_load_displacement(1.0, cover))  # zero at x = x_a
    -0.0
    """
    x = np.abs(as_finite_array("x", x))
    reference_distance = check_positive("reference_distance", reference_distance)
    check_instance("material", material, ElasticMaterial)
    scale = -2.0 * (1.0 - material.poisson_ratio**2) / (np.pi * material.youngs_modulus)
    with np.errstate(divide="ignore"):
        return scale * np.log(x / reference_distance)


def _displacement_antiderivative(
    s: np.ndarray, material: ElasticMaterial, reference_distance: float
) -> np.ndarray:
    """K(s) with dK/ds = k(s), taking s ln|s| -> 0 at s = 0."""
    scale = -2.0 * (1.0 - material.poisson_ratio**2) / (np.pi * material.youngs_modulus)
    magnitude = np.abs(s)
    safe = np.where(magnitude > 0, magnitude, 1.0)
    s_log_s = np.where(magnitude > 0, s * np.log(safe / reference_distance), 0.0)
    return scale * (s_log_s - s)


def _element_matrix(
    taxel_positions: Any, load_positions: Any, load_width: Any
) -> tuple[np.ndarray, np.ndarray]:
    """Validate positions and widths; return offsets x_i - x_j and widths broadcast to them."""
    taxels = as_finite_array("taxel_positions", taxel_positions, ndim=1)
    loads = as_finite_array("load_positions", load_positions, ndim=1)
    widths = as_finite_array("load_width", load_width)
    if widths.ndim > 1 or widths.size not in (1, loads.size):
        raise ValueError(
            f"`load_width` must be a number or one per load position ({loads.size}), "
            f"got shape {widths.shape}"
        )
    widths = np.broadcast_to(widths, loads.shape)
    if np.any(widths <= 0):
        raise ValueError(f"`load_width` must be > 0, got {float(np.min(widths)):g}")
    return taxels[:, None] - loads[None, :], widths[None, :]


def plane_strain_strain_matrix(
    taxel_positions: Any,
    load_positions: Any,
    load_width: Any,
    depth: float,
    material: ElasticMaterial,
    *,
    direction: str = "normal",
) -> np.ndarray:
    """The matrix T of zeta = T F (eq. 25.5) with element-integrated entries [1/Pa].

    Parameters
    ----------
    taxel_positions : array_like, shape (n,)
        x of the sensing elements at depth d [m].
    load_positions : array_like, shape (m,)
        Centres of the load elements on the surface [m]; need not match the taxels.
    load_width : float or array_like, shape (m,)
        Width of each load element [m] (usually the load-grid pitch dx_q).
    depth : float
        Depth d of the sensing elements [m].
    material : ElasticMaterial
        The cover.
    direction : {'normal', 'tangential'}
        Which traction component F holds.

    Returns
    -------
    numpy.ndarray, shape (n, m)
        T_ij = eps_z at taxel i per unit pressure [Pa] on load element j. Not square when
        the load grid differs from the taxel grid.

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.mechanics import ElasticMaterial
    >>> taxels = np.arange(4) * 1e-3
    >>> loads = np.arange(8) * 0.5e-3
    >>> T = plane_strain_strain_matrix(taxels, loads, 0.5e-3, 1e-3, ElasticMaterial(1e6, 0.5))
    >>> T.shape
    (4, 8)
    """
    offsets, widths = _element_matrix(taxel_positions, load_positions, load_width)
    return strip_load_strain(offsets, depth, widths, material, direction=direction)


def plane_strain_displacement_matrix(
    surface_positions: Any,
    load_positions: Any,
    load_width: Any,
    material: ElasticMaterial,
    *,
    reference_distance: float = 1.0,
) -> np.ndarray:
    """Surface displacement per unit pressure on each load element, eq. 25.3 discretised [m/Pa].

    Parameters
    ----------
    surface_positions : array_like, shape (n,)
        Points on the surface where displacement is wanted [m].
    load_positions : array_like, shape (m,)
        Centres of the load elements [m].
    load_width : float or array_like, shape (m,)
        Width of each load element [m].
    material : ElasticMaterial
        The cover.
    reference_distance : float, default 1.0
        x_a of eq. 25.4 [m] (only differences of displacement are meaningful).

    Returns
    -------
    numpy.ndarray, shape (n, m)
        D_ij = exact integral of k over load element j, seen from point i [m/Pa].

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.mechanics import ElasticMaterial
    >>> x = np.arange(3) * 1e-3
    >>> D = plane_strain_displacement_matrix(x, x, 1e-3, ElasticMaterial(1e6, 0.5))
    >>> bool(D[0, 0] > D[0, 1] > D[0, 2])  # displacement falls off away from the load
    True
    """
    offsets, widths = _element_matrix(surface_positions, load_positions, load_width)
    reference_distance = check_positive("reference_distance", reference_distance)
    check_instance("material", material, ElasticMaterial)
    upper = _displacement_antiderivative(offsets + widths / 2, material, reference_distance)
    lower = _displacement_antiderivative(offsets - widths / 2, material, reference_distance)
    return upper - lower
