"""A nearest-neighbour texture classifier on standardised features, saved as JSON.

k nearest neighbours is the classifier of the FabricSlide paper (Wang et al. 2022): it
needs no training beyond storing the examples and standardising the features, has a
single setting (k) and its predictions are explained by the neighbours. It is written here
with NumPy; scikit-learn would add a heavy dependency for twenty lines.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from taxel._validation import as_finite_array
from taxel.io import write_text

# as_features and vote are shared with _texture_validation
__all__ = ["TextureClassifier", "fit_texture_classifier"]

_FORMAT = "taxel.texture_classifier"
# Version 2 adds no field of its own but marks models whose `settings` may hold options
# that change the features (normalization, decorrelate_load, per_taxel): a reader of
# version 1 would ignore them and compute other features, so it must refuse the file.
_VERSION = 2
_READABLE_VERSIONS = (1, 2)


def as_features(name: str, features: Any, n_features: int | None = None) -> np.ndarray:
    """(n_samples, n_features) float array; NaN allowed (unobserved band), inf not."""
    try:
        array = np.array(features, dtype=np.float64, ndmin=2)
    except (TypeError, ValueError):
        raise TypeError(f"`{name}` must be numeric") from None
    if array.ndim != 2:
        raise ValueError(f"`{name}` must be (n_samples, n_features), got shape {array.shape}")
    if np.any(np.isinf(array)):
        raise ValueError(f"`{name}` must not hold infinite values")
    if n_features is not None and array.shape[1] != n_features:
        raise ValueError(f"`{name}` must have {n_features} features, got {array.shape[1]}")
    return array


def _distances(queries: np.ndarray, examples: np.ndarray) -> np.ndarray:
    """Mean squared difference over the features observed (not NaN) in both; inf if none."""
    observed_q = ~np.isnan(queries)
    observed_e = ~np.isnan(examples)
    q = np.where(observed_q, queries, 0.0)
    e = np.where(observed_e, examples, 0.0)
    # sum over shared features of (q - e)^2, expanded to matrix products
    squared = (q**2) @ observed_e.T.astype(float) + observed_q.astype(float) @ (e**2).T
    squared -= 2.0 * q @ e.T
    shared = observed_q.astype(float) @ observed_e.T.astype(float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(shared > 0, np.maximum(squared, 0.0) / shared, np.inf)


def vote(distances: np.ndarray, labels: np.ndarray, n_neighbors: int) -> np.ndarray:
    """Majority vote of the k nearest examples; a tie goes to the nearest tied class."""
    order = np.argsort(distances, axis=1, kind="stable")[:, :n_neighbors]
    predictions = []
    for neighbours in order:
        votes = labels[neighbours]
        counts = {label: int(np.sum(votes == label)) for label in votes}
        best = max(counts.values())
        predictions.append(next(label for label in votes if counts[label] == best))
    return np.array(predictions)


@dataclass(frozen=True)
class TextureClassifier:
    """A k-nearest-neighbour classifier over standardised texture features.

    Create it with `fit_texture_classifier` or `TextureClassifier.load`.

    Attributes
    ----------
    classes : tuple of str
        The class labels, sorted.
    examples : numpy.ndarray
        (n_examples, n_features) standardised training features (NaN = not observed).
    labels : tuple of str
        The class of each example.
    center, scale : numpy.ndarray
        (n_features,) the mean and standard deviation used to standardise.
    n_neighbors : int
        k, the number of neighbours that vote.
    settings : mapping
        How the features were computed (for instance the keyword arguments of
        `texture_signature`), so that new data can be treated the same way.
    """

    classes: tuple[str, ...]
    examples: np.ndarray
    labels: tuple[str, ...]
    center: np.ndarray
    scale: np.ndarray
    n_neighbors: int
    settings: Mapping[str, Any] = field(default_factory=dict)

    def predict(self, features: Any) -> np.ndarray:
        """The predicted class of each row of `features`.

        Parameters
        ----------
        features : array_like
            (n_samples, n_features) or (n_features,) raw (not standardised) features.

        Returns
        -------
        numpy.ndarray
            (n_samples,) class labels (str). Votes tied between classes go to the class of
            the nearest of the tied neighbours.
        """
        distances = self.distances(features)
        if np.any(np.all(np.isinf(distances), axis=1)):
            raise ValueError("`features` shares no observed feature with the training data")
        return vote(distances, np.array(self.labels), self.n_neighbors)

    def distances(self, features: Any) -> np.ndarray:
        """(n_samples, n_examples) mean squared standardised difference to each example."""
        queries = as_features("features", features, self.center.size) - self.center
        return _distances(queries / self.scale, self.examples)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (NaN written as null)."""

        def plain(array: np.ndarray) -> Any:
            values = array.astype(object)
            values[np.isnan(array)] = None
            return values.tolist()

        return {
            "format": _FORMAT,
            "version": _VERSION,
            "classes": list(self.classes),
            "n_neighbors": self.n_neighbors,
            "settings": dict(self.settings),
            "center": plain(self.center),
            "scale": plain(self.scale),
            "labels": list(self.labels),
            "examples": plain(self.examples),
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> TextureClassifier:
        """Rebuild a classifier from `to_dict` output, checking its content."""
        if not isinstance(data, Mapping) or data.get("format") != _FORMAT:
            raise ValueError(f"not a texture classifier (no 'format': {_FORMAT!r})")
        version = data.get("version")
        if not isinstance(version, int) or version not in _READABLE_VERSIONS:
            raise ValueError(f"unsupported classifier version {data.get('version')!r}")
        missing = [
            key
            for key in ("classes", "n_neighbors", "center", "scale", "labels", "examples")
            if key not in data
        ]
        if missing:
            raise ValueError(f"texture classifier lacks {', '.join(missing)}")

        def array(key: str) -> np.ndarray:
            values = data[key]
            try:
                return np.array(values, dtype=np.float64)  # null -> nan
            except (TypeError, ValueError):
                raise ValueError(f"texture classifier: {key!r} is not numeric") from None

        examples = as_features("examples", array("examples"))
        center = as_finite_array("center", array("center"), ndim=1)
        scale = as_finite_array("scale", array("scale"), ndim=1)
        labels = tuple(str(label) for label in data["labels"])
        if not (center.size == scale.size == examples.shape[1]) or len(labels) != len(examples):
            raise ValueError("texture classifier: inconsistent sizes of its arrays")
        if np.any(scale <= 0):
            raise ValueError("texture classifier: 'scale' must be > 0")
        classes = tuple(sorted(set(labels)))
        if not isinstance(data["classes"], list) or tuple(data["classes"]) != classes:
            raise ValueError(
                f"texture classifier: 'classes' {data['classes']!r:.60} are not those of its "
                f"labels {list(classes)}"
            )
        n_neighbors = data["n_neighbors"]
        if not isinstance(n_neighbors, int) or not 1 <= n_neighbors <= len(labels):
            raise ValueError(f"texture classifier: bad 'n_neighbors' {n_neighbors!r}")
        return cls(
            classes=classes,
            examples=examples,
            labels=labels,
            center=center,
            scale=scale,
            n_neighbors=n_neighbors,
            settings=dict(data.get("settings") or {}),
        )

    def save(self, path: str | os.PathLike[str], *, overwrite: bool = False) -> None:
        """Write the classifier as JSON; refuse to replace a file unless `overwrite`."""
        write_text(path, json.dumps(self.to_dict(), allow_nan=False) + "\n", overwrite=overwrite)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> TextureClassifier:
        """Read a classifier written by `save`."""
        path = Path(path)
        if path.is_dir():
            raise ValueError(f"{path} is a folder, not a texture classifier file")
        if not path.is_file():
            raise FileNotFoundError(f"no such file: {path}")
        try:
            data = json.loads(path.read_text(encoding="utf-8-sig"))
        except (json.JSONDecodeError, UnicodeDecodeError) as error:
            raise ValueError(f"{path}: not a JSON file ({error})") from None
        except RecursionError:
            raise ValueError(f"{path}: nested too deeply to be a texture classifier") from None
        try:
            return cls.from_dict(data)
        except (TypeError, ValueError) as error:
            raise ValueError(f"{path}: {error}") from None


def fit_texture_classifier(
    features: Any,
    labels: Sequence[str],
    *,
    n_neighbors: int = 1,
    standardize: bool = True,
    settings: Mapping[str, Any] | None = None,
) -> TextureClassifier:
    """Fit a k-nearest-neighbour texture classifier.

    Parameters
    ----------
    features : array_like
        (n_examples, n_features) features, e.g. `texture_features` of each recording; NaN
        marks a feature not observed in that example.
    labels : sequence of str
        (n_examples,) the class of each example.
    n_neighbors : int
        k >= 1, the number of neighbours that vote.
    standardize : bool
        Scale each feature by its spread over the examples (the default). False keeps the
        features as they are (center 0, scale 1), which suits features that share one unit,
        such as band levels in dB.
    settings : mapping, optional
        JSON-serialisable description of how the features were made, stored with the model.

    Returns
    -------
    TextureClassifier

    Notes
    -----
    Each feature is standardised by the mean and standard deviation of the training set
    (NaN ignored; a constant feature keeps scale 1). The distance between two samples is
    the mean squared difference of their standardised features over the features both
    observed, so that examples recorded at a lower sampling rate or higher speed (fewer
    observed bands) can still be compared.

    Examples
    --------
    >>> model = fit_texture_classifier([[0.0, 0.0], [0.1, 0.2], [5.0, 5.0]], ["a", "a", "b"])
    >>> model.predict([[4.0, 4.5], [0.3, 0.0]]).tolist()
    ['b', 'a']
    """
    examples = as_features("features", features)
    labels = tuple(str(label) for label in labels)
    if len(labels) != examples.shape[0]:
        raise ValueError(f"`labels` has {len(labels)} entries for {examples.shape[0]} examples")
    if len(set(labels)) < 2:
        raise ValueError(
            f"`labels` must name at least 2 classes to tell apart, got only {sorted(set(labels))}"
        )
    if isinstance(n_neighbors, bool) or not isinstance(n_neighbors, int | np.integer):
        raise TypeError(f"`n_neighbors` must be an integer, got {n_neighbors!r}")
    if not 1 <= n_neighbors <= len(labels):
        raise ValueError(f"`n_neighbors` must lie in [1, {len(labels)}], got {n_neighbors}")
    if np.any(np.all(np.isnan(examples), axis=0)):
        raise ValueError("`features` has a column that is NaN in every example")
    if not isinstance(standardize, bool | np.bool_):
        raise TypeError(f"`standardize` must be a bool, got {standardize!r}")
    if standardize:
        center = np.nanmean(examples, axis=0)
        spread = np.nanstd(examples, axis=0)
        scale = np.where(spread > 0, spread, 1.0)
    else:
        center, scale = np.zeros(examples.shape[1]), np.ones(examples.shape[1])
    try:
        json.dumps(dict(settings or {}))
    except TypeError as error:
        raise TypeError(f"`settings` must be JSON-serialisable ({error})") from None
    return TextureClassifier(
        classes=tuple(sorted(set(labels))),
        examples=(examples - center) / scale,
        labels=labels,
        center=center,
        scale=scale,
        n_neighbors=int(n_neighbors),
        settings=dict(settings or {}),
    )
