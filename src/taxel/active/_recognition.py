"""Recognise an object by touching it up to three times and matching a library of models.

Ellis seed, introduction: "various features of the object are needed to identify it as
matching a known model (or, if information is limited and errorful, as matching one of a
few specifiable models)". The finger touches where the object is thought to be, then twice
more along the imprint's long axis, one object length's worth either way; the rotation-
invariant features of the three touches are compared with those of the library's models
touched the same way at canonical poses, and the models are ranked. When the first touch
already leaves only one model plausible (`first_touch_radius`), the other two are not made.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel._validation import check_instance, check_positive
from taxel.active._model_library import ModelLibrary
from taxel.active._probe import NoContactError, Probe
from taxel.active._procedure import ProcedureStep, step_from_reading
from taxel.active._touch_features import TOUCH_FEATURES, touch_vector
from taxel.features import extract, prepare
from taxel.frames import transform_directions

__all__ = [
    "Recognition",
    "RecognitionResult",
    "explore",
    "first_touch_library",
    "first_touch_radius",
    "touch_descriptor",
]

N_TOUCHES = 3
_FIRST = "touch1:"  # the prefix of the first touch's features in a library
# the features of `touch_descriptor`, in its order: what a library's templates must hold
DESCRIPTOR_NAMES: tuple[str, ...] = tuple(
    f"{part}:{name}" for part in ("touch1", "min23", "max23") for name in TOUCH_FEATURES
)


def touch_descriptor(touches: Sequence[np.ndarray]) -> np.ndarray:
    """One object's descriptor from its (up to) three touch vectors.

    The first touch's features, then the smaller and the larger value of each feature over
    the second and third touch (which of the two comes first along the axis is arbitrary).

    Examples
    --------
    >>> from taxel.active._touch_features import touch_vector
    >>> descriptor = touch_descriptor([touch_vector(None)] * 3)
    >>> descriptor.shape, float(descriptor[0])
    ((39,), 0.0)
    """
    n = len(TOUCH_FEATURES)
    first = np.asarray(touches[0], float) if touches else np.full(n, np.nan)
    rest = [np.asarray(t, float) for t in touches[1:N_TOUCHES]]
    if not rest:
        return np.concatenate([first, np.full(2 * n, np.nan)])
    stack = np.stack(rest)
    with warnings.catch_warnings():  # an all-NaN feature (absent in both) stays NaN
        warnings.simplefilter("ignore", RuntimeWarning)
        low = np.nanmin(stack, axis=0)
        high = np.nanmax(stack, axis=0)
    return np.concatenate([first, low, high])


def first_touch_library(library: ModelLibrary) -> ModelLibrary | None:
    """The library restricted to its first touch's features (None when it holds none)."""
    columns = [i for i, name in enumerate(library.feature_names) if name.startswith(_FIRST)]
    if not columns:
        return None
    return ModelLibrary(
        names=library.names,
        templates=library.templates[:, columns],
        labels=library.labels,
        scales=library.scales[columns],
        feature_names=tuple(library.feature_names[i] for i in columns),
        normal_force=library.normal_force,
        step=library.step,
        sensor=library.sensor,
    )


def first_touch_radius(library: ModelLibrary) -> float:
    """How far a touch of a model may lie from that model's canonical touches, by the library.

    Each canonical touch is left out in turn and its distance (`ModelLibrary.distances`) to
    the nearest other canonical touch of its own model is taken; the largest of these is the
    radius. The library's touches are made at the canonical poses, turned and moved off-centre
    by most of the placement error, so a model lying farther than this from a touch is not
    a plausible match by the library's own evidence.

    Parameters
    ----------
    library : ModelLibrary
        Usually `first_touch_library`'s, so that the radius is that of a single touch.

    Returns
    -------
    float
        The radius (a distance, as `ModelLibrary.distances`); NaN when no model has two
        canonical touches.
    """
    labels = np.array(library.labels)
    largest = math.nan
    for index, template in enumerate(library.templates):
        same = labels == labels[index]
        same[index] = False
        if same.any():
            distance = float(library.distances(template)[same].min())
            largest = distance if math.isnan(largest) else max(largest, distance)
    return largest


