"""The report's data: experiments with their figures, tables and computed verdicts."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

__all__ = ["Experiment", "Figure", "Table", "Verdict"]


@dataclass(frozen=True)
class Verdict:
    """One claim of a seed checked against our result.

    Attributes
    ----------
    claim : str
        What is checked, in words.
    ours : str
        Our value, formatted.
    seed : str
        What the seed reports (or "-" when the seed gives no number).
    passed : bool
        Whether the claim holds for our result: always computed from the numbers.
    """

    claim: str
    ours: str
    seed: str
    passed: bool

    def to_dict(self) -> dict[str, Any]:
        return {
            "claim": self.claim,
            "ours": self.ours,
            "seed": self.seed,
            "passed": bool(self.passed),
        }


@dataclass(frozen=True)
class Figure:
    """A PNG image with its caption."""

    caption: str
    png: bytes = field(repr=False)


@dataclass(frozen=True)
class Table:
    """A small table: a header row and rows of already formatted cells."""

    title: str
    header: Sequence[str]
    rows: Sequence[Sequence[str]]

    def to_dict(self) -> dict[str, Any]:
        return {
            "title": self.title,
            "header": list(self.header),
            "rows": [list(row) for row in self.rows],
        }


@dataclass(frozen=True)
class Experiment:
    """One experiment of the seeds, run through the pipeline.

    Attributes
    ----------
    key : str
        Short identifier (used in results.json).
    title : str
        Heading in the report.
    seed_reference : str
        Which part of which seed it reproduces.
    summary : str
        What was done, in a few sentences.
    figures, tables, verdicts
        What it shows.
    numbers : Mapping[str, Any]
        Every number it computed (SI units), for results.json.
    seconds : float
        How long it took.
    """

    key: str
    title: str
    seed_reference: str
    summary: str
    figures: Sequence[Figure] = ()
    tables: Sequence[Table] = ()
    verdicts: Sequence[Verdict] = ()
    numbers: Mapping[str, Any] = field(default_factory=dict)
    seconds: float = 0.0

    @property
    def passed(self) -> bool:
        """True when every verdict passed."""
        return all(verdict.passed for verdict in self.verdicts)

    def to_dict(self) -> dict[str, Any]:
        return {
            "key": self.key,
            "title": self.title,
            "seed_reference": self.seed_reference,
            "summary": self.summary,
            "figures": [figure.caption for figure in self.figures],
            "tables": [table.to_dict() for table in self.tables],
            "verdicts": [verdict.to_dict() for verdict in self.verdicts],
            "numbers": _plain(self.numbers),
            "passed": self.passed,
            "seconds": round(self.seconds, 3),
        }


def _plain(value: Any) -> Any:
    """NumPy scalars and arrays to plain JSON values."""
    import numpy as np

    if isinstance(value, Mapping):
        return {str(key): _plain(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(item) for item in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    return value
