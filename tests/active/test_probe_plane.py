"""Contact points, plane probing and corner location on objects with known geometry."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from taxel.active import (
    Box,
    ProfileObject,
    SimulatedFinger,
    box_corner_frame,
    calibrate_contact_points,
    corner_probing_trial,
    estimate_contact_point,
    fit_plane,
    locate_corner,
    plane_probing_trial,
    probe_plane,
)
from taxel.frames import make_pose, transform_directions, transform_points
from taxel.mechanics import Sphere
from taxel.sensor import make_sensor

DOWN = np.diag([1.0, -1.0, -1.0])


@pytest.fixture(scope="module")
def sensor():
    return make_sensor("resistive16")


@pytest.fixture(scope="module")
def calibration(sensor):
    return calibrate_contact_points(sensor)


def test_calibration_reads_flat_presses_back(sensor, calibration):
    for pressure in (10e3, 80e3, 150e3):
        frame = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, pressure), rng=3)
        equivalent = calibration.equivalent_pressure(frame.raw)
        assert np.median(equivalent) == pytest.approx(pressure, rel=0.01)
        assert np.abs(equivalent - pressure).max() < 4 * calibration.noise + 0.02 * pressure
    assert 0 < calibration.noise < 2e3  # a fraction of a percent of the 200 kPa range


def test_contact_point_of_a_tilted_face_lies_on_the_face(sensor, calibration):
    # a pad tilted by 6 degrees over a flat box top touches with one side only: the pad is
    # compressed there by a few tenths of a millimetre, and the contact point must sit on
    # the true face within a few tens of micrometres
    box = Box("box", size=(0.2, 0.2, 0.04))
    tilt = Rotation.from_euler("x", 6, degrees=True).as_matrix()
    finger = SimulatedFinger(sensor, [box], make_pose(tilt @ DOWN, [0.01, 0.0, 0.06]), rng=1)
    reading = finger.press(normal_force=6.0)
    contact = estimate_contact_point(reading.frame.raw, reading.normal_force, sensor, calibration)
    point = transform_points(reading.pose, contact.point)
    assert contact.touches_border
    assert 20e-6 < contact.compression < 0.6e-3
    assert point[2] == pytest.approx(0.04, abs=30e-6)
    # the point is where the true contact is (its pressure-weighted centre), within a taxel
    truth = reading.frame.contact
    x, y = sensor.load_grid.coordinates()
    weight = truth.pressure / truth.pressure.sum()
    true_xy = np.array([(weight * x).sum(), (weight * y).sum()])
    assert np.linalg.norm(contact.point[:2] - true_xy) < 2e-3


def test_flat_contact_gives_the_face_normal(sensor, calibration):
    box = Box("box", size=(0.2, 0.2, 0.04))
    finger = SimulatedFinger(sensor, [box], make_pose(DOWN, [0.0, 0.0, 0.05]), rng=2)
    reading = finger.press(normal_force=10.0)
    contact = estimate_contact_point(reading.frame.raw, reading.normal_force, sensor, calibration)
    assert contact.n_cells == 256
    normal = transform_directions(reading.pose, contact.normal)
    assert np.degrees(np.arccos(normal @ [0.0, 0.0, 1.0])) < 0.5
    assert transform_points(reading.pose, contact.point)[2] == pytest.approx(0.04, abs=5e-6)


def test_fit_plane_recovers_a_known_plane():
    rng = np.random.default_rng(0)
    normal = np.array([0.1, -0.2, 1.0]) / np.linalg.norm([0.1, -0.2, 1.0])
    points = rng.uniform(-0.05, 0.05, (20, 3))
    points -= np.outer(points @ normal - 0.01, normal)  # onto n . p = 0.01
    found, centroid, distances = fit_plane(points, outward=[0, 0, 1])
    assert found == pytest.approx(normal, abs=1e-12)
    assert centroid @ found == pytest.approx(0.01, abs=1e-12)
    assert np.abs(distances).max() < 1e-12


@pytest.mark.parametrize(
    ("outward", "match"),
    [
        ([0, 1], r"`outward` must be a non-zero 3-vector, got \[0.0, 1.0\]"),
        ([0, 0, 0], "`outward` must be a non-zero 3-vector"),
        ([np.nan, 0, 0], "`outward` must be finite everywhere"),
        ([1, 0, 0], r"`outward` \[1.0, 0.0, 0.0\] lies in the fitted plane"),
    ],
)
def test_fit_plane_needs_an_outward_direction_off_the_plane(outward, match):
    points = [[0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]]
    with pytest.raises(ValueError, match=match):
        fit_plane(points, outward=outward)
    assert fit_plane(points, outward=[1, 0, -0.1])[0].tolist() == [0.0, 0.0, -1.0]


def test_probe_plane_on_a_tilted_box(sensor, calibration):
    tilt = Rotation.from_euler("xy", [4, -7], degrees=True)
    box = Box("box", size=(0.2, 0.2, 0.05), pose=make_pose(tilt))
    corners = [(-0.05, -0.05), (0.05, -0.05), (-0.05, 0.05), (0.05, 0.05), (0.0, 0.0)]
    poses = [make_pose(DOWN, [x, y, 0.08]) for x, y in corners]
    finger = SimulatedFinger(sensor, [box], poses[0], rng=4)
    plane = probe_plane(finger, poses, calibration=calibration)
    true = tilt.apply([0.0, 0.0, 1.0])
    assert np.degrees(np.arccos(plane.normal @ true)) < 0.05
    assert plane.residual < 20e-6
    top = transform_points(box.pose, [0.0, 0.0, 0.05])
    assert np.abs((plane.contact_points - top) @ true).max() < 50e-6
    assert len(plane.steps) == 5 and plane.steps[0].normal_force == pytest.approx(5.0)
    assert set(plane.to_dict()) >= {"normal", "residual_m", "contact_points_m", "steps"}


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_five_probes_at_random_poses_meet_the_one_degree_target(seed):
    trial = plane_probing_trial(n_probes=5, seed=seed)
    assert np.degrees(trial.normal_error) < 0.2  # the target is 1 degree
    assert np.abs(trial.point_errors).max() < 0.1e-3
    assert trial.to_dict()["n_probes"] == 5


def test_a_ball_is_not_planar(sensor, calibration):
    ball = ProfileObject("big ball", profile=Sphere(0.05), top=0.1)
    offsets = [(-0.04, -0.04), (0.04, -0.04), (-0.04, 0.04), (0.04, 0.04), (0.0, 0.0)]
    poses = [make_pose(DOWN, [x, y, 0.11]) for x, y in offsets]
    finger = SimulatedFinger(sensor, [ball], poses[0])
    plane = probe_plane(finger, poses, calibration=calibration)
    # a flat pad touches a convex object at its highest point under the pad: the apex for
    # the centre probe, the pad's inner corner cell (centre 15 mm from the pad's centre, so
    # (25, 25) mm off the apex) for the others, 50 - sqrt(50^2 - 2 * 25^2) = 14.6 mm lower;
    # the RMS residual of heights (0, 0, 0, 0, 14.6) mm about their mean plane is 0.4 * 14.6
    assert plane.residual == pytest.approx(5.86e-3, rel=0.05)
    assert plane.normal @ [0.0, 0.0, 1.0] > 0.999


def test_box_corner_frames_are_right_handed_and_point_into_the_box():
    box = Box("box", size=(0.1, 0.08, 0.06), pose=make_pose(translation=[0.3, 0.1, 0.0]))
    centre = transform_points(box.pose, [0.0, 0.0, 0.03])
    for index in range(8):
        frame = box_corner_frame(box, index)
        assert np.linalg.det(frame[:3, :3]) == pytest.approx(1.0)
        inward = centre - frame[:3, 3]
        assert np.all(frame[:3, :3].T @ inward > 0)
    with pytest.raises(ValueError, match="`index` must be an integer in"):
        box_corner_frame(box, 8)


def test_corner_within_the_one_millimetre_target():
    trial = corner_probing_trial(seed=5, guess_error=4e-3)
    assert trial.corner_error < 0.1e-3  # the target is 1 mm
    assert np.degrees(trial.edge_errors).max() < 0.2
    assert trial.estimate.residual < 20e-6
    assert len(trial.estimate.steps) == 9
    assert trial.to_dict()["corner_error_m"] == trial.corner_error


def test_bad_commands_raise_and_leave_the_finger_safe(sensor, calibration):
    box = Box("box", size=(0.1, 0.1, 0.04))
    start = make_pose(DOWN, [0.0, 0.0, 0.06])
    finger = SimulatedFinger(sensor, [box], start)
    with pytest.raises(ValueError, match="`poses` must hold at least 3 poses, got 2"):
        probe_plane(finger, [start, start])
    line = [make_pose(DOWN, [x, 0.0, 0.06]) for x in (-0.02, 0.0, 0.02)]
    with pytest.raises(ValueError, match="lie on one line"):
        probe_plane(finger, line)
    assert np.array_equal(finger.pose, start)  # validated before any motion
    off = make_pose(DOWN, [0.3, 0.02, 0.06])  # beyond the box's edge
    poses = [start, make_pose(DOWN, [0.02, 0.0, 0.06]), off]
    with pytest.raises(ValueError, match=r"probe 3 at \(300.0, 20.0, 60.0\) mm: no object"):
        probe_plane(finger, poses, calibration=calibration)
    with pytest.raises(ValueError, match="`normal_force` must be <= the finger's limit"):
        triangle = [start, poses[1], make_pose(DOWN, [0.0, 0.02, 0.06])]
        probe_plane(finger, triangle, normal_force=1e3)
    # retracted: the finger is back at an approach pose and presses normally again
    assert np.array_equal(finger.pose, start)
    finger.move_to(start)
    assert finger.press(normal_force=2.0).normal_force == pytest.approx(2.0)
    with pytest.raises(ValueError, match="`normal_force` must be > 0"):
        probe_plane(finger, poses, normal_force=-1.0)
    with pytest.raises(ValueError, match="piezo8x8"):
        calibrate_contact_points(make_sensor("piezo8x8"))
    with pytest.raises(TypeError, match="`probe` must be a Probe, got 'finger'"):
        probe_plane("finger", poses)
    with pytest.raises(ValueError, match="`n_levels` must be a whole number, got 2.5"):
        calibrate_contact_points(sensor, n_levels=2.5)
    with pytest.raises(TypeError, match="`rng` must be None, a numpy.random.Generator"):
        calibrate_contact_points(sensor, rng="x")
    with pytest.raises(ValueError, match="`n_probes` must be an integer >= 3, got 2"):
        plane_probing_trial(n_probes=2)
    with pytest.raises(ValueError, match="`sensor` must be one of"):
        plane_probing_trial("nosuch")


def test_corner_guess_off_the_box_raises():
    box = Box("box", size=(0.12, 0.1, 0.07))
    guess = box_corner_frame(box, 7)
    guess[:3, 3] += [0.2, 0.0, 0.0]
    finger = SimulatedFinger(make_sensor("resistive16"), [box], make_pose(translation=[0, 0, 0.2]))
    with pytest.raises(ValueError, match="face 1 probe 1 at .* mm: no object within"):
        locate_corner(finger, guess)


@pytest.mark.parametrize(
    ("seed", "error", "match"),
    [("x", TypeError, "`seed` must be a real number"), (-1, ValueError, "`seed` must be >= 0")],
)
def test_a_trial_seed_is_a_whole_number_at_least_zero(seed, error, match):
    with pytest.raises(error, match=match):
        plane_probing_trial(seed=seed)
    with pytest.raises(error, match=match):
        corner_probing_trial(seed=seed)


def test_a_corner_is_located_with_the_smallest_preset_at_its_force_limit():
    # capacitive4x4's finger is limited to exactly the 5 N the probing presses with
    trial = corner_probing_trial("capacitive4x4", seed=0)
    assert trial.corner_error < 0.1e-3


class _FailingArm:
    """A driver whose arm refuses the `fail_at`-th press with its own error (not ValueError)."""

    def __init__(self, finger, fail_at):
        self.finger, self.fail_at, self.presses, self.pressed = finger, fail_at, 0, False
        self.sensor = finger.sensor

    @property
    def pose(self):
        return self.finger.pose

    def move_to(self, pose):
        self.finger.move_to(pose)

    def press(self, *, normal_force=None, depth=None):
        self.presses += 1
        self.pressed = True  # the arm has started pressing when its limit trips
        if self.presses == self.fail_at:
            raise RuntimeError("force beyond the arm's limit")
        return self.finger.press(normal_force=normal_force, depth=depth)

    def slide(self, path, *, speed, normal_force):
        return self.finger.slide(path, speed=speed, normal_force=normal_force)

    def retract(self):
        self.pressed = False
        self.finger.retract()


def test_a_driver_error_passes_unchanged_after_the_retract(sensor, calibration):
    # a driver's own error (not a ValueError) must not leave the arm pressed on the object
    box = Box("box", size=(0.1, 0.1, 0.04))
    poses = [make_pose(DOWN, [x, y, 0.06]) for x, y in ((0, 0), (0.02, 0), (0, 0.02))]
    arm = _FailingArm(SimulatedFinger(sensor, [box], poses[0]), fail_at=2)
    with pytest.raises(RuntimeError, match="force beyond the arm's limit"):
        probe_plane(arm, poses, calibration=calibration)
    assert arm.presses == 2 and not arm.pressed
    corner_box = Box("box", size=(0.1, 0.08, 0.06))
    guess = box_corner_frame(corner_box, 0)
    arm = _FailingArm(SimulatedFinger(sensor, [corner_box], make_pose(DOWN, [0, 0, 0.1])), 4)
    with pytest.raises(RuntimeError, match="force beyond the arm's limit"):
        locate_corner(arm, guess, calibration=calibration)
    assert arm.presses == 4 and not arm.pressed
