"""Deformation and stiffness from a touch, a light and a firm press (Ellis seed, 2.2)."""

import json
import math

import numpy as np
import pytest

from taxel.active import (
    Deformation,
    PadCalibration,
    SimulatedFinger,
    calibrate_pad,
    make_block,
    make_deformation_object,
    measure_deformation,
)
from taxel.frames import make_pose
from taxel.mechanics import ElasticMaterial
from taxel.sensor import make_sensor

DOWN = np.diag([1.0, -1.0, -1.0])


@pytest.fixture(scope="module")
def calibration():
    return calibrate_pad(radii=(4e-3, 16e-3, 64e-3))


def test_calibration_holds_the_rigid_references(calibration):
    assert calibration.forces.tolist() == [0.5, 12.0, 39.0]
    assert calibration.areas.shape == (3, 5)  # three balls and two cubes
    # a rigid ball of 4 mm radius pushes 0.75 mm into the 1 mm pad at 12 N: the pad's own
    # compression is of the order of what a soft object's deformation would be
    assert calibration.compressions[1, 0] == pytest.approx(0.749e-3, rel=0.02)
    # harder presses compress more; larger contacts less
    assert np.all(np.diff(calibration.compressions, axis=0) > 0)
    assert calibration.compression(39.0, 5e-4) < calibration.compression(39.0, 1e-4)


def test_pad_compression_interpolates_and_extends():
    calibration = PadCalibration(
        forces=np.array([1.0, 2.0]),
        areas=np.array([[1e-5, 4e-5], [1e-5, 4e-5]]),
        compressions=np.array([[4e-4, 1e-4], [8e-4, 2e-4]]),
    )
    # halfway in ln(area): the geometric mean; beyond: the last slope (-1 here) goes on
    assert calibration.compression(1.0, 2e-5) == pytest.approx(2e-4)
    assert calibration.compression(2.0, 8e-5) == pytest.approx(1e-4)
    assert calibration.compression(1.0, 1e-6) == pytest.approx(4e-4)
    with pytest.raises(ValueError, match="`normal_force` must be one of the calibrated"):
        calibration.compression(3.0, 1e-5)


def test_racquet_ball_reproduces_the_seed(calibration):
    result = measure_deformation("racquet ball", calibration=calibration, rng=2)
    assert result.deformable
    # Ellis: 57 mm nominal, 53 mm at 12 N, 47 mm at 39 N. The hollow ball's wall is set by
    # the 53 mm; its bending and air then give 45.8 mm at 39 N (a solid ball: 48.2 mm)
    assert result.unloaded_height == pytest.approx(57.0e-3, abs=0.2e-3)
    assert result.heights[1] == pytest.approx(53.0e-3, abs=0.2e-3)
    assert result.heights[2] == pytest.approx(45.8e-3, abs=0.2e-3)
    assert result.height_change == pytest.approx(7.2e-3, abs=0.2e-3)
    # a shell's deflection grows about linearly (a Hertz contact's as F^(2/3)); the air
    # it compresses stiffens it at the firm press
    assert 0.75 < result.deflection_exponent < 0.95
    # 27 N over the ball's 7.2 mm: about 3.7 kN/m, the pad hardly moves
    assert result.stiffness == pytest.approx(27.0 / 7.2e-3, rel=0.05)
    assert result.deformability > 100
    # the flattened disc grows with the deflection, a^2 = 2 R delta - delta^2
    assert result.area_pixels[2] > 2.0 * result.area_pixels[1]
    json.dumps(result.to_dict())


@pytest.fixture(scope="module")
def small_calibration():
    return calibrate_pad("capacitive4x4", forces=(0.5, 2.0, 4.0))


