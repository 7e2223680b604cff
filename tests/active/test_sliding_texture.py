"""Active texture: sliding over gratings and the seed's textures at several speeds."""

import numpy as np
import pytest

from taxel.active import (
    Grating,
    ProfileObject,
    SampledProfile,
    SimulatedFinger,
    TextureSliding,
    slide_texture,
    texture_speed_study,
    texture_surface,
)
from taxel.frames import make_pose
from taxel.sensor import make_sensor

DOWN = np.diag([1.0, -1.0, -1.0])


@pytest.fixture(scope="module")
def grating_slides():
    plate = ProfileObject("grating", profile=Grating(pitch=4e-3, amplitude=0.2e-3), top=0.01)
    slides = {}
    for speed in (0.04, 0.08):
        start = make_pose(DOWN, [0.0, 0.0, 0.0105])
        finger = SimulatedFinger(make_sensor("resistive16"), [plate], start, rng=1)
        slides[speed] = slide_texture(finger, speed=speed, length=0.02, segment_length=0.008)
    return slides


def test_grating_peaks_at_the_inverse_pitch_at_any_speed(grating_slides):
    slow, fast = grating_slides[0.04], grating_slides[0.08]
    assert slow.peak_spatial_frequency == pytest.approx(250.0)
    assert fast.peak_spatial_frequency == pytest.approx(250.0)
    # twice the speed: half the steps over the same 20 mm at 500 frames/s
    assert slow.time.size == 2 * fast.time.size - 1 == 251
    assert fast.signature.centroid == pytest.approx(slow.signature.centroid, rel=0.03)
    # the band holding 250 cycles/m carries the most power, at both speeds
    band = int(np.searchsorted(slow.signature.band_edges, 250.0)) - 1
    assert np.argmax(slow.band_level) == np.argmax(fast.band_level) == band
    step = slow.steps[0]
    assert step.action == "slide 20 mm at 40 mm/s"
    assert step.normal_force == pytest.approx(3.0)
    assert slow.to_dict()["peak_spatial_frequency"] == pytest.approx(250.0)


def test_seed_textures_are_told_apart_across_speeds():
    study = texture_speed_study(("rasp", "screen"), (0.05, 0.1), length=0.016)
    assert study.accuracy == 1.0
    assert study.centroid_spread.max() < 0.08  # short slides: 8 mm Welch segments
    # rasp teeth every 3 mm (333 cycles/m); screen holes every 6 mm (167 cycles/m)
    assert study.centroid[0].mean() > 1.3 * study.centroid[1].mean()
    assert np.trace(study.confusion) == 4
    assert set(study.to_dict()) >= {"accuracy", "unnormalised_accuracy", "level_spread_db"}


def test_sampled_profile_matches_its_source():
    source = texture_surface("rasp")
    sampled = SampledProfile(source, extent=(-0.01, 0.01, -0.01, 0.01), spacing=20e-6)
    u = np.linspace(-0.009, 0.009, 37)
    v = np.full_like(u, 0.0031)
    assert sampled.local_heights(u, v) == pytest.approx(source.local_heights(u, v), abs=10e-6)
    assert np.isinf(sampled.local_heights(np.array([0.02]), np.array([0.0]))).all()
    screen = SampledProfile(texture_surface("screen"), extent=(-0.01, 0.01, -0.01, 0.01))
    assert np.isinf(screen.local_heights(np.array([0.0]), np.array([0.0]))).all()  # a hole


def test_bad_settings_raise():
    with pytest.raises(ValueError, match="`speed` must be > 0"):
        plate = ProfileObject("grating", profile=Grating(), top=0.01)
        finger = SimulatedFinger(
            make_sensor("resistive16"), [plate], make_pose(DOWN, [0, 0, 0.011])
        )
        slide_texture(finger, speed=0.0)
    with pytest.raises(ValueError, match="`segment_length` must be <= half"):
        TextureSliding(length=0.01, segment_length=0.008)
    with pytest.raises(ValueError, match="`textures` must hold foam, rasp, screen"):
        texture_surface("felt")
    with pytest.raises(ValueError, match="`pitch` must be > 0"):
        Grating(pitch=-1.0)
