"""``taxel active ...``: the active-touch procedures on a simulated finger, as subcommands.

Each subcommand runs one procedure of `taxel.active` in simulation, with the object's truth
known, and prints what was measured against the truth (`taxel.cli._active_procedures`);
``slip`` instead reads a recorded sequence of frames (`taxel.cli._active_slip`).
"""

from __future__ import annotations

import argparse
from collections.abc import Callable

from taxel.cli import _active_procedures as procedures
from taxel.cli import _active_recognize, _active_slip
from taxel.cli._arguments import (
    DEFORMATION_OBJECTS,
    MODEL_NAMES,
    choice,
    finite,
    integer_in,
    positive,
    positive_in,
    preset,
    real_in,
    seed,
)

__all__ = ["register"]


def _add(
    group: argparse._SubParsersAction,
    name: str,
    help_text: str,
    handler: Callable[[argparse.Namespace], int],
) -> argparse.ArgumentParser:
    parser = group.add_parser(name, help=help_text, description=help_text)
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    parser.add_argument("--seed", type=seed, default=0, help="random seed of the trial")
    parser.add_argument(
        "--no-progress",
        action="store_true",
        help="no progress bar (one is drawn on stderr only when it is a terminal)",
    )
    parser.set_defaults(handler=handler)
    return parser


