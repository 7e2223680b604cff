"""Frustrated TIR sensor (Figure 25.9): eq. 25.19, contact area, camera and scratches."""

import math

import numpy as np
import pytest

from taxel.transducers import (
    FtirTransducer,
    Transducer,
    camera_image,
    contact_area_fraction,
    critical_angle,
    glass_scratches,
    is_totally_reflected,
    pressure_from_contact_fraction,
)


def test_eq_25_19_and_the_critical_angle():
    theta = critical_angle(waveguide_index=1.49)
    assert theta == pytest.approx(math.asin(1 / 1.49), rel=1e-15)
    below, above = theta - 1e-9, theta + 1e-9
    assert not is_totally_reflected(below, waveguide_index=1.49)
    assert is_totally_reflected(above, waveguide_index=1.49)
    # as printed, n2 sin(alpha) <= n1 holds exactly for the rays that escape
    angles = np.linspace(0, np.pi / 2, 91)
    printed = 1.49 * np.sin(angles) <= 1.0
    escaping = ~is_totally_reflected(angles, waveguide_index=1.49)
    assert np.array_equal(printed[angles != theta], escaping[angles != theta])


def test_window_of_angles_trapped_by_air_and_frustrated_by_rubber():
    low = critical_angle(waveguide_index=1.49)
    high = critical_angle(waveguide_index=1.49, surrounding_index=1.41)
    assert math.degrees(low) == pytest.approx(42.16, abs=0.01)
    assert math.degrees(high) == pytest.approx(71.14, abs=0.01)
    FtirTransducer(ray_angle=0.5 * (low + high))
    for angle in (low - 0.01, high + 0.01):
        with pytest.raises(ValueError, match="`ray_angle` must lie in"):
            FtirTransducer(ray_angle=angle)


def test_flat_membrane_gives_a_binary_image():
    pressure = np.zeros((8, 8))
    pressure[2:5, 3:7] = np.linspace(1e2, 5e5, 12).reshape(3, 4)
    sensor = FtirTransducer(textured=False)
    image = sensor.respond(pressure)
    assert image.dtype == np.uint8
    assert set(np.unique(image).tolist()) == {24, 120}
    assert np.array_equal(image == 120, pressure > 0)
    recovered = sensor.invert(image)
    assert np.all(recovered[pressure == 0] == 0) and np.all(np.isnan(recovered[pressure > 0]))


def test_contact_area_is_linear_at_light_load_and_saturates():
    pressure = np.linspace(0, 2e6, 2001)
    fraction = contact_area_fraction(pressure, contact_modulus=1.33e6, rms_slope=0.2)
    assert np.all(np.diff(fraction) >= 0) and fraction[-1] == pytest.approx(1.0, abs=1e-12)
    assert np.all(np.diff(fraction, 2) <= 1e-15)  # concave: each kPa adds less
    light = contact_area_fraction(1e2, contact_modulus=1.33e6, rms_slope=0.2)
    assert light == pytest.approx(math.sqrt(8 / math.pi) * 1e2 / (1.33e6 * 0.2), rel=1e-6)
    back = pressure_from_contact_fraction(fraction[:500], contact_modulus=1.33e6, rms_slope=0.2)
    assert np.allclose(back, pressure[:500], rtol=1e-9, atol=1e-6)


def test_brightness_saturates_at_the_full_contact_level():
    sensor = FtirTransducer()
    pressure = np.linspace(0, 2e6, 401).reshape(1, -1)
    image = sensor.respond(pressure)[0].astype(int)
    assert image[0] == 24 and image.max() == 120
    assert np.all(np.diff(image) >= 0)
    saturated = pressure[0] >= 1.2 * sensor.saturation_pressure
    assert np.all(image[saturated] == 120)
    gain_low = image[20] - image[0]  # first 100 kPa
    gain_high = image[360] - image[200]  # 1 -> 1.8 MPa
    assert gain_low > 25 and gain_high == 0
    # the seed sensor's 60 psi working range lies below saturation: still graded there
    sixty_psi = 60 * 6894.757
    assert 1.5 * sixty_psi < sensor.saturation_pressure < 2 * sixty_psi
    slope = np.diff(sensor.respond(np.array([[0.95, 1.0]]) * sixty_psi).astype(int))
    assert slope[0, 0] >= 1  # a grey step within the top 5 % of the range


def test_round_trip_within_two_percent_of_full_scale():
    sensor = FtirTransducer()
    full_scale = sensor.saturation_pressure
    top = pressure_from_contact_fraction(
        0.95, contact_modulus=sensor.contact_modulus, rms_slope=sensor.rms_slope
    )
    pressure = np.linspace(0, top, 300).reshape(15, 20)
    error = np.abs(sensor.invert(sensor.respond(pressure)) - pressure)
    assert np.max(error) < 0.02 * full_scale


