"""Helpers of the reconstruction benchmark: force and centroid of contacts, two-point resolution.

Imported by ``bench_reconstruction.py``; not a topic of its own.
"""

from __future__ import annotations

import time

import numpy as np
from scipy import optimize, special

from taxel.reconstruction import (
    ADMMSolver,
    SupportSolver,
    TikhonovSolver,
    forward_model_preset,
    forward_operator,
)
from taxel.sensor._resolution import peak_dip

DIP = 0.2  # the valley lies at least 20 % below the lower peak (Rayleigh's Airy discs: 26 %)
STEP = 0.05  # [d] separation step of the fine scan
COARSE = 0.2  # [d] separation step of the coarse scan
CONFIRM = 2  # a separation counts once the next two coarse steps are resolved too
REFERENCE = "two-point model fitted, from the truth (reference)"


def centroid(pressure: np.ndarray, spacing: float) -> np.ndarray:
    """(x, y) centroid [m] of a field in the sensor frame."""
    rows, cols = pressure.shape
    y = (np.arange(rows) - (rows - 1) / 2) * spacing
    x = (np.arange(cols) - (cols - 1) / 2) * spacing
    total = pressure.sum()
    return np.array([(pressure.sum(axis=0) * x).sum(), (pressure.sum(axis=1) * y).sum()]) / total


def force_and_centroid(pressure, truth, spec) -> tuple[float, float]:
    """Relative force error and centroid error [taxel pitches] of a map against the truth."""
    force = pressure.sum() / truth.sum() - 1
    shift = centroid(pressure, spec.load_pitch) - centroid(truth, spec.load_pitch)
    return float(force), float(np.hypot(*shift) / spec.taxel_pitch)


def contact_methods(spec) -> dict:
    """The methods compared for force and centroid: (label, solver, solve options)."""
    return {
        "tikhonov order 1, whole map": (TikhonovSolver(spec, order=1), {}),
        "nonneg order 0, whole map": (ADMMSolver(spec, method="nonneg", order=0), {}),
        "support (library)": (SupportSolver(spec), {}),
    }


def contact_rows(
    sensors,
    loads,
    make_load,
    seeds: int,
    level: float = 0.01,
    *,
    first_seed: int = 0,
    only: tuple[str, ...] | None = None,
    contacts: tuple[str, ...] = (),
) -> list[dict]:
    """Force, centroid and relative L2 error of each method (or of those labelled in
    `only`) on each (sensor, load, seed), seeds from `first_seed` on; the force bounds with
    the shape known, and for the loads in `contacts` with the support known (NaN for the
    others: a field over the whole array has no support to be told)."""
    rows = []
    for sensor, oversampling in sensors.items():
        spec = forward_model_preset(sensor, oversampling=oversampling)
        truth_operator = forward_operator(spec, boundary="zero", representation="fast")
        methods = contact_methods(spec)
        if only is not None:
            methods = {label: method for label, method in methods.items() if label in only}
        for seed in range(first_seed, first_seed + seeds):
            for load in loads:
                rng = np.random.default_rng(5000 + 1000 * seed + loads.index(load))
                truth = make_load(load, spec, rng)
                clean = truth_operator.apply(truth)
                frame = clean + rng.normal(0.0, level * spec.full_scale, clean.shape)
                bound = shape_known_std(clean, level * spec.full_scale)
                support_bound = (
                    support_known_std(truth, truth_operator, level * spec.full_scale)
                    if load in contacts
                    else float("nan")
                )
                for label, (solver, options) in methods.items():
                    started = time.perf_counter()
                    result = solver.solve(frame, **options)
                    seconds = time.perf_counter() - started
                    force, shift = force_and_centroid(result.pressure, truth, spec)
                    error = np.linalg.norm(result.pressure - truth) / np.linalg.norm(truth)
                    rows.append(
                        {
                            "sensor": sensor,
                            "load": load,
                            "seed": seed,
                            "method": label,
                            "force": force,
                            "centroid": shift,
                            "error": float(error),
                            "seconds": seconds,
                            "fallback": "instead" in result.message,
                            "bound": bound,
                            "support_bound": support_bound,
                        }
                    )
    return rows


