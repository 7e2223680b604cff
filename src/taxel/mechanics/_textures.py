"""Textured surfaces of the Ellis seed's texture experiment: stiff foam, wood rasp, screen.

Each is a periodic height field generated reproducibly from its parameters (and `seed`),
sampled once on a fine tile and interpolated wherever it is placed.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy import ndimage

from taxel._validation import check_count, check_positive
from taxel.mechanics._indenter_base import Indenter

__all__ = ["PerforatedScreen", "StiffFoam", "WoodRasp"]

_TILE = 40e-3  # smallest tile period [m]: larger than the 33 mm sensor of the Ellis seed
_RESOLUTION = 60e-6  # tile sampling [m]: several samples per taxel of the finest sensor


@dataclass(frozen=True)
class _Tile:
    """A periodic height field: heights on a grid covering period_x by period_y [m]."""

    heights: np.ndarray
    period_x: float
    period_y: float


def _sample(tile: _Tile, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Interpolate a periodic tile at (u, v), keeping +inf cells infinite."""
    rows, cols = tile.heights.shape
    u, v = np.broadcast_arrays(u, v)
    coordinates = np.stack([v.ravel() / tile.period_y * rows, u.ravel() / tile.period_x * cols])
    samples = tile.heights
    finite = np.where(np.isfinite(samples), samples, 0.0)
    holes = (~np.isfinite(samples)).astype(float)
    heights = ndimage.map_coordinates(finite, coordinates, order=1, mode="grid-wrap")
    inside_hole = ndimage.map_coordinates(holes, coordinates, order=1, mode="grid-wrap")
    return np.where(inside_hole >= 0.5, np.inf, heights).reshape(u.shape)


def _lattice_tile(pitch: float, row_pitch: float) -> tuple[int, int, np.ndarray, np.ndarray]:
    """Lattice counts and sample coordinates of a tile of a staggered lattice.

    Returns whole numbers of sites per row and of rows (even, so staggered rows wrap around)
    covering at least _TILE, and the coordinates (x, y) [m] of the tile's samples.
    """
    per_row = int(np.ceil(_TILE / pitch))
    rows = 2 * int(np.ceil(_TILE / (2 * row_pitch)))  # even, so staggered rows wrap around
    x = np.arange(int(np.ceil(per_row * pitch / _RESOLUTION))) * _RESOLUTION
    y = np.arange(int(np.ceil(rows * row_pitch / _RESOLUTION))) * _RESOLUTION
    x *= per_row * pitch / (x.size * _RESOLUTION)
    y *= rows * row_pitch / (y.size * _RESOLUTION)
    grid_x, grid_y = np.meshgrid(x, y)
    return per_row, rows, grid_x, grid_y


@lru_cache(maxsize=8)
def _foam_tile(cell_size: float, depth: float, seed: int) -> _Tile:
    rng = np.random.default_rng(seed)
    size = int(np.ceil(_TILE / min(cell_size / 6, _RESOLUTION)))
    noise = rng.standard_normal((size, size))
    field = ndimage.gaussian_filter(noise, sigma=size * cell_size / _TILE / 2, mode="wrap")
    heights = depth * (field.max() - field) / (field.max() - field.min())
    heights.setflags(write=False)
    return _Tile(heights, _TILE, _TILE)


@dataclass(frozen=True)
class StiffFoam(Indenter):
    """Stiff conductive foam: an irregular surface of cells about `cell_size` [m] across.

    Heights vary randomly over `depth` [m] with a correlation length of about half a cell.
    """

    cell_size: float = 1.5e-3
    depth: float = 0.3e-3
    seed: int = 0

    def __post_init__(self) -> None:
        # a NaN or text seed was stored and failed only when the heights were drawn
        object.__setattr__(self, "seed", check_count("seed", self.seed, minimum=0))
        check_positive("cell_size", self.cell_size)
        check_positive("depth", self.depth)

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        return _sample(_foam_tile(self.cell_size, self.depth, self.seed), u, v)


def _staggered_neighbours(
    x: np.ndarray, y: np.ndarray, pitch: float, row_pitch: float, per_row: int, rows: int
) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """For each point, offsets (dx, dy) to the nearby sites of a staggered periodic lattice.

    Rows are `row_pitch` apart and every other row is shifted by half a `pitch`. Returns,
    for the sites in the 3 x 3 neighbourhood, (dx, dy, row index, column index).
    """
    row_step, column_step = row_pitch, pitch
    nearest_row = np.floor(y / row_step + 0.5).astype(int)
    sites = []
    for row_shift in (-1, 0, 1):
        row = nearest_row + row_shift
        offset = 0.5 * column_step * (row % 2)
        nearest_column = np.floor((x - offset) / column_step + 0.5).astype(int)
        for column_shift in (-1, 0, 1):
            column = nearest_column + column_shift
            dx = x - (column * column_step + offset)
            dy = y - row * row_step
            sites.append((dx, dy, row % rows, column % per_row))
    return sites


