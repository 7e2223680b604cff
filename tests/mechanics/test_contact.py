"""The contact solver against Hertz, the punch, a periodic closed form, and its invariants."""

import numpy as np
import pytest
from scipy import integrate

from taxel.mechanics import (
    Cylinder,
    ElasticMaterial,
    FlatPunch,
    Sphere,
    effective_modulus,
    flat_punch,
    grid_coordinates,
    hertz_cylinder,
    hertz_sphere,
    layer_displacement_transfer,
    solve_contact,
)

COVER = ElasticMaterial(1e6, 0.5)
SHAPE, SPACING, RADIUS = (128, 128), 0.1e-3, 10e-3  # a = 17.8 cells at 1 N


@pytest.fixture(scope="module")
def sphere_heights():
    return Sphere(RADIUS).on_grid(SHAPE, SPACING)


@pytest.fixture(scope="module")
def sphere_result(sphere_heights):
    return solve_contact(sphere_heights, SPACING, COVER, normal_force=1.0)


def _radius_grid():
    x, y = grid_coordinates(SHAPE, SPACING)
    return np.hypot(x, y)


def test_sphere_against_hertz(sphere_result):
    hertz = hertz_sphere(1.0, RADIUS, COVER.plane_strain_modulus)
    result = sphere_result
    assert result.converged and result.residual < 1e-8
    assert result.normal_force == pytest.approx(1.0, rel=1e-6)  # force balance
    assert result.indentation == pytest.approx(hertz.indentation, rel=0.01)
    radius = np.sqrt(result.contact_area / np.pi)
    assert abs(radius - hertz.contact_radius) < SPACING
    r = _radius_grid()
    inside = r < 0.9 * hertz.contact_radius
    error = np.abs(result.pressure - hertz.pressure(r))[inside].max()
    assert error < 0.01 * hertz.peak_pressure
    assert np.all(result.pressure >= 0)
    # the surface inside the contact follows the indenter: u = delta - h there
    assert np.allclose(
        result.displacement[result.contact] + 0.0,
        result.indentation - Sphere(RADIUS).on_grid(SHAPE, SPACING)[result.contact],
        atol=1e-6 * result.indentation,
    )


def test_sphere_indentation_control(sphere_heights):
    hertz = hertz_sphere(1.0, RADIUS, COVER.plane_strain_modulus)
    result = solve_contact(sphere_heights, SPACING, COVER, indentation=hertz.indentation)
    assert result.converged
    assert result.normal_force == pytest.approx(1.0, rel=0.01)
    assert result.indentation == hertz.indentation


def test_warm_start_gives_the_same_answer(sphere_heights, sphere_result):
    cold = solve_contact(sphere_heights, SPACING, COVER, normal_force=1.05)
    warm = solve_contact(sphere_heights, SPACING, COVER, normal_force=1.05, initial=sphere_result)
    assert warm.converged
    assert np.abs(warm.pressure - cold.pressure).max() < 1e-6 * cold.pressure.max()
    assert warm.n_iterations <= cold.n_iterations


def test_warm_start_from_a_smaller_contact_grows_the_window(sphere_heights):
    small = solve_contact(sphere_heights, SPACING, COVER, normal_force=0.1)
    big = solve_contact(sphere_heights, SPACING, COVER, normal_force=2.0, initial=small)
    hertz = hertz_sphere(2.0, RADIUS, COVER.plane_strain_modulus)
    assert big.converged
    assert abs(np.sqrt(big.contact_area / np.pi) - hertz.contact_radius) < SPACING


@pytest.mark.parametrize("load", [{"normal_force": 0.0}, {"indentation": 0.0}])
def test_no_load_is_no_contact(sphere_heights, load):
    """At zero force (or approach) the sphere rests at first touch: nothing is pressed."""
    result = solve_contact(sphere_heights, SPACING, COVER, **load)
    assert result.pressure.shape == result.displacement.shape == SHAPE
    assert not result.pressure.any() and not result.displacement.any()
    assert not result.contact.any() and result.contact_area == 0.0
    assert (result.normal_force, result.indentation) == (0.0, 0.0)
    assert result.converged and (result.n_iterations, result.residual) == (0, 0.0)
    assert result.message == "no load: the indenter rests at first touch, with no contact"