def shape_known_std(clean: np.ndarray, sigma: float) -> float:
    """Relative standard deviation of the total force that the best unbiased estimator
    reaches when it knows the load's exact shape and position and only its scale is
    unknown (Cramer-Rao: readings = s A t + white noise of std sigma, so std(s) =
    sigma / |A t|). Any estimator that must also find the shape does no better on average."""
    return float(sigma / np.linalg.norm(clean))


def support_known_std(truth: np.ndarray, operator, sigma: float) -> float:
    """Relative standard deviation of the total force that the best unbiased estimator
    reaches when it knows which cells the load presses on (truth > 0) but not how it is
    shared between them: the minimum-norm w with A_S^T w = 1 gives the estimate w . b, of
    std sigma |w| (Gauss-Markov). The gap to `shape_known_std` is the price of not knowing
    the shape, which no method that finds the shape from the frame avoids on average."""
    cells = np.flatnonzero(truth.ravel() > 0)
    units = np.zeros((cells.size, truth.size))
    units[np.arange(cells.size), cells] = 1.0
    columns = operator.apply(units.reshape(cells.size, *truth.shape)).reshape(cells.size, -1)
    weights = np.linalg.lstsq(columns, np.ones(cells.size), rcond=None)[0]
    return float(sigma * np.linalg.norm(weights) / truth.sum())


def within_chance(std: float, tolerance: float = 0.02) -> float:
    """Chance that an unbiased Gaussian estimate of relative std `std` lies within
    `tolerance` of the truth: erf(tolerance / (std sqrt 2))."""
    return float(special.erf(tolerance / (std * np.sqrt(2.0))))


def contact_table(rows: list[dict], sensors, loads, *, timed: bool = True) -> list[str]:
    header = (
        "| sensor | load | method | force error: worst (mean) | centroid error [taxels]: "
        "worst (mean) | rel. L2 error (mean) | within 2 % and 0.1 taxel |"
    )
    lines = [header + (" time per frame |" if timed else ""), "|---" * (8 if timed else 7) + "|"]
    for sensor in sensors:
        for load in loads:
            labels = dict.fromkeys(r["method"] for r in rows if r["sensor"] == sensor)
            for label in labels:
                chosen = [
                    r
                    for r in rows
                    if (r["sensor"], r["load"], r["method"]) == (sensor, load, label)
                ]
                force = np.array([r["force"] for r in chosen])
                shift = np.array([r["centroid"] for r in chosen])
                good = sum(abs(f) <= 0.02 and s <= 0.1 for f, s in zip(force, shift, strict=True))
                fallback = sum(r["fallback"] for r in chosen)
                note = f" ({fallback} fell back to nonneg)" if fallback else ""
                lines.append(
                    f"| {sensor} | {load} | {label}{note} | {np.abs(force).max():.2%} "
                    f"({force.mean():+.2%}) | {shift.max():.3f} ({shift.mean():.3f}) | "
                    f"{np.mean([r['error'] for r in chosen]):.3f} | {good} of {len(chosen)} |"
                    + (
                        f" {np.median([r['seconds'] for r in chosen]) * 1e3:.0f} ms |"
                        if timed
                        else ""
                    )
                )
    return lines


