"""Files of the active procedures (tables, libraries, calibrations) that are corrupt."""

import json

import numpy as np
import pytest

from taxel.active import SECTION_DESCRIPTORS, EdgeRadiusTable, ModelLibrary, PadCalibration

N_DESCRIPTORS = len(SECTION_DESCRIPTORS)


def _table():
    return EdgeRadiusTable(
        radii=np.array([1e-3, 2e-3, 4e-3]),
        forces=np.array([12.0, 39.0]),
        reference_loads=np.array([1e3, 3e3]),
        intercepts=np.arange(3.0)[:, None, None] * np.ones((3, 2, N_DESCRIPTORS)),
        slopes=np.zeros((3, 2, N_DESCRIPTORS)),
        spreads=np.ones((2, N_DESCRIPTORS)),
        sensor="vhdta128",
        n_presses=6,
    )


def _library(names=("washer", "coin")):
    return ModelLibrary(
        names=names,
        templates=np.array([[1.0, 2.0], [3.0, 4.0]]),
        labels=("washer", "coin"),
        scales=np.ones(2),
        feature_names=("a", "b"),
        normal_force=15.0,
        step=1e-3,
    )


def _calibration():
    return PadCalibration(
        forces=np.array([0.5, 12.0, 39.0]),
        areas=np.full((3, 2), 1e-5),
        compressions=np.full((3, 2), 1e-4),
        sensor="vhdta128",
    )


@pytest.mark.parametrize(
    ("make", "key", "value", "match"),
    [
        (_table, "radii_m", "abc", "could not convert string to float"),
        (_table, "radii_m", [1e-3], "`radii` must hold at least 2 known radii, got 1"),
        (_table, "radii_m", [1e-3, 1e-3, 2e-3], "`radii` must be positive and increasing"),
        (_table, "intercepts", [[1, 2], [3]], "inhomogeneous"),
        (_table, "n_presses", None, "int"),
        (_table, "n_presses", 1e999, "infinity"),  # json writes it as Infinity
        (_library, "templates", 5, "not iterable"),
        (_library, "templates", [[1, 2], [3]], "inhomogeneous"),
        (_library, "normal_force_n", "abc", "could not convert"),
        (_library, "normal_force_n", None, "float"),
        (_library, "labels", 5, "not iterable"),
        (_calibration, "areas_m2", [[1], [1, 2]], "inhomogeneous"),
        (_calibration, "forces_n", "x", "could not convert"),
    ],
)
def test_a_corrupt_file_is_refused_naming_the_file_and_what_is_wrong(
    tmp_path, make, key, value, match
):
    saved = make()
    path = tmp_path / "file.json"
    data = saved.to_dict()
    data[key] = value
    path.write_text(json.dumps(data))
    with pytest.raises(ValueError, match=match) as refused:
        type(saved).load(path)
    assert str(refused.value).startswith(f"`path` {str(path)!r} is not ")
    assert "taxel can read" in str(refused.value)


@pytest.mark.parametrize("make", [_table, _library, _calibration])
def test_a_file_saved_with_a_byte_order_mark_is_read(tmp_path, make):
    # an editor on Windows may save UTF-8 with a byte-order mark, which is no part of JSON
    saved = make()
    path = tmp_path / "file.json"
    path.write_text(json.dumps(saved.to_dict()), encoding="utf-8-sig")
    assert type(saved).load(path).to_dict() == saved.to_dict()


def test_a_table_s_version_is_said_as_written(tmp_path):
    data = _table().to_dict()
    data["version"] = "2"  # text, not the number 2
    path = tmp_path / "table.json"
    path.write_text(json.dumps(data))
    with pytest.raises(ValueError, match="holds a version '2' table, this is version 2"):
        EdgeRadiusTable.load(path)


def test_a_library_naming_a_model_twice_is_refused():
    with pytest.raises(ValueError, match=r"`names` must name each model once, got \['washer'"):
        _library(names=("washer", "washer", "coin"))
