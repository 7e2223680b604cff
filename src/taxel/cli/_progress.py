"""The progress bars of the long commands, on stderr, drawn by tqdm.

The procedures of `taxel.active`, the contact solver of `taxel.mechanics` and the iterative
solvers of `taxel.reconstruction` take a ``progress(done, total)`` callback and print
nothing; here such a callback drives a bar. It is drawn only when stderr is a terminal
(tqdm's own default, ``disable=None``), so that a script, a pipe and the tests, which read
stderr, get no bar, and it never writes to stdout (``--json`` stays clean). The bar is
erased when its block ends, well or not: an error is then the one line left on stderr.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager, contextmanager
from typing import Any

__all__ = [
    "LONG_RUN",
    "ProgressCallback",
    "add_no_progress",
    "announced",
    "progress_bar",
    "solving_on",
]

ProgressCallback = Callable[[int, int], None]

# [s] the bar of a command that is often quick (simulate, reconstruct) waits this long
LONG_RUN = 1.0
# load grids of this many cells (512 x 512: vhdta128 at --oversampling 4) or more take
# seconds to set up before a solver's first iteration (their kernels, a minute at 2048^2)
SLOW_GRID = 512 * 512


@contextmanager
def progress_bar(
    description: str,
    unit: str,
    *,
    enabled: bool = True,
    before: Callable[[], None] | None = None,
    delay: float = 0.0,
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
    delay : float, default 0
        Seconds after the first call before the bar is drawn: a run that ends sooner leaves
        no trace (tqdm's ``delay``).
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
                delay=delay,
            )
        bar.update(done - bar.n)

    try:
        yield update
    finally:
        if bar is not None:
            bar.close()


def _erase_line() -> None:
    sys.stderr.write("\r\x1b[K")  # back to the line's start, and clear it
    sys.stderr.flush()


@contextmanager
def announced(
    notice: str, description: str, unit: str, *, bar: bool = True
) -> Iterator[ProgressCallback]:
    """Say on a terminal what takes a while while it runs; erase it after.

    A long step (a build, a fine grid's solve) can run for seconds before its first
    iteration, so a user at a terminal is told why nothing happens. The block gets a
    ``progress(done, total)`` callback: at its first call a bar labelled `description`,
    counting `unit`, replaces the notice (unless `bar` is False, as with ``--no-progress``;
    see `progress_bar`). The line is erased when the block ends, well or not: an error is
    then the one line left on stderr, as for any error; a script reading stderr (not a
    terminal) gets no such line at all.
    """
    shown = sys.stderr.isatty()
    if shown:  # (short, so that it fits on one line of a terminal and erases whole)
        sys.stderr.write(f"{notice} (this takes a while) ...")
        sys.stderr.flush()
    try:
        with progress_bar(description, unit, enabled=bar, before=_erase_line) as update:
            yield update
    finally:
        if shown:
            _erase_line()


def solving_on(
    shape: tuple[int, int], description: str, *, bar: bool = True
) -> AbstractContextManager[ProgressCallback]:
    """The bar of a solve on a load grid of `shape`, as a context manager giving its callback.

    Drawn once the solve has run `LONG_RUN`; on a grid of `SLOW_GRID` cells or more, whose
    set-up takes seconds before the first iteration, after a notice shown at once.
    """
    rows, cols = shape
    if rows * cols >= SLOW_GRID:
        notice = f"solving on a {rows} x {cols} load grid"
        return announced(notice, description, "iteration", bar=bar)
    return progress_bar(description, "iteration", enabled=bar, delay=LONG_RUN)


def add_no_progress(parser: argparse.ArgumentParser) -> None:
    """Add ``--no-progress`` (as ``no_progress``) to a command whose bar waits `LONG_RUN`."""
    parser.add_argument(
        "--no-progress",
        action="store_true",
        help=f"no progress bar (one is drawn on stderr when it is a terminal and the run "
        f"lasts over {LONG_RUN:g} s; on a load grid of {SLOW_GRID:,} cells or more a notice "
        "comes first, at once, and stays)",
    )
