"""``taxel reconstruct``: writes the map, prints lambda and norms, one-line errors."""

import json
import re

import numpy as np
import pytest

from taxel.cli import main
from taxel.reconstruction import forward_operator


def test_writes_the_pressure_map_and_reports(frame_file, tmp_path, capsys):
    out = tmp_path / "pressure.npy"
    code = main(
        [
            "reconstruct",
            str(frame_file),
            "--sensor",
            "resistive16",
            "--order",
            "1",
            "--out",
            str(out),
        ]
    )
    assert code == 0
    assert np.load(out).shape == (16, 16)
    text = capsys.readouterr().out
    assert "centre of pressure (x, y) = (" in text
    # the default rule: the discrepancy principle with the noise estimated from the frame
    assert "lambda = " in text and "(discrepancy)" in text and "residual norm" in text
    # the norms in their units: readings in Pa, the order-1 penalty in Pa per load cell
    assert re.search(r"residual norm [-+.e0-9]+ Pa, solution norm [-+.e0-9]+ Pa/cell, ", text)


@pytest.mark.parametrize("method", ["tikhonov", "tsvd", "nonneg", "tv", "support"])
def test_json_summary(frame_file, tmp_path, capsys, method):
    out = tmp_path / "p.npy"
    arguments = [
        "reconstruct",
        str(frame_file),
        "--sensor",
        "resistive16",
        "--method",
        method,
        "--lambda",
        "discrepancy",
        "--noise-level",
        "1000",
        "--json",
        "--out",
        str(out),
    ]
    assert main(arguments) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["method"] == method and summary["rule"] == "discrepancy"
    assert summary["regularization"] > 0 and summary["residual_norm"] > 0
    assert summary["normal_force_n"] == pytest.approx(0.1 * 9 * 4e-6 * 40e3 * 10, rel=0.3)
    if method == "support":  # the load alone: no noise of unloaded cells
        # the load's centre: row 6, column 7 of 16 at a 2 mm pitch
        assert summary["centroid_m"] == pytest.approx([-1e-3, -3e-3], abs=0.1e-3)
    else:
        assert len(summary["centroid_m"]) == 2


def test_a_given_lambda_and_oversampling(frame_file, tmp_path, capsys):
    out = tmp_path / "p.npy"
    arguments = [
        "reconstruct",
        str(frame_file),
        "--sensor",
        "resistive16",
        "--lambda",
        "0.05",
        "--oversampling",
        "2",
        "--json",
        "--out",
        str(out),
    ]
    assert main(arguments) == 0
    assert json.loads(capsys.readouterr().out)["regularization"] == 0.05
    assert np.load(out).shape == (32, 32)


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--sensor", "vhdta128"], "holds frames of (16, 16), but --sensor vhdta128's frames"),
        (["--sensor", "gelsight"], "`--sensor` must be one of vhdta128, harmon10x20, resistive16"),
        (  # a preset `taxel simulate` takes, refused saying why
            ["--sensor", "photoelastic64"],
            "reflective8x8; got 'photoelastic64' ('photoelastic64' does not give one reading "
            "per taxel of its 'stress_difference'; the pressure cannot be reconstructed",
        ),
        (["--sensor", "microbend16"], "got 'microbend16' ('microbend16' does not give one"),
        (["--sensor", "resistive16", "--lambda", "-2"], "--lambda: must be a number from 0 to"),
        (["--sensor", "resistive16", "--lambda", "1e300"], "--lambda: must be a number from 0 to"),
        (["--sensor", "resistive16", "--lambda", "oracle"], "--lambda: must be one of gcv"),
        (["--sensor", "resistive16", "--lambda", "inf"], "--lambda: must be a number from 0 to"),
        (["--sensor", "resistive16", "--noise-level", "0"], "--noise-level: must be > 0"),
        (  # was taken: a 2 N contact read 0.02 N
            ["--sensor", "resistive16", "--noise-level", "1e300"],
            "--noise-level must be below the full-scale reading of resistive16 (2e+05 Pa), "
            "got 1e+300",
        ),
        (
            ["--sensor", "resistive16", "--noise-level", "2e5", "--method", "support"],
            "--noise-level must be below the full-scale reading of resistive16 (2e+05 Pa), "
            "got 200000",
        ),
        (["--sensor", "resistive16", "--method", "tv", "--order", "2"], "got --order 2"),
    ],
)
def test_errors_are_one_line_and_exit_2(frame_file, tmp_path, capsys, extra, message):
    try:
        code = main(["reconstruct", str(frame_file), *extra, "--out", str(tmp_path / "p.npy")])
    except SystemExit as stop:  # argparse's own errors
        code = stop.code
    assert code == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and message in error and "Traceback" not in error


