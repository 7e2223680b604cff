"""``taxel design PRESET``: a preset sensor measured against Harmon's criteria.

Prints the measured value, Harmon's target and the verdict of each criterion (chapter
section 25.2), then how each was measured; ``--json`` prints the same in SI units.
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

from taxel.cli._arguments import PRESET_NAMES, preset, seed
from taxel.cli._progress import announced

__all__ = ["register"]


def _verdict(row: Any) -> str:
    return {True: "pass", False: "FAIL", None: "-"}[row.passed]


def _text(table: Any, sensor: Any) -> str:
    lines = [f"{sensor.name}: {sensor.description}" if sensor.description else sensor.name]
    lines.append(
        f"Harmon's criteria (chapter section 25.2), measured; class {table.density_class}"
    )
    lines.append("")
    cells = [(row.criterion, *row.display(), _verdict(row)) for row in table.rows]
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
    # (vhdta128 takes seconds; the library reports no progress: a notice on a terminal)
    with announced(f"measuring {sensor.name} against Harmon's criteria", "", "", bar=False):
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
    parser = commands.add_parser(
        "design",
        help="measure a preset sensor against Harmon's criteria",
        description="Simulate a preset sensor (calibration, two-point loads, sweeps, "
        "loading cycles) and print each of Harmon's criteria: measured value, target, "
        f"verdict. Presets: {', '.join(PRESET_NAMES)}.",
    )
    parser.add_argument("preset", type=preset, metavar="PRESET", help="sensor preset")
    parser.add_argument("--json", action="store_true", help="print JSON (SI units)")
    parser.add_argument(
        "--seed", type=seed, default=0, metavar="N", help="noise seed of the measurements (0)"
    )
    parser.set_defaults(handler=_run)
