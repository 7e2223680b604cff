"""Speed of the full feature set (issue 5), and of each one-feature function, timed in rounds.

The machine is shared and its speed drifts by up to 2x from one minute to the next. Each
synthetic frame is therefore timed once per round, a round after each section of the
benchmark, so that the rounds sample the machine at different moments. A round's figure is
the median CPU time of its calls; the verdict takes the round whose median over the
patterns is least, as `timeit` advises (interference only adds time), and the slowest
round is given beside it. The one-feature functions (`find_contact`, ...) are timed in the
same rounds, for a sensor loop that needs less than every feature.
"""

from __future__ import annotations

import statistics
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests" / "features"))
import synthetic

from reconstruction_speed import dct_probe
from taxel.features import (
    classify_contact,
    contact_plane,
    detect_holes,
    detect_slots,
    extract,
    find_contact,
    prepare,
    texture_measures,
)

PATTERNS = ["cone", "band", "arc", "washer", "corner", "plate_with_slot", "texture"]
CLOCK = time.thread_time  # CPU time of this thread: what one core spends, whatever the load
SIZES = (("128x128 FTIR 8-bit", 3.3e-2 / 128, 1000e-6), ("16x16 pressure", 1.5e-3, 100e-6))


# what a loop that needs less than every feature can call instead (each prepares the image)
ONE_FEATURE = (
    ("prepare", prepare, "validation, noise, smoothing, contact mask"),
    ("find_contact", find_contact, "contact, regions, centroid"),
    ("classify_contact", classify_contact, "contact type"),
    ("detect_holes", detect_holes, "holes, both tests"),
    ("detect_slots", detect_slots, "slots"),
    ("contact_plane", contact_plane, "planarity"),
    ("texture_measures", texture_measures, "texture"),
)


def median_time(image: np.ndarray, pitch: float, repeats: int, function=extract) -> float:
    """Median CPU time of `function` (by default `extract`) on one image [s]."""
    function(image, pitch)  # warm caches
    times = []
    for _ in range(repeats):
        start = CLOCK()
        function(image, pitch)
        times.append(CLOCK() - start)
    return statistics.median(times)


@dataclass
class SpeedRounds:
    """The synthetic frames, rendered once; `round()` times each of them once more."""

    quick: bool = False
    frames: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    # per size: per round, per pattern [s]
    rounds: list[list[list[float]]] = field(default_factory=lambda: [[] for _ in SIZES])
    # per round: the time of a bare 128 x 128 DCT [s], how fast the machine was then
    probes: list[float] = field(default_factory=list)
    # per one-feature function, per size: per round, the median over the patterns [s]
    single: dict[str, list[list[float]]] = field(
        default_factory=lambda: {name: [[] for _ in SIZES] for name, _, _ in ONE_FEATURE}
    )

    def __post_init__(self) -> None:
        for name in PATTERNS:
            pattern = getattr(synthetic, name)
            big = synthetic.render(pattern, ftir=True, noise=0.03, scratches=3, rng=0)
            small = synthetic.render(pattern, (16, 16), noise=0.01, rng=0)
            self.frames[name] = (big, small)

    @property
    def repeats(self) -> int:
        return 30 if self.quick else 300

    def round(self) -> None:
        """Time every frame once more, and the machine's speed just before."""
        self.probes.append(dct_probe())
        for index, (_, pitch, _) in enumerate(SIZES):
            self.rounds[index].append(
                [median_time(self.frames[name][index], pitch, self.repeats) for name in PATTERNS]
            )
            for name, function, _ in ONE_FEATURE:
                times = [
                    median_time(self.frames[pattern][index], pitch, self.repeats // 3, function)
                    for pattern in PATTERNS
                ]
                self.single[name][index].append(statistics.median(times))

    def one_feature_table(self) -> str:
        """CPU time of each one-feature function (at least one round must have run)."""
        lines = [
            "One feature at a time, for a loop that needs less than every feature (each "
            "call prepares the image itself): median over the seven patterns of the median "
            f"CPU time of {self.repeats // 3} calls [us], in each round; the least and the "
            "slowest round, marked where even the least is over the full feature set's "
            "target.\n",
            "| function | what | " + " | ".join(label for label, _, _ in SIZES) + " |",
            "|---|---|" + "---|" * len(SIZES),
        ]
        for name, _, what in ONE_FEATURE:
            cells = []
            for rounds, (_, _, target) in zip(self.single[name], SIZES, strict=True):
                best, worst = min(rounds), max(rounds)
                mark = f" (over {target * 1e6:.0f})" if best > target else ""
                cells.append(f"{best * 1e6:.0f}{mark} / {worst * 1e6:.0f}")
            lines.append(f"| `{name}` | {what} | {' | '.join(cells)} |")
        return "\n".join(lines)

    def table(self) -> str:
        """The speed table (at least one round must have run)."""
        count = len(self.rounds[0])
        header = " | ".join(
            f"{label}, CPU [us]: least round / slowest round" for label, _, _ in SIZES
        )
        lines = [f"| indenter | {header} |", "|---|" + "---|" * len(SIZES)]
        for position, name in enumerate(PATTERNS):
            cells = []
            for rounds in self.rounds:
                values = [times[position] * 1e6 for times in rounds]
                cells.append(f"{min(values):.0f} / {max(values):.0f}")
            lines.append(f"| {name} | {' | '.join(cells)} |")
        cells = []
        for rounds, (_, _, target) in zip(self.rounds, SIZES, strict=True):
            medians = [statistics.median(times) for times in rounds]
            best, worst = min(medians), max(medians)
            verdict = "met" if best <= target else "not met"
            cells.append(
                f"**{best * 1e6:.0f}** / {worst * 1e6:.0f} (target {target * 1e6:.0f} CPU: "
                f"{verdict})"
            )
        lines.append(f"| **median over the indenters** | {' | '.join(cells)} |")
        spread = (
            "spread over this benchmark's run (one after each of its sections)"
            if count > 1
            else "(a quick run: one round, at its end)"
        )
        lines.append(
            f"\n{count} round{'s' if count > 1 else ''} of {self.repeats} calls per frame "
            f"{spread}: a round's figure is the median of its calls; each indenter's least "
            "and slowest rounds are shown, and the verdict takes the round whose median over "
            "the indenters is least (interference from the shared machine only adds time). "
            "A bare 128 x 128 DCT took "
            + ", ".join(f"{probe * 1e6:.0f}" for probe in self.probes)
            + " us of CPU just before each round."
        )
        return "\n".join(lines)
