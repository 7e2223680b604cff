"""The iterative solvers' progress(done, total): every iteration of every run, to the budget."""

import numpy as np
import pytest

from taxel.reconstruction import ADMMSolver, forward_model_preset, reconstruct

SPEC = forward_model_preset("resistive16", shape=(8, 8))


@pytest.fixture(scope="module")
def frame():
    truth = np.zeros((8, 8))
    truth[2:5, 3:6] = 40e3
    solver = ADMMSolver(SPEC, method="nonneg")
    noisy = solver.operator.apply(truth)
    return noisy + np.random.default_rng(3).normal(0.0, 400.0, noisy.shape)


def _record(calls):
    return lambda done, total: calls.append((done, total))


@pytest.mark.parametrize(
    ("method", "rule", "runs"),
    [
        ("nonneg", "discrepancy", 1),
        ("tv", 300.0, 1),  # a given mu: one run
        ("tv", "discrepancy", 10),  # the search for mu: up to 10 runs
        ("tv", "gcv", 11),  # and first a nonneg run for the target residual
    ],
)
def test_every_iteration_is_counted_and_the_bar_ends_full(frame, method, rule, runs):
    solver = ADMMSolver(SPEC, method=method, max_iterations=200)
    states = []
    plain = solver.solve(frame, regularization=rule, callback=states.append)
    calls, counted = [], []
    result = solver.solve(
        frame, regularization=rule, callback=counted.append, progress=_record(calls)
    )
    budget = runs * 200
    assert {total for _, total in calls} == {budget}
    done = [d for d, _ in calls]
    assert done == [*range(1, len(done)), budget]  # one by one, then the whole budget
    assert len(done) >= len(counted) >= result.n_iterations  # a companion's run counts too
    # the progress changes nothing: the same result, the same callback states
    assert len(counted) == len(states)
    assert np.array_equal(plain.pressure, result.pressure)
    assert plain.regularization == result.regularization


def test_a_run_that_uses_its_whole_budget_is_not_told_twice(frame):
    solver = ADMMSolver(SPEC, method="tv", max_iterations=5, tolerance=1e-15)
    calls = []
    solver.solve(frame, regularization=300.0, progress=_record(calls))
    assert calls == [(1, 5), (2, 5), (3, 5), (4, 5), (5, 5)]


def test_reconstruct_passes_it_to_the_iterative_methods_only(frame):
    calls = []
    reconstruct(frame, SPEC, method="tv", regularization=300.0, progress=_record(calls))
    assert calls[0] == (1, 1000) and calls[-1] == (1000, 1000)
    for method in ("tikhonov", "tsvd", "support"):
        silent = []
        reconstruct(frame, SPEC, method=method, progress=_record(silent))
        assert silent == []


@pytest.mark.parametrize("method", ["tv", "tikhonov"])
def test_progress_must_be_callable(frame, method):
    with pytest.raises(TypeError, match="`progress` must be a callable"):
        reconstruct(frame, SPEC, method=method, progress="bar")
