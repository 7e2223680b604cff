"""Labelled tactile frames from the sensor simulator, for the features benchmark.

Every indenter of `taxel.mechanics` is pressed on a sensor of `taxel.sensor` at a random
position, rotation, size and force; Gaussian noise of a random level is added to the frame
and the sensor is given a random pose. The labels come from what was pressed (the indenter's
class and placement) and from the solved contact on the sensor's load grid, never from the
image. `LABEL_RULES` states each rule; the Markdown of the benchmark prints it.

Solved frames are cached in ``benchmarks/.cache`` (ignored by git): a cache file is named
by the sensor (its name and a digest of its whole model, so that a changed preset is never
read from an old file), the number of frames per indenter, the seed and `VERSION`.
"""

from __future__ import annotations

import gzip
import hashlib
import math
import pickle
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from scipy import ndimage
from scipy.spatial.transform import Rotation

from taxel.frames import make_pose, transform_points
from taxel.mechanics import INDENTER_NAMES, make_indenter
from taxel.sensor import TactileSensor, make_sensor

VERSION = 4  # bump when the scenes, labels or solver change: old cache files are then ignored
CACHE = Path(__file__).resolve().parent / ".cache"
POINT_SIZE = 2.5e-3  # [m], the default `point_size` of taxel.features.extract
NOISE_LEVELS = (0.0, 0.05)  # added noise, fraction of the sensor's full scale

# (random parameters, force range [N], one-line label rule) per indenter; sizes in metres
LABEL_RULES = {
    "pen": "point (a tip; pressed with 0.3-5 N, writing forces, its contact stays <= 2.5 mm)",
    "sphere": "point if the true contact's major axis <= the point size, else surface",
    "edge": "line",
    "cylinder": "line (a cylinder's side is a line contact whatever its width)",
    "punch": "surface",
    "washer": "surface; hole if its hole is enclosed by the true contact on the array (*)",
    "can": "arc (the rim radius is the arc's radius)",
    "box-edge": "line",
    "box-corner": "point if the true contact's major axis <= the point size, else corner",
    "slot": "surface; slot if >= half the slot's length lies on the array",
    "hole": "surface; hole if the hole is enclosed by the true contact on the array (*)",
    "foam": "surface (texture)",
    "rasp": "surface (texture)",
    "screen": "surface (texture); hole if one of its holes is enclosed by the true contact (*)",
}


@dataclass(frozen=True)
class Labelled:
    """One simulated frame and what is true about it.

    Attributes
    ----------
    indenter : str
    parameters : dict
        The indenter's size parameters [m] (and seeds).
    force : float
        Normal force [N].
    position : (float, float)
        Placement of the indenter's origin on the sensor [m].
    angle : float
        Placement angle [rad].
    noise_level : float
        Added Gaussian noise, fraction of full scale [-].
    raw : numpy.ndarray
        The frame as the sensor outputs it, with the added noise.
    contact_type : str
        True contact type (see `LABEL_RULES`).
    hole, slot : bool
        Whether a hole or a slot is truly present on the array.
    centroid_m : (float, float)
        Force-weighted centroid of the true pressure on the array, sensor frame [m].
    felt_centroid_m : (float, float)
        Centroid of what the transducers sense (the sensed quantity at the taxels,
        noise-free) over the whole array, sensor frame [m]: where an exact, noise-free
        sensor weighing its whole array would put the contact. The cover spreads the
        load, and what it spreads off the array is not felt: a contact the array's edge
        cuts is felt off its pressure's centroid (the floor of the centroid error).
    major_axis_m : float
        Full major axis of the true contact region, 4 sqrt(largest variance) [m].
    line_angle : float or None
        The line's direction in [0, pi) [rad] (line contacts).
    arc_radius : float or None
        The rim radius [m] (arc contacts).
    pose : numpy.ndarray, shape (4, 4)
        Random sensor pose T_BS.
    position_base_m : (float, float, float)
        The true centroid (on the cover's surface, z = 0) in the base frame [m].
    """

    indenter: str
    parameters: dict[str, Any]
    force: float
    position: tuple[float, float]
    angle: float
    noise_level: float
    raw: np.ndarray
    contact_type: str
    hole: bool
    slot: bool
    centroid_m: tuple[float, float]
    felt_centroid_m: tuple[float, float]
    major_axis_m: float
    line_angle: float | None
    arc_radius: float | None
    pose: np.ndarray
    position_base_m: tuple[float, float, float]


def _log_uniform(rng: np.random.Generator, low: float, high: float) -> float:
    return float(math.exp(rng.uniform(math.log(low), math.log(high))))


