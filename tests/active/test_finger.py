"""The scene, the probe interface and the simulated finger."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from taxel.active import (
    Box,
    Probe,
    ProfileObject,
    SimulatedFinger,
    make_ball,
    make_hollow_ball,
)
from taxel.frames import make_pose, transform_points
from taxel.mechanics import ElasticMaterial, hertz_sphere, make_indenter
from taxel.sensor import make_sensor

DOWN = np.diag([1.0, -1.0, -1.0])  # sensor z pointing down at the table


@pytest.fixture(scope="module")
def sensor():
    return make_sensor("resistive16")


def test_finger_is_a_probe(sensor):
    finger = SimulatedFinger(sensor, [make_ball("ball", 5e-3)], make_pose(DOWN, [0, 0, 0.02]))
    assert isinstance(finger, Probe)


def test_ray_distances_of_box_faces_and_ball():
    box = Box("box", size=(0.1, 0.08, 0.04), pose=make_pose(translation=[0.2, 0.0, 0.0]))
    origins = np.array([[0.2, 0.0, 0.05], [0.2, 0.01, 0.1], [0.5, 0.0, 0.05]])
    distances = box.ray_distances(origins, [0.0, 0.0, -1.0])
    assert distances[:2] == pytest.approx([0.01, 0.06], abs=1e-9)
    assert np.isinf(distances[2])
    sideways = box.ray_distances(np.array([[0.1, 0.0, 0.02]]), [1.0, 0.0, 0.0])
    assert sideways[0] == pytest.approx(0.05, abs=1e-9)
    ball = make_ball("ball", 5e-3, position=(0.01, 0.0))
    above = ball.ray_distances(np.array([[0.01, 0.0, 0.03], [0.013, 0.0, 0.03]]), [0, 0, -1])
    assert above[0] == pytest.approx(0.02, abs=1e-12)
    assert above[1] == pytest.approx(0.03 - (5e-3 + np.sqrt(25e-6 - 9e-6)), abs=1e-9)
    assert len(box.corners) == 8


# resistive16 has cell centres at odd millimetres: put apexes there, so that first touch on
# the grid is the true first touch
APEX = (0.001, -0.001)  # base frame; the sensor's (1 mm, 1 mm) when facing down at the origin


def test_press_a_rigid_ball_travels_to_touch_plus_indentation(sensor):
    ball = make_ball("steel ball", 6.25e-3, position=APEX)
    finger = SimulatedFinger(sensor, [ball], make_pose(DOWN, [0.0, 0.0, 0.03]))
    reading = finger.press(normal_force=4.0)
    assert reading.normal_force == pytest.approx(4.0, rel=1e-9)
    touch = 0.03 - 12.5e-3
    assert touch < reading.travel < touch + sensor.cover.thickness
    assert reading.travel - touch == pytest.approx(reading.frame.contact.indentation)
    # the object pushes the sensor up: +z in the base frame, with no net torque (centred)
    assert reading.wrench[:3] == pytest.approx([0.0, 0.0, 4.0], abs=1e-9)
    assert reading.pose[2, 3] == pytest.approx(0.03 - reading.travel)


def test_elastic_ball_flattens_on_both_sides(sensor):
    soft = ElasticMaterial(0.45e6, 0.5)
    ball = make_ball("racquet ball", 28.5e-3, soft)
    finger = SimulatedFinger(make_sensor("vhdta128"), [ball], make_pose(DOWN, [0, 0, 0.06]))
    reading = finger.press(normal_force=12.0)
    # the ball's own flattening at the table is Hertz's, against a rigid flat
    table = hertz_sphere(12.0, 28.5e-3, soft.plane_strain_modulus).indentation
    assert ball.support_travel(12.0) == pytest.approx(table, rel=1e-12)
    squeeze = reading.travel - (0.06 - 57e-3)
    assert squeeze > 2 * table * 0.8  # the sensor side flattens about as much again


def test_position_control_of_an_elastic_ball_counts_its_give_at_the_table():
    # depth is the travel past the first touch (`Probe.press`): for a ball that also
    # flattens on the table, the press's approach into the cover plus that give
    ball = make_ball("rubber ball", 15e-3, ElasticMaterial(2e6, 0.49))
    finger = SimulatedFinger(make_sensor("resistive16"), [ball], make_pose(DOWN, [0, 0, 0.035]))
    forced = finger.press(normal_force=6.0)
    finger.retract()
    gap = forced.travel - forced.frame.contact.indentation - ball.support_travel(6.0)
    again = finger.press(depth=forced.travel - gap)
    assert again.frame.contact.normal_force == pytest.approx(6.0, rel=1e-4)
    assert again.travel == pytest.approx(forced.travel, abs=1e-8)


def test_a_hollow_ball_flattens_by_its_shell_at_both_poles():
    wall = ElasticMaterial(3.64e6, 0.5)
    ball = make_hollow_ball("racquet ball", 28.5e-3, 4e-3, wall)
    finger = SimulatedFinger(make_sensor("resistive16"), [ball], make_pose(DOWN, [0, 0, 0.06]))
    reading = finger.press(normal_force=12.0)
    delta = ball.shell.deflection(12.0)
    assert ball.flattening(12.0) == ball.support_travel(12.0) == delta
    contact = reading.frame.contact
    # the travel: the gap (3 mm, to the load grid's nearest cell, 1.4 mm off the top),
    # the cover's indentation by the flattened disc, and both poles' flattening
    gap = reading.travel - contact.indentation - 2 * delta
    assert gap == pytest.approx(0.06 - 57e-3 + 28.5e-3 - np.sqrt(28.5e-3**2 - 2e-6), abs=1e-9)
    # the sensor meets the flattened disc: its area, pi (2 R delta - delta^2), 3.5 cm^2
    disc = np.pi * ball.shell.contact_radius(delta) ** 2
    assert contact.contact_area == pytest.approx(disc, rel=0.1)
    # position control: the force whose press travels the given depth past the first touch
    finger.retract()
    again = finger.press(depth=reading.travel - gap)
    assert again.frame.contact.normal_force == pytest.approx(12.0, rel=1e-4)
    assert again.travel == pytest.approx(reading.travel, abs=1e-8)
    finger.retract()
    with pytest.raises(ValueError, match="`depth` .* needs more than the finger's limit"):
        finger.press(depth=20e-3)
    with pytest.raises(ValueError, match="`depth` 1e-09 m is less than the travel of the"):
        finger.press(depth=1e-9)  # it gave scipy's "f(a) and f(b) must have different signs"


def test_position_control_of_a_hollow_ball_stays_within_its_model():
    # vhdta128's finger gives up to 113 N, the racquet ball's shell model holds to 64 N:
    # the force for a depth is sought below the smaller (it asked the shell for 113 N)
    wall = ElasticMaterial(3.64e6, 0.5)
    ball = make_hollow_ball("racquet ball", 28.5e-3, 4e-3, wall)
    finger = SimulatedFinger(make_sensor("vhdta128"), [ball], make_pose(DOWN, [0, 0, 0.06]))
    assert finger.max_force > ball.largest_force == ball.shell.largest_force
    forced = finger.press(normal_force=12.0)
    finger.retract()
    gap = forced.travel - forced.frame.contact.indentation - 2 * ball.shell.deflection(12.0)
    again = finger.press(depth=forced.travel - gap)
    assert again.frame.contact.normal_force == pytest.approx(12.0, rel=1e-4)
    finger.retract()
    with pytest.raises(ValueError, match="'racquet ball' past what its model describes"):
        finger.press(depth=40e-3)
    # a ball softer than 1 N (the force the test of giving way used) under a light finger
    soft = make_hollow_ball("soft ball", 20e-3, 1e-3, ElasticMaterial(1e6, 0.5))
    assert soft.largest_force < 1.0
    light = SimulatedFinger(
        make_sensor("resistive16"), [soft], make_pose(DOWN, [0, 0, 0.045]), max_force=0.4
    )
    pressed = light.press(normal_force=0.3)
    light.retract()
    gap = pressed.travel - pressed.frame.contact.indentation - 2 * soft.shell.deflection(0.3)
    again = light.press(depth=pressed.travel - gap)
    assert again.frame.contact.normal_force == pytest.approx(0.3, rel=1e-4)


def test_off_centre_contact_gives_a_torque(sensor):
    ball = make_ball("ball", 6.25e-3, position=(0.005, 0.0))
    finger = SimulatedFinger(sensor, [ball], make_pose(DOWN, [0.0, 0.0, 0.02]))
    reading = finger.press(normal_force=2.0)
    torque = reading.wrench[3:]
    lever = np.cross([0.005, 0.0, 0.0], reading.wrench[:3])  # about the sensor origin
    assert torque == pytest.approx(lever, abs=2e-4 * np.abs(lever).max())


def test_tilted_finger_on_a_box_face_touches_at_a_corner_of_the_pad():
    box = Box("box", size=(0.2, 0.2, 0.04))
    rotation = Rotation.from_euler("xyz", [180 + 4, 0, 0], degrees=True).as_matrix()
    finger = SimulatedFinger(make_sensor("resistive16"), [box], make_pose(rotation, [0, 0, 0.045]))
    reading = finger.press(normal_force=3.0)
    rows = np.nonzero(reading.frame.contact.contact.any(axis=1))[0]
    assert rows.max() - rows.min() < 10  # a band along one side, not the whole pad
    assert reading.frame.contact.converged


def test_position_control_and_retract(sensor):
    ball = make_ball("ball", 6.25e-3, position=APEX)
    finger = SimulatedFinger(sensor, [ball], make_pose(DOWN, [0.0, 0.0, 0.02]))
    reading = finger.press(depth=0.2e-3)
    assert reading.travel == pytest.approx(0.02 - 12.5e-3 + 0.2e-3)
    finger.retract()
    assert finger.pose[2, 3] == pytest.approx(0.02)


def test_slide_reads_one_frame_per_period(sensor):
    plate = ProfileObject("foam", profile=make_indenter("foam"), top=0.01)
    finger = SimulatedFinger(sensor, [plate], make_pose(DOWN, [0.0, 0.0, 0.011]))
    path = np.array([[0.0, 0.0, 0.011], [0.005, 0.0, 0.011]])
    readings = finger.slide(path, speed=0.05, normal_force=2.0)
    assert len(readings) == int(0.005 / (0.05 / sensor.frame_rate)) + 1
    assert np.diff([r.time for r in readings]) == pytest.approx(1 / sensor.frame_rate)
    assert all(r.normal_force == pytest.approx(2.0) for r in readings)


def test_bad_commands_leave_the_probe_safe(sensor):
    ball = make_ball("ball", 6.25e-3)
    start = make_pose(DOWN, [0.0, 0.0, 0.02])
    finger = SimulatedFinger(sensor, [ball], start)
    with pytest.raises(ValueError, match="`normal_force` must be <= the finger's limit"):
        finger.press(normal_force=1e4)
    with pytest.raises(ValueError, match="inside an object"):
        finger.move_to(make_pose(DOWN, [0.0, 0.0, 0.005]))
    assert np.array_equal(finger.pose, start)
    finger.move_to(make_pose(DOWN, [0.5, 0.0, 0.02]))
    with pytest.raises(ValueError, match="no object within the finger's reach"):
        finger.press(normal_force=1.0)
    with pytest.raises(ValueError, match="exactly one of"):
        finger.press()


def test_contact_point_maps_to_the_base_frame(sensor):
    ball = make_ball("ball", 6.25e-3, position=(0.1, 0.05))
    pose = make_pose(DOWN, [0.099, 0.051, 0.02])  # the apex under the cell at (1, 1) mm
    finger = SimulatedFinger(sensor, [ball], pose)
    reading = finger.press(normal_force=2.0)
    top = transform_points(reading.pose, [0.0, 0.0, 0.0])
    # the pressed sensor origin sits on the ball's (indented) top
    assert top[:2] == pytest.approx([0.099, 0.051], abs=1e-12)
    assert top[2] == pytest.approx(12.5e-3 - reading.frame.contact.indentation, abs=1e-9)


def test_slide_over_holes_warm_starts_from_material_only(sensor):
    # a perforated screen: frames whose last contact now lies over a hole used to warm-start
    # the solver with pressure on an infinite height (NaN gap)
    plate = ProfileObject("screen", profile=make_indenter("screen"), top=0.01)
    finger = SimulatedFinger(sensor, [plate], make_pose(DOWN, [0.0, 0.0, 0.0105]))
    path = np.array([[0.0, 0.0, 0.0105], [0.008, 0.0, 0.0105]])
    readings = finger.slide(path, speed=0.08, normal_force=3.0)
    assert all(r.normal_force == pytest.approx(3.0) for r in readings)
    assert all(r.frame.contact.converged for r in readings)


def test_a_finger_takes_a_sensor_or_a_preset_name_and_a_list_of_objects(sensor):
    ball = make_ball("ball", 6.25e-3)
    start = make_pose(DOWN, [0.0, 0.0, 0.02])
    by_name = SimulatedFinger("resistive16", [ball], start)
    assert by_name.sensor.name == sensor.name == "resistive16"
    assert by_name.press(normal_force=2.0).normal_force == pytest.approx(2.0)
    with pytest.raises(TypeError, match="`sensor` must be a TactileSensor or a preset name"):
        SimulatedFinger(None, [ball], start)
    with pytest.raises(TypeError, match="`scene` must be a sequence of SceneObject items"):
        SimulatedFinger(sensor, ball, start)
    with pytest.raises(ValueError, match="`scene` must hold at least one object"):
        SimulatedFinger(sensor, [], start)
    with pytest.raises(TypeError, match="`rng` must be None, a numpy.random.Generator"):
        SimulatedFinger(sensor, [ball], start, rng="x")
    with pytest.raises(TypeError, match="`normal_force` must be a real number, got '5'"):
        by_name.press(normal_force="5")


@pytest.mark.parametrize(
    "build", [lambda: make_ball("b", 6e-3, material="x"), lambda: Box("b", material="x")]
)
def test_an_object_s_material_must_be_an_elastic_material(build):
    with pytest.raises(TypeError, match="`material` must be an ElasticMaterial, got 'x'"):
        build()


def test_a_press_at_exactly_the_finger_s_limit_is_not_refused_for_rounding():
    # capacitive4x4's limit is 5 N; the solved force can come back 1 ulp above it
    sensor = make_sensor("capacitive4x4")
    ball = make_ball("ball", 20e-3)
    finger = SimulatedFinger(sensor, [ball], make_pose(DOWN, [0.0, 0.0, 0.045]))
    for x in np.linspace(-2e-3, 2e-3, 5):
        finger.move_to(make_pose(DOWN, [x, 0.0, 0.045]))
        assert finger.press(normal_force=finger.max_force).normal_force == pytest.approx(5.0)
        finger.retract()


def test_the_force_limit_is_a_quarter_of_the_array_at_full_scale_as_written():
    from taxel.active import finger_force_limit
    from taxel.sensor import PRESET_NAMES

    above_a_ball = make_pose(np.diag([1.0, -1.0, -1.0]), [0.0, 0.0, 0.05])
    for name in PRESET_NAMES:
        chosen = make_sensor(name)
        quarter = chosen.full_scale * chosen.geometry.active_area / 4
        assert finger_force_limit(name) == pytest.approx(quarter, rel=1e-12), name
        finger = SimulatedFinger(chosen, [make_ball("ball", 1e-3)], above_a_ball)
        assert finger.max_force == finger_force_limit(chosen), name
    # 200 kPa x 1024 mm^2 / 4 is 51.199999999999996 in floating point; the limit is 51.2 N
    assert finger_force_limit("resistive16") == 51.2
    finger = SimulatedFinger("resistive16", [make_ball("ball", 6.25e-3)], above_a_ball)
    assert finger.press(normal_force=51.2).normal_force == pytest.approx(51.2, rel=1e-9)