def explore(
    probe: Probe,
    *,
    normal_force: float,
    step: float,
    decided: Callable[[np.ndarray], bool] | None = None,
) -> tuple[list[np.ndarray], list[ProcedureStep]]:
    """Touch where the probe is, then `step` [m] either way along the imprint's long axis.

    When `decided` is given and returns True for the first touch's vector, touches 2 and 3
    are not made.
    A touch that finds nothing within the probe's reach (the probe raises
    `NoContactError`) counts as a touch without contact; any other error is raised. The
    probe is retracted after each touch and returned to its starting pose at the end, also
    when a command fails.
    """
    start = probe.pose
    sensor = probe.sensor
    vectors: list[np.ndarray] = []
    steps: list[ProcedureStep] = []
    axis = transform_directions(start, [1.0, 0.0, 0.0])
    try:
        for index, shift in enumerate((0.0, step, -step)):
            pose = start.copy()
            pose[:3, 3] += shift * axis
            if index:
                probe.move_to(pose)
                steps.append(ProcedureStep("move", position=pose[:3, 3].copy()))
            try:
                reading = probe.press(normal_force=normal_force)
            except NoContactError as error:
                vectors.append(touch_vector(None))
                steps.append(
                    ProcedureStep(f"touch {index + 1}: no contact ({error})", position=pose[:3, 3])
                )
                continue
            features = extract(reading.frame.raw, sensor, pose=reading.pose)
            probe.retract()
            vector = touch_vector(features, prepare(reading.frame.raw, sensor))
            vectors.append(vector)
            measured = dict(zip(TOUCH_FEATURES, vector, strict=True))
            steps.append(
                step_from_reading(
                    f"touch {index + 1} {normal_force:g} N: {features.contact_type}",
                    reading,
                    **{k: v for k, v in measured.items() if math.isfinite(v)},
                )
            )
            if index == 0 and decided is not None and decided(vector):
                break
            if index == 0 and features.pose is not None and features.pose.axis_base is not None:
                # the imprint's long axis, kept in the sensor's plane
                normal = transform_directions(start, [0.0, 0.0, 1.0])
                axis = np.asarray(features.pose.axis_base, float)
                axis = axis - (axis @ normal) * normal
                axis /= max(float(np.linalg.norm(axis)), 1e-12)
    finally:
        probe.retract()
        probe.move_to(start)
    steps.append(ProcedureStep("return to the start", position=start[:3, 3].copy()))
    return vectors, steps


