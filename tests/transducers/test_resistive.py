"""Resistive cells, the readout of eq. 25.6 and the passive-matrix network."""

import numpy as np
import pytest

from taxel.transducers import (
    ResistiveTransducer,
    Transducer,
    invert_resistive_scan,
    piezoresistive_pressure,
    piezoresistive_resistance,
    readout_resistance,
    readout_voltage,
    scan_resistive_matrix,
)
from taxel.transducers._resistive_matrix import _network

LAW = dict(unloaded_resistance=1e5, reference_pressure=1e4, exponent=0.8)
READOUT = dict(supply_voltage=5.0, feedback_resistance=1e3)


def test_cell_law_is_monotonic_nonlinear_and_invertible():
    pressure = np.linspace(0.0, 2e5, 101)
    resistance = piezoresistive_resistance(pressure, **LAW)
    assert resistance[0] == pytest.approx(1e5)
    assert np.all(np.diff(resistance) < 0)
    # non-linear: equal pressure steps give shrinking resistance steps
    assert np.all(np.diff(np.abs(np.diff(resistance))) < 0)
    assert piezoresistive_resistance(1e4, **LAW) == pytest.approx(1e5 * 2**-0.8, rel=1e-12)
    assert np.allclose(piezoresistive_pressure(resistance, **LAW), pressure, atol=1e-6)


def test_eq_25_6_exact_without_series_resistance():
    resistance = np.array([1e2, 3.3e3, 1e5, 4.7e6])
    voltage = readout_voltage(resistance, **READOUT)
    assert np.allclose(voltage, 1e3 * 5.0 / resistance, rtol=1e-15)
    assert np.allclose(readout_resistance(voltage, **READOUT), resistance, rtol=1e-13)


def test_series_resistance_biases_by_exactly_its_value_and_can_be_corrected():
    resistance = np.array([1e2, 1e3, 1e4])
    voltage = readout_voltage(resistance, series_resistance=60.0, **READOUT)
    naive = readout_resistance(voltage, **READOUT)
    assert np.allclose(naive - resistance, 60.0, rtol=1e-9)
    # the relative bias is largest for the small (loaded) resistances
    assert (naive / resistance - 1).tolist() == pytest.approx([0.6, 0.06, 0.006])
    corrected = readout_resistance(voltage, series_resistance=60.0, **READOUT)
    assert np.allclose(corrected, resistance, rtol=1e-12)


def test_supply_variation_scales_the_estimate():
    ripple = 5.0 * (1 + 0.02 * np.sin(np.linspace(0, 2 * np.pi, 9)))
    voltage = readout_voltage(1e4, supply_voltage=ripple, feedback_resistance=1e3)
    estimate = readout_resistance(voltage, **READOUT)
    assert np.allclose(estimate, 1e4 * 5.0 / ripple, rtol=1e-12)


def test_transducer_round_trip_and_protocol():
    cell = ResistiveTransducer(exponent=0.7, series_resistance=120.0)
    assert isinstance(cell, Transducer)
    assert (cell.quantity, cell.quantity_unit, cell.signal_unit) == ("pressure", "Pa", "V")
    pressure = np.linspace(0.0, 2e5, 41)
    assert np.allclose(cell.invert(cell.respond(pressure)), pressure, atol=1e-6)


def _figure_25_4_matrix():
    resistance = np.full((3, 3), 1e3)  # loaded cells
    resistance[1, 0] = 1e5  # R_21, unloaded
    return resistance


def test_ghost_paths_appear_with_floating_lines():
    resistance = _figure_25_4_matrix()
    voltage = scan_resistive_matrix(resistance, unselected="floating", **READOUT)
    apparent = readout_resistance(voltage, **READOUT)
    # R_21 in parallel with the ghost network: the chains row 2 -> col l -> row k -> col 1
    # are 1 kOhm + (1 kOhm || ...) ... the exact two-terminal value is 1234.57 Ohm
    assert apparent[1, 0] == pytest.approx(1234.5679, rel=1e-6)
    # a uniform matrix shows crosstalk too: every cell reads low
    uniform = readout_resistance(
        scan_resistive_matrix(np.full((3, 3), 1e3), unselected="floating", **READOUT),
        **READOUT,
    )
    assert np.all(uniform < 1e3)


def test_two_by_two_floating_closed_form():
    # In a 2x2 matrix the ghost path of cell (0, 0) is the chain R01 + R11 + R10.
    r = np.array([[1e3, 2e3], [3e3, 4e3]])
    voltage = scan_resistive_matrix(r, unselected="floating", **READOUT)
    expected = 1.0 / (1 / 1e3 + 1 / (2e3 + 4e3 + 3e3))
    assert readout_resistance(voltage, **READOUT)[0, 0] == pytest.approx(expected, rel=1e-12)


