"""The features' worst centroids, over fresh draws of their noise (vhdta128).

A frame's centroid error mixes the estimator's bias for that contact (where it lands on
average) with the one draw of noise the frame carries. Each frame of the accuracy set
whose centroid error is over 0.5 taxel is pressed again and read with `DRAWS` new draws of
the camera's noise and of the added Gaussian noise, at the frame's own noise level, as
`features_scenes.simulate` makes them; the features' mean error over the draws is the
bias, and its root mean square about the truth splits into the bias squared and the
noise's variance. Beside them, how much of the stress the cover brings to the glass lies
above the FTIR's saturation, where the grey level stops growing and the load is felt by
no taxel, and the centroid of that stress, exact and noise-free, clipped at saturation and
weighed over the array grown by `_MARGIN` taxels (no load beyond the array, as simulated):
where the image is saturated, what a read-back can see at best.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from features_scenes import _output_range, full_scale
from taxel.features import extract
from taxel.mechanics import make_indenter
from taxel.reconstruction import as_forward_model_spec, forward_operator

DRAWS = 40
_SEED = 7300
_MARGIN = 32  # taxels: over 8 cover depths of vhdta128, where the spread is nil
_SATURATED = 1e-3  # a frame is saturated when this share of its stress is above saturation


def _centre(values: np.ndarray) -> np.ndarray:
    """Centroid (row, column) of an image [taxels]."""
    rows, cols = np.indices(values.shape)
    total = values.sum()
    return np.array([(values * rows).sum(), (values * cols).sum()]) / total


def saturation_floor(pressure: np.ndarray, sensor) -> tuple[float, float]:
    """Share of the stress at the glass above saturation, and the clipped stress's error.

    The error [taxels] is that of the centroid of the exact stress over the array grown by
    `_MARGIN`, clipped at the transducer's saturation pressure, against the load's.
    """
    spec = as_forward_model_spec(sensor)
    rows, cols = spec.shape
    grown = replace(spec, shape=(rows + 2 * _MARGIN, cols + 2 * _MARGIN), dead_taxels=())
    stress = forward_operator(grown, boundary="zero").apply(np.pad(pressure, _MARGIN))
    clipped = np.minimum(stress, sensor.transducer.saturation_pressure)
    error = _centre(clipped) - _MARGIN - _centre(pressure)
    return float(1.0 - clipped.sum() / stress.sum()), float(np.hypot(*error))


def _pressed(frame, sensor):
    """The frame's contact, solved again (noise-free)."""
    indenter = make_indenter(frame.indenter, **frame.parameters)
    return sensor.press(
        indenter, normal_force=frame.force, position=frame.position, angle=frame.angle
    )


def redrawn_errors(frame, sensor, scale: float, draws: int, pressed=None) -> np.ndarray:
    """The features' centroid error (x, y) [taxels] on `draws` fresh draws of the noise."""
    pressed = _pressed(frame, sensor) if pressed is None else pressed
    contact = pressed.contact
    pitch = math.sqrt(sensor.taxel_pitch[0] * sensor.taxel_pitch[1])
    low, high = _output_range(pressed.raw, sensor)
    errors = np.full((draws, 2), np.nan)
    for draw in range(draws):
        rng = np.random.default_rng([_SEED, draw])
        raw = sensor.frame_from_pressure(
            contact.pressure, displacement=contact.displacement, rng=rng, contact=contact
        ).raw
        noisy = raw + rng.normal(0.0, frame.noise_level * scale, size=raw.shape)
        raw = np.clip(np.rint(noisy), low, high).astype(raw.dtype)
        found = extract(raw, sensor).contact.centroid_m
        if found is not None:
            errors[draw] = np.subtract(found, frame.centroid_m) / pitch
    return errors


def section(rows: list[dict], sensor, quick: bool) -> str:
    """The markdown section, on the frames of `rows` (`evaluate`'s) over 0.5 taxel."""
    draws = 8 if quick else DRAWS
    scale = full_scale(sensor)
    over = sorted(
        (r for r in rows if r["centroid"] is not None and r["centroid"] > 0.5),
        key=lambda r: -r["centroid"],
    )
    lines = [
        "\n### The frames over 0.5 taxel, over fresh draws of their noise (vhdta128)\n",
        f"Each frame whose centroid error is over 0.5 taxel, pressed again and read with "
        f"{draws} new draws of the camera's and the added noise at its own level "
        "(`benchmarks/features_redraw.py`). Bias: the features' mean error over the draws; "
        "rms: their root mean square error about the truth, whose square is the bias's "
        "plus the noise's variance. Saturated: the share of the stress at the glass above "
        "the FTIR's saturation, and the centroid error of the exact stress clipped there "
        "(see the module).\n",
        "| indenter | added noise | error, benchmark's draw | bias | rms | bias's share of "
        "the mean squared error | draws over 0.5 | saturated: stress, centroid error |",
        "|---|---|---|---|---|---|---|---|",
    ]
    biased = noisy = 0
    saturated = []
    for row in over:
        frame = row["frame"]
        pressed = _pressed(frame, sensor)
        share_above, floor = saturation_floor(np.asarray(pressed.contact.pressure), sensor)
        if share_above >= _SATURATED:
            saturated.append(floor)
        errors = redrawn_errors(frame, sensor, scale, draws, pressed)
        found = errors[np.isfinite(errors[:, 0])]
        clipped = f"{share_above:.1%}, {floor:.2f}" if share_above >= _SATURATED else "-"
        if not found.size:
            lines.append(
                f"| {frame.indenter} | {frame.noise_level:.1%} | - | - | - | - | - | {clipped} |"
            )
            continue
        bias = float(np.hypot(*found.mean(axis=0)))
        rms = float(np.sqrt(np.mean(np.sum(found**2, axis=1))))
        share = bias**2 / rms**2 if rms > 0 else 0.0
        biased += bias > 0.5
        noisy += share < 0.5
        over_count = int(np.count_nonzero(np.hypot(found[:, 0], found[:, 1]) > 0.5))
        lines.append(
            f"| {frame.indenter} | {frame.noise_level:.1%} | {row['centroid']:.2f} | "
            f"{bias:.2f} | {rms:.2f} | {share:.0%} | {over_count} of {len(found)} | "
            f"{clipped} |"
        )
    floors = ", ".join(f"{value:.2f}" for value in sorted(saturated, reverse=True))
    lines += [
        "",
        f"Of these {len(over)} frames, {biased} have a bias over 0.5 taxel by itself, and "
        f"for {noisy} the noise's variance is most of the mean squared error. "
        f"{len(saturated)} are saturated (0.1 % of the stress or more); the exact stress "
        f"clipped at saturation puts them {floors or '-'} taxel off.",
    ]
    return "\n".join(lines)
