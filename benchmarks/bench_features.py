"""Speed and accuracy of taxel.features.extract.

Speed: the full feature set on 128x128 and 16x16 frames of each synthetic indenter of
``tests/features/synthetic.py``. Accuracy: >= 1000 labelled frames per sensor from the sensor
simulator (``features_scenes.py``: every indenter, random position, rotation, size, force,
noise and sensor pose), scored for contact type (per-class confusion), hole and slot F1,
centroid, line angle, arc radius and 3-D position errors. Also: frames at rest
(``features_rest.py``), a camera that differs from its model (``features_camera.py``) and the
seed's texture experiment.

Run alone: ``python benchmarks/bench_features.py [--quick] [--seed N]``; ``--details``
also prints every misclassified frame (for development).
"""

from __future__ import annotations

import collections
import math
import statistics
import sys
import time
from dataclasses import replace
from pathlib import Path

import cv2
import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "tests" / "features"))
import synthetic  # noqa: E402

import features_camera  # noqa: E402
import features_redraw  # noqa: E402
import features_rest  # noqa: E402
import features_scenes  # noqa: E402
import features_speed  # noqa: E402
from taxel.features import CONTACT_TYPES, contact_regions, extract, prepare  # noqa: E402
from taxel.features._pressure_centre import _clipped, _windows  # noqa: E402
from taxel.features._window import catchment_reach  # noqa: E402

PATTERNS = features_speed.PATTERNS
SEED = 2026  # the benchmark's fixed seed
RECHECK_SEED = 2027  # a second draw, to show the rules were not fitted to the first
SENSORS = ("vhdta128", "16x16")
CLOCK = time.thread_time  # CPU time of this thread: what one core spends, whatever the load


def _calibration() -> float:
    """Time of one small NumPy operation (a 16 x 16 float32 add) on this machine [s]."""
    array = np.zeros((16, 16), np.float32)
    best = math.inf
    for _ in range(20):
        start = CLOCK()
        for _ in range(1000):
            array + 1
        best = min(best, (CLOCK() - start) / 1000)
    return best


def _call_budget(unit: float) -> str:
    """Function calls of one `extract` on the 16 x 16 frames, against the time budget."""
    python, compiled = [], []
    events = collections.Counter()

    def count(frame, event, argument):
        events[event] += 1

    for name in PATTERNS:
        image = synthetic.render(getattr(synthetic, name), (16, 16), noise=0.01, rng=0)
        extract(image, 1.5e-3)  # warm caches
        events.clear()
        sys.setprofile(count)
        try:
            extract(image, 1.5e-3)
        finally:
            sys.setprofile(None)
        python.append(events["call"])
        compiled.append(events["c_call"])
    return (
        f"On 16 x 16 one call makes a median of {statistics.median(python):.0f} Python "
        f"function calls and {statistics.median(compiled):.0f} calls of compiled functions "
        "the profiler sees (OpenCV's, NumPy's other than ufuncs, builtins; not the ufuncs "
        "and array operators, which it does not see), over the seven patterns. The 100 us "
        f"target is the time of {100e-6 / unit:.0f} of this machine's 16 x 16 additions: "
        "the budget of a compiled kernel, not of a Python pipeline of this many steps, "
        "where the arithmetic on 256 taxels is a few microseconds and the calls are the "
        "cost.\n"
    )


_STAGES = (
    ("prepare", "validate, remove defects, noise, smooth, segment, outlines"),
    ("contact_regions", "centroid, area, axes of the regions"),
    ("texture_core", "high points, spectrum, roughness"),
    ("gaps_core", "holes and slots (basins at three levels)"),
    ("fit_line_and_circle", "line and circle through the outline"),
    ("shape_core", "contact type"),
    ("plane_core", "planarity"),
    ("diameter_test", "the seed's hole test"),
)