def test_a_four_by_four_array_sees_its_presses_and_tells_soft_from_rigid(small_calibration):
    # capacitive4x4's finger presses at most 5 N; its image is 4 x 4 taxels, whose 2 x 2
    # interior a press fills: the contact threshold takes the sensor's measured noise
    options = {"sensor": "capacitive4x4", "forces": (2.0, 4.0), "calibration": small_calibration}
    soft = measure_deformation("racquet ball", rng=0, **options)
    assert soft.deformable
    assert soft.area_pixels == (4, 4, 4)  # the central 2 x 2 taxels, 100 mm^2
    # the hollow ball's wall is a spring of about 5.8 kN/m at each pole (the air adds little
    # at small deflections): 2 N more gives 2 x 0.345 mm, and the finger finds 0.68 mm
    # (2.9 kN/m; 3.7 kN/m on vhdta128 from 12 to 39 N, where its air stiffens it)
    assert soft.height_change == pytest.approx(0.69e-3, abs=0.03e-3)
    assert soft.stiffness == pytest.approx(2.0 / 0.69e-3, rel=0.05)
    assert soft.unloaded_height == pytest.approx(57.0e-3, abs=0.2e-3)
    rigid = measure_deformation("steel ball", rng=0, **options)
    assert not rigid.deformable
    assert abs(rigid.height_change) < 1e-6
    assert rigid.deformability < 0.01
    assert rigid.stiffness > 1000 * soft.stiffness
    # the same frames without noise give the same verdicts
    assert measure_deformation("racquet ball", rng=None, **options).deformable


def test_the_noise_is_the_sensor_s_on_small_arrays_only():
    from taxel.active._imaging import frame_noise

    # capacitive4x4's readout noise: 5e-4 of its span, about 30 of its 16-bit counts
    assert frame_noise(make_sensor("capacitive4x4")) == pytest.approx(29.7, abs=0.1)
    for name in ("resistive16", "piezo8x8", "reflective8x8", "harmon10x20", "vhdta128"):
        assert frame_noise(make_sensor(name)) is None  # their images show their own


def test_acrylic_sphere_is_rigid(calibration):
    result = measure_deformation("acrylic sphere", calibration=calibration, rng=2)
    assert not result.deformable
    # the finger travels 0.38 mm further at 39 N, and that is all the pad's
    assert result.travels[2] - result.travels[1] == pytest.approx(0.38e-3, abs=0.02e-3)
    assert abs(result.height_change) < 0.05e-3
    assert result.heights[1] == pytest.approx(12.5e-3, abs=0.05e-3)
    # what is left of the travel after the pad's compression is a small fraction of it
    assert result.deformability < 0.3
    assert result.stiffness > 100 * 27.0 / 4.8e-3


@pytest.mark.parametrize(
    ("shape", "size", "modulus", "deformable"),
    [("ball", 10e-3, 10e6, True), ("ball", 10e-3, 70e9, False), ("block", 20e-3, 1e6, True)],
)
def test_verdict_of_balls_and_blocks(calibration, shape, size, modulus, deformable):
    item = make_deformation_object(
        "sample", shape=shape, size=size, youngs_modulus=modulus, poisson_ratio=0.45
    )
    result = measure_deformation(item, calibration=calibration, rng=3)
    assert result.deformable is deformable


def test_calibration_round_trips_through_a_file(calibration, tmp_path):
    loaded = PadCalibration.load(calibration.save(tmp_path / "pad.json"))
    assert loaded.compression(12.0, 2e-4) == calibration.compression(12.0, 2e-4)
    assert loaded.sensor == "vhdta128"


def test_block_has_a_flat_filleted_face():
    block = make_block("block", 20e-3, ElasticMaterial(1e6, 0.45))
    heights = block.profile.local_heights(np.array([0.0, 9e-3, 9.9e-3, 10.5e-3]), np.zeros(4))
    assert heights[:2].tolist() == [0.0, 0.0]
    assert heights[2] == pytest.approx(1e-3 - math.sqrt(1e-6 - 0.9e-3**2))
    assert math.isinf(heights[3])


def test_bad_commands_leave_the_finger_retracted(calibration):
    sensor = make_sensor("vhdta128")
    ball = make_deformation_object("rubber ball")
    start = make_pose(DOWN, [0.0, 0.0, ball.top + 0.005])
    finger = SimulatedFinger(sensor, [ball], start)
    too_hard = PadCalibration(
        forces=np.array([0.5, 12.0, 500.0]),
        areas=calibration.areas,
        compressions=calibration.compressions,
        sensor="vhdta128",
    )
    with pytest.raises(ValueError, match="`normal_force` must be <= the finger's limit"):
        Deformation(too_hard).run(finger)
    assert np.array_equal(finger.pose, start)
    away = SimulatedFinger(sensor, [ball], make_pose(DOWN, [0.2, 0.0, ball.top + 0.005]))
    with pytest.raises(ValueError, match="no object within the finger's reach"):
        Deformation(calibration).run(away)
    with pytest.raises(ValueError, match="`forces` must be a light and a firm force"):
        measure_deformation("rubber ball", forces=(39.0, 12.0), calibration=calibration)
    with pytest.raises(ValueError, match="`name` must be one of racquet ball"):
        make_deformation_object("jelly")
    # the racquet ball's 4 mm wall in a smaller ball: named by this function's `size`
    with pytest.raises(ValueError, match=r"half the `size` 0.006 m .* 0.004 \('racquet ball'"):
        make_deformation_object("racquet ball", size=6e-3)
    with pytest.raises(ValueError, match="must hold 3 forces"):
        Deformation(
            PadCalibration(
                forces=np.array([12.0]), areas=np.ones((1, 2)), compressions=np.ones((1, 2))
            )
        )


