"""A parameter rule that finds no lambda inside its range says so (it used to be silent)."""

import numpy as np
import pytest

from taxel.reconstruction import forward_operator, reconstruct

LARGEST = "lambda held at the largest of its range"


@pytest.fixture(scope="module")
def frame():
    """A 1.44 N press on resistive16 (rms reading 6.5 kPa, |b| = 1.04e5 Pa), 1 kPa noise."""
    truth = np.zeros((16, 16))
    truth[5:8, 6:9] = 40e3
    frame = forward_operator("resistive16").apply(truth)
    return frame + np.random.default_rng(0).normal(0, 1e3, frame.shape)


def test_a_noise_level_above_the_readings_holds_lambda_at_the_bound(frame):
    # tau sigma sqrt(m) = 5e4 x 16 = 8e5 Pa, above the residual of any lambda (|b|)
    result = reconstruct(frame, "resistive16", noise_level=5e4)
    assert result.at_bound is True
    assert result.regularization == pytest.approx(10.0)
    assert result.residual_norm == pytest.approx(1.0322e5, rel=1e-4)
    assert result.message == (
        "direct solve; the discrepancy rule found no lambda inside [0.0001, 10]: "
        f"{LARGEST}, 10, as no residual reaches tau sigma sqrt(m) (the noise level is as "
        "large as the readings)"
    )
    # within the readings' size the rule meets its target: |r| = 1e3 x 16
    fitted = reconstruct(frame, "resistive16", noise_level=1e3)
    assert fitted.at_bound is False and fitted.message == "direct solve"
    assert fitted.residual_norm == pytest.approx(1.6e4, rel=1e-3)
    assert fitted.normal_force == pytest.approx(1.28, abs=0.01)


def test_each_frame_of_a_batch_and_each_method_says_it(frame):
    # a press 20 times lighter reads |b| = 5.2e3 Pa, below 1e3 x 16
    batch = reconstruct(np.stack([frame, 0.05 * frame]), "resistive16", noise_level=1e3)
    np.testing.assert_array_equal(batch.at_bound, [False, True])
    assert f"{LARGEST}, 10 in 1 of 2 frames" in batch.message
    for method in ("tsvd", "nonneg", "support"):
        result = reconstruct(frame, "resistive16", method=method, noise_level=5e4)
        assert result.at_bound is True, method
    assert "(discrepancy, at its bound)" in result.message  # support's first stage
    given = reconstruct(frame, "resistive16", regularization=10.0)
    assert given.at_bound is False and given.message == "direct solve"


def test_a_smoothing_penalty_has_room_above_lambda_10(frame):
    """Order 2 passes smooth modes (g up to 3.9e4): the residual still grows past lambda 10.

    With 5 kPa of noise the target, 8e4 Pa, lies between the residual at lambda 10
    (6.18e4 Pa) and its limit (1.01e5 Pa): the range that ended at 10 held lambda there,
    silently, 23 % short of the target; it now reaches 10 sqrt(max g) and finds the root.
    """
    result = reconstruct(frame, "resistive16", order=2, noise_level=5e3)
    assert result.at_bound is False
    assert result.regularization == pytest.approx(24.6, rel=0.01)
    assert result.residual_norm == pytest.approx(8e4, rel=1e-3)
    capped = reconstruct(frame, "resistive16", order=2, regularization=10.0)
    assert capped.residual_norm == pytest.approx(6.18e4, rel=1e-3)
    # at the top of the longer range every mode is filtered to about 1 %: the 1.55 N
    # spread almost evenly (within 2 %) over the 16 x 16 cells of 2 mm
    flat = reconstruct(frame, "resistive16", order=2, noise_level=5e4)
    assert flat.at_bound is True and flat.regularization == pytest.approx(2046, rel=0.01)
    assert flat.normal_force == pytest.approx(1.546, rel=1e-3)
    assert np.ptp(flat.pressure) < 0.02 * flat.pressure.mean()


@pytest.mark.parametrize("order", [1, 2])
def test_the_lcurve_corner_is_not_the_collapsed_end_of_a_longer_range(frame, order):
    # above sqrt(max g) every mode is more than half filtered and the L-curve shrinks to its
    # end point; searched there, its curvature peaked at the top of the range (lambda 268
    # and 7200 here), where the pressure is a flat 1.5 N spread over the whole array
    result = reconstruct(frame, "resistive16", order=order, regularization="lcurve")
    assert result.regularization < 0.01 * float(result.curve.regularization.max())
    assert result.normal_force == pytest.approx(1.44, rel=0.15)


def test_a_tv_search_that_cannot_reach_its_target_says_so(frame):
    # the residual of any mu stays below tau sigma sqrt(m) = 8e5 Pa: the search gives up
    held = reconstruct(frame, "resistive16", method="tv", noise_level=5e4)
    assert held.at_bound is True
    assert "the discrepancy rule found no mu with its target residual" in held.message
    assert held.residual_norm < 8e5
    fitted = reconstruct(frame, "resistive16", method="tv", noise_level=1e3)
    assert fitted.at_bound is False and "no mu" not in fitted.message
    assert fitted.residual_norm == pytest.approx(1.6e4, rel=0.03)


def test_an_lcurve_corner_at_the_end_of_its_window_is_at_the_bound(frame):
    """The L-curve's corner is sought inside a window of the grid (where the curve has not
    collapsed); a curvature greatest at the window's end is no corner, and says so (it was
    reported as a corner found, at_bound False, on 20 of 20 resistive16 frames at order 0)."""
    from taxel.reconstruction import solver_for

    low, high = solver_for("resistive16", order=0).scan.searched("lcurve")
    grid = solver_for("resistive16", order=0).scan.grid
    assert grid[0] < low < high < grid[-1]  # a window inside the grid
    result = reconstruct(frame, "resistive16", regularization="lcurve")
    assert result.at_bound is True
    assert result.regularization == pytest.approx(low, rel=1e-12)
    assert result.message == (
        f"direct solve; the lcurve rule found no lambda inside [{low:.3g}, {high:.3g}]: "
        f"lambda held at the smallest of its range, {low:.3g}, as the L-curve has no corner "
        "inside"
    )
    # a smooth load at order 2 has its corner inside the window
    rows, cols = np.mgrid[:16, :16]
    smooth = 30e3 * np.exp(-((cols - 7.5) ** 2 + (rows - 7.2) ** 2) / 20)
    readings = forward_operator("resistive16").apply(smooth)
    readings += np.random.default_rng(1).normal(0, 1e3, readings.shape)
    inside = reconstruct(readings, "resistive16", order=2, regularization="lcurve")
    low2, high2 = solver_for("resistive16", order=2).scan.searched("lcurve")
    assert inside.at_bound is False and inside.message == "direct solve"
    assert low2 * 1.5 < inside.regularization < high2 / 1.5
