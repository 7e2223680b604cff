"""Grouped cross-validation of the texture classifier, and choosing its settings by it.

Every scheme here holds out whole groups of recordings (all those at one sliding speed, one
force setting, ...), so that a recording is never both trained and tested on and the
held-out condition is unseen. A choice among feature sets, k and standardisation is made by
`choose_texture_model` on the training groups alone; `nested_cross_validate_texture` repeats
that choice inside every outer fold, so the accuracy it reports is not that of a choice
made on the test data.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel.active._texture_classifier import as_features, fit_texture_classifier, vote

__all__ = [
    "CrossValidation",
    "TextureModelChoice",
    "choose_texture_model",
    "cross_validate_texture",
    "nested_cross_validate_texture",
]


@dataclass(frozen=True)
class CrossValidation:
    """Outcome of a grouped cross-validation.

    Attributes
    ----------
    classes : tuple of str
        Row and column order of `confusion`.
    predictions : numpy.ndarray
        (n_examples,) predicted label of each example, from the fold that held it out.
    accuracy : float
        Fraction of examples predicted right.
    confusion : numpy.ndarray
        (n_classes, n_classes) counts: row = true class, column = predicted class.
    group_accuracy : dict
        Accuracy on each held-out group.
    selected : dict
        For a nested cross-validation, what was chosen on the other groups to predict each
        held-out group (a `TextureModelChoice`); empty otherwise.
    """

    classes: tuple[str, ...]
    predictions: np.ndarray
    accuracy: float
    confusion: np.ndarray
    group_accuracy: dict[Any, float]
    selected: dict[Any, Any] = field(default_factory=dict)


def cross_validate_texture(
    features: Any,
    labels: Sequence[str],
    groups: Sequence[Any],
    *,
    n_neighbors: int = 1,
    standardize: bool = True,
) -> CrossValidation:
    """Leave-one-group-out cross-validation of `fit_texture_classifier`.

    Parameters
    ----------
    features : array_like
        (n_examples, n_features).
    labels : sequence of str
        (n_examples,) true classes.
    groups : sequence
        (n_examples,) a group key per example (e.g. the sliding speed); each group is held
        out in turn, and the model fitted on all the others predicts it, so no example is
        ever in the training set of its own prediction.
    n_neighbors : int
        k of the classifier.
    standardize : bool
        Whether the classifier standardises the features (see `fit_texture_classifier`).

    Returns
    -------
    CrossValidation

    Examples
    --------
    >>> result = cross_validate_texture(
    ...     [[0.0], [0.2], [5.0], [5.1]], ["a", "a", "b", "b"], [1, 2, 1, 2])
    >>> result.accuracy, result.confusion.tolist()
    (1.0, [[2, 0], [0, 2]])
    """
    examples = as_features("features", features)
    labels_array, keys, unique = check_groups(examples, labels, groups)
    predictions = np.empty(len(keys), dtype=object)
    for key in unique:
        held = np.array([other == key for other in keys])
        model = fit_texture_classifier(
            examples[~held],
            labels_array[~held].tolist(),
            n_neighbors=n_neighbors,
            standardize=standardize,
        )
        predictions[held] = model.predict(examples[held])
    return summarise(labels_array, predictions, keys, unique)


def check_groups(
    examples: np.ndarray, labels: Sequence[str], groups: Sequence[Any]
) -> tuple[np.ndarray, list[Any], list[Any]]:
    """Labels as an array, the group keys, and the distinct groups in a stable order."""
    labels_array = np.array([str(label) for label in labels])
    keys = list(groups)
    if not (len(labels_array) == len(keys) == examples.shape[0]):
        raise ValueError("`features`, `labels` and `groups` must have the same length")
    unique = sorted(set(keys), key=lambda key: (str(type(key)), key))
    if len(unique) < 2:
        raise ValueError(f"`groups` must hold at least two groups, got {len(unique)}")
    return labels_array, keys, unique


def summarise(
    labels: np.ndarray,
    predictions: np.ndarray,
    keys: list[Any],
    unique: list[Any],
    selected: dict[Any, Any] | None = None,
) -> CrossValidation:
    """Accuracy, confusion matrix and per-group accuracy of held-out predictions."""
    group_accuracy = {}
    for key in unique:
        held = np.array([other == key for other in keys])
        group_accuracy[key] = float(np.mean(predictions[held] == labels[held]))
    classes = tuple(sorted(set(labels.tolist())))
    index = {label: position for position, label in enumerate(classes)}
    confusion = np.zeros((len(classes), len(classes)), dtype=np.int64)
    for true, predicted in zip(labels, predictions, strict=True):
        confusion[index[true], index[predicted]] += 1
    accuracy = float(np.trace(confusion) / len(keys))
    return CrossValidation(
        classes, predictions.astype(str), accuracy, confusion, group_accuracy, selected or {}
    )


@dataclass(frozen=True)
class TextureModelChoice:
    """The features, k and standardisation that cross-validated best on some data.

    Attributes
    ----------
    features : str
        Name of the chosen candidate feature set.
    n_neighbors : int
        The chosen k.
    standardize : bool
        Whether the chosen classifier standardises the features.
    accuracy : float
        Its leave-one-group-out accuracy on the data it was chosen on (an optimistic
        figure: it is the best of several).
    scores : dict
        Leave-one-group-out accuracy of every combination tried, keyed by
        ``(features, standardize, n_neighbors)``.
    """

    features: str
    n_neighbors: int
    standardize: bool
    accuracy: float
    scores: dict[tuple[str, bool, int], float]


def _check_candidates(candidates: Mapping[str, Any]) -> dict[str, np.ndarray]:
    if not isinstance(candidates, Mapping) or not candidates:
        raise ValueError("`candidates` must be a non-empty mapping of name -> features")
    checked = {
        str(name): as_features(f"candidates[{name!r}]", value)
        for name, value in candidates.items()
    }
    sizes = {name: array.shape[0] for name, array in checked.items()}
    if len(set(sizes.values())) > 1:
        raise ValueError(f"the candidate feature sets differ in their number of examples: {sizes}")
    return checked


def _check_options(n_neighbors: Sequence[int], standardize: Sequence[bool]) -> None:
    ks = list(n_neighbors)
    if not ks or any(
        isinstance(k, bool) or not isinstance(k, int | np.integer) or k < 1 for k in ks
    ):
        raise ValueError(f"`n_neighbors` must be a non-empty sequence of integers >= 1, got {ks}")
    flags = list(standardize)
    if not flags or any(not isinstance(flag, bool | np.bool_) for flag in flags):
        raise ValueError(f"`standardize` must be a non-empty sequence of bools, got {flags}")


def choose_texture_model(
    candidates: Mapping[str, Any],
    labels: Sequence[str],
    groups: Sequence[Any],
    *,
    n_neighbors: Sequence[int] = (1, 3, 5),
    standardize: Sequence[bool] = (True, False),
) -> TextureModelChoice:
    """Choose the feature set, k and standardisation by leave-one-group-out accuracy.

    Parameters
    ----------
    candidates : mapping of str to array_like
        Named feature sets, each (n_examples, n_features_of_that_set), rows in the same
        order (the same recordings).
    labels : sequence of str
        (n_examples,) true classes.
    groups : sequence
        (n_examples,) group key of each example; each group is held out in turn.
    n_neighbors : sequence of int
        The values of k tried.
    standardize : sequence of bool
        The standardisation options tried.

    Returns
    -------
    TextureModelChoice
        The combination of highest accuracy; among equals, the first in the order
        candidates (as given), then `standardize`, then `n_neighbors`, so list the
        preferred (simplest) options first.

    Examples
    --------
    >>> noisy = [[0.0, 9.0], [0.1, 0.0], [5.0, 0.5], [5.2, 9.5]]
    >>> clean = [[0.0], [0.1], [5.0], [5.2]]
    >>> choice = choose_texture_model(
    ...     {"noisy": noisy, "clean": clean}, ["a", "a", "b", "b"], [1, 2, 1, 2],
    ...     n_neighbors=(1,))
    >>> choice.features, choice.n_neighbors, choice.accuracy
    ('clean', 1, 1.0)
    """
    sets = _check_candidates(candidates)
    _check_options(n_neighbors, standardize)
    first = next(iter(sets.values()))
    labels_array, keys, unique = check_groups(first, labels, groups)
    ks = [int(k) for k in n_neighbors]
    if max(ks) > len(keys) - max(sum(other == key for other in keys) for key in unique):
        raise ValueError(
            f"`n_neighbors` up to {max(ks)} exceeds the examples of some training fold"
        )
    scores: dict[tuple[str, bool, int], float] = {}
    for name, examples in sets.items():
        for flag in standardize:
            right = dict.fromkeys(ks, 0)
            for key in unique:
                held = np.array([other == key for other in keys])
                model = fit_texture_classifier(
                    examples[~held], labels_array[~held].tolist(), standardize=bool(flag)
                )
                distances = model.distances(examples[held])
                for k in ks:
                    predicted = vote(distances, np.array(model.labels), k)
                    right[k] += int(np.sum(predicted == labels_array[held]))
            for k in ks:
                scores[(name, bool(flag), k)] = right[k] / len(keys)
    best = max(scores.values())
    name, flag, k = next(combination for combination, score in scores.items() if score == best)
    return TextureModelChoice(name, k, flag, best, scores)


def nested_cross_validate_texture(
    candidates: Mapping[str, Any],
    labels: Sequence[str],
    groups: Sequence[Any],
    *,
    n_neighbors: Sequence[int] = (1, 3, 5),
    standardize: Sequence[bool] = (True, False),
) -> CrossValidation:
    """Leave-one-group-out cross-validation with the settings chosen inside each fold.

    Parameters
    ----------
    candidates, labels, groups, n_neighbors, standardize
        As for `choose_texture_model`; at least three groups.

    Returns
    -------
    CrossValidation
        Its `selected` maps each held-out group to the `TextureModelChoice` made, by
        leave-one-group-out over the remaining groups only, for predicting it.

    Notes
    -----
    For each outer group g: `choose_texture_model` runs on the examples outside g (its own
    folds hold out one of those groups at a time), the chosen classifier is fitted on all
    examples outside g and predicts g. No example of g takes part in the choice, so the
    accuracy is an honest estimate for the whole procedure, choice included.

    Examples
    --------
    >>> clean = [[0.0], [0.1], [0.2], [5.0], [5.2], [5.1]]
    >>> result = nested_cross_validate_texture(
    ...     {"clean": clean}, ["a", "a", "a", "b", "b", "b"], [1, 2, 3, 1, 2, 3],
    ...     n_neighbors=(1,), standardize=(True,))
    >>> result.accuracy, result.selected[1].features
    (1.0, 'clean')
    """
    sets = _check_candidates(candidates)
    _check_options(n_neighbors, standardize)
    first = next(iter(sets.values()))
    labels_array, keys, unique = check_groups(first, labels, groups)
    if len(unique) < 3:
        raise ValueError(f"nested cross-validation needs at least three groups, got {len(unique)}")
    predictions = np.empty(len(keys), dtype=object)
    selected = {}
    for key in unique:
        held = np.array([other == key for other in keys])
        choice = choose_texture_model(
            {name: examples[~held] for name, examples in sets.items()},
            labels_array[~held].tolist(),
            [other for other, out in zip(keys, held, strict=True) if not out],
            n_neighbors=n_neighbors,
            standardize=standardize,
        )
        model = fit_texture_classifier(
            sets[choice.features][~held],
            labels_array[~held].tolist(),
            n_neighbors=choice.n_neighbors,
            standardize=choice.standardize,
        )
        predictions[held] = model.predict(sets[choice.features][held])
        selected[key] = choice
    return summarise(labels_array, predictions, keys, unique, selected)
