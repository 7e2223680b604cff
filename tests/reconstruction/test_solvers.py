"""Solvers: exact recovery, dense/fast agreement, parameter rules, constraints, bad input."""

import pickle

import numpy as np
import pytest

import taxel.reconstruction._tikhonov as tikhonov
from taxel.mechanics import make_indenter, solve_contact
from taxel.reconstruction import (
    ADMMSolver,
    TikhonovSolver,
    forward_model_preset,
    forward_operator,
    lcurve_curvature,
    naive_inverse,
    reconstruct,
)
from taxel.reconstruction._choice import _parabola_vertices

SMALL = forward_model_preset("resistive16", shape=(10, 10))
# vhdta128's ratio of depth to pitch (3.9) on a small grid: badly conditioned
STEEP = forward_model_preset("vhdta128", shape=(24, 24))


def _patch(shape, value=40e3):
    truth = np.zeros(shape)
    truth[3:6, 4:7] = value
    return truth


@pytest.mark.parametrize("order", [0, 1, 2])
@pytest.mark.parametrize("representation", ["dense", "fast"])
def test_exact_recovery_without_noise(order, representation):
    solver = TikhonovSolver(SMALL, order=order, boundary="reflect", representation=representation)
    truth = _patch(SMALL.shape)
    frame = solver.operator.apply(truth)
    result = solver.solve(frame, regularization=0.0)
    assert np.allclose(result.pressure, truth, atol=1e-8 * 40e3)
    # the residual is sqrt(|b|^2 - |fitted|^2): zero to sqrt(rounding)
    assert result.residual_norm < 1e-6 * np.linalg.norm(frame) and result.method == "naive"


def test_exact_recovery_on_the_zero_boundary_model():
    solver = TikhonovSolver(SMALL, order=1)  # dense, exact model
    assert solver.operator.boundary == "zero"
    truth = _patch(SMALL.shape)
    truth[0, 0] = 10e3  # in the corner: no boundary error in the exact model
    result = solver.solve(solver.operator.apply(truth), regularization=0.0)
    assert np.allclose(result.pressure, truth, atol=1e-8 * 40e3)


@pytest.mark.parametrize("oversampling", [1, 2])
@pytest.mark.parametrize("order", [0, 1, 2])
@pytest.mark.parametrize("rule", [1e-2, "gcv", "lcurve", "discrepancy"])
def test_dense_and_fast_solutions_agree(order, oversampling, rule):
    spec = SMALL.with_changes(shape=(6, 7), oversampling=oversampling)
    solvers = [
        TikhonovSolver(spec, order=order, boundary="reflect", representation=r)
        for r in ("dense", "fast")
    ]
    rng = np.random.default_rng(order)
    frame = solvers[0].operator.apply(rng.random(spec.load_shape) * 1e4)
    frame += rng.normal(0, 100, frame.shape)
    dense, fast = (s.solve(frame, regularization=rule, noise_level=100.0) for s in solvers)
    assert dense.regularization == pytest.approx(fast.regularization, rel=1e-6)
    assert np.allclose(
        dense.pressure, fast.pressure, rtol=0, atol=1e-8 * np.abs(dense.pressure).max()
    )
    assert dense.residual_norm == pytest.approx(fast.residual_norm, rel=1e-4, abs=1e-6)


@pytest.mark.parametrize("oversampling", [1, 2, 3])
@pytest.mark.parametrize("order", [0, 1, 2])
@pytest.mark.parametrize("representation", ["dense", "fast"])
def test_cell_variance_is_the_diagonal_of_the_solution_covariance(
    order, oversampling, representation
):
    spec = SMALL.with_changes(shape=(5, 6), oversampling=oversampling)
    solver = TikhonovSolver(spec, order=order, boundary="reflect", representation=representation)
    lam = 0.03
    # the solution map is linear: its columns are the solutions of unit frames
    units = np.eye(30).reshape(30, 5, 6)
    columns = solver.solve(units, regularization=lam).pressure
    expected = (columns**2).sum(axis=0)
    factors = solver.filter_factors(np.array([lam]))[0]
    variance = solver.spectrum.cell_variance(factors)
    assert np.allclose(variance, expected, rtol=1e-9)


def test_corner_cells_of_a_thick_cover_are_noisier():
    # the low modes a thick cover passes peak at the edges of the reflective model
    solver = TikhonovSolver(STEEP, order=0, representation="fast")
    variance = solver.spectrum.cell_variance(solver.filter_factors(np.array([0.05]))[0])
    assert variance[0, 0] > 1.5 * variance[12, 12] and variance[0, 12] > 1.2 * variance[12, 12]


