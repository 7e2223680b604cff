"""Whole-number settings (numbers of probes, frames, trials) checked without int()'s surprises."""

from __future__ import annotations

import math
import numbers
from typing import Any

__all__ = ["is_whole"]


def is_whole(value: Any) -> bool:
    """True when `value` is a finite real number with no fractional part, not a bool.

    ``int(value) != value`` raises OverflowError for inf and an unnamed ValueError for NaN;
    this only answers, so that the caller's message, naming its parameter, is raised.

    Examples
    --------
    >>> [is_whole(v) for v in (3, 3.0, 3.5, float("inf"), float("nan"), "3", True)]
    [True, True, False, False, False, False, False]
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    return math.isfinite(value) and float(value).is_integer()
