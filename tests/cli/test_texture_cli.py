"""``taxel texture fit`` and ``taxel texture classify`` on small synthetic recordings."""

import json
from pathlib import Path

import numpy as np
import pytest

from taxel.active import TextureClassifier, texture_features, texture_signature
from taxel.cli import main
from taxel.cli._texture import _features
from taxel.io import read_fabricslide

HEADER = "timestamp, proximity1, proximity2, " + ", ".join(f"channel{i}" for i in range(1, 17))
PERIODS = {"Ribbed": 0.02, "Coarse": 0.06}  # spatial period of each fake fabric [m]


def _recording(path, period, velocity, seed):
    """A FabricSlide-like csv: 16 taxels over a grating of `period`, 35 Hz, 0.3 m travel."""
    rng = np.random.default_rng(seed)
    time = np.arange(0.0, 0.3 / abs(velocity), 1 / 35.0)
    position = velocity * time
    phase = np.linspace(0, 2, 16)
    waves = 6 * np.sin(2 * np.pi * position[:, None] / period + phase)
    readings = np.round(120 + waves + rng.normal(0, 1.0, waves.shape))
    stamps = np.round(1000 + 1000 * time).astype(int)
    rows = [
        f"{stamp}, 0, 65535, " + ", ".join(str(int(value)) for value in row)
        for stamp, row in zip(stamps, readings, strict=True)
    ]
    path.write_text("\n".join([HEADER, *rows]) + "\n")
    return path


@pytest.fixture
def folders(tmp_path):
    train, test = tmp_path / "train", tmp_path / "test"
    train.mkdir()
    test.mkdir()
    seed = 0
    for fabric, period in PERIODS.items():
        for velocity in (-20, 20, 100):
            seed += 1
            _recording(
                train / f"{fabric}_F150_V{velocity}mmps_0.csv", period, velocity / 1e3, seed
            )
        seed += 1
        _recording(test / f"{fabric}_F150_V-50mmps_1.csv", period, -0.05, seed)
    return train, test