def _add_press_force(parser: argparse.ArgumentParser) -> None:
    """The --force of the probing procedures (5 N, within the finger's limit)."""
    parser.add_argument(
        "--force",
        type=positive,
        default=5.0,
        help="press force [N] (5), at most the finger's limit: the sensor's full-scale "
        "pressure over a quarter of its area (reflective8x8: 0.576 N)",
    )


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``taxel active`` and its procedures to the command line."""
    parser = commands.add_parser(
        "active",
        help="active touch with a simulated finger",
        description="Active touch (Ellis, section 2.2): a simulated finger carrying a sensor "
        "presses, probes and slides, and each procedure reports what it found and did.",
    )
    group = parser.add_subparsers(
        dest="procedure", metavar="PROCEDURE", required=True, parser_class=type(parser)
    )
    plane = _add(
        group,
        "probe-plane",
        "surface normal and planarity of a tilted box face " "from several probes at random poses",
        procedures.probe_plane,
    )
    plane.add_argument(
        "--sensor", type=preset, default="resistive16", help="static sensor preset (%(default)s)"
    )
    plane.add_argument(
        "--probes",
        type=integer_in(3, 1000),  # about 45 ms a press: 1000 take most of a minute
        default=5,
        help="number of presses (5), 3-1000",
    )
    _add_press_force(plane)
    plane.add_argument(
        "--face-tilt-deg",
        type=real_in(0.0, 45.0),
        default=15.0,
        help="largest tilt of the face [deg], 0-45",
    )
    plane.add_argument(
        "--pose-tilt-deg",
        type=real_in(0.0, 30.0),
        default=10.0,
        help="largest tilt of the probing poses [deg], 0-30",
    )
    corner = _add(
        group,
        "locate-corner",
        "a box corner from probing its three faces",
        procedures.locate_corner,
    )
    corner.add_argument(
        "--sensor", type=preset, default="resistive16", help="static sensor preset (%(default)s)"
    )
    corner.add_argument(
        "--probes-per-face",
        type=integer_in(3, 300),  # taxel.active MIN_PROBES: three presses fix a plane
        default=3,
        help="presses on each face (3), 3-300",
    )
    _add_press_force(corner)
    corner.add_argument(
        "--guess-error-mm",
        type=positive_in(0.0, 1000.0),
        default=3.0,
        help="how far the starting guess is from the corner [mm]",
    )
    edge = _add(
        group,
        "edge-radius",
        "the radius of an edge from a light and a firm press "
        "against an empirical table (Ellis, section 2.2)",
        procedures.edge_radius,
    )
    edge.add_argument(
        "--radius-mm",
        type=positive_in(0.0, 1000.0),
        required=True,
        help="radius of the simulated edge to measure [mm], at most 1000",
    )
    edge.add_argument(
        "--forces",
        type=positive,
        nargs=2,
        metavar=("LIGHT", "FIRM"),
        help="the light and the firm press [N] (12 39); at most the finger's limit, the "
        "sensor's full-scale pressure over a quarter of its area (photoelastic64: 12.8 N); a "
        "--table is made at its forces",
    )
    edge.add_argument(
        "--sensor", type=preset, default="vhdta128", help="sensor preset (%(default)s)"
    )
    edge.add_argument(
        "--table",
        metavar="TABLE.json",
        help="the empirical table: loaded if it exists, else built and saved",
    )
    edge.add_argument(
        "--x-mm",
        type=finite,
        default=0.0,
        help="a point of the edge's crest, x [mm]; the crest must pass within a sensor's reach "
        "of its centre (vhdta128: 8.7 mm, resistive16: 3 mm)",
    )
    edge.add_argument("--y-mm", type=finite, default=0.0, help="the same point's y [mm]")
    edge.add_argument("--angle-deg", type=finite, default=0.0, help="edge direction [deg]")
    stiff = _add(
        group,
        "stiffness",
        "deformation and stiffness, rigid or deformable (Ellis, section 2.2), from three "
        "presses: a 0.5 N touch finds the object's surface (and, with the light press, its "
        "unloaded height), then a light and a firm press (--forces) measure how much it gives",
        procedures.stiffness,
    )
    stiff.add_argument(
        "--object",
        type=choice(DEFORMATION_OBJECTS),
        help=f"named object, pressed as it is ({', '.join(DEFORMATION_OBJECTS)}; default "
        "racquet ball)",
    )
    stiff.add_argument(
        "--shape",
        choices=("ball", "hollow-ball", "block"),
        help="instead of --object, a custom solid or hollow ball or a block: give its "
        "--size-mm and --modulus-mpa (and a hollow ball's --wall-mm)",
    )
    stiff.add_argument(
        "--size-mm", type=positive_in(0.0, 1000.0), help="ball radius or block edge [mm], <= 1000"
    )
    stiff.add_argument(
        "--modulus-mpa",
        type=positive_in(1e-6, 1e7),
        help="its Young's modulus [MPa], 1e-6 (1 Pa) to 1e7 (10 TPa); a hollow ball's wall's",
    )
    stiff.add_argument(
        "--wall-mm",
        type=positive_in(0.0, 500.0),
        help="a hollow ball's wall thickness [mm], under half its radius",
    )
    stiff.add_argument(
        "--gauge-kpa",
        type=real_in(0.0, 1e4),
        help="a hollow ball's air pressure above the atmosphere's [kPa] (0; a tennis ball ~90)",
    )
    stiff.add_argument(
        "--poisson-ratio", type=real_in(-0.999, 0.5), help="its Poisson's ratio (0.5)"
    )
    stiff.add_argument(
        "--forces",
        type=positive,
        nargs=2,
        default=(12.0, 39.0),
        metavar=("LIGHT", "FIRM"),
        help="the light and the firm press [N] (12 39), made after the 0.5 N touch; at most "
        "the finger's limit (see edge-radius)",
    )
    stiff.add_argument(
        "--sensor", type=preset, default="vhdta128", help="sensor preset (%(default)s)"
    )
    stiff.add_argument(
        "--calibration",
        metavar="PAD.json",
        help="pad calibration: loaded if it exists, else built and saved",
    )
    recognize = _add(
        group,
        "recognize",
        "recognize an object against a library of models from up to three touches: one "
        "when the first touch leaves only one model within the library's spread of a touch, "
        "else three",
        _active_recognize.recognize,
    )
    recognize.add_argument(
        "--object",
        required=True,
        type=choice(MODEL_NAMES),
        help=f"the model to touch ({', '.join(MODEL_NAMES)})",
    )
    recognize.add_argument(
        "--sensor", type=preset, default="vhdta128", help="sensor preset (%(default)s)"
    )
    recognize.add_argument(
        "--force",
        type=positive,
        help="force of each touch [N] (15, or the --library's), at most the finger's limit "
        "(see probe-plane); a library is built at this force",
    )
    recognize.add_argument(
        "--three-touches",
        action="store_true",
        help="always touch three times, even when the first touch decides",
    )
    recognize.add_argument(
        "--library",
        metavar="LIBRARY.json",
        help="model library: loaded if it exists, else built and saved",
    )
    _active_slip.register(group)
