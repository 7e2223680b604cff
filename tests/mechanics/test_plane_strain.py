"""Plane-strain kernels of the chapter (eqs. 25.2-25.5) against the fact sheet and quadrature."""

import numpy as np
import pytest
from scipy import integrate

from taxel.mechanics import (
    ElasticMaterial,
    line_load_displacement,
    line_load_strain,
    plane_strain_displacement_matrix,
    plane_strain_strain_matrix,
    strip_load_strain,
)

COVER = ElasticMaterial(1e6, 0.3)
DEPTH = 2e-3


def test_line_load_reference_values():
    # ../shared/reference/mechanics.md: P = 100 N/m, nu = 0.3, d = 2 mm, E = 1 MPa
    assert 100 * line_load_strain(0.0, DEPTH, COVER) == pytest.approx(-2.896620e-2, rel=5e-7)
    assert 100 * line_load_strain(DEPTH, DEPTH, COVER) == pytest.approx(-4.138029e-3, rel=5e-7)


def test_line_load_shape_features():
    nu, d = COVER.poisson_ratio, DEPTH
    peak = -2 * (1 + nu) * (1 - nu) / (np.pi * COVER.youngs_modulus * d)
    assert line_load_strain(0.0, d, COVER) == pytest.approx(peak, rel=1e-12)
    zero = d * np.sqrt((1 - nu) / nu)
    assert abs(line_load_strain(zero, d, COVER)) < 1e-12 * abs(peak)
    lobe = d * np.sqrt((2 - nu) / nu)
    ratio = line_load_strain(lobe, d, COVER) / peak
    assert ratio == pytest.approx(-(nu**2) / (4 * (1 - nu)), rel=1e-12)
    x = np.linspace(lobe * 0.9, lobe * 1.1, 201)
    assert np.argmax(line_load_strain(x, d, COVER)) == 100  # the lobe is the maximum


def test_line_load_integral():
    total, _ = integrate.quad(lambda x: line_load_strain(x, DEPTH, COVER), -np.inf, np.inf)
    nu = COVER.poisson_ratio
    assert total == pytest.approx(-(1 + nu) * (1 - 2 * nu) / COVER.youngs_modulus, rel=1e-9)


def test_incompressible_line_load_integrates_to_zero():
    cover = ElasticMaterial(1e6, 0.5)
    total, _ = integrate.quad(lambda x: line_load_strain(x, DEPTH, cover), -np.inf, np.inf)
    assert abs(total) < 1e-12


@pytest.mark.parametrize("direction", ["normal", "tangential"])
@pytest.mark.parametrize("offset", [0.0, 0.7e-3, 3.1e-3, -5e-3])
def test_strip_is_exact_integral_of_line_load(direction, offset):
    width = 1.3e-3
    expected, _ = integrate.quad(
        lambda s: line_load_strain(offset - s, DEPTH, COVER, direction=direction),
        -width / 2,
        width / 2,
        epsabs=1e-20,
        epsrel=1e-13,
    )
    got = strip_load_strain(offset, DEPTH, width, COVER, direction=direction)
    assert got == pytest.approx(expected, rel=1e-9, abs=1e-18)


def test_tangential_kernel_is_odd_and_normal_even():
    x = np.linspace(0.1e-3, 8e-3, 50)
    tangential = line_load_strain(x, DEPTH, COVER, direction="tangential")
    normal = line_load_strain(x, DEPTH, COVER)
    assert np.allclose(line_load_strain(-x, DEPTH, COVER, direction="tangential"), -tangential)
    assert np.allclose(line_load_strain(-x, DEPTH, COVER), normal)
    # ahead of a tangential load (x > 0, near the surface) the layer is compressed
    assert tangential[0] < 0


def test_strain_matrix_matches_fine_collocation():
    taxels = np.arange(6) * 1e-3
    loads = np.arange(12) * 0.5e-3 - 0.25e-3
    matrix = plane_strain_strain_matrix(taxels, loads, 0.5e-3, 1e-3, COVER)
    assert matrix.shape == (6, 12)
    # fine collocation: 2000 sub-elements per load element
    sub = (np.arange(2000) + 0.5) / 2000 * 0.5e-3 - 0.25e-3
    fine = np.array(
        [
            [line_load_strain(t - (c + sub), 1e-3, COVER).mean() * 0.5e-3 for c in loads]
            for t in taxels
        ]
    )
    assert np.allclose(matrix, fine, rtol=1e-6, atol=0)


def test_point_collocation_error_at_pitch_equal_depth():
    # the fact sheet: point collocation errs by ~20-28 % at pitch = d
    d = 1e-3
    exact = strip_load_strain(0.0, d, d, COVER)
    collocated = line_load_strain(0.0, d, COVER) * d
    assert 0.15 < abs(collocated / exact - 1) < 0.3


def test_superposition_and_symmetry():
    x = np.arange(10) * 0.8e-3
    matrix = plane_strain_strain_matrix(x, x, 0.8e-3, 1e-3, COVER)
    assert np.allclose(matrix, matrix.T, rtol=1e-12)
    first, second = np.zeros(10), np.zeros(10)
    first[2], second[7] = 1e3, 2e3
    assert np.allclose(matrix @ (first + second), matrix @ first + matrix @ second)


def test_displacement_kernel_and_matrix():
    x = np.array([0.5, 1.0, 2.0])
    k = line_load_displacement(x, COVER, reference_distance=1.0)
    scale = -2 * (1 - 0.09) / (np.pi * 1e6)
    assert np.allclose(k, scale * np.log(x), rtol=1e-12)
    centres = np.arange(5) * 1e-3
    matrix = plane_strain_displacement_matrix(centres, centres, 1e-3, COVER)
    expected, _ = integrate.quad(
        lambda s: line_load_displacement(2e-3 - s, COVER), -0.5e-3, 0.5e-3, epsrel=1e-13
    )
    assert matrix[2, 0] == pytest.approx(expected, rel=1e-9)
    diagonal, _ = integrate.quad(
        lambda s: line_load_displacement(s, COVER), -0.5e-3, 0.5e-3, points=[0.0], epsrel=1e-12
    )
    assert matrix[0, 0] == pytest.approx(diagonal, rel=1e-9)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"depth": 0.0}, r"`depth` must be > 0, got 0"),
        ({"depth": -1e-3}, r"`depth` must be > 0"),
        ({"direction": "sideways"}, r"`direction` must be one of normal, tangential"),
    ],
)
def test_bad_arguments(kwargs, match):
    arguments = {"depth": 1e-3, "direction": "normal"} | kwargs
    with pytest.raises(ValueError, match=match):
        line_load_strain(0.0, arguments["depth"], COVER, direction=arguments["direction"])


def test_nan_position_is_rejected():
    with pytest.raises(ValueError, match="`x` must be finite"):
        line_load_strain([0.0, np.nan], 1e-3, COVER)
    with pytest.raises(ValueError, match="`load_width` must be > 0"):
        plane_strain_strain_matrix([0.0], [0.0], 0.0, 1e-3, COVER)
