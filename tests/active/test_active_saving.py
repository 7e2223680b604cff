"""Builds that save their result check the file first: refused before the work, not after."""

import pytest

from taxel.active import build_edge_radius_table, build_model_library


def _edge_table(path, progress):
    return build_edge_radius_table(
        [2e-3, 6e-3], sensor="resistive16", orientations=2, path=path, progress=progress
    )


def _library(path, progress):
    return build_model_library(
        ["washer", "pen"], sensor="resistive16", rotations=1, path=path, progress=progress
    )


@pytest.mark.parametrize("build", [_edge_table, _library])
def test_an_existing_file_is_neither_overwritten_nor_built_for(tmp_path, build):
    path = tmp_path / "saved.json"
    path.write_text('{"mine": true}')
    done = []
    with pytest.raises(FileExistsError):
        build(path, lambda count, total: done.append(count))
    assert done == []  # refused before the first press
    assert path.read_text() == '{"mine": true}'


@pytest.mark.parametrize("build", [_edge_table, _library])
@pytest.mark.parametrize("name", ["missing/table.json", "."])
def test_a_file_that_cannot_be_written_is_refused_before_building(tmp_path, build, name):
    done = []
    with pytest.raises(ValueError, match="`path`"):
        build(tmp_path / name, lambda count, total: done.append(count))
    assert done == []
