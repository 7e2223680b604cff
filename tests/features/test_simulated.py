"""The features on frames of the sensor simulator, one per kind of indenter, known answers."""

import math
from dataclasses import replace

import numpy as np
import pytest

from taxel.features import extract, prepare, sensor_noise
from taxel.frames import make_pose
from taxel.mechanics import make_indenter
from taxel.sensor import calibrate, make_sensor


@pytest.fixture(scope="module")
def vhdta():
    return make_sensor("vhdta128")


def _press(sensor, name, force, position=(0.0, 0.0), angle=0.0, **parameters):
    indenter = make_indenter(name, **parameters)
    return sensor.press(indenter, normal_force=force, position=position, angle=angle, rng=0)


def _pressure_centroid(sensor, frame):
    x, y = sensor.load_grid.coordinates()
    pressure = frame.contact.pressure
    return np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()


@pytest.mark.parametrize(
    ("name", "force", "parameters", "expected"),
    [
        ("pen", 1.0, {}, "point"),
        ("sphere", 5.0, {}, "surface"),  # a 12.5 mm sphere at 5 N: a 5 mm contact
        ("punch", 5.0, {}, "surface"),
        ("edge", 5.0, {}, "line"),
        ("cylinder", 5.0, {}, "line"),
        ("box-edge", 5.0, {}, "line"),
        # a rounded triangle (3.9 mm at 8 N) has three lobes; at 4 N (3.1 mm) its image is
        # flat-topped (saturated) and read as a point while the limit added the whole blur
        ("box-corner", 8.0, {}, "corner"),
        ("box-corner", 4.0, {}, "corner"),
    ],
)
def test_contact_type_of_simulated_frames(vhdta, name, force, parameters, expected):
    frame = _press(vhdta, name, force, position=(1e-3, -2e-3), angle=0.4, **parameters)
    features = extract(frame.raw, vhdta)
    assert features.contact_type == expected
    assert not features.holes.present and not features.slots.present
    # the centre of pressure within half a taxel of the force-weighted centroid
    error = np.linalg.norm(
        np.array(features.contact.centroid_m) - _pressure_centroid(vhdta, frame)
    )
    assert error < 0.5 * vhdta.taxel_pitch[0]


@pytest.mark.parametrize(
    ("radius", "force", "width_mm"),
    [(3e-3, 1.5, 2.92), (6e-3, 1.0, 3.16)],
)
def test_a_sphere_contact_wider_than_the_point_size_is_a_surface(vhdta, radius, force, width_mm):
    # Hertz's pressure is half its peak sqrt(3)/2 of the way to the contact's edge: the
    # half-peak region of these contacts (2.9 and 3.2 mm wide, above the 2.5 mm point size)
    # measures 2.6-2.7 mm, which read as a point against the point size itself
    frame = _press(vhdta, "sphere", force, position=(1e-3, -2e-3), angle=0.4, radius=radius)
    mask = frame.contact.contact
    rows, cols = np.nonzero(mask)
    spacing = vhdta.load_grid.spacing[0]
    points = np.vstack((rows, cols)) * spacing
    variance = np.linalg.eigvalsh(np.cov(points, bias=True)).max() + spacing**2 / 12
    assert 4 * math.sqrt(variance) == pytest.approx(width_mm * 1e-3, abs=0.01e-3)
    features = extract(frame.raw, vhdta)
    assert features.contact_type == "surface"
    assert features.shape.rule == "compact face"


def test_edge_direction_within_two_degrees(vhdta):
    angle = 0.7
    frame = _press(vhdta, "box-edge", 10.0, position=(2e-3, 1e-3), angle=angle)
    line = extract(frame.raw, vhdta).shape.line
    error = abs((line.angle_rad - angle + math.pi / 2) % math.pi - math.pi / 2)
    assert math.degrees(error) < 0.5