@pytest.mark.parametrize("order", [0, 1, 2])
def test_solution_is_the_minimizer(order):
    solver = TikhonovSolver(STEEP.with_changes(shape=(8, 8), oversampling=2), order=order)
    rng = np.random.default_rng(4)
    frame = rng.normal(0, 1e3, solver.spec.shape)
    result = solver.solve(frame, regularization=0.05)
    from taxel.reconstruction._model import dense_penalty

    matrix = solver.operator.to_matrix()
    x = result.pressure.ravel()
    weight = 0.05**2 * solver.spectrum.scale
    gradient = (
        matrix.T @ (matrix @ x - frame.ravel())
        + weight * dense_penalty(solver.spec.load_shape, order) @ x
    )
    assert np.abs(gradient).max() < 1e-9 * np.abs(matrix.T @ frame.ravel()).max()


def test_lcurve_curvature_agrees_with_finite_differences():
    rng = np.random.default_rng(0)
    g = np.logspace(0, -12, 200)
    beta2 = (np.sqrt(g) + rng.normal(0, 1e-4, g.size)) ** 2
    lam = np.logspace(-6, 0, 3001)
    f = g / (g + lam[:, None] ** 2)
    rho = ((1 - f) ** 2 * beta2).sum(axis=1)
    eta = (f**2 * beta2 / g).sum(axis=1)
    deta = -(4 / lam) * ((1 - f) * f**2 * beta2 / g).sum(axis=1)
    kappa = lcurve_curvature(lam, rho, eta, deta)
    x, y = 0.5 * np.log(rho), 0.5 * np.log(eta)
    dx, dy = np.gradient(x, lam), np.gradient(y, lam)
    ddx, ddy = np.gradient(dx, lam), np.gradient(dy, lam)
    numeric = (dx * ddy - ddx * dy) / (dx**2 + dy**2) ** 1.5
    inner = slice(10, -10)
    assert np.allclose(kappa[inner], numeric[inner], rtol=2e-3, atol=2e-3 * np.abs(kappa).max())
    # and the derivative of eta is the analytic one
    assert np.allclose(np.gradient(eta, lam)[inner], deta[inner], rtol=1e-3)


def test_truncated_svd_keeps_whole_modes():
    solver = TikhonovSolver(SMALL, truncated=True, representation="fast", boundary="reflect")
    factors = solver.filter_factors(np.array([0.7]))
    assert set(np.unique(factors)) <= {0.0, 1.0}
    result = solver.solve(solver.operator.apply(_patch(SMALL.shape)), regularization="gcv")
    assert result.method == "tsvd" and np.isfinite(result.pressure).all()


def test_naive_inverse_blows_up_with_noise_and_regularization_does_not():
    operator = forward_operator(STEEP)
    truth = np.zeros(STEEP.shape)
    truth[8:16, 9:14] = 100e3
    clean = operator.apply(truth)
    errors = {}
    for noise in (1e-4, 1e-3):
        frame = clean + np.random.default_rng(0).normal(0, noise * 413.7e3, clean.shape)
        naive = naive_inverse(frame, STEEP).pressure
        regularized = reconstruct(frame, STEEP, order=1).pressure
        errors[noise] = [
            np.linalg.norm(p - truth) / np.linalg.norm(truth) for p in (naive, regularized)
        ]
    assert errors[1e-3][0] > 10 * errors[1e-3][1]  # naive is useless at 0.1 % noise
    assert errors[1e-3][0] == pytest.approx(10 * errors[1e-4][0], rel=0.05)  # linear in noise
    assert errors[1e-3][1] < 0.5


@pytest.mark.parametrize("method", ["nonneg", "tv"])
@pytest.mark.parametrize("representation", ["dense", "fast"])
def test_constrained_solutions_are_never_negative(method, representation):
    solver = ADMMSolver(SMALL, method=method, boundary="reflect", representation=representation)
    rng = np.random.default_rng(1)
    frame = solver.operator.apply(_patch(SMALL.shape)) + rng.normal(0, 2e3, SMALL.shape)
    for rule in ("gcv", "discrepancy"):
        result = solver.solve(frame, regularization=rule, noise_level=2e3)
        assert result.pressure.min() >= 0.0 and result.converged
        assert result.method == method


