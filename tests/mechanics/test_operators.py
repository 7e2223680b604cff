"""Grid operators: adjoints, symmetry, superposition, exact kernels, layer limits."""

import numpy as np
import pytest

from taxel.mechanics import (
    ElasticMaterial,
    depth_strain_operator,
    depth_stress_operator,
    rectangle_displacement,
    rectangle_strain,
    surface_displacement_operator,
)

COVER = ElasticMaterial(1e6, 0.3)
RUBBER = ElasticMaterial(0.5e6, 0.5)
SPACING = (0.4e-3, 0.5e-3)


def _operators():
    shape = (12, 10)
    yield surface_displacement_operator(shape, SPACING, COVER)
    yield surface_displacement_operator(shape, SPACING, COVER, periodic=True)
    yield surface_displacement_operator(shape, SPACING, RUBBER, thickness=2e-3)
    yield surface_displacement_operator(shape, SPACING, RUBBER, periodic=True, thickness=2e-3)
    yield depth_strain_operator(shape, SPACING, 1e-3, COVER)
    yield depth_strain_operator(shape, SPACING, 1e-3, COVER, periodic=True)
    yield depth_strain_operator(shape, SPACING, 1e-3, RUBBER, thickness=3e-3)
    yield depth_strain_operator(shape, SPACING, 1e-3, RUBBER, periodic=True, thickness=3e-3)
    yield depth_stress_operator(shape, SPACING, 1e-3, COVER)
    yield depth_stress_operator(shape, SPACING, 1e-3, RUBBER, thickness=3e-3)
    yield depth_stress_operator(shape, SPACING, 1e-3, RUBBER, periodic=True)


@pytest.mark.parametrize("operator", list(_operators()), ids=repr)
def test_dot_test(operator):
    rng = np.random.default_rng(1)
    x = rng.standard_normal((3, *operator.shape))  # a batch of three fields
    y = rng.standard_normal((3, *operator.shape))
    left = np.vdot(operator.apply(x), y)
    right = np.vdot(x, operator.adjoint(y))
    assert left == pytest.approx(right, rel=1e-12)


@pytest.mark.parametrize("operator", list(_operators()), ids=repr)
def test_dense_matrix_is_the_operator(operator):
    matrix = operator.to_matrix()
    field = np.random.default_rng(2).standard_normal(operator.shape)
    assert np.allclose(
        matrix @ field.ravel(),
        operator.apply(field).ravel(),
        rtol=1e-10,
        atol=1e-12 * np.abs(matrix).max() * field.size,
    )
    # reciprocity (Maxwell-Betti): the influence matrix is symmetric
    assert np.allclose(matrix, matrix.T, rtol=1e-9, atol=1e-12 * np.abs(matrix).max())


def test_zero_padded_kernels_are_the_exact_cell_integrals():
    shape, depth = (6, 7), 0.8e-3
    displacement = surface_displacement_operator(shape, SPACING, COVER)
    strain = depth_strain_operator(shape, SPACING, depth, COVER)
    unit = np.zeros(shape)
    unit[2, 3] = 1.0
    rows, cols = np.mgrid[: shape[0], : shape[1]]
    y, x = (rows - 2) * SPACING[0], (cols - 3) * SPACING[1]
    expected = rectangle_displacement(x, y, SPACING[1] / 2, SPACING[0] / 2, COVER)
    assert np.allclose(displacement.apply(unit), expected, rtol=1e-12)
    bounds = (-SPACING[1] / 2, SPACING[1] / 2, -SPACING[0] / 2, SPACING[0] / 2)
    assert np.allclose(
        strain.apply(unit), rectangle_strain(x, y, bounds, depth, COVER), rtol=1e-12
    )


