"""Spatial-frequency texture signature: known answers on synthetic gratings and surfaces."""

import numpy as np
import pytest

from taxel.active import (
    DEFAULT_BAND_EDGES,
    band_power,
    spatial_power_spectrum,
    texture_features,
    texture_signature,
)

RATE = 35.0  # Hz, as the FabricSlide finger
TRAVEL = 0.5  # m


def _slide(profile, velocity, *, start=0.0, rate=RATE, travel=TRAVEL, offset=150.0):
    """Readings of taxels sliding at `velocity` over `profile(x)` [reading] from `start`."""
    time = np.arange(0.0, travel / abs(velocity), 1.0 / rate)
    position = start + velocity * time
    return time, offset + profile(position)


def _grating(period, amplitude=4.0):
    return lambda x: amplitude * np.sin(2 * np.pi * x / period)


def _rough_surface(seed=3, low=8.0, high=100.0, n_waves=400):
    """A band-limited random profile with a k^-1 amplitude spectrum, two taxels 5 mm apart."""
    rng = np.random.default_rng(seed)
    k = np.exp(rng.uniform(np.log(low), np.log(high), n_waves))
    amplitude = 8.0 / k * np.sqrt(k)
    phase = rng.uniform(0, 2 * np.pi, n_waves)

    def profile(x):
        x = np.stack([x, x + 0.005], axis=-1)[..., None]
        return np.sum(amplitude * np.sin(2 * np.pi * k * x + phase), axis=-1)

    return profile


@pytest.mark.parametrize("speed", [0.02, 0.05, 0.12])
def test_grating_peak_is_at_its_spatial_frequency_at_any_speed(speed):
    time, readings = _slide(_grating(0.025), speed)
    k, psd = spatial_power_spectrum(readings, RATE, speed)
    assert k[np.argmax(psd)] == pytest.approx(40.0, abs=1.0)  # 1 / 25 mm = 40 cycles/m
    assert k[1] == pytest.approx(5.0, rel=0.05)  # resolution 1 / segment_length
    signature = texture_signature(readings, time, speed)
    assert signature.centroid == pytest.approx(40.0, rel=0.03)
    # a sinusoid of amplitude 4 has variance 8; its gradient RMS is 4 * 2 pi k / sqrt 2
    assert signature.rms[0] == pytest.approx(np.sqrt(8.0), rel=0.02)
    assert signature.rms_gradient[0] == pytest.approx(4 * 2 * np.pi * 40 / np.sqrt(2), rel=0.03)


def test_same_grating_same_signature_at_two_speeds():
    time, readings = _slide(_grating(0.025), 0.02)
    slow = texture_signature(readings, time, 0.02)
    time, readings = _slide(_grating(0.025), 0.12)
    fast = texture_signature(readings, time, 0.12)
    np.testing.assert_allclose(slow.band_power, fast.band_power, rtol=0.1, atol=1e-3)
    # the temporal peaks differ six-fold (0.8 Hz and 4.8 Hz); the spatial ones do not
    assert slow.spatial_frequency[np.argmax(slow.pooled_psd)] == pytest.approx(40.0, abs=1)
    assert fast.spatial_frequency[np.argmax(fast.pooled_psd)] == pytest.approx(40.0, abs=1)


def test_rough_surface_levels_agree_across_speeds_and_directions():
    surface = _rough_surface()
    levels = []
    for velocity in (0.02, 0.06, -0.06, 0.15):
        start = 0.0 if velocity > 0 else TRAVEL
        time, readings = _slide(surface, velocity, start=start)
        signature = texture_signature(readings, time, velocity)
        assert signature.band_power.shape == (7, 2)
        levels.append(signature.band_level)
    for other in levels[1:]:
        np.testing.assert_allclose(other, levels[0], atol=0.5)  # dB


def test_direction_reversal_is_the_same_path_backwards():
    surface = _rough_surface(seed=5)
    time, forward = _slide(surface, 0.05)
    backward = forward[::-1]  # the same positions, visited the other way
    there = texture_signature(forward, time, 0.05, trim_fraction=0)
    back = texture_signature(backward, time, -0.05, trim_fraction=0)
    np.testing.assert_allclose(back.band_power, there.band_power, rtol=1e-9)


def test_spectrum_keeps_the_variance():
    rng = np.random.default_rng(1)
    noise = rng.normal(0.0, 2.0, 4000)
    k, psd = spatial_power_spectrum(noise, 100.0, 0.04)
    total = band_power(k, psd, [0.0, k[-1]])[0, 0]
    assert total == pytest.approx(4.0, rel=0.05)
    # the spatial PSD of white noise is the temporal one (variance / (fs / 2)) times |v|
    assert np.median(psd[1:-1]) == pytest.approx(4.0 / 50.0 * 0.04, rel=0.2)


def test_band_power_splits_bins_and_marks_unobserved_bands():
    k = np.arange(0.0, 21.0, 2.0)  # bins of width 2 centred on 0, 2, ..., 20
    psd = np.ones((k.size, 3))
    power = band_power(k, psd, [0.0, 1.0, 5.0, 20.0, 30.0])
    np.testing.assert_allclose(power[:3], [[1.0] * 3, [4.0] * 3, [15.0] * 3])
    assert np.all(np.isnan(power[3]))
    with pytest.raises(ValueError, match="`spatial_psd` must be >= 0 \\(a power\\), got -1"):
        band_power(k, -psd, [0.0, 1.0, 5.0])


