"""The `progress` callback of the long procedures: called once per unit of work, and the
result the same with it or without it."""

import numpy as np
import pytest

from taxel.active import (
    build_edge_radius_table,
    build_model_library,
    calibrate_pad,
    corner_probing_trial,
    plane_probing_trial,
)


class _Calls(list):
    def __call__(self, done: int, total: int) -> None:
        self.append((done, total))


def _counted(total: int) -> list[tuple[int, int]]:
    return [(done, total) for done in range(1, total + 1)]


def test_plane_probing_tells_each_press():
    calls = _Calls()
    told = plane_probing_trial(n_probes=4, seed=2, progress=calls)
    assert calls == _counted(4)
    untold = plane_probing_trial(n_probes=4, seed=2)
    assert told.to_dict() == untold.to_dict()


def test_corner_probing_tells_each_press_on_the_three_faces():
    calls = _Calls()
    told = corner_probing_trial(probes_per_face=4, seed=1, progress=calls)
    assert calls == _counted(12)
    assert told.to_dict() == corner_probing_trial(probes_per_face=4, seed=1).to_dict()


def test_edge_radius_table_tells_each_edge():
    calls = _Calls()
    told = build_edge_radius_table([2e-3, 6e-3], orientations=2, progress=calls)
    assert calls == _counted(4)  # two radii at two orientations
    untold = build_edge_radius_table([2e-3, 6e-3], orientations=2)
    assert told.to_dict() == untold.to_dict()


def test_model_library_tells_each_canonical_pose():
    calls = _Calls()
    # a model named twice is touched once
    told = build_model_library(["coin", "pen", "coin"], rotations=2, progress=calls)
    assert calls == _counted(4)
    assert told.to_dict() == build_model_library(["coin", "pen"], rotations=2).to_dict()


def test_pad_calibration_tells_each_press():
    calls = _Calls()
    told = calibrate_pad("capacitive4x4", forces=(0.5, 2.0, 4.0), progress=calls)
    assert calls == _counted(told.areas.size)
    untold = calibrate_pad("capacitive4x4", forces=(0.5, 2.0, 4.0))
    np.testing.assert_array_equal(told.compressions, untold.compressions)


def test_progress_must_be_callable():
    with pytest.raises(TypeError, match="`progress` must be a callable"):
        plane_probing_trial(progress=True)  # type: ignore[arg-type]
