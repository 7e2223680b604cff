"""The models' canonical touch descriptors and the matching of an object against them.

The descriptors come from simulated touches of each model at canonical poses (centred
under the finger, turned in equal steps, noise-free), made exactly as the recognition
procedure touches an unknown object, so that the two are comparable feature by feature.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_positive
from taxel.active._json_files import parsing, read_json, write_json

__all__ = ["ModelLibrary"]

_FORMAT = "taxel.model_library"
_VERSION = 1
# a feature's spread is at least this: presence and holes count, lengths are in mm
_FLOORS = {
    "present": 0.25,
    "hole": 0.25,
    "log_area": 0.05,
    "circle_fit": 0.02,
    "curvature": 0.01,
    "band_curvature": 0.01,
}
_DEFAULT_FLOOR = 0.5  # mm for lengths; also covers the scores and ratios
_MISSING = 9.0  # squared standardised penalty for a feature seen in one and not the other
_CAP = 16.0  # no single feature adds more than four spreads squared: one odd fit can't decide


@dataclass(frozen=True, eq=False)
class ModelLibrary:
    """Canonical descriptors of the object models, and how they were made.

    Attributes
    ----------
    names : tuple of str
        The models, in library order.
    templates : numpy.ndarray
        (n_templates, n_features) descriptors of the canonical touches (NaN: not seen).
    labels : tuple of str
        The model of each template.
    scales : numpy.ndarray
        (n_features,) spread of each feature within a model (pooled over the models and
        floored), which standardises the differences.
    feature_names : tuple of str
        Name of each descriptor feature.
    normal_force : float
        Force of each touch [N].
    step : float
        Distance of touches 2 and 3 from touch 1 [m].
    sensor : str
        The sensor the library was made with.
    """

    names: tuple[str, ...]
    templates: np.ndarray
    labels: tuple[str, ...]
    scales: np.ndarray
    feature_names: tuple[str, ...]
    normal_force: float
    step: float
    sensor: str = ""

    def __post_init__(self) -> None:
        templates = np.array(self.templates, dtype=float, ndmin=2)
        if templates.shape[0] != len(self.labels) or templates.shape[1] != len(self.feature_names):
            raise ValueError(
                f"`templates` must be (n_labels={len(self.labels)}, "
                f"n_features={len(self.feature_names)}), got {templates.shape}"
            )
        if len(self.names) < 2:
            raise ValueError(f"`names` must hold at least 2 models, got {list(self.names)}")
        if len(set(self.names)) != len(self.names):
            raise ValueError(f"`names` must name each model once, got {list(self.names)}")
        missing = sorted(set(self.names) - set(self.labels))
        if missing:
            raise ValueError(f"`templates` has no template of {', '.join(missing)}")
        scales = as_finite_array("scales", self.scales, ndim=1)
        if scales.size != len(self.feature_names) or np.any(scales <= 0):
            raise ValueError("`scales` must hold one positive spread per feature")
        check_positive("normal_force", self.normal_force)
        check_positive("step", self.step)
        object.__setattr__(self, "templates", templates)
        object.__setattr__(self, "scales", scales)
        object.__setattr__(self, "names", tuple(self.names))
        object.__setattr__(self, "labels", tuple(self.labels))
        object.__setattr__(self, "feature_names", tuple(self.feature_names))

    @classmethod
    def from_templates(
        cls,
        templates: Any,
        labels: Any,
        feature_names: Any,
        *,
        normal_force: float,
        step: float,
        sensor: str = "",
    ) -> ModelLibrary:
        """A library whose feature spreads are pooled from the templates themselves."""
        array = np.array(templates, dtype=float, ndmin=2)
        labels = tuple(str(label) for label in labels)
        names = tuple(dict.fromkeys(labels))
        feature_names = tuple(feature_names)
        squares = np.zeros(array.shape[1])
        counts = np.zeros(array.shape[1])
        for name in names:
            rows = array[[label == name for label in labels]]
            seen = np.isfinite(rows)
            n = seen.sum(axis=0)
            mean = np.where(n > 0, np.nansum(rows, axis=0) / np.maximum(n, 1), 0.0)
            deviation = np.where(seen, rows - mean, 0.0)
            squares += (deviation**2).sum(axis=0)
            counts += np.maximum(n - 1, 0)
        pooled = np.sqrt(squares / np.maximum(counts, 1))
        floors = np.array(
            [_FLOORS.get(name.split(":")[-1], _DEFAULT_FLOOR) for name in feature_names]
        )
        return cls(
            names=names,
            templates=array,
            labels=labels,
            scales=np.maximum(pooled, floors),
            feature_names=feature_names,
            normal_force=normal_force,
            step=step,
            sensor=sensor,
        )

    def distances(self, descriptor: Any) -> np.ndarray:
        """Distance of a descriptor to every template (n_templates,).

        The mean over the features of the squared standardised difference, each capped at
        four spreads (so that one unstable fit cannot outvote the others), counting a
        feature seen in only one of the two as a difference of three spreads; features
        seen in neither are left out.
        """
        query = np.asarray(descriptor, dtype=float)
        if query.shape != (len(self.feature_names),):
            raise ValueError(
                f"`descriptor` must have {len(self.feature_names)} features, got {query.shape}"
            )
        seen_query = np.isfinite(query)
        seen_template = np.isfinite(self.templates)
        both = seen_query & seen_template
        difference = np.where(both, (query - self.templates) / self.scales, 0.0) ** 2
        difference = np.minimum(difference, _CAP)
        one = seen_query ^ seen_template
        total = difference.sum(axis=1) + _MISSING * one.sum(axis=1)
        counted = (both | one).sum(axis=1)
        return total / np.maximum(counted, 1)

    def match(self, descriptor: Any) -> list[tuple[str, float, float]]:
        """Models ranked by their nearest template: (name, score, distance), best first.

        The score is exp(-distance / 2) normalised over the models.
        """
        distances = self.distances(descriptor)
        labels = np.array(self.labels)
        best = np.array([distances[labels == name].min() for name in self.names])
        weights = np.exp(-(best - best.min()) / 2.0)
        scores = weights / weights.sum()
        order = np.argsort(best, kind="stable")
        return [(self.names[i], float(scores[i]), float(best[i])) for i in order]

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (the file layout of `save`; NaN becomes None)."""
        return {
            "format": _FORMAT,
            "version": _VERSION,
            "sensor": self.sensor,
            "normal_force_n": self.normal_force,
            "step_m": self.step,
            "names": list(self.names),
            "feature_names": list(self.feature_names),
            "labels": list(self.labels),
            "scales": self.scales.tolist(),
            "templates": [
                [float(v) if math.isfinite(v) else None for v in row] for row in self.templates
            ],
        }

    def save(self, path: str | os.PathLike[str], *, overwrite: bool = False) -> Path:
        """Write the library as JSON (an existing file only with `overwrite`)."""
        return write_json(path, self.to_dict(), overwrite=overwrite)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> ModelLibrary:
        """Read a library written by `save`."""
        source = Path(path)
        data = read_json(
            source,
            _FORMAT,
            (
                "names",
                "templates",
                "labels",
                "scales",
                "feature_names",
                "normal_force_n",
                "step_m",
            ),
            "a model library",
        )
        with parsing(source, "a model library"):
            templates = np.array(
                [[np.nan if v is None else v for v in row] for row in data["templates"]], float
            )
            return cls(
                names=tuple(data["names"]),
                templates=templates,
                labels=tuple(data["labels"]),
                scales=np.array(data["scales"], float),
                feature_names=tuple(data["feature_names"]),
                normal_force=float(data["normal_force_n"]),
                step=float(data["step_m"]),
                sensor=str(data.get("sensor", "")),
            )
