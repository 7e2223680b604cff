"""``taxel demo [--out DIR] [--quick]``: the seeds' experiments end to end, as a report."""

from __future__ import annotations

import argparse
from pathlib import Path

from taxel.cli._files import writing
from taxel.cli._main import CommandLineError

__all__ = ["register"]

_FILES = ("report.html", "results.json")


def _output_folder(text: str) -> Path:
    """The --out folder, created if needed, once it is known to take the report's files.

    Checked before the experiments run (they take minutes), not after.
    """
    from taxel.io import check_new_file

    if not text.strip():
        raise CommandLineError(f"--out must name a folder, got {text!r}")
    folder = Path(text)
    if folder.exists() and not folder.is_dir():
        raise CommandLineError(f"--out {text!r} must be a folder, but it is a file")
    try:
        with writing("--out", folder):
            folder.mkdir(parents=True, exist_ok=True)
    except OSError as error:  # about a parent made on the way: named, as is the folder
        why = f"{error.strerror or error}: {error.filename}"
        raise CommandLineError(f"--out {text} cannot be made ({why})") from None
    check_new_file(folder / _FILES[0], suffix=".html", overwrite=True, name="--out")
    return folder


def _run(arguments: argparse.Namespace) -> int:
    from taxel.report import run_demo

    folder = _output_folder(arguments.out)
    with writing("--out", *(folder / name for name in _FILES)):
        result = run_demo(folder, quick=arguments.quick, progress=not arguments.no_progress)
    width = max(len(experiment.title) for experiment in result.experiments)
    print(f"{'experiment':{width}}  checks  verdict")
    for experiment in result.experiments:
        checks = f"{sum(v.passed for v in experiment.verdicts)}/{len(experiment.verdicts)}"
        verdict = "pass" if experiment.passed else "FAIL"
        print(f"{experiment.title:{width}}  {checks:>6}  {verdict}")
    print(
        f"\n{result.passed} of {len(result.experiments)} experiments pass every check "
        f"({result.seconds:.0f} s)"
    )
    print(f"report:  {result.report_path}\nresults: {result.results_path}")
    return 0


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``taxel demo`` to the command line."""
    parser = commands.add_parser(
        "demo",
        help="run the seeds' experiments and write an HTML report",
        description="Run the seeds' experiments and write report.html and results.json into "
        "DIR. The report and results of an earlier demo there are replaced (both at once, "
        "once the new ones are complete); files of those names that taxel demo did not "
        "write are refused.",
    )
    parser.add_argument(
        "--out", metavar="DIR", default="demo-output", help="output folder (default: demo-output)"
    )
    parser.add_argument(
        "--quick", action="store_true", help="fewer trials and smaller tables: a fast look"
    )
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    parser.set_defaults(handler=_run)