@pytest.mark.parametrize("shape", [(1, 1), (2, 2), (3, 5), (8, 8), (8, 1), (13, 7)])
def test_zero_padded_operator_is_the_linear_convolution_of_its_kernel_on_any_grid(shape):
    # grids whose padded FFT length is odd (2 * 8 - 1 = 15) once wrapped around by a cell
    operator = surface_displacement_operator(shape, SPACING, COVER)
    field = np.random.default_rng(3).random(shape)
    rows, cols = shape
    expected = np.zeros(shape)
    for row in range(rows):
        for col in range(cols):
            window = operator.kernel[rows - 1 - row : 2 * rows - 1 - row]
            window = window[:, cols - 1 - col : 2 * cols - 1 - col]
            expected += field[row, col] * window
    assert np.allclose(operator.apply(field), expected, rtol=1e-12, atol=0)


def test_superposition():
    operator = depth_strain_operator((16, 16), 0.5e-3, 1e-3, COVER)
    rng = np.random.default_rng(3)
    a, b = rng.random((2, 16, 16))
    assert np.allclose(operator @ (2 * a + 3 * b), 2 * (operator @ a) + 3 * (operator @ b))


def test_periodic_and_zero_padded_agree_for_a_smooth_local_load():
    shape, spacing, depth = (64, 64), 0.25e-3, 0.5e-3
    rows, cols = np.mgrid[:64, :64]
    pressure = np.exp(-((rows - 32) ** 2 + (cols - 31) ** 2) / (2 * 4.0**2))
    linear = depth_strain_operator(shape, spacing, depth, COVER).apply(pressure)
    periodic = depth_strain_operator(shape, spacing, depth, COVER, periodic=True).apply(pressure)
    assert np.abs(linear - periodic).max() < 5e-3 * np.abs(linear).max()


def test_thick_layer_is_a_halfspace_and_thin_layer_is_oedometric():
    shape, spacing, depth = (24, 24), 0.5e-3, 0.5e-3
    field = np.zeros(shape)
    field[8:16, 8:16] = 1e4
    halfspace = depth_strain_operator(shape, spacing, depth, COVER).apply(field)
    thick = depth_strain_operator(shape, spacing, depth, COVER, thickness=1.0).apply(field)
    # a 1 m layer still differs physically by ~ load / (E h^2): 2e-6 of the peak here
    assert np.allclose(thick, halfspace, atol=1e-5 * np.abs(halfspace).max())
    # a layer much thinner than the loaded patch: uniform oedometric strain under the patch
    thin = 0.1e-3
    strain = depth_strain_operator((64, 64), 0.25e-3, thin / 2, COVER, thickness=thin)
    displacement = surface_displacement_operator((64, 64), 0.25e-3, COVER, thickness=thin)
    load = np.zeros((64, 64))
    load[16:48, 16:48] = 1e4
    centre = (slice(28, 36), slice(28, 36))
    oedometric = 1e4 / COVER.constrained_modulus
    assert np.allclose(strain.apply(load)[centre], -oedometric, rtol=2e-3)
    assert np.allclose(displacement.apply(load)[centre], oedometric * thin, rtol=2e-3)


def test_a_layer_a_twentieth_of_a_cell_thick_is_still_oedometric_and_thinner_is_refused():
    # the thinnest layer modelled: 1/20 of a 0.2 mm cell; the correction's quadrature holds
    thin = 0.01e-3
    displacement = surface_displacement_operator((32, 32), 0.2e-3, COVER, thickness=thin)
    load = np.zeros((32, 32))
    load[8:24, 8:24] = 1e4
    oedometric = 1e4 / COVER.constrained_modulus
    assert np.allclose(displacement.apply(load)[14:18, 14:18], oedometric * thin, rtol=3e-3)
    for build in (surface_displacement_operator, depth_strain_operator):
        extra = (thin / 4,) if build is depth_strain_operator else ()
        with pytest.raises(ValueError, match=r"`thickness` must be at least 1/20 of the grid"):
            build((8, 8), 0.2e-3, *extra, COVER, thickness=0.009e-3)


def test_incompressible_halfspace_strain_of_uniform_load_vanishes():
    operator = depth_strain_operator((32, 32), 0.5e-3, 0.5e-3, RUBBER, periodic=True)
    strain = operator.apply(np.full((32, 32), 1e4))
    assert np.all(np.isfinite(strain))
    assert np.abs(strain).max() < 1e-14


