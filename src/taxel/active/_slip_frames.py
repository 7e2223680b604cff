"""Frames of a hold-then-slip contact: sigma_z at the sensing depth from pressure and traction.

The normal stress the sensing elements feel is the sensor's own cover operator applied to
the surface pressure plus, for the tangential traction q along a direction, Cerruti's
point-force solution for a half-space, sigma_z = -3 Q x d^2 / (2 pi rho^5) (compression ahead
of the force), integrated over each load-grid cell. Both are linear: they are turned once
into dense (cells x taxels) matrices, so a whole sequence costs two matrix products.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy import ndimage

from taxel.mechanics import depth_stress_operator
from taxel.sensor import TactileSensor

__all__ = ["sensed_stress"]


@lru_cache(maxsize=4)
def _cerruti_kernels(sensor: TactileSensor) -> tuple[np.ndarray, np.ndarray]:
    """sigma_z at the sensing depth per unit traction on a cell, along x and along y."""
    grid = sensor.load_grid
    dy, dx = grid.spacing
    rows, cols = grid.shape
    depth = sensor.cover.depth
    sub = (np.arange(4) + 0.5) / 4 - 0.5  # 4 x 4 points per cell
    oy, ox = np.meshgrid(np.arange(-rows + 1, rows) * dy, np.arange(-cols + 1, cols) * dx)
    kx, ky = np.zeros(oy.T.shape), np.zeros(oy.T.shape)
    for sy in sub * dy:
        for sx in sub * dx:
            px, py = (ox + sx).T, (oy + sy).T
            rho5 = (px**2 + py**2 + depth**2) ** 2.5
            kx += -3 * px * depth**2 / (2 * np.pi * rho5) / 16
            ky += -3 * py * depth**2 / (2 * np.pi * rho5) / 16
    return kx * dx * dy, ky * dx * dy


def _block_map(kernel: np.ndarray, sensor: TactileSensor) -> np.ndarray:
    """(cells, taxels) matrix of a linear convolution kernel followed by taxel means.

    `kernel` holds K(x_i - x_j) on offsets -(n-1)..(n-1); the response at cell i to a unit
    load on every cell j is K[i - j], a flipped window of the kernel.
    """
    grid = sensor.load_grid
    rows, cols = grid.shape
    block_rows, block_cols = rows // sensor.shape[0], cols // sensor.shape[1]
    result = np.zeros((sensor.shape[0], sensor.shape[1], rows, cols))
    for row in range(rows):
        for col in range(cols):
            window = kernel[row : row + rows, col : col + cols][::-1, ::-1]
            result[row // block_rows, col // block_cols] += window
    result /= block_rows * block_cols
    return result.reshape(sensor.shape[0] * sensor.shape[1], rows * cols).T


@lru_cache(maxsize=4)
def _taxel_operators(sensor: TactileSensor) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Dense maps from load-grid cells to sigma_z per taxel: pressure, traction x, traction y."""
    grid, cover = sensor.load_grid, sensor.cover
    operator = depth_stress_operator(
        grid.shape, grid.spacing, cover.depth, cover.material, thickness=cover.thickness
    )
    kx, ky = _cerruti_kernels(sensor)
    assert operator.kernel is not None  # a zero-padded operator keeps its real-space kernel
    return (
        _block_map(operator.kernel, sensor),
        _block_map(kx, sensor),
        _block_map(ky, sensor),
    )


def sensed_stress(
    sensor: TactileSensor,
    master: np.ndarray,
    spacing: float,
    kinematics: dict,
    offsets: np.ndarray,
    normal_force: float,
    direction: float,
) -> np.ndarray:
    """sigma_z at the sensing depth, per taxel and frame [Pa] (< 0 in compression).

    `master` is the contact pressure on a fine grid of `spacing` [m], re-sampled at each
    frame's pattern `offsets` (n_frames, 2) [m] and scaled to the frame's normal force;
    `kinematics` gives the stick ratio c/a (for the Ciavarella-Jager traction), the
    friction coefficient and the force jitter of each frame; `direction` [rad] is the
    direction of the tangential load in the sensor frame.
    """
    grid = sensor.load_grid
    x, y = grid.coordinates()
    centre = (master.shape[0] - 1) / 2
    cell = grid.spacing[0] * grid.spacing[1]
    n_frames = offsets.shape[0]
    pressure: np.ndarray = np.empty((n_frames, *grid.shape))
    traction = np.empty_like(pressure)
    for k in range(n_frames):
        u, v = (x - offsets[k, 0]) / spacing, (y - offsets[k, 1]) / spacing
        sample = ndimage.map_coordinates(master, [v + centre, u + centre], order=1, cval=0.0)
        scale = normal_force * kinematics["force_scale"][k] / max(sample.sum() * cell, 1e-300)
        pressure[k] = sample * scale
        traction[k] = pressure[k]
        ratio = kinematics["stick"][k]
        if ratio > 0.02:  # Ciavarella-Jager: minus the same field at the reduced load N'
            inner = ndimage.map_coordinates(
                master, [v / ratio + centre, u / ratio + centre], order=1, cval=0.0
            )
            traction[k] -= ratio * inner * scale
    traction *= kinematics["friction"][:, None, None]
    to_pressure, to_x, to_y = _taxel_operators(sensor)
    along = np.cos(direction) * to_x + np.sin(direction) * to_y
    pressure, traction = pressure.reshape(n_frames, -1), traction.reshape(n_frames, -1)
    loaded = np.nonzero(pressure.any(axis=0) | traction.any(axis=0))[0]  # the path's cells
    stress = pressure[:, loaded] @ to_pressure[loaded] + traction[:, loaded] @ along[loaded]
    return stress.reshape(n_frames, *sensor.shape)
