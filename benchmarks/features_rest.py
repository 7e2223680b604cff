"""Frames at rest: how often the features report a contact on an unloaded sensor.

A robot polls its fingers between touches, so a frame with nothing on it must read as no
contact. Each preset with image frames reads unloaded frames with its own noise; the
features run on each as they are, and after subtracting a reference (the mean of 8 other
unloaded frames, as a user records at start-up). The benchmark's labelled frames are also
scored with such a reference, to show what it costs or gains on contacts.
"""

from __future__ import annotations

import collections

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
        "The labelled frames of the accuracy benchmark above, each tared by a reference "
        "of the same sensor (a raw frame whose contact covers the whole array, such as a "
        "texture pressed over a 16 x 16 array, has no taxel at rest to read the no-load "
        "level from; a tared frame's is 0):\n",
        "| sensor | frames | contact type | no contact found | centroid error median / p95 "
        "/ max [taxel] | line angle max [deg] | arc radius max [%] |",
        "|---|---|---|---|---|---|---|",
    ]
    tared_misses: dict[str, collections.Counter] = {}
    for name in ("vhdta128", "16x16"):
        sensor = features_scenes.benchmark_sensor(name)
        reference = _reference(sensor, 9001)
        frames_labelled = features_scenes.load(name, 10 if quick else 72, seed)
        for label, options in (("as read", {}), ("with a reference", {"reference": reference})):
            rows = evaluate(frames_labelled, sensor, **options)
            accuracy = np.mean([r["type"] == r["truth"] for r in rows])
            missed = sum(r["type"] == "none" and r["truth"] != "none" for r in rows)
            centroid = np.array([r["centroid"] for r in rows if r["centroid"] is not None])
            angle = max(r["angle"] for r in rows if r["angle"] is not None)
            radius = max(r["radius"] for r in rows if r["radius"] is not None) * 100
            lines.append(
                f"| {name} | {label} | {accuracy:.1%} | {missed} of {len(rows)} | "
                f"{np.median(centroid):.3f} / {np.percentile(centroid, 95):.2f} / "
                f"{centroid.max():.2f} | {angle:.3f} | {radius:.2f} |"
            )
            if options:
                missed_rows = [r for r in rows if r["type"] == "none" and r["truth"] != "none"]
                found = sum(
                    extract(r["frame"].raw, sensor, noise="sensor", **options).contact_type
                    == r["truth"]
                    for r in missed_rows
                )
                tared_misses[name] = (
                    collections.Counter(r["indenter"] for r in missed_rows),
                    found,
                )
    for name, (misses, found) in tared_misses.items():
        if misses:
            counts = ", ".join(f"{indenter} {count}" for indenter, count in misses.most_common())
            lines.append(
                f"\nContacts missed on tared {name} frames, by indenter: {counts}; with the "
                f'sensor\'s own noise (`noise="sensor"`) {found} of them get their type right.'
            )
    lines.append(
        "\nA texture pressed over the whole of a small array leaves no taxel at rest, and "
        "its taxels differ from each other as much as noise does: the noise estimated from "
        "the frame is then the texture's, and the contact does not clear it even with the "
        "no-load level known. The sensor's own noise is right only for frames no noisier "
        "than the sensor's model (these carry up to "
        f"{features_scenes.NOISE_LEVELS[1]:.0%} of full scale more)."
    )
    return "\n".join(lines)
