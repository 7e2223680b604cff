"""Mechanics functions name a material that is not an ElasticMaterial, and other bad input."""

import numpy as np
import pytest

from taxel.mechanics import (
    ElasticMaterial,
    halfspace_displacement_transfer,
    halfspace_strain_transfer,
    inplane_stress_difference,
    layer_displacement_transfer,
    layer_strain_transfer,
    layer_stress_transfer,
    line_load_displacement,
    line_load_strain,
    plane_strain_displacement_matrix,
    plane_strain_strain_matrix,
    strip_load_strain,
)

X = np.linspace(-2e-3, 2e-3, 5)
CALLS = {
    "line_load_strain": lambda m: line_load_strain(X, 1e-3, m),
    "line_load_displacement": lambda m: line_load_displacement(X + 3e-3, m),
    "strip_load_strain": lambda m: strip_load_strain(X, 1e-3, 1e-3, m),
    "plane_strain_strain_matrix": lambda m: plane_strain_strain_matrix(X, X, 1e-3, 1e-3, m),
    "plane_strain_displacement_matrix": lambda m: plane_strain_displacement_matrix(X, X, 1e-3, m),
    "halfspace_displacement_transfer": lambda m: halfspace_displacement_transfer(1e3, m),
    "halfspace_strain_transfer": lambda m: halfspace_strain_transfer(1e3, 1e-3, m),
    "layer_displacement_transfer": lambda m: layer_displacement_transfer(1e3, 2e-3, m),
    "layer_strain_transfer": lambda m: layer_strain_transfer(1e3, 1e-3, 2e-3, m),
    "layer_stress_transfer": lambda m: layer_stress_transfer(1e3, 1e-3, 2e-3, m),
    "inplane_stress_difference": lambda m: inplane_stress_difference(
        np.ones((4, 4)), 1e-3, 1e-3, m
    ),
}


@pytest.mark.parametrize("name", sorted(CALLS))
@pytest.mark.parametrize("bad", [1e6, "silicone", None, (1e6, 0.45)])
def test_a_material_that_is_not_an_elastic_material_is_named(name, bad):
    # these raised AttributeError: 'float' object has no attribute 'poisson_ratio'
    with pytest.raises(TypeError, match="`material` must be an ElasticMaterial, got"):
        CALLS[name](bad)


@pytest.mark.parametrize("name", sorted(CALLS))
def test_a_real_material_still_works(name):
    assert np.all(np.isfinite(CALLS[name](ElasticMaterial(1e6, 0.45))))


def test_strip_widths_that_do_not_match_the_positions_are_named():
    cover = ElasticMaterial(1e6, 0.45)
    with pytest.raises(ValueError, match="`x` and `width` must have shapes that broadcast"):
        strip_load_strain(X, 1e-3, np.array([1e-3, 2e-3]), cover)
    with pytest.raises(ValueError, match=r"`load_width` must be a number or one per load"):
        plane_strain_strain_matrix(X, X, np.array([1e-3, 2e-3]), 1e-3, cover)
    with pytest.raises(ValueError, match=r"`load_width` must be a number or one per load"):
        plane_strain_displacement_matrix(X, X, np.full((5, 1), 1e-3), cover)


def test_inplane_stress_difference_names_an_empty_grid_and_a_bad_padding():
    cover = ElasticMaterial(1e6, 0.45)
    with pytest.raises(ValueError, match=r"`pressure` must have at least one cell, got shape"):
        inplane_stress_difference(np.zeros((0, 3)), 1e-3, 1e-3, cover)
    for bad in (np.nan, np.inf, 2.5, 0, "2", None):
        with pytest.raises((ValueError, TypeError), match="`padding` must be"):
            inplane_stress_difference(np.ones((4, 4)), 1e-3, 1e-3, cover, padding=bad)
