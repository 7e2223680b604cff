import json
from pathlib import Path

import numpy as np
import pytest

from taxel.cli import main
from taxel.mechanics import make_indenter
from taxel.sensor import make_sensor


def test_simulate_writes_the_raw_frame_and_the_truth(tmp_path, capsys):
    out, truth = tmp_path / "frame.npy", tmp_path / "truth.npz"
    argv = ["simulate", "--sensor", "resistive16", "--object", "sphere", "--force", "2"]
    assert main([*argv, "--out", str(out), "--truth", str(truth), "--seed", "4"]) == 0
    assert "wrote" in capsys.readouterr().out
    raw = np.load(out)
    sensor = make_sensor("resistive16")
    expected = sensor.press(make_indenter("sphere"), normal_force=2.0, rng=4)
    assert np.array_equal(raw, expected.raw)
    data = np.load(truth)
    meta = json.loads(str(data["meta"]))
    assert meta["sensor"] == "resistive16" and meta["converged"]
    assert data["pressure"].shape == sensor.load_grid.shape
    cell = np.prod(data["spacing"])
    assert data["pressure"].sum() * cell == pytest.approx(2.0, rel=1e-6)
    assert data["contact"].dtype == bool and data["contact"].any()
    assert -data["taxel_stress"].sum() * cell == pytest.approx(2.0, rel=0.03)
    assert data["taxel_strain"].min() < 0 and data["taxel_displacement"].max() > 0


def test_simulate_refuses_to_overwrite(tmp_path, capsys):
    out = tmp_path / "frame.npy"
    out.write_bytes(b"keep")
    argv = ["simulate", "--sensor", "capacitive4x4", "--object", "sphere", "--force", "1"]
    assert main([*argv, "--out", str(out)]) == 2
    assert "exists; pass --overwrite" in capsys.readouterr().err
    assert out.read_bytes() == b"keep"
    assert main([*argv, "--out", str(out), "--overwrite"]) == 0
    assert np.load(out).shape == (4, 4)


def test_the_can_rim_crosses_the_sensor_by_default(tmp_path):
    truth = tmp_path / "can.npz"
    argv = ["simulate", "--sensor", "resistive16", "--object", "can", "--force", "3"]
    argv += ["--oversampling", "4", "--out", str(tmp_path / "can.npy"), "--truth", str(truth)]
    assert main(argv) == 0
    data = np.load(truth)
    contact = data["contact"]
    assert contact.shape == (64, 64)  # 0.5 mm cells resolve the 1 mm lip
    # an arc of radius 26 mm through the middle, its centre 26 mm to the left
    rows = np.flatnonzero(contact.any(axis=1))
    assert rows.min() == 0 and rows.max() == 63
    assert 31 <= np.flatnonzero(contact[32]).mean() <= 32
    x = (np.arange(64) - 31.5) * 0.5e-3
    y = x[:, None]
    radius = np.hypot(x[None, :] + 0.026, y)[contact]
    assert np.all(np.abs(radius - 0.026) < 1e-3)
    assert json.loads(str(data["meta"]))["position"] == [-0.026, 0.0]


@pytest.mark.parametrize(
    ("extra", "match"),
    [
        (["--sensor", "resistive99", "--object", "pen"], "--sensor: must be one of vhdta128"),
        (["--sensor", "resistive16", "--object", "cup"], "argument --object: must be one of pen"),
        (["--sensor", "resistive16", "--object", "can", "--x", "0"], "is over no cell of the"),
        (["--sensor", "resistive16", "--object", "pen", "--x", "10"], "lowest point off the 32"),
        (["--sensor", "resistive16", "--object", "sphere", "--y", "-0.02"], "2.64 mm higher up"),
        (["--sensor", "capacitive4x4", "--object", "punch"], "give --oversampling 2 or more"),
        (["--sensor", "resistive16", "--object", "pen", "--angle", "nan"], "must be finite"),
    ],
)
def test_bad_arguments_exit_2_with_one_line(tmp_path, capsys, extra, match):
    argv = ["simulate", *extra, "--out", str(tmp_path / "f.npy")]
    if "--force" not in extra:
        argv += ["--force", "1"]
    try:
        code = main(argv)
    except SystemExit as stop:  # argparse's own errors
        code = stop.code
    assert code == 2
    err = capsys.readouterr().err
    assert match in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "f.npy").exists()


