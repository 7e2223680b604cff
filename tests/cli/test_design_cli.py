import json

import pytest

from taxel.cli import main


@pytest.mark.parametrize("preset", ["vhdta128", "harmon10x20"])
def test_design_prints_the_harmon_table(capsys, preset):
    assert main(["design", preset]) == 0
    out = capsys.readouterr().out
    for criterion in (
        "spatial resolution",
        "array size",
        "sensitivity",
        "dynamic range",
        "hysteresis",
        "stability",
        "sampling rate",
        "monotonic response",
        "compliant interface",
    ):
        assert criterion in out
    assert "measured" in out and "target" in out and "verdict" in out
    lines = {line.split("  ")[0]: line for line in out.splitlines()}
    resolution = lines["spatial resolution"]
    assert " mm " in resolution and "1-2 mm" in resolution
    if preset == "vhdta128":
        assert "1.16 mm" in resolution and resolution.rstrip().endswith("pass")
        assert "VHDTA" in out
    else:
        assert "2.25 mm" in resolution and resolution.rstrip().endswith("FAIL")
        assert lines["sampling rate"].split()[2:4] == ["1000", "Hz"]


def test_design_json_is_in_si_units(capsys):
    assert main(["design", "capacitive4x4", "--json", "--seed", "2"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["sensor"] == "capacitive4x4" and data["seed"] == 2
    rows = {row["criterion"]: row for row in data["rows"]}
    assert rows["spatial resolution"]["unit"] == "m"
    assert rows["spatial resolution"]["value"] == pytest.approx(6.25e-3)
    assert rows["array size"]["passed"] is False  # 4 x 4 is below 5 x 10
    assert data["passed"] + data["failed"] == 9


@pytest.mark.parametrize(
    ("argv", "match"),
    [
        (["design", "vhdta256"], "PRESET: must be one of vhdta128"),
        (["design", "vhdta128", "--seed", "x"], "argument --seed: must be an integer"),
    ],
)
def test_design_errors_are_one_line(capsys, argv, match):
    try:
        code = main(argv)
    except SystemExit as stop:  # argparse's own errors
        code = stop.code
    assert code == 2
    err = capsys.readouterr().err
    assert match in err and len(err.strip().splitlines()) == 1