def test_nan_frame_and_missing_file(tmp_path, capsys):
    bad = tmp_path / "bad.npy"
    np.save(bad, np.full((16, 16), np.nan))
    out = str(tmp_path / "p.npy")
    assert main(["reconstruct", str(bad), "--sensor", "resistive16", "--out", out]) == 2
    assert f"`FRAME` {str(bad)!r} must be finite" in capsys.readouterr().err
    missing = str(tmp_path / "missing.npy")
    assert main(["reconstruct", missing, "--sensor", "resistive16", "--out", out]) == 2
    assert "`FRAME` must be an existing .npy file" in capsys.readouterr().err


def test_raw_frames_need_a_calibration_and_nothing_is_overwritten(tmp_path, capsys):
    import numpy as np

    from taxel.cli import main

    raw = tmp_path / "raw.npy"
    assert (
        main(
            [
                "simulate",
                "--sensor",
                "resistive16",
                "--object",
                "sphere",
                "--force",
                "2",
                "--seed",
                "1",
                "--out",
                str(raw),
            ]
        )
        == 0
    )
    out = tmp_path / "pressure.npy"
    assert main(["reconstruct", str(raw), "--sensor", "resistive16", "--out", str(out)]) == 2
    assert "holds raw codes" in capsys.readouterr().err and not out.exists()
    calibration = tmp_path / "cal.npz"
    assert main(["calibrate", "--sensor", "resistive16", "--out", str(calibration)]) == 0
    assert (
        main(
            [
                "reconstruct",
                str(raw),
                "--sensor",
                "resistive16",
                "--calibration",
                str(calibration),
                "--order",
                "1",
                "--out",
                str(out),
                "--json",
            ]
        )
        == 0
    )
    summary = json.loads(capsys.readouterr().out.splitlines()[-1])
    assert summary["normal_force_n"] == pytest.approx(2.0, rel=0.05)
    before = np.load(raw)
    for target, flags, message in (
        (out, [], "exists; pass --overwrite"),
        (raw, ["--overwrite"], "is an input file"),
    ):
        assert (
            main(
                [
                    "reconstruct",
                    str(raw),
                    "--sensor",
                    "resistive16",
                    "--calibration",
                    str(calibration),
                    "--out",
                    str(target),
                    *flags,
                ]
            )
            == 2
        )
        assert message in capsys.readouterr().err
    assert np.array_equal(np.load(raw), before)
    assert main(["calibrate", "--sensor", "resistive16", "--out", str(calibration)]) == 2
    assert "exists" in capsys.readouterr().err


def _frame_files(folder):
    """Files that are no FRAME: empty, archives, text, a lying header, complex, a folder."""
    empty = folder / "empty.npy"
    empty.write_bytes(b"")
    archive = folder / "archive.npy"
    with archive.open("wb") as handle:
        np.savez(handle, frame=np.ones((16, 16)))
    complex_values = folder / "complex.npy"
    np.save(complex_values, np.ones((16, 16), complex))
    text = folder / "text.npy"
    np.save(text, np.full((16, 16), "a"))
    corrupt_archive = folder / "corrupt.npz"
    corrupt_archive.write_bytes(b"PK\x03\x04 garbage")
    csv = folder / "frame.csv"
    csv.write_text("1, 2\n3, 4\n")
    claims = folder / "claims.npy"  # a header claiming 2 TB: no MemoryError
    with claims.open("wb") as handle:
        header = {"descr": "<f8", "fortran_order": False, "shape": (10**6, 1000, 16, 16)}
        np.lib.format.write_array_header_1_0(handle, header)
        handle.write(bytes(64))
    return {
        empty: "not a readable .npy file",
        archive: "is an .npz archive",
        corrupt_archive: "is an .npz archive",
        csv: "no NumPy header: a text or image file?",
        claims: "truncated or corrupt: its header claims shape (1000000, 1000, 16, 16)",
        complex_values: "holds complex128 values, not real numbers",
        text: "holds <U1 values, not real numbers",
        folder: "is a folder",
    }


