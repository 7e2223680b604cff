"""The optional progress callback of the long procedures and builds.

A procedure that loops over many presses (probes, table entries, library models) takes a
keyword-only ``progress`` callback, None by default (the library itself prints nothing).
It is called as ``progress(done, total)`` after each unit of work: ``done`` runs from 1 to
``total``, which is the same in every call. The command line passes one that drives a
progress bar on stderr.
"""

from __future__ import annotations

from collections.abc import Callable

__all__ = ["Progress", "check_progress"]

Progress = Callable[[int, int], object]


def check_progress(progress: Progress | None) -> Progress | None:
    """`progress` itself when it is None or callable; else a TypeError naming it."""
    if progress is not None and not callable(progress):
        raise TypeError(f"`progress` must be a callable (done, total) or None, got {progress!r}")
    return progress
