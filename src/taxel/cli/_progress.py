"""The progress bars of the long commands, on stderr, drawn by tqdm.

The procedures of `taxel.active` take a ``progress(done, total)`` callback and print
nothing; here such a callback drives a bar. It is drawn only when stderr is a terminal
(tqdm's own default, ``disable=None``), so that a script, a pipe and the tests, which read
stderr, get no bar, and it never writes to stdout (``--json`` stays clean). The bar is
erased when its block ends, well or not: an error is then the one line left on stderr.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

__all__ = ["ProgressCallback", "progress_bar"]

ProgressCallback = Callable[[int, int], None]


@contextmanager
def progress_bar(
    description: str,
    unit: str,
    *,
    enabled: bool = True,
    before: Callable[[], None] | None = None,
) -> Iterator[ProgressCallback]:
    """A callback ``progress(done, total)`` that shows a bar on stderr while the block runs.

    Parameters
    ----------
    description : str
        The bar's label.
    unit : str
        What is counted (a press, an edge, a model pose).
    enabled : bool, default True
        False: the callback does nothing (``--no-progress``).
    before : callable, optional
        Called once, just before the bar first appears (to erase a notice it replaces).
    """
    bar: Any = None

    def update(done: int, total: int) -> None:
        nonlocal bar
        if not enabled:
            return
        if bar is None:
            from tqdm import tqdm

            shown = sys.stderr.isatty()
            if shown and before is not None:
                before()
            bar = tqdm(
                total=total,
                desc=description,
                unit=unit,
                leave=False,
                file=sys.stderr,
                disable=not shown,
            )
        bar.update(done - bar.n)

    try:
        yield update
    finally:
        if bar is not None:
            bar.close()
