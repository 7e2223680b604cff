"""One-call recognition in simulation: build the model library, recognise a placed model."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from functools import lru_cache
from typing import Any

import numpy as np

from taxel._validation import (
    as_rng,
    check_choice,
    check_count,
    check_finite,
    check_pair,
    check_positive,
)
from taxel.active._finger import SimulatedFinger
from taxel.active._imaging import imaging_sensor
from taxel.active._model_library import ModelLibrary
from taxel.active._object_library import MODEL_NAMES, make_model
from taxel.active._progress import Progress, check_progress
from taxel.active._recognition import (
    DESCRIPTOR_NAMES,
    Recognition,
    RecognitionResult,
    explore,
    touch_descriptor,
)
from taxel.frames import make_pose
from taxel.io import check_new_file
from taxel.sensor import TactileSensor

__all__ = ["DESCRIPTOR_NAMES", "build_model_library", "recognize_object"]

_DOWN = np.diag([1.0, -1.0, -1.0])
_STANDOFF = 5e-3
DEFAULT_TOUCH_FORCE = 15.0
DEFAULT_STEP = 20e-3
DEFAULT_POSITION_ERROR = 3e-3
_GOLDEN_ANGLE = math.pi * (3.0 - math.sqrt(5.0))


def _finger(
    sensor: TactileSensor, name: str, position: tuple[float, float], angle: float, rng: Any
) -> SimulatedFinger:
    """A finger above the base origin, over model `name` placed at `position`, `angle`."""
    model = make_model(name, position=position, angle=angle)
    above = make_pose(_DOWN, [0.0, 0.0, model.top + _STANDOFF])
    return SimulatedFinger(sensor, [model], above, rng=rng)


def build_model_library(
    models: Sequence[str] = MODEL_NAMES,
    *,
    sensor: str | TactileSensor = "vhdta128",
    rotations: int = 8,
    normal_force: float = DEFAULT_TOUCH_FORCE,
    step: float = DEFAULT_STEP,
    position_error: float = DEFAULT_POSITION_ERROR,
    rng: Any = 0,
    path: str | os.PathLike[str] | None = None,
    progress: Progress | None = None,
) -> ModelLibrary:
    """Touch every model at canonical poses and keep the descriptors.

    Parameters
    ----------
    models : sequence of str, default all of `MODEL_NAMES`
        The models to recognise among (at least 2).
    sensor : str or TactileSensor, default "vhdta128"
        The sensor on the finger.
    rotations : int, default 8
        Canonical poses per model, turned by 360 / rotations degrees each time; every
        other one is moved off-centre by 0.8 `position_error` (in directions a golden
        angle apart), so that the library sees how placement changes the touches.
    normal_force : float, default 15
        Force of each touch [N].
    step : float, default 0.02
        Distance of touches 2 and 3 from touch 1 [m].
    position_error : float, default 0.003
        How far from the finger the objects to recognise may lie [m].
    rng : numpy.random.Generator or int, optional
        The sensor's noise in the canonical touches (default seed 0; None: noise-free).
        A library touched with the noise on learns how much each feature varies.
    path : path, optional
        Where to save the library as JSON.
    progress : callable, optional
        Called as ``progress(done, total)`` after each canonical pose touched, ``total``
        being the distinct models times `rotations` (None: not told).

    Returns
    -------
    ModelLibrary
    """
    models = [check_choice("models", name, MODEL_NAMES) for name in models]
    if len(set(models)) < 2:
        raise ValueError(f"`models` must name at least 2 models, got {models}")
    rotations = check_count("rotations", rotations)
    normal_force = check_positive("normal_force", normal_force)
    step = check_positive("step", step)
    position_error = check_positive("position_error", position_error, allow_zero=True)
    generator = as_rng("rng", rng)
    progress = check_progress(progress)
    if path is not None:  # refused now, not after the presses
        check_new_file(path, name="path")
    chosen = imaging_sensor(sensor)
    templates, labels = [], []
    unique = list(dict.fromkeys(models))
    for name in unique:
        for k in range(rotations):
            angle = 2 * math.pi * k / rotations
            # every other pose off-centre by most of the placement error, in turning directions
            offset = 0.8 * position_error * (k % 2)
            direction = k * _GOLDEN_ANGLE
            position = (offset * math.cos(direction), offset * math.sin(direction))
            finger = _finger(chosen, name, position, angle, generator)
            vectors, _ = explore(finger, normal_force=normal_force, step=step)
            templates.append(touch_descriptor(vectors))
            labels.append(name)
            if progress is not None:
                progress(len(templates), len(unique) * rotations)
    library = ModelLibrary.from_templates(
        templates, labels, DESCRIPTOR_NAMES, normal_force=normal_force, step=step,
        sensor=chosen.name,
    )  # fmt: skip
    if path is not None:
        library.save(path)
    return library


@lru_cache(maxsize=2)
def _default_library(sensor_name: str) -> ModelLibrary:
    return build_model_library(sensor=sensor_name)


def recognize_object(
    name: str,
    *,
    library: ModelLibrary | str | os.PathLike[str] | None = None,
    sensor: str | TactileSensor = "vhdta128",
    position: tuple[float, float] | None = None,
    angle: float | None = None,
    position_error: float = DEFAULT_POSITION_ERROR,
    rng: Any = None,
    stop_early: bool = True,
) -> RecognitionResult:
    """Place model `name` at a pose, touch it and rank the library's models.

    Parameters
    ----------
    name : str
        The model to place (one of `MODEL_NAMES`); the procedure never sees it.
    library : ModelLibrary or path, optional
        The models to match against; None builds the default library for this sensor
        (`build_model_library`, about a minute, then kept for the session).
    sensor : str or TactileSensor, default "vhdta128"
        The sensor on the finger (must be the library's).
    position : tuple of float, optional
        Where the object's footprint centre lies relative to the point under the finger's
        start pose [m]; None draws it uniformly within `position_error` of it.
    angle : float, optional
        The object's rotation [rad]; None draws it uniformly.
    position_error : float, default 0.003
        How far from the finger the object may lie when `position` is drawn [m].
    rng : numpy.random.Generator or int, optional
        Draws the pose and the sensor noise (None: noise-free frames and a pose from a
        fresh generator).
    stop_early : bool, default True
        Stop after the first touch when it leaves only one model plausible
        (`Recognition`); False always touches three times.

    Returns
    -------
    RecognitionResult
    """
    check_choice("name", name, MODEL_NAMES)
    position_error = check_positive("position_error", position_error, allow_zero=True)
    if position is not None:
        position = check_pair("position", position)
    if angle is not None:
        angle = check_finite("angle", angle)
    checked_rng = as_rng("rng", rng)
    chosen = imaging_sensor(sensor)
    if library is None:
        if isinstance(sensor, str):
            library = _default_library(sensor)
        else:
            library = build_model_library(sensor=chosen)
    procedure = Recognition(library, stop_early=stop_early)
    generator = checked_rng if checked_rng is not None else np.random.default_rng()
    if position is None:
        radius = position_error * math.sqrt(generator.uniform())
        direction = generator.uniform(0.0, 2 * math.pi)
        position = (radius * math.cos(direction), radius * math.sin(direction))
    if angle is None:
        angle = float(generator.uniform(0.0, 2 * math.pi))
    noise = None if checked_rng is None else generator
    return procedure.run(_finger(chosen, name, position, angle, noise))
