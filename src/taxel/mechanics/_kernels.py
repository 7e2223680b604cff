r"""Influence kernels of one grid cell: what a unit pressure on one cell does to every other.

Half-space kernels are exact cell integrals (Love's rectangle for displacement, the
rectangle strain formula at depth). A layer bonded to a rigid base is the half-space kernel
plus a correction, the Hankel transform of the difference of the transfer functions:

.. math:: \delta(r) = \frac{1}{2\pi}\int_0^\infty [T_{layer}(q) - T_{half}(q)]\,J_0(q r)\,q\,dq

The difference decays like :math:`e^{-q(2h-d)}`, so the correction is smooth at the cell
scale and is integrated over each cell with Gauss-Legendre points. Beyond 30 thicknesses a
bonded layer transmits nothing, so there the correction is minus the half-space kernel.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import cast

import numpy as np

from taxel.mechanics._boussinesq import (
    point_load_displacement,
    point_load_strain,
    point_load_stress,
    rectangle_displacement,
    rectangle_strain,
    rectangle_stress,
)
from taxel.mechanics._materials import ElasticMaterial
from taxel.mechanics._transfer import (
    halfspace_strain_transfer,
    halfspace_stress_transfer,
    layer_displacement_transfer,
    layer_strain_transfer,
    layer_stress_transfer,
)

__all__ = ["depth_kernel", "displacement_kernel"]

# a bonded layer's response has decayed to nothing this many thicknesses from the load
_LAYER_REACH = 30.0
# Gauss points per cell side: at least 4, and enough to resolve the correction's own scale
_MIN_GAUSS_POINTS = 4
_POINTS_PER_DECAY_LENGTH = 8.0
# A layer is modelled as the half-space plus a correction integrated over each cell: down to
# a twentieth of the cell (the kernel's sum under uniform pressure is then within 0.25 % of
# the confined compression h (1 + nu)(1 - 2 nu) / ((1 - nu) E) for nu <= 0.49). Thinner, the
# correction cancels the half-space kernel to rounding (an incompressible layer 1/60 of a
# cell thick gave a negative compliance, and so a negative contact force) and the
# quadrature's cost grows as (cell / thickness)^2: a finer grid is the answer.
_THINNEST_LAYER = 1.0 / 20.0  # [cell]


def offsets(count: int, step: float) -> np.ndarray:
    """Offsets -(count-1) .. (count-1) times step [m]."""
    return np.arange(-(count - 1), count) * step


def _hankel_table(
    q_times_difference: Callable[[np.ndarray], np.ndarray], decay_length: float, reach: float
) -> tuple[np.ndarray, np.ndarray]:
    """Tabulate delta(r) on [0, reach] given q (T_layer - T_half)(q), decaying over a length."""
    # scipy's integrate and special take about 0.4 s to import: only layered covers need them
    from scipy import integrate, special

    q_max = 20.0 / decay_length
    # resolve the oscillation of J0(q r) up to r = reach: dq * reach <= 0.2
    n_q = int(np.clip(q_max * reach / 0.2, 400, 40000)) | 1
    q = np.linspace(0.0, q_max, n_q)
    weights = q_times_difference(q) / (2.0 * np.pi)
    radii = np.linspace(0.0, reach, 1200)
    values = np.empty_like(radii)
    for start in range(0, radii.size, 200):  # chunks keep the J0 matrix small
        chunk = radii[start : start + 200]
        values[start : start + 200] = integrate.simpson(
            special.j0(np.outer(chunk, q)) * weights, x=q, axis=1
        )
    return radii, values


def _check_layer(thickness: float, dy: float, dx: float) -> None:
    """Raise when a layer is too thin for cells of dy x dx to model (see _THINNEST_LAYER)."""
    cell = max(dy, dx)
    if thickness < _THINNEST_LAYER * cell:
        raise ValueError(
            f"`thickness` must be at least 1/20 of the grid spacing ({cell:g} m) to be "
            f"modelled on this grid, got {thickness:g} m; use a finer grid"
        )


def _cell_average(
    table: tuple[np.ndarray, np.ndarray],
    far_field: Callable[[np.ndarray], np.ndarray],
    decay_length: float,
    dy: float,
    dx: float,
    y: np.ndarray,
    x: np.ndarray,
) -> np.ndarray:
    """Integrate the tabulated correction over each cell (Gauss-Legendre), per unit pressure."""
    count = max(
        _MIN_GAUSS_POINTS, int(np.ceil(_POINTS_PER_DECAY_LENGTH * max(dy, dx) / decay_length))
    )
    nodes, weights = np.polynomial.legendre.leggauss(count)
    radii, values = table
    total = np.zeros(np.broadcast_shapes(y.shape, x.shape))
    correction = np.empty_like(total)
    for node_y, weight_y in zip(nodes, weights, strict=True):
        for node_x, weight_x in zip(nodes, weights, strict=True):
            r = np.hypot(y + node_y * dy / 2, x + node_x * dx / 2)
            # the table within its reach, minus the far field beyond (each only where used)
            within = r <= radii[-1]
            correction[within] = np.interp(r[within], radii, values)
            beyond = ~within
            correction[beyond] = -far_field(r[beyond])
            total += weight_y * weight_x * correction
    return total * dx * dy / 4.0


def _by_symmetry(
    kernel_of: Callable[[np.ndarray, np.ndarray], np.ndarray], y: np.ndarray, x: np.ndarray
) -> np.ndarray:
    """``kernel_of(y, x)``, on offsets symmetric about 0 computed for y, x >= 0 and mirrored.

    A cell centred at 0 and a response that depends on the distance alone make every
    kernel even in y and in x: on the offsets -(n-1) .. (n-1) of a linear convolution
    (`y` a column, `x` a row) a quarter of the points gives them all, which a fine grid's
    kernels, seconds to a minute to build, need. Other offsets are computed as given.
    """
    column, row = np.ravel(y), np.ravel(x)
    symmetric = (
        np.shape(y) == (column.size, 1)
        and np.shape(x) == (1, row.size)
        and column.size % 2 == 1
        and row.size % 2 == 1
        and np.array_equal(column, -column[::-1])
        and np.array_equal(row, -row[::-1])
    )
    if not symmetric:
        return kernel_of(y, x)
    quadrant = kernel_of(y[column.size // 2 :], x[:, row.size // 2 :])
    half = np.concatenate([quadrant[:0:-1], quadrant], axis=0)
    return np.concatenate([half[:, :0:-1], half], axis=1)


def displacement_kernel(
    y: np.ndarray,
    x: np.ndarray,
    spacing: tuple[float, float],
    material: ElasticMaterial,
    *,
    thickness: float | None = None,
) -> np.ndarray:
    """Surface displacement at (y, x) per unit pressure on the cell centred at 0 [m/Pa]."""
    dy, dx = spacing
    if thickness is not None:
        _check_layer(thickness, dy, dx)

    def at(y: np.ndarray, x: np.ndarray) -> np.ndarray:
        halfspace = rectangle_displacement(x, y, dx / 2, dy / 2, material)
        if thickness is None:
            return halfspace
        reach = _LAYER_REACH * thickness
        # q U_half(q) = 2/E* exactly, so q (U_layer - U_half) is finite at q = 0
        table = _hankel_table(
            lambda q: q * layer_displacement_transfer(q, thickness, material)
            - 2.0 / material.plane_strain_modulus,
            2.0 * thickness,
            reach,
        )

        def far(r: np.ndarray) -> np.ndarray:
            return point_load_displacement(r, 0.0, 1.0, material)

        return halfspace + _cell_average(table, far, 2.0 * thickness, dy, dx, y, x)

    return _by_symmetry(at, y, x)


def _strain_parts(depth: float, material: ElasticMaterial, thickness: float | None):
    """Half-space cell kernel, transfer difference and point-load far field of eps_z.

    `thickness` is None for a half-space; the transfer difference is then never called.
    """
    return (
        lambda x, y, bounds: rectangle_strain(x, y, bounds, depth, material),
        lambda q: layer_strain_transfer(q, depth, cast(float, thickness), material)
        - halfspace_strain_transfer(q, depth, material),
        lambda r: point_load_strain(r, depth, 1.0, material),
    )


def _stress_parts(depth: float, material: ElasticMaterial, thickness: float | None):
    """Half-space cell kernel, transfer difference and point-load far field of sigma_z.

    `thickness` is None for a half-space; the transfer difference is then never called.
    """
    return (
        lambda x, y, bounds: rectangle_stress(x, y, bounds, depth),
        lambda q: layer_stress_transfer(q, depth, cast(float, thickness), material)
        - halfspace_stress_transfer(q, depth),
        lambda r: point_load_stress(r, depth, 1.0),
    )


_DEPTH_QUANTITIES = {"strain": _strain_parts, "stress": _stress_parts}


def depth_kernel(
    quantity: str,
    y: np.ndarray,
    x: np.ndarray,
    spacing: tuple[float, float],
    depth: float,
    material: ElasticMaterial,
    *,
    thickness: float | None = None,
) -> np.ndarray:
    """eps_z [1/Pa] or sigma_z [-] at depth under (y, x) per unit pressure on the cell at 0."""
    dy, dx = spacing
    halfspace_cell, difference, far = _DEPTH_QUANTITIES[quantity](depth, material, thickness)
    if thickness is not None:
        _check_layer(thickness, dy, dx)

    def at(y: np.ndarray, x: np.ndarray) -> np.ndarray:
        halfspace = halfspace_cell(x, y, (-dx / 2, dx / 2, -dy / 2, dy / 2))
        if thickness is None:
            return halfspace
        decay = 2.0 * thickness - depth
        table = _hankel_table(lambda q: q * difference(q), decay, _LAYER_REACH * thickness)
        return halfspace + _cell_average(table, far, decay, dy, dx, y, x)

    return _by_symmetry(at, y, x)
