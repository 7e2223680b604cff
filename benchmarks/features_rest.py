"""Frames at rest: how often the features report a contact on an unloaded sensor.

A robot polls its fingers between touches, so a frame with nothing on it must read as no
contact. Each preset with image frames reads unloaded frames with its own noise; the
features run on each as they are, and after subtracting a reference (the mean of 8 other
unloaded frames, as a user records at start-up). The benchmark's labelled frames are also
scored with such a reference, to show what it costs or gains on contacts.
"""

from __future__ import annotations

import numpy as np

import features_scenes
from taxel.features import extract
from taxel.sensor import PRESET_NAMES, make_sensor

FRAMES = 200
REFERENCE_FRAMES = 8


def _reference(sensor, seed: int) -> np.ndarray:
    """The mean of `REFERENCE_FRAMES` unloaded frames, drawn apart from the trials."""
    rest = np.zeros(sensor.load_grid.shape)
    frames = [
        sensor.frame_from_pressure(rest, rng=np.random.default_rng([seed, index])).raw
        for index in range(REFERENCE_FRAMES)
    ]
    return np.mean(frames, axis=0)


def _false_contacts(name: str, frames: int) -> tuple[int, int, dict[str, int]]:
    """False contacts without and with a reference, and where the untared ones lay."""
    sensor = make_sensor(name)
    rest = np.zeros(sensor.load_grid.shape)
    reference = _reference(sensor, 9000)
    plain = tared = 0
    found: dict[str, int] = {}
    for index in range(frames):
        raw = sensor.frame_from_pressure(rest, rng=np.random.default_rng([7000, index])).raw
        features = extract(raw, sensor)
        if features.contact.present:
            plain += 1
            found[features.contact_type] = found.get(features.contact_type, 0) + 1
        tared += extract(raw, sensor, reference=reference).contact.present
    return plain, tared, found


def image_presets() -> list[str]:
    """The presets whose raw frames are images the features take (2-D, >= 3 x 3)."""
    names = []
    for name in PRESET_NAMES:
        sensor = make_sensor(name)
        raw = sensor.frame_from_pressure(np.zeros(sensor.load_grid.shape)).raw
        if raw.ndim == 2 and min(raw.shape) >= 3:  # (a microbend array reads its fibres)
            names.append(name)
    return names


def section(quick: bool, seed: int, evaluate) -> str:
    """The markdown section: false contacts per preset, and the labelled frames tared.

    `evaluate(frames, sensor, **options)` scores labelled frames (`bench_features.evaluate`).
    """
    frames = 40 if quick else FRAMES
    lines = [
        "\n### Frames at rest (no contact)\n",
        f"{frames} unloaded frames per preset with its own noise (seed 7000), features "
        "with the defaults, then with a reference subtracted (`extract(..., reference=)`, "
        f"`taxel features --reference`): the mean of {REFERENCE_FRAMES} other unloaded "
        "frames.\n",
        "| preset | shape | false contacts, as read | with a reference | types found |",
        "|---|---|---|---|---|",
    ]
    for name in image_presets():
        plain, tared, found = _false_contacts(name, frames)
        shape = " x ".join(map(str, make_sensor(name).shape))
        kinds = ", ".join(f"{kind} {count}" for kind, count in sorted(found.items())) or "-"
        lines.append(
            f"| {name} | {shape} | {plain / frames:.1%} | {tared / frames:.1%} | {kinds} |"
        )
    lines += [
        "",
        "As read, an FTIR frame keeps its glass's scratches. The 3 x 3 opening removes "
        "their bright lines but not all of them: beside a scratch the 3 x 3 minimum holds "
        "some of its pixels, so on noisy frames a residue of up to 1 DN (about 4 noise "
        "sigmas of the smoothed image on vhdta128) stays along the scratches, most where "
        "two run close or cross; with the noise, that reaches the 11-sigma seed threshold. "
        "It is a fixed pattern, which an unloaded frame takes away before the opening is "
        "needed. The noise the thresholds count in is measured on the frame (on integer "
        "frames as the median of grouped data, see `noise_from_residual`).\n",
        "The labelled vhdta128 frames of the accuracy benchmark above, each tared by a "
        "reference of the same sensor:\n",
        "| vhdta128 | contact type | centroid error median / p95 / max [taxel] | line angle "
        "max [deg] | arc radius max [%] |",
        "|---|---|---|---|---|",
    ]
    sensor = features_scenes.benchmark_sensor("vhdta128")
    reference = _reference(sensor, 9001)
    frames_labelled = features_scenes.load("vhdta128", 10 if quick else 72, seed)
    for label, options in (("as read", {}), ("with a reference", {"reference": reference})):
        rows = evaluate(frames_labelled, sensor, **options)
        accuracy = np.mean([r["type"] == r["truth"] for r in rows])
        centroid = np.array([r["centroid"] for r in rows if r["centroid"] is not None])
        angle = max(r["angle"] for r in rows if r["angle"] is not None)
        radius = max(r["radius"] for r in rows if r["radius"] is not None) * 100
        lines.append(
            f"| {label} | {accuracy:.1%} | {np.median(centroid):.3f} / "
            f"{np.percentile(centroid, 95):.2f} / {centroid.max():.2f} | {angle:.3f} | "
            f"{radius:.2f} |"
        )
    return "\n".join(lines)
