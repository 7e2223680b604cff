"""Negative numbers in exponent notation are values of a flag, not flags (``--x -1e-3``)."""

import pytest

from taxel.cli import main


def test_a_negative_position_in_exponent_notation_is_taken(tmp_path, capsys):
    out = tmp_path / "f.npy"
    argv = ["simulate", "--sensor", "resistive16", "--object", "sphere", "--force", "1"]
    assert main([*argv, "--x", "-1e-3", "--y", "-2.5E-3", "--out", str(out), "--no-progress"]) == 0
    assert "at (-1, -2.5) mm" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["features", "f.npy", "--pitch", "-1e-3"], "argument --pitch: must be > 0, got -1e-3"),
        (
            ["simulate", "--sensor", "resistive16", "--object", "pen", "--force", "-1e-2"],
            "argument --force: must be >= 0, got -1e-2",
        ),
        (["reconstruct", "f.npy", "--lambda", "-1e-3"], "argument --lambda: must be a number"),
        (["simulate", "--x", "-inf"], "argument --x: must be finite, got -inf"),
    ],
)
def test_a_negative_value_is_judged_as_a_value(capsys, argv, message):
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err and "expected one argument" not in err