def _profile(repeats: int) -> str:
    """Where the time goes: CPU time of each stage of `extract`, median over the patterns."""
    import taxel.features._extract as stages
    import taxel.features._textured as judged  # `extract` finds the gaps through it

    homes = {name: judged if name == "gaps_core" else stages for name, _ in _STAGES}
    spent: dict[str, list[float]] = {name: [] for name, _ in _STAGES}
    originals = {name: getattr(homes[name], name) for name, _ in _STAGES}
    nested: list[float] = []  # time of the stages called inside the running ones

    def timed(name):
        # a stage's own time: the outline fit, made when the contact type first needs it,
        # runs inside shape_core and counts once, as fit_line_and_circle
        def call(*args, **kwargs):
            start = CLOCK()
            nested.append(0.0)
            result = originals[name](*args, **kwargs)
            elapsed = CLOCK() - start
            inner = nested.pop()
            if nested:
                nested[-1] += elapsed
            spent[name][-1] = min(spent[name][-1], elapsed - inner)
            return result

        return call

    rows = []
    try:
        for name in originals:
            setattr(homes[name], name, timed(name))
        for label, shape, pitch in (
            ("128x128", (128, 128), 3.3e-2 / 128),
            ("16x16", (16, 16), 1.5e-3),
        ):
            per_pattern: dict[str, list[float]] = {name: [] for name in originals}
            totals = []
            for pattern in PATTERNS:
                generator = getattr(synthetic, pattern)
                if shape == (128, 128):
                    image = synthetic.render(generator, ftir=True, noise=0.03, scratches=3, rng=0)
                else:
                    image = synthetic.render(generator, shape, noise=0.01, rng=0)
                for name in originals:
                    spent[name].append(math.inf)  # stays inf for a stage that is skipped
                best = math.inf
                for _ in range(repeats):
                    start = CLOCK()
                    extract(image, pitch)
                    best = min(best, CLOCK() - start)
                totals.append(best)
                for name in originals:
                    value = spent[name][-1]
                    per_pattern[name].append(0.0 if not math.isfinite(value) else value)
            total = statistics.median(totals)
            parts = {name: statistics.median(values) for name, values in per_pattern.items()}
            rows.append((label, total, parts))
    finally:
        for name, function in originals.items():
            setattr(homes[name], name, function)
    lines = [
        "Where the time goes: the least CPU time of each stage over the calls, median over "
        "the seven patterns [us] (`rest`: result objects, validation of the options, glue).\n",
        "| stage | what | " + " | ".join(label for label, _, _ in rows) + " |",
        "|---|---|" + "---|" * len(rows),
    ]
    for name, what in _STAGES:
        cells = " | ".join(f"{parts[name] * 1e6:.0f}" for _, _, parts in rows)
        lines.append(f"| {name} | {what} | {cells} |")
    rest = " | ".join(f"{(total - sum(parts.values())) * 1e6:.0f}" for _, total, parts in rows)
    lines.append(f"| rest | | {rest} |")
    totals_cells = " | ".join(f"**{total * 1e6:.0f}**" for _, total, _ in rows)
    lines.append(f"| **total** (least time per call) | | {totals_cells} |")
    return "\n".join(lines)


