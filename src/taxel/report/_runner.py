"""Run the seeds' experiments and write report.html and results.json."""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from taxel.io import write_files
from taxel.report._active_seed import deformation, edge_radius
from taxel.report._context import DemoContext
from taxel.report._design import harmon_criteria
from taxel.report._html import render_html
from taxel.report._inverse import inverse_problem
from taxel.report._mechanics import forward_problem
from taxel.report._model import Experiment
from taxel.report._passive import can_top, edge_at_two_forces, pen_tip, texture_table, washer
from taxel.report._probing import slot_corner_normal

__all__ = ["EXPERIMENTS", "DemoResult", "run_demo"]

ExperimentFunction = Callable[[DemoContext], Experiment]

# in the order of the seeds
EXPERIMENTS: tuple[ExperimentFunction, ...] = (
    pen_tip,
    edge_at_two_forces,
    can_top,
    washer,
    texture_table,
    deformation,
    edge_radius,
    slot_corner_normal,
    forward_problem,
    inverse_problem,
    harmon_criteria,
)


@dataclass(frozen=True)
class DemoResult:
    """What a demo run produced."""

    experiments: tuple[Experiment, ...]
    report_path: Path
    results_path: Path
    seconds: float

    @property
    def passed(self) -> int:
        """Number of experiments whose every check passed."""
        return sum(experiment.passed for experiment in self.experiments)


_TITLE = "<title>taxel: the seeds' experiments</title>"


def _written_by_taxel(path: Path) -> bool:
    """Whether an existing report.html or results.json came from an earlier demo run."""
    text = path.read_text(encoding="utf-8", errors="replace")
    if path.suffix == ".html":
        return _TITLE in text
    try:
        data = json.loads(text)
    except json.JSONDecodeError:
        return False
    return isinstance(data, dict) and {"quick", "seconds", "experiments"} <= set(data)


def _writable_folder(out: Path) -> Path:
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise ValueError(f"`out` must be a folder, but {out} is a file")
    out.mkdir(parents=True, exist_ok=True)
    for name in ("report.html", "results.json"):
        existing = out / name
        if existing.exists() and not _written_by_taxel(existing):
            raise FileExistsError(
                f"{existing} exists and was not written by taxel demo; choose another --out"
            )
    return out


def run_demo(
    out: Path | str,
    *,
    quick: bool = False,
    experiments: Sequence[ExperimentFunction] | None = None,
    progress: bool = True,
) -> DemoResult:
    """Run the experiments and write ``report.html`` and ``results.json`` into `out`.

    Parameters
    ----------
    out : path
        Output folder (created if needed). The two files in it, when an earlier run wrote
        them, are replaced once both new ones are written; other files of those names are
        refused.
    quick : bool
        Fewer trials, for a fast look.
    experiments : sequence of callables, optional
        The experiments to run (default: `EXPERIMENTS`, all of them in the seeds' order).
    progress : bool
        Show a progress bar on stderr.

    Returns
    -------
    DemoResult
    """
    folder = _writable_folder(Path(out))
    if experiments is None:
        experiments = EXPERIMENTS
    context = DemoContext(quick=quick)
    started = time.perf_counter()
    results: list[Experiment] = []
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=len(experiments), desc="taxel demo", unit="experiment", leave=True)
    for function in experiments:
        if bar is not None:
            bar.set_postfix_str(function.__name__)
        begin = time.perf_counter()
        experiment = function(context)
        results.append(_timed(experiment, time.perf_counter() - begin))
        if bar is not None:
            bar.update()
    if bar is not None:
        bar.close()
    seconds = time.perf_counter() - started
    report = folder / "report.html"
    html = render_html(results, quick=quick, seconds=seconds, seed=context.seed)
    numbers = {
        "quick": quick,
        "seed": context.seed,
        "seconds": round(seconds, 2),
        "experiments": [experiment.to_dict() for experiment in results],
    }
    result_file = folder / "results.json"
    text = json.dumps(numbers, indent=2, allow_nan=True)
    # both or neither, each complete: a failed write (a full disk) keeps an earlier run's
    write_files(
        [
            (report, lambda temporary: temporary.write_text(html, encoding="utf-8")),
            (result_file, lambda temporary: temporary.write_text(text, encoding="utf-8")),
        ]
    )
    return DemoResult(tuple(results), report, result_file, seconds)


def _timed(experiment: Experiment, seconds: float) -> Experiment:
    from dataclasses import replace

    return replace(experiment, seconds=seconds)
