"""Pressure reconstruction: accuracy, parameter choice, resolution, boundary cost, speed (issue 4).

Truth fields are generated on the solver's load grid: contact pressures of a sphere, a
finite edge and a flat punch by `taxel.mechanics.solve_contact` (cover bonded to its rigid
backing), two point loads and random smooth fields analytically. Readings are the exact
(zero-boundary) forward model applied to the truth plus Gaussian noise of 0.5 %, 1 % and 5 %
of full scale. The truth lives on the same grid as the unknowns (no model error besides the
boundary model of the fast solver); simulated sensor frames can replace this later.
"""

from __future__ import annotations

import os
import time

import numpy as np

from taxel.mechanics import make_indenter, solve_contact
from taxel.reconstruction import (
    TikhonovSolver,
    forward_model_preset,
    forward_operator,
)

# the two configurations of the issue, as plain parameters (oversampling: load cells per taxel)
SENSORS = {"vhdta128": 1, "resistive16": 2}
NOISE = (0.005, 0.01, 0.05)  # of full scale
LOADS = ("sphere", "edge", "two points", "punch", "random smooth")
FORCES = {"sphere": 2.0, "edge": 4.0, "punch": 5.0}  # [N]
RULES = ("gcv", "lcurve", "discrepancy")


def _spec(name: str, oversampling: int | None = None):
    return forward_model_preset(name, oversampling=oversampling or SENSORS[name])


def centroid(pressure: np.ndarray, spacing: float) -> np.ndarray:
    """(x, y) centroid [m] of a field in the sensor frame."""
    rows, cols = pressure.shape
    y = (np.arange(rows) - (rows - 1) / 2) * spacing
    x = (np.arange(cols) - (cols - 1) / 2) * spacing
    total = pressure.sum()
    return np.array([(pressure.sum(axis=0) * x).sum(), (pressure.sum(axis=1) * y).sum()]) / total


def make_load(name: str, spec, rng: np.random.Generator) -> np.ndarray:
    """A truth pressure field [Pa] on the load grid of `spec`, placed off the grid nodes."""
    shape, pitch = spec.load_shape, spec.load_pitch
    offset = (rng.uniform(-0.5, 0.5) * spec.taxel_pitch, rng.uniform(-0.5, 0.5) * spec.taxel_pitch)
    if name in FORCES:
        parameters = {"length": 20e-3} if name == "edge" else {}
        indenter = make_indenter(name, **parameters)
        heights = indenter.on_grid(shape, pitch, position=offset, angle=rng.uniform(0, np.pi))
        return solve_contact(
            heights, pitch, spec.material, thickness=spec.thickness, normal_force=FORCES[name]
        ).pressure
    field = np.zeros(shape)
    if name == "two points":
        separation = max(2.0 * spec.depth, 2 * spec.load_pitch)
        steps = int(round(separation / spec.load_pitch / 2))
        centre = (shape[0] // 2, shape[1] // 2)
        field[centre[0], centre[1] - steps] = field[centre[0], centre[1] + steps] = 1.0
        return field * 0.5 / pitch**2  # 0.5 N each
    # a random smooth field: six Gaussian bumps 1-3 depths wide in the middle 60 %
    y, x = np.mgrid[: shape[0], : shape[1]] * pitch
    for _ in range(6):
        width = rng.uniform(1.0, 3.0) * spec.depth
        cy, cx = rng.uniform(0.2, 0.8, 2) * np.array(shape) * pitch
        field += rng.uniform(0.3, 1.0) * np.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * width**2))
    return field * 0.4 * spec.full_scale / field.max()


def relative_error(estimate: np.ndarray, truth: np.ndarray) -> float:
    return float(np.linalg.norm(estimate - truth) / np.linalg.norm(truth))


def _scan(solver: TikhonovSolver, frame: np.ndarray, truth: np.ndarray) -> tuple[float, float]:
    """Best relative error over the solver's lambda grid (knowing the truth), and its lambda."""
    grid = solver.scan.grid
    batch = np.broadcast_to(frame, (grid.size, *frame.shape))
    beta, free, _ = solver.spectrum.analyze(np.ascontiguousarray(batch))
    pressure = solver.spectrum.synthesize(solver.filter_factors(grid) * beta, free)
    errors = np.linalg.norm((pressure - truth).reshape(grid.size, -1), axis=1)
    index = int(np.argmin(errors))
    return float(errors[index] / np.linalg.norm(truth)), float(grid[index])


