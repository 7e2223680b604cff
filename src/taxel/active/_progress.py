"""The optional progress callback of the long procedures and builds.

A procedure that loops over many presses (probes, table entries, library models) takes a
keyword-only ``progress`` callback, None by default (the library itself prints nothing).
It is called as ``progress(done, total)`` after each unit of work: ``done`` runs from 1 to
``total``, which is the same in every call. The command line passes one that drives a
progress bar on stderr.
"""

from __future__ import annotations

from collections.abc import Callable

from taxel._validation import check_progress

__all__ = ["Progress", "check_progress"]

Progress = Callable[[int, int], object]