def test_can_rim_is_an_arc_of_its_radius(vhdta):
    radius = 26e-3
    frame = _press(vhdta, "can", 10.0, position=(0.0, -radius - 2e-3), rim_radius=radius)
    features = extract(frame.raw, vhdta)
    assert features.contact_type == "arc"
    assert features.shape.circle.radius_m == pytest.approx(radius, rel=0.03)


def test_washer_hole_and_its_radius(vhdta):
    frame = _press(vhdta, "washer", 20.0, position=(2e-3, 0.0))
    features = extract(frame.raw, vhdta)
    assert features.contact_type == "surface"
    assert features.holes.count == 1 and features.holes.diameter_test
    hole = features.holes.items[0]
    assert hole.center_m == pytest.approx((2e-3, 0.0), abs=0.3e-3)
    assert hole.radius_m == pytest.approx(4.2e-3 + 0.2e-3, rel=0.15)  # the hole's flat rim


def test_plate_with_hole_and_plate_with_slot(vhdta):
    holed = extract(_press(vhdta, "hole", 100.0, position=(-3e-3, 4e-3)).raw, vhdta)
    assert holed.contact_type == "surface" and holed.holes.count == 1
    assert not holed.slots.present
    assert holed.holes.items[0].center_m == pytest.approx((-3e-3, 4e-3), abs=0.3e-3)
    slotted = extract(_press(vhdta, "slot", 100.0, angle=0.3).raw, vhdta)
    assert slotted.contact_type == "surface" and slotted.slots.count == 1
    assert not slotted.holes.present
    slot = slotted.slots.items[0]
    assert math.degrees(abs(slot.angle_rad - 0.3)) < 2.0
    assert slot.width_m == pytest.approx(3e-3, rel=0.25)
    assert slot.length_m == pytest.approx(15e-3, rel=0.15)


def test_hole_too_near_the_border_is_not_read_again_from_its_floor(vhdta):
    # a 2.5 mm hole in a gently crowned plate whose wall to the array's border (16.5 mm) is
    # 0.4 mm, under the cover's 1 mm depth: refused at the 25 % level; the contact
    # threshold's basin is its floor, read against the hole's own flanks as a 1.4 mm hole
    # clear of the border
    shape = {"hole_radius": 2.5e-3, "crown_radius": 0.39}
    frame = _press(vhdta, "hole", 111.0, position=(13.6e-3, 9.9e-3), **shape)
    assert not extract(frame.raw, vhdta).holes.present
    # with its wall twice as thick (1.5 taxels more), the hole is found
    frame = _press(vhdta, "hole", 111.0, position=(13.2e-3, 9.9e-3), **shape)
    assert extract(frame.raw, vhdta).holes.count == 1


def test_rasp_is_a_texture(vhdta):
    features = extract(_press(vhdta, "rasp", 40.0).raw, vhdta)
    assert features.contact_type == "surface"
    assert features.shape.rule == "many high points (texture)"
    assert features.texture.maxima_count >= 10
    assert not features.holes.present


def test_position_in_the_base_frame(vhdta):
    frame = _press(vhdta, "pen", 1.0, position=(4e-3, -6e-3))
    pose = make_pose(None, (0.1, 0.2, 0.3))
    features = extract(frame.raw, vhdta, pose=pose)
    expected = np.array([0.1, 0.2, 0.3]) + np.append(_pressure_centroid(vhdta, frame), 0.0)
    assert np.linalg.norm(np.array(features.pose.position_base_m) - expected) < 0.1e-3


def test_sixteen_by_sixteen_pen_and_edge():
    sensor = make_sensor("resistive16")
    pen = extract(_press(sensor, "pen", 2.0, position=(3e-3, 3e-3)).raw, sensor)
    assert pen.contact_type == "point"
    edge = extract(_press(sensor, "edge", 20.0, angle=0.5).raw, sensor)
    assert edge.contact_type == "line"
    error = abs((edge.shape.line.angle_rad - 0.5 + math.pi / 2) % math.pi - math.pi / 2)
    assert math.degrees(error) < 3.0