@lru_cache(maxsize=8)
def _rasp_tile(
    tooth_pitch: float, row_pitch: float, tooth_height: float, scatter: float, seed: int
) -> _Tile:
    rng = np.random.default_rng(seed)
    per_row, rows, x, y = _lattice_tile(tooth_pitch, row_pitch)
    tips = scatter * rng.random((rows, per_row))
    heights = np.full(x.shape, tooth_height + scatter)
    # a tooth is a steep pyramid (faces at 60 degrees), its tip lower by its scatter
    slope = np.tan(np.radians(60))
    for dx, dy, row, column in _staggered_neighbours(x, y, tooth_pitch, row_pitch, per_row, rows):
        tooth = tips[row, column] + np.maximum(np.abs(dx), np.abs(dy)) * slope
        np.minimum(heights, tooth, out=heights)
    heights -= heights.min()
    heights.setflags(write=False)
    return _Tile(heights, per_row * tooth_pitch, rows * row_pitch)


@dataclass(frozen=True)
class WoodRasp(Indenter):
    """The teeth of a wood rasp: staggered rows of sharp pyramids.

    Teeth sit `tooth_pitch` [m] apart in rows `row_pitch` [m] apart; their tips scatter in
    height by up to `scatter` [m], as hand-cut teeth do; `tooth_height` [m] is their height.
    """

    tooth_pitch: float = 3.0e-3
    row_pitch: float = 2.5e-3
    tooth_height: float = 0.8e-3
    scatter: float = 0.05e-3
    seed: int = 0

    def __post_init__(self) -> None:
        # a NaN or text seed was stored and failed only when the heights were drawn
        object.__setattr__(self, "seed", check_count("seed", self.seed, minimum=0))
        for name in ("tooth_pitch", "row_pitch", "tooth_height"):
            check_positive(name, getattr(self, name))
        check_positive("scatter", self.scatter, allow_zero=True)

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        tile = _rasp_tile(
            self.tooth_pitch, self.row_pitch, self.tooth_height, self.scatter, self.seed
        )
        return _sample(tile, u, v)


@lru_cache(maxsize=8)
def _screen_tile(hole_diameter: float, pitch: float, waviness: float, seed: int) -> _Tile:
    rng = np.random.default_rng(seed)
    row_pitch = pitch * np.sqrt(3) / 2  # holes on a 60-degree staggered pattern
    per_row, rows, x, y = _lattice_tile(pitch, row_pitch)
    # the sheet is not perfectly flat: a long-wave waviness of amplitude `waviness`
    # generated on a 1 mm grid and upsampled: the waves are ~10 mm long
    coarse_shape = (int(round(rows * row_pitch / 1e-3)), int(round(per_row * pitch / 1e-3)))
    coarse = ndimage.gaussian_filter(rng.standard_normal(coarse_shape), 10.0, mode="wrap")
    zoom = (x.shape[0] / coarse_shape[0], x.shape[1] / coarse_shape[1])
    noise = ndimage.zoom(coarse, zoom, order=3, mode="grid-wrap", grid_mode=True)
    heights = waviness * (noise - noise.min()) / (noise.max() - noise.min())
    holes = np.zeros(x.shape, dtype=bool)
    for dx, dy, _, _ in _staggered_neighbours(x, y, pitch, row_pitch, per_row, rows):
        holes |= np.hypot(dx, dy) < hole_diameter / 2
    heights = np.where(holes, np.inf, heights - heights[~holes].min())
    heights.setflags(write=False)
    return _Tile(heights, per_row * pitch, rows * row_pitch)


@dataclass(frozen=True)
class PerforatedScreen(Indenter):
    """A perforated metal screen: round holes of `hole_diameter` [m] on a staggered `pitch` [m].

    `waviness` [m] is the sheet's deviation from flat over long wavelengths.
    """

    hole_diameter: float = 4e-3
    pitch: float = 6e-3
    waviness: float = 0.1e-3
    seed: int = 0

    def __post_init__(self) -> None:
        # a NaN or text seed was stored and failed only when the heights were drawn
        object.__setattr__(self, "seed", check_count("seed", self.seed, minimum=0))
        check_positive("hole_diameter", self.hole_diameter)
        check_positive("pitch", self.pitch)
        check_positive("waviness", self.waviness, allow_zero=True)
        if self.hole_diameter >= self.pitch:
            raise ValueError(f"`hole_diameter` must be < `pitch`, got {self.hole_diameter:g}")

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        return _sample(
            _screen_tile(self.hole_diameter, self.pitch, self.waviness, self.seed), u, v
        )