def bound_table(rows: list[dict], sensors, contacts) -> list[str]:
    """Frames within 2 % of the force: the support method against the expectation for an
    unbiased estimator told each load's exact shape (`shape_known_std`), or only the cells
    it presses on (`support_known_std`)."""
    lines = [
        "| sensor | load | frames | force std (mean), shape known / support known | "
        "expected within 2 %, shape known / support known | support method: within 2 % | "
        "support method: rms force error |",
        "|---|---|---|---|---|---|---|",
    ]
    for sensor in sensors:
        for load in contacts:
            chosen = [
                r
                for r in rows
                if (r["sensor"], r["load"], r["method"]) == (sensor, load, "support (library)")
            ]
            if not chosen:
                continue
            force = np.array([r["force"] for r in chosen])
            shape = np.array([r["bound"] for r in chosen])
            support = np.array([r["support_bound"] for r in chosen])
            expected = [sum(within_chance(b) for b in bounds) for bounds in (shape, support)]
            lines.append(
                f"| {sensor} | {load} | {len(chosen)} | {shape.mean():.2%} / "
                f"{support.mean():.2%} | {expected[0]:.1f} ({expected[0] / len(chosen):.0%}) / "
                f"{expected[1]:.1f} ({expected[1] / len(chosen):.0%}) | "
                f"{np.sum(np.abs(force) <= 0.02)} ({np.mean(np.abs(force) <= 0.02):.0%}) | "
                f"{np.sqrt(np.mean(force**2)):.2%} |"
            )
    return lines


def contact_targets(
    rows: list[dict], contacts, sensor: str | None = None
) -> tuple[int, int, int, int]:
    """(force ok, centroid ok, both ok, frames) of the library method on contact loads,
    on one sensor or on all."""
    chosen = [
        r
        for r in rows
        if r["method"] == "support (library)"
        and r["load"] in contacts
        and sensor in (None, r["sensor"])
    ]
    force = sum(abs(r["force"]) <= 0.02 for r in chosen)
    shift = sum(r["centroid"] <= 0.1 for r in chosen)
    both = sum(abs(r["force"]) <= 0.02 and r["centroid"] <= 0.1 for r in chosen)
    return force, shift, both, len(chosen)


def bound_expectation(
    rows: list[dict], contacts, sensor: str | None = None, *, bound: str = "bound"
) -> float:
    """Expected number of contact frames within 2 % of the force for an unbiased estimator
    that knows each load's exact shape (`bound` "bound", `shape_known_std`: the most any
    method can hope for on average) or only its support ("support_bound",
    `support_known_std`)."""
    chosen = [
        r
        for r in rows
        if r["method"] == "support (library)"
        and r["load"] in contacts
        and sensor in (None, r["sensor"])
    ]
    return sum(within_chance(r[bound]) for r in chosen)


# -- two-point resolution ------------------------------------------------------------------------
def two_points(truth_spec, separation: float, force: float = 0.5) -> np.ndarray:
    """Two point loads of `force` [N] at +-separation/2 along x about the centre of the
    middle taxel, on the truth grid; a point between its cells is shared bilinearly."""
    k = truth_spec.oversampling
    pitch = truth_spec.load_pitch
    rows, cols = truth_spec.shape
    row = rows // 2 * k + (k - 1) / 2  # the middle taxel's centre, in fine-cell indices
    col = cols // 2 * k + (k - 1) / 2
    field = np.zeros(truth_spec.load_shape)
    for sign in (-1, 1):
        _bilinear(field, pitch, row, col + sign * separation / 2 / pitch, force)
    return field


def _bilinear(field: np.ndarray, pitch: float, row: float, col: float, force: float) -> None:
    """Add a point load of `force` [N] at fractional cell indices (row, col), shared
    bilinearly between the four cells around it, to a pressure field [Pa] in place."""
    rows, cols = field.shape
    row = min(max(row, 0.0), rows - 1.000001)
    col = min(max(col, 0.0), cols - 1.000001)
    top, left = int(np.floor(row)), int(np.floor(col))
    down, right = row - top, col - left
    for fine_row, row_weight in ((top, 1 - down), (top + 1, down)):
        for fine_col, col_weight in ((left, 1 - right), (left + 1, right)):
            field[fine_row, fine_col] += force * row_weight * col_weight / pitch**2