def test_camera_noise_statistics():
    fraction = np.full((200, 200), 0.5)
    frame = camera_image(fraction, rng=np.random.default_rng(11)).astype(float)
    mean = 24 + 96 * 0.5
    variance = 0.025 * mean + (0.025 * 10) ** 2 + 1 / 12  # shot + read + rounding
    assert frame.mean() == pytest.approx(mean, abs=0.02)
    assert frame.var() == pytest.approx(variance, rel=0.05)
    again = camera_image(fraction, rng=11)
    assert np.array_equal(frame, again)  # an int seed is a Generator of that seed
    assert camera_image([0.0, 0.5, 1.0], bits=4).tolist() == [15, 15, 15]  # clipped
    assert camera_image([0.0, 1.0], bits=10).dtype == np.uint16


def test_scratches_are_fixed_reproducible_bright_streaks():
    first = glass_scratches((64, 64), rng=3, count=5)
    assert np.array_equal(first, glass_scratches((64, 64), rng=np.random.default_rng(3), count=5))
    assert not np.array_equal(first, glass_scratches((64, 64), rng=4, count=5))
    assert 0.0 < (first > 0).mean() < 0.25 and first.max() <= 0.25
    assert np.all(glass_scratches((8, 8), rng=0, count=0) == 0)
    with pytest.raises(ValueError, match=r"`shape` must be a \(rows, cols\) pair, got \(8,\)"):
        glass_scratches((8,), rng=0)
    with pytest.raises(ValueError, match="`count` must be a whole number, got 2.5"):
        glass_scratches((8, 8), rng=0, count=2.5)
    sensor = FtirTransducer(scratch_count=5, scratch_seed=3)
    pressure = np.zeros((64, 64))
    image = sensor.respond(pressure)
    assert np.array_equal(image > 24, first > 0.5 / 96)  # streaks show where nothing touches
    assert np.all(sensor.invert(image) < 2e3)  # the known pattern is subtracted
    assert np.max(sensor.invert(image, subtract_scratches=False)) > 3e4  # phantom contact


def test_protocol_and_errors():
    sensor = FtirTransducer()
    assert isinstance(sensor, Transducer)
    assert (sensor.quantity, sensor.quantity_unit, sensor.signal_unit) == ("pressure", "Pa", "DN")
    with pytest.raises(ValueError, match="`pressure` must be 2-D"):
        sensor.respond(np.zeros(4))
    with pytest.raises(ValueError, match="`bits` must be an integer in 1..16, got 0"):
        camera_image(0.5, bits=0)
    with pytest.raises(ValueError, match="`bright_level` must exceed dark_level = 24"):
        FtirTransducer(bright_level=20.0)
    with pytest.raises(ValueError, match="`waveguide_index` must exceed surrounding_index"):
        critical_angle(waveguide_index=1.3, surrounding_index=1.41)
    with pytest.raises(TypeError, match="`rng` must be a numpy.random.Generator, an int seed"):
        glass_scratches((4, 4), rng=0.5)
    with pytest.raises(ValueError, match="`contact_fraction` must lie in"):
        pressure_from_contact_fraction(1.5, contact_modulus=1e6, rms_slope=0.2)


def test_the_scratch_pattern_is_drawn_once_per_glass_and_shape():
    sensor = FtirTransducer(scratch_count=4, scratch_seed=7)
    first = sensor.scratches((32, 32))
    assert sensor.scratches((32, 32)) is first  # cached: a frame does not redraw the glass
    assert not first.flags.writeable
    assert np.array_equal(first, glass_scratches((32, 32), rng=7, count=4))


def test_keep_sign_mirrors_the_law_below_the_unloaded_level():
    sensor = FtirTransducer(scratch_count=0)
    levels = np.arange(256.0).reshape(16, 16)
    plain = sensor.invert(levels)
    signed = sensor.invert(levels, keep_sign=True)
    above = levels >= sensor.dark_level
    assert np.array_equal(signed[above], plain[above])
    # erfinv is odd: a level d below the dark one reads minus the level d above
    for d in (1.0, 5.0, 20.0):
        low = sensor.invert(np.full((1, 1), sensor.dark_level - d), keep_sign=True)
        high = sensor.invert(np.full((1, 1), sensor.dark_level + d))
        assert low[0, 0] == pytest.approx(-high[0, 0], rel=1e-12)
    assert np.all(plain[~above] == 0.0) and np.all(signed[~above] < 0.0)


def test_keep_sign_lets_the_noise_of_an_unloaded_frame_average_out():
    sensor = FtirTransducer()
    frames = [sensor.respond(np.zeros((128, 128)), rng=seed) for seed in range(4)]
    pressure = np.stack([sensor.invert(frame, keep_sign=True) for frame in frames])
    clipped = np.stack([sensor.invert(frame) for frame in frames])
    spread = pressure.std() / math.sqrt(pressure.size)
    assert abs(pressure.mean()) < 4 * spread  # unbiased
    assert clipped.mean() > 50 * spread  # the noise above the level only: biased up
    with pytest.raises(TypeError, match="keep_sign"):
        sensor.invert(frames[0], keep_sign="yes")
