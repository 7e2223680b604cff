"""The command line: version, help, the one-line error policy, and the interim demo."""

import subprocess
import sys
from pathlib import Path

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
    assert mechanics.describe_indenters() == _arguments.INDENTER_DESCRIPTIONS
    assert active.NORMALIZATIONS == _arguments.NORMALIZATIONS
    assert active.MODEL_NAMES == _arguments.MODEL_NAMES
    assert tuple(active.DEFORMATION_OBJECTS) == _arguments.DEFORMATION_OBJECTS


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
    assert capsys.readouterr().err == (
        f"taxel demo: error: --out {str(target)!r} must be a folder, but it is a file\n"
    )
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


@pytest.mark.parametrize("out", ["", "  "])
def test_demo_refuses_an_empty_output_folder(capsys, tmp_path, monkeypatch, out, one_experiment):
    monkeypatch.chdir(tmp_path)  # an empty --out would have meant the current folder
    assert main(["demo", "--quick", "--no-progress", "--out", out]) == 2
    assert capsys.readouterr().err == f"taxel demo: error: --out must name a folder, got {out!r}\n"
    assert list(tmp_path.iterdir()) == []


def test_a_failed_demo_keeps_the_earlier_report(capsys, tmp_path, monkeypatch, one_experiment):
    assert main(["demo", "--quick", "--no-progress", "--out", str(tmp_path)]) == 0
    capsys.readouterr()
    before = {name: (tmp_path / name).read_bytes() for name in ("report.html", "results.json")}
    write_text = Path.write_text

    def disk_full(path, text, *args, **kwargs):
        if path.name.startswith(".results.json"):
            write_text(path, text[:100], *args, **kwargs)
            raise OSError(28, "No space left on device")
        return write_text(path, text, *args, **kwargs)

    monkeypatch.setattr(Path, "write_text", disk_full)
    assert main(["demo", "--quick", "--no-progress", "--out", str(tmp_path)]) == 2
    results = tmp_path / "results.json"
    assert capsys.readouterr().err == (
        f"taxel demo: error: --out {results} cannot be written (No space left on device)\n"
    )
    assert {name: (tmp_path / name).read_bytes() for name in before} == before
    assert sorted(path.name for path in tmp_path.iterdir()) == sorted(before)


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux's /proc")
def test_demo_finds_an_unwritable_folder_before_the_experiments(capsys, monkeypatch):
    from taxel.report import _runner

    monkeypatch.setattr(_runner, "EXPERIMENTS", ())  # none would run
    assert main(["demo", "--out", "/proc/taxel-demo"]) == 2
    assert capsys.readouterr().err == (
        "taxel demo: error: --out /proc/taxel-demo cannot be written (No such file or directory)\n"
    )
