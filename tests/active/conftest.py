"""Shared fixtures of the active-touch tests: one hold-then-slip trial and one hold."""

import pytest

from taxel.active import SlipScenario, simulate_slip


@pytest.fixture(scope="session")
def slip_scenario():
    """A 2 N contact of a 50 mm ball, held 60 ms, loaded to slip over 100 ms (seed 7)."""
    return SlipScenario(
        kind="slip",
        normal_force=2.0,
        radius=0.05,
        friction=0.8,
        kinetic_ratio=0.8,
        initial_load=0.0,
        hold_time=0.06,
        load_time=0.1,
        sliding_speed=0.04,
        relaxation_time=2e-3,
        direction=0.5,
        seed=7,
    )


@pytest.fixture(scope="session")
def slip(slip_scenario):
    return simulate_slip(slip_scenario)


@pytest.fixture(scope="session")
def hold():
    return simulate_slip(SlipScenario(kind="hold", load_time=0.0, seed=3))
