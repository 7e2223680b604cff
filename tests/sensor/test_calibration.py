"""Per-taxel calibration: round trip, masking of faulty taxels, files, refusals."""

import dataclasses
import json

import numpy as np
import pytest

from taxel.mechanics import make_indenter
from taxel.sensor import (
    Calibration,
    Readout,
    calibrate,
    calibration_error,
    make_sensor,
)
from taxel.sensor._monotone import isotonic_increasing

STATIC = ["harmon10x20", "resistive16", "capacitive4x4", "microbend16", "reflective8x8"]


@pytest.fixture(scope="module")
def sensors():
    return {name: make_sensor(name) for name in [*STATIC, "vhdta128"]}


@pytest.fixture(scope="module")
def vhdta128_calibration(sensors):
    return calibrate(sensors["vhdta128"])


def _between_knots(sensor, count=10):
    # pressures half-way between the 21 calibration pressures (of the sensors of STATIC)
    return (np.arange(count) * 2 + 1) / (2 * count) * sensor.full_scale


@pytest.mark.parametrize("name", STATIC)
def test_round_trip_within_two_percent_of_full_scale_without_noise(sensors, name):
    sensor = sensors[name]
    calibration = calibrate(sensor)
    assert calibration.valid.all()
    error = calibration_error(sensor, calibration, pressures=_between_knots(sensor))
    assert error.worst < 0.02
    assert error.worst < 0.002  # in fact a tenth of that: 0.11 % for microbend16
    assert not error.noisy


def test_vhdta128_round_trip_within_two_percent_up_to_sixty_psi(sensors, vhdta128_calibration):
    # The textured membrane saturates at 1.6 x 60 psi, so the image is still graded at full
    # scale; there, and at the array's corners (which feel 37 % of a plate's pressure), one
    # camera level spans 2.5-3 % of full scale, so even a perfect map errs by over 1.2 %.
    # The 81 plates straddle every level; pressures between them test the interpolation.
    sensor = sensors["vhdta128"]
    assert sensor.full_scale == pytest.approx(60 * 6894.757)
    assert 1.5 * sensor.full_scale < sensor.transducer.saturation_pressure
    assert vhdta128_calibration.pressures.size == 81 and vhdta128_calibration.valid.all()
    error = calibration_error(sensor, vhdta128_calibration)
    assert error.pressures.size == 321 and error.pressures[-1] == sensor.full_scale
    assert error.measuring_range() == sensor.full_scale
    assert 0.01 < error.worst < 0.02  # bounded below by the grey level: 1.88 %
    coarse = calibrate(sensor, n_levels=21)  # plates 5 % apart: a level can fall between
    assert calibration_error(sensor, coarse).worst > 0.02


@pytest.mark.parametrize(
    ("name", "rms", "worst"),
    [
        ("harmon10x20", 0.0004, 0.0014),
        ("resistive16", 0.0023, 0.0092),
        ("capacitive4x4", 0.0006, 0.0022),
        ("microbend16", 0.0033, 0.021),
        ("reflective8x8", 0.0015, 0.0062),
    ],
)
def test_round_trip_error_with_the_default_noise(sensors, name, rms, worst):
    sensor = sensors[name]
    error = calibration_error(sensor, calibrate(sensor, rng=0), rng=1)
    assert error.noisy
    assert error.rms == pytest.approx(rms, rel=0.15)
    assert error.worst == pytest.approx(worst, rel=0.15)


def test_dead_stuck_and_saturated_taxels_are_masked(sensors):
    sensor = sensors["resistive16"]
    faulty = dataclasses.replace(
        sensor,
        readout=dataclasses.replace(sensor.readout, dead=0.04, stuck=0.03, saturated=0.02),
    )
    faults = faulty.readout_chain.pattern.faults
    calibration = calibrate(faulty, rng=3)
    assert np.array_equal(calibration.valid, faults.working)
    assert np.array_equal(calibration.pinned, faults.dead | faults.saturated)
    assert (~calibration.valid).sum() == 10 + 8 + 5
    frame = faulty.frame_from_pressure(np.full(sensor.load_grid.shape, 1e5), rng=4)
    pressure = calibration.apply(frame.raw)
    assert np.array_equal(np.isnan(pressure), ~faults.working)
    assert np.nanmax(np.abs(pressure - 1e5)) < 0.01 * sensor.full_scale


def test_camera_sensor_masks_faulty_pixels_without_an_adc(sensors):
    sensor = sensors["vhdta128"]
    faulty = dataclasses.replace(
        sensor, readout=Readout(bits=None, dead=0.01, stuck=0.01, saturated=0.01, unit_seed=1)
    )
    calibration = calibrate(faulty, n_levels=6, repeats=2, rng=2)
    assert np.array_equal(calibration.valid, faulty.readout_chain.pattern.faults.working)
    assert (~calibration.valid).sum() == 3 * 164


