"""``taxel calibrate``: a preset sensor's per-taxel calibration from flat-plate presses."""

from __future__ import annotations

import argparse
import sys

from taxel.cli._arguments import preset, seed
from taxel.cli._files import writing
from taxel.cli._main import CommandLineError
from taxel.cli._progress import announced

__all__ = ["register"]


def _run(arguments: argparse.Namespace) -> int:
    from taxel.io import check_new_file
    from taxel.sensor import calibrate, calibration_error, make_sensor

    if not arguments.out.endswith(".npz") and arguments.out.lower().endswith(".npz"):
        # Calibration.save takes '.npz' as written; found here, not after the calibration
        raise CommandLineError(
            f"--out must name a .npz file (in lower case), got {arguments.out!r}"
        )
    out = check_new_file(arguments.out, suffix=".npz", overwrite=arguments.overwrite, name="--out")
    sensor = make_sensor(arguments.sensor)
    # (vhdta128 takes seconds; the library reports no progress: a notice on a terminal)
    with announced(f"calibrating {sensor.name} with flat-plate presses", "", "", bar=False):
        try:
            calibration = calibrate(sensor, rng=arguments.seed)
        except ValueError as refused:  # ("`sensor` 'piezo8x8' senses only changes of load")
            raise ValueError(str(refused).replace("`sensor`", "--sensor")) from None
        error = calibration_error(sensor, calibration)
    with writing("--out", out):
        calibration.save(out, overwrite=arguments.overwrite)
    excluded = int((~calibration.valid).sum())
    sys.stdout.write(
        f"calibrated {sensor.name} with flat-plate presses up to {sensor.full_scale / 1e3:.4g} "
        f"kPa; {excluded} taxel(s) excluded (dead, stuck or pinned)\n"
        f"round trip: worst {error.worst:.2%} of full scale, rms {error.rms:.2%}\n"
        f"written to {out}\n"
    )
    return 0


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``taxel calibrate`` to the command line."""
    parser = commands.add_parser(
        "calibrate",
        help="calibrate a preset sensor from flat-plate presses",
        description="Press a flat plate on the whole array at a set of pressures (with the "
        "sensor's noise), fit a monotonic map raw -> pressure per taxel, mask dead and stuck "
        "taxels, and save the calibration (.npz) for `taxel reconstruct --calibration`.",
    )
    parser.add_argument(
        "--sensor",
        type=preset,
        required=True,
        metavar="PRESET",
        help="sensor preset; not piezo8x8 (it senses only changes of load) nor photoelastic64 "
        "(a flat plate makes no fringes)",
    )
    parser.add_argument("--out", required=True, metavar="CAL.npz", help="calibration file")
    parser.add_argument("--seed", type=seed, default=0, help="noise seed of the presses (0)")
    parser.add_argument("--overwrite", action="store_true", help="replace an existing --out")
    parser.set_defaults(handler=_run)
