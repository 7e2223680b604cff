"""``taxel demo [--out DIR] [--quick]``: the seeds' experiments end to end, as a report."""

from __future__ import annotations

import argparse

__all__ = ["register"]


def _run(arguments: argparse.Namespace) -> int:
    from taxel.report import run_demo

    result = run_demo(arguments.out, quick=arguments.quick, progress=not arguments.no_progress)
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
        "demo", help="run the seeds' experiments and write an HTML report"
    )
    parser.add_argument(
        "--out", metavar="DIR", default="demo-output", help="output folder (default: demo-output)"
    )
    parser.add_argument(
        "--quick", action="store_true", help="fewer trials and smaller tables: a fast look"
    )
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    parser.set_defaults(handler=_run)