def _draw(name: str, rng: np.random.Generator, half: float) -> tuple[dict, float, tuple, float]:
    """Random parameters, force [N], position [m] and angle [rad] of one indenter.

    `half` is half the array's width [m]; tools land within half of it of the centre.
    """
    u = rng.uniform
    angle = float(u(0.0, math.pi)) if name != "box-corner" else float(u(0.0, 2 * math.pi))
    position = (float(u(-0.5, 0.5) * half), float(u(-0.5, 0.5) * half))
    if name == "pen":
        parameters = {"tip_radius": u(0.2e-3, 0.5e-3), "half_angle": math.radians(u(15, 30))}
        force = _log_uniform(rng, 0.3, 5.0)
    elif name == "sphere":
        parameters = {"radius": _log_uniform(rng, 2e-3, 15e-3)}
        force = _log_uniform(rng, 0.5, 30.0)
    elif name == "edge":
        parameters = {"radius": _log_uniform(rng, 1e-3, 6e-3)}
        force = _log_uniform(rng, 2.0, 40.0)
    elif name == "cylinder":
        parameters = {"radius": u(2e-3, 8e-3), "length": u(12e-3, 25e-3)}
        force = _log_uniform(rng, 2.0, 40.0)
    elif name == "punch":
        parameters = {"radius": u(2e-3, 5e-3), "edge_radius": u(0.05e-3, 0.3e-3)}
        force = _log_uniform(rng, 2.0, 40.0)
    elif name == "washer":
        outer = u(5e-3, 10e-3)
        parameters = {
            "outer_radius": outer,
            "inner_radius": outer * u(0.4, 0.6),
            "edge_radius": u(0.1e-3, 0.3e-3),
        }
        force = _log_uniform(rng, 5.0, 60.0)
        position = (float(u(-0.7, 0.7) * half), float(u(-0.7, 0.7) * half))
    elif name == "can":
        radius = u(20e-3, 40e-3)
        parameters = {"rim_radius": radius, "lip_radius": u(0.6e-3, 1.5e-3)}
        force = _log_uniform(rng, 2.0, 40.0)
        # the rim's centre lies off the array; its nearest point is within half/2 of the centre
        azimuth, reach = u(0.0, 2 * math.pi), radius + u(-0.5, 0.5) * half
        position = (-reach * math.cos(azimuth), -reach * math.sin(azimuth))
    elif name == "box-edge":
        parameters = {
            "edge_radius": u(0.2e-3, 1.0e-3),
            "included_angle": math.radians(u(60, 120)),
        }
        force = _log_uniform(rng, 2.0, 40.0)
    elif name == "box-corner":
        parameters = {"edge_radius": u(0.2e-3, 1.0e-3)}
        force = _log_uniform(rng, 0.5, 20.0)
    elif name == "slot":
        width = u(2e-3, 4e-3)
        parameters = {"slot_width": width, "slot_length": width * u(3.5, 6.0)}
        force = _log_uniform(rng, 30.0, 300.0)
        position = (float(u(-0.6, 0.6) * half), float(u(-0.6, 0.6) * half))
    elif name == "hole":
        parameters = {"hole_radius": u(1.5e-3, 5e-3)}
        force = _log_uniform(rng, 30.0, 300.0)
        position = (float(u(-0.9, 0.9) * half), float(u(-0.9, 0.9) * half))
    elif name == "foam":
        parameters = {
            "cell_size": u(1e-3, 2.5e-3),
            "depth": u(0.2e-3, 0.5e-3),
            "seed": int(rng.integers(1000)),
        }
        force = _log_uniform(rng, 20.0, 200.0)
    elif name == "rasp":
        pitch = u(2e-3, 4e-3)
        parameters = {
            "tooth_pitch": pitch,
            "row_pitch": pitch * u(0.7, 0.9),
            "tooth_height": u(0.5e-3, 1.0e-3),
            "seed": int(rng.integers(1000)),
        }
        force = _log_uniform(rng, 20.0, 200.0)
    elif name == "screen":
        diameter = u(3e-3, 5e-3)
        parameters = {
            "hole_diameter": diameter,
            "pitch": diameter * u(1.4, 1.7),
            "seed": int(rng.integers(1000)),
        }
        force = _log_uniform(rng, 20.0, 200.0)
    else:  # pragma: no cover - every library indenter is listed above
        raise ValueError(f"no scene for indenter {name!r}")
    if name in ("slot", "hole") and rng.random() < 0.5:
        parameters["crown_radius"] = _log_uniform(rng, 0.3, 2.0)  # a gently convex plate
    parameters = {k: float(v) if k != "seed" else v for k, v in parameters.items()}
    return parameters, force, position, angle


