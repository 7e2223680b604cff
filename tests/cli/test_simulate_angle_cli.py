"""``taxel simulate --angle``: an angle no double holds to a microradian is refused."""

import pytest

from taxel.cli import main


@pytest.mark.parametrize("angle", ["1e300", "-1e10", "9e9"])
def test_an_angle_a_double_cannot_hold_is_refused(tmp_path, capsys, angle):
    out = tmp_path / "f.npy"
    argv = ["simulate", "--sensor", "resistive16", "--object", "edge", "--force", "1"]
    with pytest.raises(SystemExit) as stop:
        main([*argv, f"--angle={angle}", "--out", str(out)])
    assert stop.value.code == 2
    assert capsys.readouterr().err == (
        "taxel simulate: error: argument --angle: a double holds an angle to 1 urad only up "
        f"to about 8.6e9 rad, got {angle}\n"
    )
    assert not out.exists()


def test_an_angle_of_many_turns_is_still_taken(tmp_path, capsys):
    out = tmp_path / "f.npy"
    argv = ["simulate", "--sensor", "resistive16", "--object", "edge", "--force", "1"]
    assert main([*argv, "--angle", "-8e9", "--out", str(out), "--no-progress"]) == 0
    assert out.exists()
