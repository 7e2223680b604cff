"""The rest level past dead taxels (`taxel.features._rest`), and the features on such frames."""

import cv2
import numpy as np
import pytest
from synthetic import _edge_peak, band, cone, render

from taxel.features import extract, prepare
from taxel.features._rest import smoothed
from taxel.mechanics import make_indenter
from taxel.sensor import make_sensor

PITCH = 3.3e-2 / 128
# a dead taxel in a corner, next to it, at the middle of an edge and inside
PLACES = [(0, 0), (1, 1), (127, 126), (0, 64), (100, 20)]


@pytest.fixture(scope="module")
def vhdta():
    return make_sensor("vhdta128")


def test_dead_taxels_are_read_as_their_neighbours_and_rest_taxels_are_not():
    rng = np.random.default_rng(3)
    frame = rng.normal(24.0, 1.0, (128, 128)).astype(np.float32)
    given = frame.copy()
    given[0, 0] = given[127, 126] = 0.0  # two dead taxels, at and next to corners
    values, smooth, level, peak, _ = smoothed(given, 1.0, 1.0, defects=True)
    clean = smoothed(frame, 1.0, 1.0, defects=True)
    assert level == pytest.approx(clean[2], abs=0.5)  # the rest level, not a dip's bottom
    assert values[0, 0] > 20.0 and values[127, 126] > 20.0
    assert given[0, 0] == 0.0  # the caller's frame is left as it was
    # a plate over the whole array but a 2 x 2 corner at rest: the corner is the rest level
    plate = rng.normal(110.0, 2.5, (128, 128)).astype(np.float32)
    plate[:2, :2] = rng.normal(24.0, 2.5, (2, 2))
    values, _, level, _, _ = smoothed(plate, 1.0, 2.5, defects=True)
    np.testing.assert_array_equal(
        values[:2, :2], cv2.morphologyEx(plate, 2, np.ones((3, 3)))[:2, :2]
    )
    assert level < 40.0
    # with no noise to measure against, none is found: the dip sets the rest level
    assert smoothed(given, 1.0, 0.0, defects=False)[2] < clean[2] - 3.0


def test_a_face_s_corner_at_rest_is_no_dead_taxel():
    # a face over a 64 x 64 array but for the 10 taxels i + j < 4 of a corner: under the
    # cover's blur the corner taxel rises through its neighbours to the face, which is no
    # spike (a first version read it as dead, one taxel after another, and halved the face)
    def face(x, y):
        across = (x + y + 60.0) / np.sqrt(2)
        return np.where(across > 0, _edge_peak(across, 40.0) * 0.3, 0)

    image = render(face, (64, 64), noise=0.005, rng=1)
    features = extract(image, PITCH)
    assert prepare(image, PITCH).mask.sum() >= 4090
    assert features.contact_type == "surface"


@pytest.mark.parametrize("place", PLACES)
@pytest.mark.parametrize("pattern", [cone, band])
def test_a_dead_taxel_changes_nothing_given_a_pitch(pattern, place):
    clean = render(pattern, ftir=True, noise=0.01, rng=4)
    dead = clean.copy()
    dead[place] = 0
    expected, found = extract(clean, PITCH), extract(dead, PITCH)
    assert found.contact_type == expected.contact_type
    assert found.contact.area_m2 == pytest.approx(expected.contact.area_m2, rel=0.02)
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
