"""Seeds, pitches and geometries are checked when the object is made, naming the field."""

import numpy as np
import pytest

from taxel.mechanics import PerforatedScreen, StiffFoam, WoodRasp
from taxel.sensor import ArrayGeometry, LoadGrid, Readout


@pytest.mark.parametrize("kind", [StiffFoam, WoodRasp, PerforatedScreen])
@pytest.mark.parametrize("bad", [np.nan, np.inf, -1, 2.5, "3", None, True])
def test_a_texture_seed_is_checked_when_made(kind, bad):
    # a NaN or text seed was stored and failed only when the heights were drawn
    with pytest.raises((ValueError, TypeError), match="`seed` must be"):
        kind(seed=bad)


@pytest.mark.parametrize("bad", [np.nan, -1, 2.5, "3", None])
def test_a_readout_unit_seed_is_checked_when_made(bad):
    with pytest.raises((ValueError, TypeError), match="`unit_seed` must be"):
        Readout(unit_seed=bad)


def test_valid_seeds_are_kept():
    assert StiffFoam(seed=3).seed == 3
    assert Readout(unit_seed=np.int64(4)).unit_seed == 4


@pytest.mark.parametrize(
    ("bad", "error"), [("1e-3", TypeError), (True, TypeError), (1j, TypeError)]
)
def test_a_pitch_that_is_not_a_number_is_named(bad, error):
    # "1e-3" and True were taken as 1 mm and 1 m; a complex pitch raised float()'s own error
    with pytest.raises(error, match="`pitch` must be"):
        ArrayGeometry(4, 4, bad)


def test_a_load_grid_needs_an_array_geometry():
    # LoadGrid(nan) was made, and failed later with an AttributeError
    with pytest.raises(TypeError, match="`geometry` must be an ArrayGeometry, got"):
        LoadGrid(np.nan)