def test_bad_inputs():
    with pytest.raises(ValueError, match="`spacing` must be > 0"):
        surface_displacement_operator((4, 4), 0.0, COVER)
    with pytest.raises(ValueError, match="`shape` must be"):
        surface_displacement_operator((4,), 1e-3, COVER)
    operator = surface_displacement_operator((4, 4), 1e-3, COVER)
    with pytest.raises(ValueError, match=r"`values` must end with the grid shape \(4, 4\)"):
        operator.apply(np.zeros((4, 5)))
    with pytest.raises(ValueError, match="`values` must be finite"):
        operator.apply(np.full((4, 4), np.nan))
    with pytest.raises(ValueError, match="`depth` must be <= `thickness`"):
        depth_strain_operator((4, 4), 1e-3, 2e-3, COVER, thickness=1e-3)


def test_stress_transmits_a_wide_load_undiminished():
    load = np.zeros((64, 64))
    load[8:56, 8:56] = 1e4
    centre = (slice(30, 34), slice(30, 34))
    for operator in (
        depth_stress_operator((64, 64), 0.25e-3, 0.5e-3, RUBBER),
        depth_stress_operator((64, 64), 0.25e-3, 0.5e-3, RUBBER, thickness=1e-3),
    ):
        assert np.allclose(operator.apply(load)[centre], -1e4, rtol=2e-3)


def test_inplane_stress_difference_of_a_small_patch_is_boussinesq():
    from taxel.mechanics import inplane_stress_difference

    nu, depth, spacing = 0.3, 1e-3, 0.05e-3
    load = np.zeros((256, 256))
    load[128, 128] = 1.0 / spacing**2  # 1 N on one cell
    field = inplane_stress_difference(load, spacing, depth, ElasticMaterial(1e6, nu), padding=4)
    for cells in (10, 20, 40):
        r = cells * spacing
        rho = np.hypot(r, depth)
        radial = ((1 - 2 * nu) / r**2 * (1 - depth / rho) - 3 * depth * r**2 / rho**5) / (
            2 * np.pi
        )
        hoop = -(1 - 2 * nu) * (1 / r**2 * (1 - depth / rho) - depth / rho**3) / (2 * np.pi)
        # tau_r_theta = 0 by symmetry: the principal difference is |sigma_r - sigma_theta|
        assert field[128, 128 + cells] == pytest.approx(abs(radial - hoop), rel=2e-3)
        assert field[128 + cells, 128] == pytest.approx(abs(radial - hoop), rel=2e-3)


@pytest.mark.parametrize("thickness", [None, 1.2e-3])
def test_kernels_built_on_a_quadrant_and_mirrored_are_the_kernels_at_every_offset(thickness):
    # a cell centred at 0 and a response that depends on the distance alone: every kernel
    # is even in y and in x, so a quarter of the offsets gives them all (4x faster builds);
    # offsets given as whole grids, not a column and a row, are computed point by point
    from taxel.mechanics._kernels import depth_kernel, displacement_kernel, offsets

    y, x = offsets(9, SPACING[0])[:, None], offsets(12, SPACING[1])[None, :]
    every_y, every_x = np.broadcast_arrays(y, x)
    pairs = [
        (
            displacement_kernel(y, x, SPACING, RUBBER, thickness=thickness),
            displacement_kernel(every_y, every_x, SPACING, RUBBER, thickness=thickness),
        )
    ]
    for quantity in ("stress", "strain"):
        mirrored = depth_kernel(quantity, y, x, SPACING, 0.8e-3, RUBBER, thickness=thickness)
        direct = depth_kernel(
            quantity, every_y, every_x, SPACING, 0.8e-3, RUBBER, thickness=thickness
        )
        pairs.append((mirrored, direct))
    for mirrored, direct in pairs:
        assert mirrored.shape == direct.shape == (17, 23)
        scale = np.abs(direct).max()
        np.testing.assert_allclose(mirrored, direct, rtol=0, atol=1e-12 * scale)
        assert np.array_equal(mirrored, mirrored[::-1]) and np.array_equal(
            mirrored, mirrored[:, ::-1]
        )
