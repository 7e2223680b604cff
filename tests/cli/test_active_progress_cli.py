"""``taxel active``: the progress bar on a terminal's stderr, never on stdout."""

import io
import json

import pytest

from taxel.cli import main


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


@pytest.mark.parametrize(
    ("args", "bar"),
    [
        (["probe-plane", "--probes", "6", "--seed", "2"], "probing: "),
        (["locate-corner", "--probes-per-face", "4"], "probing: "),
    ],
)
def test_a_terminal_sees_the_bar_and_stdout_keeps_its_json(monkeypatch, capsys, args, bar):
    assert main(["active", *args, "--json", "--no-progress"]) == 0
    plain = capsys.readouterr()
    assert plain.err == ""
    terminal = _Terminal()
    monkeypatch.setattr("sys.stderr", terminal)
    assert main(["active", *args, "--json"]) == 0
    assert capsys.readouterr().out == plain.out  # the same JSON, nothing else
    json.loads(plain.out)
    shown = terminal.getvalue()
    assert shown.startswith("\r" + bar) and "press" in shown
    assert "\n" not in shown  # erased when done (leave=False): no line left behind
    # --no-progress on a terminal: nothing on stderr
    terminal.seek(0)
    terminal.truncate()
    assert main(["active", *args, "--json", "--no-progress"]) == 0
    assert terminal.getvalue() == ""


def test_no_terminal_no_bar(capsys):
    # stderr not a terminal (a pipe, a log, these tests): tqdm's default draws nothing
    assert main(["active", "probe-plane", "--probes", "4", "--json"]) == 0
    captured = capsys.readouterr()
    assert captured.err == ""
    json.loads(captured.out)
