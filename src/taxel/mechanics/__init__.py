"""Mechanics of the sensor's elastic cover (section 25.2 of the chapter seed).

Materials
---------
ElasticMaterial, effective_modulus

Plane strain (the chapter's one-dimensional model, eqs. 25.1-25.5)
-------------------------------------------------------------------
line_load_strain, line_load_displacement, strip_load_strain,
plane_strain_strain_matrix, plane_strain_displacement_matrix
"""

from taxel.mechanics._materials import ElasticMaterial, effective_modulus
from taxel.mechanics._plane_strain import (
    line_load_displacement,
    line_load_strain,
    plane_strain_displacement_matrix,
    plane_strain_strain_matrix,
    strip_load_strain,
)

__all__ = [
    "ElasticMaterial",
    "effective_modulus",
    "line_load_displacement",
    "line_load_strain",
    "plane_strain_displacement_matrix",
    "plane_strain_strain_matrix",
    "strip_load_strain",
]
