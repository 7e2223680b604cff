"""Array geometry: where the taxels are, how dense they are, and the load grid under them."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_choice, check_instance, check_positive

__all__ = ["DENSITY_CLASSES", "ArrayGeometry", "LoadGrid", "density_class"]

LAYOUTS = ("square", "rectangular", "hexagonal")

# the Ellis seed's classes: about 1, 10, 100 and 1000 taxels per cm^2 (orders of magnitude);
# a density belongs to the class whose nominal value is nearest on a log scale
DENSITY_CLASSES: dict[str, float] = {"LDTA": 1.0, "MDTA": 10.0, "HDTA": 100.0, "VHDTA": 1000.0}


def density_class(density: float) -> str:
    """The Ellis seed's density class of an array with `density` taxels per cm^2.

    Examples
    --------
    >>> density_class(1504.0), density_class(25.0), density_class(0.5)
    ('VHDTA', 'MDTA', 'LDTA')
    """
    density = check_positive("density", density)
    names = list(DENSITY_CLASSES)
    nominal = np.log10(list(DENSITY_CLASSES.values()))
    return names[int(np.argmin(np.abs(nominal - np.log10(density))))]


@dataclass(frozen=True)
class ArrayGeometry:
    """A planar array of taxels.

    Parameters
    ----------
    rows, cols : int
        Number of taxel rows and columns.
    pitch : float or tuple of float
        Centre-to-centre spacing [m]: one value for a square array, (row_pitch, col_pitch) for a
        rectangular one. For a hexagonal (triangular) array `pitch` is the spacing along a row;
        rows are pitch * sqrt(3)/2 apart and odd rows are shifted by half a pitch.
    layout : {'square', 'rectangular', 'hexagonal'}
        The arrangement of the taxels.

    Examples
    --------
    >>> seed = ArrayGeometry(128, 128, 33e-3 / 128)  # the Ellis seed's VHDTA
    >>> round(seed.density), seed.density_class
    (1504, 'VHDTA')
    """

    rows: int
    cols: int
    pitch: Any
    layout: str = "square"

    def __post_init__(self) -> None:
        for name in ("rows", "cols"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
                raise ValueError(f"`{name}` must be a positive integer, got {value!r}")
        check_choice("layout", self.layout, LAYOUTS)
        values = np.atleast_1d(as_finite_array("pitch", self.pitch))
        if values.size not in (1, 2):
            raise ValueError(f"`pitch` must be a number or a (row, col) pair, got {self.pitch!r}")
        for value in values:
            check_positive("pitch", value)
        if self.layout == "square" and values.size == 2 and values[0] != values[1]:
            raise ValueError(f"`pitch` of a square layout must be one value, got {self.pitch!r}")
        if self.layout == "hexagonal" and values.size == 2:
            raise ValueError("`pitch` of a hexagonal layout is one value (along a row)")
        if self.layout == "hexagonal":
            row_pitch, col_pitch = float(values[0]) * np.sqrt(3) / 2, float(values[0])
        else:
            row_pitch, col_pitch = float(values[0]), float(values[-1])
        object.__setattr__(self, "pitch", (row_pitch, col_pitch))

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols)."""
        return (self.rows, self.cols)

    @property
    def taxel_pitch(self) -> tuple[float, float]:
        """(row pitch, column pitch) [m]."""
        return self.pitch

    @property
    def count(self) -> int:
        """Number of taxels."""
        return self.rows * self.cols

    @property
    def active_area(self) -> float:
        """Area covered by the taxels' cells [m^2]."""
        return self.count * self.pitch[0] * self.pitch[1]

    @property
    def extent(self) -> tuple[float, float]:
        """Width (x) and height (y) of the active area [m]."""
        width = self.cols * self.pitch[1] + (
            0.5 * self.pitch[1] if self.layout == "hexagonal" else 0
        )
        return (width, self.rows * self.pitch[0])

    @property
    def density(self) -> float:
        """Taxels per square centimetre."""
        return self.count / (self.active_area * 1e4)

    @property
    def density_class(self) -> str:
        """LDTA, MDTA, HDTA or VHDTA (Ellis seed, section 1)."""
        return density_class(self.density)

    def positions(self) -> tuple[np.ndarray, np.ndarray]:
        """Sensor-frame centres (x, y) [m] of the taxels, each of shape (rows, cols).

        The origin is the centre of the active area (docs/architecture.md, "Frames").
        """
        row_pitch, col_pitch = self.pitch
        rows, cols = np.meshgrid(np.arange(self.rows), np.arange(self.cols), indexing="ij")
        x = (cols - (self.cols - 1) / 2) * col_pitch
        if self.layout == "hexagonal":
            x = x + (rows % 2 - 0.5) * col_pitch / 2
        y = (rows - (self.rows - 1) / 2) * row_pitch
        return x, y

    def on_rectangular_grid(self, frame: Any) -> np.ndarray:
        """A frame of this array resampled onto the rectangular grid of the same pitches.

        A hexagonal array's rows are shifted by -p/4 (even rows) and +p/4 (odd rows) from
        the rectangular grid ``x = (col - (cols - 1) / 2) p`` (see `positions`); each row is
        linearly interpolated back onto that grid (weights 3/4 and 1/4, the end taxels
        held), so that image operators and index-to-metre conversions that assume a
        rectangular grid are right to within the interpolation. Other layouts are
        returned unchanged (as float).

        Examples
        --------
        >>> hexagonal = ArrayGeometry(2, 3, 1e-3, layout="hexagonal")
        >>> hexagonal.on_rectangular_grid([[0.0, 4.0, 8.0], [0.0, 4.0, 8.0]])
        array([[1., 5., 8.],
               [0., 3., 7.]])
        """
        values = np.array(frame, dtype=float)
        if values.shape != self.shape:
            raise ValueError(f"`frame` must have shape {self.shape}, got {values.shape}")
        if self.layout != "hexagonal":
            return values
        resampled = values.copy()
        even, odd = values[0::2], values[1::2]
        # even rows sit p/4 left of the grid: the grid point lies 1/4 of the way to the right
        resampled[0::2, :-1] = 0.75 * even[:, :-1] + 0.25 * even[:, 1:]
        resampled[1::2, 1:] = 0.75 * odd[:, 1:] + 0.25 * odd[:, :-1]
        return resampled

    def load_grid(self, oversampling: int = 1) -> LoadGrid:
        """The regular grid of surface cells under the array (see `LoadGrid`)."""
        return LoadGrid(self, oversampling)


