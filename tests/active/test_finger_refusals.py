"""Refused commands of the simulated finger: a clear error, and the finger left as it was."""

import numpy as np
import pytest

from taxel.active import SimulatedFinger, make_ball
from taxel.frames import make_pose

DOWN = np.diag([1.0, -1.0, -1.0])  # sensor z pointing down at the table
START = make_pose(DOWN, [0.0, 0.0, 0.02])


def _finger():
    return SimulatedFinger("resistive16", [make_ball("ball", 6.25e-3)], START)


@pytest.mark.parametrize(
    ("end", "match"),
    [
        ([0.05, 0.0, 0.02], "no object within the finger's reach"),  # slides off the ball
        ([0.0, 0.0, 0.0], "inside an object"),  # slides down into the ball
    ],
)
def test_a_slide_refused_midway_leaves_the_finger_where_it_was(end, match):
    finger = _finger()
    before = finger.press(normal_force=2.0)
    with pytest.raises(ValueError, match=match) as refused:
        finger.slide([[0.0, 0.0, 0.02], end], speed=0.05, normal_force=2.0)
    assert "the finger went back to where the slide started" in str(refused.value)
    assert np.array_equal(finger.pose, START)
    # the next valid command works, from the same place and time as before the slide
    after = finger.press(normal_force=2.0)
    assert after.travel == pytest.approx(before.travel, rel=1e-6)
    assert after.time == before.time


def test_a_slide_of_too_many_frames_is_refused_before_moving():
    finger = _finger()
    with pytest.raises(ValueError, match=r"`speed` 1e-09 m/s .* frames") as refused:
        finger.slide([[0.0, 0.0, 0.02], [0.001, 0.0, 0.02]], speed=1e-9, normal_force=2.0)
    assert "did not move" in str(refused.value)
    assert np.array_equal(finger.pose, START)
    assert finger.press(normal_force=2.0).normal_force == pytest.approx(2.0)


def test_a_pose_facing_away_from_a_lying_object_is_refused_naming_the_pose():
    finger = _finger()
    up = make_pose(np.eye(3), [0.0, 0.0, 0.02])  # the sensor normal pointing up, off the ball
    with pytest.raises(ValueError, match=r"`pose` must face the sensor down at 'ball'"):
        finger.move_to(up)
    assert np.array_equal(finger.pose, START)
    assert finger.press(normal_force=2.0).normal_force == pytest.approx(2.0)


@pytest.mark.parametrize("name", [5, None, b"ball"])
def test_a_scene_object_s_name_must_be_text(name):
    with pytest.raises(TypeError, match=r"`name` must be a str"):
        make_ball(name, 6.25e-3)
