"""Microbend fiber array (Figure 25.11): projections, attenuation, inverse to line loads."""

import numpy as np
import pytest

from taxel.transducers import (
    MicrobendTransducer,
    Transducer,
    microbend_line_loads,
    microbend_power,
    separable_pressure,
)

OPTICS = dict(stiffness=1e5, bend_loss=2.3e4, source_power=2e-3, transmission=0.7)


def test_each_fiber_reads_one_projection():
    rng = np.random.default_rng(4)
    pressure = rng.uniform(0, 5e4, size=(5, 7))
    power = microbend_power(pressure, crossing_area=2.5e-5, **OPTICS)
    assert power.shape == (12,)
    loads = microbend_line_loads(power, **OPTICS)
    force = pressure * 2.5e-5
    assert np.allclose(loads[:5], force.sum(axis=1), rtol=1e-12)
    assert np.allclose(loads[5:], force.sum(axis=0), rtol=1e-12)
    # the two layers see the same total force
    assert loads[:5].sum() == pytest.approx(loads[5:].sum(), rel=1e-12)


def test_transmission_is_exponential_in_deflection():
    forces = np.linspace(0, 3, 7)  # [N] on a single crossing
    pressure = (forces / 2.5e-5)[:, None, None]
    power = microbend_power(pressure, crossing_area=2.5e-5, **OPTICS)[:, 0]
    deflection = forces / 1e5
    assert np.allclose(power, 2e-3 * 0.7 * np.exp(-2.3e4 * deflection), rtol=1e-12)
    decibels = MicrobendTransducer(rows=1, cols=1, **OPTICS).attenuation(
        np.stack([power, power], axis=-1)
    )[:, 0]
    # linear in decibels: 0.1 dB per um of deflection, 10 um per N
    assert np.allclose(decibels, 10 * np.log10(np.e) * 2.3e4 * deflection, rtol=1e-12)
    assert decibels[2] == pytest.approx(0.99888, rel=1e-5)


def test_separable_estimate_exact_for_one_contact_and_ghosts_for_two():
    gauss = np.exp(-0.5 * ((np.arange(9) - 3.0) / 1.2) ** 2)
    single = 3e4 * np.outer(gauss, np.roll(gauss, 2))
    array = MicrobendTransducer(rows=9, cols=9, **OPTICS)
    assert np.allclose(array.invert(array.respond(single)), single, atol=1e-6)
    double = np.zeros((9, 9))
    double[1, 1] = double[7, 7] = 4e4
    estimate = array.invert(array.respond(double))
    assert estimate.sum() == pytest.approx(double.sum(), rel=1e-9)  # total force kept
    assert estimate[1, 7] == pytest.approx(2e4, rel=1e-9)  # ...but ghosts appear
    assert estimate[1, 1] == pytest.approx(2e4, rel=1e-9)


def test_batches_and_round_trip_within_full_scale():
    rng = np.random.default_rng(0)
    pressure = rng.uniform(0, 4e4, size=(3, 2, 4, 6))
    array = MicrobendTransducer(rows=4, cols=6)
    assert isinstance(array, Transducer)
    assert (array.quantity, array.quantity_unit, array.signal_unit) == ("pressure", "Pa", "W")
    signal = array.respond(pressure)
    assert signal.shape == (3, 2, 10)
    force = pressure * array.crossing_area
    loads = array.line_loads(signal)
    full_scale = 4e4 * array.crossing_area * 6
    assert np.max(np.abs(loads[..., :4] - force.sum(-1))) < 1e-9 * full_scale
    assert np.max(np.abs(loads[..., 4:] - force.sum(-2))) < 1e-9 * full_scale


def test_zero_load_inverts_to_zero():
    array = MicrobendTransducer(rows=2, cols=3)
    assert np.all(array.invert(array.respond(np.zeros((2, 3)))) == 0)


def test_errors_name_the_parameter():
    with pytest.raises(ValueError, match="`pressure` must be >= 0, got -1"):
        microbend_power(-np.ones((2, 2)), crossing_area=1e-4, **OPTICS)
    with pytest.raises(ValueError, match="`transmission` must lie in"):
        microbend_power(
            np.ones((2, 2)), crossing_area=1e-4, stiffness=1, bend_loss=1, transmission=0
        )
    with pytest.raises(ValueError, match="`power` must be > 0, got 0"):
        microbend_line_loads([0.0, 1.0], **OPTICS)
    with pytest.raises(ValueError, match=r"`pressure` must end in shape \(2, 3\)"):
        MicrobendTransducer(rows=2, cols=3).respond(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="`rows` must be a positive integer, got 0"):
        MicrobendTransducer(rows=0)
    with pytest.raises(ValueError, match="`signal` must end in length rows"):
        MicrobendTransducer(rows=2, cols=3).invert(np.ones(4))
    with pytest.raises(ValueError, match=r"`rows` must be an integer in 1..4, got 5"):
        separable_pressure(np.ones(5), rows=5, crossing_area=1.0)


def test_separable_pressure_checks_the_fiber_counts():
    loads = np.ones(5)
    # without cols, what follows the rows is the columns; with cols the count is checked
    assert separable_pressure(loads, rows=4, crossing_area=1e-5).shape == (4, 1)
    with pytest.raises(
        ValueError,
        match=r"`line_loads` must hold rows \+ cols = 4 \+ 4 = 8 values .* got shape \(5,\)",
    ):
        separable_pressure(loads, rows=4, cols=4, crossing_area=1e-5)
    assert separable_pressure(np.ones((2, 8)), rows=4, cols=4, crossing_area=1e-5).shape == (
        2,
        4,
        4,
    )
    with pytest.raises(ValueError, match=r"`cols` must be >= 1, got 0"):
        separable_pressure(loads, rows=4, cols=0, crossing_area=1e-5)
    with pytest.raises(ValueError, match=r"`rows` must be an integer in 1..4, got 4.5"):
        separable_pressure(loads, rows=4.5, crossing_area=1e-5)
    with pytest.raises(ValueError, match=r"`rows` must be an integer in 1..4, got None"):
        separable_pressure(loads, rows=None, crossing_area=1e-5)
    with pytest.raises(ValueError, match=r"`line_loads` must hold rows \+ cols >= 2 .* \(1,\)"):
        separable_pressure([1.0], rows=1, crossing_area=1e-5)
    with pytest.raises(ValueError, match=r"`line_loads` must hold .* got shape \(\)"):
        separable_pressure(1.0, rows=1, crossing_area=1e-5)
