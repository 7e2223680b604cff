"""How Harmon's rows read to a person: values in display units, targets in words."""

from __future__ import annotations

import math
from typing import Any

__all__ = ["display_cells"]


def _number(value: float, digits: int = 3) -> str:
    if 1e3 <= abs(value) < 1e9:
        return f"{value:.0f}"  # 1000, not 1e+03
    return f"{value:.{digits}g}"


def _range(low: float | None, high: float | None, scale: float, unit: str) -> str:
    if low is not None and high is not None:
        return f"{_number(low * scale)}-{_number(high * scale)} {unit}".strip()
    if low is not None:
        return f">= {_number(low * scale)} {unit}".strip()
    if high is not None:
        return f"<= {_number(high * scale)} {unit}".strip()
    return "-"


def display_cells(row: Any) -> tuple[str, str]:
    """(measured, target) of a row in display units."""
    low, high = row.target
    value = row.value
    name = row.criterion
    if name == "array size":
        shape = row.method.split(" taxels")[0]
        return f"{value:.0f} ({shape})", "5 x 10 to 10 x 20"
    if name == "dynamic range":
        measured = "-" if value is None else f"{_number(value)}:1"
        return measured, f">= {low:.0f}:1"
    if name in ("hysteresis", "stability"):
        measured = "-" if value is None else f"{value * 100:.3g} %"
        target = "none" if high is None else f"< 1 level ({high * 100:.2g} %)"
        return measured, target
    if name in ("monotonic response", "working taxels"):
        measured = "-" if value is None else f"{value * 100:.4g} % of taxels"
        return measured, "all taxels"
    if name == "reliable levels":
        return f"{value:.0f} ({math.log2(max(value, 1.0)):.1f} bits)", "-"
    if name == "density":
        return f"{value * 1e-4:.4g} /cm^2 ({row.method.split(': ')[-1]})", "-"
    scale, unit = {"m": (1e3, "mm"), "Pa": (1e-6, "MPa"), "N": (1e3, "mN"), "Hz": (1.0, "Hz")}[
        row.unit
    ]
    measured = "not measurable" if value is None else f"{_number(value * scale)} {unit}"
    if value is None and row.passed is False:  # measured, but beyond what the array shows
        measured = {
            "spatial resolution": "not resolved on the array",
            "sensitivity": "above the full-scale force",
        }.get(name, measured)
    return measured, _range(low, high, scale, unit)
