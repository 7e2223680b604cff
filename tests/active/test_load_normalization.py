"""Load shares and load decorrelation: invariance to the load, known gains, error cases."""

import numpy as np
import pytest

from taxel.active import load_shares, remove_load_coherent, texture_features, texture_signature

RATE = 35.0  # Hz, as the FabricSlide finger
OFFSETS = np.array([0.0, 0.004, 0.008, 0.012])  # taxel positions along the path [m]
STATIC = np.array([80.0, 140.0, 200.0, 110.0])  # static reading of each taxel [reading]


def _rough(x, seed=11, n_waves=300):
    """A band-limited random profile (periods 8 to 100 mm), relative units."""
    rng = np.random.default_rng(seed)
    k = np.exp(rng.uniform(np.log(10.0), np.log(120.0), n_waves))
    phase = rng.uniform(0, 2 * np.pi, n_waves)
    return np.sum(0.02 / np.sqrt(k) * np.sin(2 * np.pi * k * x[..., None] + phase), axis=-1)


def _finger(speed, load, *, travel=0.5):
    """Readings of four taxels that each press the same profile at their own position.

    `load(t)` multiplies every reading, as a change of the normal force does to first order.
    """
    time = np.arange(0.0, travel / speed, 1.0 / RATE)
    position = speed * time[:, None] + OFFSETS
    pattern = STATIC * (1.0 + _rough(position))
    return time, load(time)[:, None] * pattern


def _steady(force):
    return lambda t: np.full_like(t, force)


def _oscillating(force, amplitude=0.15, frequency=2.3):
    """A force loop oscillating at a fixed temporal frequency, whatever the speed."""
    return lambda t: force * (1.0 + amplitude * np.sin(2 * np.pi * frequency * t))


def test_shares_average_to_one_and_ignore_any_common_factor():
    rng = np.random.default_rng(0)
    readings = rng.uniform(50, 200, (40, 6))
    shares = load_shares(readings)
    np.testing.assert_allclose(shares.mean(axis=1), 1.0)
    factor = 1.0 + 0.5 * np.sin(np.arange(40.0))  # a different load at every step
    np.testing.assert_allclose(load_shares(factor[:, None] * readings), shares, rtol=1e-12)


def test_a_grating_at_two_forces_gives_the_same_normalised_levels():
    time, light = _finger(0.05, _steady(120.0))
    _, firm = _finger(0.05, _steady(250.0))
    one = texture_signature(light, time, 0.05, normalization="load")
    two = texture_signature(firm, time, 0.05, normalization="load")
    np.testing.assert_allclose(two.band_level, one.band_level, atol=1e-9)
    assert one.level_reference == 1.0
    assert two.mean_reading == pytest.approx(250 / 120 * one.mean_reading)


@pytest.mark.parametrize("speed", [0.02, 0.1, 0.15])
def test_an_oscillating_force_leaves_the_load_signature_unchanged(speed):
    time, steady = _finger(speed, _steady(200.0))
    _, shaking = _finger(speed, _oscillating(200.0))
    calm = texture_signature(steady, time, speed, normalization="load")
    shaken = texture_signature(shaking, time, speed, normalization="load")
    np.testing.assert_allclose(shaken.band_level, calm.band_level, atol=1e-9)
    # the static normalisation sees the oscillation in the band holding 2.3 Hz / speed
    static_calm = texture_signature(steady, time, speed)
    static_shaken = texture_signature(shaking, time, speed)
    band = np.searchsorted(calm.band_edges, 2.3 / speed) - 1
    if 0 <= band < calm.band_edges.size - 1:
        excess = static_shaken.pooled_band_level[band] - static_calm.pooled_band_level[band]
        assert excess > 5.0  # dB


def test_load_decorrelation_removes_a_load_dependent_redistribution():
    """A firmer press widens the contact: edge taxels gain more than in proportion."""
    time, steady = _finger(0.05, _steady(200.0))
    _, shaking = _finger(0.05, _oscillating(200.0))
    relative = shaking.mean(axis=1) / shaking.mean() - 1.0
    widening = np.array([0.3, -0.2, -0.25, 0.15])  # sums to 0: the load moves outwards
    widened = shaking + np.outer(relative, widening * shaking.mean())
    calm = texture_signature(steady, time, 0.05, normalization="load")
    plain = texture_signature(widened, time, 0.05, normalization="load")
    cleaned = texture_signature(widened, time, 0.05, normalization="load", decorrelate_load=True)
    band = np.searchsorted(calm.band_edges, 2.3 / 0.05) - 1  # the band holding 2.3 Hz
    error_plain = np.abs(plain.band_level - calm.band_level)
    error_cleaned = np.abs(cleaned.band_level - calm.band_level)
    assert error_plain[band].min() > 5.0  # dB, on every taxel
    assert error_cleaned[band].max() < 0.5
    # the share is not linear in the load: its second harmonic (4.6 Hz) stays, slightly
    assert error_cleaned.max() < 2.0
    assert cleaned.load_decorrelated and not plain.load_decorrelated


def test_removing_the_load_recovers_the_gains():
    t = np.arange(2000) / 100.0  # 20 s at 100 Hz: whole periods of every sinusoid below
    load = 150.0 * (1.0 + 0.1 * np.sin(2 * np.pi * 2.3 * t))
    texture = np.stack([np.sin(2 * np.pi * 7.1 * t), np.cos(2 * np.pi * 5.3 * t)], axis=1)
    gains = np.array([0.8, -0.3])
    relative = load / load.mean()
    mixed = texture + np.outer(relative, gains) + 4.0 + 0.5 * t[:, None]  # offset and drift
    removed = mixed - remove_load_coherent(mixed, load)
    np.testing.assert_allclose(removed, np.outer(relative, gains), atol=0.01)
    # a load that is constant or a straight line has nothing to remove
    np.testing.assert_array_equal(remove_load_coherent(mixed, 100.0 + t), mixed)


def test_pooled_features_only():
    time, readings = _finger(0.05, _steady(150.0))
    signature = texture_signature(readings, time, 0.05, normalization="load")
    pooled = texture_features(signature, per_taxel=False)
    np.testing.assert_allclose(pooled, signature.pooled_band_level)
    assert texture_features(signature).shape == (4 * 7 + 7,)


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (lambda: load_shares(np.ones((5, 1))), ValueError, "at least two taxels"),
        (lambda: load_shares(np.ones(5)), ValueError, "`readings` must be 2-D"),
        (
            lambda: load_shares(np.array([[1.0, 2.0], [-1.0, -2.0]])),
            ValueError,
            "> 0 at every step, got -1.5 at step 1",
        ),
        (
            lambda: remove_load_coherent(np.ones((5, 2)), np.ones(4)),
            ValueError,
            "`load` has 4 steps but `signals` has 5",
        ),
        (
            lambda: remove_load_coherent(np.ones((5, 2)), -np.ones(5)),
            ValueError,
            "the mean of `load` must be > 0, got -1",
        ),
        (
            lambda: texture_signature(np.ones(200), np.arange(200.0), 0.05, normalization="load"),
            ValueError,
            "need at least two taxels, got 1",
        ),
        (
            lambda: texture_signature(
                np.ones((200, 2)), np.arange(200.0), 0.05, normalization="x"
            ),
            ValueError,
            "`normalization` must be one of static, load; got 'x'",
        ),
        (
            lambda: texture_signature(
                np.ones((200, 2)), np.arange(200.0), 0.05, decorrelate_load="yes"
            ),
            TypeError,
            "`decorrelate_load` must be a bool",
        ),
    ],
)
def test_errors(call, error, message):
    with pytest.raises(error, match=message):
        call()
