"""A model library of other features than recognition's touches is refused when given."""

import numpy as np
import pytest

from taxel.active import ModelLibrary, Recognition, SimulatedFinger, make_model
from taxel.active._recognition import DESCRIPTOR_NAMES
from taxel.frames import make_pose


def test_a_library_of_other_features_is_refused_naming_it_before_any_touch(tmp_path):
    library = ModelLibrary(
        names=("washer", "coin"),
        templates=np.array([[1.0, 2.0], [3.0, 4.0]]),
        labels=("washer", "coin"),
        scales=np.ones(2),
        feature_names=("a", "b"),
        normal_force=15.0,
        step=0.02,
    )
    for given in (library, library.save(tmp_path / "library.json")):
        with pytest.raises(ValueError, match=r"`library` holds the features a, b \(2\), not"):
            Recognition(given)


def test_a_library_of_recognition_s_features_is_taken():
    start = make_pose(np.diag([1.0, -1.0, -1.0]), [0.0, 0.0, 0.01])
    finger = SimulatedFinger("vhdta128", [make_model("washer")], start)
    n = len(DESCRIPTOR_NAMES)
    library = ModelLibrary(
        names=("washer", "coin"),
        templates=np.arange(2.0 * n).reshape(2, n),
        labels=("washer", "coin"),
        scales=np.ones(n),
        feature_names=DESCRIPTOR_NAMES,
        normal_force=15.0,
        step=0.02,
    )
    result = Recognition(library, stop_early=False).run(finger)
    assert result.n_touches == 3
    assert {name for name, _, _ in result.candidates} == {"washer", "coin"}