def test_a_warm_start_from_rest_is_a_cold_start(sphere_heights, sphere_result):
    # the rest's zero force used to scale the first guess: 1 N / 0 N
    rest = solve_contact(sphere_heights, SPACING, COVER, normal_force=0.0)
    warm = solve_contact(sphere_heights, SPACING, COVER, normal_force=1.0, initial=rest)
    np.testing.assert_array_equal(warm.pressure, sphere_result.pressure)
    assert warm.n_iterations == sphere_result.n_iterations


def test_translation_moves_the_solution(sphere_result):
    shifted = Sphere(RADIUS).on_grid(SHAPE, SPACING, position=(5 * SPACING, -3 * SPACING))
    result = solve_contact(shifted, SPACING, COVER, normal_force=1.0)
    moved = np.roll(sphere_result.pressure, (-3, 5), axis=(0, 1))
    assert np.abs(result.pressure - moved).max() < 1e-6 * moved.max()


def test_cylinder_against_hertz():
    rows, cols, spacing, radius = 96, 384, 0.025e-3, 5e-3
    heights = Cylinder(radius).on_grid((rows, cols), spacing)
    result = solve_contact(heights, spacing, COVER, normal_force=0.5)
    assert result.converged
    profile = result.pressure[:, cols // 2]  # mid-length: plane strain
    hertz = hertz_cylinder(profile.sum() * spacing, radius, COVER.plane_strain_modulus)
    assert hertz.half_width / spacing >= 12
    y = grid_coordinates((rows, cols), spacing)[1][:, 0]
    inside = np.abs(y) < 0.9 * hertz.half_width
    assert np.abs(profile - hertz.pressure(y))[inside].max() < 0.01 * hertz.peak_pressure
    assert abs(np.count_nonzero(profile) * spacing / 2 - hertz.half_width) < spacing


def test_elastic_indenter_uses_the_effective_modulus(sphere_heights):
    result = solve_contact(
        sphere_heights, SPACING, COVER, normal_force=1.0, indenter_material=COVER
    )
    hertz = hertz_sphere(1.0, RADIUS, effective_modulus(COVER, COVER))
    assert result.indentation == pytest.approx(hertz.indentation, rel=0.01)
    assert abs(np.sqrt(result.contact_area / np.pi) - hertz.contact_radius) < SPACING
    # the cover takes half of the approach when both bodies are the same material
    centre = np.unravel_index(np.argmax(result.pressure), SHAPE)
    assert result.displacement[centre] == pytest.approx(result.indentation / 2, rel=0.02)


def test_flat_punch_stiffness():
    radius, depth = 2e-3, 20e-6
    heights = FlatPunch(radius).on_grid((96, 96), 0.05e-3)
    result = solve_contact(heights, 0.05e-3, COVER, indentation=depth)
    expected = flat_punch(depth, radius, COVER.plane_strain_modulus).normal_force
    # the grid resolves the rim singularity only to within a cell: 2 % here
    assert result.normal_force == pytest.approx(expected, rel=0.02)
    assert result.pressure.max() > 3 * result.pressure[48, 48]  # the rim carries the peak


@pytest.mark.parametrize("thickness_in_radii", [20, 40])
def test_thick_layer_matches_halfspace(sphere_heights, sphere_result, thickness_in_radii):
    hertz = hertz_sphere(1.0, RADIUS, COVER.plane_strain_modulus)
    thickness = thickness_in_radii * hertz.contact_radius
    layer = solve_contact(sphere_heights, SPACING, COVER, normal_force=1.0, thickness=thickness)
    assert layer.converged
    inside = _radius_grid() < 0.9 * hertz.contact_radius
    difference = np.abs(layer.pressure - sphere_result.pressure)[inside].max()
    assert difference < 0.01 * hertz.peak_pressure
    assert layer.contact_area == pytest.approx(sphere_result.contact_area, rel=0.01)
    # the approach is smaller by the displacement a half-space would have beyond the layer:
    # about 0.75 a/h, predicted independently from the Hertz pressure's Hankel transform
    a, p0 = hertz.contact_radius, hertz.peak_pressure

    def hertz_transform(q):
        s = q * a
        return 2 * np.pi * p0 * a**2 * (np.sin(s) - s * np.cos(s)) / s**3

    change, _ = integrate.quad(
        lambda q: (
            q * layer_displacement_transfer(q, thickness, COVER) - 2 / COVER.plane_strain_modulus
        )
        * hertz_transform(q)
        / (2 * np.pi),
        1e-9,
        60 / thickness,
        limit=500,
    )
    predicted = sphere_result.indentation + change
    assert layer.indentation == pytest.approx(predicted, rel=0.005)


def test_periodic_sinusoid_in_full_contact():
    # Johnson section 13.2: h = D (1 - cos 2 pi x / L) pressed to a mean pressure above
    # p* = pi E* D / L stays in full contact with p = mean + p* cos(2 pi x / L)
    rows, cols, spacing = 8, 64, 0.1e-3
    wavelength, amplitude = cols * spacing, 2e-6
    x = grid_coordinates((rows, cols), spacing)[0] + spacing / 2
    heights = amplitude * (1 - np.cos(2 * np.pi * x / wavelength))
    star = np.pi * COVER.plane_strain_modulus * amplitude / wavelength
    mean = 1.5 * star
    area = rows * cols * spacing**2
    result = solve_contact(heights, spacing, COVER, normal_force=mean * area, periodic=True)
    assert result.converged and result.contact.all()
    expected = mean + star * np.cos(2 * np.pi * x / wavelength)
    assert np.abs(result.pressure - expected).max() < 2e-3 * star


def test_incompressible_and_compressible_covers_both_work(sphere_heights):
    for ratio in (0.5, 0.0, -0.3):
        cover = ElasticMaterial(1e6, ratio)
        result = solve_contact(sphere_heights, SPACING, cover, normal_force=1.0)
        hertz = hertz_sphere(1.0, RADIUS, cover.plane_strain_modulus)
        assert result.converged
        assert result.indentation == pytest.approx(hertz.indentation, rel=0.01)


def test_non_convergence_is_reported(sphere_heights):
    result = solve_contact(sphere_heights, SPACING, COVER, normal_force=1.0, max_iterations=3)
    assert not result.converged and result.n_iterations == 3
    assert "not converged" in result.message


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"normal_force": -1.0}, ValueError, r"`normal_force` must be >= 0, got -1"),
        ({"indentation": -1e-4}, ValueError, r"`indentation` must be >= 0, got -0.0001"),
        ({}, ValueError, "exactly one of `normal_force` and `indentation`"),
        ({"normal_force": 1.0, "indentation": 1e-4}, ValueError, "exactly one"),
        ({"normal_force": 1.0, "thickness": -1.0}, ValueError, "`thickness` must be > 0"),
        ({"normal_force": 1.0, "periodic": "no"}, TypeError, "`periodic` must be True or False"),
        ({"normal_force": 1.0, "max_iterations": np.nan}, ValueError, "`max_iterations` must"),
        ({"normal_force": 1.0, "max_iterations": 2.7}, ValueError, "`max_iterations` must be a"),
        ({"normal_force": 1.0, "max_iterations": "a"}, TypeError, "`max_iterations` must be a"),
        (
            {"normal_force": 1.0, "indenter_material": "steel"},
            TypeError,
            "`indenter_material` must be an ElasticMaterial, got 'steel'",
        ),
        ({"normal_force": 1.0, "initial": "x"}, TypeError, "`initial` must be a ContactResult"),
    ],
)
def test_bad_arguments(kwargs, error, match):
    with pytest.raises(error, match=match):
        solve_contact(np.zeros((8, 8)), 1e-3, COVER, **kwargs)


