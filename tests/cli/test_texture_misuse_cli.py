"""``taxel texture classify`` given a model file someone edited, or not a model at all."""

import json

import numpy as np
import pytest

from taxel.cli import main

HEADER = "timestamp, proximity1, proximity2, " + ", ".join(f"channel{i}" for i in range(1, 17))


def _write_recording(path, period, velocity, seed):
    """A FabricSlide-like csv: 16 taxels over a grating of `period` [m], 35 Hz, 0.3 m travel."""
    rng = np.random.default_rng(seed)
    time = np.arange(0.0, 0.3 / abs(velocity), 1 / 35.0)
    waves = 6 * np.sin(2 * np.pi * velocity * time[:, None] / period + np.linspace(0, 2, 16))
    readings = np.round(120 + waves + rng.normal(0, 1.0, waves.shape)).astype(int)
    stamps = np.round(1000 + 1000 * time).astype(int)
    rows = [
        f"{stamp}, 0, 65535, " + ", ".join(map(str, row))
        for stamp, row in zip(stamps, readings, strict=True)
    ]
    path.write_text("\n".join([HEADER, *rows]) + "\n")


@pytest.fixture(scope="module")
def fitted(tmp_path_factory):
    """(model.json as a dict, a recording to classify, the folder to write models in)."""
    folder = tmp_path_factory.mktemp("texture")
    train = folder / "train"
    train.mkdir()
    for seed, (fabric, period, velocity) in enumerate(
        (fabric, period, velocity)
        for fabric, period in (("Ribbed", 0.02), ("Coarse", 0.06))
        for velocity in (-20, 20, 100)
    ):
        _write_recording(
            train / f"{fabric}_F150_V{velocity}mmps_0.csv", period, velocity / 1e3, seed
        )
    recording = folder / "Ribbed_F150_V-50mmps_1.csv"
    _write_recording(recording, 0.02, -0.05, 99)
    assert main(["texture", "fit", str(train), "--out", str(folder / "model.json")]) == 0
    return json.loads((folder / "model.json").read_text()), recording, folder


def _one_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    return err


@pytest.mark.parametrize(
    ("setting", "value", "message"),
    [
        ("per_taxel", "no", 'its per_taxel must be true or false, got "no"'),
        (
            "per_taxel",
            False,
            "its settings give 7 features per recording, but it was fitted on 119",
        ),
        (
            "band_edges",
            [10.0, 20.0],
            "its settings give 17 features per recording, but it was fitted",
        ),
        ("reader", "other", "fitted on 'other' recordings; taxel texture reads FabricSlide ones"),
    ],
)
def test_a_model_whose_settings_do_not_hold_is_named(fitted, capsys, setting, value, message):
    data, recording, folder = fitted
    edited = folder / f"edited_{setting}_{value}.json"
    edited.write_text(json.dumps({**data, "settings": {**data["settings"], setting: value}}))
    assert main(["texture", "classify", str(recording), "--model", str(edited)]) == 2
    err = _one_line(capsys)
    assert err.startswith(f"taxel texture classify: error: --model {edited}: {message}")
    assert "`" not in err


def test_a_folder_given_as_the_model_names_the_flag(fitted, capsys):
    _, recording, folder = fitted
    assert main(["texture", "classify", str(recording), "--model", str(folder)]) == 2
    assert f"error: --model {folder} is a folder, not a texture classifier file" in _one_line(
        capsys
    )


def test_a_recording_too_short_is_named_without_the_librarys_words(fitted, capsys):
    _, recording, folder = fitted
    short = folder / "Ribbed_F150_V-50mmps_2.csv"
    short.write_text("\n".join(recording.read_text().splitlines()[:3]) + "\n")
    assert main(["texture", "classify", str(short), "--model", str(folder / "model.json")]) == 2
    err = _one_line(capsys)
    assert (
        f"error: {short}: it holds 2 readings of each taxel; a recording needs at least 16" in err
    )
