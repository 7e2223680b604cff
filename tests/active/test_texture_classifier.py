"""k-NN texture classifier: predictions, NaN handling, JSON round trip, grouped validation."""

import json
from pathlib import Path

import numpy as np
import pytest

from taxel.active import (
    TextureClassifier,
    cross_validate_texture,
    fit_texture_classifier,
    texture_features,
    texture_signature,
)
from taxel.io import read_fabricslide

DATA = Path(__file__).resolve().parents[2].parent / "shared" / "data" / "fabricslide" / "fabric"
FEATURES = np.array([[0.0, 0.0, 10.0], [0.2, 0.1, 10.5], [4.0, 4.0, 10.0], [4.2, 3.9, 9.0]])
LABELS = ["silk", "silk", "wool", "wool"]


def test_standardisation_and_prediction():
    model = fit_texture_classifier(FEATURES, LABELS)
    assert model.classes == ("silk", "wool")
    np.testing.assert_allclose(model.center, [2.1, 2.0, 9.875])
    np.testing.assert_allclose(model.examples.mean(axis=0), 0.0, atol=1e-12)
    np.testing.assert_allclose(model.examples.std(axis=0), 1.0)
    assert model.predict([[3.5, 3.0, 10.0], [0.5, 0.5, 9.0]]).tolist() == ["wool", "silk"]
    assert model.predict([3.9, 4.1, 9.5]).tolist() == ["wool"]  # one sample as 1-D


def test_constant_feature_keeps_unit_scale():
    model = fit_texture_classifier([[1.0, 5.0], [2.0, 5.0]], ["a", "b"])
    np.testing.assert_array_equal(model.scale, [0.5, 1.0])


def test_votes_and_ties():
    features = [[0.0], [1.0], [1.1], [1.2], [10.0]]
    labels = ["a", "b", "b", "c", "c"]
    assert fit_texture_classifier(features, labels, n_neighbors=3).predict([[0.1]]) == ["b"]
    # a 1-1 tie between a and b: the nearest of the tied neighbours wins
    model = fit_texture_classifier([[0.0], [1.0]], ["a", "b"], n_neighbors=2)
    assert model.predict([[0.4], [0.6]]).tolist() == ["a", "b"]


def test_unobserved_features_are_skipped():
    features = [[0.0, 0.0, 0.0], [5.0, 5.0, 5.0], [0.1, 0.0, np.nan]]
    model = fit_texture_classifier(features, ["a", "b", "a"])
    # the query lacks the third feature; its first two place it with "b"
    assert model.predict([[5.0, 4.0, np.nan]]).tolist() == ["b"]
    with pytest.raises(ValueError, match="shares no observed feature"):
        model.predict([[np.nan, np.nan, np.nan]])


def test_json_round_trip(tmp_path):
    features = FEATURES.copy()
    features[1, 2] = np.nan
    settings = {"segment_length": 0.2, "band_edges": [10.0, 20.0]}
    model = fit_texture_classifier(features, LABELS, n_neighbors=3, settings=settings)
    path = tmp_path / "model.json"
    model.save(path)
    text = path.read_text()
    assert "NaN" not in text and json.loads(text)["examples"][1][2] is None
    loaded = TextureClassifier.load(path)
    assert loaded.labels == model.labels and loaded.n_neighbors == 3
    assert dict(loaded.settings) == settings
    np.testing.assert_array_equal(loaded.examples, model.examples)  # NaN where NaN
    np.testing.assert_array_equal(loaded.center, model.center)
    queries = np.array([[0.1, 0.3, 9.0], [3.0, 3.5, np.nan]])
    assert loaded.predict(queries).tolist() == model.predict(queries).tolist()
    # the same file saved again by an editor that writes a UTF-8 byte-order mark
    path.write_text(text, encoding="utf-8-sig")
    assert (
        TextureClassifier.load(path).predict(queries).tolist() == loaded.predict(queries).tolist()
    )


def test_save_refuses_to_overwrite(tmp_path):
    path = tmp_path / "model.json"
    path.write_text("precious")
    model = fit_texture_classifier(FEATURES, LABELS)
    with pytest.raises(FileExistsError, match="`path` '.*model.json' exists; pass overwrite=True"):
        model.save(path)
    assert path.read_text() == "precious"
    model.save(path, overwrite=True)
    assert TextureClassifier.load(path).labels == tuple(LABELS)


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("{", "not a JSON file"),
        ('{"format": "other"}', "not a texture classifier"),
        ('{"format": "taxel.texture_classifier", "version": 9}', "unsupported classifier version"),
        (
            '{"format": "taxel.texture_classifier", "version": 1}',
            "texture classifier lacks classes, n_neighbors",
        ),
    ],
)
def test_load_rejects_bad_files(tmp_path, content, message):
    path = tmp_path / "model.json"
    path.write_text(content)
    with pytest.raises(ValueError, match=f"model.json: {message}"):
        TextureClassifier.load(path)