def test_bad_heights_and_shapes(sphere_result):
    heights = np.zeros((8, 8))
    heights[2, 3] = np.nan
    with pytest.raises(ValueError, match="`heights` must not contain NaN"):
        solve_contact(heights, 1e-3, COVER, normal_force=1.0)
    with pytest.raises(ValueError, match="`heights` must be 2-D"):
        solve_contact(np.zeros(8), 1e-3, COVER, normal_force=1.0)
    with pytest.raises(ValueError, match=r"`initial.pressure` must have shape \(8, 8\)"):
        solve_contact(np.zeros((8, 8)), 1e-3, COVER, normal_force=1.0, initial=sphere_result)
    with pytest.raises(ValueError, match="at least one finite value"):
        solve_contact(np.full((8, 8), np.inf), 1e-3, COVER, normal_force=1.0)


@pytest.mark.parametrize("material", [None, "rubber"])
def test_the_cover_must_be_a_material(material):
    with pytest.raises(TypeError, match="`material` must be an ElasticMaterial, got"):
        solve_contact(np.zeros((8, 8)), 1e-3, material, normal_force=1.0)
    with pytest.raises(TypeError, match="`first` must be an ElasticMaterial, got"):
        effective_modulus(material)
    with pytest.raises(TypeError, match="`second` must be an ElasticMaterial, got 'x'"):
        effective_modulus(COVER, "x")