@pytest.mark.parametrize("method", ["tikhonov", "tsvd", "nonneg", "tv"])
@pytest.mark.parametrize("rule", ["gcv", "lcurve", "discrepancy"])
def test_a_frame_without_touch_gives_no_pressure_and_no_warning(method, rule):
    # an all-zero frame has no residual at any lambda (its GCV is 0, its noise estimate 0);
    # warnings are errors in the tests
    result = reconstruct(np.zeros(SMALL.shape), SMALL, method=method, regularization=rule)
    assert np.all(result.pressure == 0.0)


def test_total_variation_is_the_same_at_any_pressure_scale():
    # the shrinkage of a gradient of near-zero size divided by it: no overflow at 250 MPa
    # (a spec without a full scale: the noise of 2e7 Pa is beyond resistive16's 2e5 Pa)
    spec = SMALL.with_changes(full_scale=None)
    frame = forward_operator(spec).apply(_patch(spec.shape))
    frame += np.random.default_rng(2).normal(0, 2e3, spec.shape)
    small = reconstruct(frame, spec, method="tv", noise_level=2e3)
    large = reconstruct(frame * 1e4, spec, method="tv", noise_level=2e7)
    assert large.converged
    assert np.allclose(large.pressure, small.pressure * 1e4, rtol=1e-9, atol=1e-9 * 40e7)


def test_tv_recovers_a_punch_better_than_tikhonov():
    spec = forward_model_preset("resistive16")
    truth = np.zeros(spec.shape)
    truth[5:10, 4:9] = 50e3
    frame = forward_operator(spec).apply(truth)
    frame += np.random.default_rng(0).normal(0, 2e3, frame.shape)
    tv = reconstruct(frame, spec, method="tv", regularization="discrepancy", noise_level=2e3)
    tikhonov = reconstruct(frame, spec, order=1, regularization="discrepancy", noise_level=2e3)
    error = [np.linalg.norm(r.pressure - truth) for r in (tv, tikhonov)]
    assert error[0] < 0.7 * error[1]


def test_super_resolution_improves_the_centroid_of_an_edge():
    """A load grid of half the taxel pitch places edges closer, on 12 random edges.

    The truth is solved on a grid 4 times finer than the taxels (neither solver's grid),
    read with 1 % noise. The support method's windowed centroid gains (mean 0.048 -> 0.027
    taxel here; on 3 other draws of 12 edges, 0.033 -> 0.024, 0.028 -> 0.023,
    0.040 -> 0.034). A linear method has no such gain to show: a convolution keeps the
    load's first moment, whatever grid it is solved on (docs/benchmarks.md).
    """
    truth_spec = forward_model_preset("resistive16", oversampling=4)
    operator = forward_operator(truth_spec)
    rng = np.random.default_rng(1)

    def centroid(pressure, pitch, window=True):
        rows, cols = pressure.shape
        x = (np.arange(cols) - (cols - 1) / 2) * pitch
        y = (np.arange(rows) - (rows - 1) / 2) * pitch
        p = np.where(pressure > 0.1 * pressure.max(), pressure, 0.0) if window else pressure
        return np.array([(p.sum(0) * x).sum(), (p.sum(1) * y).sum()]) / p.sum()

    errors: dict[int, list[float]] = {1: [], 2: []}
    for _ in range(12):
        position, angle = tuple(rng.uniform(-3e-3, 3e-3, 2)), rng.uniform(0.0, np.pi)
        heights = make_indenter("edge", length=16e-3).on_grid(
            truth_spec.load_shape, truth_spec.load_pitch, position=position, angle=angle
        )
        truth = solve_contact(
            heights,
            truth_spec.load_pitch,
            truth_spec.material,
            thickness=truth_spec.thickness,
            normal_force=4.0,
        ).pressure
        frame = operator.apply(truth) + rng.normal(0, 0.01 * 200e3, truth_spec.shape)
        expected = centroid(truth, truth_spec.load_pitch, window=False)
        for k in (1, 2):
            spec = truth_spec.with_changes(oversampling=k)
            result = reconstruct(frame, spec, method="support")
            shift = centroid(result.pressure, spec.load_pitch) - expected
            errors[k].append(np.hypot(*shift) / truth_spec.taxel_pitch)
    coarse, fine = np.array(errors[1]), np.array(errors[2])
    assert fine.mean() < 0.7 * coarse.mean()
    assert fine.max() < 0.1  # the centroid target, on every edge