@pytest.mark.parametrize(
    ("extra", "match"),
    [
        (["--force", "-1"], "argument --force: must be >= 0, got -1"),
        (["--force=-0.001"], "argument --force: must be >= 0, got -0.001"),
        (["--force", "nan"], "argument --force: must be >= 0, got nan"),
        (["--force", "1", "--seed", "-3"], "argument --seed: must be >= 0"),
        (["--force", "1", "--out", "frame.csv"], "--out must name a .npy file"),
        (["--force", "1", "--oversampling", "0"], "argument --oversampling: must lie in 1..16"),
    ],
)
def test_bad_numbers_exit_2_with_one_line(tmp_path, capsys, extra, match):
    argv = ["simulate", "--sensor", "resistive16", "--object", "pen"]
    if "--out" not in extra:
        extra = [*extra, "--out", str(tmp_path / "f.npy")]
    try:
        code = main([*argv, *extra])
    except SystemExit as stop:
        code = stop.code
    assert code == 2
    err = capsys.readouterr().err
    assert match in err and len(err.strip().splitlines()) == 1


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux's /proc")
def test_a_truth_that_cannot_be_written_leaves_no_frame(tmp_path, capsys):
    # /proc takes no new files, even from root: the frame must not be left behind alone
    out = tmp_path / "f.npy"
    argv = ["simulate", "--sensor", "resistive16", "--object", "pen", "--force", "1"]
    assert main([*argv, "--out", str(out), "--truth", "/proc/truth.npz"]) == 2
    err = capsys.readouterr().err
    assert "--truth /proc/truth.npz cannot be written" in err and err.count("\n") == 1
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_a_read_only_folder_is_a_one_line_error(tmp_path, capsys, monkeypatch):
    # there neither the temporary file can be written nor removed; the error names the flag
    from taxel.cli import _simulate

    def read_only(path, *args, **kwargs):
        raise OSError(30, "Read-only file system", str(path))

    monkeypatch.setattr(_simulate, "_save", read_only)
    monkeypatch.setattr(Path, "unlink", read_only)
    out = tmp_path / "frame.npy"
    argv = ["simulate", "--sensor", "capacitive4x4", "--object", "sphere", "--force", "1"]
    assert main([*argv, "--out", str(out)]) == 2
    assert capsys.readouterr().err == (
        f"taxel simulate: error: --out {out} cannot be written (Read-only file system)\n"
    )


def test_a_force_beyond_the_models_is_refused_as_the_flag(tmp_path, capsys):
    # at 1e200 N the contact pressure overflowed to inf, reported as `pressure` not finite
    argv = ["simulate", "--sensor", "resistive16", "--object", "sphere", "--force", "1e200"]
    with pytest.raises(SystemExit) as stop:
        main([*argv, "--out", str(tmp_path / "f.npy")])
    assert stop.value.code == 2
    assert "argument --force: must be at most 1e+06, got 1e200" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_simulate_warns_when_the_sensing_plane_is_pressed_beyond_full_scale(tmp_path, capsys):
    # a 12 N ball of 6.25 mm on vhdta128 loads its sensing plane to 815 kPa, twice the
    # 413.7 kPa full scale; 3 N to 349 kPa, within it
    argv = ["simulate", "--sensor", "vhdta128", "--object", "sphere", "--out"]
    assert main([*argv, str(tmp_path / "hard.npy"), "--force", "12"]) == 0
    err = capsys.readouterr().err
    assert "warning: the taxels feel up to 814.8 kPa" in err
    assert "full scale of 413.7 kPa" in err
    assert main([*argv, str(tmp_path / "light.npy"), "--force", "3"]) == 0
    assert capsys.readouterr().err == ""