def test_microbend_is_calibrated_per_fibre(sensors):
    sensor = sensors["microbend16"]
    calibration = calibrate(sensor, n_levels=8)
    assert calibration.shape == (32,)
    assert calibration.direction == -1  # light is lost as the load grows
    frame = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 4e4))
    assert np.abs(calibration.apply(frame.raw) - 4e4).max() < 0.01 * sensor.full_scale


def test_apply_takes_a_stack_of_frames_and_extends_or_clips_the_range(sensors):
    sensor = sensors["capacitive4x4"]
    calibration = calibrate(sensor, n_levels=11)
    frames = np.stack(
        [
            sensor.frame_from_pressure(np.full(sensor.load_grid.shape, p)).raw
            for p in (0.0, 1e4, 2.5e4)
        ]
    )
    pressure = calibration.apply(frames)
    assert pressure.shape == (3, 4, 4)
    assert np.allclose(pressure[:, 0, 0], [0.0, 1e4, 2.5e4], atol=10.0)
    below = calibration.apply(np.zeros((4, 4)))  # below rest: the slope there continues
    assert np.all((below < -2e3) & (below > -3e3))  # 2978 codes below rest, ~1 Pa each
    assert np.all(calibration.apply(np.zeros((4, 4)), clip=True) == 0.0)
    assert np.all(calibration.apply(np.full((4, 4), 65535)) == sensor.full_scale)
    with pytest.raises(ValueError, match="`raw` must end in the calibrated shape"):
        calibration.apply(np.zeros((3, 3)))


def test_flat_runs_of_readings_return_the_middle_of_their_pressures():
    readings = np.array([0.0, 1.0, 2.0, 2.0, 2.0, 3.0])[:, None]
    calibration = Calibration(
        "toy",
        np.arange(6.0),
        readings,
        np.ones(1, bool),
        np.zeros(1, bool),
        np.zeros(1, bool),
        np.zeros(1),
        5.0,
        1,
    )
    assert calibration.apply(np.array([[2.0], [1.0], [0.5]])).ravel().tolist() == [
        3.0,
        1.0,
        pytest.approx(0.5, abs=0.1),
    ]


def _pool_adjacent_violators(values):
    blocks = []  # [sum, count]
    for value in values:
        blocks.append([value, 1])
        while len(blocks) > 1 and blocks[-2][0] / blocks[-2][1] > blocks[-1][0] / blocks[-1][1]:
            total, count = blocks.pop()
            blocks[-1][0] += total
            blocks[-1][1] += count
    return np.concatenate([np.full(count, total / count) for total, count in blocks])


def test_isotonic_regression_matches_pool_adjacent_violators():
    rng = np.random.default_rng(0)
    values = np.cumsum(rng.normal(0.2, 1.0, (17, 50)), axis=0)
    fitted = isotonic_increasing(values)
    expected = np.stack([_pool_adjacent_violators(column) for column in values.T], axis=1)
    assert np.allclose(fitted, expected)
    assert np.all(np.diff(fitted, axis=0) >= -1e-12)


def test_a_failed_save_keeps_the_old_file_and_leaves_no_partial_one(
    tmp_path, sensors, monkeypatch
):
    calibration = calibrate(sensors["reflective8x8"], rng=5, repeats=3)
    path = calibration.save(tmp_path / "reflective.npz")
    before = path.read_bytes()

    def disk_full(stream, **arrays):
        stream.write(b"PK\x03\x04 half a zip")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(np, "savez", disk_full)
    with pytest.raises(OSError, match="No space left on device") as failure:
        calibration.save(path, overwrite=True)
    assert failure.value.filename == str(path)
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["reflective.npz"]


def test_save_and_load(tmp_path, sensors):
    sensor = sensors["reflective8x8"]
    calibration = calibrate(sensor, rng=5, repeats=3)
    path = calibration.save(tmp_path / "reflective.npz")
    again = Calibration.load(path)
    assert again.sensor_name == "reflective8x8" and again.repeats == 3
    assert np.array_equal(again.readings, calibration.readings)
    assert np.array_equal(again.valid, calibration.valid)
    raw = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 1.5e3), rng=6).raw
    assert np.array_equal(again.apply(raw), calibration.apply(raw))
    with pytest.raises(
        FileExistsError, match="`path` '.*reflective.npz' exists; pass overwrite=True"
    ):
        calibration.save(path)
    calibration.save(path, overwrite=True)
    with pytest.raises(ValueError, match="must end in .npz"):
        calibration.save(tmp_path / "reflective.json")
    bad = tmp_path / "bad.npz"
    np.savez(bad, readings=np.zeros((3, 2)))
    with pytest.raises(ValueError, match="not a taxel calibration file"):
        Calibration.load(bad)
    with pytest.raises(FileNotFoundError, match="no such file"):
        Calibration.load(tmp_path / "none.npz")


