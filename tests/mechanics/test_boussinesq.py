"""3-D closed forms against quadrature of the point-load solutions and known identities."""

import numpy as np
import pytest
from scipy import integrate

from taxel.mechanics import (
    ElasticMaterial,
    point_load_displacement,
    point_load_strain,
    point_load_stress,
    rectangle_displacement,
    rectangle_strain,
    rectangle_stress,
)

COVER = ElasticMaterial(1e6, 0.3)
DEPTH = 1e-3


def test_point_load_axis_values():
    nu, modulus = COVER.poisson_ratio, COVER.youngs_modulus
    axis = -(1 + nu) * (3 - 2 * nu) / (2 * np.pi * modulus * DEPTH**2)
    assert point_load_strain(0.0, DEPTH, 1.0, COVER) == pytest.approx(axis, rel=1e-12)
    assert point_load_stress(0.0, DEPTH, 1.0) == pytest.approx(-3 / (2 * np.pi * DEPTH**2))
    surface = point_load_displacement(2e-3, 0.0, 1.0, COVER)
    assert surface == pytest.approx((1 - nu**2) / (np.pi * modulus * 2e-3), rel=1e-12)


def test_point_load_strain_is_hookes_law_of_the_stresses():
    # eps_z = (sigma_z - nu (sigma_r + sigma_theta)) / E with Johnson's eq. 3.22 stresses
    r, z, nu, modulus = 0.7e-3, DEPTH, COVER.poisson_ratio, COVER.youngs_modulus
    rho = np.hypot(r, z)
    sigma_z = -3 * z**3 / (2 * np.pi * rho**5)
    sigma_r = (1 - 2 * nu) / (2 * np.pi * r**2) * (1 - z / rho) - 3 * z * r**2 / (
        2 * np.pi * rho**5
    )
    sigma_theta = -(1 - 2 * nu) / (2 * np.pi * r**2) * (1 - z / rho - r**2 * z / rho**3)
    hooke = (sigma_z - nu * (sigma_r + sigma_theta)) / modulus
    assert point_load_strain(r, z, 1.0, COVER) == pytest.approx(hooke, rel=1e-10)
    assert point_load_stress(r, z, 1.0) == pytest.approx(sigma_z, rel=1e-12)


def test_total_vertical_force_is_transmitted_at_every_depth():
    total, _ = integrate.quad(
        lambda r: 2 * np.pi * r * point_load_stress(r, DEPTH, 1.0), 0, np.inf, epsrel=1e-12
    )
    assert total == pytest.approx(-1.0, rel=1e-9)


@pytest.mark.parametrize(("x", "y"), [(0.0, 0.0), (0.3e-3, -0.2e-3), (1.5e-3, 0.9e-3)])
def test_rectangle_strain_is_integral_of_point_load(x, y):
    x1, x2, y1, y2 = -0.25e-3, 0.35e-3, -0.3e-3, 0.2e-3
    expected, _ = integrate.dblquad(
        lambda b, a: point_load_strain(np.hypot(x - a, y - b), DEPTH, 1.0, COVER),
        x1,
        x2,
        y1,
        y2,
        epsabs=0,
        epsrel=1e-12,
    )
    got = rectangle_strain(x, y, (x1, x2, y1, y2), DEPTH, COVER)
    assert got == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize(("x", "y"), [(2.1e-3, 0.4e-3), (-3e-3, -2.5e-3)])
def test_love_rectangle_is_integral_of_boussinesq_away_from_patch(x, y):
    a, b = 0.5e-3, 0.3e-3
    expected, _ = integrate.dblquad(
        lambda t, s: point_load_displacement(np.hypot(x - s, y - t), 0.0, 1.0, COVER),
        -a,
        a,
        -b,
        b,
        epsabs=0,
        epsrel=1e-12,
    )
    assert rectangle_displacement(x, y, a, b, COVER) == pytest.approx(expected, rel=1e-9)


def test_love_rectangle_centre_is_integral_with_singularity():
    a = b = 0.5e-3

    # centre of a square: integrate the 1/r singularity in polar coordinates, by symmetry
    def radial(theta):
        reach = a / max(abs(np.cos(theta)), abs(np.sin(theta)))
        return reach  # integral of r * (1/r) dr from 0 to reach

    angular, _ = integrate.quad(radial, 0, 2 * np.pi, epsrel=1e-13, limit=200, points=[np.pi / 4])
    nu, modulus = COVER.poisson_ratio, COVER.youngs_modulus
    expected = (1 - nu**2) / (np.pi * modulus) * angular
    assert rectangle_displacement(0.0, 0.0, a, b, COVER) == pytest.approx(expected, rel=1e-9)