@dataclass(frozen=True)
class RecognitionResult:
    """The models ranked against the touches of an object.

    Attributes
    ----------
    name : str
        The best-matching model.
    candidates : tuple of (str, float, float)
        Every model with its score (the share of exp(-distance / 2) over all models, in
        [0, 1]) and its distance (mean squared standardised feature difference to the
        model's nearest canonical touch), best first.
    descriptor : numpy.ndarray
        The object's descriptor (`touch_descriptor`).
    n_touches : int
        Touches made: 1 when the first touch left only one model within
        `first_touch_radius` (the candidates are then ranked by that touch alone), else 3.
    message : str
        How sure the match is, in words.
    steps : tuple of ProcedureStep
        What the finger did and measured.
    first_touch_radius : float, default nan
        The stopping rule's radius (`first_touch_radius` of the library's first touches):
        after the first touch, a model farther than this is implausible, and with one model
        left the procedure stops. NaN when the rule was not applied.
    """

    name: str
    candidates: tuple[tuple[str, float, float], ...]
    descriptor: np.ndarray = field(repr=False)
    n_touches: int
    message: str
    steps: tuple[ProcedureStep, ...] = field(repr=False)
    first_touch_radius: float = math.nan

    @property
    def score(self) -> float:
        """Score of the best model."""
        return self.candidates[0][1]

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary."""
        return {
            "name": self.name,
            "score": self.score,
            "candidates": [
                {"name": name, "score": score, "distance": distance}
                for name, score, distance in self.candidates
            ],
            "n_touches": self.n_touches,
            "first_touch_radius": self.first_touch_radius
            if math.isfinite(self.first_touch_radius)
            else None,
            "message": self.message,
            "steps": [step.to_dict() for step in self.steps],
        }


class Recognition:
    """Touch an object up to three times and rank the library's models (seed, intro).

    Parameters
    ----------
    library : ModelLibrary or path
        The models' canonical descriptors (`build_model_library`, `ModelLibrary.load`);
        its force and exploration step are used.
    stop_early : bool, default True
        Stop after the first touch when it leaves only one model plausible (see Notes);
        False always touches three times.

    Notes
    -----
    Touch 1 is made where the probe is (above where the object is thought to be). The
    imprint's major axis (or the sensor's x axis when nothing was touched) then sets the
    direction of touches 2 and 3, one library step to either side: along a pen or a key
    they find the ends, across a small object its rim, beside a can top its rim. The
    touches' rotation-invariant features (`TOUCH_FEATURES`) form the descriptor
    (`touch_descriptor`) that `ModelLibrary.match` compares with every model.

    Stopping early: after touch 1, every model is compared on that touch's features alone
    (`first_touch_library`). A model is plausible when its distance is within the library's
    own spread of a single touch (`first_touch_radius`: the largest distance of a canonical
    touch from its model's other canonical touches). When exactly one model is plausible,
    touches 2 and 3 are not made and that model is the answer. On the seven models of
    `MODEL_NAMES` (vhdta128, 8 rotations) this stops after one touch for most objects; when
    the first touch leaves two models or none plausible, all three are made.
    """

    def __init__(self, library: ModelLibrary | str | Any, *, stop_early: bool = True) -> None:
        if not isinstance(library, ModelLibrary):
            if not isinstance(library, str | os.PathLike):
                raise TypeError(f"`library` must be a ModelLibrary or its file, got {library!r}")
            library = ModelLibrary.load(library)
        if tuple(library.feature_names) != DESCRIPTOR_NAMES:
            shown = ", ".join(library.feature_names[:3]) + ", ..." * (
                len(library.feature_names) > 3
            )
            raise ValueError(
                f"`library` holds the features {shown} ({len(library.feature_names)}), not the "
                f"{len(DESCRIPTOR_NAMES)} of this version's touches ({DESCRIPTOR_NAMES[0]}, "
                "...): build it again with build_model_library"
            )
        self.library = library
        check_instance("stop_early", stop_early, bool)
        self.stop_early = stop_early
        self._first = first_touch_library(library) if self.stop_early else None
        self.first_touch_radius = (
            first_touch_radius(self._first) if self._first is not None else math.nan
        )

    def _first_touch_match(self, vector: np.ndarray) -> list[tuple[str, float, float]] | None:
        """The models ranked by the first touch when it leaves only one plausible, else None."""
        if self._first is None or not math.isfinite(self.first_touch_radius) or vector[0] <= 0:
            return None
        n = len(self._first.feature_names)
        ranked = self._first.match(touch_descriptor([vector])[:n])
        plausible = [name for name, _, distance in ranked if distance <= self.first_touch_radius]
        return ranked if len(plausible) == 1 else None

    def run(self, probe: Probe) -> RecognitionResult:
        """Explore the object and rank the models."""
        check_instance("probe", probe, Probe)
        library = self.library
        if library.sensor and probe.sensor.name != library.sensor:
            raise ValueError(
                f"`library` was made on sensor {library.sensor!r}, the probe carries "
                f"{probe.sensor.name!r}"
            )
        vectors, steps = explore(
            probe,
            normal_force=check_positive("normal_force", library.normal_force),
            step=library.step,
            decided=lambda vector: self._first_touch_match(vector) is not None,
        )
        if not any(vector[0] > 0 for vector in vectors):
            raise ValueError(
                "no touch found contact: the object is not within "
                f"{library.step * 1e3:g} mm of the start pose"
            )
        descriptor = touch_descriptor(vectors)
        first = self._first_touch_match(vectors[0]) if len(vectors) == 1 else None
        ranked = first if first is not None else library.match(descriptor)
        best, runner_up = ranked[0], ranked[1] if len(ranked) > 1 else None
        if first is not None:
            message = (
                f"{best[0]} (decided by the first touch: the only model within "
                f"{self.first_touch_radius:.2f} of it)"
            )
        elif runner_up is None or best[1] > 0.9:
            message = f"{best[0]} (clear match)"
        else:
            message = f"{best[0]}, or perhaps {runner_up[0]} (score {best[1]:.2f})"
        return RecognitionResult(
            name=best[0],
            candidates=tuple(ranked),
            descriptor=descriptor,
            n_touches=len(vectors),
            message=message,
            steps=tuple(steps),
            first_touch_radius=self.first_touch_radius,
        )
