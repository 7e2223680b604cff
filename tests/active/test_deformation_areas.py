"""The imprint areas the deformation procedure reports, against the contact they show.

A block or a ball pressed harder touches the sensor over an area that never shrinks (the
pressure under a rigid indenter grows everywhere with the force), and the tactile image
shows that area blurred by the cover, by about its depth all round.
"""

import dataclasses
import math

import numpy as np
import pytest

from taxel.active import (
    DEFORMATION_OBJECTS,
    Deformation,
    SimulatedFinger,
    calibrate_pad,
    make_deformation_object,
)
from taxel.active._deformable_objects import top_height
from taxel.frames import make_pose
from taxel.sensor import make_sensor

DOWN = np.diag([1.0, -1.0, -1.0])


class RecordingFinger(SimulatedFinger):
    """A simulated finger that keeps every reading, with the contact the solver found."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.readings = []

    def press(self, **kwargs):
        reading = super().press(**kwargs)
        self.readings.append(reading)
        return reading


@pytest.fixture(scope="module")
def calibration():
    return calibrate_pad("vhdta128", radii=(4e-3, 16e-3, 64e-3))


def _press(calibration, name, sensor, seed):
    item = make_deformation_object(name)
    above = make_pose(DOWN, [0.0, 0.0, top_height(item) + 5e-3])
    finger = RecordingFinger(sensor, [item], above, rng=seed)
    result = Deformation(calibration).run(finger)
    cell = float(np.prod(sensor.load_grid.spacing))
    true = [float(reading.frame.contact.contact.sum()) * cell for reading in finger.readings]
    return result, true


def _radius(area):
    return math.sqrt(area / math.pi)


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("name", list(DEFORMATION_OBJECTS))
def test_areas_never_shrink_with_force(calibration, name, seed):
    # the wood block showed 5707 px at 12 N and 5633 at 39 N: the light press's outline
    # was set by the noise, ~4 sigmas over the background, the firm one's at 12 % of the
    # contrast over the image's minimum, 10 % over the background
    sensor = make_sensor("vhdta128")
    result, true = _press(calibration, name, sensor, seed)
    assert np.all(np.diff(true) >= 0)  # the solver's contact grows: 5124 -> 5184 cells
    assert np.all(np.diff(result.area_pixels) >= 0), result.area_pixels
    assert result.area_growth >= 1.0


@pytest.mark.parametrize("name", list(DEFORMATION_OBJECTS))
def test_areas_follow_the_contact_within_the_cover_depth(calibration, name):
    # the image is the contact blurred by the 1 mm cover: the imprint's equivalent radius
    # lies within a cover depth of the contact's (outside a small stiff ball's by 0.4-0.8
    # mm; on the racquet ball's, whose pressure falls to zero at its edge, within 0.05 mm)
    sensor = make_sensor("vhdta128")
    result, true = _press(calibration, name, sensor, seed=0)
    depth = sensor.cover.depth
    for measured, contact in zip(result.areas[1:], true[1:], strict=True):
        assert abs(_radius(measured) - _radius(contact)) <= depth


def test_a_ball_on_a_thick_cover_shows_hertz_area():
    # on a 10 mm cover the steel ball's contact radius at 0.5, 2 and 4 N (1.8-3.6 mm, under
    # 0.4 of the thickness) is Hertz's a = (3 F R / 4 E*)^(1/3); the image's equivalent
    # radius lies within the 1 mm cover depth beyond it (it was 0.5-0.6 mm)
    base = make_sensor("vhdta128")
    sensor = dataclasses.replace(base, cover=dataclasses.replace(base.cover, thickness=10e-3))
    forces = (0.5, 2.0, 4.0)
    pad = calibrate_pad(sensor, forces=forces, radii=(4e-3, 16e-3))
    result, true = _press(pad, "steel ball", sensor, seed=0)
    _, radius, modulus, poisson = DEFORMATION_OBJECTS["steel ball"]
    cover = sensor.cover.material
    combined = 1.0 / (
        (1 - cover.poisson_ratio**2) / cover.youngs_modulus + (1 - poisson**2) / modulus
    )
    for force, measured, contact in zip(forces, result.areas, true, strict=True):
        hertz = (3 * force * radius / (4 * combined)) ** (1 / 3)
        assert _radius(contact) == pytest.approx(hertz, rel=0.05)
        assert 0.0 <= _radius(measured) - hertz <= sensor.cover.depth
    assert np.all(np.diff(result.area_pixels) > 0)


def test_a_press_past_a_photoelastic_layers_first_fringe_is_refused():
    # photoelastic64's fringe turns back at about 1 N under a 20 mm steel ball: the imprint
    # then shrinks as the load grows, and a rigid ball would read as deformable
    sensor = make_sensor("photoelastic64")
    calibration = calibrate_pad(sensor, forces=(0.5, 4.0, 12.0), radii=(4e-3, 16e-3, 64e-3))
    item = make_deformation_object("steel ball")
    above = make_pose(DOWN, [0.0, 0.0, top_height(item) + 5e-3])
    finger = SimulatedFinger(sensor, [item], above, rng=0)
    with pytest.raises(ValueError, match="the press at 4 N takes photoelastic64's reading to"):
        Deformation(calibration).run(finger)
