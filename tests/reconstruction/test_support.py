"""Non-negative least squares on the support of a regularized estimate."""

import numpy as np
import pytest
from scipy import optimize

from taxel.reconstruction import (
    ReconstructionResult,
    SupportSolver,
    forward_model_preset,
    nonneg_quadratic,
    reconstruct,
    solver_for,
)
from taxel.reconstruction._restricted import component_scores

SMALL = forward_model_preset("resistive16", shape=(12, 12))
THICK = forward_model_preset("vhdta128", shape=(40, 40))  # d = 3.9 pitches


def _centroid(pressure):
    rows, cols = np.indices(pressure.shape)
    return np.array([(pressure * rows).sum(), (pressure * cols).sum()]) / pressure.sum()


@pytest.mark.parametrize("seed", range(4))
def test_nonneg_quadratic_meets_the_kkt_conditions(seed):
    rng = np.random.default_rng(seed)
    factor = rng.normal(size=(40, 30))
    matrix = factor.T @ factor + 0.1 * np.eye(30)
    vector = rng.normal(size=30) * 5
    y, iterations, converged = nonneg_quadratic(matrix, vector, vector > 0)
    multiplier = matrix @ y - vector
    assert y.min() >= 0 and multiplier.min() > -1e-9 and converged
    assert np.abs(y * multiplier).max() < 1e-9  # complementarity
    root = np.linalg.cholesky(matrix).T  # matrix = root^T root
    reference, _ = optimize.nnls(root, np.linalg.solve(root.T, vector))
    assert np.allclose(y, reference, atol=1e-8)


@pytest.mark.parametrize(
    "spec, options",
    [
        (SMALL, {"representation": "fast", "boundary": "reflect"}),  # gathered from a kernel
        (SMALL.with_changes(oversampling=2), {"representation": "fast", "boundary": "reflect"}),
        (SMALL.with_changes(dead_taxels=[(2, 3)]), {"representation": "fast"}),
    ],
    ids=["kernel", "columns-oversampled", "columns-dead-taxel"],
)
def test_restricted_normal_matrix_agrees_with_the_dense_one(spec, options):
    solver = SupportSolver(spec, **options)
    dense = SupportSolver(spec, representation="dense", boundary="reflect")
    live = spec.live_taxels
    cells = np.array([0, 7, 30, 31, 55, 100, 143])
    matrix = dense.spectrum._matrix
    expected = matrix[:, cells].T @ matrix[:, cells]
    assert np.allclose(solver._normal_block(cells, live), expected, atol=1e-10 * expected.max())


def test_force_and_centroid_of_a_compact_load():
    solver = SupportSolver(THICK)
    truth = np.zeros(THICK.shape)
    rows, cols = np.indices(THICK.shape)
    inside = (rows - 19.3) ** 2 + (cols - 21.6) ** 2 < 5.2**2
    truth[inside] = 150e3 * np.sqrt(1 - ((rows - 19.3) ** 2 + (cols - 21.6) ** 2)[inside] / 5.2**2)
    frame = solver.operator.apply(truth)
    frame += np.random.default_rng(5).normal(0.0, 0.01 * THICK.full_scale, frame.shape)
    result = solver.solve(frame)
    assert result.method == "support" and result.pressure.min() >= 0 and result.converged
    # the rim may be peeled where the load fades, not where it is strong
    assert result.support[truth > 0.6 * truth.max()].all()
    assert result.normal_force == pytest.approx(truth.sum() * THICK.load_pitch**2, rel=0.01)
    assert np.hypot(*(_centroid(result.pressure) - _centroid(truth))) < 0.05
    # the same in metres in the sensor frame, from the result itself
    row, col = _centroid(truth)
    centre = [(col - (truth.shape[1] - 1) / 2), (row - (truth.shape[0] - 1) / 2)]
    shift = np.subtract(result.centroid_m, np.multiply(centre, THICK.load_pitch))
    assert np.hypot(*shift) < 0.05 * THICK.load_pitch
    # the whole-map Tikhonov estimate it started from carries the noise of every taxel
    linear = reconstruct(frame, THICK)
    assert np.hypot(*(_centroid(linear.pressure) - _centroid(truth))) > 0.1