def accuracy(quick: bool) -> tuple[list[dict], float]:
    """Every (sensor, load, noise, order, rule) case: error at the rule's lambda and the best."""
    rows: list[dict] = []
    started = time.perf_counter()
    seeds = 1 if quick else 2
    for sensor in SENSORS:
        spec = _spec(sensor)
        truth_operator = forward_operator(spec, boundary="zero", representation="auto")
        if truth_operator.representation == "dense" or spec.load_shape[0] > 64:
            truth_operator = forward_operator(spec, boundary="zero", representation="fast")
        solvers = {order: TikhonovSolver(spec, order=order) for order in (0, 1, 2)}
        for seed in range(seeds):
            for load in LOADS:
                rng = np.random.default_rng(1000 * seed + LOADS.index(load))
                truth = make_load(load, spec, rng)
                clean = truth_operator.apply(truth)
                for level in NOISE[:2] if quick else NOISE:
                    sigma = level * spec.full_scale
                    frame = clean + rng.normal(0.0, sigma, clean.shape)
                    for order, solver in solvers.items():
                        best, best_lam = _scan(solver, frame, truth)
                        for rule in RULES:
                            result = solver.solve(frame, regularization=rule, noise_level=sigma)
                            rows.append(
                                _metrics(
                                    sensor,
                                    load,
                                    level,
                                    order,
                                    rule,
                                    seed,
                                    spec,
                                    truth,
                                    result,
                                    best,
                                    best_lam,
                                )
                            )
    return rows, time.perf_counter() - started


def _metrics(sensor, load, level, order, rule, seed, spec, truth, result, best, best_lam):
    pressure = result.pressure
    error = relative_error(pressure, truth)
    force = pressure.sum() / truth.sum() - 1
    shift = centroid(pressure, spec.load_pitch) - centroid(truth, spec.load_pitch)
    return {
        "sensor": sensor,
        "load": load,
        "noise": level,
        "order": order,
        "rule": rule,
        "seed": seed,
        "error": error,
        "best": best,
        "ratio": error / best,
        "lambda": float(result.regularization),
        "best_lambda": best_lam,
        "force": float(force),
        "centroid": float(np.hypot(*shift) / spec.taxel_pitch),
    }


def _table(rows: list[dict]) -> list[str]:
    lines = [
        "| sensor | rule | order | cases | within 1.25x of best | median ratio | worst ratio |",
        "|---|---|---|---|---|---|---|",
    ]
    for sensor in SENSORS:
        for rule in RULES:
            for order in (0, 1, 2):
                chosen = [
                    r
                    for r in rows
                    if (r["sensor"], r["rule"], r["order"]) == (sensor, rule, order)
                ]
                ratios = np.array([r["ratio"] for r in chosen])
                lines.append(
                    f"| {sensor} | {rule} | {order} | {ratios.size} | "
                    f"{np.mean(ratios <= 1.25):.0%} | {np.median(ratios):.3f} | "
                    f"{ratios.max():.2f} |"
                )
    return lines


def _per_load(rows: list[dict], rule: str, order: int) -> list[str]:
    lines = [
        "| sensor | load | noise | rel. L2 error | best possible | force error | centroid error "
        "[taxels] |",
        "|---|---|---|---|---|---|---|",
    ]
    for sensor in SENSORS:
        for load in LOADS:
            for level in NOISE:
                chosen = [
                    r
                    for r in rows
                    if (r["sensor"], r["load"], r["noise"], r["rule"], r["order"])
                    == (sensor, load, level, rule, order)
                ]
                if not chosen:
                    continue
                mean = {
                    k: np.mean([abs(r[k]) for r in chosen])
                    for k in ("error", "best", "force", "centroid")
                }
                lines.append(
                    f"| {sensor} | {load} | {level:.1%} | {mean['error']:.3f} | "
                    f"{mean['best']:.3f} | {mean['force']:.2%} | {mean['centroid']:.3f} |"
                )
    return lines


def run(quick: bool = False) -> str:
    rows, seconds = accuracy(quick)
    lines = [
        "## Pressure reconstruction (`taxel.reconstruction`)",
        "",
        "Sensors (plain parameters of the issue): vhdta128 = 128 x 128 taxels at 0.2578 mm, "
        "1 mm cover (E = 0.5 MPa, nu = 0.49) on glass, stress at d = 1 mm, full scale "
        "413.7 kPa, solved on the taxel grid (k = 1, DCT, reflective boundaries); resistive16 = "
        "16 x 16 taxels at 2 mm, 1.5 mm cover (E = 1 MPa, nu = 0.49), stress at d = 1.5 mm, "
        "full scale 200 kPa, solved on a 32 x 32 load grid (k = 2, dense, exact zero boundary). "
        "Noise: Gaussian, % of full scale. Readings: exact linear-convolution model of the "
        "truth. Loads: sphere R = 6.25 mm (2 N), edge R = 3.2 mm x 20 mm (4 N), flat punch "
        "a = 3 mm (5 N), two 0.5 N points 2 d apart, random smooth fields (peak 40 % of full "
        "scale); random sub-taxel positions and angles.",
        "",
        f"### Automatic lambda against the best lambda (scanned knowing the truth), "
        f"{len(rows) // 9} frames",
        "",
        *_table(rows),
        "",
        f"All rules and orders together: {np.mean([r['ratio'] <= 1.25 for r in rows]):.0%} "
        "of cases within 1.25x.",
        "",
        "### Errors, Tikhonov order 1 with GCV (mean over seeds)",
        "",
        *_per_load(rows, "gcv", 1),
        "",
        f"_Accuracy sweep: {seconds:.0f} s; load average "
        f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores._",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    print(run(quick=True))
