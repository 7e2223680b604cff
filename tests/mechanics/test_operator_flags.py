"""The grid operators name a non-bool `periodic` and a material that is not one."""

import numpy as np
import pytest

from taxel.mechanics import (
    ElasticMaterial,
    depth_strain_operator,
    depth_stress_operator,
    surface_displacement_operator,
)

COVER = ElasticMaterial(1e6, 0.45)
MAKERS = {
    "surface": lambda **kw: surface_displacement_operator((8, 8), 1e-3, kw.pop("m", COVER), **kw),
    "strain": lambda **kw: depth_strain_operator((8, 8), 1e-3, 1e-3, kw.pop("m", COVER), **kw),
    "stress": lambda **kw: depth_stress_operator((8, 8), 1e-3, 1e-3, kw.pop("m", COVER), **kw),
}


@pytest.mark.parametrize("kind", sorted(MAKERS))
@pytest.mark.parametrize("bad", ["no", 1, None, np.array([True, False])])
def test_periodic_must_be_a_bool(kind, bad):
    # "no" and 1 were truthy and gave a periodic operator; an array raised NumPy's error
    with pytest.raises(TypeError, match="`periodic` must be True or False, got"):
        MAKERS[kind](periodic=bad)


@pytest.mark.parametrize("kind", sorted(MAKERS))
def test_the_material_must_be_an_elastic_material(kind):
    # depth_stress_operator took a string as its material (half-space stress ignores it)
    with pytest.raises(TypeError, match="`material` must be an ElasticMaterial"):
        MAKERS[kind](m="silicone")


@pytest.mark.parametrize("kind", sorted(MAKERS))
@pytest.mark.parametrize("periodic", [True, False, np.bool_(True)])
def test_a_bool_still_works(kind, periodic):
    op = MAKERS[kind](periodic=periodic)
    assert op.periodic == bool(periodic)
