"""Transfer functions: half-space against Hankel transforms, the layer against a BVP solve."""

import numpy as np
import pytest
from scipy import integrate, special

from taxel.mechanics import (
    ElasticMaterial,
    halfspace_displacement_transfer,
    halfspace_strain_transfer,
    halfspace_stress_transfer,
    layer_displacement_transfer,
    layer_strain_transfer,
    layer_stress_transfer,
    point_load_strain,
    point_load_stress,
)

COVER = ElasticMaterial(1e6, 0.3)


@pytest.mark.parametrize("q", [200.0, 1500.0, 4000.0])
def test_halfspace_strain_is_hankel_transform_of_point_load(q):
    depth = 1e-3
    value, _ = integrate.quad(
        lambda r: 2 * np.pi * r * point_load_strain(r, depth, 1.0, COVER) * special.j0(q * r),
        0,
        5.0,
        limit=20000,
        epsabs=1e-17,
    )
    assert halfspace_strain_transfer(q, depth, COVER) == pytest.approx(value, rel=1e-6)


def test_halfspace_displacement():
    q = np.array([10.0, 1e3])
    assert np.allclose(
        halfspace_displacement_transfer(q, COVER), 2 / (COVER.plane_strain_modulus * q)
    )


def _layer_bvp(q, thickness, material, depth):
    """Solve Navier's equations for one Fourier mode with scipy's BVP solver."""
    nu, modulus = material.poisson_ratio, material.youngs_modulus
    mu = modulus / (2 * (1 + nu))
    lam = 2 * mu * nu / (1 - 2 * nu)

    def rhs(z, y):
        u, du, w, dw = y
        ddu = q**2 * u - (lam + mu) / mu * q * (dw - q * u)
        ddw = (mu * q**2 * w + (lam + mu) * q * du) / (lam + 2 * mu)
        return np.vstack([du, ddu, dw, ddw])

    def boundary(top, bottom):
        u, du, w, dw = top
        stress_zz = lam * (-q * u + dw) + 2 * mu * dw
        return np.array([stress_zz + 1.0, du + q * w, bottom[0], bottom[2]])

    z = np.linspace(0, thickness, 400)
    solution = integrate.solve_bvp(
        rhs, boundary, z, np.zeros((4, z.size)), tol=1e-10, max_nodes=200000
    )
    assert solution.success
    u, _, _, dw = solution.sol(depth)
    stress = lam * (-q * u + dw) + 2 * mu * dw
    return solution.sol(0.0)[2], dw, stress


@pytest.mark.parametrize("qh", [0.05, 0.7, 2.0, 6.0])
def test_layer_matches_boundary_value_solution(qh):
    thickness, depth = 2e-3, 0.8e-3
    q = qh / thickness
    displacement, strain, stress = _layer_bvp(q, thickness, COVER, depth)
    assert layer_displacement_transfer(q, thickness, COVER) == pytest.approx(
        displacement, rel=1e-6
    )
    assert layer_strain_transfer(q, depth, thickness, COVER) == pytest.approx(strain, rel=1e-6)
    assert layer_stress_transfer(q, depth, thickness, COVER) == pytest.approx(stress, rel=1e-6)


def test_layer_tends_to_halfspace_when_thick():
    q = np.array([500.0, 2000.0, 8000.0])
    thick = 1.0
    assert np.allclose(
        layer_displacement_transfer(q, thick, COVER),
        halfspace_displacement_transfer(q, COVER),
        rtol=1e-12,
    )
    assert np.allclose(
        layer_strain_transfer(q, 1e-3, thick, COVER),
        halfspace_strain_transfer(q, 1e-3, COVER),
        rtol=1e-12,
    )


def test_layer_tends_to_oedometric_limit_when_thin():
    thickness, q = 1e-3, np.array([0.0, 1e-3, 1.0])  # q h << 1
    expected = thickness / COVER.constrained_modulus
    assert np.allclose(layer_displacement_transfer(q, thickness, COVER), expected, rtol=1e-6)
    strain = layer_strain_transfer(q, 0.5e-3, thickness, COVER)
    assert np.allclose(strain, -1 / COVER.constrained_modulus, rtol=1e-6)


def test_incompressible_layer_without_division_by_zero():
    rubber = ElasticMaterial(1e6, 0.5)
    q = np.array([0.0, 1e-2, 1e3, 1e5])
    with np.errstate(all="raise"):
        displacement = layer_displacement_transfer(q, 1e-3, rubber)
        strain = layer_strain_transfer(q, 0.5e-3, 1e-3, rubber)
        halfspace = halfspace_strain_transfer(q, 0.5e-3, rubber)
    assert displacement[0] == 0.0 and np.all(np.isfinite(strain))
    assert halfspace[0] == 0.0  # no eps_z under a uniform load on an incompressible half-space


def test_bad_inputs():
    with pytest.raises(ValueError, match="`wavenumber` must be >= 0"):
        halfspace_strain_transfer(-1.0, 1e-3, COVER)
    with pytest.raises(ValueError, match=r"`depth` must be <= `thickness`"):
        layer_strain_transfer(1.0, 2e-3, 1e-3, COVER)
    with pytest.raises(ValueError, match="`thickness` must be > 0"):
        layer_displacement_transfer(1.0, 0.0, COVER)


@pytest.mark.parametrize("q", [200.0, 1500.0])
def test_halfspace_stress_is_hankel_transform_of_point_load(q):
    depth = 1e-3
    value, _ = integrate.quad(
        lambda r: 2 * np.pi * r * point_load_stress(r, depth, 1.0) * special.j0(q * r),
        0,
        5.0,
        limit=20000,
        epsabs=1e-14,
    )
    assert halfspace_stress_transfer(q, depth) == pytest.approx(value, rel=1e-6)


def test_layer_stress_limits():
    q = np.array([0.0, 1e-3, 500.0, 3000.0])
    assert layer_stress_transfer(q[:2], 0.5e-3, 1e-3, COVER) == pytest.approx(-1.0, rel=1e-6)
    assert np.allclose(
        layer_stress_transfer(q, 1e-3, 1.0, COVER), halfspace_stress_transfer(q, 1e-3), rtol=1e-12
    )
