"""``taxel active ...``: the active-touch procedures on a simulated finger.

Each subcommand runs one procedure of `taxel.active` in simulation, with the object's truth
known, and prints what was measured against the truth; ``--json`` prints the procedure's
result (SI units), steps included. Degrees and millimetres are converted here, at the edge.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Callable
from typing import Any

__all__ = ["register"]


def _emit(arguments: argparse.Namespace, payload: dict[str, Any], lines: list[str]) -> int:
    if arguments.json:
        json.dump(payload, sys.stdout, indent=2, allow_nan=True, default=float)
        sys.stdout.write("\n")
    else:
        sys.stdout.write("\n".join(lines) + "\n")
    return 0


def _probe_plane(arguments: argparse.Namespace) -> int:
    from taxel.active import plane_probing_trial

    trial = plane_probing_trial(
        arguments.sensor,
        n_probes=arguments.probes,
        face_tilt=math.radians(arguments.face_tilt_deg),
        pose_tilt=math.radians(arguments.pose_tilt_deg),
        normal_force=arguments.force,
        seed=arguments.seed,
    )
    estimate = trial.estimate
    lines = [
        f"probed {arguments.probes} times with {arguments.sensor} at {arguments.force:g} N",
        "normal (base frame): " + ", ".join(f"{v:+.5f}" for v in estimate.normal),
        "true normal:         " + ", ".join(f"{v:+.5f}" for v in trial.true_normal),
        f"normal error: {math.degrees(trial.normal_error):.4f} deg",
        f"planarity residual: {estimate.residual * 1e6:.2f} um",
    ]
    return _emit(arguments, trial.to_dict(), lines)


def _locate_corner(arguments: argparse.Namespace) -> int:
    from taxel.active import corner_probing_trial

    trial = corner_probing_trial(
        arguments.sensor,
        guess_error=arguments.guess_error_mm * 1e-3,
        probes_per_face=arguments.probes_per_face,
        normal_force=arguments.force,
        seed=arguments.seed,
    )
    lines = [
        f"probed three faces ({arguments.probes_per_face} presses each) with {arguments.sensor}",
        "corner (base frame): "
        + ", ".join(f"{v * 1e3:.3f}" for v in trial.estimate.corner)
        + " mm",
        "true corner:         " + ", ".join(f"{v * 1e3:.3f}" for v in trial.true_corner) + " mm",
        f"corner error: {trial.corner_error * 1e3:.4f} mm "
        f"(the guess was {trial.guess_error * 1e3:.2f} mm off)",
    ]
    return _emit(arguments, trial.to_dict(), lines)


def _add(
    group: argparse._SubParsersAction,
    name: str,
    help_text: str,
    handler: Callable[[argparse.Namespace], int],
) -> argparse.ArgumentParser:
    parser = group.add_parser(name, help=help_text, description=help_text)
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    parser.add_argument("--seed", type=int, default=0, help="random seed of the trial")
    parser.set_defaults(handler=handler)
    return parser


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``taxel active`` and its procedures to the command line."""
    parser = commands.add_parser("active", help="active touch with a simulated finger")
    group = parser.add_subparsers(
        dest="procedure", metavar="PROCEDURE", required=True, parser_class=type(parser)
    )
    plane = _add(
        group,
        "probe-plane",
        "surface normal and planarity of a tilted box face " "from several probes at random poses",
        _probe_plane,
    )
    plane.add_argument("--sensor", default="resistive16", help="static sensor preset")
    plane.add_argument("--probes", type=int, default=5, help="number of presses (>= 3)")
    plane.add_argument("--force", type=float, default=5.0, help="press force [N]")
    plane.add_argument(
        "--face-tilt-deg", type=float, default=15.0, help="largest tilt of the face [deg]"
    )
    plane.add_argument(
        "--pose-tilt-deg", type=float, default=10.0, help="largest tilt of the probing poses [deg]"
    )
    corner = _add(
        group, "locate-corner", "a box corner from probing its three faces", _locate_corner
    )
    corner.add_argument("--sensor", default="resistive16", help="static sensor preset")
    corner.add_argument("--probes-per-face", type=int, default=3, help="presses on each face")
    corner.add_argument("--force", type=float, default=5.0, help="press force [N]")
    corner.add_argument(
        "--guess-error-mm",
        type=float,
        default=3.0,
        help="how far the starting guess is from the corner [mm]",
    )