def _claiming_member(path, shape):
    """An .npz archive whose one array's header claims `shape` of float64 over 64 bytes."""
    import io
    import zipfile

    member = io.BytesIO()
    header = {"descr": "<f8", "fortran_order": False, "shape": shape}
    np.lib.format.write_array_header_1_0(member, header)
    member.write(bytes(64))
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("readings.npy", member.getvalue())
    return path


def test_a_damaged_calibration_file_is_refused_naming_it(tmp_path):
    # numpy.load believed the headers: 8 TB allocated (a MemoryError) before it found the
    # data missing, and a text file was offered for unpickling
    huge = _claiming_member(tmp_path / "huge.npz", (10**6, 10**6))
    with pytest.raises(
        ValueError,
        match=r"huge\.npz: not a taxel calibration file \(truncated or corrupt: its header "
        r"claims shape \(1000000, 1000000\) of float64 \(8000000000000 bytes\), but 64 bytes "
        r"follow\)",
    ):
        Calibration.load(huge)
    single = tmp_path / "single.npz"  # one array saved with np.save, under an .npz name
    with open(single, "wb") as stream:
        np.save(stream, np.ones(3))
    text = tmp_path / "text.npz"
    text.write_text("pressures, readings\n1, 2\n")
    empty = tmp_path / "empty.npz"
    empty.write_bytes(b"")
    for path, problem in [
        (single, "one array (.npy), not an .npz archive"),
        (text, "not an .npz archive: a text or image file?"),
        (empty, "the file is empty"),
    ]:
        with pytest.raises(ValueError) as refused:
            Calibration.load(path)
        assert str(refused.value) == f"{path}: not a taxel calibration file ({problem})"


def test_a_calibration_with_a_corrupt_compressed_array_is_refused(
    tmp_path, sensors, spoil_deflate
):
    sensor = sensors["capacitive4x4"]
    good = tmp_path / "good.npz"
    calibrate(sensor, n_levels=6).save(good)
    with np.load(good) as stored:
        arrays = dict(stored)
    packed = tmp_path / "packed.npz"
    np.savez_compressed(packed, **arrays)
    assert Calibration.load(packed).sensor_name == "capacitive4x4"
    spoil_deflate(packed, "readings.npy")  # the readings' deflate stream
    with pytest.raises(ValueError, match=r"packed\.npz: not a taxel calibration file \("):
        Calibration.load(packed)


def test_sensors_that_cannot_be_calibrated_per_taxel_say_why():
    with pytest.raises(ValueError, match="senses only changes of load"):
        calibrate(make_sensor("piezo8x8"))
    with pytest.raises(ValueError, match="photoelastic: a flat plate makes no fringes"):
        calibrate(make_sensor("photoelastic64"))


def test_bad_calibration_arguments(sensors):
    sensor = sensors["capacitive4x4"]
    with pytest.raises(ValueError, match="`pressures` must hold at least 4 increasing"):
        calibrate(sensor, pressures=[0.0, 2e4, 1e4, 3e4])
    with pytest.raises(ValueError, match="`n_levels` must be >= 4, got 2"):
        calibrate(sensor, n_levels=2)
    with pytest.raises(ValueError, match="`repeats` must be >= 1, got 0"):
        calibrate(sensor, repeats=0)
    with pytest.raises(ValueError, match="`min_response` must lie in"):
        calibrate(sensor, min_response=1.5)
    with pytest.raises(TypeError, match="`sensor` must be a TactileSensor"):
        calibrate("capacitive4x4")
    with pytest.raises(ValueError, match="`pressures` must lie in \\[0, full_scale"):
        calibration_error(sensor, calibrate(sensor, n_levels=4), pressures=[1e6])


def test_felt_pressure_is_the_stress_at_depth_under_any_load(sensors):
    # a plate over the array loads its edge taxels less; a sphere by the edge shows it
    sensor = dataclasses.replace(sensors["resistive16"], readout=Readout(bits=16))
    calibration = calibrate(sensor)
    assert calibration.felt_fraction[8, 8] == pytest.approx(1.0, abs=1e-3)
    assert calibration.felt_fraction[0, 0] == pytest.approx(0.81, abs=0.01)
    frame = sensor.press(make_indenter("sphere"), normal_force=0.3, position=(-15e-3, -15e-3))
    felt = -frame.fields.stress
    assert felt[0, 0] > 0.2 * felt.max()  # the corner taxel is loaded
    error = np.abs(calibration.felt_pressure(frame.raw) - felt)
    assert error.max() < 1e-3 * sensor.full_scale
    plate_equivalent = calibration.apply(frame.raw)
    assert plate_equivalent[0, 0] == pytest.approx(felt[0, 0] / 0.81, rel=0.02)


