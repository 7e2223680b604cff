"""Time-dependent non-idealities: hysteresis, lag, creep, drift, temperature."""

import math

import numpy as np
import pytest

from taxel.transducers import (
    add_drift,
    creep,
    first_order_lag,
    play_hysteresis,
    temperature_dependence,
)


def triangle(amplitude, samples_per_leg, cycles=2):
    up = np.linspace(0, amplitude, samples_per_leg + 1)
    leg = np.concatenate([up[1:], up[::-1][1:]])
    return np.concatenate([np.tile(leg, cycles)])


@pytest.mark.parametrize("n_operators", [1, 5])
def test_major_loop_has_the_stated_width(n_operators):
    x = triangle(10.0, 200)
    y = play_hysteresis(x, loop_width=2.0, n_operators=n_operators)
    second = slice(400, 800)  # the second cycle, on the major loop
    xs, ys = x[second], y[second]
    rising = np.interp(5.0, xs[:200], ys[:200])
    falling = np.interp(5.0, xs[200:][::-1], ys[200:][::-1])
    assert falling - rising == pytest.approx(2.0, rel=1e-9)


def test_hysteresis_is_rate_independent_and_switchable():
    coarse = triangle(4.0, 8)
    fine = triangle(4.0, 32)
    y_coarse = play_hysteresis(coarse, loop_width=1.0, n_operators=3)
    y_fine = play_hysteresis(fine, loop_width=1.0, n_operators=3)
    assert np.allclose(y_fine[3::4], y_coarse, atol=1e-12)
    assert np.array_equal(play_hysteresis(coarse), coarse)
    batch = play_hysteresis(np.stack([coarse, 2 * coarse]), loop_width=1.0)
    assert np.allclose(batch[0], play_hysteresis(coarse, loop_width=1.0))


def test_first_order_lag_is_exact_for_a_ramp():
    tau, dt, rate = 0.3, 0.05, 2.0
    k = np.arange(40)
    elapsed = (k + 1) * dt  # the ramp starts one step before the first sample
    y = first_order_lag(rate * elapsed, dt, time_constant=tau)
    exact = rate * (elapsed - tau * (1 - np.exp(-elapsed / tau)))
    assert np.allclose(y, exact, rtol=1e-12, atol=1e-15)
    settled = first_order_lag(np.full(5, 3.0), dt, time_constant=tau, initial_value=3.0)
    assert np.allclose(settled, 3.0, rtol=1e-15)


def test_creep_under_a_held_load():
    dt, tau = 0.01, 0.5
    y = creep(np.ones(600), dt, creep_fraction=0.15, time_constant=tau)
    assert y[-1] == pytest.approx(1.15, rel=1e-5)
    slope = np.polyfit(np.arange(1, 600) * dt, np.log(1.15 - y[1:]), 1)[0]
    assert -1 / slope == pytest.approx(tau, rel=1e-9)
    assert np.array_equal(creep(np.ones(3), dt), np.ones(3))


def test_drift_trend_and_random_walk():
    x = np.zeros((2000, 101))
    y = add_drift(x, 0.1, rate=0.5, random_walk=0.2, rng=np.random.default_rng(9))
    trend = 0.5 * 0.1 * np.arange(101)
    assert np.allclose(y.mean(axis=0), trend, atol=0.03)
    spread = (y - trend).var(axis=0)
    assert spread[-1] == pytest.approx(0.2**2 * 10.0, rel=0.08)  # sigma^2 t after 10 s
    assert spread[0] == 0.0
    assert np.array_equal(add_drift(x[:2], 0.1), x[:2])
    with pytest.raises(TypeError, match="`rng` is required"):
        add_drift(x[:2], 0.1, random_walk=0.1)


def test_temperature_dependence():
    temps = np.array([283.15, 293.15, 313.15])
    y = temperature_dependence(
        np.array([2.0, 2.0, 2.0]), temps, gain_coefficient=1e-3, offset_coefficient=-0.01
    )
    assert np.allclose(y, [2 * 0.99 + 0.1, 2.0, 2 * 1.02 - 0.2])
    assert np.array_equal(temperature_dependence([1.0, 2.0], 350.0), [1.0, 2.0])


def test_errors_name_the_parameter():
    with pytest.raises(ValueError, match="`loop_width` must be >= 0, got -1"):
        play_hysteresis([0.0, 1.0], loop_width=-1.0)
    with pytest.raises(ValueError, match="`n_operators` must be a positive integer, got 0"):
        play_hysteresis([0.0, 1.0], loop_width=1.0, n_operators=0)
    with pytest.raises(ValueError, match="`time_constant` must be > 0, got 0"):
        creep([0.0, 1.0], 0.1, creep_fraction=0.1, time_constant=0.0)
    with pytest.raises(ValueError, match="`signal` must be a time series"):
        first_order_lag(1.0, 0.1, time_constant=1.0)
    with pytest.raises(ValueError, match="`temperature` must be > 0 K, got -5"):
        temperature_dependence(1.0, -5.0)
    assert math.isfinite(float(first_order_lag([1.0], 0.1, time_constant=0.0)[0]))
