"""The sensor's forward operator: dot tests, dense and fast agree, the models' structure."""

import numpy as np
import pytest
from scipy import fft

from taxel.mechanics import ElasticMaterial, depth_stress_operator
from taxel.reconstruction import ForwardModelSpec, forward_model_preset, forward_operator
from taxel.reconstruction._model import block_average, dense_penalty, fold_1d, penalty_eigenvalues

SMALL = forward_model_preset("resistive16", shape=(5, 6))
LAYOUTS = [(b, r) for b in ("zero", "reflect") for r in ("dense", "fast")]


@pytest.mark.parametrize("oversampling", [1, 2, 3])
@pytest.mark.parametrize(("boundary", "representation"), LAYOUTS)
def test_dot_test(boundary, representation, oversampling):
    spec = SMALL.with_changes(oversampling=oversampling)
    operator = forward_operator(spec, boundary=boundary, representation=representation)
    rng = np.random.default_rng(0)
    x = rng.standard_normal((3, *spec.load_shape))  # a batch of three
    y = rng.standard_normal((3, *spec.shape))
    left, right = np.vdot(operator.apply(x), y), np.vdot(x, operator.adjoint(y))
    assert left == pytest.approx(right, rel=1e-12)


@pytest.mark.parametrize("oversampling", [1, 2])
@pytest.mark.parametrize("boundary", ["zero", "reflect"])
def test_dense_and_fast_are_the_same_map(boundary, oversampling):
    spec = SMALL.with_changes(oversampling=oversampling)
    dense = forward_operator(spec, boundary=boundary, representation="dense")
    fast = forward_operator(spec, boundary=boundary, representation="fast")
    # the dense matrices are built independently (kernel gather, sum over mirror images)
    assert np.allclose(dense.to_matrix(), fast.to_matrix(), rtol=0, atol=1e-13)


@pytest.mark.parametrize(
    "quantity, depth, thickness",
    [("stress", 1e-3, None), ("strain", 1e-3, 2e-3), ("displacement", 0.0, 2e-3)],
)
def test_other_quantities_dense_and_fast_agree(quantity, depth, thickness):
    spec = ForwardModelSpec(
        (4, 5), 1e-3, ElasticMaterial(1e6, 0.4), depth, thickness=thickness, quantity=quantity
    )
    for boundary in ("zero", "reflect"):
        dense = forward_operator(spec, boundary=boundary, representation="dense").to_matrix()
        fast = forward_operator(spec, boundary=boundary, representation="fast").to_matrix()
        assert np.allclose(dense, fast, rtol=0, atol=1e-12 * np.abs(dense).max())


def test_zero_model_at_oversampling_one_is_the_mechanics_operator():
    spec = SMALL
    mechanics = depth_stress_operator(
        spec.shape, spec.taxel_pitch, spec.depth, spec.material, thickness=spec.thickness
    )
    ours = forward_operator(spec, boundary="zero", representation="dense")
    assert np.allclose(ours.to_matrix(), -mechanics.to_matrix(), rtol=1e-12, atol=1e-15)


def test_oversampled_model_is_fine_operator_then_block_average():
    spec = SMALL.with_changes(oversampling=2)
    fine = depth_stress_operator(
        spec.load_shape, spec.load_pitch, spec.depth, spec.material, thickness=spec.thickness
    )
    pressure = np.random.default_rng(1).random(spec.load_shape)
    expected = block_average(-fine.apply(pressure), 2)
    assert np.allclose(forward_operator(spec, boundary="zero").apply(pressure), expected)


def test_models_agree_away_from_the_edges_and_differ_at_them():
    spec = forward_model_preset("resistive16", shape=(16, 16))
    zero = forward_operator(spec, boundary="zero", representation="dense")
    reflect = forward_operator(spec, boundary="reflect", representation="dense")
    centre = np.zeros(spec.shape)
    centre[7:9, 7:9] = 1.0
    edge = np.zeros(spec.shape)
    edge[7:9, 0] = 1.0
    assert np.abs(zero.apply(centre) - reflect.apply(centre)).max() < 1e-4
    assert np.abs(zero.apply(edge) - reflect.apply(edge)).max() > 0.05


def test_uniform_pressure_reads_itself_in_the_reflective_model():
    operator = forward_operator(SMALL, boundary="reflect", representation="fast")
    readings = operator.apply(np.full(SMALL.shape, 2e4))
    assert np.allclose(readings, 2e4, rtol=1e-3)


@pytest.mark.parametrize("factor", [1, 2, 3, 4])
def test_fold_is_the_block_average_in_dct_bases(factor):
    coarse = 7
    fine_basis = fft.dct(np.eye(coarse * factor), norm="ortho", axis=0)
    coarse_basis = fft.dct(np.eye(coarse), norm="ortho", axis=0)
    average = np.kron(np.eye(coarse), np.ones((1, factor)) / factor)
    expected = coarse_basis @ average @ fine_basis.T
    index, weight = fold_1d(coarse, factor)
    folded = np.zeros_like(expected)
    valid = index >= 0
    folded[index[valid], np.flatnonzero(valid)] = weight[valid]
    assert np.allclose(folded, expected, atol=1e-14)


@pytest.mark.parametrize("order", [0, 1, 2])
def test_penalty_is_diagonal_in_the_dct(order):
    shape = (5, 4)
    matrix = dense_penalty(shape, order)
    eye = np.eye(20).reshape(20, *shape)
    basis = fft.idctn(eye, norm="ortho", axes=(1, 2)).reshape(20, 20)  # rows: DCT modes
    diagonal = basis @ matrix @ basis.T
    assert np.allclose(diagonal, np.diag(penalty_eigenvalues(shape, order).ravel()), atol=1e-12)


def test_bad_input():
    operator = forward_operator(SMALL)
    with pytest.raises(ValueError, match="`pressure` must end with the shape"):
        operator.apply(np.zeros((4, 4)))
    with pytest.raises(ValueError, match="`pressure` must be finite"):
        operator.apply(np.full(SMALL.shape, np.nan))
    with pytest.raises(ValueError, match="`boundary` must be one of"):
        forward_operator(SMALL, boundary="periodic")
    with pytest.raises(ValueError, match="`boundary` 'zero' has no fast factorization"):
        from taxel.reconstruction._spectral import build_spectrum

        build_spectrum(forward_operator(SMALL, boundary="zero", representation="fast"), 0)
