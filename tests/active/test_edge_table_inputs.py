"""Inputs of the edge-radius table's build refused at once, before any press."""

import pytest

from taxel.active import build_edge_radius_table, make_ball


@pytest.mark.parametrize("forces", [(), (12.0, 12.0), (39.0, 12.0, 39.0)])
def test_no_forces_or_a_repeated_force_is_refused_before_pressing(forces):
    pressed = []
    with pytest.raises(ValueError, match=r"`forces` must hold one or more distinct forces"):
        build_edge_radius_table(
            [2e-3, 6e-3],
            sensor="resistive16",
            forces=forces,
            orientations=2,
            progress=lambda done, total: pressed.append(done),
        )
    assert pressed == []


@pytest.mark.parametrize("position", [(0.0, 0.0, 0.0), (0.0,), "xyz"])
def test_a_ball_s_position_must_be_an_x_y_pair(position):
    with pytest.raises(ValueError, match=r"`position` must be an \(x, y\) pair"):
        make_ball("ball", 5e-3, position=position)
