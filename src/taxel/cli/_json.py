"""Results printed as strict JSON (internal to the command line)."""

from __future__ import annotations

import json
import math
from typing import Any

__all__ = ["strict_json"]


def strict_json(payload: Any) -> str:
    """`payload` as indented JSON, every NaN or infinite number as null.

    Strict JSON has no NaN or Infinity tokens (Python writes them, `jq` and JavaScript
    refuse them); NumPy scalars are written as numbers.
    """
    return json.dumps(_finite(payload), indent=2, allow_nan=False, default=float)


def _finite(value: Any) -> Any:
    if isinstance(value, dict):
        return {key: _finite(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(item) for item in value]
    if isinstance(value, float) and not math.isfinite(value):  # (numpy's float64 too)
        return None
    return value