def test_unreadable_frames_are_one_line_errors(tmp_path, capsys):
    out = tmp_path / "out" / "p.npy"
    out.parent.mkdir()
    for path, message in _frame_files(tmp_path).items():
        code = main(["reconstruct", str(path), "--sensor", "resistive16", "--out", str(out)])
        error = capsys.readouterr().err
        assert code == 2 and error.count("\n") == 1 and message in error, (path, error)
        assert not out.exists()


def test_unreadable_calibrations_are_one_line_errors(tmp_path, capsys):
    from taxel.sensor import calibrate, make_sensor

    frame = tmp_path / "frame.npy"
    np.save(frame, np.full((16, 16), 100, np.int64))
    one_array = tmp_path / "one.npy"
    np.save(one_array, np.ones(3))
    empty = tmp_path / "empty.npz"
    empty.write_bytes(b"")
    good = tmp_path / "good.npz"
    calibrate(make_sensor("resistive16")).save(good)
    with np.load(good) as stored:
        arrays = dict(stored)
    arrays["pressures"] = arrays["pressures"][::-1].copy()
    falling = tmp_path / "falling.npz"
    np.savez(falling, **arrays)
    other = tmp_path / "other.npz"  # an .npz of other arrays: said in words, not ('meta')
    np.savez(other, a=np.zeros(3))
    partial = tmp_path / "partial.npz"
    np.savez(partial, **{key: arrays[key] for key in ("meta", "pressures", "readings")})
    arrays["pressures"] = arrays["pressures"][::-1].copy()  # (rising again)
    arrays["unresponsive"] = np.ones_like(arrays["unresponsive"])
    dead = tmp_path / "dead.npz"  # NumPy's warnings of empty means came first (4 lines)
    np.savez(dead, **arrays)
    cases = {
        tmp_path / "missing.npz": f"--calibration {tmp_path / 'missing.npz'}: no such file\n",
        other: f"--calibration {other}: not a taxel calibration file: it lacks the array(s) "
        "felt_fraction, meta, noise, pinned, pressures, readings, unresponsive that `taxel "
        "calibrate` writes (it holds a)\n",
        partial: "it lacks the array(s) felt_fraction, noise, pinned, unresponsive that",
        one_array: "not an .npz archive",
        empty: "not a taxel calibration file",
        falling: "`pressures` must rise strictly",
        tmp_path: "a folder, not a taxel calibration file",
        dead: "excludes every taxel of resistive16 (none responds to load)",
    }
    out = tmp_path / "p.npy"
    for path, message in cases.items():
        arguments = ["reconstruct", str(frame), "--sensor", "resistive16", "--out", str(out)]
        assert main([*arguments, "--calibration", str(path)]) == 2
        error = capsys.readouterr().err
        assert error.count("\n") == 1 and message in error, (path, error)


def test_a_calibration_whose_header_claims_terabytes_is_one_line(tmp_path, capsys):
    import io
    import zipfile

    frame = tmp_path / "frame.npy"
    np.save(frame, np.full((16, 16), 100, np.int64))
    member = io.BytesIO()
    header = {"descr": "<f8", "fortran_order": False, "shape": (10**6, 10**6)}
    np.lib.format.write_array_header_1_0(member, header)
    member.write(bytes(64))
    claims = tmp_path / "claims.npz"
    with zipfile.ZipFile(claims, "w") as archive:
        archive.writestr("readings.npy", member.getvalue())
    out = tmp_path / "p.npy"
    arguments = ["reconstruct", str(frame), "--sensor", "resistive16", "--out", str(out)]
    # numpy allocated the 8 TB first: a MemoryError and its traceback
    assert main([*arguments, "--calibration", str(claims)]) == 2
    assert capsys.readouterr().err == (
        f"taxel reconstruct: error: --calibration {claims}: not a taxel calibration file "
        "(truncated or corrupt: its header claims shape (1000000, 1000000) of float64 "
        "(8000000000000 bytes), but 64 bytes follow)\n"
    )
    assert not out.exists()


def test_a_batch_of_any_shape_is_reconstructed_frame_by_frame(frame_file, tmp_path, capsys):
    frame = np.load(frame_file)
    batch = tmp_path / "batch.npy"
    np.save(batch, np.stack([np.stack([frame, 2 * frame])] * 2))  # (2, 2, 16, 16)
    out = tmp_path / "p.npy"
    assert main(["reconstruct", str(batch), "--sensor", "resistive16", "--out", str(out)]) == 0
    pressure = np.load(out)
    assert pressure.shape == (2, 2, 16, 16)
    assert np.allclose(pressure[1], pressure[0])
    assert pressure[0, 1].sum() == pytest.approx(2 * pressure[0, 0].sum(), rel=0.05)
    text = capsys.readouterr().out
    assert "written to" in text and "pressure map (2, 2, 16, 16)" in text
    forces = text.split("force ")[1].split(" N")[0]
    assert len(forces.split(", ")) == 4  # one force per frame


