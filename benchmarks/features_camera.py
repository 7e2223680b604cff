"""A camera that differs from its model: offset, uneven lighting, exposure (vhdta128).

Given an FTIR sensor, the features read its raw frame back through the model's response
(dark level, glass scratches, grey level to contact area to pressure). A real camera's dark
level, lighting and exposure drift from any model. Every 17th frame of the accuracy set is
changed as such a camera would change it, then dithered and rounded to 8 bits, and the
features run on it as read, and against a reference recorded by the same camera at rest
(the mean of unloaded frames, changed alike).
"""

from __future__ import annotations

import statistics
from collections.abc import Callable

import numpy as np

from taxel.features import extract

EVERY = 17  # the frames scored: every 17th of the accuracy set
REFERENCE_FRAMES = 8
_SEED = 6100


Change = Callable[[np.ndarray], np.ndarray]


def _changes(shape: tuple[int, int]) -> list[tuple[str, Change, bool]]:
    """What each camera does to a frame (grey levels, float) of `shape`, and whether its
    reference at rest was recorded after the change (else before: a drift since)."""
    across = np.linspace(0.0, 1.0, shape[1])[None, :]  # 0 at the first column, 1 at the last
    return [
        ("as modelled", lambda frame: frame, True),
        ("+0.3 grey level (dark level)", lambda frame: frame + 0.3, True),
        ("+2 grey levels (dark level)", lambda frame: frame + 2.0, True),
        ("ramp of 1 grey level across the columns", lambda frame: frame + across, True),
        ("ramp of 4 grey levels across the columns", lambda frame: frame + 4.0 * across, True),
        ("exposure -10 % (dark level too)", lambda frame: 0.9 * frame, True),
        ("exposure +10 % (dark level too)", lambda frame: 1.1 * frame, True),
        ("dark level drifts +1 after the reference", lambda frame: frame + 1.0, False),
    ]


def _as_read(frame: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """A changed frame as an 8-bit camera gives it: dithered, rounded, clipped."""
    dithered = frame + rng.uniform(-0.5, 0.5, frame.shape)
    return np.clip(np.rint(dithered), 0, 255).astype(np.uint8)


def _scores(frames: list, sensor, reference: np.ndarray | None) -> tuple[list[float], int]:
    """Centroid errors [taxels] (inf without a contact) and the correct contact types."""
    pitch = float(np.mean(sensor.taxel_pitch))
    errors, correct = [], 0
    for frame, labelled in frames:
        features = extract(frame, sensor, pose=labelled.pose, reference=reference)
        correct += features.contact_type == labelled.contact_type
        found = features.contact.centroid_m
        error = np.inf if found is None else np.hypot(*np.subtract(found, labelled.centroid_m))
        errors.append(float(error / pitch))
    return errors, correct


def _cell(errors: list[float], correct: int) -> str:
    """median / p95 / max [taxels], frames over 0.5 taxel, contact type accuracy."""
    ordered = np.sort(errors)
    p95 = float(np.percentile(ordered, 95)) if np.isfinite(ordered).all() else np.inf
    over = sum(error > 0.5 for error in errors)
    return (
        f"{statistics.median(errors):.3f} / {p95:.2f} / {ordered[-1]:.2f}, {over} | "
        f"{correct / len(errors):.1%}"
    )


def section(labelled: list, sensor, quick: bool) -> str:
    """The markdown section, on every `EVERY`-th labelled vhdta128 frame."""
    chosen = labelled[:: EVERY * (4 if quick else 1)]
    rest = np.zeros(sensor.load_grid.shape)
    unloaded = np.mean(
        [
            sensor.frame_from_pressure(rest, rng=np.random.default_rng([_SEED, index])).raw
            for index in range(REFERENCE_FRAMES)
        ],
        axis=0,
    )
    lines = [
        "\n### A camera that differs from its model (vhdta128)\n",
        f"Every {EVERY * (4 if quick else 1)}th frame of the accuracy set ({len(chosen)} "
        "frames), changed as a camera that differs from the sensor's model would change "
        "it, then dithered, rounded and clipped to 8 bits; the features run on it as read, "
        "and against a reference from the same camera at rest (the mean of "
        f"{REFERENCE_FRAMES} unloaded frames, changed alike, or for the last row recorded "
        "before the camera drifted: `reference=`). Centroid error "
        "median / p95 / max [taxels], frames over 0.5 taxel; contact type accuracy.\n",
        "| camera | as read: centroid | type | with a reference: centroid | type |",
        "|---|---|---|---|---|",
    ]
    rng = np.random.default_rng(_SEED)
    for name, change, after in _changes(sensor.shape):
        frames = [(_as_read(change(item.raw.astype(float)), rng), item) for item in chosen]
        reference = change(unloaded) if after else unloaded
        plain = _cell(*_scores(frames, sensor, None))
        tared = _cell(*_scores(frames, sensor, reference))
        lines.append(f"| {name} | {plain} | {tared} |")
    lines += [
        "",
        "As read, an offset or a tilt of the background is measured where the contact "
        "leaves half the array or more as background (a level from 3 standard errors, a "
        "tilt from half a grey level), and a ramp steep enough to move the contact's cut is "
        "taken out before segmentation; a texture or plate over most of the array leaves "
        "too little background to tell its own faint light from the camera's. A reference "
        "from the same camera takes away its dark level, lighting and glass whatever the "
        "contact; the exposure's change of the contact's own light is left (the exposure "
        "rows show what it costs). A drift since the reference was recorded is an offset "
        "again, measured as one when the contact leaves half the array as background.",
    ]
    return "\n".join(lines)