def test_heights_are_a_gap_and_cannot_be_negative(sphere_heights):
    with pytest.raises(ValueError, match="`heights` must be >= 0 .*, got a minimum of -0.000999"):
        solve_contact(sphere_heights - 1e-3, SPACING, COVER, normal_force=1.0)
    # a vertex computed a rounding error below zero is zero
    nudged = solve_contact(sphere_heights - 1e-19, SPACING, COVER, normal_force=1.0)
    plain = solve_contact(sphere_heights, SPACING, COVER, normal_force=1.0)
    assert nudged.normal_force == pytest.approx(plain.normal_force, rel=1e-9)
    assert np.allclose(nudged.pressure, plain.pressure, atol=1e-6 * plain.pressure.max())


@pytest.mark.parametrize(
    ("spacing", "error", "match"),
    [
        (1e-300, ValueError, "`spacing` must be >= 1e-09 m, got 1e-300"),
        ("a", TypeError, "`spacing` must be a number or a"),
        (None, TypeError, "`spacing` must be a number or a"),
        (True, TypeError, "`spacing` must be a number or a"),
    ],
)
def test_spacing_is_a_length_of_at_least_a_nanometre(spacing, error, match):
    with pytest.raises(error, match=match):
        solve_contact(np.zeros((8, 8)), spacing, COVER, normal_force=0.1)


@pytest.mark.parametrize("shape", [(1, 1), (8, 1), (1, 8)])
def test_a_single_row_or_column_of_cells_is_solved(shape):
    result = solve_contact(np.zeros(shape), 1e-3, COVER, normal_force=0.1)
    assert result.converged and result.normal_force == pytest.approx(0.1)
    # a flat row pressed down all along: every cell carries load, symmetrically
    assert np.all(result.pressure > 0)
    assert np.allclose(result.pressure, result.pressure[::-1, ::-1], rtol=1e-6)


@pytest.mark.parametrize(
    ("load", "match"),
    [
        ({"normal_force": 1e300}, "`normal_force` 1e\\+300 N is too large to solve"),
        ({"indentation": 1e300}, "`indentation` 1e\\+300 m is too large to solve"),
    ],
)
@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # the overflow on the way
def test_a_load_whose_pressure_overflows_is_refused_by_name(load, match):
    # a NaN pressure field came back silently, and a sensor then blamed `pressure`
    heights = Sphere(RADIUS).on_grid((32, 32), SPACING)
    with pytest.raises(ValueError, match=match):
        solve_contact(heights, SPACING, COVER, **load)