def test_a_failed_write_names_out_and_never_writes_it(frame_file, tmp_path, capsys, monkeypatch):
    from pathlib import Path

    from taxel.io import _writers

    def disk_full(path, *args, **kwargs):
        raise OSError(28, "No space left on device", str(path))

    monkeypatch.setattr(_writers.np, "save", disk_full)
    monkeypatch.setattr(Path, "unlink", disk_full)  # nor can the temporary be removed
    out = tmp_path / "p.npy"
    argv = ["reconstruct", str(frame_file), "--sensor", "resistive16", "--out", str(out)]
    assert main(argv) == 2
    assert capsys.readouterr().err == (
        f"taxel reconstruct: error: --out {out} cannot be written (No space left on device)\n"
    )
    assert not out.exists()


def test_a_calibration_of_another_kind_is_named(tmp_path, capsys):
    from taxel.sensor import calibrate, make_sensor

    frame = tmp_path / "frame.npy"
    np.save(frame, np.full((16, 16), 100, np.int64))
    text = tmp_path / "cal.json"
    text.write_text('{"format": "taxel.pad_calibration"}')
    out = tmp_path / "p.npy"
    arguments = ["reconstruct", str(frame), "--sensor", "resistive16", "--out", str(out)]
    assert main([*arguments, "--calibration", str(text)]) == 2
    assert (
        capsys.readouterr().err
        == (  # not numpy's offer to unpickle it
            f"taxel reconstruct: error: --calibration {text}: not a taxel calibration file "
            "(not an .npz archive; `taxel calibrate` makes one)\n"
        )
    )
    other = tmp_path / "cap.npz"
    calibrate(make_sensor("capacitive4x4"), n_levels=6).save(other)
    assert main([*arguments, "--calibration", str(other)]) == 2
    assert capsys.readouterr().err == (
        f"taxel reconstruct: error: --calibration {other} was made for capacitive4x4, not "
        "--sensor resistive16\n"
    )
    assert not out.exists()


def test_wrong_frames_and_calibrations_name_the_file_and_the_sensor(tmp_path, capsys):
    # the frame's shape was reported as the library's `frame`, and a calibration of
    # resistive16 given for vhdta128 as a frame of the wrong shape
    from taxel.sensor import calibrate, make_sensor

    wrong, line, codes = tmp_path / "pwrong.npy", tmp_path / "line.npy", tmp_path / "v.npy"
    np.save(wrong, np.ones((8, 16)))
    np.save(line, np.ones(16))
    np.save(codes, np.full((128, 128), 100, np.int64))
    calibration = tmp_path / "cal.npz"
    calibrate(make_sensor("resistive16"), n_levels=6).save(calibration)
    out = tmp_path / "p.npy"
    cases = [
        (
            [str(wrong), "--sensor", "resistive16"],
            f"`FRAME` {str(wrong)!r} holds frames of (8, 16), but --sensor resistive16's "
            "frames are (16, 16)",
        ),
        (
            [str(line), "--sensor", "resistive16"],
            f"`FRAME` {str(line)!r} holds an array of shape (16,), not frames of --sensor "
            "resistive16, which are (16, 16)",
        ),
        (
            [str(codes), "--sensor", "vhdta128", "--calibration", str(calibration)],
            f"--calibration {calibration} was made for resistive16, not --sensor vhdta128",
        ),
        (
            [str(wrong), "--sensor", "resistive16", "--calibration", str(calibration)],
            f"`FRAME` {str(wrong)!r} holds frames of (8, 16), but --sensor resistive16's "
            "frames are (16, 16)",
        ),
    ]
    odd = tmp_path / "odd.npz"  # named resistive16, calibrating 4 x 4 frames
    calibrate(make_sensor("capacitive4x4"), n_levels=6).save(odd)
    with np.load(odd) as archive:
        arrays = dict(archive)
    arrays["meta"] = np.array(str(arrays["meta"]).replace("capacitive4x4", "resistive16"))
    with odd.open("wb") as handle:
        np.savez(handle, **arrays)
    cases.append(
        (
            [str(wrong), "--sensor", "resistive16", "--calibration", str(odd)],
            f"--calibration {odd} is of resistive16 but calibrates frames of (4, 4), "
            "not (16, 16)",
        )
    )
    for arguments, message in cases:
        assert main(["reconstruct", *arguments, "--out", str(out)]) == 2
        assert capsys.readouterr().err == f"taxel reconstruct: error: {message}\n"
    assert not out.exists()


