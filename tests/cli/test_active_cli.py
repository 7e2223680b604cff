"""``taxel active``: the procedures from the command line."""

import io
import json
from pathlib import Path

import pytest

from taxel.cli import main


def test_probe_plane_prints_the_normal_and_its_error(capsys):
    assert main(["active", "probe-plane", "--probes", "4", "--seed", "3"]) == 0
    out = capsys.readouterr().out
    error = float(out.split("normal error: ")[1].split(" deg")[0])
    assert error < 1.0  # the target for five probes, met with four here


def test_probe_plane_json_holds_the_estimate_and_steps(capsys):
    assert main(["active", "probe-plane", "--json", "--seed", "1"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert len(result["estimate"]["steps"]) >= 5
    assert result["normal_error_deg"] == pytest.approx(result["normal_error_rad"] * 57.29578)


def test_locate_corner(capsys):
    assert main(["active", "locate-corner", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["corner_error_m"] < 1e-3


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["active", "probe-plane", "--probes", "2"], "--probes: must lie in 3..1000, got 2"),
        (["active", "probe-plane", "--sensor", "piezo8x8"], "piezo8x8"),
        (["active", "probe-plane", "--sensor", "nothing"], "--sensor: must be one of vhdta128"),
        (["active", "probe-plane", "--sensor", "microbend16"], "reads one signal per fibre"),
        (["active", "recognize", "--object", "pen", "--sensor", "microbend16"], "per fibre"),
        (
            ["active", "edge-radius", "--radius-mm", "2", "--table", "no-such-folder/t.json"],
            "--table is in a folder that does not exist",
        ),
        (["active"], "the following arguments are required: PROCEDURE"),
    ],
)
def test_bad_arguments_are_one_line_and_exit_2(capsys, arguments, message):
    try:
        code = main(arguments)
    except SystemExit as stop:
        code = stop.code
    assert code == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and message in error


@pytest.fixture(scope="module")
def small_files(tmp_path_factory):
    """Small tables and libraries built once, so the commands only load them."""
    from taxel.active import build_edge_radius_table, build_model_library, calibrate_pad

    folder = tmp_path_factory.mktemp("active")
    build_edge_radius_table((2.2e-3, 3.3e-3, 4.7e-3), orientations=2, path=folder / "t.json")
    build_model_library(("washer", "coin"), rotations=2, path=folder / "l.json")
    calibrate_pad(radii=(3e-3, 10e-3)).save(folder / "pad.json")
    return folder


def test_edge_radius_loads_its_table(capsys, small_files):
    table = small_files / "t.json"
    before = table.read_text()
    assert (
        main(
            [
                "active",
                "edge-radius",
                "--radius-mm",
                "3",
                "--table",
                str(table),
                "--json",
                "--seed",
                "1",
            ]
        )
        == 0
    )
    result = json.loads(capsys.readouterr().out)
    assert result["radius_m"] == pytest.approx(3e-3, abs=0.4e-3)
    # the simulated edge's radius and the error, as the text prints them
    assert result["true_radius_m"] == 3e-3
    assert result["error_m"] == pytest.approx(result["radius_m"] - 3e-3, abs=1e-15)
    args = ["active", "edge-radius", "--radius-mm", "3", "--table", str(table), "--seed", "1"]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert f"error: {result['error_m'] * 1e3:+.3f} mm" in text
    assert table.read_text() == before  # loaded, never rewritten
    # beyond the table's radii (2.2-4.7 mm), the table says so, not only in JSON
    args = ["active", "edge-radius", "--radius-mm", "9", "--table", str(table), "--seed", "1"]
    assert main(args) == 0
    assert "match: at the end of the table" in capsys.readouterr().out


def test_stiffness_tells_the_racquet_ball_from_the_acrylic_sphere(capsys, small_files):
    pad = str(small_files / "pad.json")
    assert main(["active", "stiffness", "--calibration", pad]) == 0
    out = capsys.readouterr().out
    # three presses, as the help says: the touch that finds the ball, a light and a firm press
    assert out.startswith("racquet ball touched at 0.5 N, then pressed at 12 N and 39 N on ")
    assert "verdict: deformable" in out
    assert "inf" not in out  # a pad whose compression did not grow is said so, not "inf N/m"
    seed = "the seed (Ellis 2.2, its 128 x 128 sensor): height unloaded / at 12 / 39 N 57 / 53"
    assert seed in out
    assert "contact area at 12 / 39 N 674 / 4681 pixels" in out
    assert "contact area at 0.5 / 12 / 39 N: " in out
    assert main(["active", "stiffness", "--object", "acrylic sphere", "--calibration", pad]) == 0
    assert "verdict: rigid" in capsys.readouterr().out


def test_stiffness_on_the_four_by_four_array(capsys, tmp_path):
    # its 2 x 2 interior is all contact: the image alone took its press for noise
    pad = str(tmp_path / "pad4.json")
    args = ["active", "stiffness", "--sensor", "capacitive4x4", "--forces", "2", "4"]
    assert main([*args, "--calibration", pad]) == 0
    captured = capsys.readouterr()
    assert "verdict: deformable" in captured.out and "4 / 4 / 4 pixels" in captured.out
    assert captured.err == f"built the pad calibration and saved it to {pad}\n"
    assert main([*args, "--object", "steel ball", "--calibration", pad, "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["deformable"] is False and result["area_pixels"] == [4, 4, 4]
    assert abs(result["height_change_m"]) < 1e-6


def test_recognize_ranks_the_candidates(capsys, small_files):
    library = str(small_files / "l.json")
    assert (
        main(["active", "recognize", "--object", "washer", "--library", library, "--seed", "2"])
        == 0
    )
    out = capsys.readouterr().out
    # the washer's first touch leaves only it within the library's spread: one touch
    assert out.startswith("touched a washer 1 time(s) at 15 N on vhdta128\n")
    assert "recognized as: washer (decided by the first touch: the only model within " in out
    args = ["active", "recognize", "--object", "washer", "--library", library, "--seed", "2"]
    assert main([*args, "--three-touches", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["name"] == "washer" and result["n_touches"] == 3


def test_recognize_names_the_flag_of_a_library_of_other_features(capsys, small_files, tmp_path):
    from taxel.active import DESCRIPTOR_NAMES, ModelLibrary

    library = ModelLibrary.load(small_files / "l.json")
    assert tuple(library.feature_names) == DESCRIPTOR_NAMES
    other = ModelLibrary(
        names=library.names,
        templates=library.templates[:, :2],
        labels=library.labels,
        scales=library.scales[:2],
        feature_names=("area", "force"),
        normal_force=library.normal_force,
        step=library.step,
        sensor=library.sensor,
    )
    path = tmp_path / "other.json"
    other.save(path)
    saved = path.read_text()
    assert main(["active", "recognize", "--object", "coin", "--library", str(path)]) == 2
    assert capsys.readouterr().err == (
        f"taxel active recognize: error: --library {str(path)!r} holds a library of 2 other "
        f"features than the {len(DESCRIPTOR_NAMES)} of this version's touches: build it again\n"
    )
    assert path.read_text() == saved  # never rebuilt over


def test_recognize_presses_within_the_finger_s_limit(capsys, small_files):
    library = str(small_files / "l.json")  # made at the default 15 N
    # photoelastic64's finger presses at most 12.8 N: refused before a library is built
    assert main(["active", "recognize", "--object", "washer", "--sensor", "photoelastic64"]) == 2
    assert capsys.readouterr().err == (
        "taxel active recognize: error: --force 15: the finger with photoelastic64 presses "
        "at most 12.8 N (its full-scale pressure over a quarter of its area); give --force of "
        "at most 12.8\n"
    )
    assert main(["active", "recognize", "--object", "coin", "--library", library, "--force", "10"])
    assert capsys.readouterr().err == (
        f"taxel active recognize: error: --force 10: the --library {library} was made with "
        "15 N; give that or another --library\n"
    )


def test_stiffness_of_a_custom_ball_and_bad_files(capsys, small_files, tmp_path):
    pad = str(small_files / "pad.json")
    assert (
        main(
            [
                "active",
                "stiffness",
                "--shape",
                "ball",
                "--size-mm",
                "10",
                "--modulus-mpa",
                "1",
                "--calibration",
                pad,
                "--json",
            ]
        )
        == 0
    )
    assert json.loads(capsys.readouterr().out)["deformable"] is True  # 1 MPa: softer than the pad
    # a tennis ball: a hollow rubber ball inflated to 90 kPa (its air carries most of the load)
    hollow = ["active", "stiffness", "--shape", "hollow-ball", "--size-mm", "33.5"]
    hollow += ["--modulus-mpa", "4", "--wall-mm", "3.3", "--gauge-kpa", "90"]
    assert main([*hollow, "--calibration", pad, "--json"]) == 0
    tennis = json.loads(capsys.readouterr().out)
    assert tennis["deformable"] is True
    # the finger's travel from 12 to 39 N: 2.66 mm of the shell's give at its two poles
    heights = tennis["heights_m"]
    assert heights[1] - heights[2] == pytest.approx(2.66e-3, abs=0.05e-3)
    broken = tmp_path / "broken.json"
    broken.write_text('{"format": "taxel.pad_calibration"}')
    assert main(["active", "stiffness", "--calibration", str(broken)]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "lacks forces_n" in error


@pytest.mark.parametrize(
    ("procedure", "flag", "what"),
    [
        (["edge-radius", "--radius-mm", "2"], "--table", "an edge radius table"),
        (["stiffness"], "--calibration", "a pad calibration"),
        (["recognize", "--object", "washer"], "--library", "a model library"),
    ],
)
def test_a_wrong_or_deeply_nested_file_names_its_flag(capsys, tmp_path, procedure, flag, what):
    other = tmp_path / "other.json"
    other.write_text('{"format": "something else"}')
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 100_000 + "]" * 100_000)  # the JSON parser's recursion limit
    assert main(["active", *procedure, flag, str(other)]) == 2
    program = f"taxel active {procedure[0]}"
    assert capsys.readouterr().err == f"{program}: error: {flag} {str(other)!r} is not {what}\n"
    assert main(["active", *procedure, flag, str(deep)]) == 2
    assert capsys.readouterr().err == (
        f"{program}: error: {flag} {str(deep)!r} is nested too deeply to be {what}\n"
    )


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["edge-radius", "--radius-mm=1e200"], "argument --radius-mm: must be at most 1000, got"),
        (
            ["stiffness", "--shape", "ball", "--size-mm=1e200", "--modulus-mpa", "1"],
            "argument --size-mm: must be at most 1000, got 1e200",
        ),
        (
            ["stiffness", "--shape", "block", "--size-mm", "20", "--modulus-mpa=1e-300"],
            "argument --modulus-mpa: must be at least 1e-06, got 1e-300",
        ),
        (
            ["stiffness", "--shape", "block", "--size-mm", "20", "--modulus-mpa=1e308"],
            "argument --modulus-mpa: must be at most 1e+07, got 1e308",
        ),
        (["locate-corner", "--guess-error-mm=1e308"], "--guess-error-mm: must be at most 1000"),
        (
            ["stiffness", "--shape", "ball", "--size-mm", "20"],
            "--shape ball needs its --size-mm and --modulus-mpa",
        ),
        (
            ["stiffness", "--shape", "hollow-ball", "--size-mm", "20", "--modulus-mpa", "4"],
            "--shape hollow-ball needs its --wall-mm",
        ),
        (
            [
                "stiffness",
                "--shape",
                "block",
                "--size-mm",
                "20",
                "--modulus-mpa",
                "4",
                "--wall-mm=2",
            ],
            "--wall-mm describes a hollow ball, not a --shape block",
        ),
        (
            ["stiffness", "--shape=ball", "--size-mm=20", "--modulus-mpa=2", "--gauge-kpa=50"],
            "--gauge-kpa describes a hollow ball, not a --shape ball",
        ),
        (
            ["stiffness", "--shape=hollow-ball", "--size-mm=10", "--modulus-mpa=4", "--wall-mm=6"],
            "--wall-mm 6 must be under half the --size-mm 10",
        ),
        (  # a named object is pressed as it is: never silently replaced or altered
            ["stiffness", "--object", "steel ball", "--shape", "ball", "--size-mm", "20"],
            "--object 'steel ball' conflicts with --shape ball: give either a named --object",
        ),
        (
            ["stiffness", "--object", "steel ball", "--modulus-mpa", "1"],
            "--object 'steel ball' conflicts with --modulus-mpa 1: --object presses the named "
            "object as it is",
        ),
        (
            ["stiffness", "--size-mm", "20", "--poisson-ratio", "0.3"],
            "--size-mm 20 --poisson-ratio 0.3 describes a custom object: give --shape ball, "
            "hollow-ball (with --wall-mm) or block",
        ),
        (["recognize", "--object", "nosuch"], "argument --object: must be one of washer, coin"),
        (["stiffness", "--object", "nosuch"], "argument --object: must be one of racquet ball"),
        (
            ["probe-plane", "--sensor", "reflective8x8"],
            "--force 5: the finger with reflective8x8 presses at most 0.576 N (its full-scale "
            "pressure over a quarter of its area); give --force of at most 0.576",
        ),
        (
            ["locate-corner", "--force", "60"],
            "--force 60: the finger with resistive16 presses at most 51.2 N",
        ),
        (
            ["edge-radius", "--radius-mm", "2", "--sensor", "capacitive4x4"],
            "--forces 12 39: the finger with capacitive4x4 presses at most 5 N",
        ),
        (
            ["stiffness", "--forces", "1", "1e308"],
            "--forces 1 1e+308: the finger with vhdta128 presses at most 112.6 N",
        ),
        (
            ["stiffness", "--forces", "0.3", "4", "--calibration", "/nonexistent/pad.json"],
            "--forces 0.3 4: the light press must exceed the 0.5 N touch",
        ),
        (
            ["stiffness", "--forces", "39", "12", "--calibration", "/nonexistent/pad.json"],
            "--forces 39 12: give the light force first, then a firmer one",
        ),
        (
            ["stiffness", "--forces", "0.3", "0.3"],
            "--forces 0.3 0.3: give the light force first, then a firmer one",
        ),
        (  # the flags, not the library's `image`; refused before the table is built
            ["edge-radius", "--radius-mm", "3", "--y-mm", "10", "--table", "/no/t.json"],
            "error: --y-mm 10: the edge's crest passes 10 mm from the sensor's centre; on "
            "vhdta128 it must pass within 8.7 mm (the cross-section is read 7 mm either side "
            "of it, inside the active area)\n",
        ),
        (  # 12.4 mm along y at 45 degrees: 8.77 mm from the centre
            ["edge-radius", "--radius-mm", "3", "--y-mm=12.4", "--angle-deg=45", "--table", "/t"],
            "--y-mm 12.4 --angle-deg 45: the edge's crest passes 8.77 mm from the sensor's "
            "centre; on vhdta128 it must pass within 8.7 mm",
        ),
        (
            [
                "edge-radius",
                "--radius-mm",
                "3",
                "--x-mm=-4",
                "--angle-deg=90",
                "--sensor",
                "resistive16",
                "--table",
                "/no/t.json",
            ],
            "--x-mm -4 --angle-deg 90: the edge's crest passes 4 mm from the sensor's centre; "
            "on resistive16 it must pass within 3.0 mm",
        ),
        (
            ["edge-radius", "--radius-mm", "3", "--sensor", "harmon10x20"],
            "error: --sensor harmon10x20 is too small for an edge cross-section: 10 x 20 taxels",
        ),
        (  # refused by the table's build (made at these --forces), named as the flag too
            ["edge-radius", "--radius-mm", "3.2", "--sensor", "piezo8x8", "--forces", "2", "5"],
            "error: --sensor piezo8x8 is too small for an edge cross-section: 8 x 8 taxels",
        ),
        (
            ["locate-corner", "--guess-error-mm", "900"],
            "error: --guess-error-mm 900: probing from a guess this far off the corner missed "
            "the box (face 1 probe 1 found nothing within the finger's reach)\n",
        ),
        (  # refused before the table is built
            ["edge-radius", "--radius-mm", "0.1", "--table", "/no/t.json"],
            "--radius-mm 0.1: vhdta128's load grid resolves edges of radius above 0.129 mm",
        ),
        (  # refused before the table is built or written
            ["edge-radius", "--radius-mm", "3", "--forces", "39", "12", "--table", "/no/t.json"],
            "--forces 39 12: give the light force first, then a firmer one",
        ),
    ],
)
def test_bad_values_are_refused_before_any_press(capsys, arguments, message):
    try:
        code = main(["active", *arguments])
    except SystemExit as stop:  # argparse's own errors
        code = stop.code
    assert code == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and message in error, error


def test_a_force_at_the_finger_s_limit_is_taken_and_one_above_is_refused():
    from taxel.cli._active_procedures import _check_forces
    from taxel.cli._main import CommandLineError

    _check_forces("--force", [51.2], "resistive16")  # the limit as it is written
    with pytest.raises(CommandLineError, match="presses at most 51.2 N .* at most 51.2$"):
        _check_forces("--force", [51.3], "resistive16")
    # shown to four digits, rounded down: 0.576 N as it is, 112.625855595 N as 112.6 N
    with pytest.raises(CommandLineError, match="presses at most 0.576 N .* at most 0.576$"):
        _check_forces("--forces", [0.1, 0.6], "reflective8x8")
    with pytest.raises(CommandLineError, match="presses at most 112.6 N .* at most 112.6$"):
        _check_forces("--force", [113.0], "vhdta128")


def test_edge_radius_presses_at_the_given_forces(capsys, small_files, tmp_path):
    from taxel.active import EdgeRadiusTable

    table = small_files / "t.json"  # made at 12 and 39 N
    args = ["active", "edge-radius", "--radius-mm", "3", "--forces", "8", "30"]
    assert main([*args, "--table", str(table)]) == 2
    assert capsys.readouterr().err == (
        f"taxel active edge-radius: error: --forces 8 30: the --table {table} was made with "
        "12 39 N; give those or another --table\n"
    )
    made = tmp_path / "t830.json"
    assert main([*args, "--table", str(made), "--seed", "1"]) == 0
    captured = capsys.readouterr()
    assert "edge of radius 3 mm pressed at 8 N and 30 N on vhdta128" in captured.out
    assert "estimated radius: " in captured.out
    assert EdgeRadiusTable.load(made).forces.tolist() == [8.0, 30.0]


def test_stiffness_refuses_a_pad_calibration_made_at_other_forces(capsys, small_files):
    pad = small_files / "pad.json"  # made at 0.5, 12 and 39 N
    assert main(["active", "stiffness", "--forces", "10", "30", "--calibration", str(pad)]) == 2
    assert capsys.readouterr().err == (
        f"taxel active stiffness: error: --forces 10 30: the --calibration {pad} was made at "
        "12 39 N; give those or another --calibration\n"
    )


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["probe-plane", "--probes", "100000"], "argument --probes: must lie in 3..1000"),
        (["locate-corner", "--probes-per-face", "5000"], "--probes-per-face: must lie in 3..300"),
    ],
)
def test_probe_counts_have_an_upper_bound(capsys, arguments, message):
    # 100000 presses would take over an hour at about 45 ms each, without a word
    with pytest.raises(SystemExit) as stop:
        main(["active", *arguments])
    assert stop.value.code == 2
    assert message in capsys.readouterr().err


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux's /proc")
def test_an_unwritable_table_is_found_before_the_build(capsys):
    # /proc takes no new file: found at once, not after building the table
    assert main(["active", "edge-radius", "--radius-mm", "2", "--table", "/proc/t.json"]) == 2
    assert capsys.readouterr().err == (
        "taxel active edge-radius: error: --table /proc/t.json cannot be written "
        "(No such file or directory)\n"
    )


