"""``taxel calibrate`` and ``design`` run for seconds: a terminal is told while they do."""

import io

import pytest

from taxel.cli import main


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


@pytest.mark.parametrize(
    ("args", "notice"),
    [
        (
            ["calibrate", "--sensor", "capacitive4x4"],
            "calibrating capacitive4x4 with flat-plate presses",
        ),
        (["design", "capacitive4x4"], "measuring capacitive4x4 against Harmon's criteria"),
    ],
)
def test_a_terminal_is_told_and_the_notice_erased(tmp_path, capsys, monkeypatch, args, notice):
    if args[0] == "calibrate":
        args = [*args, "--out", str(tmp_path / "cal.npz")]
    terminal = _Terminal()
    monkeypatch.setattr("sys.stderr", terminal)
    assert main(args) == 0
    assert terminal.getvalue() == f"{notice} (this takes a while) ...\r\x1b[K"
    assert "this takes a while" not in capsys.readouterr().out


@pytest.mark.parametrize(
    ("preset", "why"),
    [
        ("piezo8x8", "senses only changes of load (stress): a static calibration is not defined"),
        ("photoelastic64", "is photoelastic: a flat plate makes no fringes"),
    ],
)
def test_a_preset_that_cannot_be_calibrated_names_the_flag(tmp_path, capsys, preset, why):
    out = tmp_path / "cal.npz"
    assert main(["calibrate", "--sensor", preset, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"taxel calibrate: error: --sensor {preset!r} {why}")
    assert err.count("\n") == 1 and "`" not in err and not out.exists()


def test_the_help_says_which_presets_cannot_be_calibrated(capsys):
    with pytest.raises(SystemExit):
        main(["calibrate", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "not piezo8x8 (it senses only changes of load) nor photoelastic64" in text
