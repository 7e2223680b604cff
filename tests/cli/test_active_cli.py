"""``taxel active``: the procedures from the command line."""

import json

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
        (["active", "probe-plane", "--probes", "2"], "argument --probes: must be >= 3, got 2"),
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
    assert table.read_text() == before  # loaded, never rewritten
    # beyond the table's radii (2.2-4.7 mm), the table says so, not only in JSON
    args = ["active", "edge-radius", "--radius-mm", "9", "--table", str(table), "--seed", "1"]
    assert main(args) == 0
    assert "match: at the end of the table" in capsys.readouterr().out


def test_stiffness_tells_the_racquet_ball_from_the_acrylic_sphere(capsys, small_files):
    pad = str(small_files / "pad.json")
    assert main(["active", "stiffness", "--calibration", pad]) == 0
    assert "verdict: deformable" in capsys.readouterr().out
    assert main(["active", "stiffness", "--object", "acrylic sphere", "--calibration", pad]) == 0
    assert "verdict: rigid" in capsys.readouterr().out


def test_recognize_ranks_the_candidates(capsys, small_files):
    library = str(small_files / "l.json")
    assert (
        main(["active", "recognize", "--object", "washer", "--library", library, "--seed", "2"])
        == 0
    )
    assert "recognized as: washer" in capsys.readouterr().out


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
    broken = tmp_path / "broken.json"
    broken.write_text('{"format": "taxel.pad_calibration"}')
    assert main(["active", "stiffness", "--calibration", str(broken)]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "lacks forces_n" in error
