"""Settings of the probing and sliding procedures refused when the procedure is made."""

import numpy as np
import pytest

from taxel.active import CornerProbing, SimulatedFinger, TextureSliding, make_ball
from taxel.frames import make_pose


@pytest.mark.parametrize("edges", [[], [100.0], [400.0, 200.0, 100.0], [-1.0, 100.0]])
def test_band_edges_are_checked_before_the_finger_slides(edges):
    with pytest.raises(ValueError, match=r"`band_edges` must be at least two increasing values"):
        TextureSliding(band_edges=edges)


def test_a_corner_s_calibration_must_be_a_contact_point_calibration():
    with pytest.raises(TypeError, match=r"`calibration` must be a ContactPointCalibration"):
        CornerProbing(calibration="flat.json")


def test_a_texture_slide_with_bad_band_edges_leaves_the_finger_unmoved():
    start = make_pose(np.diag([1.0, -1.0, -1.0]), [0.0, 0.0, 0.02])
    finger = SimulatedFinger("resistive16", [make_ball("ball", 6.25e-3)], start)
    with pytest.raises(ValueError, match="`band_edges`"):
        TextureSliding(band_edges=[1.0]).run(finger, speed=0.01)
    assert np.array_equal(finger.pose, start)