@pytest.mark.parametrize("position", [(10e-3, -6e-3), (-9e-3, 8e-3)])
def test_sixteen_by_sixteen_washer_cut_by_the_border_is_a_face(position):
    # a 14 mm washer cut by the array's border: its rim, 3.5 taxels in radius, passed the
    # straight tolerance over its 8-10 taxels and read as a face's straight edge (`line`)
    sensor = replace(make_sensor("resistive16"), oversampling=4)
    washer = {"outer_radius": 7e-3, "inner_radius": 3e-3, "edge_radius": 0.15e-3}
    frame = _press(sensor, "washer", 20.0, position=position, **washer)
    shape = extract(frame.raw, sensor).shape
    assert shape.contact_type == "surface"
    assert shape.rule == "face with a curved free outline"


@pytest.mark.parametrize(
    ("length", "radius", "force", "angle"),
    [(16e-3, 5e-3, 5.0, 0.3), (14e-3, 4e-3, 3.0, 1.1), (18e-3, 6e-3, 8.0, 2.0)],
)
def test_sixteen_by_sixteen_short_cylinder_is_a_line(length, radius, force, angle):
    # the cover's 4 mm blur widens a 14-18 mm cylinder's region on the 2 mm array to nearly
    # its length (a compact face, or a face with a closed outline); its signal, the blur
    # taken out, is a band's
    sensor = replace(make_sensor("resistive16"), oversampling=4)
    cylinder = {"radius": radius, "length": length}
    frame = _press(sensor, "cylinder", force, position=(1e-3, -1e-3), angle=angle, **cylinder)
    shape = extract(frame.raw, sensor).shape
    assert (shape.contact_type, shape.rule) == ("line", "straight band")
    error = abs((shape.line.angle_rad - angle + math.pi / 2) % math.pi - math.pi / 2)
    assert math.degrees(error) < 1.0


@pytest.mark.parametrize("pitch", [2e-3, np.float64(2e-3), np.array([2e-3, 2e-3])])
def test_a_sensor_whose_pitch_is_one_number_is_a_sensor(pitch):
    # a duck-typed sensor giving its pitch as one number (as a bare pitch may be) failed in
    # the cover's blur: "'float' object is not subscriptable", "unhashable type"
    sensor = make_sensor("resistive16")

    class Described:
        taxel_pitch = pitch

        def __getattr__(self, name):
            return getattr(sensor, name)

    raw = _press(sensor, "sphere", 2.0).raw
    assert extract(raw, Described()).to_json() == extract(raw, sensor).to_json()


def test_a_4x4_frame_takes_the_sensors_noise():
    # 4 taxels read 8371 against 3040-3101 on a noise-free frame: the 4 interior taxels
    # cannot give the noise (it came out ~3500 codes); the sensor's is 33.2 codes
    sensor = make_sensor("capacitive4x4")
    raw = sensor.press(make_indenter("sphere"), normal_force=0.5).raw
    assert raw[1, 1] == 8371 and raw[0, 1] == 3101
    assert sensor_noise(sensor) == pytest.approx(33.2, abs=0.05)
    features = extract(raw, sensor)
    assert features.contact.present and features.contact_type == "surface"
    assert features.contact.centroid_index == pytest.approx((1.5, 1.5), abs=1e-6)
    assert features.contact.area_m2 == pytest.approx(4 * 25e-6)
    # with the sensor's own noise, an unloaded noisy frame shows no contact
    rest = np.zeros(sensor.load_grid.shape)
    for seed in range(5):
        assert not extract(sensor.frame_from_pressure(rest, rng=seed).raw, sensor).contact.present
    # a calibrated image takes the same noise in pascals, through the sensor's gain: the
    # rest frames' spread once calibrated (the 16 interior taxels' estimate read one taxel
    # at 18 kPa as noise of 5.9 kPa, and found no contact)
    calibration = calibrate(sensor, rng=0)
    rest_pa = [calibration.felt_pressure(sensor.frame_from_pressure(rest, rng=seed).raw)
               for seed in range(40)]  # fmt: skip
    spread = float(np.std(np.array(rest_pa) - np.mean(rest_pa, axis=0)))
    noise_pa = prepare(rest_pa[0], sensor, calibrated=True).raw_noise
    assert noise_pa == pytest.approx(sensor_noise(sensor) / sensor.flat_plate_gain)
    assert noise_pa == pytest.approx(spread, rel=0.15)
    pressed = sensor.press(
        make_indenter("sphere"), normal_force=0.5, position=(3e-3, -2e-3), rng=1
    )
    felt = calibration.felt_pressure(pressed.raw)
    features = extract(felt, sensor, calibrated=True)
    assert features.contact.present
    assert np.unravel_index(np.argmax(felt), felt.shape) == (1, 2)
    assert features.contact.centroid_m == pytest.approx((2.5e-3, -2.5e-3), abs=1.5e-3)
    assert not any(extract(frame, sensor, calibrated=True).contact.present for frame in rest_pa)