def _major_axis(mask: np.ndarray, spacing: tuple[float, float]) -> float:
    rows, cols = np.nonzero(mask)
    if rows.size == 0:
        return 0.0
    dy, dx = spacing
    points = np.vstack((rows * dy, cols * dx))
    covariance = np.cov(points, bias=True) + np.eye(2) * dy * dx / 12.0
    return float(4.0 * math.sqrt(np.linalg.eigvalsh(covariance)[-1]))


def _enclosed_missing(contact: np.ndarray, missing: np.ndarray, minimum: int, margin: int) -> bool:
    """Whether some region of missing material (+inf heights) is enclosed by contact.

    A gap counts when it is a 4-connected set of non-contact cells that stays `margin`
    cells clear of the grid's border, holds at least `minimum` cells, and is mostly missing
    material.
    """
    labels, count = ndimage.label(~contact)
    if count == 0:
        return False
    edge = max(margin, 1)
    border = np.unique(
        np.concatenate(
            (
                labels[:edge].ravel(),
                labels[-edge:].ravel(),
                labels[:, :edge].ravel(),
                labels[:, -edge:].ravel(),
            )
        )
    )
    sizes = np.bincount(labels.ravel(), minlength=count + 1)
    empty = np.bincount(labels.ravel(), missing.ravel(), minlength=count + 1)
    for label in range(1, count + 1):
        if label in border or sizes[label] < minimum:
            continue
        if empty[label] >= 0.5 * sizes[label]:
            return True
    return False


def _slot_seen(
    parameters: dict,
    position: tuple[float, float],
    angle: float,
    sensor: TactileSensor,
    mask: np.ndarray,
) -> bool:
    """At least half the slot's length lies on the array, with contact along both walls."""
    grid = sensor.load_grid
    dy, dx = grid.spacing
    rows, cols = grid.shape
    along = np.linspace(-0.5, 0.5, 201) * parameters["slot_length"]
    direction = np.array([math.cos(angle), math.sin(angle)])
    normal = np.array([-direction[1], direction[0]])
    offset = parameters["slot_width"] / 2 + max(sensor.taxel_pitch)  # just outside each wall
    seen = []
    for shift in (0.0, offset, -offset):
        px = position[0] + along * direction[0] + shift * normal[0]
        py = position[1] + along * direction[1] + shift * normal[1]
        col = np.rint(px / dx + (cols - 1) / 2).astype(int)
        row = np.rint(py / dy + (rows - 1) / 2).astype(int)
        inside = (row >= 0) & (row < rows) & (col >= 0) & (col < cols)
        touching = np.zeros(along.size, bool)
        touching[inside] = mask[row[inside], col[inside]]
        seen.append((inside, touching))
    (centre, _), (wall_a, touch_a), (wall_b, touch_b) = seen
    if centre.mean() < 0.5:
        return False
    walls = [touch[inside].mean() if inside.any() else 0.0 for inside, touch in seen[1:]]
    return bool(min(walls) >= 0.9)


def _labels(
    name: str,
    parameters: dict,
    position: tuple[float, float],
    angle: float,
    sensor: TactileSensor,
    contact: Any,
    heights: np.ndarray,
) -> dict[str, Any]:
    grid = sensor.load_grid
    spacing = grid.spacing
    pressure, mask = contact.pressure, contact.contact
    x, y = grid.coordinates()
    total = float(pressure.sum())
    centroid = (float((pressure * x).sum() / total), float((pressure * y).sum() / total))
    major = _major_axis(mask, spacing)
    point_size = max(POINT_SIZE, 2.0 * max(sensor.taxel_pitch))
    kind = {
        "pen": "point",
        "sphere": "surface",
        "edge": "line",
        "cylinder": "line",
        "punch": "surface",
        "washer": "surface",
        "can": "arc",
        "box-edge": "line",
        "box-corner": "corner",
    }.get(name, "surface")
    if name in ("sphere", "box-corner") and major <= point_size:
        kind = "point"
    # a hole must be resolved: at least a disk of one taxel's radius, and seen all round,
    # with a wall on the array at least as wide as the cover is deep (2 taxels at least):
    # closer to the border the blurred wall cannot be told from the array's edge
    minimum = max(int(math.pi * (max(sensor.taxel_pitch) / min(spacing)) ** 2), 3)
    wall = max(sensor.cover.depth, 2.0 * max(sensor.taxel_pitch))
    margin = int(math.ceil(wall / min(spacing)))
    missing = ~np.isfinite(heights)
    hole = name in ("washer", "hole", "screen") and _enclosed_missing(
        mask, missing, minimum, margin
    )
    slot = name == "slot" and _slot_seen(parameters, position, angle, sensor, mask)
    return {
        "contact_type": kind,
        "hole": bool(hole),
        "slot": slot,
        "centroid_m": centroid,
        "major_axis_m": major,
        "line_angle": angle % math.pi if kind == "line" else None,
        "arc_radius": parameters["rim_radius"] if name == "can" else None,
    }


