"""Capacitive taxels: eqs. 25.7-25.13, stray capacitance, temperature and shear."""

import numpy as np
import pytest

from taxel.transducers import (
    VACUUM_PERMITTIVITY,
    CapacitiveTransducer,
    Transducer,
    capacitance_from_detector_voltage,
    detector_voltage,
    plate_capacitance,
    strain_from_detector_voltage,
)

PLATES = dict(plate_width=2e-3, plate_length=1e-3, permittivity=2.8 * VACUUM_PERMITTIVITY)
C0 = 2.8 * VACUUM_PERMITTIVITY * 2e-3 * 1e-3 / 1e-4


def detector(omega=2 * np.pi * 1e5, stray=1e-10):
    return dict(
        detector_resistance=1e6,
        detector_capacitance=stray,
        angular_frequency=omega,
        source_voltage=5.0,
    )


def test_eqs_25_9_and_25_11():
    assert plate_capacitance(1e-4, **PLATES) == pytest.approx(C0, rel=1e-14)
    dh = np.array([0.0, 1e-5, 5e-5])
    assert np.allclose(plate_capacitance(1e-4 - dh, **PLATES), C0 * 1e-4 / (1e-4 - dh))


def test_eq_25_8_is_the_limit_of_eq_25_7():
    capacitance = 1e-12
    errors = []
    for stray in (1e-11, 1e-10, 1e-9):
        exact = detector_voltage(capacitance, **detector(omega=1e9, stray=stray))
        approx = detector_voltage(capacitance, approximate=True, **detector(stray=stray))
        errors.append(float(1 - exact / approx))
        # at large omega the only difference is C_ij in the denominator
        assert errors[-1] == pytest.approx(capacitance / (capacitance + stray), rel=1e-6)
    assert errors[0] > errors[1] > errors[2]
    # at low omega eq. 25.7 rolls off and eq. 25.8 does not
    slow = detector_voltage(capacitance, **detector(omega=1e3))
    assert slow < 0.6 * detector_voltage(capacitance, approximate=True, **detector())


@pytest.mark.parametrize("approximate", [False, True])
def test_detector_inverse(approximate):
    capacitance = np.array([0.0, 1e-13, 1e-12, 3e-11])
    setup = detector(omega=2e4, **{}) | {"approximate": approximate}
    voltage = detector_voltage(capacitance, **setup)
    assert np.allclose(capacitance_from_detector_voltage(voltage, **setup), capacitance, atol=0)


def test_eq_25_13_exact_under_eq_25_8_and_biased_under_eq_25_7():
    dh = np.array([0.01, 0.05, 0.1, 0.2, 0.4]) * 1e-4
    true_strain = -dh / 1e-4
    capacitance = plate_capacitance(1e-4 - dh, **PLATES)
    setup = detector(omega=1e9)
    v0_approx = detector_voltage(C0, approximate=True, **setup)
    v_approx = detector_voltage(capacitance, approximate=True, **setup)
    assert np.allclose(strain_from_detector_voltage(v_approx, v0_approx), true_strain, rtol=1e-12)

    v0 = detector_voltage(C0, **setup)
    estimate = strain_from_detector_voltage(detector_voltage(capacitance, **setup), v0)
    error = np.abs(estimate - true_strain)
    assert np.all(np.diff(error) > 0)  # grows with the strain
    # high-frequency closed form: the estimate is scaled by C_d / (C0 + C_d)
    assert np.allclose(estimate, true_strain * 1e-10 / (C0 + 1e-10), rtol=1e-8)
    # normalising by |V_d0| instead is the small-strain form, with a second-order error
    linearised = (v_approx - v0_approx) / v0_approx
    assert np.allclose(linearised, dh / (1e-4 - dh), rtol=1e-12)
    assert np.all(np.diff(np.abs(linearised + true_strain) / np.abs(true_strain)) > 0)


def test_stray_capacitance_dilutes_the_strain():
    cell = CapacitiveTransducer(stray_capacitance=0.5e-12, detector_capacitance=1e-6)
    c0 = VACUUM_PERMITTIVITY * 3.0 * 1e-6 / 1e-4
    estimate = cell.invert(cell.respond(-0.1), method="chapter")
    # under eq. 25.8 with C_s in parallel: (1 - C0_total / C_total) = 0.1 C0 / (C0 + 0.9 C_s)
    expected = -(1 - (c0 + 0.5e-12) / (c0 / 0.9 + 0.5e-12))
    assert estimate == pytest.approx(expected, rel=1e-5)
    assert abs(estimate) < 0.05
    assert cell.invert(cell.respond(-0.1)) == pytest.approx(-0.1, rel=1e-9)