def two_point_model_fit(frame: np.ndarray, truth_spec, operator, separation: float, sigma: float):
    """Reference, not a library method: the maximum-likelihood fit of the exact model.

    The model knows there are two point loads and has the true forward operator; their
    positions and forces (6 parameters) are fitted to the frame by Levenberg-Marquardt,
    started from the truth. It shows what the frame itself says about the two loads:
    where its force split wanders so far that one load falls under half the other's peak,
    the frame does not fix the split, and a method that resolves them more often does so
    by a prior that pulls the two forces together (a ridge spreads force evenly), not
    from the data. Returns the fitted loads as a pressure map on the truth grid.
    """
    k, pitch = truth_spec.oversampling, truth_spec.load_pitch
    rows, cols = truth_spec.shape
    row, col = rows // 2 * k + (k - 1) / 2, cols // 2 * k + (k - 1) / 2
    half = separation / 2 / pitch
    start = np.array([row, col - half, 0.5, row, col + half, 0.5])

    def loads(parameters: np.ndarray) -> np.ndarray:
        field = np.zeros(truth_spec.load_shape)
        for point_row, point_col, force in parameters.reshape(2, 3):
            _bilinear(field, pitch, point_row, point_col, force)
        return field

    def misfit(parameters: np.ndarray) -> np.ndarray:
        return ((operator.apply(loads(parameters)) - frame) / sigma).ravel()

    return loads(optimize.least_squares(misfit, start, method="lm").x)