def test_peeling_the_rim_sharpens_point_loads():
    spec = forward_model_preset("resistive16", shape=(12, 12), oversampling=2)
    truth = np.zeros(spec.load_shape)
    truth[11, [9, 14]] = 0.5 / spec.load_pitch**2  # two 0.5 N points 2.5 mm apart
    peeled, kept = SupportSolver(spec), SupportSolver(spec, refinements=0)
    errors = {True: [], False: []}
    for seed in range(4):
        frame = peeled.operator.apply(truth)
        frame += np.random.default_rng(seed).normal(0.0, 2e3, frame.shape)
        for solver, key in ((peeled, True), (kept, False)):
            result = solver.solve(frame)
            errors[key].append(result.normal_force - 1.0)
            if key:
                assert result.support[11, [9, 14]].all() and "refinement" in result.message
    # the blur-wide support keeps the positive half of the noise of its extra cells
    assert np.mean(errors[False]) > 0.03
    assert abs(np.mean(errors[True])) < 0.02


def test_dense_and_fast_factorizations_give_the_same_solution():
    truth = np.zeros(SMALL.shape)
    truth[4:7, 6:8] = 90e3
    solvers = [
        SupportSolver(SMALL, representation=r, boundary="reflect") for r in ("dense", "fast")
    ]
    frame = solvers[0].operator.apply(truth)
    frame += np.random.default_rng(6).normal(0.0, 1e3, frame.shape)
    dense, fast = (s.solve(frame) for s in solvers)
    assert np.array_equal(dense.support, fast.support)
    assert dense.regularization == pytest.approx(fast.regularization, rel=1e-6)
    assert np.allclose(dense.pressure, fast.pressure, atol=1e-6 * 90e3)


def test_nothing_to_find_and_too_much_to_find():
    solver = SupportSolver(SMALL)
    empty = solver.solve(np.zeros(SMALL.shape), regularization=0.1)
    assert not empty.support.any() and np.all(empty.pressure == 0.0)
    assert empty.first_regularization == 0.1 and empty.regularization == 0.0
    assert empty.message.startswith("support of 0 cells")
    truth = np.full(SMALL.shape, 50e3)
    frame = solver.operator.apply(truth) + np.random.default_rng(7).normal(0, 1e3, SMALL.shape)
    spread = SupportSolver(SMALL, max_cells=20).solve(frame)
    assert spread.support is None and "more than 20 cells" in spread.message
    assert spread.regularization == spread.first_regularization > 0  # the non-negative solve
    assert spread.pressure.min() >= 0


def test_through_reconstruct_and_bad_input():
    truth = np.zeros(SMALL.shape)
    truth[3:5, 3:5] = 60e3
    frame = solver_for(SMALL, method="support").operator.apply(truth)
    result = reconstruct(frame + 1.0, SMALL, method="support", regularization="gcv")
    assert result.method == "support" and result.rule == "gcv"
    assert solver_for(SMALL, method="support") is solver_for(SMALL, method="support")
    with pytest.raises(ValueError, match="`frame` must be one frame"):
        reconstruct(np.zeros((2, *SMALL.shape)), SMALL, method="support")
    with pytest.raises(ValueError, match="`threshold` must be > 0"):
        SupportSolver(SMALL, threshold=0.0)
    with pytest.raises(ValueError, match="`max_cells` must be >= 1"):
        SupportSolver(SMALL, max_cells=0)
    with pytest.raises(ValueError, match="`refinements` must be >= 0"):
        SupportSolver(SMALL, refinements=-1)