def test_pressures_beyond_any_contact_are_refused(frame_file, tmp_path, capsys):
    # at 1e154 Pa the norms overflowed: --json printed Infinity, stderr RuntimeWarnings
    huge = tmp_path / "huge.npy"
    np.save(huge, np.load(frame_file) * 1e150)
    out = tmp_path / "p.npy"
    argv = ["reconstruct", str(huge), "--sensor", "resistive16", "--out", str(out), "--json"]
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1
    assert f"`FRAME` {str(huge)!r} holds pressures up to " in captured.err
    assert "beyond any contact (at most 1e+12 Pa" in captured.err
    assert not out.exists()


def test_the_summary_has_no_value_json_lacks():
    from taxel.cli._reconstruct import _finite_or_none

    values = np.array([[1.5, np.inf], [np.nan, -2.0]])
    assert _finite_or_none(values) == [[1.5, None], [None, -2.0]]
    assert _finite_or_none(np.float64(-np.inf)) is None


def test_oversampling_is_refused_beyond_what_the_model_takes(frame_file, tmp_path, capsys):
    out = str(tmp_path / "p.npy")
    with pytest.raises(SystemExit) as stop:
        main(["reconstruct", str(frame_file), "--sensor", "resistive16", "--oversampling", "9"])
    assert stop.value.code == 2
    assert "argument --oversampling: must lie in 1..8, got 9" in capsys.readouterr().err
    argv = ["reconstruct", str(frame_file), "--sensor", "resistive16", "--out", out]
    assert main([*argv, "--oversampling", "2"]) == 0
    assert np.load(out).shape == (32, 32)


