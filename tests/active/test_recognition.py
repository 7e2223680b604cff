"""Recognition against a library of object models (Ellis seed, introduction)."""

import json
import math

import numpy as np
import pytest

from taxel.active import (
    MODEL_NAMES,
    TOUCH_FEATURES,
    ModelLibrary,
    Recognition,
    SimulatedFinger,
    build_model_library,
    describe_models,
    make_model,
    recognize_object,
)
from taxel.active._recognition import touch_descriptor
from taxel.active._touch_features import touch_vector
from taxel.frames import make_pose
from taxel.sensor import make_sensor

DOWN = np.diag([1.0, -1.0, -1.0])
MODELS = ("washer", "coin", "pen")


@pytest.fixture(scope="module")
def library():
    return build_model_library(MODELS, rotations=2)


def test_the_library_holds_the_seven_models():
    assert MODEL_NAMES == (
        "washer", "coin", "key blank", "bolt head", "box corner", "pen", "can"
    )  # fmt: skip
    assert set(describe_models()) == set(MODEL_NAMES)
    can = make_model("can", position=(0.05, 0.0))
    # the rim's crest is 26 mm from the can's axis, its top 115 mm up
    assert can.ray_distances(np.array([[0.076, 0.0, 0.2]]), [0, 0, -1])[0] == pytest.approx(
        0.2 - 0.115
    )
    key = make_model("key blank", angle=math.pi / 2)
    origins = np.array([[0.0, -0.016, 0.01], [0.0, 0.02, 0.01]])  # the bow's hole, the shank
    distances = key.ray_distances(origins, [0, 0, -1])
    assert math.isinf(distances[0])
    assert distances[1] == pytest.approx(0.008)


@pytest.mark.parametrize(
    ("name", "seed", "touches"), [("washer", 4, 1), ("coin", 5, 3), ("pen", 6, 3)]
)
def test_models_at_random_poses_are_recognised(library, name, seed, touches):
    result = recognize_object(name, library=library, rng=seed)
    assert result.name == name
    # this washer is told by its first touch; this coin's and pen's first touches leave no
    # model within the library's spread of one touch (0.018 with two canonical poses each)
    assert result.n_touches == touches
    assert result.candidates[0][0] == name
    assert sum(c[1] for c in result.candidates) == pytest.approx(1.0)
    assert result.score > 0.5
    json.dumps(result.to_dict())


def test_recognition_stops_when_the_first_touch_leaves_one_model(library):
    # the radius: the largest distance of a canonical touch from its model's other one
    assert Recognition(library).first_touch_radius == pytest.approx(0.0177, abs=1e-4)
    early = recognize_object("washer", library=library, rng=4)
    assert early.n_touches == 1 and early.first_touch_radius == pytest.approx(0.0177, abs=1e-4)
    (best, score, distance), (_, _, runner_up) = early.candidates[:2]
    assert best == "washer" and distance < 0.0177 < runner_up  # only the washer is plausible
    assert score > 0.98 and runner_up > 10.0
    assert early.message == "washer (decided by the first touch: the only model within 0.02 of it)"
    assert np.isnan(early.descriptor[len(TOUCH_FEATURES) :]).all()  # touches 2, 3 not made
    assert [s.action for s in early.steps][-1] == "return to the start"
    assert early.to_dict()["first_touch_radius"] == pytest.approx(0.0177, abs=1e-4)
    full = recognize_object("washer", library=library, rng=4, stop_early=False)
    assert full.n_touches == 3 and full.name == "washer"
    assert np.isnan(full.first_touch_radius) and full.to_dict()["first_touch_radius"] is None


def test_the_first_touch_radius_is_the_library_s_own_spread():
    from taxel.active._recognition import first_touch_library, first_touch_radius

    library = ModelLibrary.from_templates(
        [[1.0, 10.0, 5.0], [1.0, 12.0, 5.0], [0.0, np.nan, 5.0]],
        ["ring", "ring", "nothing"],
        ("touch1:present", "touch1:major_axis", "min23:present"),
        normal_force=10.0,
        step=0.02,
    )
    first = first_touch_library(library)
    assert first.feature_names == ("touch1:present", "touch1:major_axis")
    # the two rings differ by 2 / sqrt(2) spreads in one of two features: (2 + 0) / 2 = 1;
    # "nothing" has one canonical touch, so it sets no radius
    assert first_touch_radius(first) == pytest.approx(1.0)
    assert np.isnan(first_touch_radius(first_touch_library(library.__class__(
        names=("a", "b"), templates=[[1.0], [2.0]], labels=("a", "b"), scales=[1.0],
        feature_names=("touch1:present",), normal_force=1.0, step=0.01,
    ))))  # fmt: skip
    assert (
        first_touch_library(
            ModelLibrary.from_templates(
                [[1.0], [2.0]], ["a", "b"], ("min23:present",), normal_force=1.0, step=0.01
            )
        )
        is None
    )