@dataclass(frozen=True)
class LoadGrid:
    """Surface cells under an array: every taxel owns a block of cells.

    With `oversampling` k a square or rectangular taxel owns k x k cells; a hexagonal taxel owns
    k x 2k cells of half the width, and odd rows of taxels are shifted by k cells, so the blocks
    tile the plane like bricks. Loads are solved on this grid; a taxel reads the mean of its
    block.
    """

    geometry: ArrayGeometry
    oversampling: int = 1

    def __post_init__(self) -> None:
        check_instance("geometry", self.geometry, ArrayGeometry)
        k = self.oversampling
        if isinstance(k, bool) or not isinstance(k, int | np.integer) or k < 1:
            raise ValueError(f"`oversampling` must be a positive integer, got {k!r}")

    @property
    def _block(self) -> tuple[int, int]:
        k = self.oversampling
        return (k, 2 * k) if self.geometry.layout == "hexagonal" else (k, k)

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols) of surface cells."""
        block_rows, block_cols = self._block
        extra = block_cols // 2 if self.geometry.layout == "hexagonal" else 0
        return (self.geometry.rows * block_rows, self.geometry.cols * block_cols + extra)

    @property
    def spacing(self) -> tuple[float, float]:
        """(dy, dx) cell size [m]."""
        block_rows, block_cols = self._block
        return (self.geometry.pitch[0] / block_rows, self.geometry.pitch[1] / block_cols)

    def coordinates(self) -> tuple[np.ndarray, np.ndarray]:
        """Sensor-frame centres (x, y) [m] of the cells, each of shape `shape`."""
        rows, cols = self.shape
        dy, dx = self.spacing
        x = (np.arange(cols) - (cols - 1) / 2) * dx
        y = (np.arange(rows) - (rows - 1) / 2) * dy
        return np.broadcast_to(x[None, :], self.shape), np.broadcast_to(y[:, None], self.shape)

    def taxel_means(self, field: Any) -> np.ndarray:
        """Mean of a load-grid field over each taxel's block.

        Parameters
        ----------
        field : array_like, shape (..., *shape)
            Values on the load grid's cells (leading axes are kept).

        Returns
        -------
        numpy.ndarray, shape (..., rows, cols)
            One value per taxel.

        Examples
        --------
        >>> grid = ArrayGeometry(2, 3, 1e-3).load_grid(2)
        >>> grid.taxel_means(np.ones(grid.shape)).shape
        (2, 3)
        >>> grid.taxel_means(np.zeros((3, 3)))
        Traceback (most recent call last):
        ...
        ValueError: `field` must be on the load grid, shape (..., 4, 6), got (3, 3)
        """
        field = np.asarray(field)
        if field.ndim < 2 or field.shape[-2:] != self.shape:
            rows, cols = self.shape
            raise ValueError(
                f"`field` must be on the load grid, shape (..., {rows}, {cols}), got {field.shape}"
            )
        return self._means(field)

    def _means(self, field: np.ndarray) -> np.ndarray:
        """`taxel_means` of a field known to be on the grid (the sensor's read: unchecked)."""
        block_rows, block_cols = self._block
        rows, cols = self.geometry.shape
        if (block_rows, block_cols) == (1, 1):  # one cell per taxel: nothing to average
            return np.asarray(field, dtype=float)
        if self.geometry.layout != "hexagonal":
            blocks = field.reshape(*field.shape[:-2], rows, block_rows, cols, block_cols)
            return blocks.mean(axis=(-3, -1))
        shift = block_cols // 2
        result = np.empty((*field.shape[:-2], rows, cols))
        for parity in (0, 1):
            start = shift if parity else 0  # odd rows sit half a pitch to the right
            band = field[..., :, start : start + cols * block_cols]
            blocks = band.reshape(*field.shape[:-2], rows, block_rows, cols, block_cols)
            result[..., parity::2, :] = blocks.mean(axis=(-3, -1))[..., parity::2, :]
        return result
