"""The main job: the seeds' experiments end to end, as an HTML report (a leaf layer).

run_demo, DemoResult, EXPERIMENTS, DemoContext; the data model Experiment, Figure, Table,
Verdict.
"""

from taxel.report._context import DemoContext
from taxel.report._model import Experiment, Figure, Table, Verdict
from taxel.report._runner import EXPERIMENTS, DemoResult, run_demo

__all__ = [
    "EXPERIMENTS",
    "DemoContext",
    "DemoResult",
    "Experiment",
    "Figure",
    "Table",
    "Verdict",
    "run_demo",
]