def test_a_frame_at_zero_force_is_the_sensor_at_rest(tmp_path, capsys):
    """--force 0 writes the unloaded frame, which `taxel features --reference` takes."""
    sensor = make_sensor("vhdta128")
    rest, truth = tmp_path / "rest.npy", tmp_path / "rest.npz"
    argv = ["simulate", "--sensor", "vhdta128", "--object", "sphere", "--force", "0"]
    assert main([*argv, "--seed", "1", "--out", str(rest), "--truth", str(truth)]) == 0
    assert capsys.readouterr().out == (
        f"wrote {rest}: vhdta128 raw frame 128 x 128 (uint8, noise seed 1), sphere 0 N at "
        f"(0, 0) mm; nothing pressed, the sensor at rest; truth in {truth}\n"
    )
    # the raw frame of no pressure, its noise and fixed pattern, as a loaded press reads it
    unloaded = sensor.frame_from_pressure(np.zeros(sensor.load_grid.shape), rng=1).raw
    np.testing.assert_array_equal(np.load(rest), unloaded)
    assert np.load(rest).dtype == np.uint8
    data = np.load(truth)
    meta = json.loads(str(data["meta"]))
    assert meta["normal_force"] == 0.0 and meta["contact_area"] == 0.0
    assert meta["converged"] and (meta["n_iterations"], meta["residual"]) == (0, 0.0)
    assert meta["message"] == "no load: the indenter rests at first touch, with no contact"
    assert not data["pressure"].any() and not data["contact"].any()
    assert not data["taxel_stress"].any()
    # "-0" is 0 N, not "-0 N"
    assert main([*argv[:-1], "-0", "--out", str(tmp_path / "zero.npy")]) == 0
    assert "sphere 0 N at (0, 0) mm; nothing pressed" in capsys.readouterr().out

    # another frame at rest (other noise): read alone, vhdta128's scratches look like a
    # contact; tared by the simulated rest frame, it is none
    other = tmp_path / "other.npy"
    assert main([*argv, "--seed", "2", "--out", str(other)]) == 0
    capsys.readouterr()
    features = ["features", str(other), "--sensor", "vhdta128", "--json"]
    assert main(features) == 0
    assert json.loads(capsys.readouterr().out)["contact"]["present"]
    assert main([*features, "--reference", str(rest)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert not data["contact"]["present"] and data["contact_type"] == "none"
    # a 2 N press tared the same way is still a contact, at the origin
    loaded = tmp_path / "loaded.npy"
    argv[-1] = "2"
    assert main([*argv, "--seed", "3", "--out", str(loaded)]) == 0
    capsys.readouterr()
    features[1] = str(loaded)
    assert main([*features, "--reference", str(rest)]) == 0
    contact = json.loads(capsys.readouterr().out)["contact"]
    assert contact["present"]  # centred where the sphere pressed, to a tenth of a millimetre
    assert np.all(np.abs(contact["centroid_m"]) < 1e-4)


@pytest.mark.parametrize(
    ("sensor", "extra", "said"),
    [
        ("reflective8x8", ["--x", "0.003", "--y", "-0.002"], "pressing with 2 N closes "),
        ("reflective8x8", ["--force", "5"], "pressing with 5 N closes reflective8x8's 1.5 mm"),
        ("capacitive4x4", ["--force", "500"], "pressing with 500 N squeezes capacitive4x4's"),
    ],
)
def test_a_force_past_the_transducers_end_names_the_flag(tmp_path, capsys, sensor, extra, said):
    argv = ["simulate", "--sensor", sensor, "--object", "sphere", "--force", "2", *extra]
    assert main([*argv, "--out", str(tmp_path / "f.npy")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"taxel simulate: error: {said}")
    assert err.endswith(": --force must be smaller\n") and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_an_object_between_the_cell_centres_asks_for_oversampling(tmp_path, capsys):
    # the 6 mm punch at the centre of capacitive4x4 is over the sensor, but the nearest
    # centres of its 5 mm cells are 3.5 mm away: it touches none; 2 x 2 cells per taxel do
    argv = ["simulate", "--sensor", "capacitive4x4", "--object", "punch", "--force", "1"]
    assert main([*argv, "--out", str(tmp_path / "f.npy")]) == 2
    assert capsys.readouterr().err == (
        "taxel simulate: error: the punch at x = 0 m, y = 0 m falls between the centres of "
        "the 5 mm cells of the 20 x 20 mm load grid, on which the contact is solved: what it "
        "presses with is narrower than a cell; give --oversampling 2 or more to solve it on "
        "finer cells\n"
    )
    assert main([*argv, "--oversampling", "2", "--out", str(tmp_path / "f.npy")]) == 0
    # off the sensor, no grid finds it
    assert main([*argv, "--x", "0.5", "--out", str(tmp_path / "f.npy"), "--overwrite"]) == 2
    assert capsys.readouterr().err.endswith(
        "is over no cell of the 20 x 20 mm load grid (5 mm cells), even at --oversampling 16: "
        "move it onto the sensor\n"
    )


def test_a_displacement_sensor_pressed_beyond_full_scale_is_warned_of(tmp_path, capsys):
    # reflective8x8 feels the cover's displacement, not a stress: its check held the stress
    # it never computes (zeros) and stayed silent where `taxel reconstruct` warned
    calibration = tmp_path / "cal.npz"
    assert main(["calibrate", "--sensor", "reflective8x8", "--out", str(calibration)]) == 0
    for force, beyond in (("2", 16), ("1", 4), ("0.5", 0)):
        raw = tmp_path / f"raw{force}.npy"
        argv = ["simulate", "--sensor", "reflective8x8", "--object", "sphere", "--force", force]
        capsys.readouterr()
        assert main([*argv, "--out", str(raw)]) == 0
        err = capsys.readouterr().err
        reconstruct = ["reconstruct", str(raw), "--sensor", "reflective8x8", "--calibration"]
        assert main([*reconstruct, str(calibration), "--out", str(tmp_path / "p.npy")]) == 0
        told = capsys.readouterr().err
        (tmp_path / "p.npy").unlink()
        if not beyond:
            assert err == told == ""
            continue
        assert err.startswith("taxel simulate: warning: the cover moves up to ")
        assert (
            f"at {beyond} of them beyond what a plate at reflective8x8's full scale of 4 kPa"
            in err
        )
        # reconstruct counts them too: saturated, or (past the response's peak) read low
        counts = [int(line.split(": warning: ")[1].split()[0]) for line in told.splitlines()]
        assert sum(counts) == beyond