def test_dead_taxels_are_excluded_not_read_as_zero():
    truth = _patch(SMALL.shape)
    spec = SMALL.with_changes(dead_taxels=[(4, 5), (0, 0)])
    results = {}
    for representation in ("dense", "fast"):  # exact elimination; imputation + PCG
        operator = forward_operator(spec, boundary="reflect", representation=representation)
        frame = operator.apply(truth)
        frame[4, 5] = np.nan  # whatever a dead taxel reports is ignored
        frame[0, 0] = 1e9
        options = {"order": 1, "boundary": "reflect", "representation": representation}
        results[representation] = reconstruct(frame, spec, regularization=1e-3, **options)
        excluded = results[representation].pressure
        assert np.abs(excluded - truth).max() < 0.1 * 40e3, representation
        zeroed = np.nan_to_num(frame)  # what reading them as zero would give
        zeroed[0, 0] = 0.0
        wrong = reconstruct(zeroed, SMALL, regularization=1e-3, **options).pressure
        assert np.abs(wrong - truth).max() > 5 * np.abs(excluded - truth).max()
    assert np.allclose(results["dense"].pressure, results["fast"].pressure, atol=1e-6 * 40e3)
    assert results["dense"].residual_norm == pytest.approx(results["fast"].residual_norm, rel=1e-4)


def test_batches_are_solved_frame_by_frame():
    solver = TikhonovSolver(SMALL, order=1)
    rng = np.random.default_rng(3)
    frames = solver.operator.apply(rng.random((2, 3, *SMALL.shape)) * 1e4)
    frames += rng.normal(0, 300, frames.shape)
    batch = solver.solve(frames)
    assert batch.pressure.shape == (2, 3, *SMALL.shape)
    assert batch.regularization.shape == (2, 3)
    single = solver.solve(frames[1, 2])
    assert single.regularization == pytest.approx(batch.regularization[1, 2])
    assert np.allclose(single.pressure, batch.pressure[1, 2])


# 48 x 48 = 2304 modes: above 2048 the scan sums the coefficients in bins of g
BINNED = forward_model_preset("resistive16", shape=(48, 48))


@pytest.mark.parametrize("rule", ["gcv", "lcurve", "discrepancy"])
@pytest.mark.parametrize(
    ("spec", "layout", "count"),
    [(SMALL, {}, 12), (BINNED, {"boundary": "reflect", "representation": "fast"}, 3)],
    ids=["exact", "binned"],
)
def test_each_rule_chooses_the_same_lambda_in_a_batch_as_frame_by_frame(rule, spec, layout, count):
    solver = TikhonovSolver(spec, order=1, **layout)
    rng = np.random.default_rng(8)
    frames = solver.operator.apply(rng.random((count, *spec.shape)) * 1e4)
    frames += rng.normal(0, 300, frames.shape)
    batch = solver.solve(frames, regularization=rule)
    single = [solver.solve(frame, regularization=rule) for frame in frames]
    assert np.allclose(batch.regularization, [r.regularization for r in single], rtol=1e-12)
    assert np.allclose(batch.curve.gcv[1], single[1].curve.gcv, rtol=1e-12)


def test_a_given_lambda_solves_as_a_fresh_solver_does_after_other_lambdas():
    # the filter factors of a given lambda are kept for the frames that follow
    solver = TikhonovSolver(SMALL, order=1)
    rng = np.random.default_rng(2)
    frames = solver.operator.apply(rng.random((4, *SMALL.shape)) * 1e4)
    for lam in (0.05, 0.2, 0.0, 0.2, 0.05):
        kept = solver.solve(frames, regularization=lam)
        fresh = TikhonovSolver(SMALL, order=1).solve(frames, regularization=lam)
        assert np.array_equal(kept.pressure, fresh.pressure)
        assert np.array_equal(kept.residual_norm, fresh.residual_norm)
        assert np.array_equal(kept.solution_norm, fresh.solution_norm)


@pytest.mark.parametrize("rule", ["gcv", "lcurve", "discrepancy", 0.05])
def test_a_batch_solved_in_chunks_equals_the_whole(monkeypatch, rule):
    solver = TikhonovSolver(SMALL, order=1)
    rng = np.random.default_rng(5)
    frames = solver.operator.apply(rng.random((7, *SMALL.shape)) * 1e4)
    frames += rng.normal(0, 300, frames.shape)
    whole = solver.solve(frames, regularization=rule)
    monkeypatch.setattr(tikhonov, "_CHUNK_BYTES", 3 * 8 * frames[0].size)  # 3, 3 and 1
    chunked = solver.solve(frames, regularization=rule)
    assert np.allclose(chunked.pressure, whole.pressure, rtol=1e-12, atol=1e-9)
    for name in ("regularization", "residual_norm", "solution_norm"):
        assert np.allclose(getattr(chunked, name), getattr(whole, name), rtol=1e-12)
    if rule != 0.05:
        assert np.allclose(chunked.curve.gcv, whole.curve.gcv, rtol=1e-12)
        assert np.allclose(chunked.curve.curvature, whole.curve.curvature, rtol=1e-9, atol=1e-12)


