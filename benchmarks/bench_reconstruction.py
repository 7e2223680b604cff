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
from scipy import ndimage

from taxel.mechanics import make_indenter, solve_contact
from taxel.reconstruction import (
    ADMMSolver,
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


def window(pressure: np.ndarray, spec) -> np.ndarray:
    """Cells of the contact: >= 10 % of the peak, grown by two cover depths."""
    grow = max(1, int(np.ceil(2 * spec.depth / spec.load_pitch)))
    core = pressure >= 0.1 * pressure.max()
    return ndimage.binary_dilation(core, iterations=grow)


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
    inside = np.where(window(pressure, spec), pressure, 0.0)
    force_window = inside.sum() / truth.sum() - 1
    shift_window = centroid(inside, spec.load_pitch) - centroid(truth, spec.load_pitch)
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
        "force_window": float(force_window),
        "centroid_window": float(np.hypot(*shift_window) / spec.taxel_pitch),
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
        "| sensor | load | noise | rel. L2 error | best possible | force error (whole map) "
        "| force error (window) | centroid error [taxels] (whole map) | centroid error "
        "[taxels] (window) |",
        "|---|---|---|---|---|---|---|---|---|",
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
                keys = ("error", "best", "force", "force_window", "centroid", "centroid_window")
                worst = {k: np.max([abs(r[k]) for r in chosen]) for k in keys}
                lines.append(
                    f"| {sensor} | {load} | {level:.1%} | {worst['error']:.3f} | "
                    f"{worst['best']:.3f} | {worst['force']:.2%} | {worst['force_window']:.2%} | "
                    f"{worst['centroid']:.3f} | {worst['centroid_window']:.3f} |"
                )
    return lines


def _targets(rows: list[dict]) -> list[str]:
    """The issue's accuracy targets against this run (Tikhonov order 1, GCV at 1 % noise)."""
    overall = np.mean([r["ratio"] <= 1.25 for r in rows])
    best_rule = {
        rule: np.mean([r["ratio"] <= 1.25 for r in rows if r["rule"] == rule]) for rule in RULES
    }
    at_one = [r for r in rows if r["noise"] == 0.01 and r["rule"] == "gcv" and r["order"] == 1]
    force = [abs(r["force_window"]) <= 0.02 for r in at_one]
    whole = [abs(r["force"]) <= 0.02 for r in at_one]
    shift = [r["centroid_window"] <= 0.1 for r in at_one]
    return [
        "### Targets",
        "",
        "| target | result |",
        "|---|---|",
        f"| automatic lambda within 1.25x of the best, >= 90 % of cases | {overall:.0%} of "
        f"{len(rows)} (gcv {best_rule['gcv']:.0%}, lcurve {best_rule['lcurve']:.0%}, "
        f"discrepancy {best_rule['discrepancy']:.0%}) |",
        f"| total force within 2 % at 1 % noise (order 1, GCV) | window: {sum(force)} of "
        f"{len(force)} frames; whole map: {sum(whole)} of {len(whole)} |",
        f"| centroid within 0.1 taxel at 1 % noise (order 1, GCV, window) | {sum(shift)} of "
        f"{len(shift)} frames |",
        "| two points resolved at about 0.85 d at 1 % noise | see the two-point table |",
    ]


def _resolved(pressure: np.ndarray, row: int, left: int, right: int) -> bool:
    """Two maxima near the two points with a dip below 80 % of the lower one between them."""
    line = pressure[row]
    peaks = [line[max(c - 1, 0) : c + 2].max() for c in (left, right)]
    if right - left < 2:
        return False
    dip = line[left + 1 : right].min()
    return bool(min(peaks) > 0 and dip < 0.8 * min(peaks))


def resolution(quick: bool) -> list[str]:
    """Smallest separation of two 0.5 N points resolved at 1 % noise, in units of d."""
    lines = [
        "| sensor | load pitch / d | method | smallest separation resolved (4 of 5 seeds) "
        "[d] | separations tried [d] |",
        "|---|---|---|---|---|",
    ]
    seeds = 3 if quick else 5
    for sensor in SENSORS:
        spec = _spec(sensor)
        operator = forward_operator(spec, boundary="zero", representation="fast")
        sigma = 0.01 * spec.full_scale
        rows, cols = spec.load_shape
        cells = [c for c in range(1, 12) if c * spec.load_pitch <= 2.6 * spec.depth]
        for method, order in (("tikhonov", 0), ("tikhonov", 1), ("nonneg", 0)):
            if method == "nonneg":
                solver = ADMMSolver(spec, method="nonneg", order=order)
            else:
                solver = TikhonovSolver(spec, order=order)
            found = None
            for steps in cells:
                left = cols // 2 - steps // 2
                right = left + steps
                truth = np.zeros(spec.load_shape)
                truth[rows // 2, [left, right]] = 0.5 / spec.load_pitch**2
                clean = operator.apply(truth)
                hits = 0
                for seed in range(seeds):
                    rng = np.random.default_rng(seed)
                    frame = clean + rng.normal(0, sigma, clean.shape)
                    result = solver.solve(frame, regularization="gcv")
                    hits += _resolved(result.pressure, rows // 2, left, right)
                if hits >= seeds - 1:
                    found = steps * spec.load_pitch / spec.depth
                    break
            tried = ", ".join(f"{c * spec.load_pitch / spec.depth:.2f}" for c in cells)
            label = f"{method} order {order}, GCV"
            verdict = f"{found:.2f}" if found is not None else "not within 2.6 d"
            lines.append(
                f"| {sensor} | {spec.load_pitch / spec.depth:.2f} | {label} | {verdict} | "
                f"{tried} |"
            )
    return lines


def boundary_cost(quick: bool) -> list[str]:
    """Error of the reflective model for a sphere near the edge (readings: the true model)."""
    lines = [
        "| sensor | sphere centre from the edge | model | rel. L2 error | force error "
        "(window) |",
        "|---|---|---|---|---|",
    ]
    distances = (0.5, 1.0, 2.0, 4.0) if not quick else (0.5, 2.0)
    for sensor in SENSORS:
        spec = _spec(sensor)
        truth_operator = forward_operator(spec, boundary="zero", representation="fast")
        models = {"reflect": TikhonovSolver(spec, order=1, boundary="reflect")}
        if spec.load_shape[0] * spec.load_shape[1] <= 4096:
            models["zero (exact)"] = TikhonovSolver(spec, order=1, boundary="zero")
        half = spec.load_shape[1] * spec.load_pitch / 2
        for distance in (*distances, None):
            x = 0.0 if distance is None else -half + distance * spec.depth
            heights = make_indenter("sphere").on_grid(
                spec.load_shape, spec.load_pitch, position=(x, 0.0)
            )
            truth = solve_contact(
                heights, spec.load_pitch, spec.material, thickness=spec.thickness, normal_force=2.0
            ).pressure
            rng = np.random.default_rng(7)
            frame = truth_operator.apply(truth) + rng.normal(0, 0.01 * spec.full_scale, spec.shape)
            where = "centre" if distance is None else f"{distance:g} d"
            for name, solver in models.items():
                result = solver.solve(frame, regularization="gcv")
                inside = np.where(window(result.pressure, spec), result.pressure, 0.0)
                lines.append(
                    f"| {sensor} | {where} | {name} | "
                    f"{relative_error(result.pressure, truth):.3f} | "
                    f"{inside.sum() / truth.sum() - 1:+.2%} |"
                )
    return lines


def _median_time(call, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        call()
        times.append(time.perf_counter() - started)
    return float(np.median(times))


def speed(quick: bool) -> list[str]:
    lines = [
        "| case | median time | target |",
        "|---|---|---|",
    ]
    repeats = 20 if quick else 200
    spec = _spec("vhdta128", 1)
    rng = np.random.default_rng(0)
    frame = rng.normal(0, 4e3, spec.shape)
    for order in (0, 1):
        solver = TikhonovSolver(spec, order=order)
        solver.solve(frame)
        fixed = _median_time(lambda s=solver: s.solve(frame, regularization=0.05), repeats)
        gcv = _median_time(lambda s=solver: s.solve(frame, regularization="gcv"), repeats)
        lines.append(
            f"| vhdta128 128 x 128, Tikhonov order {order}, fixed lambda | "
            f"{fixed * 1e3:.3f} ms | 0.5 ms |"
        )
        lines.append(
            f"| vhdta128 128 x 128, Tikhonov order {order}, GCV | " f"{gcv * 1e3:.3f} ms | 1 ms |"
        )
    for k in (1, 2):
        spec = _spec("resistive16", k)
        solver = TikhonovSolver(spec, order=1)
        frames = rng.normal(0, 2e3, (1000, *spec.shape))
        solver.solve(frames[:2])
        batch_repeats = 3 if quick else 15
        fixed = _median_time(
            lambda s=solver, f=frames: s.solve(f, regularization=0.05), batch_repeats
        )
        gcv = _median_time(
            lambda s=solver, f=frames: s.solve(f, regularization="gcv"), batch_repeats
        )
        lines.append(
            f"| resistive16 16 x 16 -> {spec.load_shape[0]} x {spec.load_shape[1]}, "
            f"batch of 1000, fixed lambda | {fixed * 1e3:.1f} us per frame | 20 us |"
        )
        lines.append(
            f"| resistive16 16 x 16 -> {spec.load_shape[0]} x {spec.load_shape[1]}, "
            f"batch of 1000, GCV per frame | {gcv * 1e3:.1f} us per frame | 20 us |"
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
        *_targets(rows),
        "",
        "### Errors, Tikhonov order 1 with GCV (worst over seeds)",
        "",
        "Whole map: force and centroid of the entire reconstructed map, which integrates the "
        "noise of every taxel. Window: of the cells >= 10 % of the peak, grown by two depths d "
        "(the contact and its blur), which leaves the noise of the unloaded taxels out.",
        "",
        *_per_load(rows, "gcv", 1),
        "",
        "### Two point loads at 1 % noise",
        "",
        "Two 0.5 N loads on single load cells along a row; resolved when the reconstructed "
        "row has a dip below 80 % of the lower peak between them (a Rayleigh-like criterion).",
        "",
        *resolution(quick),
        "",
        "### What the reflective boundary costs near an edge",
        "",
        "A 2 N sphere whose centre is a given distance from the left edge; readings from the "
        "true (zero-boundary) model, 1 % noise; Tikhonov order 1, GCV.",
        "",
        *boundary_cost(quick),
        "",
        "### Speed (one core)",
        "",
        *speed(quick),
        "",
        f"_Accuracy sweep: {seconds:.0f} s; load average "
        f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores._",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    print(run(quick=True))
