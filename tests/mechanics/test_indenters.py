"""Indenter height maps: profiles, continuity, symmetry, placement and the named library."""

import numpy as np
import pytest

from taxel.mechanics import (
    INDENTER_NAMES,
    BoxCorner,
    BoxEdge,
    CanRim,
    Cone,
    Cylinder,
    FlatPunch,
    HeightMap,
    PerforatedScreen,
    PlateWithHole,
    SlottedPlate,
    Sphere,
    StiffFoam,
    Washer,
    WoodRasp,
    describe_indenters,
    grid_coordinates,
    make_indenter,
)


def test_sphere_and_cylinder_profiles():
    r = np.linspace(0, 4.9e-3, 50)
    assert np.allclose(Sphere(5e-3).local_heights(r, 0 * r), 5e-3 - np.sqrt(25e-6 - r**2))
    assert np.isinf(Sphere(5e-3).local_heights(np.array(6e-3), np.array(0.0)))
    edge = Cylinder(3.2e-3, length=10e-3)
    assert edge.local_heights(np.array(4e-3), np.array(1e-3)) == pytest.approx(
        3.2e-3 - np.sqrt(3.2e-3**2 - 1e-6)
    )
    assert np.isinf(edge.local_heights(np.array(6e-3), np.array(0.0)))


def test_cone_is_continuous_and_tangent_at_the_ball():
    cone = Cone(tip_radius=0.35e-3, half_angle=np.radians(20))
    tangent = 0.35e-3 * np.cos(np.radians(20))
    r = tangent + np.array([-1e-9, 1e-9])
    h = cone.local_heights(r, 0 * r)
    # no step: across 2 nm the height changes by no more than the cone's slope allows
    assert abs(h[1] - h[0]) <= 1.01 * 2e-9 / np.tan(np.radians(20))
    slope = (
        cone.local_heights(np.array(2e-3), np.array(0.0))
        - cone.local_heights(np.array(1e-3), np.array(0.0))
    ) / 1e-3
    assert slope == pytest.approx(1 / np.tan(np.radians(20)))


def test_punch_washer_rim_and_plates():
    punch = FlatPunch(2e-3, edge_radius=0.1e-3)
    assert punch.local_heights(np.array(1.9e-3), np.array(0.0)) == 0
    assert punch.local_heights(np.array(2.1e-3), np.array(0.0)) == pytest.approx(0.1e-3)
    washer = Washer(8e-3, 4.2e-3, edge_radius=0.2e-3)
    radii = np.array([3e-3, 6e-3, 9e-3])
    h = washer.local_heights(radii, 0 * radii)
    assert np.isinf(h[0]) and h[1] == 0 and np.isinf(h[2])
    rim = CanRim(26e-3, 1e-3)
    assert rim.local_heights(np.array(0.0), np.array(26e-3)) == 0
    assert np.isinf(rim.local_heights(np.array(0.0), np.array(0.0)))
    slot = SlottedPlate(slot_width=3e-3, slot_length=15e-3)
    assert np.isinf(slot.local_heights(np.array(7e-3), np.array(1.4e-3)))
    assert slot.local_heights(np.array(7e-3), np.array(1.6e-3)) == 0
    hole = PlateWithHole(3e-3, crown_radius=1.0)
    assert np.isinf(hole.local_heights(np.array(2.9e-3), np.array(0.0)))
    assert hole.local_heights(np.array(4e-3), np.array(0.0)) == pytest.approx(8e-6)


def test_box_edge_faces_rise_at_45_degrees():
    edge = BoxEdge(edge_radius=0.5e-3)
    v = np.array([2e-3, 3e-3])
    h = edge.local_heights(0 * v, v)
    assert (h[1] - h[0]) / 1e-3 == pytest.approx(1.0)
    assert edge.local_heights(np.array(5.0), np.array(0.0)) == 0  # constant along the edge


def test_box_corner_matches_sharp_cube_and_has_threefold_symmetry():
    sharp = BoxCorner(edge_radius=0.0)
    u, v = np.random.default_rng(0).uniform(-3e-3, 3e-3, (2, 100))
    azimuths = np.radians([180.0, 300.0, 60.0])
    planes = [-np.sqrt(2) * (np.cos(t) * u + np.sin(t) * v) for t in azimuths]
    assert np.allclose(sharp.local_heights(u, v), np.max(planes, axis=0), atol=1e-15)
    rounded = BoxCorner(edge_radius=0.5e-3)
    turn = np.radians(120)
    rotated = rounded.local_heights(
        np.cos(turn) * u - np.sin(turn) * v, np.sin(turn) * u + np.cos(turn) * v
    )
    assert np.allclose(rotated, rounded.local_heights(u, v), atol=1e-15)
    assert np.all(rounded.local_heights(u, v) >= 0)
    # mid-face, away from the vertex: the rounded solid's face is the sharp face offset by rho
    # along its normal, which lowers it by sqrt(3) rho; the tip itself is raised by rho
    far = np.array([3e-3]), np.array([0.0])
    offset = 0.5e-3 * (np.sqrt(3) - 1)
    assert rounded.local_heights(*far) == pytest.approx(
        sharp.local_heights(*far) - offset, rel=1e-9
    )


def test_placement_translates_and_rotates():
    edge = Cylinder(2e-3)
    x, y = grid_coordinates((40, 40), 0.2e-3)
    placed = edge.heights(x, y, position=(1e-3, -0.5e-3), angle=np.pi / 2)
    # rotated by 90 degrees: the edge runs along y, at x = 1 mm
    assert np.allclose(placed, edge.local_heights(y + 0.5e-3, -(x - 1e-3)))
    assert np.allclose(placed[:, 0], placed[0, 0])  # constant down a column