def dip_of(values: np.ndarray, spec, separation: float, cells_per_taxel: int) -> float:
    """Valley depth between the two loads along the middle taxel row of a map with
    `cells_per_taxel` cells per taxel (the rows of that taxel row and one on each side)."""
    rows, cols = spec.shape
    k = cells_per_taxel
    first = rows // 2 * k
    profile = values[first - 1 : first + k + 1].sum(axis=0)
    x = (np.arange(cols * k) - (cols * k - 1) / 2) * spec.taxel_pitch / k
    middle = (cols // 2 - (cols - 1) / 2) * spec.taxel_pitch
    reach = max(spec.taxel_pitch, 0.5 * spec.depth)
    return peak_dip(profile, x, middle - separation / 2, middle + separation / 2, reach)


def resolution_scan(
    sensor: str,
    solver_oversampling: int,
    truth_oversampling: int,
    seeds: int,
    upper: float,
    only: tuple[str, ...] | None = None,
    readings: bool = True,
    reference: bool = False,
) -> list[tuple[str, str, str]]:
    """Smallest separation [d] resolved (4 of 5 seeds), per method, and the range tried.

    `reference`: also the exact two-point model's maximum-likelihood fit
    (`two_point_model_fit`), on the truth grid.
    """
    spec = forward_model_preset(sensor, oversampling=solver_oversampling)
    truth_spec = forward_model_preset(sensor, oversampling=truth_oversampling)
    truth_operator = forward_operator(truth_spec, boundary="zero", representation="fast")
    sigma = 0.01 * spec.full_scale
    fast = {"representation": "fast", "boundary": "reflect"}
    methods = {
        "readings themselves": None,
        "tikhonov order 0 (default rule)": TikhonovSolver(spec, order=0),
        "nonneg order 0 (discrepancy)": ADMMSolver(spec, method="nonneg", order=0, **fast),
        "support (library)": SupportSolver(spec),
    }
    if only is not None:
        methods = {label: solver for label, solver in methods.items() if label in only}
    if not readings:
        methods.pop("readings themselves", None)
    if reference:
        methods[REFERENCE] = None
    needed = seeds - 1 if seeds > 2 else seeds
    cache: dict[float, np.ndarray] = {}

    def clean(separation_d: float) -> np.ndarray:
        key = round(separation_d, 4)
        if key not in cache:
            field = two_points(truth_spec, separation_d * spec.depth)
            cache[key] = truth_operator.apply(field)
        return cache[key]

    def resolved(label: str, solver, separation_d: float) -> bool:
        hits = 0
        for seed in range(seeds):
            noise = np.random.default_rng(seed).normal(0.0, sigma, spec.shape)
            frame = clean(separation_d) + noise
            if label == REFERENCE:
                fitted = two_point_model_fit(
                    frame, truth_spec, truth_operator, separation_d * spec.depth, sigma
                )
                dip = dip_of(fitted, spec, separation_d * spec.depth, truth_spec.oversampling)
            elif solver is None:
                dip = dip_of(frame, spec, separation_d * spec.depth, 1)
            else:
                pressure = solver.solve(frame).pressure
                dip = dip_of(pressure, spec, separation_d * spec.depth, spec.oversampling)
            hits += dip >= DIP
        return hits >= needed

    results = []
    coarse = np.round(np.arange(0.3, upper + 1e-9, COARSE), 4)
    for label, solver in methods.items():
        flags = [resolved(label, solver, s) for s in coarse]
        found = None
        for index in range(len(coarse)):
            if all(flags[index : index + CONFIRM + 1]) and index + CONFIRM < len(coarse):
                found = index
                break
        if found is None:
            results.append((label, f"not within {upper:.1f} d", "-"))
            continue
        verdict = float(coarse[found])
        if found > 0:  # refine between the last unresolved coarse step and this one
            for s in np.round(np.arange(coarse[found] - STEP, coarse[found - 1], -STEP), 4):
                if not resolved(label, solver, s):
                    break
                verdict = float(s)
        tried = f"{coarse[0]:.2f}-{coarse[-1]:.2f} d in {COARSE:g} d, refined in {STEP:g} d"
        note = " (lowest tried)" if found == 0 else ""
        results.append((label, f"{verdict:.2f}{note}", tried))
    return results


# -- full simulated frames -----------------------------------------------------------------------
def simulated_rows(sensors, forces: dict, seeds: int) -> tuple[list[dict], dict]:
    """Force and centroid from raw simulated frames through the calibration, per method.

    Each sensor is calibrated once with its noise on (`taxel.sensor.calibrate`); a frame is
    ``sensor.press(...)`` with noise, its calibrated readings ``felt_pressure(raw)`` (NaN at
    excluded taxels, which the forward model leaves out), and the truth the solved contact.
    """
    import dataclasses

    from taxel.mechanics import make_indenter
    from taxel.reconstruction import spec_from_sensor
    from taxel.sensor import calibrate, make_sensor

    rows, noise = [], {}
    for name, oversampling in sensors.items():
        sensor = dataclasses.replace(make_sensor(name), oversampling=oversampling)
        calibration = calibrate(sensor, rng=11)
        spec = spec_from_sensor(sensor, oversampling=oversampling, dead_taxels=~calibration.valid)
        methods = {
            "tikhonov order 1, whole map": TikhonovSolver(spec, order=1),
            "support (library)": SupportSolver(spec),
        }
        estimates, worst = [], 0.0
        for seed in range(seeds):
            for load, force in forces.items():
                rng = np.random.default_rng(7000 + 100 * seed + list(forces).index(load))
                position = tuple(rng.uniform(-0.5, 0.5, 2) * spec.taxel_pitch)
                parameters = {"length": 20e-3} if load == "edge" else {}
                frame = sensor.press(
                    make_indenter(load, **parameters),
                    normal_force=force,
                    position=position,
                    angle=float(rng.uniform(0, np.pi)),
                    rng=rng,
                )
                readings = calibration.felt_pressure(frame.raw)
                truth = frame.contact.pressure
                felt = -frame.fields.stress  # what the taxels feel: the model's readings
                misfit = np.nanmax(np.abs(readings - felt)) / felt.max()
                worst = max(worst, float(misfit))
                for label, solver in methods.items():
                    result = solver.solve(readings)
                    if label.startswith("tikhonov"):
                        estimates.append(float(result.noise_level) / spec.full_scale)
                    force_error, shift = force_and_centroid(result.pressure, truth, spec)
                    error = np.linalg.norm(result.pressure - truth) / np.linalg.norm(truth)
                    rows.append(
                        {
                            "sensor": name,
                            "load": load,
                            "seed": seed,
                            "method": label,
                            "force": force_error,
                            "centroid": shift,
                            "error": float(error),
                            "seconds": 0.0,
                            "fallback": "instead" in result.message,
                        }
                    )
        noise[name] = (float(np.median(estimates)), int((~calibration.valid).sum()), worst)
    return rows, noise
