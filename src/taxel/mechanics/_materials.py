"""Linear elastic materials and the effective modulus of two bodies in contact."""

from __future__ import annotations

import math
from dataclasses import dataclass

from taxel._validation import check_instance, check_positive, check_range

__all__ = ["ElasticMaterial", "effective_modulus"]


@dataclass(frozen=True)
class ElasticMaterial:
    """A homogeneous, isotropic, linear elastic material.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E [Pa], > 0.
    poisson_ratio : float
        Poisson's ratio nu [-], in (-1, 0.5]. 0.5 is incompressible (silicone covers
        are close to it) and is handled without division by zero everywhere.

    Examples
    --------
    >>> cover = ElasticMaterial(youngs_modulus=1e6, poisson_ratio=0.5)
    >>> round(cover.plane_strain_modulus)
    1333333
    >>> ElasticMaterial(youngs_modulus=-3.0, poisson_ratio=0.3)
    Traceback (most recent call last):
    ...
    ValueError: `youngs_modulus` must be > 0, got -3
    """

    youngs_modulus: float
    poisson_ratio: float

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "youngs_modulus", check_positive("youngs_modulus", self.youngs_modulus)
        )
        object.__setattr__(
            self,
            "poisson_ratio",
            check_range("poisson_ratio", self.poisson_ratio, -1.0, 0.5, low_inclusive=False),
        )

    @property
    def plane_strain_modulus(self) -> float:
        """E* = E / (1 - nu^2) [Pa], the modulus a rigid indenter feels."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)

    @property
    def shear_modulus(self) -> float:
        """G = E / (2 (1 + nu)) [Pa]."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def constrained_modulus(self) -> float:
        """Oedometric modulus M = E (1 - nu) / ((1 + nu)(1 - 2 nu)) [Pa]; inf at nu = 0.5.

        A thin layer bonded to a rigid base under uniform pressure p shortens by
        p h / M: it cannot expand sideways.
        """
        nu = self.poisson_ratio
        if nu == 0.5:
            return math.inf
        return self.youngs_modulus * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))


def effective_modulus(first: ElasticMaterial, second: ElasticMaterial | None = None) -> float:
    """Effective contact modulus E* of two elastic bodies [Pa].

    Parameters
    ----------
    first : ElasticMaterial
        One body (usually the sensor cover).
    second : ElasticMaterial, optional
        The other body (the indenter). None means rigid.

    Returns
    -------
    float
        E* from 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 [Pa] (Johnson, Contact Mechanics,
        eq. 4.22). With a rigid second body this is the plane-strain modulus of the first.

    Examples
    --------
    >>> cover = ElasticMaterial(1e6, 0.5)
    >>> round(effective_modulus(cover, cover))
    666667
    """
    check_instance("first", first, ElasticMaterial)
    compliance = 1.0 / first.plane_strain_modulus
    if second is not None:
        check_instance("second", second, ElasticMaterial)
        compliance += 1.0 / second.plane_strain_modulus
    return 1.0 / compliance