def test_touch_vectors_and_descriptors():
    empty = touch_vector(None)
    assert empty.shape == (len(TOUCH_FEATURES),)
    assert empty[0] == 0.0 and np.isnan(empty[1:]).all()
    first = np.arange(len(TOUCH_FEATURES), dtype=float)
    descriptor = touch_descriptor([first, first + 2, first - 1])
    n = len(TOUCH_FEATURES)
    assert descriptor[:n].tolist() == first.tolist()
    assert descriptor[n : 2 * n].tolist() == (first - 1).tolist()
    assert descriptor[2 * n :].tolist() == (first + 2).tolist()
    # an absent second touch leaves the other's values; absent in both stays NaN
    descriptor = touch_descriptor([first, empty, empty])
    assert descriptor[n] == 0.0 and np.isnan(descriptor[n + 1])


def test_matching_ranks_by_the_nearest_template(tmp_path):
    library = ModelLibrary.from_templates(
        [[1.0, 10.0], [1.0, 12.0], [0.0, np.nan]],
        ["ring", "ring", "nothing"],
        ("touch1:present", "touch1:major_axis"),
        normal_force=10.0,
        step=0.02,
    )
    # spreads: the ring's major axis varies by sqrt(2); presence is floored at 0.25
    assert library.scales.tolist() == pytest.approx([0.25, math.sqrt(2)])
    ranked = library.match([1.0, 11.0])
    assert [name for name, _, _ in ranked] == ["ring", "nothing"]
    # distance to the nothing template: presence differs by 4 spreads (capped at 16), the
    # major axis is seen in one only (9): mean 12.5
    assert ranked[1][2] == pytest.approx(12.5)
    assert ranked[0][2] == pytest.approx(0.25)
    loaded = ModelLibrary.load(library.save(tmp_path / "library.json"))
    assert loaded.match([1.0, 11.0]) == ranked


def test_bad_commands_leave_the_finger_at_its_start(library):
    sensor = make_sensor("vhdta128")
    start = make_pose(DOWN, [0.0, 0.0, 0.01])
    finger = SimulatedFinger(sensor, [make_model("washer", position=(0.3, 0.0))], start)
    with pytest.raises(ValueError, match="no touch found contact"):
        Recognition(library).run(finger)
    assert np.array_equal(finger.pose, start)
    with pytest.raises(ValueError, match="`name` must be one of washer"):
        recognize_object("spoon", library=library)
    with pytest.raises(TypeError, match="`library` must be a ModelLibrary or its file, got 3"):
        Recognition(3)
    with pytest.raises(TypeError, match="`probe` must be a Probe, got 'finger'"):
        Recognition(library).run("finger")
    with pytest.raises(ValueError, match="`rotations` must be a whole number, got 2.5"):
        build_model_library(["washer", "pen"], rotations=2.5)
    with pytest.raises(ValueError, match="`models` must name at least 2 models"):
        build_model_library(["washer"])
    with pytest.raises(ValueError, match="`position_error` must be >= 0, got -1"):
        build_model_library(["washer", "pen"], position_error=-1.0)
    other = ModelLibrary.from_templates(
        library.templates, library.labels, library.feature_names, normal_force=15.0,
        step=0.02, sensor="other",
    )  # fmt: skip
    with pytest.raises(ValueError, match="was made on sensor 'other'"):
        Recognition(other).run(finger)
    # a touch the finger refuses (a force beyond its limit) is an error, not "no contact"
    weak = SimulatedFinger(sensor, [make_model("washer")], start, max_force=10.0)
    with pytest.raises(ValueError, match="`normal_force` must be <= the finger's limit 10 N"):
        Recognition(library).run(weak)
    assert np.array_equal(weak.pose, start)
    with pytest.raises(ValueError, match="the finger's limit 12.8 N, got 15"):
        build_model_library(["washer", "pen"], sensor="photoelastic64")
