"""The rest level past dead taxels (`taxel.features._rest`), and the features on such frames."""

import numpy as np
import pytest
from synthetic import band, cone, render

from taxel.features import extract, prepare
from taxel.features._rest import extremes
from taxel.mechanics import make_indenter
from taxel.sensor import make_sensor

PITCH = 3.3e-2 / 128
# a dead taxel in a corner, next to it, at the middle of an edge and inside
PLACES = [(0, 0), (1, 1), (127, 126), (0, 64), (100, 20)]


@pytest.fixture(scope="module")
def vhdta():
    return make_sensor("vhdta128")


def test_a_dip_is_passed_over_and_rest_taxels_are_not():
    rng = np.random.default_rng(3)
    noisy = rng.normal(20.0, 0.3, (128, 128)).astype(np.float32)
    smooth = noisy.copy()
    lowest = float(smooth.min())
    smooth[0:2, 0:2] = 5.0  # a smoothed dead taxel's dip in a corner
    smooth[60, 60] = 15.0  # and another inside
    smooth[90, 90] = 40.0  # a peak
    level, peak, at = extremes(smooth, 0.3, 1.0)
    assert level == pytest.approx(lowest)
    assert peak == 40.0 and at == (90, 90)
    # a patch of 40 taxels at rest, the rest pressed: the patch is the rest level
    pressed = smooth + 30.0
    pressed[120:, 120:125] = 20.0
    assert extremes(pressed, 0.3, 1.0)[0] == 20.0
    # on a small array the lowest taxel is the rest level, whatever it is
    small = noisy[:16, :16].copy()
    small[0, 0] = 5.0
    assert extremes(small, 0.3, 1.0)[0] == 5.0


@pytest.mark.parametrize("place", PLACES)
@pytest.mark.parametrize("pattern", [cone, band])
def test_a_dead_taxel_changes_nothing_given_a_pitch(pattern, place):
    clean = render(pattern, ftir=True, noise=0.01, rng=4)
    dead = clean.copy()
    dead[place] = 0
    expected, found = extract(clean, PITCH), extract(dead, PITCH)
    assert found.contact_type == expected.contact_type
    # inside, the dip stays within 2.5 sigma of the rest level and is left (noise alone
    # makes such dips): it lowers the cut by 1.4 sigma, and the cone's shallow flank
    # gains 9 % of its area; at the border it is passed over
    inside = place == (100, 20)
    area = pytest.approx(expected.contact.area_m2, rel=0.1 if inside else 0.02)
    assert found.contact.area_m2 == area
    assert found.contact.centroid_m == pytest.approx(expected.contact.centroid_m, abs=0.1 * PITCH)


@pytest.mark.parametrize("place", PLACES)
def test_a_dead_pixel_of_the_camera_changes_nothing(vhdta, place):
    # an edge pressed into the vhdta128 sensor, its camera's noise on: one dark pixel at 0
    # used to make the whole array contact (in a corner, the removal of bright defects
    # widened it into a 2 x 2 block)
    frame = vhdta.press(
        make_indenter("edge"), normal_force=4.0, position=(1e-3, 0.0), angle=0.3, rng=5
    ).raw
    dead = frame.copy()
    dead[place] = 0
    expected, found = extract(frame, vhdta), extract(dead, vhdta)
    assert prepare(dead, vhdta).mask.mean() < 0.3
    assert found.contact_type == expected.contact_type == "line"
    assert found.contact.centroid_m == pytest.approx(expected.contact.centroid_m, abs=0.05 * PITCH)
