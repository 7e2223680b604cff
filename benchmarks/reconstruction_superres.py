"""Super-resolution (a load grid finer than the taxels) and the centroid of an edge.

Issue 4 asks that a load grid of half the taxel pitch improve the centroid of an edge over
the taxel grid. The truth is solved on a grid four times finer than the taxels (neither
solver's grid: no inverse crime), pressed 4 N by a 16 mm edge at a random place and angle
on resistive16, read through the exact model with 1 % noise, and reconstructed on the
taxel grid (k = 1) and on half its pitch (k = 2).
"""

from __future__ import annotations

import numpy as np

from taxel.mechanics import make_indenter, solve_contact
from taxel.reconstruction import forward_model_preset, forward_operator, reconstruct

EDGES = 24
METHODS = {
    "tikhonov order 1, gcv": {"order": 1, "regularization": "gcv"},
    "tikhonov order 1, default rule": {"order": 1},
    "support (library)": {"method": "support"},
}


def centroid(pressure: np.ndarray, pitch: float, *, window: bool) -> np.ndarray:
    """(x, y) [m] of a pressure map, over the cells above 10 % of its peak or all of them."""
    rows, cols = pressure.shape
    x = (np.arange(cols) - (cols - 1) / 2) * pitch
    y = (np.arange(rows) - (rows - 1) / 2) * pitch
    weights = np.where(pressure > 0.1 * pressure.max(), pressure, 0.0) if window else pressure
    return np.array([(weights.sum(0) * x).sum(), (weights.sum(1) * y).sum()]) / weights.sum()


def errors(edges: int = EDGES, seed: int = 5) -> dict[tuple[str, bool, int], np.ndarray]:
    """Centroid error [taxels] per (method, windowed, k), one per random edge."""
    truth_spec = forward_model_preset("resistive16", oversampling=4)
    operator = forward_operator(truth_spec)
    rng = np.random.default_rng(seed)
    found: dict[tuple[str, bool, int], list[float]] = {}
    for _ in range(edges):
        position = tuple(rng.uniform(-3e-3, 3e-3, 2))
        angle = float(rng.uniform(0.0, np.pi))
        heights = make_indenter("edge", length=16e-3).on_grid(
            truth_spec.load_shape, truth_spec.load_pitch, position=position, angle=angle
        )
        truth = solve_contact(
            heights,
            truth_spec.load_pitch,
            truth_spec.material,
            thickness=truth_spec.thickness,
            normal_force=4.0,
        ).pressure
        frame = operator.apply(truth) + rng.normal(0.0, 0.01 * 200e3, truth_spec.shape)
        expected = centroid(truth, truth_spec.load_pitch, window=False)
        for name, options in METHODS.items():
            for k in (1, 2):
                spec = truth_spec.with_changes(oversampling=k)
                pressure = reconstruct(frame, spec, **options).pressure
                for window in (True, False):
                    shift = centroid(pressure, spec.load_pitch, window=window) - expected
                    error = float(np.hypot(*shift)) / truth_spec.taxel_pitch
                    found.setdefault((name, window, k), []).append(error)
    return {key: np.array(values) for key, values in found.items()}


def section(quick: bool) -> tuple[list[str], tuple[float, float]]:
    """Markdown lines: mean centroid error at k = 1 and 2, and how often k = 2 is closer;
    and the support method's windowed mean error at k = 1 and k = 2 [taxels]."""
    edges = 6 if quick else EDGES
    found = errors(edges)
    lines = [
        "| method | centroid over | mean error, k = 1 [taxels] | mean error, k = 2 "
        "[taxels] | edges where k = 2 is closer |",
        "|---|---|---|---|---|",
    ]
    for name in METHODS:
        for window in (True, False):
            coarse, fine = found[name, window, 1], found[name, window, 2]
            lines.append(
                f"| {name} | {'cells >= 10 % of the peak' if window else 'the whole map'} | "
                f"{coarse.mean():.4f} | {fine.mean():.4f} | {int(np.sum(fine < coarse))} of "
                f"{edges} |"
            )
    coarse, fine = (found["support (library)", True, k].mean() for k in (1, 2))
    ratios = [
        found[name, window, 2].mean() / found[name, window, 1].mean()
        for name in METHODS
        if name.startswith("tikhonov")
        for window in (True, False)
    ]
    lines += [
        "",
        f"With the support method the windowed centroid's mean error is x{fine / coarse:.2f} "
        f"at k = 2; with Tikhonov x{min(ratios):.2f} to x{max(ratios):.2f}, no consistent "
        "gain, as a linear method should not have one: a convolution keeps the first moment "
        "of the load, so the readings fix the centroid whatever grid the load is solved on, "
        "and the finer grid only adds unknowns for the noise to fill; the support method's "
        "non-negative fit on a sparse support can place the line between taxel centres.",
    ]
    return lines, (float(coarse), float(fine))