def test_a_few_frames_carry_their_curves_and_the_lcurve_rule_takes_their_corner():
    solver = TikhonovSolver(SMALL, order=1)
    rng = np.random.default_rng(4)
    frames = solver.operator.apply(rng.random((6, *SMALL.shape)) * 1e4)
    frames += rng.normal(0, 300, frames.shape)
    curve = solver.solve(frames, regularization="gcv").curve
    assert curve.solution_norm.shape == curve.curvature.shape == (6, curve.regularization.size)
    for index in (0, 5):
        single = solver.solve(frames[index], regularization="gcv").curve
        assert np.allclose(single.solution_norm, curve.solution_norm[index], rtol=1e-12)
        assert np.allclose(single.curvature, curve.curvature[index], rtol=1e-9, atol=1e-12)
        assert np.allclose(curve.frame(index).curvature, curve.curvature[index])
    # |L x| at each grid lambda is the seminorm of the solution at that lambda
    lam = curve.regularization[60]
    solved = solver.solve(frames[3], regularization=float(lam))
    assert curve.solution_norm[3, 60] == pytest.approx(solved.solution_norm, rel=1e-9)
    # the L-curve rule's lambda lies within a grid step of the sampled curvature's maximum
    # (interior, and between the ends where the curve has collapsed to a point and its
    # curvature is noise: below the grid's start, above sqrt(max g))
    chosen = solver.solve(frames[3], regularization="lcurve").regularization
    first = max(solver.scan._first_meaningful, 1)
    last = min(solver.scan._last_meaningful, curve.regularization.size - 1)
    peak = np.argmax(curve.curvature[3, first:last]) + first
    step = np.diff(np.log10(curve.regularization))[0]
    assert abs(np.log10(chosen) - np.log10(curve.regularization[peak])) <= step
    # results with their curves can be pickled (worker processes, caches)
    restored = pickle.loads(pickle.dumps(solver.solve(frames[3], regularization="gcv")))
    assert np.allclose(restored.curve.curvature, curve.curvature[3], rtol=1e-9, atol=1e-12)


def test_the_grid_minimum_is_refined_to_the_parabola_vertex():
    x = np.linspace(-2.0, 2.0, 41)
    vertices = np.array([0.013, -1.37, 1.91])
    y = (x[None, :] - vertices[:, None]) ** 2
    # a constant row: its minimum is the grid's first point, an end, which stays
    y = np.vstack([y, np.full(x.size, 5.0)])
    found = _parabola_vertices(x, y, np.argmin(y, axis=1))
    assert found == pytest.approx([0.013, -1.37, 1.91, -2.0], abs=1e-12)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: reconstruct(np.zeros((4, 4)), "resistive16"), "`frame` must have shape"),
        (lambda: reconstruct(np.full((16, 16), np.nan), "resistive16"), "`frame` must be finite"),
        (
            lambda: reconstruct(np.zeros((0, 16, 16)), "resistive16"),
            r"`frame` must hold at least one frame, got shape \(0, 16, 16\)",
        ),
        (
            lambda: reconstruct(np.zeros((16, 16)), "resistive16", regularization=-1.0),
            "`regularization` must be >= 0, got -1",
        ),
        (
            lambda: reconstruct(np.zeros((16, 16)), "resistive16", regularization=1e200),
            "`regularization` must be <= 1e\\+150 .*, got 1e\\+200",
        ),
        (
            lambda: reconstruct(np.zeros((16, 16)), "resistive16", regularization="oracle"),
            "`regularization` must be a number >= 0 or one of",
        ),
        (lambda: reconstruct(np.zeros((16, 16)), "resistive16", method="magic"), "`method`"),
        (lambda: reconstruct(np.zeros((16, 16)), "resistive16", order=3), "`order` must be"),
        (lambda: reconstruct(np.zeros((16, 16)), "resistive16", tau=0), "`tau` must be > 0"),
    ],
)
def test_bad_input_names_the_parameter(call, message):
    with pytest.raises(ValueError, match=message):
        call()
