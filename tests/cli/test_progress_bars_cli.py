"""``taxel simulate`` and ``reconstruct``: a bar on a terminal's stderr for a long run only."""

import io

import numpy as np
import pytest

from taxel.cli import main


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def _simulate(tmp_path):
    out = tmp_path / "frame.npy"
    argv = ["simulate", "--sensor", "resistive16", "--object", "sphere", "--force", "2"]
    return [*argv, "--oversampling", "2", "--seed", "1", "--out", str(out), "--overwrite"]


def _reconstruct(tmp_path, frame_file):
    argv = [
        "reconstruct",
        str(frame_file),
        "--sensor",
        "resistive16",
        "--method",
        "tv",
        "--lambda",
        "300",
    ]
    return [*argv, "--json", "--out", str(tmp_path / "p.npy"), "--overwrite"]


@pytest.mark.parametrize(("command", "bar"), [("simulate", "contact: "), ("reconstruct", "tv: ")])
def test_a_terminal_sees_the_bar_and_stdout_is_unchanged(
    monkeypatch, capsys, tmp_path, frame_file, command, bar
):
    argv = _simulate(tmp_path) if command == "simulate" else _reconstruct(tmp_path, frame_file)
    assert main([*argv, "--no-progress"]) == 0
    plain = capsys.readouterr()
    assert plain.err == ""
    terminal = _Terminal()
    monkeypatch.setattr("sys.stderr", terminal)
    monkeypatch.setattr("taxel.cli._progress.LONG_RUN", 0.0)  # draw it at once
    assert main(argv) == 0
    assert capsys.readouterr().out == plain.out  # the same report, nothing else
    shown = terminal.getvalue()
    assert shown.startswith("\r" + bar) and "iteration" in shown
    assert "\n" not in shown  # erased when done (leave=False)
    # --no-progress on a terminal: nothing on stderr
    terminal.seek(0)
    terminal.truncate()
    assert main([*argv, "--no-progress"]) == 0
    assert terminal.getvalue() == ""


@pytest.mark.parametrize("command", ["simulate", "reconstruct"])
def test_a_quick_run_leaves_no_trace_on_a_terminal(
    monkeypatch, capsys, tmp_path, frame_file, command
):
    # the bar waits LONG_RUN (1 s) before it is drawn: these runs end sooner (tqdm's clock
    # stands still, so that a slow host cannot make them last longer)
    argv = _simulate(tmp_path) if command == "simulate" else _reconstruct(tmp_path, frame_file)
    terminal = _Terminal()
    monkeypatch.setattr("sys.stderr", terminal)
    monkeypatch.setattr("tqdm.std.time", lambda: 1000.0)  # frozen: no run lasts 1 s
    assert main(argv) == 0
    assert terminal.getvalue() == ""


def test_a_fine_grid_is_announced_before_its_set_up(monkeypatch, tmp_path):
    # resistive16 at --oversampling 2 is a 32 x 32 grid: taken here for a fine one
    monkeypatch.setattr("taxel.cli._progress.SLOW_GRID", 32 * 32)
    terminal = _Terminal()
    monkeypatch.setattr("sys.stderr", terminal)
    assert main(_simulate(tmp_path)) == 0
    shown = terminal.getvalue()
    assert shown.startswith("solving on a 32 x 32 load grid (this takes a while) ...\r\x1b[K")
    assert "contact: " in shown and shown.endswith("\r\x1b[K") and "\n" not in shown
    terminal.seek(0)
    terminal.truncate()
    assert main([*_simulate(tmp_path), "--no-progress"]) == 0  # the notice, no bar
    assert terminal.getvalue() == "solving on a 32 x 32 load grid (this takes a while) ...\r\x1b[K"


def test_no_terminal_no_bar(capsys, tmp_path, monkeypatch):
    # stderr not a terminal (a pipe, a log, these tests): no bar even at once
    monkeypatch.setattr("taxel.cli._progress.LONG_RUN", 0.0)
    assert main(_simulate(tmp_path)) == 0
    assert capsys.readouterr().err == ""


def test_the_flag_is_in_the_help(capsys):
    for command in ("simulate", "reconstruct"):
        with pytest.raises(SystemExit):
            main([command, "--help"])
        assert "--no-progress" in capsys.readouterr().out


def test_simulate_writes_what_the_sensor_press_reads(tmp_path):
    # with its bar, simulate writes the frame press gives, bit for bit
    import dataclasses

    from taxel.mechanics import make_indenter
    from taxel.sensor import make_sensor

    assert main([*_simulate(tmp_path), "--no-progress"]) == 0
    sensor = dataclasses.replace(make_sensor("resistive16"), oversampling=2)
    frame = sensor.press(make_indenter("sphere"), normal_force=2.0, rng=1)
    assert np.array_equal(np.load(tmp_path / "frame.npy"), frame.raw)
