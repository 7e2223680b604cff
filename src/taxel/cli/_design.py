"""``taxel design PRESET``: a preset sensor measured against Harmon's criteria.

Prints the measured value, Harmon's target and the verdict of each criterion (chapter
section 25.2), then how each was measured; ``--json`` prints the same in SI units.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from typing import Any

from taxel.cli._arguments import seed

__all__ = ["register"]


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


def _cells(row: Any) -> tuple[str, str]:
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


def _verdict(row: Any) -> str:
    return {True: "pass", False: "FAIL", None: "-"}[row.passed]


def _text(table: Any, sensor: Any) -> str:
    lines = [f"{sensor.name}: {sensor.description}" if sensor.description else sensor.name]
    lines.append(
        f"Harmon's criteria (chapter section 25.2), measured; class {table.density_class}"
    )
    lines.append("")
    cells = [(row.criterion, *_cells(row), _verdict(row)) for row in table.rows]
    header = ("criterion", "measured", "target", "verdict")
    widths = [max(len(str(line[i])) for line in [header, *cells]) for i in range(4)]
    for line in [header, *cells]:
        lines.append(
            "  ".join(str(cell).ljust(width) for cell, width in zip(line, widths, strict=False))
        )
    lines.append("")
    lines.append(f"{table.n_passed} pass, {table.n_failed} fail")
    lines.append("")
    lines.append("How each was measured:")
    lines.extend(f"  {row.criterion}: {row.method}" for row in table.rows)
    return "\n".join(line.rstrip() for line in lines)


def _run(arguments: argparse.Namespace) -> int:
    from taxel.sensor import harmon_table, make_sensor

    sensor = make_sensor(arguments.preset)
    table = harmon_table(sensor, rng=arguments.seed)
    if arguments.json:
        data = {"description": sensor.description, "seed": arguments.seed, **table.to_dict()}
        sys.stdout.write(json.dumps(data, indent=2) + "\n")
    else:
        sys.stdout.write(_text(table, sensor) + "\n")
    return 0


def register(commands: Any) -> None:
    """Add the ``design`` subcommand to the ``taxel`` parser's subcommands.

    Parameters
    ----------
    commands : argparse._SubParsersAction
        The subcommand registry of the ``taxel`` parser.
    """
    from taxel.sensor import PRESET_NAMES

    parser = commands.add_parser(
        "design",
        help="measure a preset sensor against Harmon's criteria",
        description="Simulate a preset sensor (calibration, two-point loads, sweeps, "
        "loading cycles) and print each of Harmon's criteria: measured value, target, "
        f"verdict. Presets: {', '.join(PRESET_NAMES)}.",
    )
    parser.add_argument("preset", metavar="PRESET", help="sensor preset")
    parser.add_argument("--json", action="store_true", help="print JSON (SI units)")
    parser.add_argument(
        "--seed", type=seed, default=0, metavar="N", help="noise seed of the measurements (0)"
    )
    parser.set_defaults(handler=_run)