def test_textures_are_reproducible_and_seeded():
    x, y = grid_coordinates((32, 32), 0.25e-3)
    for texture in (StiffFoam, WoodRasp, PerforatedScreen):
        first = texture(seed=1).heights(x, y)
        again = texture(seed=1).heights(x, y)
        other = texture(seed=2).heights(x, y)
        assert np.array_equal(first, again)
        assert not np.array_equal(first, other)
        assert np.nanmin(np.where(np.isfinite(first), first, np.nan)) >= 0


def test_textures_are_periodic_on_their_tile():
    # without tip scatter every tooth is alike: the pattern repeats every tooth pitch along u
    # and every two rows along v (odd rows are staggered by half a pitch)
    rasp = WoodRasp(scatter=0.0)
    u, v = np.random.default_rng(4).uniform(0, 3e-3, (2, 50))
    base = rasp.local_heights(u, v)
    # the tile is sampled every 60 um and interpolated linearly across the teeth's kinks
    # (slope 1.7): a few micrometres, against 0.6 mm for a shift that breaks the pattern
    tolerance = 5e-6
    assert np.allclose(rasp.local_heights(u + 3e-3, v), base, atol=tolerance)
    assert np.allclose(rasp.local_heights(u, v + 5e-3), base, atol=tolerance)
    assert np.allclose(rasp.local_heights(u + 1.5e-3, v + 2.5e-3), base, atol=tolerance)
    assert np.abs(rasp.local_heights(u + 1.5e-3, v) - base).max() > 100 * tolerance
    screen = PerforatedScreen(waviness=0.0)
    centre = screen.local_heights(np.array([0.0, 6e-3, 3e-3]), np.array([0.0, 0.0, 6e-3 * 0.866]))
    assert np.all(np.isinf(centre))  # hole centres of the staggered pattern
    web = screen.local_heights(np.array([3e-3]), np.array([0.0]))
    assert web == 0


def test_height_map_interpolates_and_has_no_material_outside():
    values = np.array([[0.0, 1.0], [2.0, 3.0]]) * 1e-4
    bowl = HeightMap(values, 1e-3)
    assert bowl.local_heights(np.array(0.0), np.array(0.0)) == pytest.approx(1.5e-4)
    assert np.isinf(bowl.local_heights(np.array(5e-3), np.array(0.0)))
    with pytest.raises(ValueError, match="must not contain NaN"):
        HeightMap(np.array([[np.nan]]), 1e-3)
    with pytest.raises(ValueError, match=r"above the indenter's lowest point .* -0.0001 m"):
        HeightMap(values - 1e-4, 1e-3)


def test_library_builds_every_named_indenter():
    descriptions = describe_indenters()
    assert set(descriptions) == set(INDENTER_NAMES)
    x, y = grid_coordinates((16, 16), 1e-3)
    for name in INDENTER_NAMES:
        heights = make_indenter(name).heights(
            x, y, position=(-20e-3, 0.0) if name == "can" else (0.0, 0.0)
        )
        assert heights.shape == (16, 16)
        assert not np.isnan(heights).any()
        assert np.isfinite(heights).any(), name
    assert make_indenter("sphere", radius=1e-3) == Sphere(1e-3)


@pytest.mark.parametrize(
    ("factory", "match"),
    [
        (lambda: Sphere(-1.0), "`radius` must be > 0"),
        (lambda: Cone(1e-3, 2.0), r"`half_angle` must lie in \(0, 1.5708\)"),
        (lambda: Washer(4e-3, 4e-3), "`inner_radius` \\+ 2 `edge_radius` must be <"),
        (lambda: make_indenter("teapot"), "`name` must be one of pen, sphere"),
        (lambda: PerforatedScreen(hole_diameter=7e-3), "`hole_diameter` must be < `pitch`"),
    ],
)
def test_bad_parameters(factory, match):
    with pytest.raises(ValueError, match=match):
        factory()


@pytest.mark.parametrize("position", [(0,), 0.0, (1e-3, 2e-3, 0.0)])
def test_a_position_must_be_an_x_y_pair(position):
    with pytest.raises(ValueError, match=r"`position` must be an \(x, y\) pair, got"):
        Sphere(5e-3).on_grid((8, 8), 1e-3, position=position)


@pytest.mark.parametrize(
    ("shape", "match"),
    [
        ((-8, 8), "`shape` must be >= 1, got -8"),
        ((0, 8), "`shape` must be >= 1, got 0"),
        ((8.5, 8), "`shape` must be a whole number, got 8.5"),
        ((2, 3, 4), r"`shape` must be a \(rows, cols\) pair"),
        (5, r"`shape` must be a \(rows, cols\) pair"),
    ],
)
def test_a_grid_shape_must_be_two_counts(shape, match):
    with pytest.raises(ValueError, match=match):
        Sphere(5e-3).on_grid(shape, 1e-3)


def test_heights_of_mismatched_coordinates_are_refused():
    with pytest.raises(ValueError, match=r"`x` and `y` must have shapes that broadcast .* \(3,\)"):
        Sphere(5e-3).heights(np.zeros(3), np.zeros(4))
    assert Sphere(5e-3).heights(np.zeros((1, 3)), np.zeros((4, 1))).shape == (4, 3)


def test_a_bool_is_not_a_radius():
    with pytest.raises(TypeError, match="`radius` must be a real number, got True"):
        make_indenter("sphere", radius=True)