def _speed_simulated(frames: dict[str, list], repeats: int) -> str:
    """Median time per frame over the simulated frames (each timed `repeats` times)."""
    cells = []
    for name, labelled in frames.items():
        sensor = features_scenes.benchmark_sensor(name)
        times = []
        for frame in labelled[:: max(len(labelled) // 140, 1)]:
            extract(frame.raw, sensor)
            runs = []
            for _ in range(repeats):
                start = CLOCK()
                extract(frame.raw, sensor)
                runs.append(CLOCK() - start)
            times.append(statistics.median(runs))
        cells.append(
            f"{name}: median {statistics.median(times) * 1e6:.0f} us, "
            f"95th percentile {np.percentile(times, 95) * 1e6:.0f} us"
        )
    return (
        "Per simulated frame, given the sensor (so with defect removal on vhdta128), "
        "median over every 7th frame of the accuracy set: " + "; ".join(cells) + "."
    )


def _image_centroid(frame, sensor) -> tuple[float, float] | None:
    """A reference, not a feature: the contact's centroid with the image weighed.

    What the features give a frame they cannot read back to pressure: the centroid
    weighted by the image (unsmoothed, above its baseline) over the contact mask, after
    the opening that removes narrow defects. (x, y) [m], or None when there is no read-back
    to compare with (a sensor whose frames the features do not read back).
    """
    prepared = prepare(frame.raw, sensor)
    if prepared.read_back is None or not prepared.present:
        return None
    return contact_regions(replace(prepared, read_back=None)).centroid_m


def evaluate(frames: list, sensor, **options) -> list[dict]:
    """Run the features on each labelled frame: one row of truth and estimate per frame.

    `options` go to `extract` (e.g. a `reference` frame).
    """
    rows = []
    pitch = math.sqrt(sensor.taxel_pitch[0] * sensor.taxel_pitch[1])
    for frame in frames:
        features = extract(frame.raw, sensor, pose=frame.pose, **options)
        shape = features.shape
        row = {
            "frame": frame,
            "indenter": frame.indenter,
            "truth": frame.contact_type,
            "type": features.contact_type,
            "rule": shape.rule,
            "hole": (frame.hole, features.holes.present),
            "slot": (frame.slot, features.slots.present),
            "centroid": None,
            "image_centroid": None,
            "position": None,
            "angle": None,
            "radius": None,
        }
        row["felt"] = float(np.linalg.norm(np.subtract(frame.felt_centroid_m, frame.centroid_m)))
        row["felt"] /= pitch
        if features.contact.present and features.pose is not None:
            estimate = np.array(features.contact.centroid_m)
            row["centroid"] = float(np.linalg.norm(estimate - frame.centroid_m)) / pitch
            base = np.array(features.pose.position_base_m)
            row["position"] = float(np.linalg.norm(base - frame.position_base_m))
        centre = _image_centroid(frame, sensor)
        if centre is not None:
            row["image_centroid"] = float(np.linalg.norm(np.subtract(centre, frame.centroid_m)))
            row["image_centroid"] /= pitch
        if frame.line_angle is not None and shape.line is not None:
            error = (shape.line.angle_rad - frame.line_angle) % math.pi
            row["angle"] = math.degrees(min(error, math.pi - error))
        if frame.arc_radius is not None and shape.circle is not None:
            radius = shape.circle.radius_m
            row["radius"] = abs(radius / frame.arc_radius - 1.0) if math.isfinite(radius) else 1.0
        rows.append(row)
    return rows


def _f1_score(pairs: list[tuple[bool, bool]]) -> tuple[float, str]:
    hits = sum(t and p for t, p in pairs)
    false_alarms = sum(p and not t for t, p in pairs)
    misses = sum(t and not p for t, p in pairs)
    denominator = 2 * hits + false_alarms + misses
    f1 = 2 * hits / denominator if denominator else 1.0
    return f1, f"{f1:.4f} ({hits} found, {false_alarms} false, {misses} missed)"


def _f1_row(name: str, pairs: list[tuple[bool, bool]], target: float, judge: bool) -> str:
    f1, text = _f1_score(pairs)
    verdict = ("met" if f1 >= target else "**not met**") if judge else "-"
    return f"| {name} | {text} | >= {target:g} | {verdict} |"


def _stats_row(
    name: str, values: list, unit: str, target: float, judge: bool, scale: float = 1.0
) -> str:
    """A row: median / 95th percentile / max, the target, and which of the three meet it."""
    array = np.array([v for v in values if v is not None], dtype=float) * scale
    if array.size == 0:
        return f"| {name} | - | <= {target:g} {unit} | - |"
    stats = {
        "median": np.median(array),
        "p95": np.percentile(array, 95),
        "max": array.max(),
    }
    text = " / ".join(f"{value:.3g}" for value in stats.values())
    verdict = ", ".join(
        f"{label} {'met' if value <= target else '**not met**'}" for label, value in stats.items()
    )
    if not judge:
        verdict = "-"
    return f"| {name} | {text} {unit} (n = {array.size}) | <= {target:g} {unit} | {verdict} |"


def _confusion(rows: list[dict]) -> list[str]:
    found = list(CONTACT_TYPES)
    lines = [
        "| true \\ found | " + " | ".join(found) + " | recall |",
        "|---|" + "---|" * (len(found) + 1),
    ]
    for kind in CONTACT_TYPES[1:]:
        subset = [r for r in rows if r["truth"] == kind]
        if not subset:
            continue
        counts = [sum(r["type"] == f for r in subset) for f in found]
        cells = [
            f"**{c}**" if f == kind else (str(c) if c else ".")
            for f, c in zip(found, counts, strict=True)
        ]
        recall = counts[found.index(kind)] / len(subset)
        lines.append(f"| {kind} ({len(subset)}) | " + " | ".join(cells) + f" | {recall:.1%} |")
    return lines


def _per_indenter(rows: list[dict]) -> list[str]:
    lines = [
        "| indenter | frames | type correct | centroid error median / p95 / max [taxels] "
        "| centroid error over 0.5 taxel | the floor over 0.5 taxel (of those, both) |",
        "|---|---|---|---|---|---|",
    ]
    for name in dict.fromkeys(r["indenter"] for r in rows):
        subset = [r for r in rows if r["indenter"] == name]
        correct = sum(r["type"] == r["truth"] for r in subset)
        errors = np.array([r["centroid"] for r in subset if r["centroid"] is not None])
        centroid, over = "-", "-"
        if errors.size:
            median, p95 = np.percentile(errors, [50, 95])
            centroid = f"{median:.2f} / {p95:.2f} / {errors.max():.2f}"
            over = f"{np.count_nonzero(errors > 0.5)} of {errors.size}"
        floor = [r["felt"] > 0.5 for r in subset]
        both = sum(r["felt"] > 0.5 and (r["centroid"] or 0.0) > 0.5 for r in subset)
        lines.append(
            f"| {name} | {len(subset)} | {correct} | {centroid} | {over} "
            f"| {sum(floor)} of {len(subset)} ({both}) |"
        )
    return lines


def score(rows: list[dict], name: str) -> list[str]:
    """Markdown tables of one sensor's results."""
    accuracy = np.mean([r["type"] == r["truth"] for r in rows])
    judge = name == "vhdta128"  # the targets; the 16 x 16 numbers are for reference
    target = ""
    if judge:
        target = f" (target >= 97 %: {'met' if accuracy >= 0.97 else '**not met**'})"
    reference = [r["image_centroid"] for r in rows]
    reference_row = []
    if any(value is not None for value in reference):
        reference_row.append(
            _stats_row(
                "centroid error, the image weighed instead of read back to pressure "
                "(reference, see below)",
                reference,
                "taxel",
                0.5,
                False,
            )
        )
    lines = [
        f"\n### {name}: {len(rows)} frames\n",
        f"Contact type accuracy **{accuracy:.1%}**{target}.\n",
        *_confusion(rows),
        "",
        "| measure | median / 95th percentile / max | target (vhdta128) | verdict |",
        "|---|---|---|---|",
        _f1_row("hole detection F1", [r["hole"] for r in rows], 0.98, judge),
        _f1_row("slot detection F1", [r["slot"] for r in rows], 0.95, judge),
        _stats_row("centroid error", [r["centroid"] for r in rows], "taxel", 0.5, judge),
        _stats_row(
            "centroid error of an exact, noise-free sensor weighing its whole array "
            "(the floor, see below)",
            [r["felt"] for r in rows],
            "taxel",
            0.5,
            False,
        ),
        *reference_row,
        _stats_row(
            "line angle error (line frames)",
            [r["angle"] for r in rows if r["truth"] == "line"],
            "deg",
            2.0,
            judge,
        ),
        _stats_row(
            "arc radius error (arc frames)",
            [r["radius"] for r in rows if r["truth"] == "arc"],
            "%",
            5.0,
            judge,
            100,
        ),
        _stats_row("3-D position error", [r["position"] for r in rows], "mm", 0.5, judge, 1e3),
        "",
        *_per_indenter(rows),
        *_floor_note(rows),
        *_read_back_note(rows, features_scenes.benchmark_sensor(name)),
    ]
    return lines


def _floor_note(rows: list[dict]) -> list[str]:
    """What the floor row shows."""
    over = [r for r in rows if r["centroid"] is not None and r["centroid"] > 0.5]
    both = [r for r in over if r["felt"] > 0.5]
    floor = sum(r["felt"] > 0.5 for r in rows)
    return [
        "",
        "The floor: the centroid of what the transducers sense (the sensed quantity at every "
        "taxel, noise-free, weighed over the whole array) against the pressure's centroid. "
        "The cover spreads every load over a few cover depths, and what it spreads off the "
        "array is felt nowhere: a contact the array's edge cuts (a plate, a texture, an edge "
        f"across the array) is felt off its centroid. It is over 0.5 taxel in {floor} of "
        f"{len(rows)} frames; of the {len(over)} frames whose centroid error is over 0.5 "
        f"taxel, {len(both)} are among them. The floor is not a bound on every estimator: "
        "the features' read-back (see below) runs on beyond the array's edges, into what the "
        "load on the array that explains the frame presses there, and so undoes the loss. "
        "That assumes no load beyond the edges, as in this simulator, whose load grid is the "
        "array; a plate pressed across a real sensor has load there, which the read-back "
        "then puts at the edge. The floor says how far from the pressure's centroid the "
        "array's own view of such a contact lies.",
    ]


def _read_back_note(rows: list[dict], sensor) -> list[str]:
    """What the reference centroid row shows (only for a sensor whose frames read back)."""
    pairs = [
        (r["centroid"], r["image_centroid"])
        for r in rows
        if r["centroid"] is not None and r["image_centroid"] is not None
    ]
    if not pairs:
        return []
    features, image = np.array(pairs).T
    cost: dict[bool, list[float]] = {False: [], True: []}  # by whether the reach crosses an edge
    for row in rows[:: max(len(rows) // 50, 1)]:
        prepared = prepare(row["frame"].raw, sensor)
        if not prepared.present:
            continue
        widest = _windows(prepared, catchment_reach(prepared))[-1]
        crosses = widest != _clipped(widest, prepared.mask.shape)
        weighed = replace(prepared, read_back=None)
        times = {}
        for name, case in (("read", prepared), ("weighed", weighed)):
            runs = []
            for _ in range(7):
                start = CLOCK()
                contact_regions(case)
                runs.append(CLOCK() - start)
            times[name] = min(runs)
        cost[crosses].append(times["read"] - times["weighed"])
    spent = [
        f"{statistics.median(cost[crosses]) * 1e3:.2f} ms a frame {where} (median over "
        f"{len(cost[crosses])} frames, least of 7 runs each)"
        for crosses, where in ((False, "inside the array"), (True, "across an edge"))
        if cost[crosses]
    ]
    return [
        "",
        "Centroid reference row: given this sensor, the features read the raw frame back to "
        "pressure through the camera's response (the glass's scratches subtracted, the grey "
        "level read as real contact area and that as pressure, signed so that the noise "
        "averages out) and take its centre over the smallest window, from the contact mask "
        "through its bounding box grown by 0-32 taxels up to the reach of its load (3.5 cover "
        "depths), whose centre agrees with every larger window's within 2.5 noise sigmas "
        "(Lepski's rule). Where that reach crosses the array's edge, the windows run on into "
        "the array grown by it, with what the load on the array that explains the frame "
        "presses there (a zero-boundary Tikhonov solution by conjugate gradients, "
        "`taxel.reconstruction.extend_readings`). The reference row "
        "weighs the image instead (unsmoothed, above its baseline, over the contact mask, after "
        "the opening that removes narrow defects), as the features do for a frame they cannot "
        f"read back. On the {len(pairs)} frames with both, errors above 0.5 taxel: "
        f"{np.sum(features > 0.5)} (features) against {np.sum(image > 0.5)} (image weighed); "
        f"median {np.median(features):.3f} against {np.median(image):.3f}, 95th percentile "
        f"{np.percentile(features, 95):.2f} against {np.percentile(image, 95):.2f} taxel. The "
        f"read-back and its windows cost {' and '.join(spent)}.",
    ]


def _rules_table() -> list[str]:
    lines = ["| indenter | label |", "|---|---|"]
    lines += [f"| {k} | {v} |" for k, v in features_scenes.LABEL_RULES.items()]
    return lines


def _accuracy(
    quick: bool, seed: int = SEED, details: bool = False
) -> tuple[str, dict, dict[str, list[dict]]]:
    """Accuracy on simulated frames (cached under benchmarks/.cache), the frames, the rows."""
    per_indenter = 10 if quick else 72
    frames, parts, scored = {}, [], {}
    for name in SENSORS:
        sensor = features_scenes.benchmark_sensor(name)
        frames[name] = features_scenes.load(name, per_indenter, seed)
        rows = scored[name] = evaluate(frames[name], sensor)
        parts += score(rows, name)
        if details:
            for r in rows:
                if (
                    r["type"] != r["truth"]
                    or r["hole"][0] != r["hole"][1]
                    or (r["slot"][0] != r["slot"][1])
                ):
                    f = r["frame"]
                    print(
                        f"{name} {r['indenter']:10s} {r['truth']:>7s} -> {r['type']:7s} "
                        f"[{r['rule']}] hole {r['hole']} slot {r['slot']} F={f.force:.1f} "
                        f"major={f.major_axis_m * 1e3:.2f}mm noise={f.noise_level:.3f} "
                        f"{f.parameters}"
                    )
    recheck = []
    if not quick:
        recheck = [
            f"\n### Second draw (seed {RECHECK_SEED}, 20 frames per indenter)\n",
            "The same scoring on other random frames, to check that no rule was fitted to "
            "the first draw.\n",
            "| sensor | type accuracy | hole F1 | slot F1 | centroid median | line angle "
            "median | arc radius median | 3-D median |",
            "|---|---|---|---|---|---|---|---|",
        ]
        for name in SENSORS:
            sensor = features_scenes.benchmark_sensor(name)
            rows = evaluate(features_scenes.load(name, 20, RECHECK_SEED), sensor)
            accuracy = np.mean([r["type"] == r["truth"] for r in rows])
            medians = [
                np.median([r[k] for r in rows if r[k] is not None] or [np.nan]) * scale
                for k, scale in (("centroid", 1), ("angle", 1), ("radius", 100), ("position", 1e3))
            ]
            recheck.append(
                f"| {name} | {accuracy:.1%} | {_f1_score([r['hole'] for r in rows])[0]:.3f} | "
                f"{_f1_score([r['slot'] for r in rows])[0]:.3f} | {medians[0]:.3g} taxel | "
                f"{medians[1]:.3g} deg | {medians[2]:.3g} % | {medians[3]:.3g} mm |"
            )
    scales = {
        name: features_scenes.full_scale(features_scenes.benchmark_sensor(name))
        for name in SENSORS
    }
    header = [
        "\n### Accuracy on simulated frames\n",
        f"{per_indenter} frames of each of the 14 library indenters per sensor (seed {seed}), "
        "from `benchmarks/features_scenes.py`: random size, force, position and rotation, "
        "solved by `taxel.mechanics.solve_contact` through `TactileSensor.press` with the "
        "sensor's own noise (camera for vhdta128; readout noise, gain, offset and crosstalk "
        "for the 16x16 array). Then Gaussian noise of standard deviation `level x full "
        "scale` is added, `level` uniform in [0, 5 %], full scale being the mean reading "
        "change from the unloaded array to the whole array at the sensor's full-scale "
        f"pressure ({scales['vhdta128']:.0f} DN on vhdta128, {scales['16x16']:.0f} codes on "
        "the 16x16), and the frame is rounded "
        "and clipped to the output's range. The 16x16 array is the `resistive16` preset "
        "(2 mm pitch) with its contacts solved on 0.5 mm cells.\n",
        "Labels come from the physics, never from the image. Contact type, by indenter "
        "(the *point size* is max(2.5 mm, 2 taxel pitches), the 2.5 mm default "
        "`point_size` or the array's Nyquist limit):\n",
        *_rules_table(),
        "",
        "Centroid truth: the force-weighted centroid of the solved pressure on the array. "
        "3-D truth: that point (z = 0, on the cover) mapped through a random pose (uniform "
        "rotation, translation in a 1 m cube). Line angle truth: the placement angle; arc "
        "radius truth: the rim radius. (*) A hole is enclosed when a 4-connected gap of the "
        "solved contact, of at least one taxel's disk, mostly without material (+inf "
        "heights), stays clear of the array's border by a wall as wide as the cover is deep "
        "(2 taxels at least; closer, the blurred wall cannot be told from the array's edge); "
        "a slot is present when half its length lies on the array with contact along both "
        "walls. Errors are given as median / 95th percentile / max.\n",
    ]
    return "\n".join(header + parts + recheck), frames, scored


def run(quick: bool = False, seed: int = SEED, details: bool = False) -> str:
    cv2.setNumThreads(1)
    timings = features_speed.SpeedRounds(quick)

    # a round of timings after each section (one in a quick run), so that they sample the
    # machine at different moments (see `features_speed`)
    def timing_round(last: bool = False) -> None:
        if not quick or last:
            timings.round()

    accuracy, frames, scored = _accuracy(quick, seed, details)
    redrawn = features_redraw.section(
        scored["vhdta128"], features_scenes.benchmark_sensor("vhdta128"), quick
    )
    timing_round()
    calibration = _calibration()
    profile = _profile(10 if quick else 60)
    timing_round()
    budget = _call_budget(calibration)
    simulated = _speed_simulated(frames, 5 if quick else 20)
    timing_round()
    rest = features_rest.section(quick, seed, evaluate)
    timing_round()
    camera = features_camera.section(
        frames["vhdta128"], features_scenes.benchmark_sensor("vhdta128"), quick
    )
    texture = _seed_texture(quick)
    timing_round(last=True)
    parts = [
        "## Features\n",
        "`taxel.features.extract`, full feature set, median CPU time (`time.thread_time`) "
        "on one core (OpenCV single-threaded, BLAS one thread), synthetic frames from "
        "`tests/features/synthetic.py` given a bare pitch. CPU time, not wall time, because "
        "the machine is shared (wall time also counts the waits for the core): on it a "
        f"16 x 16 float32 add takes {calibration * 1e6:.2f} us (about 0.3-0.5 us on a "
        "current desktop core), so these numbers are a few times what a dedicated core "
        "gives.\n",
        timings.table(),
        "",
        timings.one_feature_table(),
        "",
        profile,
        "",
        budget,
        simulated,
        accuracy,
        redrawn,
        rest,
        camera,
        texture,
    ]
    return "\n".join(parts)


def _seed_texture(quick: bool) -> str:
    """The seed's texture table (section 2.1, figures 6-8) beside ours, on several draws."""
    from taxel.report import DemoContext
    from taxel.report._passive import SEED_TEXTURE, texture_table

    seeds = (1985, 1) if quick else (1985, 1, 2, 3, 4)
    draws = [texture_table(DemoContext(seed=seed)) for seed in seeds]
    tables = [{row[0]: row[1:3] for row in draw.tables[0].rows} for draw in draws]
    lines = [
        "\n### The seed's texture experiment (figures 6-8)\n",
        "Stiff foam, wood rasp and perforated screen pressed with 30 N over the whole "
        "vhdta128 array (`taxel demo`'s experiment), the image smoothed with a Gaussian, "
        "then the seed's two measures: the number of local maxima and their mean height "
        f"above the background [grey levels]; {len(seeds)} noise draws (seeds "
        f"{', '.join(map(str, seeds))}).\n",
        "| object | seed: maxima / mean height | taxel, each draw: maxima / mean height |",
        "|---|---|---|",
    ]
    for name in ("foam", "screen", "rasp"):
        ours = "; ".join(f"{table[name][0]} / {table[name][1]}" for table in tables)
        count, height = SEED_TEXTURE[name]
        lines.append(f"| {name} | {count} / {height:.2f} | {ours} |")
    claims = [verdict.claim for verdict in draws[0].verdicts]
    held = [sum(draw.verdicts[i].passed for draw in draws) for i in range(len(claims))]
    lines += [
        "",
        "| the seed's finding | draws where it holds |",
        "|---|---|",
        *(f"| {claim} | {n} of {len(draws)} |" for claim, n in zip(claims, held, strict=True)),
        "",
        "The simulated surfaces are the library's, not the seed's samples, and the seed "
        "does not give its forces, so the counts and heights are not its own; its "
        "orderings are what the findings above check.",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    seed = int(sys.argv[sys.argv.index("--seed") + 1]) if "--seed" in sys.argv else SEED
    print(run(quick="--quick" in sys.argv, seed=seed, details="--details" in sys.argv))
