"""Speed of taxel.features.extract (and, once the sensor simulator lands, its accuracy).

``run()`` times the full feature set on 128x128 and 16x16 frames of each synthetic indenter.
The accuracy part (>= 1000 simulated frames, every indenter; contact-type accuracy, hole and
slot F1, centroid, line angle, arc radius and 3-D position errors) plugs in as
``_accuracy(quick)``: give it frames with ground truth from the simulator and append its
Markdown table to the section.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import cv2
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "features"))
import synthetic

from taxel.features import extract

PATTERNS = ["cone", "band", "arc", "washer", "corner", "plate_with_slot", "texture"]


def _median_time(image: np.ndarray, pitch: float, repeats: int) -> float:
    extract(image, pitch)  # warm caches
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        extract(image, pitch)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def _speed(quick: bool) -> str:
    cv2.setNumThreads(1)
    repeats = 30 if quick else 300
    lines = [
        "| indenter | 128x128 FTIR 8-bit [us] | 16x16 pressure [us] |",
        "|---|---|---|",
    ]
    big, small = [], []
    for name in PATTERNS:
        pattern = getattr(synthetic, name)
        frame = synthetic.render(pattern, ftir=True, noise=0.03, scratches=3, rng=0)
        grid = synthetic.render(pattern, (16, 16), noise=0.01, rng=0)
        big.append(_median_time(frame, 3.3e-2 / 128, repeats))
        small.append(_median_time(grid, 1.5e-3, repeats))
        lines.append(f"| {name} | {big[-1] * 1e6:.0f} | {small[-1] * 1e6:.0f} |")
    lines.append(
        f"| **median** | **{statistics.median(big) * 1e6:.0f}** (target 1000) "
        f"| **{statistics.median(small) * 1e6:.0f}** (target 100) |"
    )
    return "\n".join(lines)


def _accuracy(quick: bool) -> str | None:
    """Accuracy on simulated frames: waits for the sensor simulator (taxel.sensor)."""
    return None


def run(quick: bool = False) -> str:
    parts = [
        "## Features\n",
        "`taxel.features.extract`, full feature set, median of "
        f"{30 if quick else 300} calls on one core (OpenCV single-threaded), synthetic "
        "frames from `tests/features/synthetic.py`.\n",
        _speed(quick),
    ]
    accuracy = _accuracy(quick)
    parts.append(
        "\nAccuracy on simulated frames: not measured yet (needs the sensor simulator)."
        if accuracy is None
        else accuracy
    )
    return "\n".join(parts)


if __name__ == "__main__":
    print(run(quick="--quick" in sys.argv))
