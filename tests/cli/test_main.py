"""The command line: version, help, the one-line error policy, and the interim demo."""

import subprocess
import sys

import pytest

import taxel
from taxel.cli import main


def test_version(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out.strip() == f"taxel {taxel.__version__}"


def test_help_lists_subcommands(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    assert "demo" in capsys.readouterr().out


def test_unknown_command_is_one_line_and_exit_2(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["teleport"])
    assert stop.value.code == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "invalid choice: 'teleport'" in error


def test_no_command_is_a_one_line_usage_error(capsys):
    assert main([]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err == "taxel: error: a COMMAND is required (taxel --help lists them)\n"


def test_the_parser_s_names_are_the_library_s():
    from taxel import active, mechanics, sensor
    from taxel.cli import _arguments

    assert sensor.PRESET_NAMES == _arguments.PRESET_NAMES
    assert mechanics.INDENTER_NAMES == _arguments.INDENTER_NAMES
    assert active.NORMALIZATIONS == _arguments.NORMALIZATIONS


def test_help_does_not_load_the_library_s_layers():
    # the parser alone: `taxel --help` answers in a fraction of a second
    code = (
        "import sys; from taxel.cli._main import _build_parser; _build_parser(); "
        "print(sorted(m for m in sys.modules if m.startswith(('taxel.', 'scipy'))))"
    )
    completed = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    loaded = completed.stdout
    for layer in ("sensor", "mechanics", "transducers", "active", "features", "report"):
        assert f"'taxel.{layer}" not in loaded
    assert "'scipy" not in loaded


def test_python_dash_m_runs_the_same_program():
    completed = subprocess.run(
        [sys.executable, "-m", "taxel", "--version"], capture_output=True, text=True, check=False
    )
    assert completed.returncode == 0 and completed.stdout.startswith("taxel ")


@pytest.fixture
def one_experiment(monkeypatch):
    """The command line's plumbing only: the experiments themselves are tested in tests/report."""
    from taxel.report import _runner
    from taxel.report._passive import pen_tip

    monkeypatch.setattr(_runner, "EXPERIMENTS", (pen_tip,))


def test_demo_writes_the_report_and_prints_a_summary(capsys, tmp_path, one_experiment):
    assert main(["demo", "--quick", "--no-progress", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "experiments pass every check" in out
    assert (tmp_path / "report.html").exists() and (tmp_path / "results.json").exists()


def test_demo_refuses_a_file_as_output_folder(capsys, tmp_path, one_experiment):
    target = tmp_path / "taken.txt"
    target.write_text("keep me")
    assert main(["demo", "--quick", "--no-progress", "--out", str(target)]) == 2
    assert "`out` must be a folder" in capsys.readouterr().err
    assert target.read_text() == "keep me"


def test_demo_replaces_only_its_own_files(capsys, tmp_path, one_experiment):
    assert main(["demo", "--quick", "--no-progress", "--out", str(tmp_path)]) == 0
    assert main(["demo", "--quick", "--no-progress", "--out", str(tmp_path)]) == 0  # rerun
    capsys.readouterr()
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "report.html").write_text("<html>my own notes</html>")
    assert main(["demo", "--quick", "--no-progress", "--out", str(mine)]) == 2
    assert "was not written by taxel demo" in capsys.readouterr().err
    assert (mine / "report.html").read_text() == "<html>my own notes</html>"