def test_the_help_lists_every_sensor_the_reconstruction_inverts(capsys):
    from taxel.cli._reconstruct import INVERTIBLE_PRESETS
    from taxel.reconstruction import FORWARD_MODEL_PRESETS

    assert INVERTIBLE_PRESETS == FORWARD_MODEL_PRESETS
    with pytest.raises(SystemExit):
        main(["reconstruct", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "the frame's sensor: " + ", ".join(FORWARD_MODEL_PRESETS) in text
    assert "noise std of one calibrated reading, in its unit (Pa; m for reflective8x8)" in text


def test_a_displacement_sensor_is_calibrated_to_metres(tmp_path, capsys):
    # reflective8x8 senses the surface displacement: its calibrated frame was fed in Pa to
    # a forward model in metres, and 0.05 N came back as 5.2e5 N (support), 5.7e5 N
    raw, calibration = tmp_path / "rf.npy", tmp_path / "c.npz"
    sensor = ["--sensor", "reflective8x8"]
    simulate = ["simulate", *sensor, "--object", "sphere", "--force", "0.05", "--seed", "2"]
    assert main([*simulate, "--out", str(raw)]) == 0
    assert main(["calibrate", *sensor, "--out", str(calibration)]) == 0
    capsys.readouterr()
    for method in ("support", "tikhonov"):
        out = tmp_path / f"{method}.npy"
        arguments = ["reconstruct", str(raw), *sensor, "--calibration", str(calibration)]
        assert main([*arguments, "--method", method, "--out", str(out), "--json"]) == 0
        summary = json.loads(capsys.readouterr().out)
        assert summary["normal_force_n"] == pytest.approx(0.05, rel=0.02), method
        assert summary["residual_norm"] < 1e-4  # metres
        assert np.nansum(np.load(out)) * 9e-6 == pytest.approx(0.05, rel=0.02)


def test_raw_codes_of_a_sensor_of_load_changes_are_refused_with_why(tmp_path, capsys):
    raw = tmp_path / "piezo.npy"
    np.save(raw, np.full((8, 8), 2048, np.int64))
    out = tmp_path / "p.npy"
    arguments = ["reconstruct", str(raw), "--sensor", "piezo8x8", "--out", str(out)]
    assert main(arguments) == 2
    assert capsys.readouterr().err == (
        "taxel reconstruct: error: --sensor piezo8x8 senses only changes of load (stress): "
        "no static calibration maps its raw codes (`taxel calibrate` cannot make one); give "
        f"FRAME {str(raw)!r} as the stress change each taxel felt [Pa], in real numbers\n"
    )
    stress = tmp_path / "stress.npy"  # the stress change, in real numbers, is inverted
    truth = np.zeros((8, 8))
    truth[3:5, 3:5] = 20e3
    np.save(stress, forward_operator("piezo8x8").apply(truth))
    assert main(["reconstruct", str(stress), "--sensor", "piezo8x8", "--out", str(out)]) == 0
    assert np.load(out).sum() == pytest.approx(truth.sum(), rel=0.02)


def test_support_reports_the_lambda_given_and_its_own_stage_s(frame_file, tmp_path, capsys):
    # `--method support --lambda 0.01` printed the support stage's GCV lambda as "(given)"
    out = tmp_path / "p.npy"
    arguments = ["reconstruct", str(frame_file), "--sensor", "resistive16", "--out", str(out)]
    arguments += ["--method", "support", "--lambda", "0.01", "--overwrite"]
    assert main(arguments) == 0
    first_line = capsys.readouterr().out.splitlines()[0]
    assert first_line.startswith("support (order 0), lambda = 0.01 (given); support ridge lambda")
    assert first_line.endswith("(gcv)")
    assert main([*arguments, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["rule"] == "given" and summary["regularization"] == 0.01
    assert summary["support_rule"] == "gcv"
    assert 0 < summary["support_regularization"] != 0.01
    assert f"support ridge lambda = {summary['support_regularization']:.4g} (gcv)" in first_line
    assert main([*arguments[:-5], "--json", "--overwrite"]) == 0  # tikhonov: one stage
    summary = json.loads(capsys.readouterr().out)
    assert summary["support_regularization"] is None and summary["support_rule"] is None


def test_readings_beyond_the_calibrations_full_scale_are_warned_of(tmp_path, capsys):
    # a 6.25 mm ball at 5 N loads resistive16's sensing plane to 246 kPa, beyond its
    # 200 kPa full scale, at its 4 middle taxels; at 2 N to 98 kPa
    calibration = tmp_path / "cal.npz"
    assert main(["calibrate", "--sensor", "resistive16", "--out", str(calibration)]) == 0
    for force, warned in (("5", "warning: 4 taxel readings of"), ("2", None)):
        raw = tmp_path / f"raw{force}.npy"
        argv = ["simulate", "--sensor", "resistive16", "--object", "sphere", "--force", force]
        assert main([*argv, "--out", str(raw)]) == 0
        capsys.readouterr()
        argv = ["reconstruct", str(raw), "--sensor", "resistive16"]
        argv += ["--calibration", str(calibration), "--out", str(tmp_path / f"p{force}.npy")]
        assert main(argv) == 0
        err = capsys.readouterr().err
        if warned is None:
            assert err == ""
        else:
            assert warned in err and "beyond the calibration's full scale" in err


def test_a_rule_held_at_its_bound_is_printed(frame_file, tmp_path, capsys):
    """--noise-level above the readings (8e5 Pa x sqrt(m) against |b| = 1.04e5 Pa) is said."""
    arguments = ["reconstruct", str(frame_file), "--sensor", "resistive16", "--noise-level"]
    arguments += ["5e4", "--out", str(tmp_path / "p.npy"), "--overwrite"]
    assert main(arguments) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first == (
        "tikhonov (order 0), lambda = 10 (discrepancy, at its bound: the largest of its "
        "range, 10, as no residual reaches tau sigma sqrt(m) (the noise level is as large as "
        "the readings))"
    )
    assert main([*arguments, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["at_bound"] is True and summary["regularization"] == pytest.approx(10.0)
    assert "lambda held at the largest of its range, 10" in summary["message"]
    # within the readings' size: not at the bound, and the text as before
    arguments[5] = "1000"
    assert main(arguments) == 0
    assert "(discrepancy)\n" in capsys.readouterr().out
    assert main([*arguments, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["at_bound"] is False and summary["message"] == "direct solve"


def test_a_tv_search_that_misses_its_target_is_printed(frame_file, tmp_path, capsys):
    arguments = ["reconstruct", str(frame_file), "--sensor", "resistive16", "--method", "tv"]
    arguments += ["--noise-level", "5e4", "--out", str(tmp_path / "p.npy")]
    assert main([*arguments, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["at_bound"] is True
    assert "found no mu with its target residual" in summary["message"]
    assert main([*arguments, "--overwrite"]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert "(discrepancy, at its bound: no mu reaches the target, held at " in first
    assert first.endswith(", target 8e+05)")


def test_readings_below_the_calibrations_no_load_level_are_warned_of(tmp_path, capsys):
    # resistive16 reads 79 to 269 at rest and its ADC gives codes 0 to 4095: -50 everywhere
    # is no frame of it; it read as -12 N without a word
    calibration = tmp_path / "cal.npz"
    assert main(["calibrate", "--sensor", "resistive16", "--out", str(calibration)]) == 0
    negative, low = tmp_path / "negative.npy", tmp_path / "low.npy"
    np.save(negative, np.full((16, 16), -50))
    np.save(low, np.full((16, 16), 30))
    capsys.readouterr()
    argv = ["reconstruct", str(negative), "--sensor", "resistive16"]
    argv += ["--calibration", str(calibration), "--out", str(tmp_path / "p.npy")]
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert err == (
        f"taxel reconstruct: warning: 256 taxel readings of {negative} are below the "
        "calibration's no-load level (down to -50 (a code below 0, which no ADC outputs); "
        "no load reads 78.875 to 268.5): they read as a negative pressure, and the force "
        "recovered is wrong (is FRAME a raw frame of this resistive16?)\n"
    )
    argv[1] = str(low)
    assert main([*argv, "--overwrite"]) == 0
    err = capsys.readouterr().err
    assert "readings of" in err and "down to 30; no load reads 78.875" in err
    # noisy frames at rest and loaded are not warned of
    for force in ("0", "2"):
        raw = tmp_path / f"raw{force}.npy"
        simulate = ["simulate", "--sensor", "resistive16", "--object", "sphere", "--seed", "5"]
        assert main([*simulate, "--force", force, "--out", str(raw)]) == 0
        argv[1] = str(raw)
        assert main([*argv, "--overwrite"]) == 0
        assert capsys.readouterr().err == ""


@pytest.mark.parametrize("command", ["simulate", "reconstruct", "calibrate"])
def test_an_empty_out_is_reported_as_given(tmp_path, capsys, command):
    # Path("") reads as ".": the error said "got '.'"
    frame = tmp_path / "frame.npy"
    np.save(frame, np.zeros((16, 16)))
    argv = {
        "simulate": ["simulate", "--sensor", "resistive16", "--object", "pen", "--force", "1"],
        "reconstruct": ["reconstruct", str(frame), "--sensor", "resistive16"],
        "calibrate": ["calibrate", "--sensor", "resistive16"],
    }[command]
    assert main([*argv, "--out", ""]) == 2
    suffix = ".npz" if command == "calibrate" else ".npy"
    assert capsys.readouterr().err == (
        f"taxel {command}: error: --out must name a {suffix} file, got ''\n"
    )


def test_taxels_the_calibration_excludes_are_left_out_and_counted(tmp_path, capsys):
    # a calibration of a resistive16 with dead taxels marks them; their readings are NaN,
    # which failed the fit ("must be finite at live taxels") before they were passed on
    from dataclasses import replace

    from taxel.mechanics import make_indenter
    from taxel.sensor import calibrate, make_sensor

    sensor = make_sensor("resistive16")
    sensor = replace(sensor, readout=replace(sensor.readout, dead=0.02))
    calibration = calibrate(sensor, rng=1)
    calibration.save(tmp_path / "cal.npz")
    frame = sensor.press(make_indenter("sphere"), normal_force=2.0, rng=3)
    np.save(tmp_path / "raw.npy", frame.raw)
    dead = int(np.count_nonzero(~calibration.valid))
    argv = ["reconstruct", str(tmp_path / "raw.npy"), "--sensor", "resistive16"]
    argv += ["--calibration", str(tmp_path / "cal.npz"), "--method", "support"]
    assert main([*argv, "--out", str(tmp_path / "p.npy")]) == 0
    out = capsys.readouterr().out
    assert f"{dead} taxels excluded by --calibration {tmp_path / 'cal.npz'}" in out
    assert main([*argv, "--out", str(tmp_path / "q.npy"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["excluded_taxels"] == dead
    assert summary["normal_force_n"] == pytest.approx(2.0, rel=0.03)
