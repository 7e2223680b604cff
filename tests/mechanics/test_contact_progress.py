"""solve_contact's progress(done, total): one call per iteration, over every window, to total."""

import numpy as np
import pytest

from taxel.mechanics import ElasticMaterial, Sphere, solve_contact

COVER = ElasticMaterial(1e6, 0.5)
SHAPE, SPACING, RADIUS = (64, 64), 0.1e-3, 10e-3


@pytest.fixture(scope="module")
def heights():
    return Sphere(RADIUS).on_grid(SHAPE, SPACING)


def _record(calls):
    return lambda done, total: calls.append((done, total))


def _check_counts(calls, result, budget):
    done = [d for d, _ in calls]
    assert {t for _, t in calls} == {budget}  # the same total in every call
    assert done[: result.n_iterations] == list(range(1, result.n_iterations + 1))
    assert calls[-1] == (budget, budget)  # finished: the bar ends full
    assert len(calls) == result.n_iterations + (result.n_iterations < budget)


def test_one_call_per_iteration_then_the_budget(heights):
    calls = []
    result = solve_contact(heights, SPACING, COVER, normal_force=0.5, progress=_record(calls))
    assert result.converged and 1 < result.n_iterations < 2000
    _check_counts(calls, result, 2000)
    # the callback changes nothing of the solve
    plain = solve_contact(heights, SPACING, COVER, normal_force=0.5)
    assert np.array_equal(plain.pressure, result.pressure)
    assert plain.n_iterations == result.n_iterations


def test_counts_run_on_over_the_windows_tried(heights):
    # a warm start from a smaller contact outgrows its first window and solves again
    small = solve_contact(heights, SPACING, COVER, normal_force=0.05)
    calls = []
    result = solve_contact(
        heights, SPACING, COVER, normal_force=1.0, initial=small, progress=_record(calls)
    )
    assert "2 window(s)" in result.message or "3 window(s)" in result.message
    _check_counts(calls, result, 2000)


def test_an_unconverged_solve_ends_at_its_budget(heights):
    calls = []
    result = solve_contact(
        heights,
        SPACING,
        COVER,
        normal_force=0.5,
        max_iterations=3,
        tolerance=1e-15,
        progress=_record(calls),
    )
    assert not result.converged
    assert calls == [(1, 3), (2, 3), (3, 3)]


@pytest.mark.parametrize("load", [{"normal_force": 0.0}, {"indentation": 0.0}])
def test_nothing_to_solve_is_done_at_once(heights, load):
    calls = []
    solve_contact(heights, SPACING, COVER, max_iterations=50, progress=_record(calls), **load)
    assert calls == [(50, 50)]


def test_indentation_control_reports_too(heights):
    calls = []
    result = solve_contact(heights, SPACING, COVER, indentation=20e-6, progress=_record(calls))
    _check_counts(calls, result, 2000)


def test_progress_must_be_callable(heights):
    with pytest.raises(TypeError, match="`progress` must be a callable"):
        solve_contact(heights, SPACING, COVER, normal_force=0.5, progress=5)
