"""The noise level estimated from a frame, and the default parameter rule built on it."""

import numpy as np
import pytest

from taxel.reconstruction import (
    TikhonovSolver,
    estimate_noise_level,
    forward_model_preset,
    reconstruct,
)
from taxel.reconstruction._noise import combined_noise, high_frequency_noise, spectral_noise

THICK = forward_model_preset("vhdta128", shape=(32, 32))  # d = 3.9 pitches
THIN = forward_model_preset("resistive16")  # d = 0.75 pitch


def _frame(solver, truth, sigma, seed):
    frame = solver.operator.apply(truth)
    return frame + np.random.default_rng(seed).normal(0.0, sigma, frame.shape)


@pytest.mark.parametrize("spec", [THICK, THIN], ids=["thick", "thin"])
def test_pure_noise_gives_its_std(spec):
    solver = TikhonovSolver(spec)
    frames = np.random.default_rng(0).normal(0.0, 1e3, (400, *spec.shape))
    estimates = solver.estimate_noise_level(frames)
    assert estimates.shape == (400,)
    # each estimate is a median: a few % off, and the minimum of two leans low by about 2 %
    assert np.median(estimates) == pytest.approx(1e3, rel=0.05)
    # the thin 16 x 16 array has only 127 least-passed modes and 225 differences: its
    # estimates spread by about 9 %, and 3.3 % of frames fall more than 20 % off (measured
    # on 4000 frames); the thick cover's none
    assert np.mean(np.abs(estimates / 1e3 - 1) > 0.2) <= 0.06


def test_a_sharp_load_on_a_thin_cover_fools_the_spectral_estimate_but_not_the_combined():
    solver = TikhonovSolver(THIN)
    truth = np.zeros(THIN.shape)
    truth[5:8, 6:9] = 150e3
    truth[11, 3] = 300e3
    frame = _frame(solver, truth, 1e3, 1)
    beta = solver.spectrum.analyze(frame[None])[0]
    spectral = spectral_noise(beta, solver._noise_modes)[0]
    assert spectral > 2e3  # the signal reaches the least-passed modes
    assert solver.estimate_noise_level(frame) == pytest.approx(1e3, rel=0.2)


def test_a_broad_smooth_load_fools_the_differences_but_not_the_combined():
    solver = TikhonovSolver(THICK)
    rows, cols = np.mgrid[:32, :32]
    truth = 300e3 * np.exp(-((rows - 15.3) ** 2 + (cols - 16.8) ** 2) / (2 * 8.0**2))
    frame = _frame(solver, truth, 500.0, 2)
    live = THICK.live_taxels
    assert high_frequency_noise(frame[None], live)[0] > 1.2 * 500.0
    assert solver.estimate_noise_level(frame) == pytest.approx(500.0, rel=0.1)


def test_dead_taxels_and_the_public_function():
    spec = THIN.with_changes(dead_taxels=[(3, 3), (8, 9)])
    frames = np.random.default_rng(3).normal(0.0, 2e3, (12, *spec.shape))
    frames[:, 3, 3] = np.nan
    frames[:, 8, 9] = 1e9  # whatever a dead taxel reports is ignored
    fast = TikhonovSolver(spec, representation="fast", boundary="reflect")
    # 254 readings: each estimate is within about 15 %, their median much closer
    for estimates in (estimate_noise_level(frames, spec), fast.estimate_noise_level(frames)):
        assert np.median(estimates) == pytest.approx(2e3, rel=0.08)
        assert np.all(np.abs(estimates / 2e3 - 1) < 0.3)
    assert estimate_noise_level(frames[0], spec) == pytest.approx(2e3, rel=0.3)


def test_combination_ignores_zero_and_infinite_estimates():
    combined = combined_noise(np.array([0.0, 3.0, np.inf]), np.array([2.0, 5.0, np.inf]))
    assert combined.tolist() == [2.0, 3.0, 0.0]


def test_the_default_rule_is_the_discrepancy_principle_with_the_estimate():
    solver = TikhonovSolver(THIN, order=1)
    truth = np.zeros(THIN.shape)
    truth[6:10, 5:9] = 60e3
    frame = _frame(solver, truth, 2e3, 4)
    result = reconstruct(frame, THIN, order=1)
    assert result.rule == "discrepancy"
    assert result.noise_level == pytest.approx(solver.estimate_noise_level(frame))
    # the residual equals the noise the rule was told of
    assert result.residual_norm == pytest.approx(result.noise_level * 16, rel=0.02)
    given = reconstruct(frame, THIN, order=1, noise_level=2e3)
    assert given.noise_level == 2e3


def test_a_noise_free_frame_is_fitted_exactly():
    solver = TikhonovSolver(THIN, order=1)
    truth = np.zeros(THIN.shape)
    truth[6:10, 5:9] = 60e3
    result = solver.solve(solver.operator.apply(truth))
    # what is left is the load's own trace in the estimators: 0.03 % of its peak
    assert result.noise_level < 1e-3 * 60e3
    assert np.abs(result.pressure - truth).max() < 1e-2 * 60e3
    silent = solver.solve(np.zeros(THIN.shape))  # nothing to estimate from: no failure
    assert silent.noise_level == 0.0 and np.all(silent.pressure == 0.0)


def test_a_noise_level_at_full_scale_or_beyond_is_refused():
    # 1e300 Pa was taken: the discrepancy principle smoothed a 2 N contact to 0.02 N
    truth = np.zeros((16, 16))
    truth[6:9, 7:10] = 30e3
    frame = TikhonovSolver(THIN).operator.apply(truth)
    for method in ("tikhonov", "support", "nonneg"):
        with pytest.raises(
            ValueError,
            match=r"`noise_level` must be below the full-scale reading \(2e\+05 Pa\), got 1e\+300",
        ):
            reconstruct(frame, "resistive16", method=method, noise_level=1e300)
    with pytest.raises(ValueError, match=r"reading \(0.0004068 m\), got 0.001"):
        reconstruct(np.zeros((8, 8)), "reflective8x8", noise_level=1e-3)
    with pytest.raises(ValueError, match="`noise_level` must be below the full-scale reading"):
        THIN.with_changes(noise_level=2e5)
    assert THIN.with_changes(full_scale=None, noise_level=3e5).noise_level == 3e5  # no bound
    noisy = frame + np.random.default_rng(0).normal(0.0, 400.0, frame.shape)
    result = reconstruct(noisy, "resistive16", order=1, noise_level=400.0)  # as before
    assert result.normal_force == pytest.approx(truth.sum() * 4e-6, rel=0.05)