def test_grounded_lines_remove_crosstalk():
    resistance = _figure_25_4_matrix()
    voltage = scan_resistive_matrix(resistance, unselected="grounded", **READOUT)
    assert np.allclose(readout_resistance(voltage, **READOUT), resistance, rtol=1e-12)


def test_switch_resistance_leaves_a_residue_that_the_inversion_removes():
    resistance = _figure_25_4_matrix()
    setup = dict(READOUT, switch_resistance=50.0, unselected="grounded")
    voltage = scan_resistive_matrix(resistance, **setup)
    naive = readout_resistance(voltage, series_resistance=100.0, **READOUT)
    assert naive[1, 0] == pytest.approx(68091.89, rel=1e-6)  # row sag and ghost leak
    fit = invert_resistive_scan(voltage, **setup)
    assert fit.converged
    assert np.allclose(fit.resistance, resistance, rtol=1e-9)


@pytest.mark.parametrize("unselected", ["floating", "grounded"])
@pytest.mark.parametrize("switch_resistance", [0.0, 80.0])
def test_network_inversion_round_trip(unselected, switch_resistance):
    rng = np.random.default_rng(7)
    resistance = np.exp(rng.uniform(np.log(1e2), np.log(1e6), size=(6, 5)))
    setup = dict(READOUT, switch_resistance=switch_resistance, unselected=unselected)
    fit = invert_resistive_scan(scan_resistive_matrix(resistance, **setup), **setup)
    assert fit.converged and fit.message == "converged"
    assert fit.residual < 1e-10
    assert np.allclose(fit.resistance, resistance, rtol=1e-7)


@pytest.mark.parametrize("unselected", ["floating", "grounded"])
def test_network_jacobian_matches_finite_differences(unselected):
    rng = np.random.default_rng(3)
    conductance = 1 / rng.uniform(1e3, 1e5, size=(3, 4))
    _, jacobian = _network(conductance, 100.0, unselected)
    analytic = jacobian()
    numeric = np.zeros_like(analytic)
    for k in range(3):
        for col in range(4):
            step = np.zeros_like(conductance)
            step[k, col] = 1e-6 * conductance[k, col]
            up = _network(conductance + step, 100.0, unselected)[0]
            down = _network(conductance - step, 100.0, unselected)[0]
            numeric[k, col] = (up - down) / (2 * step[k, col])
    assert np.allclose(analytic, numeric, rtol=1e-5, atol=1e-9 * np.abs(analytic).max())


def test_non_convergence_is_an_outcome():
    resistance = np.exp(np.random.default_rng(1).uniform(np.log(1e2), np.log(1e6), (5, 5)))
    setup = dict(READOUT, unselected="floating")
    fit = invert_resistive_scan(
        scan_resistive_matrix(resistance, **setup), max_iterations=1, **setup
    )
    assert not fit.converged
    assert fit.n_iterations == 1
    assert "no convergence" in fit.message


def test_errors_name_the_parameter():
    with pytest.raises(ValueError, match="`pressure` must be >= 0, got -1"):
        piezoresistive_resistance(-1.0, **LAW)
    with pytest.raises(ValueError, match="`exponent` must be > 0, got 0"):
        ResistiveTransducer(exponent=0.0)
    with pytest.raises(ValueError, match="`series_resistance` must be >= 0, got -5"):
        readout_voltage(1e3, series_resistance=-5.0, **READOUT)
    with pytest.raises(ValueError, match="`resistance` must be > 0, got 0"):
        scan_resistive_matrix(np.zeros((2, 2)), **READOUT)
    with pytest.raises(ValueError, match="`unselected` must be one of floating, grounded"):
        scan_resistive_matrix(np.ones((2, 2)), unselected="open", **READOUT)
    with pytest.raises(ValueError, match="`resistance` must be 2-D"):
        scan_resistive_matrix(np.ones(3), **READOUT)
    with pytest.raises(ValueError, match="`max_iterations` must be a positive integer, got 0"):
        invert_resistive_scan(np.ones((2, 2)), max_iterations=0, **READOUT)


def test_noisy_floating_scan_ends_as_an_outcome_and_beats_the_naive_reading():
    rng = np.random.default_rng(0)
    resistance = np.exp(rng.uniform(np.log(1e2), np.log(1e6), size=(6, 6)))
    setup = dict(READOUT, unselected="floating")
    voltage = scan_resistive_matrix(resistance, **setup)
    noisy = voltage * (1 + 1e-3 * rng.standard_normal(voltage.shape))
    fit = invert_resistive_scan(noisy, **setup)  # no exact positive network exists
    assert not fit.converged and fit.n_iterations == 50
    assert np.all(np.isfinite(fit.resistance)) and np.all(fit.resistance > 0)
    fitted = np.median(np.abs(fit.resistance / resistance - 1))
    naive = np.median(np.abs(readout_resistance(noisy, **READOUT) / resistance - 1))
    # the network model removes the ghosts but amplifies 0.1 % noise about twentyfold
    assert fitted < 0.05 < 0.5 < naive
