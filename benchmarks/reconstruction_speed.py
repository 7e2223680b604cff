"""Reconstruction speed (issue 4), timed in rounds spread over the benchmark's run.

The machine is shared and its speed drifts by up to 2x from one minute to the next (a bare
128 x 128 DCT takes 130-300 us of CPU). Each case is therefore timed once per round, a
round after each section of the benchmark, so the rounds sample the machine at different
moments. A round's figure is the median CPU time of its calls; the table gives each case's
least round, as `timeit` advises (interference only adds time), with its slowest round and
the bare DCT's time in each round beside it.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy.fft import dctn

from taxel.reconstruction import (
    SupportSolver,
    TikhonovSolver,
    forward_model_preset,
    forward_operator,
)


def median_time(call: Callable[[], object], repeats: int) -> float:
    """Median CPU time of this thread per call [s]: what one core spends, whatever the load."""
    times = []
    for _ in range(repeats):
        started = time.thread_time()
        call()
        times.append(time.thread_time() - started)
    return float(np.median(times))


def dct_probe() -> float:
    """Median CPU time of a bare 128 x 128 DCT [s]: how fast the shared machine is now.

    About 115 us when the machine is quiet; the speed benchmarks time one before each round.
    """
    image = np.random.default_rng(0).random((128, 128))
    return median_time(lambda: dctn(image, type=2, norm="ortho"), 2000)


@dataclass
class _Case:
    name: str
    call: Callable[[], object]
    repeats: int
    frames: int  # per call: the time is given per frame
    target: float | None  # [s] per frame
    unit: str  # "ms" or "us"
    rounds: list[float] = field(default_factory=list)


@dataclass
class SpeedRounds:
    """The speed cases, built once; `round()` times each of them once more.

    `make_load(name, spec, rng)` gives a truth pressure (the benchmark's own loads).
    """

    make_load: Callable[..., np.ndarray]
    quick: bool = False
    cases: list[_Case] = field(default_factory=list)
    dct_rounds: list[float] = field(default_factory=list)

    def __post_init__(self) -> None:
        repeats = 20 if self.quick else 200
        rng = np.random.default_rng(0)
        spec = forward_model_preset("vhdta128", oversampling=1)
        frame = rng.normal(0, 4e3, spec.shape)
        for order in (0, 1):
            solver = TikhonovSolver(spec, order=order)
            solver.solve(frame)
            name = f"vhdta128 128 x 128, Tikhonov order {order}"
            for label, rule, target in (
                ("fixed lambda", 0.05, 0.5e-3),
                ("GCV", "gcv", 1e-3),
                ("default rule (discrepancy, sigma estimated)", None, 1e-3),
            ):
                call = _solve(solver, frame, rule)
                self.cases.append(_Case(f"{name}, {label}", call, repeats, 1, target, "ms"))
        for k in (1, 2):
            spec = forward_model_preset("resistive16", oversampling=k)
            solver = TikhonovSolver(spec, order=1)
            frames = rng.normal(0, 2e3, (1000, *spec.shape))
            solver.solve(frames[:2])
            name = (
                f"resistive16 16 x 16 -> {spec.load_shape[0]} x {spec.load_shape[1]}, "
                "batch of 1000"
            )
            for label, rule in (("fixed lambda", 0.05), ("GCV", "gcv"), ("default rule", None)):
                self.cases.append(
                    _Case(
                        f"{name}, {label}, per frame",
                        _solve(solver, frames, rule),
                        3 if self.quick else 9,
                        1000,
                        20e-6,
                        "us",
                    )
                )
        # the support method on one contact frame (its cost grows with the support's cells)
        for sensor, k in (("vhdta128", 1), ("resistive16", 2)):
            spec = forward_model_preset(sensor, oversampling=k)
            truth = self.make_load("sphere", spec, np.random.default_rng(3))
            frame = forward_operator(spec).apply(truth)
            frame += rng.normal(0, 0.01 * spec.full_scale, frame.shape)
            solver = SupportSolver(spec)
            cells = int(solver.solve(frame).support.sum())
            name = f"{sensor}, support, one 2 N sphere frame ({cells} cells in the support)"
            self.cases.append(_Case(name, _solve(solver, frame, None), 5, 1, None, "ms"))

    def round(self) -> None:
        """Time every case once more, and a bare 128 x 128 DCT for the machine's speed."""
        self.dct_rounds.append(dct_probe())
        for case in self.cases:
            case.rounds.append(median_time(case.call, case.repeats) / case.frames)

    def lines(self) -> list[str]:
        """The section's text and table (at least one round must have run)."""
        count = len(self.dct_rounds)
        dct = [t * 1e6 for t in self.dct_rounds]
        lines = [
            "Median CPU time of the calling thread (numerical libraries held to one thread), "
            + (
                f"in {count} rounds spread over this benchmark's run (one after each section "
                "above)"
                if count > 1
                else "in one round (a quick run; a full run spreads six over its sections)"
            )
            + ": the machine is shared and its speed drifts by "
            "up to 2x from one minute to the next, so each case's figure is its least round, "
            "as `timeit` advises (interference only adds time), and its slowest round is "
            "given beside it. For scale, one bare 128 x 128 DCT-II (scipy.fft.dctn; a "
            f"fixed-lambda solve makes two) took {min(dct):.0f} to {max(dct):.0f} us of CPU "
            f"from round to round (rounds in order: {', '.join(f'{t:.0f}' for t in dct)} us).",
            "",
            "| case | median time, least round | slowest round | target | verdict |",
            "|---|---|---|---|---|",
        ]
        for case in self.cases:
            scale = {"ms": 1e3, "us": 1e6}[case.unit]
            best, worst = min(case.rounds), max(case.rounds)
            cells = f"{best * scale:.3g} {case.unit} | {worst * scale:.3g} {case.unit}"
            if case.target is None:
                lines.append(f"| {case.name} | {cells} | - | - |")
                continue
            verdict = "met" if best <= case.target else "**not met**"
            target = f"{case.target * scale:g} {case.unit}"
            lines.append(f"| {case.name} | {cells} | {target} | {verdict} |")
        return lines


def _solve(solver, frames: np.ndarray, rule) -> Callable[[], object]:
    """A call solving `frames` by `rule` (a lambda, a rule's name, or None: the default)."""
    if rule is None:
        return lambda: solver.solve(frames)
    return lambda: solver.solve(frames, regularization=rule)