def test_temperature_shifts_the_unloaded_reading():
    cell = CapacitiveTransducer(
        permittivity_temperature_coefficient=-1e-3, gap_temperature_coefficient=3e-4
    )
    warm = cell.reference_temperature + 20.0
    ratio = cell.respond(0.0, temperature=warm) / cell.respond(0.0)
    expected_capacitance_ratio = (1 - 0.02) / (1 + 0.006)
    assert ratio == pytest.approx(expected_capacitance_ratio, rel=1e-3)  # eq. 25.8 regime
    apparent = cell.invert(cell.respond(0.0, temperature=warm))
    assert apparent == pytest.approx(1 / expected_capacitance_ratio - 1, rel=1e-9)
    assert abs(cell.invert(cell.respond(-0.1, temperature=warm), temperature=warm) + 0.1) < 1e-12


def test_shear_offset_reduces_the_overlap():
    cell = CapacitiveTransducer()
    offsets = np.array([0.0, 1e-4, 2e-4, -2e-4])
    signal = cell.respond(-0.1, shear_offset=offsets)
    assert np.all(np.diff(signal[:3]) < 0)
    assert signal[2] == pytest.approx(signal[3], rel=1e-15)
    capacitance = cell.capacitance(-0.1, shear_offset=offsets)
    assert np.allclose(capacitance / capacitance[0], 1 - np.abs(offsets) / 1e-3)
    # a pure shear reads as a tension of l / (l - |dx|) - 1
    assert cell.invert(cell.respond(0.0, shear_offset=2e-4)) == pytest.approx(0.25, rel=1e-9)


def test_round_trip_and_protocol():
    cell = CapacitiveTransducer(stray_capacitance=1e-13, angular_frequency=1e4)
    assert isinstance(cell, Transducer)
    assert (cell.quantity, cell.quantity_unit, cell.signal_unit) == ("strain", "-", "V")
    strain = np.linspace(-0.5, 0.2, 29)
    assert np.allclose(cell.invert(cell.respond(strain)), strain, atol=1e-10)


def test_errors_name_the_parameter():
    with pytest.raises(ValueError, match="`gap` must be > 0, got 0"):
        plate_capacitance(0.0, **PLATES)
    with pytest.raises(ValueError, match="`gap` must be > 0, got -1e-05"):
        CapacitiveTransducer(gap=-1e-5)
    with pytest.raises(ValueError, match="`shear_offset` must satisfy"):
        plate_capacitance(1e-4, shear_offset=2e-3, **PLATES)
    with pytest.raises(ValueError, match="`voltage` must lie in"):
        capacitance_from_detector_voltage(5.0, **detector())
    with pytest.raises(ValueError, match="`strain` must be > -1, got -1"):
        CapacitiveTransducer().respond(-1.0)
    with pytest.raises(ValueError, match="`method` must be one of exact, chapter"):
        CapacitiveTransducer().invert(0.01, method="linear")
    with pytest.raises(ValueError, match="`detector_capacitance` must be > 0"):
        detector_voltage(1e-12, **detector(stray=0.0))


def test_arrays_that_do_not_broadcast_are_named():
    wrong_length = r"`gap`, `permittivity` and `shear_offset` must have shapes that broadcast"
    permittivity = np.full(2, 2.8 * VACUUM_PERMITTIVITY)
    with pytest.raises(ValueError, match=wrong_length + r" together, got \(3,\), \(2,\) and \(\)"):
        plate_capacitance(
            np.full(3, 1e-4), plate_width=2e-3, plate_length=1e-3, permittivity=permittivity
        )
    # one permittivity per cell broadcasts
    cells = plate_capacitance(
        np.full(2, 1e-4), plate_width=2e-3, plate_length=1e-3, permittivity=permittivity
    )
    assert cells == pytest.approx([C0, C0])
    with pytest.raises(ValueError, match=r"`voltage` and `unloaded_voltage` .* \(3,\) and \(2,\)"):
        strain_from_detector_voltage(np.ones(3), np.ones(2))
    cell = CapacitiveTransducer()
    given = r"`strain`, `shear_offset` and `temperature` must have shapes that broadcast"
    with pytest.raises(ValueError, match=given + r" together, got \(3,\), \(\) and \(2,\)"):
        cell.respond(np.zeros(3), temperature=np.full(2, 300.0))
    with pytest.raises(ValueError, match=given + r" together, got \(3,\), \(2,\) and \(\)"):
        cell.respond(np.zeros(3), shear_offset=np.zeros(2))