def test_component_scores_of_independent_cells():
    # A^T A diagonal (cells that do not overlap), no ridge: x_i = h_i / e_i with variance
    # 1 / e_i, so a group's total over its std is sum(h / e) / sqrt(sum(1 / e))
    eigenvalues = np.array([4.0, 1.0, 9.0, 2.0])
    rhs = np.array([8.0, -1.0, 3.0, 1.0])
    labels = np.array([1, 1, 2, 2])
    scores = component_scores(np.diag(eigenvalues), rhs, 0.0, labels)
    expected = [(2.0 - 1.0) / np.sqrt(1 / 4 + 1), (1 / 3 + 0.5) / np.sqrt(1 / 9 + 1 / 2)]
    assert np.allclose(scores, expected)


def test_a_weak_second_contact_far_away_is_kept():
    # step 5 drops lone components that are weak in the restricted fit, not real ones
    solver = SupportSolver(THICK)
    truth = np.zeros(THICK.shape)
    truth[18:22, 18:22] = 100e3
    sigma = 0.01 * THICK.full_scale
    frame = solver.operator.apply(truth) + np.random.default_rng(8).normal(0, sigma, THICK.shape)
    first = solver.linear.solve(frame)
    factors = solver.linear.filter_factors(np.atleast_1d(first.regularization))[0]
    std = float(first.noise_level) * np.sqrt(solver.spectrum.cell_variance(factors))
    # a real load at (5, 33) whose first estimate just clears the threshold: it stays
    unit = np.zeros(THICK.shape)
    unit[5, 33] = 1.0
    gain = solver.linear.solve(solver.operator.apply(unit), regularization=first.regularization)
    weak = 1.3 * solver.threshold * std[5, 33] / gain.pressure[5, 33]
    result = solver.solve(frame + weak * solver.operator.apply(unit))
    assert result.support[5, 33] and "dropped" not in result.message


def test_a_batch_has_a_centroid_per_frame_and_nan_without_force():
    truth = np.zeros(SMALL.shape)
    truth[2:4, 8:10] = 50e3  # rows 2-3, columns 8-9 of 12: (x, y) = (3, -3) pitches
    frames = np.stack([SupportSolver(SMALL).operator.apply(truth), np.zeros(SMALL.shape)])
    result = reconstruct(frames, SMALL, regularization=1e-9)  # exact without noise
    assert result.centroid_m.shape == (2, 2)
    np.testing.assert_allclose(result.centroid_m[0] / SMALL.load_pitch, [3.0, -3.0], atol=1e-3)
    assert np.isnan(result.centroid_m[1]).all()


def test_the_first_stage_keeps_the_lambda_its_rule_gave():
    # the result's lambda is the support stage's (GCV); the first stage's, chosen by the
    # rule the caller named, was lost: a given 0.01 read back as "given" 0.0046
    truth = np.zeros(SMALL.shape)
    truth[3:5, 3:5] = 60e3
    solver = solver_for(SMALL, method="support")
    frame = solver.operator.apply(truth) + np.random.default_rng(8).normal(0, 1e3, SMALL.shape)
    given = solver.solve(frame, regularization=0.01)
    assert given.rule == "given" and given.first_regularization == 0.01
    assert given.support.any() and given.regularization != 0.01
    chosen = solver.solve(frame, regularization="gcv")
    gcv = solver.linear.solve(frame, regularization="gcv").regularization
    assert chosen.first_regularization == pytest.approx(gcv, rel=1e-12)
    assert reconstruct(frame, SMALL).first_regularization is None  # one stage: tikhonov


def test_a_centre_of_pressure_off_the_grid_is_nan():
    # a field pulling almost as much as it pushes: halves of +100 and -99.6 kPa put its
    # centre about 2000 pitches off the 16-pitch map, which means nothing: NaN
    pressure = np.zeros((2, 16, 16))
    pressure[:, :, :8] = 100e3
    pressure[0, :, 8:] = -99.6e3
    pressure[1, :, 8:] = 50e3  # pressing everywhere: its centre lies on the grid
    result = ReconstructionResult(
        pressure, 0.0, "given", "naive", 0, 0.0, 0.0, None, None, spacing=1e-3
    )
    assert np.isnan(result.centroid_m[0]).all()
    x, y = result.centroid_m[1] / result.spacing
    assert x == pytest.approx((100 * -4 + 50 * 4) / 150) and abs(y) < 1e-9
