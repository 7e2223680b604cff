"""The dense factorization split by mirror symmetry agrees with the plain one."""

import numpy as np
import pytest

import taxel.reconstruction._mirror as mirror
import taxel.reconstruction._spectral as spectral
from taxel.reconstruction import TikhonovSolver, forward_model_preset

RESISTIVE = forward_model_preset("resistive16", shape=(10, 12))


def test_unfold_is_the_adjoint_of_fold_and_undoes_it_times_four():
    rng = np.random.default_rng(0)
    x = rng.normal(size=(3, 6, 8))
    parts = [rng.normal(size=(3, 12)) for _ in range(4)]
    folded = mirror.fold(x)
    assert np.allclose(mirror.unfold(folded, (6, 8)), 4 * x)
    inner = sum(np.vdot(f, p) for f, p in zip(folded, parts, strict=True))
    assert inner == pytest.approx(np.vdot(x, mirror.unfold(parts, (6, 8))), rel=1e-12)


def test_no_split_without_the_symmetry_or_with_odd_sizes():
    rng = np.random.default_rng(1)
    assert mirror.mirror_blocks(rng.normal(size=(16, 16)), (4, 4), (4, 4)) is None
    assert mirror.mirror_blocks(np.eye(9), (3, 3), (3, 3)) is None


def test_the_split_svd_reproduces_the_matrix_with_orthonormal_modes_in_one_part_each():
    operator = TikhonovSolver(RESISTIVE, representation="dense").spectrum._matrix
    u, s, vt, blocks = mirror.mirror_blocks(operator, RESISTIVE.shape, RESISTIVE.load_shape)
    assert np.allclose(u * s @ vt, operator, atol=1e-12 * np.abs(operator).max())
    assert np.allclose(u.T @ u, np.eye(s.size), atol=1e-12)
    assert np.allclose(np.sort(s), np.sort(np.linalg.svd(operator, compute_uv=False)))
    # a mode of part c changes sign under the reflections that part is odd along
    modes = u.T.reshape(-1, *RESISTIVE.shape)
    odd_rows, odd_cols = blocks.parts >= 2, blocks.parts % 2 == 1
    signs_rows = np.where(odd_rows, -1, 1)[:, None, None]
    signs_cols = np.where(odd_cols, -1, 1)[:, None, None]
    assert np.allclose(modes[:, ::-1], signs_rows * modes, atol=1e-12)
    assert np.allclose(modes[:, :, ::-1], signs_cols * modes, atol=1e-12)


@pytest.mark.parametrize("order", [0, 1, 2])
@pytest.mark.parametrize("oversampling", [1, 2])
@pytest.mark.parametrize("rule", ["gcv", "lcurve", 0.05, 0.0])
def test_split_and_plain_factorizations_solve_alike(monkeypatch, order, oversampling, rule):
    spec = RESISTIVE.with_changes(oversampling=oversampling)
    split = TikhonovSolver(spec, order=order, representation="dense")
    with monkeypatch.context() as patch:
        patch.setattr(spectral, "mirror_blocks", lambda *args: None)
        plain = TikhonovSolver(spec, order=order, representation="dense")
    assert split.spectrum._mirror is not None and plain.spectrum._mirror is None
    truth = np.zeros(spec.load_shape)
    truth[3 * oversampling : 6 * oversampling, 2 * oversampling : 4 * oversampling] = 50e3
    rng = np.random.default_rng(2)
    frames = split.operator.apply(truth) + rng.normal(0.0, 1e3, (7, *spec.shape))
    # chunks of 3 frames: the batch crosses chunk boundaries
    monkeypatch.setattr(mirror, "_CHUNK_BYTES", 3 * 8 * truth.size)
    a, b = split.solve(frames, regularization=rule), plain.solve(frames, regularization=rule)
    assert np.allclose(a.regularization, b.regularization, rtol=1e-9)
    assert np.allclose(a.pressure, b.pressure, atol=1e-9 * np.abs(b.pressure).max())
    assert np.allclose(a.residual_norm, b.residual_norm, rtol=1e-9)
    assert np.allclose(a.solution_norm, b.solution_norm, rtol=1e-9)


def test_dead_taxels_use_the_plain_factorization():
    spec = RESISTIVE.with_changes(dead_taxels=[(2, 3)])
    solver = TikhonovSolver(spec, representation="dense")
    assert solver.spectrum._mirror is None
