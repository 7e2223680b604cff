import math

import pytest

from taxel.mechanics import ElasticMaterial, effective_modulus


def test_moduli_of_known_material():
    steel = ElasticMaterial(210e9, 0.3)
    assert steel.plane_strain_modulus == pytest.approx(210e9 / 0.91, rel=1e-12)
    assert steel.shear_modulus == pytest.approx(210e9 / 2.6, rel=1e-12)
    assert steel.constrained_modulus == pytest.approx(210e9 * 0.7 / (1.3 * 0.4), rel=1e-12)


def test_incompressible_material_is_handled():
    silicone = ElasticMaterial(1e6, 0.5)
    assert silicone.plane_strain_modulus == pytest.approx(4e6 / 3)
    assert math.isinf(silicone.constrained_modulus)


def test_effective_modulus_of_two_bodies():
    cover = ElasticMaterial(1e6, 0.5)
    glass = ElasticMaterial(70e9, 0.22)
    expected = 1 / (0.75 / 1e6 + (1 - 0.22**2) / 70e9)
    assert effective_modulus(cover, glass) == pytest.approx(expected, rel=1e-12)
    assert effective_modulus(cover) == cover.plane_strain_modulus
    # identical bodies: half the modulus of one
    assert effective_modulus(cover, cover) == pytest.approx(cover.plane_strain_modulus / 2)


@pytest.mark.parametrize(
    ("modulus", "ratio", "match"),
    [
        (-3.0, 0.3, r"`youngs_modulus` must be > 0, got -3"),
        (0.0, 0.3, r"`youngs_modulus` must be > 0"),
        (math.nan, 0.3, r"`youngs_modulus` must be finite"),
        (1e6, 0.51, r"`poisson_ratio` must lie in \(-1, 0.5\], got 0.51"),
        (1e6, -1.0, r"`poisson_ratio` must lie in \(-1, 0.5\]"),
    ],
)
def test_bad_material_is_rejected(modulus, ratio, match):
    with pytest.raises(ValueError, match=match):
        ElasticMaterial(modulus, ratio)


def test_non_numeric_modulus_is_a_type_error():
    with pytest.raises(TypeError, match="`youngs_modulus` must be a real number"):
        ElasticMaterial("soft", 0.3)
    with pytest.raises(TypeError, match="`youngs_modulus` must be a real number, got True"):
        ElasticMaterial(True, 0.3)
