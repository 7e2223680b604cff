"""Slip detection online: `SlipMonitor` in a 1 kHz sensor loop, against `SlipDetector.run`.

Usage: ``python benchmarks/slip_stream.py [--quick]``; `section(quick)` returns the Markdown
section. The frames are simulated trials (`slip_trials`) of the benchmark's finger
(`slip_sensors`: resistive16 static array and piezo8x8 PVDF array at 1 kHz). Each trial's
frames are pushed one at a time, as a robot's loop would; every push is timed (wall clock,
one core), and the events are compared with the batch detector's on the whole sequence.
"""

from __future__ import annotations

import os

# one core, as the targets are stated; set before NumPy/SciPy load their thread pools
for _variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from taxel.active import SlipDetector, SlipMonitor, slip_sensors, slip_trials  # noqa: E402

SEED = 2024  # the evaluation trials of the slip benchmark (bench_probing.py)
FRAME_PERIOD = 1e-3  # [s] at 1 kHz


def _stream(detector: SlipDetector, sequence, with_piezo: bool) -> tuple:
    """Push a trial's frames one by one.

    Returns (same events as the batch?, wall-clock times [s], CPU times [s], the last
    warm-up frame's wall-clock time [s]); the times are those after the warm-up.
    """
    piezo = sequence.piezo_frames if with_piezo else None
    batch = detector.run(sequence.static_frames, piezo, frame_rate=sequence.frame_rate)
    monitor = SlipMonitor(detector, frame_rate=sequence.frame_rate)
    times = np.empty((sequence.static_frames.shape[0], 2))
    for index, frame in enumerate(sequence.static_frames):
        other = None if piezo is None else piezo[index]
        wall, cpu = time.perf_counter(), time.thread_time()
        monitor.push(frame, other)
        times[index] = time.perf_counter() - wall, time.thread_time() - cpu
    warm_up = detector.warm_up
    same = monitor.events == batch.events
    return same, times[warm_up:, 0], times[warm_up:, 1], float(times[warm_up - 1, 0])


def section(quick: bool) -> str:
    """The Markdown section: time per pushed frame and agreement with the batch detector."""
    counts = (4, 2, 2) if quick else (20, 10, 10)
    sequences = slip_trials(*counts, seed=SEED)
    time_constant = slip_sensors()[1].transducer.time_constant  # type: ignore[attr-defined]
    paths = [
        ("static + PVDF", SlipDetector(piezo_time_constant=time_constant), True),
        ("static only", SlipDetector(), False),
    ]
    rows = []
    agreements = []
    for name, detector, with_piezo in paths:
        results = [_stream(detector, sequence, with_piezo) for sequence in sequences]
        same = sum(result[0] for result in results)
        agreements.append(same)
        times = np.concatenate([result[1] for result in results]) * 1e3
        cpu = np.concatenate([result[2] for result in results]) * 1e3
        ends = np.array([result[3] for result in results]) * 1e3
        over = np.mean(times > FRAME_PERIOD * 1e3) * 100
        rows.append(
            f"| {name} | {times.size} | {np.median(times):.3f} | "
            f"{np.percentile(times, 99):.3f} | {times.max():.3f} | {over:.2f} | "
            f"{np.median(cpu):.3f} / {np.percentile(cpu, 99):.3f} | "
            f"{np.median(ends):.1f} | {same} / {len(sequences)} |"
        )
    machine = platform.processor() or platform.machine()
    kinds = ", ".join(
        f"{count} {kind}" for kind, count in zip(("slip", "hold", "steady"), counts, strict=False)
    )
    return "\n".join(
        [
            "### Slip online: `SlipMonitor`, one frame at a time (1 kHz sensor loop)\n",
            f"Trials: `slip_trials` seed {SEED} ({kinds}; {'quick run' if quick else 'full run'}),"
            " resistive16 static frames and piezo8x8 PVDF frames at 1 kHz, default thresholds "
            "(the PVDF amplifiers' time constant given). Each frame is pushed as a robot's loop "
            "would; the time of each push is wall clock (`time.perf_counter`) on one core "
            "(OMP_NUM_THREADS=1, OPENBLAS_NUM_THREADS=1), after the warm-up; the CPU time "
            "(`time.thread_time`) leaves out what other processes took. The last warm-up "
            "frame registers all 40 warm-up frames at once (the reference image is known only "
            "then) and is listed on its own. Agreement: the trials whose events (kind, frame, "
            "time, channel) are identical to `SlipDetector.run` on the whole sequence.\n",
            "| frames | pushes timed | median [ms] | p99 [ms] | max [ms] | over 1 ms [%] | "
            "CPU median / p99 [ms] | last warm-up frame, median [ms] | same events as batch |",
            "|---|---|---|---|---|---|---|---|---|",
            *rows,
            "",
            f"Frame period: {FRAME_PERIOD * 1e3:.0f} ms. Machine: {machine}, Python "
            f"{platform.python_version()}, {time.strftime('%Y-%m-%d')}.",
        ]
    )


if __name__ == "__main__":
    print(section("--quick" in sys.argv[1:]))