def test_a_build_that_fails_leaves_one_line(capsys, tmp_path):
    # the table's build refuses the sensor: the error alone, no notice of the build before it
    table = tmp_path / "t.json"
    args = ["active", "edge-radius", "--radius-mm", "3", "--sensor", "capacitive4x4"]
    assert main([*args, "--forces", "2", "4", "--table", str(table)]) == 2
    assert capsys.readouterr().err == (
        "taxel active edge-radius: error: --sensor capacitive4x4 is too small for an edge "
        "cross-section: 4 x 4 taxels at 5 x 5 mm leave 0.0 mm clear of the border across the "
        "edge, and the section needs 14 mm\n"
    )
    assert not table.exists()


def test_a_procedure_that_fails_after_its_build_leaves_one_line(capsys, tmp_path):
    # the calibration is built and saved; the 0.5 mm ball then falls between the load
    # grid's points 5 mm apart: the error is the only line, and the file is kept for reuse
    pad = tmp_path / "pad4.json"
    args = ["active", "stiffness", "--sensor", "capacitive4x4", "--forces", "2", "4"]
    ball = ["--shape", "ball", "--size-mm", "0.5", "--modulus-mpa", "1"]
    assert main([*args, *ball, "--calibration", str(pad)]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.count("\n") == 1
    assert captured.err == (
        "taxel active stiffness: error: --size-mm 0.5: the finger found no custom ball, too "
        "small for capacitive4x4's load grid\n"
    )
    assert pad.exists()
    assert main([*args, "--calibration", str(pad)]) == 0  # loaded: nothing on stderr
    assert capsys.readouterr().err == ""


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_a_terminal_is_told_of_the_build_while_it_runs(monkeypatch, tmp_path):
    terminal = _Terminal()
    monkeypatch.setattr("sys.stderr", terminal)
    pad = tmp_path / "pad4.json"
    args = ["active", "stiffness", "--sensor", "capacitive4x4", "--forces", "2", "4"]
    ball = ["--shape", "ball", "--size-mm", "0.5", "--modulus-mpa", "1"]
    assert main([*args, *ball, "--calibration", str(pad)]) == 2
    # the notice, then the build's progress bar in its place (of 21 presses: 7 references at
    # 3 forces), both erased (carriage return, clear to the line's end) before the error
    notice = "building the pad calibration (this takes a while) ...\r\x1b[K"
    shown, erased, error = terminal.getvalue().rpartition("\r\x1b[K")
    assert shown.startswith(notice + "\rbuilding the pad calibration:")
    assert "/21 " in shown
    assert "\n" not in shown
    assert error.startswith("taxel active stiffness: error: --size-mm 0.5: the finger found no")
    assert error.count("\n") == 1
    terminal.seek(0)
    terminal.truncate()
    other = tmp_path / "other.json"
    assert main([*args, "--calibration", str(other), "--json"]) == 0
    shown, erased, note = terminal.getvalue().rpartition("\r\x1b[K")
    assert shown.startswith(notice) and "/21 " in shown
    assert note == f"built the pad calibration and saved it to {other}\n"
    # --no-progress: the notice alone
    terminal.seek(0)
    terminal.truncate()
    last = tmp_path / "last.json"
    assert main([*args, "--calibration", str(last), "--json", "--no-progress"]) == 0
    assert terminal.getvalue() == f"{notice}built the pad calibration and saved it to {last}\n"


def test_a_terminal_is_told_of_the_pad_calibration_the_procedure_builds(monkeypatch, capsys):
    terminal = _Terminal()
    monkeypatch.setattr("sys.stderr", terminal)
    args = ["active", "stiffness", "--sensor", "capacitive4x4", "--forces", "2", "4", "--json"]
    assert main(args) == 0
    # no --calibration: the pad is calibrated first, said while it is, with a progress bar
    shown = terminal.getvalue()
    assert shown.startswith("building the pad calibration (this takes a while) ...\r\x1b[K")
    assert "building the pad calibration: " in shown and "/21 " in shown
    assert shown.endswith("\r\x1b[K") and "\n" not in shown
    assert json.loads(capsys.readouterr().out)["deformable"] is True  # the racquet ball


def test_stiffness_help_tells_of_its_three_presses(capsys):
    with pytest.raises(SystemExit):
        main(["active", "stiffness", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "from three presses: a 0.5 N touch finds the object's surface" in text
    assert "then a light and a firm press (--forces)" in text
    assert "made after the 0.5 N touch" in text


@pytest.mark.parametrize(
    ("procedure", "flag", "name"),
    [
        (["edge-radius", "--radius-mm", "3"], "--table", "t.json"),
        (["stiffness"], "--calibration", "pad.json"),
        (["recognize", "--object", "coin"], "--library", "l.json"),
    ],
)
def test_a_file_made_on_another_sensor_names_its_flag_and_the_sensor(
    capsys, small_files, procedure, flag, name
):
    path = small_files / name  # made on vhdta128
    assert main(["active", *procedure, flag, str(path), "--sensor", "resistive16"]) == 2
    assert capsys.readouterr().err == (
        f"taxel active {procedure[0]}: error: {flag} {path} was made on vhdta128, not on "
        f"--sensor resistive16: give --sensor vhdta128 or another {flag}\n"
    )


def test_a_custom_object_too_small_to_find_names_its_size(capsys, small_files):
    pad = str(small_files / "pad.json")
    args = ["--shape", "ball", "--size-mm", "0.01", "--modulus-mpa", "1", "--calibration", pad]
    assert main(["active", "stiffness", *args]) == 2
    assert capsys.readouterr().err == (
        "taxel active stiffness: error: --size-mm 0.01: the finger found no custom ball, too "
        "small for vhdta128's load grid\n"
    )


def test_an_edge_at_the_stated_limit_is_measured(capsys, small_files):
    # 8.7 mm off the centre, the limit the refusal states, along the side and the diagonal
    table = str(small_files / "t.json")
    for where in (["--y-mm", "8.7"], ["--x-mm=-8.7", "--angle-deg", "90"]):
        assert main(["active", "edge-radius", "--radius-mm", "3", "--table", table, *where]) == 0
        estimate = capsys.readouterr().out.split("estimated radius: ")[1].split(" mm")[0]
        assert abs(float(estimate) - 3.0) < 0.2


def test_json_output_is_strict_json_with_null_for_non_finite_numbers(capsys):
    import argparse

    import numpy as np

    from taxel.cli._active_procedures import _emit

    payload = {
        "stiffness_n_per_m": float("inf"),
        "growth": np.float64("nan"),
        "steps": [{"measurements": {"area": float("-inf"), "force": 2.0}}],
        "points": (1.0, float("nan")),
    }
    assert _emit(argparse.Namespace(json=True), payload, []) == 0

    def refuse(token):
        raise AssertionError(f"non-standard JSON token {token}")

    result = json.loads(capsys.readouterr().out, parse_constant=refuse)
    assert result == {
        "stiffness_n_per_m": None,
        "growth": None,
        "steps": [{"measurements": {"area": None, "force": 2.0}}],
        "points": [1.0, None],
    }


@pytest.mark.parametrize(
    ("command", "flag", "name", "key", "value", "message"),
    [
        (["edge-radius", "--radius-mm", "3"], "--table", "t.json", "radii_m", "abc", "convert"),
        (["edge-radius", "--radius-mm", "3"], "--table", "t.json", "radii_m", [3e-3], "2 known"),
        (["edge-radius", "--radius-mm", "3"], "--table", "t.json", "n_presses", 1e999, "infinity"),
        (["recognize", "--object", "coin"], "--library", "l.json", "templates", 5, "iterable"),
        (["stiffness"], "--calibration", "pad.json", "areas_m2", [[1], [1, 2]], "inhomogeneous"),
    ],
)
def test_a_corrupt_file_is_one_line_naming_the_flag_and_the_file(
    capsys, tmp_path, small_files, command, flag, name, key, value, message
):
    data = json.loads((small_files / name).read_text())
    data[key] = value
    corrupt = tmp_path / name
    corrupt.write_text(json.dumps(data))
    before = corrupt.read_text()
    assert main(["active", *command, flag, str(corrupt), "--no-progress"]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1
    assert f"{flag} {str(corrupt)!r} is not " in error and message in error
    assert corrupt.read_text() == before  # never rebuilt over