def test_fit_then_classify(folders, tmp_path, capsys):
    train, test = folders
    model_path = tmp_path / "model.json"
    assert main(["texture", "fit", str(train), "--out", str(model_path)]) == 0
    assert "fitted 6 recordings of 2 classes (Coarse 3, Ribbed 3)" in capsys.readouterr().out
    model = TextureClassifier.load(model_path)
    assert model.classes == ("Coarse", "Ribbed")
    assert model.settings["reader"] == "fabricslide"

    files = sorted(str(path) for path in test.iterdir())
    assert main(["texture", "classify", *files, "--model", str(model_path)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines == [f"{files[0]}\tCoarse", f"{files[1]}\tRibbed"]

    assert main(["texture", "classify", *files, "--model", str(model_path), "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert rows == [
        {"file": files[0], "predicted": "Coarse"},
        {"file": files[1], "predicted": "Ribbed"},
    ]
    # a folder stands for the recordings in it; one without any is named
    assert main(["texture", "classify", str(test), "--model", str(model_path)]) == 0
    assert capsys.readouterr().out.splitlines() == lines
    assert main(["texture", "classify", str(tmp_path), "--model", str(model_path)]) == 2
    assert _one_line_error(capsys) == (
        f"taxel texture classify: error: FILE {tmp_path}: holds no FabricSlide recording "
        "(<Fabric>_F*_V*mmps_*.csv)\n"
    )


def test_fit_refuses_to_overwrite_unless_forced(folders, tmp_path, capsys):
    train, _ = folders
    model_path = tmp_path / "model.json"
    model_path.write_text("keep me")
    assert main(["texture", "fit", str(train), "--out", str(model_path)]) == 2
    error = capsys.readouterr().err
    expected = f"--out '{model_path}' exists; pass --overwrite to replace it"
    assert error == f"taxel texture fit: error: {expected}\n"
    assert model_path.read_text() == "keep me"
    assert main(["texture", "fit", str(train), "--out", str(model_path), "--overwrite"]) == 0
    assert TextureClassifier.load(model_path).n_neighbors == 1


def test_fit_never_writes_over_a_recording_and_reads_a_folder_once(folders, tmp_path, capsys):
    train, _ = folders
    recording = train / "Ribbed_F150_V20mmps_0.csv"
    kept = recording.read_text()
    assert main(["texture", "fit", str(train), "--out", str(recording), "--overwrite"]) == 2
    assert "--out must name a .json file" in _one_line_error(capsys)
    assert recording.read_text() == kept
    folder = tmp_path / "model.json"
    folder.mkdir()
    assert main(["texture", "fit", str(train), "--out", str(folder), "--overwrite"]) == 2
    assert "is a folder; name a file" in _one_line_error(capsys)
    assert main(["texture", "fit", str(train), str(train), "--out", str(tmp_path / "m.json")]) == 0
    assert "fitted 6 recordings" in capsys.readouterr().out


def _one_line_error(capsys):
    captured = capsys.readouterr()
    assert captured.err.count("\n") == 1 and "Traceback" not in captured.err
    return captured.err


def test_errors_are_one_line(folders, tmp_path, capsys):
    train, test = folders
    model_path = tmp_path / "model.json"
    assert main(["texture", "fit", str(tmp_path / "absent"), "--out", str(model_path)]) == 2
    assert _one_line_error(capsys) == (
        f"taxel texture fit: error: DIR {tmp_path / 'absent'}: no such folder\n"
    )
    with pytest.raises(SystemExit) as stop:  # argparse's own usage errors
        main(["texture", "fit", str(train), "--out", str(model_path), "--neighbors", "0"])
    assert stop.value.code == 2
    assert "--neighbors: must be >= 1, got 0" in _one_line_error(capsys)

    # each recording travels 0.3 m, 0.24 m after trimming: no room for a 0.5 m segment
    code = main(
        ["texture", "fit", str(train), "--out", str(model_path), "--segment-length", "0.5"]
    )
    assert code == 2
    error = _one_line_error(capsys)
    assert "_F150_V" in error and "--segment-length must be at most the record's travel" in error
    assert not model_path.exists()

    main(["texture", "fit", str(train), "--out", str(model_path)])
    capsys.readouterr()
    broken = test / "Ribbed_F150_V-50mmps_2.csv"
    broken.write_text(HEADER + "\n1000, 0, 65535, 1, 2\n")
    code = main(["texture", "classify", str(broken), "--model", str(model_path)])
    assert code == 2
    assert "Ribbed_F150_V-50mmps_2.csv, line 2: ragged row: 5 fields" in _one_line_error(capsys)
    code = main(["texture", "classify", str(broken), "--model", str(tmp_path / "none.json")])
    assert code == 2
    assert _one_line_error(capsys) == (
        f"taxel texture classify: error: --model {tmp_path / 'none.json'}: no such file\n"
    )
    not_a_model = tmp_path / "bad.json"
    not_a_model.write_text("[1, 2]")
    code = main(["texture", "classify", str(broken), "--model", str(not_a_model)])
    assert code == 2
    assert "not a texture classifier" in _one_line_error(capsys)


def test_usage_errors_exit_2(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["texture"])
    assert stop.value.code == 2
    assert "required: ACTION" in _one_line_error(capsys)
    with pytest.raises(SystemExit) as stop:
        main(["texture", "classify", "x.csv"])
    assert stop.value.code == 2
    assert "--model" in _one_line_error(capsys)


def test_feature_options_are_stored_and_reused(folders, tmp_path, capsys):
    train, test = folders
    files = sorted(str(path) for path in test.iterdir())
    default = tmp_path / "default.json"
    assert main(["texture", "fit", str(train), "--out", str(default)]) == 0
    stored = json.loads(default.read_text())
    assert stored["version"] == 2
    assert stored["settings"]["normalization"] == "load"
    assert stored["settings"]["decorrelate_load"] is True
    assert stored["settings"]["per_taxel"] is True
    assert len(stored["examples"][0]) == 16 * 7 + 7

    options = ["--normalization", "static", "--keep-load-coherent", "--pooled-only"]
    pooled = tmp_path / "pooled.json"
    assert main(["texture", "fit", str(train), "--out", str(pooled), *options]) == 0
    stored = json.loads(pooled.read_text())
    assert stored["settings"]["normalization"] == "static"
    assert stored["settings"]["decorrelate_load"] is False
    assert len(stored["examples"][0]) == 7
    capsys.readouterr()
    assert main(["texture", "classify", *files, "--model", str(pooled)]) == 0
    assert capsys.readouterr().out.splitlines() == [f"{files[0]}\tCoarse", f"{files[1]}\tRibbed"]


def test_a_version_1_model_gets_the_features_of_version_1(folders, tmp_path, capsys):
    """Models written before the feature options existed keep their meaning."""
    train, test = folders
    path = tmp_path / "model.json"
    options = ["--normalization", "static", "--keep-load-coherent"]
    assert main(["texture", "fit", str(train), "--out", str(path), *options]) == 0
    data = json.loads(path.read_text())
    data["version"] = 1
    for name in ("normalization", "decorrelate_load", "per_taxel"):
        del data["settings"][name]
    path.write_text(json.dumps(data))
    files = sorted(str(path) for path in test.iterdir())
    capsys.readouterr()
    assert main(["texture", "classify", *files, "--model", str(path)]) == 0
    assert capsys.readouterr().out.splitlines() == [f"{files[0]}\tCoarse", f"{files[1]}\tRibbed"]
    recording = read_fabricslide(files[0])
    static = texture_features(
        texture_signature(recording.readings, recording.time, recording.sliding_velocity)
    )
    np.testing.assert_array_equal(_features(Path(files[0]), data["settings"], {}), static)


def test_segment_lengths_out_of_range_are_refused(folders, tmp_path, capsys):
    train, _ = folders
    model_path = tmp_path / "model.json"
    with pytest.raises(SystemExit) as stop:  # an overflow inside the spectrum, before
        main(["texture", "fit", str(train), "--out", str(model_path), "--segment-length=1e308"])
    assert stop.value.code == 2
    assert "--segment-length: must be at most 100, got 1e308" in _one_line_error(capsys)
    # 20 mm/s at 35 Hz: 0.57 mm per sample, 4.6 mm for 8; a shorter segment used to pass
    # silently (lengthened to 8 samples)
    code = main(["texture", "fit", str(train), "--out", str(model_path), "--segment-length=2e-3"])
    assert code == 2
    error = _one_line_error(capsys)
    assert "_F150_V" in error
    assert "--segment-length must span at least 8 samples (0.004571 m at 0.02 m/s" in error
    assert error.endswith("got 0.002\n")
    assert not model_path.exists()


def test_a_constant_recording_is_named(folders, tmp_path, capsys):
    train, test = folders
    model_path = tmp_path / "model.json"
    assert main(["texture", "fit", str(train), "--out", str(model_path)]) == 0
    constant = test / "Ribbed_F150_V20mmps_9.csv"
    rows = [f"{1000 + 28 * step}, 0, 65535, " + ", ".join(["120"] * 16) for step in range(300)]
    constant.write_text("\n".join([HEADER, *rows]) + "\n")
    good = test / "Coarse_F150_V-50mmps_1.csv"
    assert main(["texture", "classify", str(good), str(constant), "--model", str(model_path)]) == 2
    error = _one_line_error(capsys)
    assert error.startswith(f"taxel texture classify: error: {constant}: ") and "constant" in error


def test_a_deeply_nested_model_is_refused(folders, tmp_path, capsys, monkeypatch):
    _, test = folders
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 100_000 + "]" * 100_000)
    recording = str(next(test.iterdir()))
    assert main(["texture", "classify", recording, "--model", str(deep)]) == 2
    assert _one_line_error(capsys) == (
        f"taxel texture classify: error: --model {deep}: nested too deeply to be a texture "
        "classifier\n"
    )
    # given as ./deep.json, which the loader reads (and names) as deep.json
    monkeypatch.chdir(tmp_path)
    assert main(["texture", "classify", recording, "--model", "./deep.json"]) == 2
    assert _one_line_error(capsys) == (
        "taxel texture classify: error: --model deep.json: nested too deeply to be a "
        "texture classifier\n"
    )


def test_too_many_neighbors_names_the_flag_and_the_recordings(folders, tmp_path, capsys):
    train, _ = folders  # six recordings
    model_path = tmp_path / "model.json"
    args = ["texture", "fit", str(train), "--out", str(model_path)]
    assert main([*args, "--neighbors", "1000"]) == 2
    assert _one_line_error(capsys) == (
        "taxel texture fit: error: --neighbors 1000: the classifier votes among the 6 "
        "recordings it is fitted on; give at most 6\n"
    )
    assert not model_path.exists()
    assert main([*args, "--neighbors", "6"]) == 0  # as many as there are: taken
    assert "fitted 6 recordings" in capsys.readouterr().out


def test_a_trim_that_leaves_too_little_travel_names_the_trim(folders, tmp_path, capsys):
    """The trim's error names --trim-fraction, not --segment-length (it named the latter)."""
    train, test = folders
    model_path = tmp_path / "model.json"
    args = ["texture", "fit", str(train), "--out", str(model_path)]
    # 20 mm/s at 35 Hz for 0.3 m: 525 steps; a trim of 0.45 at each end keeps 53, 0.0303 m
    assert main([*args, "--trim-fraction", "0.45"]) == 2
    error = _one_line_error(capsys)
    assert error.startswith(f"taxel texture fit: error: {train / 'Coarse_F150_V-20mmps_0.csv'}: ")
    assert error.endswith(
        ": --trim-fraction 0.45 leaves 0.03029 m of the record's 0.3001 m travel (53 of 525 "
        "steps at 0.02 m/s and 34.9933 Hz), less than --segment-length 0.2\n"
    )
    assert not model_path.exists()
    # the 105 steps at 100 mm/s keep 11, too few for any segment
    assert main([*args, "--trim-fraction", "0.45", "--segment-length", "0.02"]) == 2
    assert _one_line_error(capsys).endswith(
        "_V100mmps_0.csv: --trim-fraction 0.45 leaves 11 of the record's 105 steps, fewer "
        "than the 16 a spectrum needs\n"
    )
    # a trim of 0.4 leaves 0.06 m of each record, which holds a 0.05 m segment
    assert main([*args, "--trim-fraction", "0.4", "--segment-length", "0.05"]) == 0
    capsys.readouterr()

    # a model's settings are named as the model's, in classify
    recording = str(test / "Coarse_F150_V-50mmps_1.csv")
    data = json.loads(model_path.read_text())
    data["settings"]["segment_length"] = 0.2
    model_path.write_text(json.dumps(data))
    assert main(["texture", "classify", recording, "--model", str(model_path)]) == 2
    assert _one_line_error(capsys).endswith(
        ": the model's trim_fraction 0.4 leaves 0.05998 m of the record's 0.2999 m travel (42 "
        "of 210 steps at 0.05 m/s and 35.0128 Hz), less than the model's segment_length 0.2\n"
    )
    data["settings"]["segment_length"] = "0.2"  # a string: a TypeError, named the same way
    model_path.write_text(json.dumps(data))
    assert main(["texture", "classify", recording, "--model", str(model_path)]) == 2
    assert _one_line_error(capsys) == (
        f"taxel texture classify: error: {recording}: the model's segment_length must be a "
        "real number, got '0.2'\n"
    )


def test_missing_recordings_and_a_single_fabric_are_said_so(folders, tmp_path, capsys):
    train, test = folders
    model_path = tmp_path / "model.json"
    assert main(["texture", "fit", str(train), "--out", str(model_path)]) == 0
    capsys.readouterr()
    # a missing recording is missing, not "not a FabricSlide file name"
    missing = tmp_path / "missing.csv"
    assert main(["texture", "classify", str(missing), "--model", str(model_path)]) == 2
    assert _one_line_error(capsys) == (
        f"taxel texture classify: error: FILE {missing}: no such file or folder\n"
    )
    # a folder of one fabric: not "`labels` must name at least 2 classes"
    one = tmp_path / "one"
    one.mkdir()
    for path in train.glob("Ribbed_*.csv"):
        (one / path.name).write_bytes(path.read_bytes())
    out = tmp_path / "one.json"
    assert main(["texture", "fit", str(one), "--out", str(out)]) == 2
    assert _one_line_error(capsys) == (
        f"taxel texture fit: error: DIR {one}: holds recordings of one fabric only (Ribbed, "
        "3 recordings); a classifier tells fabrics apart: give folders with recordings of at "
        "least 2 fabrics\n"
    )
    assert not out.exists()
    assert main(["texture", "fit", str(one), str(train), "--out", str(out)]) == 0
