"""Piezoelectric film: eqs. 25.14-25.18, the charge amplifier's decay, the current mode."""

import math

import numpy as np
import pytest

from taxel.transducers import (
    PVDF_D33,
    VACUUM_PERMITTIVITY,
    PiezoelectricTransducer,
    Transducer,
    charge_amplifier_output,
    charge_amplifier_stress,
    current_amplifier_output,
    current_amplifier_stress,
    piezoelectric_charge,
    piezoelectric_voltage,
)

AMP = dict(area=2e-6, feedback_capacitance=1e-11)


def test_eqs_25_14_to_25_16_agree():
    stress = np.array([-2e4, -1e3, 5e3])
    charge = piezoelectric_charge(stress, area=2e-6)
    assert np.allclose(charge, -33e-12 * 2e-6 * stress, rtol=1e-15)
    voltage = piezoelectric_voltage(stress, film_thickness=28e-6)
    capacitance = 12.0 * VACUUM_PERMITTIVITY * 2e-6 / 28e-6  # eq. 25.15
    assert np.allclose(voltage, charge / capacitance, rtol=1e-12)


def test_ideal_charge_amplifier_is_eq_25_17():
    stress = -1e4 * np.sin(np.linspace(0, 3, 50)) ** 2
    output = charge_amplifier_output(stress, 1e-3, **AMP)
    assert np.allclose(output, -piezoelectric_charge(stress, area=2e-6) / 1e-11, rtol=1e-12)


@pytest.mark.parametrize("resistance", [1e8, 1e9, 3.7e9])
def test_static_load_decays_with_tau_rf_cf(resistance):
    step = np.full(200, -1e4)
    output = charge_amplifier_output(step, 1e-4, feedback_resistance=resistance, **AMP)
    tau = resistance * 1e-11
    # fitted time constant of the held load's decay
    slope = np.polyfit(np.arange(200) * 1e-4, np.log(output / output[0]), 1)[0]
    assert -1 / slope == pytest.approx(tau, rel=1e-9)
    # the first sample of a step within one interval: g = (tau/dt)(1 - exp(-dt/tau))
    gain = tau / 1e-4 * -math.expm1(-1e-4 / tau)
    assert output[0] == pytest.approx(-PVDF_D33 * 2e-6 * 1e4 / 1e-11 * -gain, rel=1e-12)
    assert abs(output[-1]) < abs(output[0])


def test_reset_discharges_the_feedback_capacitor():
    step = np.full(10, -1e4)
    output = charge_amplifier_output(step, 1e-3, reset_interval=4, **AMP)
    first = output[0]
    assert first < 0
    assert np.allclose(output[:4], first)  # ideal integrator holds the step
    assert np.allclose(output[4:], 0.0)  # after the reset the held load is forgotten


@pytest.mark.parametrize("reset_interval", [None, 7])
@pytest.mark.parametrize("resistance", [math.inf, 5e8])
def test_charge_amplifier_round_trip(reset_interval, resistance):
    rng = np.random.default_rng(2)
    stress = np.cumsum(rng.normal(0, 300, size=(3, 60)), axis=-1)
    kw = dict(AMP, feedback_resistance=resistance, reset_interval=reset_interval)
    output = charge_amplifier_output(stress, 2e-4, **kw)
    assert output.shape == stress.shape
    assert np.allclose(charge_amplifier_stress(output, 2e-4, **kw), stress, atol=1e-6)


def test_current_mode_sees_the_rate_eq_25_18():
    time = np.arange(4000) * 1e-5
    omega = 2 * np.pi * 250.0  # a vibration at 250 Hz
    stress = -500.0 * np.sin(omega * time)
    output = current_amplifier_output(stress, 1e-5, area=1e-6, feedback_resistance=1e9)
    exact = 1e-6 * 1e9 * PVDF_D33 * -500.0 * omega * np.cos(omega * (time - 0.5e-5))
    assert np.allclose(output[1:], exact[1:], rtol=0, atol=1e-4 * np.abs(exact).max())
    held = current_amplifier_output(np.full(5, -1e4), 1e-3, area=1e-6, feedback_resistance=1e9)
    assert np.all(held[1:] == 0.0)  # a steady load is invisible
    recovered = current_amplifier_stress(output, 1e-5, area=1e-6, feedback_resistance=1e9)
    assert np.allclose(recovered, stress, atol=1e-9)


@pytest.mark.parametrize("amplifier", ["charge", "current"])
def test_transducer_round_trip(amplifier):
    film = PiezoelectricTransducer(amplifier=amplifier)
    assert isinstance(film, Transducer)
    assert (film.quantity, film.quantity_unit, film.signal_unit) == ("stress", "Pa", "V")
    stress = -1e4 * np.sin(np.linspace(0, np.pi, 80)) ** 2
    recovered = film.invert(film.respond(stress, time_step=1e-3), time_step=1e-3)
    assert np.max(np.abs(recovered - stress)) < 1e-6 * 1e4
    assert film.time_constant == pytest.approx(0.1)


def test_errors_name_the_parameter():
    with pytest.raises(ValueError, match="`feedback_capacitance` must be > 0, got 0"):
        charge_amplifier_output([0.0, 1.0], 1e-3, area=1e-6, feedback_capacitance=0.0)
    with pytest.raises(ValueError, match="`time_step` must be > 0, got -0.001"):
        current_amplifier_output([0.0, 1.0], -1e-3, area=1e-6, feedback_resistance=1e6)
    with pytest.raises(ValueError, match="`reset_interval` must be a positive integer, got 0"):
        PiezoelectricTransducer(reset_interval=0)
    with pytest.raises(ValueError, match="`amplifier` must be one of charge, current"):
        PiezoelectricTransducer(amplifier="voltage")
    with pytest.raises(ValueError, match="`d33` must be non-zero, got 0"):
        piezoelectric_charge(1.0, area=1e-6, d33=0.0)
    with pytest.raises(ValueError, match="`feedback_resistance` must be finite, got inf"):
        PiezoelectricTransducer(amplifier="current", feedback_resistance=math.inf)
    with pytest.raises(ValueError, match="`stress` must be a time series"):
        PiezoelectricTransducer().respond(1.0, time_step=1e-3)
    with pytest.raises(ValueError, match=r"`stress` must be a time series .*, got shape \(0,\)"):
        charge_amplifier_output(np.zeros(0), 1e-3, area=1e-6, feedback_capacitance=1e-11)
