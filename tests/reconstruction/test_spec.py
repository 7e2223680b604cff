"""The forward-model specification, its presets and duck typing."""

import numpy as np
import pytest

from taxel.mechanics import ElasticMaterial
from taxel.reconstruction import (
    FORWARD_MODEL_PRESETS,
    ForwardModelSpec,
    as_forward_model_spec,
    forward_model_preset,
)

COVER = ElasticMaterial(1e6, 0.49)


def test_presets_hold_the_issue_numbers():
    assert {"vhdta128", "resistive16"} <= set(FORWARD_MODEL_PRESETS)
    big = forward_model_preset("vhdta128")
    assert big.shape == (128, 128) and big.taxel_pitch == pytest.approx(33e-3 / 128)
    assert (big.depth, big.thickness) == (1e-3, 1e-3)
    assert big.full_scale == pytest.approx(60 * 6894.757)  # 60 psi, the Ellis seed's range
    assert big.material == ElasticMaterial(0.5e6, 0.49) and big.quantity == "stress"
    small = forward_model_preset("resistive16", oversampling=2)
    assert small.shape == (16, 16) and small.taxel_pitch == 2e-3
    assert (small.depth, small.thickness, small.full_scale) == (1.5e-3, 1.5e-3, 200e3)
    assert small.load_shape == (32, 32) and small.load_pitch == 1e-3


def test_dead_taxels_from_mask_or_pairs():
    mask = np.zeros((4, 5), dtype=bool)
    mask[1, 2] = mask[3, 0] = True
    from_mask = ForwardModelSpec((4, 5), 1e-3, COVER, 1e-3, dead_taxels=mask)
    from_pairs = ForwardModelSpec((4, 5), 1e-3, COVER, 1e-3, dead_taxels=[(3, 0), (1, 2)])
    assert from_mask == from_pairs and from_mask.dead_taxels == ((1, 2), (3, 0))
    assert np.array_equal(~from_mask.live_taxels, mask)
    assert hash(from_mask) == hash(from_pairs)  # usable as a cache key
    whole = ForwardModelSpec((4.0, 5), 1e-3, COVER, 1e-3, dead_taxels=[(3.0, 0), (1, 2)])
    assert whole == from_pairs and whole.shape == (4, 5)


def test_preset_refuses_a_triple_as_a_dead_taxel():
    with pytest.raises(ValueError, match=r"`dead_taxels` must be a boolean mask or \(row, col\)"):
        forward_model_preset("resistive16", dead_taxels=[(1, 2, 3)])


class _Sensor:
    def forward_model_spec(self):
        return forward_model_preset("resistive16")


def test_duck_typing():
    assert as_forward_model_spec(_Sensor()) == forward_model_preset("resistive16")
    assert as_forward_model_spec("vhdta128").shape == (128, 128)
    with pytest.raises(TypeError, match="`sensor` must be a ForwardModelSpec"):
        as_forward_model_spec(3.0)


@pytest.mark.parametrize(
    "changes, message",
    [
        ({"shape": (1, 4)}, "`shape` must be at least"),
        ({"taxel_pitch": -1.0}, "`taxel_pitch` must be > 0, got -1"),
        ({"quantity": "heat"}, "`quantity` must be one of"),
        ({"depth": 2e-3, "thickness": 1e-3}, "`depth` must be <= `thickness`"),
        ({"oversampling": 1.5}, "`oversampling` must be an integer"),
        ({"dead_taxels": [(9, 9)]}, "`dead_taxels` must lie inside"),
        ({"noise_level": 0.0}, "`noise_level` must be > 0"),
        ({"shape": (16.5, 16)}, r"`shape` must be a whole number, got 16.5"),
        ({"shape": 16}, r"`shape` must be a \(rows, cols\) pair, got 16"),
        ({"oversampling": "2"}, r"`oversampling` must be an integer in 1..8, got '2'"),
        ({"dead_taxels": [(1, 2, 3)]}, r"`dead_taxels` must be a boolean mask or \(row, col\)"),
        ({"dead_taxels": [1, 2, 3, 4]}, r"`dead_taxels` must be .* pairs, got \[1, 2, 3, 4\]"),
        ({"dead_taxels": [(1, 2), (1, 2, 3)]}, r"`dead_taxels` must be a boolean mask"),
        ({"dead_taxels": np.ones((4, 4), int)}, r"`dead_taxels` must be a boolean mask"),
        ({"dead_taxels": [(1.5, 2)]}, r"`dead_taxels` must hold whole-number \(row, col\)"),
        ({"dead_taxels": [("a", "b")]}, r"`dead_taxels` must hold whole-number"),
    ],
)
def test_bad_spec(changes, message):
    arguments = {"shape": (4, 4), "taxel_pitch": 1e-3, "material": COVER, "depth": 1e-3}
    with pytest.raises(ValueError, match=message):
        ForwardModelSpec(**(arguments | changes))


def test_unknown_preset():
    with pytest.raises(
        ValueError, match="`sensor` must be one of vhdta128, harmon10x20, resistive16"
    ):
        forward_model_preset("gelsight")


def test_spec_follows_any_sensor_and_refuses_fibre_readings():
    from taxel.reconstruction import spec_from_sensor
    from taxel.sensor import make_sensor

    capacitive = spec_from_sensor(make_sensor("capacitive4x4"))
    assert capacitive.quantity == "stress"  # the cell's own modulus: stress at depth
    assert capacitive.taxel_pitch == 5e-3
    with pytest.raises(ValueError, match="does not give one reading per taxel"):
        spec_from_sensor(make_sensor("microbend16"))
    with pytest.raises(ValueError, match="must be a square array"):
        spec_from_sensor(
            make_sensor("harmon10x20").__class__(
                **{
                    **make_sensor("harmon10x20").__dict__,
                    "geometry": make_sensor("harmon10x20").geometry.__class__(
                        4, 4, 1e-3, layout="hexagonal"
                    ),
                }
            )
        )