def test_noise_about_no_load_stays_zero_mean(sensors):
    sensor = sensors["resistive16"]
    calibration = calibrate(sensor, rng=0)
    rest = sensor.frame_from_pressure(np.zeros(sensor.load_grid.shape)).quantity
    frames = np.stack([sensor.read(rest, rng=seed) for seed in range(40)])
    pressure = calibration.apply(frames)
    # 40 x 256 readings with 0.5 kPa of noise: the mean is within 3 standard errors of 0
    noise = pressure.std()
    assert 0.3e3 < noise < 1e3
    assert abs(pressure.mean()) < 3 * noise / np.sqrt(pressure.size) + 20.0
    clipped = calibration.apply(frames, clip=True)
    assert clipped.mean() > 0.3 * noise  # clipping at 0 biases an unloaded sensor


def test_counts_and_rng_of_a_calibration_are_checked(sensors):
    sensor = sensors["capacitive4x4"]
    with pytest.raises(ValueError, match="`n_levels` must be finite, got nan"):
        calibrate(sensor, n_levels=np.nan)
    with pytest.raises(ValueError, match="`repeats` must be a whole number, got 2.5"):
        calibrate(sensor, repeats=2.5, rng=0)
    for rng, error in (("x", TypeError), (1.5, TypeError), (True, TypeError), (-1, ValueError)):
        with pytest.raises(error, match="`rng`"):
            calibrate(sensor, rng=rng)


def test_readings_below_no_load_are_flagged_past_the_noise():
    sensor = make_sensor("resistive16")
    calibration = calibrate(sensor, rng=3)
    rest = calibration.readings[0]
    assert not calibration.below_rest(rest).any()
    assert not calibration.below_rest(calibration.readings[-1]).any()
    # the noise of frames at rest stays within the margin
    frames = np.array(
        [
            sensor.frame_from_pressure(np.zeros(sensor.load_grid.shape), rng=seed).raw
            for seed in range(10)
        ]
    )
    assert not calibration.below_rest(frames).any()
    assert calibration.below_rest(np.full((2, 16, 16), -50)).all()
    with pytest.raises(ValueError, match=r"`raw` must end in the calibrated shape \(16, 16\)"):
        calibration.below_rest(np.zeros((4, 4)))


def test_a_file_without_a_calibrations_arrays_names_what_it_lacks(tmp_path):
    path = tmp_path / "other.npz"
    np.savez(path, a=np.zeros(3))
    with pytest.raises(ValueError) as refused:
        Calibration.load(path)
    assert str(refused.value) == (
        f"{path}: not a taxel calibration file: it lacks the array(s) felt_fraction, meta, "
        "noise, pinned, pressures, readings, unresponsive that `taxel calibrate` writes (it "
        "holds a)"
    )
    good = tmp_path / "good.npz"
    calibrate(make_sensor("capacitive4x4")).save(good)
    with np.load(good) as stored:
        arrays = dict(stored)
    meta = json.loads(str(arrays["meta"]))
    del meta["repeats"]
    arrays["meta"] = np.array(json.dumps(meta))
    np.savez(path, **arrays)
    with pytest.raises(ValueError, match=r"not a taxel calibration file: its meta lacks repeats$"):
        Calibration.load(path)
    # meta values that are no full scale or count: "could not convert string to float",
    # without the file, or a negative full scale accepted
    for key, value, problem in (
        ("full_scale", "abc", "full_scale must be a pressure > 0 [Pa], got 'abc'"),
        ("full_scale", -5.0, "full_scale must be a pressure > 0 [Pa], got -5.0"),
        ("full_scale", [1], "full_scale must be a pressure > 0 [Pa], got [1]"),
        ("repeats", "x", "repeats must be a whole number >= 1, got 'x'"),
        ("repeats", 2.5, "repeats must be a whole number >= 1, got 2.5"),
    ):
        changed = json.loads(str(np.load(good)["meta"]))
        changed[key] = value
        np.savez(path, **{**arrays, "meta": np.array(json.dumps(changed))})
        with pytest.raises(ValueError) as refused:
            Calibration.load(path)
        assert str(refused.value) == f"{path}: its meta's {problem}"
