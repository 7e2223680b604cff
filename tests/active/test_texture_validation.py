"""Choosing the texture classifier's settings by grouped cross-validation, and nesting it."""

import numpy as np
import pytest

from taxel.active import (
    TextureModelChoice,
    choose_texture_model,
    cross_validate_texture,
    fit_texture_classifier,
    nested_cross_validate_texture,
)

GROUPS = [g for g in (1, 2, 3, 4) for _ in range(6)]
LABELS = ["a", "a", "a", "b", "b", "b"] * 4


def _sets(seed=0):
    rng = np.random.default_rng(seed)
    truth = np.array([0.0 if label == "a" else 5.0 for label in LABELS])
    good = truth[:, None] + rng.normal(0, 0.3, (24, 2))
    noise = rng.normal(0, 3.0, (24, 2))
    return {"noise": noise, "good": good}


def test_the_separating_feature_set_is_chosen_in_every_fold():
    result = nested_cross_validate_texture(_sets(), LABELS, GROUPS)
    assert result.accuracy == 1.0
    assert set(result.selected) == {1, 2, 3, 4}
    for choice in result.selected.values():
        assert isinstance(choice, TextureModelChoice)
        assert choice.features == "good" and choice.accuracy == 1.0
        assert len(choice.scores) == 2 * 2 * 3  # sets x standardise x k


def test_the_choice_for_a_group_is_made_without_it():
    sets = _sets(seed=4)
    # a feature set that is right on group 4 alone and noise elsewhere
    trap = sets["noise"].copy()
    in_four = np.array(GROUPS) == 4
    trap[in_four, 0] = [0.0 if label == "a" else 100.0 for label in np.array(LABELS)[in_four]]
    sets = {"trap": trap, "good": sets["good"]}
    result = nested_cross_validate_texture(sets, LABELS, GROUPS)
    assert result.selected[4].features == "good"
    keep = ~in_four
    alone = choose_texture_model(
        {name: values[keep] for name, values in sets.items()},
        np.array(LABELS)[keep].tolist(),
        np.array(GROUPS)[keep].tolist(),
    )
    assert alone == result.selected[4]


def test_ties_go_to_the_first_option():
    sets = _sets()
    choice = choose_texture_model(
        {"good": sets["good"], "copy": sets["good"]},
        LABELS,
        GROUPS,
        n_neighbors=(3, 1),
        standardize=(False, True),
    )
    assert (choice.features, choice.standardize, choice.n_neighbors) == ("good", False, 3)
    assert choice.scores[("copy", True, 1)] == 1.0


def test_scores_match_plain_cross_validation():
    sets = _sets(seed=2)
    choice = choose_texture_model(sets, LABELS, GROUPS)
    for (name, flag, k), score in choice.scores.items():
        plain = cross_validate_texture(sets[name], LABELS, GROUPS, n_neighbors=k, standardize=flag)
        assert score == pytest.approx(plain.accuracy)


def test_standardisation_can_be_switched_off():
    # feature 0 tells the classes apart by 1 unit, feature 1 is noise of 10 units
    features = [[0.0, 0.0], [0.1, 10.0], [1.0, 9.0], [1.1, 1.0]]
    labels = ["a", "a", "b", "b"]
    raw = fit_texture_classifier(features, labels, standardize=False)
    np.testing.assert_array_equal(raw.center, [0.0, 0.0])
    np.testing.assert_array_equal(raw.scale, [1.0, 1.0])
    np.testing.assert_array_equal(raw.examples, features)
    query = [[0.8, 9.9]]
    assert raw.predict(query).tolist() == ["a"]  # the noise, unscaled, dominates
    assert fit_texture_classifier(features, labels).predict(query).tolist() == ["b"]
    with pytest.raises(TypeError, match="`standardize` must be a bool"):
        fit_texture_classifier(features, labels, standardize="no")


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: choose_texture_model({}, LABELS, GROUPS), "non-empty mapping"),
        (
            lambda: choose_texture_model({"x": np.zeros((5, 1))}, LABELS, GROUPS),
            "must have the same length",
        ),
        (
            lambda: choose_texture_model(
                {"x": np.zeros((24, 1)), "y": np.zeros((23, 1))}, LABELS, GROUPS
            ),
            "differ in their number of examples",
        ),
        (
            lambda: choose_texture_model(_sets(), LABELS, GROUPS, n_neighbors=(0,)),
            "`n_neighbors` must be a non-empty sequence of integers >= 1",
        ),
        (
            lambda: choose_texture_model(_sets(), LABELS, GROUPS, n_neighbors=(30,)),
            "exceeds the examples of some training fold",
        ),
        (
            lambda: choose_texture_model(_sets(), LABELS, GROUPS, standardize=(1,)),
            "`standardize` must be a non-empty sequence of bools",
        ),
        (
            lambda: nested_cross_validate_texture(_sets(), LABELS, [1, 2] * 12),
            "needs at least three groups, got 2",
        ),
    ],
)
def test_errors(call, message):
    with pytest.raises(ValueError, match=message):
        call()