def full_scale(sensor: TactileSensor) -> float:
    """Mean reading change from the unloaded array to the full-scale pressure [output units]."""
    shape = sensor.load_grid.shape
    rest = sensor.frame_from_pressure(np.zeros(shape)).raw
    loaded = sensor.frame_from_pressure(np.full(shape, sensor.full_scale)).raw
    return float(np.mean(loaded) - np.mean(rest))


def benchmark_sensor(name: str) -> TactileSensor:
    """The sensor a benchmark name stands for.

    'vhdta128' is the preset; '16x16' is the resistive16 preset with its contacts solved on
    4 x 4 cells per taxel (0.5 mm), so that a pen or an edge is resolved by the mechanics
    even though the array samples it at 2 mm.
    """
    if name == "16x16":
        return replace(make_sensor("resistive16"), oversampling=4)
    return make_sensor(name)


def _output_range(raw: np.ndarray, sensor: TactileSensor) -> tuple[float, float]:
    if raw.dtype == np.uint8:
        return 0.0, 255.0
    bits = sensor.readout.bits or 16
    return 0.0, float(2**bits - 1)


def simulate(sensor_name: str, per_indenter: int, seed: int) -> list[Labelled]:
    """Labelled frames: `per_indenter` of each library indenter, reproducible from `seed`."""
    sensor = benchmark_sensor(sensor_name)
    scale = full_scale(sensor)
    half = min(n * p for n, p in zip(sensor.shape, sensor.taxel_pitch, strict=True)) / 2
    x, y = sensor.load_grid.coordinates()
    taxel_x, taxel_y = sensor.geometry.positions()
    frames = []
    for index, name in enumerate(INDENTER_NAMES):
        rng = np.random.default_rng([seed, index])
        for _ in range(per_indenter):
            parameters, force, position, angle = _draw(name, rng, half)
            indenter = make_indenter(name, **parameters)
            frame = sensor.press(
                indenter, normal_force=force, position=position, angle=angle, rng=rng
            )
            heights = indenter.heights(x, y, position=position, angle=angle)
            truth = _labels(name, parameters, position, angle, sensor, frame.contact, heights)
            felt = np.asarray(frame.quantity, dtype=float)
            truth["felt_centroid_m"] = (
                float((felt * taxel_x).sum() / felt.sum()),
                float((felt * taxel_y).sum() / felt.sum()),
            )
            level = float(rng.uniform(*NOISE_LEVELS))
            low, high = _output_range(frame.raw, sensor)
            noisy = frame.raw + rng.normal(0.0, level * scale, size=frame.raw.shape)
            raw = np.clip(np.rint(noisy), low, high).astype(frame.raw.dtype)
            pose = make_pose(Rotation.random(random_state=rng), rng.uniform(-0.5, 0.5, 3))
            centroid = (*truth["centroid_m"], 0.0)
            base = tuple(float(v) for v in transform_points(pose, centroid))
            frames.append(
                Labelled(
                    name,
                    parameters,
                    force,
                    position,
                    angle,
                    level,
                    raw,
                    pose=pose,
                    position_base_m=base,
                    **truth,
                )  # fmt: skip
            )
    return frames


def load(sensor_name: str, per_indenter: int, seed: int) -> list[Labelled]:
    """`simulate`, through the cache."""
    model = hashlib.sha256(repr(benchmark_sensor(sensor_name)).encode()).hexdigest()[:8]
    name = f"features-{sensor_name}-{model}-{per_indenter}-{seed}-v{VERSION}.pkl.gz"
    path = CACHE / name
    if path.exists():
        with gzip.open(path, "rb") as stream:
            return pickle.load(stream)
    frames = simulate(sensor_name, per_indenter, seed)
    CACHE.mkdir(exist_ok=True)
    (CACHE / ".gitignore").write_text("*\n")
    with gzip.open(path, "wb") as stream:
        pickle.dump(frames, stream)
    return frames