def test_noise_sensor_is_asked_for_on_raw_frames_of_a_sensor():
    # resistive16 is large enough to estimate its own noise: the sensor's is opt-in
    sensor = make_sensor("resistive16")
    raw = sensor.press(make_indenter("sphere"), normal_force=1.0).raw
    noise = sensor_noise(sensor)
    # its frames' spread at rest: the readout's noise and each taxel's offset together
    rest = np.zeros(sensor.load_grid.shape)
    frames = np.array([sensor.frame_from_pressure(rest, rng=seed).raw for seed in range(20)])
    assert noise == pytest.approx(np.std(frames - np.median(frames)), rel=0.03)
    assert prepare(raw, sensor).raw_noise == pytest.approx(42.27, abs=0.01)
    assert prepare(raw, sensor, noise="sensor").raw_noise == noise
    with pytest.raises(ValueError, match="`noise='sensor'` is the noise of the sensor's raw"):
        extract(raw.astype(float), sensor, calibrated=True, noise="sensor")
    with pytest.raises(ValueError, match="`noise` must be a number or 'sensor', got 'camera'"):
        extract(raw, sensor, noise="camera")
    with pytest.raises(TypeError, match="`noise='sensor'` needs `sensor_or_pitch` to be a"):
        extract(raw, 2e-3, noise="sensor")
    with pytest.raises(TypeError, match="`sensor` must be a sensor that reads frames"):
        sensor_noise(2e-3)


def test_a_pvdf_frame_falls_with_pressure_and_is_turned_over():
    # piezo8x8 rests at code ~2048 and a press swings its pressed taxels down (to 0 at
    # 1 N): read as it is, the unpressed taxels were the contact (61 of 64 taxels)
    sensor = make_sensor("piezo8x8")
    assert sensor.reading_falls_with_pressure and sensor.flat_plate_gain < 0
    for force in (0.05, 1.0):
        frame = sensor.press(
            make_indenter("sphere"), normal_force=force, position=(3e-3, -2e-3), rng=1
        )
        features = extract(frame.raw, sensor)
        pressed = np.unravel_index(np.argmin(frame.raw), frame.raw.shape)
        assert features.contact.present and features.contact.area_m2 <= 4 * 2.5e-3**2
        assert np.round(features.contact.centroid_index) == pytest.approx(pressed)
        assert features.contact.centroid_m == pytest.approx((3e-3, -2e-3), abs=1.25e-3)
    # a baseline is given in the frame's own units, and turned over with it
    assert prepare(frame.raw, sensor, baseline=2048).baseline == -2048
    # a calibrated image (pressure) is never turned over
    pressure = np.zeros(sensor.shape)
    pressure[2, 5] = 1e4
    assert extract(pressure, sensor, calibrated=True).contact.centroid_index == pytest.approx(
        (2.0, 5.0), abs=0.01
    )