def test_levels_are_relative_to_the_contact_level():
    surface = _rough_surface(seed=7)
    time, readings = _slide(surface, 0.05, offset=100.0)
    once = texture_signature(readings, time, 0.05)
    twice = texture_signature(2 * readings, time, 0.05)  # a contact twice as strong
    np.testing.assert_allclose(twice.band_level, once.band_level, atol=1e-9)
    assert twice.mean_reading == pytest.approx(2 * once.mean_reading)
    np.testing.assert_allclose(twice.band_power, 4 * once.band_power, rtol=1e-12)


def test_features_layout_and_nan_above_nyquist():
    time, readings = _slide(_rough_surface(), 0.05)
    signature = texture_signature(readings, time, 0.05)
    features = texture_features(signature)
    assert features.shape == (2 * 7 + 7,)
    np.testing.assert_allclose(features[:7], signature.band_level[:, 0])
    np.testing.assert_allclose(features[-7:], signature.pooled_band_level)
    # 10 Hz sampling at 0.1 m/s resolves 50 cycles/m: the bands above are not observed
    time, readings = _slide(_rough_surface(), 0.1, rate=10.0, travel=2.0)
    coarse = texture_signature(readings, time, 0.1)
    assert coarse.nyquist_spatial_frequency == pytest.approx(50.0, rel=0.01)
    observed = DEFAULT_BAND_EDGES[1:] <= 50.0
    assert np.all(np.isfinite(coarse.band_power[observed]))
    assert np.all(np.isnan(coarse.band_power[~observed]))


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"sliding_velocity": 0.0}, ValueError, "`sliding_velocity` must be nonzero"),
        ({"time": np.arange(10.0)}, ValueError, "`time` has 10 steps but `readings` has 200"),
        ({"time": -np.arange(200.0)}, ValueError, "`time` must be non-decreasing"),
        ({"time": np.zeros(200)}, ValueError, "`time` must advance"),
        ({"trim_fraction": 0.5}, ValueError, r"`trim_fraction` must lie in \[0, 0.45\]"),
        ({"band_edges": [5.0, 3.0]}, ValueError, "`band_edges` must be at least two increasing"),
        ({"segment_length": -1}, ValueError, "`segment_length` must be > 0, got -1"),
        # 200 steps at 35 Hz and 50 mm/s: 0.2857 m of travel, 0.2286 m in the 160 steps
        # kept: a longer segment is the segment's error, one in between the trim's
        (
            {"segment_length": 0.3},
            ValueError,
            r"`segment_length` must be at most the record's travel \(0.2857 m: 200 steps",
        ),
        (
            {"segment_length": 0.25},
            ValueError,
            r"`trim_fraction` 0.1 leaves 0.2286 m of the record's 0.2857 m travel \(160 of "
            r"200 steps at 0.05 m/s and 35 Hz\), less than `segment_length` 0.25$",
        ),
        (
            {"readings": np.ones(40), "time": np.arange(40.0) / RATE, "trim_fraction": 0.45},
            ValueError,
            "`trim_fraction` 0.45 leaves 4 of the record's 40 steps, fewer than the 16 a "
            "spectrum needs",
        ),
        # a segment beyond float's range of samples, and one of fewer than 8 samples
        # (at 35 Hz and 50 mm/s a sample is 1.43 mm of travel)
        (
            {"segment_length": 1e308},
            ValueError,
            r"`segment_length` must be at most the record's travel .* got 1e\+308",
        ),
        (
            {"segment_length": 0.01},
            ValueError,
            r"`segment_length` must span at least 8 samples \(0.01143 m at 0.05 m/s and 35 Hz\)",
        ),
        ({"readings": np.full(200, np.nan)}, ValueError, "`readings` must be finite"),
        (
            {"readings": np.ones(12), "time": np.arange(12.0)},
            ValueError,
            "`readings` must have at least 16 steps, got 12",
        ),
    ],
)
def test_signature_errors(kwargs, error, message):
    arguments = {"readings": np.ones(200), "time": np.arange(200.0) / RATE}
    arguments["sliding_velocity"] = 0.05
    arguments.update(kwargs)
    readings = arguments.pop("readings")
    time = arguments.pop("time")
    velocity = arguments.pop("sliding_velocity")
    with pytest.raises(error, match=message):
        texture_signature(readings, time, velocity, **arguments)


def test_a_segment_the_trim_left_too_short_fits_the_untrimmed_record():
    time = np.arange(200.0) / RATE  # 0.2857 m at 50 mm/s
    signature = texture_signature(np.ones(200), time, 0.05, segment_length=0.25, trim_fraction=0.0)
    # a 0.25 m segment: spectral resolution 4 cycles/m
    assert signature.spatial_frequency[1] == pytest.approx(4.0, rel=0.01)


def test_features_need_a_positive_contact_level_and_some_texture():
    time = np.arange(200.0) / RATE
    with pytest.raises(ValueError, match="mean reading, which must be > 0, got -0.99"):
        texture_features(texture_signature(np.sin(time * 30) - 1, time, 0.05))
    with pytest.raises(ValueError, match="a band holds no measurable power"):
        texture_features(texture_signature(np.full(200, 3.0), time, 0.05))
