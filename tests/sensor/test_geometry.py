import re

import numpy as np
import pytest

from taxel.mechanics import ElasticMaterial
from taxel.sensor._cover import Cover
from taxel.sensor._geometry import ArrayGeometry, density_class


def test_ellis_vhdta_density():
    geometry = ArrayGeometry(128, 128, 33e-3 / 128)
    # the seed: "3.3 cm on a side ... approximately 1504 taxels/cm^2"
    assert geometry.density == pytest.approx(128**2 / 3.3**2, rel=1e-12)
    assert round(geometry.density) == 1504
    assert geometry.density_class == "VHDTA"
    assert geometry.extent == pytest.approx((33e-3, 33e-3))


@pytest.mark.parametrize(
    ("density", "name"),
    [(0.8, "LDTA"), (2.0, "LDTA"), (4.0, "MDTA"), (25.0, "MDTA"), (40.0, "HDTA"), (400, "VHDTA")],
)
def test_density_classes_by_order_of_magnitude(density, name):
    assert density_class(density) == name


def test_positions_are_centred_and_pitched():
    geometry = ArrayGeometry(3, 4, (1e-3, 2e-3), layout="rectangular")
    x, y = geometry.positions()
    assert np.allclose(x[0], [-3e-3, -1e-3, 1e-3, 3e-3])
    assert np.allclose(y[:, 0], [-1e-3, 0, 1e-3])
    assert geometry.density == pytest.approx(1 / (0.1 * 0.2))


def test_hexagonal_layout_staggers_rows():
    geometry = ArrayGeometry(4, 5, 2e-3, layout="hexagonal")
    x, y = geometry.positions()
    assert geometry.pitch[0] == pytest.approx(2e-3 * np.sqrt(3) / 2)
    assert x[1, 0] - x[0, 0] == pytest.approx(1e-3)
    # every taxel's nearest neighbours are one pitch away: a triangular lattice
    points = np.stack([x.ravel(), y.ravel()], axis=1)
    distances = np.linalg.norm(points[:, None] - points[None], axis=-1)
    np.fill_diagonal(distances, np.inf)
    assert np.allclose(distances.min(axis=1), 2e-3)


@pytest.mark.parametrize("layout", ["square", "hexagonal"])
@pytest.mark.parametrize("oversampling", [1, 2])
def test_load_grid_blocks_average_to_taxels(layout, oversampling):
    geometry = ArrayGeometry(4, 6, 1e-3, layout=layout)
    grid = geometry.load_grid(oversampling)
    x, y = grid.coordinates()
    # the mean of the cell coordinates over each block is the taxel's centre
    taxel_x, taxel_y = geometry.positions()
    assert np.allclose(grid.taxel_means(x), taxel_x, atol=1e-12)
    assert np.allclose(grid.taxel_means(y), taxel_y, atol=1e-12)
    assert np.allclose(grid.taxel_means(np.ones(grid.shape)), 1.0)
    assert grid.taxel_means(np.ones((3, *grid.shape))).shape == (3, 4, 6)  # leading axes kept


@pytest.mark.parametrize("layout", ["square", "hexagonal"])
@pytest.mark.parametrize("oversampling", [1, 2])
def test_load_grid_names_a_field_of_another_shape(layout, oversampling):
    grid = ArrayGeometry(4, 6, 1e-3, layout=layout).load_grid(oversampling)
    rows, cols = grid.shape
    expected = rf"`field` must be on the load grid, shape \(\.\.\., {rows}, {cols}\)"
    for field in (np.zeros((3, 3)), np.zeros(rows * cols), np.zeros((cols, rows))):
        with pytest.raises(ValueError, match=expected + ", got " + re.escape(str(field.shape))):
            grid.taxel_means(field)


def test_fields_name_a_displacement_off_the_load_grid():
    from taxel.sensor import make_sensor, taxel_fields

    sensor = make_sensor("capacitive4x4")
    grid = sensor.load_grid
    with pytest.raises(ValueError, match=r"`displacement` must be on the sensor's load grid"):
        taxel_fields(np.zeros(grid.shape), grid, sensor.cover, displacement=np.zeros((3, 3)))


def test_bad_geometry_and_cover():
    with pytest.raises(ValueError, match="`pitch` must be > 0, got 0"):
        ArrayGeometry(4, 4, 0.0)
    with pytest.raises(ValueError, match="`rows` must be a positive integer"):
        ArrayGeometry(0, 4, 1e-3)
    with pytest.raises(ValueError, match="`layout` must be one of"):
        ArrayGeometry(4, 4, 1e-3, layout="spiral")
    with pytest.raises(ValueError, match="`thickness` must be >= `depth`"):
        Cover(ElasticMaterial(1e6, 0.4), depth=2e-3, thickness=1e-3)