def test_load_rejects_inconsistent_content(tmp_path):
    data = fit_texture_classifier(FEATURES, LABELS).to_dict()
    data["labels"] = data["labels"][:3]
    path = tmp_path / "model.json"
    path.write_text(json.dumps(data))
    with pytest.raises(ValueError, match="inconsistent sizes"):
        TextureClassifier.load(path)
    with pytest.raises(FileNotFoundError, match="no such file: .*absent.json"):
        TextureClassifier.load(tmp_path / "absent.json")


@pytest.mark.parametrize("classes", [[], ["wool", "silk"], ["silk", "wool", "felt"], "silkwool"])
def test_load_rejects_classes_other_than_its_labels(tmp_path, classes):
    data = fit_texture_classifier(FEATURES, LABELS).to_dict()
    assert data["classes"] == sorted(set(LABELS))
    data["classes"] = classes
    path = tmp_path / "model.json"
    path.write_text(json.dumps(data))
    with pytest.raises(
        ValueError, match=r"'classes' .* are not those of its labels \['silk', 'wool'\]"
    ):
        TextureClassifier.load(path)


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"labels": ["a"]}, ValueError, "`labels` has 1 entries for 4 examples"),
        ({"labels": ["a"] * 4}, ValueError, r"at least 2 classes to tell apart, got only \['a'\]"),
        ({"n_neighbors": 0}, ValueError, r"`n_neighbors` must lie in \[1, 4\], got 0"),
        ({"n_neighbors": 1.5}, TypeError, "`n_neighbors` must be an integer, got 1.5"),
        ({"features": [[np.inf] * 3] * 4}, ValueError, "must not hold infinite values"),
        ({"features": [[np.nan, 1.0]] * 4}, ValueError, "a column that is NaN in every"),
        ({"settings": {"f": object()}}, TypeError, "`settings` must be JSON-serialisable"),
    ],
)
def test_fit_errors(kwargs, error, message):
    arguments = {"features": FEATURES, "labels": LABELS, **kwargs}
    with pytest.raises(error, match=message):
        fit_texture_classifier(arguments.pop("features"), arguments.pop("labels"), **arguments)


def test_cross_validation_never_tests_on_training_examples():
    # each example has an identical twin with the other label in the other group: a model
    # that had seen the test example would be right, a held-out one is always wrong
    features = [[0.0], [0.0], [9.0], [9.0]]
    labels = ["a", "b", "c", "d"]
    result = cross_validate_texture(features, labels, groups=[1, 2, 1, 2])
    assert result.accuracy == 0.0
    assert result.predictions.tolist() == ["b", "a", "d", "c"]
    assert result.group_accuracy == {1: 0.0, 2: 0.0}
    assert result.confusion.sum() == 4 and np.trace(result.confusion) == 0


def test_cross_validation_confusion():
    features = [[0.0], [0.3], [5.0], [5.2], [0.4], [4.0]]
    labels = ["a", "a", "b", "b", "b", "a"]
    result = cross_validate_texture(features, labels, [0, 1, 0, 1, 2, 2])
    assert result.classes == ("a", "b")
    assert result.confusion.tolist() == [[1, 2], [1, 2]]  # worked out by hand
    assert result.accuracy == pytest.approx(3 / 6)
    with pytest.raises(ValueError, match="at least two groups"):
        cross_validate_texture(features, labels, [0] * 6)


@pytest.mark.skipif(not DATA.is_dir(), reason=f"FabricSlide data not found at {DATA}")
def test_real_fabrics_across_speeds():
    # train at 10 and 100 mm/s, classify at 50 mm/s: unseen speed, same fabrics
    def features(name):
        recording = read_fabricslide(DATA / name)
        signature = texture_signature(
            recording.readings, recording.time, recording.sliding_velocity
        )
        return texture_features(signature)

    fabrics = ["Denim", "Linen", "Canvas"]
    train = [f"{fabric}_F150_V{v}mmps_0.csv" for fabric in fabrics for v in (-10, -100)]
    model = fit_texture_classifier(
        [features(name) for name in train], [name.split("_")[0] for name in train]
    )
    tests = [f"{fabric}_F150_V-50mmps_0.csv" for fabric in fabrics]
    assert model.predict([features(name) for name in tests]).tolist() == fabrics


def test_a_file_nested_too_deeply_for_the_json_parser_is_a_value_error(tmp_path):
    from taxel.active import EdgeRadiusTable, ModelLibrary

    deep = tmp_path / "deep.json"
    deep.write_text("[" * 100_000 + "]" * 100_000)  # beyond the parser's recursion limit
    with pytest.raises(ValueError, match="nested too deeply to be a texture classifier"):
        TextureClassifier.load(deep)
    for kind in (EdgeRadiusTable, ModelLibrary):
        with pytest.raises(ValueError, match=r"`path` .*deep.json' is nested too deeply to be"):
            kind.load(deep)
