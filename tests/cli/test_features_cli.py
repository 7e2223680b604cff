import json
import math

import cv2
import numpy as np
import pytest

from taxel.cli import main


@pytest.fixture
def washer():
    y, x = np.mgrid[:64, :64] - 31.5
    r = np.hypot(x, y)
    return np.where((r < 24) & (r > 10), 200, 24).astype(np.uint8)


@pytest.mark.parametrize("suffix", [".npy", ".npz", ".png", ".tif", ".csv"])
def test_formats_give_json(tmp_path, capsys, washer, suffix):
    path = tmp_path / f"frame{suffix}"
    if suffix == ".npy":
        np.save(path, washer)
    elif suffix == ".npz":
        np.savez(path, frame=washer)
    elif suffix == ".csv":
        np.savetxt(path, washer, delimiter=",", fmt="%d")
    else:
        image = washer.astype(np.uint16) * 257 if suffix == ".tif" else washer
        cv2.imwrite(str(path), image)
    assert main(["features", str(path), "--pitch", "2.5e-4", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["contact"]["present"] and data["holes"]["count"] == 1
    assert data["contact_type"] == "surface"


def test_table_pose_and_figure(tmp_path, capsys, washer):
    frame = tmp_path / "frame.npy"
    np.save(frame, washer)
    pose = tmp_path / "pose.json"
    pose.write_text(json.dumps({"translation": [0.1, 0.2, 0.3], "rotvec": [0, 0, 0]}))
    figure = tmp_path / "features.png"
    args = ["features", str(frame), "--pitch", "2.5e-4", "--pose", str(pose)]
    assert main([*args, "--figure", str(figure)]) == 0
    out = capsys.readouterr().out
    assert "contact type" in out and "(100.000, 200.000, 300.000)" in out
    assert figure.stat().st_size > 1000


def test_sensor_preset_gives_the_pitch(tmp_path, capsys):
    # a 4 x 6 taxel bar, columns 9-14, on a 16 x 16 array
    frame = np.full((16, 16), 100.0)
    frame[6:10, 9:15] = 3000.0
    path = tmp_path / "frame.npy"
    np.save(path, frame)
    assert main(["features", str(path), "--sensor", "resistive16", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    x, y = data["contact"]["centroid_m"]
    # resistive16 has a 2 mm pitch: column 11.5 lies 4 taxels (8 mm) right of the centre 7.5
    assert x == pytest.approx(4 * 2e-3, abs=0.2e-3)
    assert y == pytest.approx(0.0, abs=0.2e-3)


def test_known_noise_finds_a_texture_that_covers_the_array(tmp_path, capsys):
    # a 16 x 16 array covered by a texture as fine as its taxels reads as noise, unless the
    # sensor's noise (4 counts) is given
    rng = np.random.default_rng(3)
    path = tmp_path / "texture.npy"
    np.save(path, 1000 + 300 * rng.random((16, 16)) + rng.normal(0, 4, (16, 16)))
    args = ["features", str(path), "--pitch", "2e-3", "--json"]
    assert main(args) == 0
    assert json.loads(capsys.readouterr().out)["contact_type"] == "none"
    assert main([*args, "--noise", "4"]) == 0
    assert json.loads(capsys.readouterr().out)["contact_type"] == "surface"


@pytest.mark.parametrize(
    ("setup", "extra", "match"),
    [
        ("missing", ["--pitch", "1e-3"], "no such file"),
        ("text", ["--pitch", "1e-3"], "unknown frame format"),
        ("frame", [], "--pitch"),
        ("frame", ["--sensor", "nosuch"], "--sensor: must be one of vhdta128"),
        ("frame", ["--sensor", "vhdta128", "--pitch", "1e-3"], "not both"),
        ("frame", ["--pitch", "-1"], "argument --pitch: must be > 0, got -1"),
        ("frame", ["--sensor", "resistive16"], "a 64 x 64 image, but resistive16 frames are 16 x"),
        ("frame", ["--pitch", "1e-3", "--pose", "MISSING"], "--pose MISSING: No such file"),
        ("frame", ["--pitch", "1e-3", "--pose", "BOTH"], "not both"),
        ("frame", ["--pitch", "1e-3", "--pose", "ZERO"], "--pose ZERO: 'quaternion' [0, 0, 0, 0]"),
        ("archive", ["--pitch", "1e-3"], "holds 2 arrays (a, b); choose one with --key"),
        ("archive", ["--pitch", "1e-3", "--key", "c"], "no array named 'c'"),
        ("complex", ["--pitch", "1e-3"], "complex128 data, not real numbers"),
        ("nan", ["--pitch", "1e-3"], "finite"),
        ("badpose", ["--pitch", "1e-3", "--pose", "POSE"], "not valid JSON"),
        ("frame", ["--pitch", "1e-3", "--noise", "-2"], "argument --noise: must be > 0, got -2"),
        ("frame", ["--pitch", "1e-3", "--noise", "nan"], "argument --noise: must be > 0, got nan"),
        # beyond single precision (NumPy's overflow warnings were printed, and a result)
        ("frame", ["--pitch", "1e-3", "--noise", "1e40"], "--noise must lie in (0, 1e+15]"),
        (
            "small",
            ["--pitch", "5e-3"],
            "4 interior taxel(s) cannot estimate its own noise (it "
            "needs 16): give --noise (one taxel's noise sigma, in the image's units) or --sensor",
        ),
    ],
)
def test_errors_are_one_line(tmp_path, capsys, washer, setup, extra, match):
    frame = tmp_path / "frame.npy"
    np.save(frame, washer)
    target = {"missing": tmp_path / "none.npy", "text": tmp_path / "a.txt"}.get(setup, frame)
    if setup == "text":
        target.write_text("1,2")
    if setup == "nan":
        np.save(frame, np.full((8, 8), np.nan))
    if setup == "small":  # a 4 x 4 array: too small to tell its noise from a contact
        np.save(frame, np.pad(np.full((2, 2), 100.0), 1))
    if setup == "archive":
        target = tmp_path / "two.npz"
        np.savez(target, a=washer, b=washer)
    if setup == "complex":
        np.save(frame, washer.astype(complex))
    poses = {name: tmp_path / f"{name.lower()}.json" for name in ("POSE", "BOTH", "ZERO")}
    poses["POSE"].write_text("{not json")
    rotation = {"rotvec": [0, 0, 0], "quaternion": [0, 0, 0, 1]}
    poses["BOTH"].write_text(json.dumps({"translation": [0, 0, 0], **rotation}))
    poses["ZERO"].write_text(json.dumps({"translation": [0, 0, 0], "quaternion": [0, 0, 0, 0]}))
    poses["MISSING"] = tmp_path / "missing.json"
    extra = [str(poses[item]) if item in poses else item for item in extra]
    match = match.replace("MISSING", str(poses["MISSING"])).replace("ZERO", str(poses["ZERO"]))
    try:
        code = main(["features", str(target), *extra])
    except SystemExit as stop:  # argparse's own errors
        code = stop.code
    assert code == 2
    err = capsys.readouterr().err
    assert match in err and len(err.strip().splitlines()) == 1


def test_a_failed_figure_keeps_the_old_one(tmp_path, capsys, washer, full_disk_savefig):
    frame, figure = tmp_path / "frame.npy", tmp_path / "features.png"
    np.save(frame, washer)
    figure.write_bytes(b"old figure")
    args = ["features", str(frame), "--pitch", "2.5e-4", "--figure", str(figure), "--overwrite"]
    assert main(args) == 2
    assert capsys.readouterr().err == (
        f"taxel features: error: --figure {figure} cannot be written (No space left on device)\n"
    )
    assert figure.read_bytes() == b"old figure"
    assert sorted(path.name for path in tmp_path.iterdir()) == ["features.png", "frame.npy"]
    full_disk_savefig.undo()
    assert main(args) == 0
    assert cv2.imread(str(figure)).shape[:2] == (600, 600)


@pytest.mark.parametrize(
    ("content", "problem"),
    [
        ('{"translation": [0, 0, 0], "quaternion": null}', "'quaternion' must be a list of 4"),
        ('{"translation": null, "rotvec": [0, 0, 0]}', "'translation' must be a list of 3"),
        ('{"translation": [0, 0, 0], "rotvec": [0, 0, true]}', "'rotvec' must be a list of 3"),
        ("[" * 40_000 + "]" * 40_000, "nested too deeply to be a pose"),
        # a number JSON holds but a float cannot (it was a traceback)
        ('{"translation": [1' + "0" * 400 + ", 0, 0]}", "the number 10000000000000000... is"),
        (
            '{"matrix": [[1e400, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}',
            "the number 1e400 is too",
        ),
        # JSON has no NaN, but Python reads it (max() then took [0, 0, 0, NaN] for zeros)
        ('{"translation": [0, 0, 0], "quaternion": [0, 0, 0, NaN]}', "NaN is not a number a"),
        ('{"translation": [0, 0, 0], "quaternion": [0, 0, 1, Infinity]}', "Infinity is not a"),
        # keys that were ignored: the pose was read as identity, or without its translation
        (
            '{"translation": [0, 0, 0], "rotvec": [0, 0, 0], "frame": "base"}',
            "unknown key 'frame'",
        ),
        ('{"Translation": [0.4, 0.1, 0.25]}', "unknown key 'Translation': a pose is a 4x4 list"),
        (
            '{"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], '
            '"translation": [0.4, 0.1, 0.25]}',
            "'matrix' is the whole pose (its last column the translation), so 'translation'",
        ),
        (
            '{"rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "rotvec": [0, 0, 0], '
            '"translation": [0, 0, 0]}',
            "give one rotation: 'rotation' or 'rotvec', not both",
        ),
        ('{"translation": [0, 0, 0], "translation": [1, 0, 0]}', "key 'translation' given twice"),
        ('{"rotvec": [0, 0, 1]}', "no 'translation': a pose is"),
        (
            '{"rotation": [[1, 0, 0], [0, 1, 0]], "translation": [0, 0, 0]}',
            "'rotation' must be a 3x3 list of numbers (rows), got [[1, 0, 0], [0, 1, 0]]",
        ),
        (
            '{"rotation": [[1, 0, 0], [0, 1, 0], [0, 0, -1]], "translation": [0, 0, 0]}',
            "`rotation` must have a proper rotation block (orthonormal, det +1)",
        ),
        ("[" + " " * 200_000 + "]", "more than 100 kB: not a pose file"),
        # JSON's true read as 1 (a metre's translation), a ragged list, bytes of no text
        ("[[1, 0, 0, true], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]", "`pose` must be numeric"),
        (
            '{"matrix": [[true, false, false, false], [false, true, false, false], '
            "[false, false, true, false], [false, false, false, true]]}",
            "`pose` must be numeric, got a boolean in it",
        ),
        ("[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0]]", "`pose` must be a regular"),
        (b"\xff\xfe[", "not a text file (cannot decode it as UTF-8)"),
    ],
)
def test_poses_that_are_no_poses_are_one_line(tmp_path, capsys, washer, content, problem):
    frame, pose = tmp_path / "frame.npy", tmp_path / "pose.json"
    np.save(frame, washer)
    pose.write_bytes(content) if isinstance(content, bytes) else pose.write_text(content)
    assert main(["features", str(frame), "--pitch", "2.5e-4", "--pose", str(pose)]) == 2
    error = capsys.readouterr().err
    assert error.startswith(f"taxel features: error: --pose {pose}: {problem}")
    assert error.count("\n") == 1


@pytest.mark.parametrize(
    ("pitch", "message"), [("2", "must be at most 1, got 2"), ("1e-170", "must be at least 1e-09")]
)
def test_the_pitch_is_checked_as_the_flag(tmp_path, capsys, washer, pitch, message):
    frame = tmp_path / "frame.npy"
    np.save(frame, washer)
    with pytest.raises(SystemExit) as stop:
        main(["features", str(frame), "--pitch", pitch])
    assert stop.value.code == 2
    assert f"argument --pitch: {message}" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("setup", "extra", "message"),
    [
        ("npy", ["--key", "nonsense"], "--key names an array of an .npz archive, not of a .npy"),
        ("archive", [], "holds 2 arrays (a, b); choose one with --key"),
        ("mask", [], "the frame holds bool data, not real numbers"),
        ("huge", [], "values up to 1e+300, beyond the 1e+15 the features handle"),
        # the digits that tell it from the limit, which 3 would round to it
        ("just over", [], "values up to 1.0000001e+15, beyond the 1e+15"),
        ("time", [], "has a time column: a sequence of frames, where one frame is read"),
    ],
)
def test_frames_the_features_cannot_take(tmp_path, capsys, washer, setup, extra, message):
    suffix = {"archive": ".npz", "time": ".csv"}.get(setup, ".npy")
    path = tmp_path / f"frame{suffix}"
    if setup == "archive":
        np.savez(path, a=washer, b=washer)
    elif setup == "time":
        path.write_text("timestamp, a, b\n0.0, 1, 2\n")
    else:
        frame = {
            "npy": washer,
            "mask": washer > 100,
            "huge": washer * 1e300 / washer.max(),
            "just over": washer * 1.0000001e15 / washer.max(),
        }
        np.save(path, frame[setup])
    assert main(["features", str(path), "--pitch", "2.5e-4", *extra]) == 2
    error = capsys.readouterr().err
    assert error.startswith(f"taxel features: error: {path}: ") and message in error
    assert error.count("\n") == 1


def test_pressure_map_chains_and_defects_flag(tmp_path, capsys):
    # a pressure map as sparse as `taxel reconstruct --method support` writes: 1 taxel in 3
    # of a 2 mm disc 10 taxels right of the centre, 0.25 MPa each (vhdta128: 0.2578 mm)
    y, x = np.mgrid[:128, :128]
    disc = np.hypot(y - 63.5, x - 73.5) <= 7.75
    pressure = np.where(disc & ((y + 2 * x) % 3 == 0), 2.5e5, 0.0)
    path = tmp_path / "pressure.npy"
    np.save(path, pressure)
    args = ["features", str(path), "--sensor", "vhdta128", "--calibrated", "--json"]
    assert main(args) == 0
    contact = json.loads(capsys.readouterr().out)["contact"]
    pitch = 3.3e-2 / 128
    assert contact["present"]
    assert contact["total_force_n"] == pytest.approx(pressure.sum() * pitch**2, rel=1e-6)
    assert pressure.sum() * pitch**2 == pytest.approx(1.014, abs=0.001)
    # the speckle's centre of pressure: (9.795, 0.205) taxels off the array's centre
    centre = [(x * pressure).sum() / pressure.sum(), (y * pressure).sum() / pressure.sum()]
    assert np.subtract(centre, 63.5) == pytest.approx([9.795, 0.205], abs=0.001)
    assert contact["centroid_m"] == pytest.approx(
        (np.subtract(centre, 63.5) * pitch).tolist(), abs=0.03 * pitch
    )
    # --defects asks for the 3 x 3 opening, which erases such a map
    assert main([*args, "--defects"]) == 0
    assert not json.loads(capsys.readouterr().out)["contact"]["present"]


def test_no_defects_keeps_a_thin_line_on_a_raw_frame(tmp_path, capsys):
    # on a raw vhdta128 frame a line 1 taxel wide is a scratch, removed by default
    frame = np.full((128, 128), 20, np.uint8)
    frame[40, 30:90] = 200
    path = tmp_path / "frame.npy"
    np.save(path, frame)
    args = ["features", str(path), "--sensor", "vhdta128", "--json"]
    assert main(args) == 0
    assert not json.loads(capsys.readouterr().out)["contact"]["present"]
    assert main([*args, "--no-defects"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["contact"]["present"] and data["contact_type"] == "line"
    assert data["contact"]["centroid_index"] == pytest.approx([40.0, 59.5], abs=0.01)


def test_an_explicit_defects_flag_says_when_it_erased_the_contact(tmp_path, capsys):
    # a pen tip on a 2 mm array lights 2 x 2 taxels: --defects takes it for a hot pixel
    frame = np.random.default_rng(0).normal(1000.0, 5.0, (16, 16))
    frame[7:9, 7:9] += 3000.0
    path = tmp_path / "frame.npy"
    np.save(path, frame)
    args = ["features", str(path), "--pitch", "2e-3", "--json"]
    assert main([*args, "--defects"]) == 0
    captured = capsys.readouterr()
    assert not json.loads(captured.out)["contact"]["present"]
    assert "--defects removed the only contact" in captured.err
    assert "--no-defects keeps it" in captured.err
    assert main(args) == 0  # by default (no cover known) the spot stays, and no word
    captured = capsys.readouterr()
    assert json.loads(captured.out)["contact"]["present"] and captured.err == ""


def test_a_4x4_frame_takes_the_presets_noise(tmp_path, capsys):
    # a noise-free 0.5 N sphere on capacitive4x4: 4 taxels at 8371 codes, ~3100 elsewhere
    frame = tmp_path / "cap.npy"
    args = ["--sensor", "capacitive4x4", "--object", "sphere", "--force", "0.5"]
    assert main(["simulate", *args, "--out", str(frame)]) == 0
    capsys.readouterr()
    assert main(["features", str(frame), "--sensor", "capacitive4x4", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["contact"]["present"] and data["contact_type"] == "surface"
    assert data["contact"]["centroid_m"] == pytest.approx([0.0, 0.0], abs=1e-6)
    assert data["contact"]["area_m2"] == pytest.approx(100e-6)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--pitch", "5e-3", "--noise", "sensor"], "--noise sensor needs the sensor named with"),
        (
            ["--sensor", "capacitive4x4", "--calibrated", "--noise", "sensor"],
            "--noise sensor is the noise of the sensor's raw frames, not of a --calibrated",
        ),
    ],
)
def test_noise_sensor_errors(tmp_path, capsys, extra, message):
    path = tmp_path / "frame.npy"
    np.save(path, np.full((4, 4), 3000, np.int64))
    assert main(["features", str(path), *extra]) == 2
    error = capsys.readouterr().err
    assert message in error and error.count("\n") == 1
    with pytest.raises(SystemExit) as stop:
        main(["features", str(path), "--sensor", "capacitive4x4", "--noise", "camera"])
    assert stop.value.code == 2
    assert "--noise: must be a number > 0 or 'sensor', got 'camera'" in capsys.readouterr().err


def test_pose_as_rotation_and_translation(tmp_path, capsys, washer):
    # the sensor upside down (x kept, y and z flipped) 0.4, 0.1, 0.25 m from the base
    frame, pose = tmp_path / "frame.npy", tmp_path / "pose.json"
    np.save(frame, washer)
    rotation = [[1, 0, 0], [0, -1, 0], [0, 0, -1]]
    pose.write_text(json.dumps({"rotation": rotation, "translation": [0.4, 0.1, 0.25]}))
    assert main(["features", str(frame), "--pitch", "2.5e-4", "--pose", str(pose), "--json"]) == 0
    contact = json.loads(capsys.readouterr().out)["contact"]
    x, y, _ = contact["position_sensor_m"]
    assert contact["centroid_base_m"] == pytest.approx([0.4 + x, 0.1 - y, 0.25], abs=1e-12)
    assert contact["normal_base"] == pytest.approx([0.0, 0.0, -1.0])
    # the same pose as a matrix
    matrix = [[*rotation[i], t] for i, t in enumerate((0.4, 0.1, 0.25))] + [[0, 0, 0, 1]]
    pose.write_text(json.dumps({"matrix": matrix}))
    assert main(["features", str(frame), "--pitch", "2.5e-4", "--pose", str(pose), "--json"]) == 0
    again = json.loads(capsys.readouterr().out)["contact"]
    assert again["centroid_base_m"] == contact["centroid_base_m"]
    # the same file as Windows' Notepad saves it, with a UTF-8 byte-order mark
    pose.write_text(json.dumps({"matrix": matrix}), encoding="utf-8-sig")
    assert main(["features", str(frame), "--pitch", "2.5e-4", "--pose", str(pose), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["contact"] == contact


@pytest.mark.parametrize(
    "quaternion",
    [
        [0, 0, 1e300, 1e300],
        [0, 0, 1e-300, 1e-300],
        [0, 0, 2**-0.5, 2**-0.5],
        [0, 0, 1.7e308, 1.7e308],  # its length overflows even math.hypot
    ],
)
def test_quaternions_of_any_length_give_their_rotation(tmp_path, capsys, washer, quaternion):
    # a quarter turn about z, however long the quaternion (its squares over- or underflow)
    frame, pose = tmp_path / "frame.npy", tmp_path / "pose.json"
    np.save(frame, washer)
    pose.write_text(json.dumps({"translation": [0, 0, 0], "quaternion": quaternion}))
    assert main(["features", str(frame), "--pitch", "2.5e-4", "--pose", str(pose), "--json"]) == 0
    contact = json.loads(capsys.readouterr().out)["contact"]
    x, y, _ = contact["position_sensor_m"]
    assert contact["centroid_base_m"] == pytest.approx([-y, x, 0.0], abs=1e-12)


@pytest.mark.parametrize(("angle", "code"), [(2.0**33 - 1, 0), (2.0**33, 2), (1e300, 2)])
def test_a_rotation_vector_longer_than_a_double_holds_is_refused(
    tmp_path, capsys, washer, angle, code
):
    frame, pose = tmp_path / "frame.npy", tmp_path / "pose.json"
    np.save(frame, washer)
    pose.write_text(json.dumps({"translation": [0, 0, 0], "rotvec": [0, 0, angle]}))
    assert main(["features", str(frame), "--pitch", "2.5e-4", "--pose", str(pose)]) == code
    err = capsys.readouterr().err
    assert ("'rotvec' has length" in err) == (code == 2)


@pytest.mark.parametrize(("metres", "shown"), [(1e300, "1.000e+303"), (1e307, "1.000e+310")])
def test_the_table_shows_huge_positions_in_exponent_notation(
    tmp_path, capsys, washer, metres, shown
):
    # (1e307 m is 1e310 mm, beyond a double: it was shown as inf)
    frame, pose = tmp_path / "frame.npy", tmp_path / "pose.json"
    np.save(frame, washer)
    pose.write_text(json.dumps({"translation": [0, 0, metres], "rotvec": [0, 0, 0]}))
    assert main(["features", str(frame), "--pitch", "2.5e-4", "--pose", str(pose)]) == 0
    line = next(row for row in capsys.readouterr().out.splitlines() if "base [mm]" in row)
    assert line.endswith(f", {shown})") and len(line) < 80


@pytest.mark.parametrize("suffix", [".npy", ".png"])
def test_calibrated_refuses_raw_codes(tmp_path, capsys, washer, suffix):
    # an 8-bit camera frame read as pressure gave a "total force" of a few mN
    path = tmp_path / f"frame{suffix}"
    np.save(path, washer) if suffix == ".npy" else cv2.imwrite(str(path), washer)
    args = ["features", str(path), "--pitch", "2.5e-4", "--calibrated", "--json"]
    assert main(args) == 2
    assert capsys.readouterr().err == (
        f"taxel features: error: {path} holds raw codes (uint8), not pressure [Pa]: leave out "
        "--calibrated for a raw frame, or give a pressure map (`taxel reconstruct FRAME "
        "--calibration CAL.npz` makes one)\n"
    )
    # the same numbers as pressure [Pa]: 200 Pa on the washer's 1488 taxels (93.0 mm^2),
    # 18.6 mN, and 24 Pa on the other 2608: as pressure, a load on every taxel (none is at
    # a pressure map's no-load level, 0), the whole array's contact
    np.save(tmp_path / "pressure.npy", washer.astype(float))
    assert main([*args[:1], str(tmp_path / "pressure.npy"), *args[2:]]) == 0
    contact = json.loads(capsys.readouterr().out)["contact"]
    assert np.count_nonzero(washer == 200) * 200 * 2.5e-4**2 == pytest.approx(0.0186)
    assert contact["total_force_n"] == pytest.approx(0.0186 + 24 * 2608 * 2.5e-4**2, rel=1e-5)
    assert contact["area_m2"] == pytest.approx(64 * 64 * 2.5e-4**2)


def test_reference_frame_tares_a_frame_at_rest(tmp_path, capsys):
    from taxel.sensor import make_sensor

    sensor = make_sensor("vhdta128")
    rest = np.zeros(sensor.load_grid.shape)
    reference = np.mean([sensor.frame_from_pressure(rest, rng=100 + k).raw for k in range(8)], 0)
    np.save(tmp_path / "reference.npy", reference)
    # an unloaded frame in which two crossing scratches outlast the opening
    frame = sensor.frame_from_pressure(rest, rng=3).raw
    np.save(tmp_path / "frame.npy", frame)
    args = ["features", str(tmp_path / "frame.npy"), "--sensor", "vhdta128", "--json"]
    assert main(args) == 0
    assert json.loads(capsys.readouterr().out)["contact"]["present"]
    assert main([*args, "--reference", str(tmp_path / "reference.npy")]) == 0
    data = json.loads(capsys.readouterr().out)
    assert not data["contact"]["present"] and data["contact_type"] == "none"


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (np.zeros((64, 64)), "a 64 x 64 frame, but"),
        (np.full((128, 128), np.inf), "--reference: "),
        (None, "--reference REFERENCE: no such file"),
        # int64's least, whose absolute value overflows to itself: it slipped past the check
        (
            np.full((128, 128), np.iinfo(np.int64).min),
            "--reference REFERENCE: values up to 9.22e+18, beyond the 1e+15",
        ),
    ],
)
def test_reference_errors_are_one_line(tmp_path, capsys, content, message):
    np.save(tmp_path / "frame.npy", np.zeros((128, 128), np.uint8))
    if content is not None:
        np.save(tmp_path / "reference.npy", content)
    args = ["features", str(tmp_path / "frame.npy"), "--sensor", "vhdta128"]
    assert main([*args, "--reference", str(tmp_path / "reference.npy")]) == 2
    err = capsys.readouterr().err
    message = message.replace("REFERENCE", str(tmp_path / "reference.npy"))
    assert message in err and len(err.strip().splitlines()) == 1


def test_sensors_whose_frames_are_no_plain_images(tmp_path, capsys):
    from taxel.mechanics import make_indenter
    from taxel.sensor import make_sensor

    sphere = make_indenter("sphere")
    # a PVDF frame falls where it is pressed: the contact is the pressed taxel (before,
    # the 61 taxels left unpressed)
    piezo = make_sensor("piezo8x8")
    path = tmp_path / "piezo.npy"
    np.save(path, piezo.press(sphere, normal_force=1.0, position=(3e-3, -2e-3), rng=1).raw)
    assert main(["features", str(path), "--sensor", "piezo8x8", "--json"]) == 0
    contact = json.loads(capsys.readouterr().out)["contact"]
    assert contact["centroid_m"] == pytest.approx([3.75e-3, -1.25e-3], abs=0.1e-3)
    assert contact["area_m2"] == pytest.approx(2.5e-3**2)
    # a photoelastic frame past its first fringe is read with a warning; below it, none
    photoelastic = make_sensor("photoelastic64")
    for force, warned in ((0.5, False), (2.0, True)):
        frame = photoelastic.press(sphere, normal_force=force, position=(3e-3, -2e-3))
        np.save(path := tmp_path / f"fringes{force}.npy", frame.raw)
        assert main(["features", str(path), "--sensor", "photoelastic64", "--json"]) == 0
        captured = capsys.readouterr()
        assert json.loads(captured.out)["contact"]["present"]
        assert ("reaches the first fringe of the photoelastic64 layer" in captured.err) is warned
    # microbend fibres are no image
    np.save(path := tmp_path / "fibres.npy", np.zeros(32, np.int64))
    assert main(["features", str(path), "--sensor", "microbend16"]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1
    assert "--sensor microbend16 reads 32 fibres, not an image of its 16 x 16 crossings" in error


def test_table_names_its_axes_and_shows_directions_alike(tmp_path, capsys):
    # a horizontal bar: the line's angle and the contact's orientation are one direction,
    # shown in (-90, 90] (before: "line angle 180.0" beside "orientation -0.1")
    frame = np.full((32, 32), 10.0)
    frame[14:18, 2:30] = 200.0
    path = tmp_path / "bar.npy"
    np.save(path, frame)
    assert main(["features", str(path), "--pitch", "1e-3"]) == 0
    rows = dict(
        line.split("  ", 1) for line in capsys.readouterr().out.splitlines() if "  " in line
    )
    rows = {name.strip(): value.strip() for name, value in rows.items()}
    assert rows["centroid (x, y) [mm]"] == "(0.000, 0.000)"
    assert rows["centroid (row, col) [taxels]"] == "(15.50, 15.50)"
    assert abs(float(rows["orientation [deg]"])) < 1.0
    assert abs(float(rows["line angle [deg]"])) < 1.0


def test_a_raw_frame_pressed_all_over_is_warned_of(tmp_path, capsys):
    # a plate over the whole array, or a frame saturated everywhere: no taxel at rest, so
    # the smoothed minimum is no baseline and a raw frame reads "no contact" by itself
    from taxel.sensor import make_sensor

    sensor = make_sensor("resistive16")
    grid = sensor.load_grid.shape
    np.save(tmp_path / "plate.npy", sensor.frame_from_pressure(np.full(grid, 20e3), rng=1).raw)
    np.save(tmp_path / "rest.npy", sensor.frame_from_pressure(np.zeros(grid), rng=2).raw)
    args = ["features", str(tmp_path / "plate.npy"), "--sensor", "resistive16"]
    assert main(args) == 0
    captured = capsys.readouterr()
    assert "contact                        no" in captured.out
    assert captured.err.startswith(
        "taxel features: warning: no contact found, but even the least pressed taxels of "
        f"{tmp_path / 'plate.npy'} read 9% of full scale above resistive16 at rest: "
    )
    assert "give --reference REST.npy, a frame of the sensor at rest\n" in captured.err
    # pressed harder, the pad's free rim reads less than the middle: a contact is found,
    # measured from a level under the load, and warned of too
    harder = sensor.frame_from_pressure(np.full(grid, 120e3), rng=1).raw
    np.save(tmp_path / "harder.npy", harder)
    assert main(["features", str(tmp_path / "harder.npy"), "--sensor", "resistive16"]) == 0
    captured = capsys.readouterr()
    assert "contact                        yes" in captured.out
    assert captured.err.startswith(
        f"taxel features: warning: even the least pressed taxels of {tmp_path / 'harder.npy'}"
    )
    # with the frame at rest as its reference, the whole array is the contact
    assert main([*args, "--reference", str(tmp_path / "rest.npy"), "--json"]) == 0
    captured = capsys.readouterr()
    assert captured.err == ""
    assert json.loads(captured.out)["contact"]["area_m2"] == pytest.approx(32e-3**2)
    # a frame at rest is not warned of
    assert main(["features", str(tmp_path / "rest.npy"), "--sensor", "resistive16"]) == 0
    assert capsys.readouterr().err == ""


def test_a_depth_map_gives_the_contact_plane_s_normal(tmp_path, capsys):
    # an optical sensor's indentation map: a face tilted 10 degrees about x
    pitch = 2.5e-4
    y, x = (np.mgrid[:64, :64] - 31.5) * pitch
    tilt = math.radians(10)
    np.save(tmp_path / "depth.npy", 2e-4 + math.tan(tilt) * y)
    np.save(tmp_path / "image.npy", np.where(np.hypot(x, y) < 6e-3, 1.0, 0.0))
    args = ["features", str(tmp_path / "image.npy"), "--pitch", str(pitch), "--json"]
    assert main(args) == 0
    assert json.loads(capsys.readouterr().out)["normal"] is None  # no depth, no normal
    assert main([*args, "--depth", str(tmp_path / "depth.npy")]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["tilt_rad"] == pytest.approx(tilt, abs=1e-6)
    assert data["normal"][1] == pytest.approx(math.sin(tilt), abs=1e-6)
    # a depth map of another shape is one line naming the flag
    np.save(tmp_path / "small.npy", np.zeros((8, 8)))
    assert main([*args, "--depth", str(tmp_path / "small.npy")]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and f"--depth {tmp_path / 'small.npy'}: a 8 x 8 frame" in error
    # a depth out of range is named by the flag and the file, not by the library's parameter
    np.save(tmp_path / "deep.npy", np.full((64, 64), 5.0))
    assert main([*args, "--depth", str(tmp_path / "deep.npy")]) == 2
    assert capsys.readouterr().err == (
        f"taxel features: error: --depth {tmp_path / 'deep.npy'} is an indentation in metres "
        "and must lie within +-1 m, got 5\n"
    )
