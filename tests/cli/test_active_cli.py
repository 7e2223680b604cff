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
        (["active", "probe-plane", "--probes", "2"], "`n_probes` must be an integer >= 3"),
        (["active", "probe-plane", "--sensor", "piezo8x8"], "piezo8x8"),
        (["active", "probe-plane", "--sensor", "nothing"], "`sensor`"),
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
