"""What the cover delivers to the sensing elements: the mechanical fields at each taxel."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from taxel.mechanics import (
    ContactResult,
    ConvolutionOperator,
    ElasticMaterial,
    depth_strain_operator,
    depth_stress_operator,
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


@lru_cache(maxsize=16)
def depth_operators(
    shape: tuple[int, int],
    spacing: tuple[float, float],
    depth: float,
    material: ElasticMaterial,
    thickness: float | None,
) -> tuple[ConvolutionOperator, ConvolutionOperator]:
    """Stress and strain operators to the sensing depth on a load grid (built once, cached)."""
    return (
        depth_stress_operator(shape, spacing, depth, material, thickness=thickness),
        depth_strain_operator(shape, spacing, depth, material, thickness=thickness),
    )


def taxel_fields(
    contact: ContactResult, grid: LoadGrid, cover: Cover, *, need: tuple[str, ...] = FIELD_NAMES
) -> TaxelFields:
    """Average the fields of a solved contact over each taxel's cell.

    Parameters
    ----------
    contact : ContactResult
        A contact solved on `grid` (same shape and spacing).
    grid : LoadGrid
        The sensor's load grid.
    cover : Cover
        The sensor's cover.
    need : tuple of str
        Fields to compute; the others are returned as zeros (saves a convolution each).

    Returns
    -------
    TaxelFields
    """
    if contact.pressure.shape != grid.shape:
        raise ValueError(
            f"`contact` must be solved on the sensor's load grid {grid.shape}, "
            f"got {contact.pressure.shape}"
        )
    rows, cols = grid.geometry.shape
    zeros = np.zeros((rows, cols))
    stress_operator, strain_operator = depth_operators(
        grid.shape, grid.spacing, cover.depth, cover.material, cover.thickness
    )
    pressure = contact.pressure
    return TaxelFields(
        pressure=grid.taxel_means(pressure) if "pressure" in need else zeros,
        stress=grid.taxel_means(stress_operator.apply(pressure)) if "stress" in need else zeros,
        strain=grid.taxel_means(strain_operator.apply(pressure)) if "strain" in need else zeros,
        displacement=(grid.taxel_means(contact.displacement) if "displacement" in need else zeros),
    )
