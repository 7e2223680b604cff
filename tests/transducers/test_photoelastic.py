"""Photoelastic polariscope (Figure 25.12): stress-optic law, fringes, load recovery.

Test fields come from Flamant's line load P [N/m] on a half-space (plane strain), whose
principal stress difference is 2 P z / (pi rho^2): its fringes are circles through the load.
"""

import numpy as np
import pytest

from taxel.transducers import (
    PhotoelasticTransducer,
    Transducer,
    fit_load_scale,
    photoelastic_retardation,
    polariscope_intensity,
    principal_stress_difference,
    unwrap_retardation,
)

LOAD = 2000.0  # N/m
LAYER = PhotoelasticTransducer(stress_optic_coefficient=3e-10)  # a soft urethane, say


def flamant(x, z, load=LOAD):
    rho4 = (x**2 + z**2) ** 2
    sxx = -2 * load * x**2 * z / (np.pi * rho4)
    szz = -2 * load * z**3 / (np.pi * rho4)
    sxz = -2 * load * x * z**2 / (np.pi * rho4)
    return sxx, szz, sxz


def test_flamant_principal_stress_difference():
    x, z = np.meshgrid(np.linspace(-5e-3, 5e-3, 21), np.linspace(0.2e-3, 8e-3, 17))
    difference = principal_stress_difference(*flamant(x, z))
    assert np.allclose(difference, 2 * LOAD * z / (np.pi * (x**2 + z**2)), rtol=1e-12)


def test_stress_optic_law_double_pass():
    delta = photoelastic_retardation(
        1e5, layer_thickness=2e-3, stress_optic_coefficient=3e-10, wavelength=550e-9
    )
    assert delta == pytest.approx(2 * 2 * np.pi * 2e-3 * 3e-10 * 1e5 / 550e-9, rel=1e-14)
    single = photoelastic_retardation(
        1e5, layer_thickness=2e-3, stress_optic_coefficient=3e-10, wavelength=550e-9, passes=1
    )
    assert delta == pytest.approx(2 * single, rel=1e-15)
    assert LAYER.fringe_stress == pytest.approx(550e-9 / (2 * 2e-3 * 3e-10), rel=1e-14)


def test_dark_and_light_fields_are_complementary():
    delta = np.linspace(0, 20, 101)
    dark = polariscope_intensity(delta, field="dark", source_intensity=3.0)
    light = polariscope_intensity(delta, field="light", source_intensity=3.0)
    assert np.allclose(dark + light, 3.0)
    assert dark[0] == 0.0 and light[0] == 3.0  # unstressed: black in a dark field


@pytest.mark.parametrize("order", [1, 2, 3])
def test_isochromatics_are_circles_through_the_load(order):
    # sigma_1 - sigma_2 = N f on the circle r = D cos(theta), D = 2 P / (pi N f)
    diameter = 2 * LOAD / (np.pi * order * LAYER.fringe_stress)
    theta = np.linspace(-1.2, 1.2, 25)
    x = diameter * np.cos(theta) * np.sin(theta)
    z = diameter * np.cos(theta) ** 2
    intensity = LAYER.respond(principal_stress_difference(*flamant(x, z)))
    assert np.max(intensity) < 1e-20
    # on the circle 2 % larger, the order is N / 1.02 all round
    outside = LAYER.respond(principal_stress_difference(*flamant(1.02 * x, 1.02 * z)))
    assert np.allclose(outside, np.sin(np.pi * order / 1.02) ** 2, rtol=1e-9)


def test_fringe_counting_along_the_line_of_action_recovers_the_load():
    depth = np.geomspace(10e-3, 0.5e-3, 400)  # walk towards the load
    difference = principal_stress_difference(*flamant(0.0 * depth, depth))
    intensity = LAYER.respond(difference)
    fringes = difference.max() / LAYER.fringe_stress
    assert fringes > 5
    recovered = LAYER.invert(intensity)
    assert np.allclose(recovered, difference, rtol=1e-9)
    load = np.pi * depth * recovered / 2  # sigma_1 - sigma_2 = 2 P / (pi z) on the axis
    assert np.allclose(load, LOAD, rtol=1e-9)


def test_unwrap_with_light_field_and_batches():
    delta = np.stack([np.linspace(0.2, 12, 300), np.linspace(0.0, 30, 300) ** 1.1 / 2])
    intensity = polariscope_intensity(delta, field="light", source_intensity=2.0)
    out = unwrap_retardation(intensity, field="light", source_intensity=2.0)
    assert np.allclose(out, delta, atol=1e-7)


def test_least_squares_fit_of_the_load_on_a_fringe_map():
    x, z = np.meshgrid(np.linspace(-5e-3, 5e-3, 48), np.linspace(0.6e-3, 8e-3, 40))
    unit = principal_stress_difference(*flamant(x, z, load=1.0))  # per N/m
    clean = LAYER.respond(LOAD * unit)
    fit = LAYER.fit_load(clean, unit, max_load=5000.0)
    assert fit.converged
    assert fit.load == pytest.approx(LOAD, rel=1e-8)
    assert fit.residual < 1e-8
    noisy = clean + np.random.default_rng(5).normal(0, 0.05, clean.shape)
    fit = LAYER.fit_load(noisy, unit, max_load=5000.0)
    assert fit.load == pytest.approx(LOAD, rel=2e-3)
    assert fit.residual == pytest.approx(0.05, rel=0.1)


def test_round_trip_within_full_scale_and_protocol():
    assert isinstance(LAYER, Transducer)
    assert (LAYER.quantity, LAYER.quantity_unit, LAYER.signal_unit) == (
        "stress_difference",
        "Pa",
        "W/m^2",
    )
    difference = np.linspace(0.0, 6 * LAYER.fringe_stress, 500)
    error = np.abs(LAYER.invert(LAYER.respond(difference)) - difference)
    assert np.max(error) < 1e-8 * difference.max()


def test_errors_name_the_parameter():
    with pytest.raises(ValueError, match="`stress_difference` must be >= 0, got -1"):
        LAYER.respond(-1.0)
    with pytest.raises(ValueError, match="`field` must be one of dark, light; got 'bright'"):
        polariscope_intensity(1.0, field="bright")
    with pytest.raises(ValueError, match="`unit_retardation` must have the shape of intensity"):
        fit_load_scale(np.ones(3), np.ones(4), max_load=1.0)
    with pytest.raises(ValueError, match="`layer_thickness` must be > 0, got 0"):
        PhotoelasticTransducer(layer_thickness=0.0)
    with pytest.raises(ValueError, match="`passes` must be a positive integer, got 0"):
        PhotoelasticTransducer(passes=0)
    with pytest.raises(ValueError, match=r"`intensity` must be a path .*, got shape \(0,\)"):
        unwrap_retardation(np.zeros(0))
    with pytest.raises(ValueError, match=r"`intensity` must be a path .*, got shape \(\)"):
        unwrap_retardation(0.5)


def test_stress_components_that_do_not_broadcast_are_named():
    with pytest.raises(
        ValueError,
        match=r"`stress_a`, `stress_b` and `shear_stress` must have shapes that broadcast "
        r"together, got \(3,\), \(2,\) and \(\)",
    ):
        principal_stress_difference(np.zeros(3), np.zeros(2), 0.0)
    assert principal_stress_difference(np.zeros((3, 1)), np.zeros(2), 1.0).shape == (3, 2)
