"""Poses: construction, inverse, composition, points versus directions, and bad input."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import taxel.frames
from taxel.frames import (
    as_pose,
    compose_poses,
    invert_pose,
    make_pose,
    sensor_pose,
    transform_directions,
    transform_points,
)


def _random_pose(rng):
    return make_pose(Rotation.random(random_state=rng), rng.normal(size=3))


def test_public_namespace():
    assert sorted(taxel.frames.__all__) == [
        "as_pose",
        "compose_poses",
        "invert_pose",
        "make_pose",
        "sensor_pose",
        "transform_directions",
        "transform_points",
    ]


@pytest.mark.parametrize("seed", range(5))
def test_inverse_and_composition(seed):
    rng = np.random.default_rng(seed)
    a, b, c = (_random_pose(rng) for _ in range(3))
    assert np.allclose(invert_pose(a) @ a, np.eye(4), atol=1e-12)
    assert np.allclose(compose_poses(a, b, c), a @ b @ c)
    assert np.allclose(invert_pose(compose_poses(a, b)), invert_pose(b) @ invert_pose(a))
    points = rng.normal(size=(7, 3))
    back = transform_points(invert_pose(a), transform_points(a, points))
    assert np.allclose(back, points)


def test_points_translate_directions_do_not():
    pose = make_pose(Rotation.from_euler("x", 180, degrees=True), [1.0, 2.0, 3.0])
    assert np.allclose(transform_points(pose, [0.0, 0.0, 1.0]), [1.0, 2.0, 2.0])
    assert np.allclose(transform_directions(pose, [0.0, 0.0, 1.0]), [0.0, 0.0, -1.0])


def test_rotation_preserves_distances():
    rng = np.random.default_rng(9)
    pose = _random_pose(rng)
    points = rng.normal(size=(2, 3))
    moved = transform_points(pose, points)
    assert np.linalg.norm(moved[0] - moved[1]) == pytest.approx(
        np.linalg.norm(points[0] - points[1])
    )


def test_sensor_chain():
    flange = make_pose(Rotation.from_euler("z", 90, degrees=True), [0.5, 0.0, 0.4])
    mount = make_pose(translation=[0.02, 0.0, 0.1])
    chain = sensor_pose(flange, mount)
    # the mount offset along the flange's x becomes the base's y after the 90 deg turn
    assert np.allclose(chain[:3, 3], [0.5, 0.02, 0.5])


def test_matrix_rotation_accepted():
    matrix = Rotation.from_rotvec([0.1, -0.2, 0.3]).as_matrix()
    assert np.allclose(make_pose(matrix)[:3, :3], matrix)


@pytest.mark.parametrize(
    ("value", "match"),
    [
        (np.eye(3), r"`pose` must have shape \(4, 4\)"),
        (np.diag([1.0, 1.0, 2.0, 1.0]), "proper rotation"),
        (np.diag([1.0, 1.0, -1.0, 1.0]), "proper rotation"),
        (np.full((4, 4), np.nan), "finite"),
    ],
)
def test_bad_pose(value, match):
    with pytest.raises(ValueError, match=match):
        as_pose(value)


@pytest.mark.parametrize(
    "value",
    [
        np.eye(4, dtype=bool),  # a mask, which other inputs read as 0 and 1
        [[1, 0, 0, True], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]],  # True: a metre
        (np.eye(4)[0], (0, 1, 0, 0), [0, 0, 1, np.False_], [0, 0, 0, 1]),
    ],
)
def test_a_pose_holding_booleans_is_refused(value):
    with pytest.raises(TypeError, match="`pose` must be numeric, got a boolean in it"):
        as_pose(value)
    with pytest.raises(TypeError, match="`pose` must be numeric, got a boolean in it"):
        as_pose(np.array(value, dtype=object))


def test_make_pose_refuses_booleans():
    with pytest.raises(TypeError, match="`translation` must be numeric, got a boolean"):
        make_pose(None, [True, 0.0, 0.0])  # True: a metre
    with pytest.raises(TypeError, match="`rotation` must be numeric, got a boolean"):
        make_pose(np.eye(3, dtype=bool))


def test_a_ragged_pose_is_named_so():
    with pytest.raises(ValueError, match="`pose` must be a regular array: its nested lists"):
        as_pose([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1]])


def test_bad_arguments():
    with pytest.raises(ValueError, match="translation"):
        make_pose(None, [1.0, 2.0])
    with pytest.raises(ValueError, match="rotation"):
        make_pose(np.eye(2))
    with pytest.raises(ValueError, match="points"):
        transform_points(np.eye(4), [1.0, 2.0])
    with pytest.raises(ValueError, match="poses"):
        compose_poses()
    with pytest.raises(ValueError, match="flange_to_sensor"):
        sensor_pose(np.eye(4), np.zeros((4, 4)))
