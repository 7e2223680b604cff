"""What the cover delivers to the sensing elements: the mechanical fields at each taxel."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from taxel.mechanics import (
    ConvolutionOperator,
    ElasticMaterial,
    depth_strain_operator,
    depth_stress_operator,
    surface_displacement_operator,
)
from taxel.sensor._cover import Cover
from taxel.sensor._geometry import LoadGrid

__all__ = ["FIELD_NAMES", "TaxelFields", "taxel_fields"]

FIELD_NAMES = ("pressure", "stress", "strain", "displacement")


@dataclass(frozen=True)
class TaxelFields:
    """Mechanical fields averaged over each taxel's cell, each of shape (rows, cols).

    Attributes
    ----------
    pressure : numpy.ndarray
        Contact pressure on the cover's outer surface [Pa].
    stress : numpy.ndarray
        Normal stress sigma_z at the sensing depth [Pa], < 0 in compression.
    strain : numpy.ndarray
        Normal strain eps_z at the sensing depth [-], < 0 in compression.
    displacement : numpy.ndarray
        Normal displacement of the outer surface into the cover [m].
    """

    pressure: np.ndarray = field(repr=False)
    stress: np.ndarray = field(repr=False)
    strain: np.ndarray = field(repr=False)
    displacement: np.ndarray = field(repr=False)

    def get(self, name: str) -> np.ndarray:
        """The field called `name` (one of FIELD_NAMES)."""
        if name not in FIELD_NAMES:
            raise ValueError(f"`name` must be one of {', '.join(FIELD_NAMES)}; got {name!r}")
        return getattr(self, name)


def depth_operators(
    shape: tuple[int, int],
    spacing: tuple[float, float],
    depth: float,
    material: ElasticMaterial,
    thickness: float | None,
) -> tuple[ConvolutionOperator, ConvolutionOperator]:
    """Stress and strain operators to the sensing depth on a load grid (built once, cached)."""
    return (
        _depth_operator("stress", shape, spacing, depth, material, thickness),
        _depth_operator("strain", shape, spacing, depth, material, thickness),
    )


@lru_cache(maxsize=32)
def _depth_operator(
    name: str,
    shape: tuple[int, int],
    spacing: tuple[float, float],
    depth: float,
    material: ElasticMaterial,
    thickness: float | None,
) -> ConvolutionOperator:
    # one at a time: a sensor needs one of the two, and each costs a kernel table to build
    build = depth_stress_operator if name == "stress" else depth_strain_operator
    return build(shape, spacing, depth, material, thickness=thickness)


@lru_cache(maxsize=16)
def _displacement_operator(
    shape: tuple[int, int],
    spacing: tuple[float, float],
    material: ElasticMaterial,
    thickness: float | None,
) -> ConvolutionOperator:
    return surface_displacement_operator(shape, spacing, material, thickness=thickness)


def taxel_fields(
    pressure: np.ndarray,
    grid: LoadGrid,
    cover: Cover,
    *,
    displacement: np.ndarray | None = None,
    need: tuple[str, ...] = FIELD_NAMES,
) -> TaxelFields:
    """Average the mechanical fields of a surface pressure over each taxel's cell.

    Parameters
    ----------
    pressure : numpy.ndarray
        Surface pressure on the sensor's load grid [Pa] (e.g. ``ContactResult.pressure``).
    grid : LoadGrid
        The sensor's load grid.
    cover : Cover
        The sensor's cover.
    displacement : numpy.ndarray, optional
        Surface displacement on the load grid [m] if already known (a contact solve gives
        it); computed from the pressure when needed and not given.
    need : tuple of str
        Fields to compute; the others are not computed (each saves a convolution) and are
        returned as NaN, so that no one takes them for an unloaded field.

    Returns
    -------
    TaxelFields
    """
    if pressure.shape != grid.shape:
        raise ValueError(
            f"`pressure` must be on the sensor's load grid {grid.shape}, got {pressure.shape}"
        )
    if displacement is not None and np.shape(displacement) != grid.shape:
        raise ValueError(
            f"`displacement` must be on the sensor's load grid {grid.shape}, got "
            f"{np.shape(displacement)}"
        )
    skipped = np.full(grid.geometry.shape, np.nan)
    skipped.flags.writeable = False  # shared by the fields not computed
    key = (grid.shape, grid.spacing, cover.depth, cover.material, cover.thickness)

    def at_depth(name: str) -> np.ndarray:
        if name not in need:
            return skipped
        return grid._means(_depth_operator(name, *key).apply(pressure))

    displacement_means = skipped
    if "displacement" in need:
        if displacement is None:
            operator = _displacement_operator(
                grid.shape, grid.spacing, cover.material, cover.thickness
            )
            displacement = operator.apply(pressure)
        displacement_means = grid._means(displacement)
    return TaxelFields(
        pressure=grid._means(pressure) if "pressure" in need else skipped,
        stress=at_depth("stress"),
        strain=at_depth("strain"),
        displacement=displacement_means,
    )