def test_a_touch_too_faint_to_see_is_no_failure(calibration):
    # a 25 mm rigid face touched with 0.05 N is under 100 Pa: no imprint the camera shows;
    # the pad's compression there is taken as zero and the presses that follow decide
    faint = PadCalibration(
        forces=np.array([0.05, 12.0, 39.0]),
        areas=calibration.areas,
        compressions=calibration.compressions,
        sensor=calibration.sensor,
    )
    block = make_deformation_object(
        "acrylic block", shape="block", size=25e-3, youngs_modulus=3.2e9, poisson_ratio=0.37
    )
    top = float(block.top)
    finger = SimulatedFinger(make_sensor("vhdta128"), [block], make_pose(DOWN, [0, 0, top + 5e-3]))
    result = Deformation(faint).run(finger)
    assert result.area_pixels[0] == 0 and result.pad_compressions[0] == 0.0
    assert result.area_pixels[1] > 0
    assert not result.deformable
    assert result.heights[1] == pytest.approx(top, abs=0.05e-3)


def test_a_press_beyond_half_the_object_s_height_is_refused(calibration):
    # a 1 kPa ball 10 cm across would flatten by more than its size at 12 N: linear
    # elasticity no longer describes it, so the finger refuses instead of extrapolating
    with pytest.raises(ValueError, match=r"would compress it by .* more than half its height"):
        measure_deformation(
            "soft ball",
            calibration=calibration,
            shape="ball",
            size=0.05,
            youngs_modulus=1e3,
            poisson_ratio=0.4,
        )


@pytest.mark.parametrize("forces", [(12.0,), (12.0, 39.0, 50.0), 12.0, "12"])
def test_the_presses_are_a_light_and_a_firm_force(calibration, forces):
    with pytest.raises(ValueError, match=r"`forces` must be a \(light, firm\) pair"):
        measure_deformation("rubber ball", forces=forces, calibration=calibration)


def test_a_procedure_is_given_its_calibration_a_probe_and_a_table_height(calibration):
    with pytest.raises(TypeError, match="`calibration` must be a PadCalibration or its file"):
        Deformation(3)
    with pytest.raises(ValueError, match="`table_height` must be finite, got nan"):
        Deformation(calibration, table_height=np.nan)
    with pytest.raises(TypeError, match="`probe` must be a Probe, got 'finger'"):
        Deformation(calibration).run("finger")


@pytest.mark.parametrize(
    ("changes", "match"),
    [
        ({"forces": (0.5,)}, r"`forces` must hold at least 3 distinct forces"),
        ({"forces": (0.5, 12.0, 12.0)}, r"`forces` must hold at least 3 distinct forces"),
        ({"radii": ()}, r"`radii` must hold at least 2 distinct radii, got \[\]"),
        ({"radii": 4e-3}, r"`radii` must be a sequence of numbers, got 0.004"),
    ],
)
def test_a_pad_calibration_needs_the_three_presses_and_small_references(changes, match):
    with pytest.raises(ValueError, match=match):
        calibrate_pad("resistive16", **changes)


def test_reference_balls_between_the_load_grid_s_points_are_left_out_or_refused():
    # capacitive4x4's load grid: 4 x 4 points 5 mm apart, the nearest 3.54 mm from the
    # centre, where the balls are pressed: the 2 mm ball touches none of them
    with pytest.raises(ValueError, match=r"`radii` must be > 3.54 mm for capacitive4x4, got 2 mm"):
        calibrate_pad("capacitive4x4", forces=(0.5, 2.0, 4.0), radii=(2e-3, 8e-3))
    calibration = calibrate_pad("capacitive4x4", forces=(0.5, 2.0, 4.0), rng=None)
    assert calibration.areas.shape == (3, 5 + 2)  # balls of 4-64 mm and the two cubes
    assert np.all(calibration.compressions > 0)