def test_love_square_corner_is_half_the_centre_and_symmetric():
    centre = rectangle_displacement(0.0, 0.0, 1e-3, 1e-3, COVER)
    corner = rectangle_displacement(-1e-3, 1e-3, 1e-3, 1e-3, COVER)
    assert corner / centre == pytest.approx(0.5, abs=1e-14)
    points = np.array([0.3e-3, 1.7e-3, 5e-3])
    values = rectangle_displacement(points, 0.2e-3, 1e-3, 0.6e-3, COVER)
    assert np.allclose(values, rectangle_displacement(-points, -0.2e-3, 1e-3, 0.6e-3, COVER))
    # far from the patch it looks like a point load of the same total force
    far = rectangle_displacement(0.2, 0.0, 1e-3, 0.6e-3, COVER)
    assert far == pytest.approx(point_load_displacement(0.2, 0.0, 2.4e-6, COVER), rel=1e-5)


def test_rectangle_displacement_is_stable_far_on_the_negative_side():
    # t(X, Y) needs ln(Y + r) with Y < 0: written without cancellation
    values = rectangle_displacement(np.array([-1.0, 1.0]), 0.0, 1e-3, 1e-3, COVER)
    assert values[0] == pytest.approx(values[1], rel=1e-9)


def test_bad_inputs():
    with pytest.raises(ValueError, match="`depth` must be > 0"):
        point_load_strain(0.0, 0.0, 1.0, COVER)
    with pytest.raises(ValueError, match="`bounds` must satisfy"):
        rectangle_strain(0.0, 0.0, (1.0, 0.0, 0.0, 1.0), 1e-3, COVER)
    with pytest.raises(ValueError, match="`half_width` must be > 0"):
        rectangle_displacement(0.0, 0.0, -1.0, 1.0, COVER)
    with pytest.raises(ValueError, match="`normal_force` must be finite"):
        point_load_stress(0.0, 1e-3, np.nan)


@pytest.mark.parametrize(("x", "y"), [(0.0, 0.0), (0.3e-3, -0.2e-3), (2e-3, 1e-3)])
def test_rectangle_stress_is_integral_of_point_load(x, y):
    x1, x2, y1, y2 = -0.25e-3, 0.35e-3, -0.3e-3, 0.2e-3
    expected, _ = integrate.dblquad(
        lambda b, a: point_load_stress(np.hypot(x - a, y - b), DEPTH, 1.0),
        x1,
        x2,
        y1,
        y2,
        epsabs=0,
        epsrel=1e-12,
    )
    got = rectangle_stress(x, y, (x1, x2, y1, y2), DEPTH)
    assert got == pytest.approx(expected, rel=1e-9)


def test_arrays_that_do_not_broadcast_are_named():
    radius, depth = np.zeros(3), np.full(2, DEPTH)
    both = r"`radius` and `depth` must have shapes that broadcast together, got \(3,\) and \(2,\)"
    with pytest.raises(ValueError, match=both):
        point_load_stress(radius, depth, 1.0)
    with pytest.raises(ValueError, match=both):
        point_load_displacement(radius, depth, 1.0, COVER)
    xy = r"`x` and `y` must have shapes that broadcast together, got \(3,\) and \(2,\)"
    with pytest.raises(ValueError, match=xy):
        rectangle_strain(radius, np.zeros(2), (-1e-3, 1e-3, -1e-3, 1e-3), DEPTH, COVER)
    with pytest.raises(ValueError, match=xy):
        rectangle_stress(radius, np.zeros(2), (-1e-3, 1e-3, -1e-3, 1e-3), DEPTH)
    with pytest.raises(ValueError, match=xy):
        rectangle_displacement(radius, np.zeros(2), 1e-3, 1e-3, COVER)
    # shapes that broadcast give the grid
    assert point_load_stress(radius[:, None], depth, 1.0).shape == (3, 2)


def test_bad_bounds_and_material_are_named():
    with pytest.raises(ValueError, match=r"`bounds` must be \(x1, x2, y1, y2\), got \(0, 1, 0\)"):
        rectangle_strain(0.0, 0.0, (0, 1, 0), DEPTH, COVER)
    with pytest.raises(TypeError, match=r"`bounds` must be \(x1, x2, y1, y2\), got None"):
        rectangle_stress(0.0, 0.0, None, DEPTH)
    with pytest.raises(TypeError, match="`material` must be an ElasticMaterial, got None"):
        point_load_strain(0.0, DEPTH, 1.0, None)
    with pytest.raises(TypeError, match="`material` must be an ElasticMaterial, got 'rubber'"):
        rectangle_displacement(0.0, 0.0, 1e-3, 1e-3, "rubber")
