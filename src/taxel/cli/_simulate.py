"""``taxel simulate``: one raw frame of a preset sensor pressed by a named object.

``taxel simulate --sensor PRESET --object NAME --force NEWTONS --out FRAME.npy`` solves the
contact, runs the transducer and readout, and saves the raw frame; ``--truth TRUTH.npz``
also saves what produced it (pressure on the load grid, contact, taxel fields). Positions
are given in metres in the sensor frame; files are never replaced unless ``--overwrite``.
``--force 0`` writes the frame at rest (nothing pressed), the unloaded reference that
``taxel features --reference`` subtracts.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from taxel.cli._arguments import (
    INDENTER_DESCRIPTIONS,
    INDENTER_NAMES,
    PRESET_NAMES,
    choice,
    finite,
    integer_in,
    nonnegative_in,
    preset,
    seed,
)
from taxel.cli._files import cannot_write
from taxel.cli._main import CommandLineError
from taxel.cli._progress import add_no_progress, solving_on
from taxel.io import check_new_file, write_files

__all__ = ["register"]

_LARGEST_OVERSAMPLING = 16  # --oversampling's bound


def _angle(text: str) -> float:
    """--angle [rad]: finite, and held by a double to 1 urad (as `taxel features --pose`)."""
    value = finite(text)
    if math.ulp(value) > 1e-6:  # from 2**33 rad on: its sine and cosine are noise
        raise argparse.ArgumentTypeError(
            f"a double holds an angle to 1 urad only up to about 8.6e9 rad, got {text}"
        )
    return value


def _default_position(indenter: Any) -> tuple[float, float]:
    # a can's origin is the centre of its rim: put the centre one rim radius off the
    # sensor so the arc passes through the middle of the array
    radius = getattr(indenter, "rim_radius", None)
    return (-float(radius), 0.0) if radius is not None else (0.0, 0.0)


def _truth(frame: Any, sensor: Any, meta: dict[str, Any]) -> dict[str, Any]:
    from taxel.sensor import taxel_fields

    contact = frame.contact
    fields = taxel_fields(
        contact.pressure, sensor.load_grid, sensor.cover, displacement=contact.displacement
    )
    taxel_x, taxel_y = sensor.geometry.positions()
    return {
        "meta": np.array(json.dumps(meta)),
        "pressure": contact.pressure,
        "contact": contact.contact,
        "displacement": contact.displacement,
        "spacing": np.asarray(contact.spacing),
        "taxel_x": taxel_x,
        "taxel_y": taxel_y,
        "taxel_pressure": fields.pressure,
        "taxel_stress": fields.stress,
        "taxel_strain": fields.strain,
        "taxel_displacement": fields.displacement,
        "quantity": frame.quantity,
        "signal": frame.signal,
    }


def _write_both(
    out: Path, raw: np.ndarray, truth: Path | None, arrays: dict[str, Any] | None
) -> None:
    """Write the frame and its truth: both, or (when either write fails) neither."""
    jobs: list[tuple[Path, Callable[[Path], Any]]] = [
        (out, lambda temporary: _save(temporary, np.save, raw, allow_pickle=False))
    ]
    options = {out: "--out"}
    if truth is not None and arrays is not None:
        jobs.append((truth, lambda temporary: _save(temporary, np.savez_compressed, **arrays)))
        options[truth] = "--truth"
    try:
        write_files(jobs)
    except OSError as error:
        raise cannot_write(error, options) from None


def _save(path: Path, save: Callable[..., None], *args: Any, **kwargs: Any) -> None:
    """`save` (np.save or np.savez_compressed) to an open file, so no suffix is added."""
    with open(path, "wb") as stream:
        save(stream, *args, **kwargs)


def _check_lowest_point_on_sensor(
    indenter: Any,
    heights: np.ndarray,
    sensor: Any,
    position: tuple[float, float],
    arguments: argparse.Namespace,
) -> None:
    """Refuse an object whose lowest point lies off the array (its edge would meet a flank).

    Such an object is pressed by its side, or not at all, not as asked. Only an origin off
    the array is judged, by the object's height there (a can's origin, the centre of its
    rim, has no surface: its rim crosses the array, and it passes).
    """
    width, height = sensor.geometry.extent
    x, y = position
    if abs(x) <= width / 2 and abs(y) <= height / 2:
        return
    at_origin = indenter.heights(
        np.array([x]), np.array([y]), position=position, angle=arguments.angle
    )[0]
    finite = heights[np.isfinite(heights)]
    if not np.isfinite(at_origin) or finite.size == 0:
        return
    above = float(finite.min() - at_origin)
    if above > max(sensor.load_grid.spacing):
        raise CommandLineError(
            f"the {arguments.object} at x = {x:g} m, y = {y:g} m has its lowest point off "
            f"the {width * 1e3:g} x {height * 1e3:g} mm array, which would meet it "
            f"{above * 1e3:.3g} mm higher up: move it onto the sensor"
        )


def _over_no_cell(
    indenter: Any, sensor: Any, position: tuple[float, float], arguments: argparse.Namespace
) -> CommandLineError:
    """The error for an object whose surface lies over no cell centre of the load grid.

    An object over the sensor but smaller than its cells (a punch narrower than the gaps
    between cell centres) falls between them: a finer grid, as --oversampling asks, finds
    it, and the error names the least one that does. One off the sensor must be moved.
    """
    width, height = (size * 1e3 for size in sensor.geometry.extent)
    cell = sensor.load_grid.spacing[1] * 1e3
    x, y = position
    where = f"the {arguments.object} at x = {x:g} m, y = {y:g} m"
    grid = f"the {width:g} x {height:g} mm load grid"
    base = sensor.oversampling if arguments.oversampling is None else arguments.oversampling
    for factor in range(base + 1, _LARGEST_OVERSAMPLING + 1):
        finer = sensor.geometry.load_grid(factor)
        cell_x, cell_y = finer.coordinates()
        heights = indenter.heights(cell_x, cell_y, position=position, angle=arguments.angle)
        if np.any(np.isfinite(heights)):
            return CommandLineError(
                f"{where} falls between the centres of the {cell:.3g} mm cells of {grid}, "
                "on which the contact is solved: what it presses with is narrower than a "
                f"cell; give --oversampling {factor} or more to solve it on finer cells"
            )
    return CommandLineError(
        f"{where} is over no cell of {grid} ({cell:.3g} mm cells), even at --oversampling "
        f"{_LARGEST_OVERSAMPLING}: move it onto the sensor"
    )


def _warn_if_saturated(frame: Any, sensor: Any) -> None:
    """Warn (stderr) when the sensing plane is pressed beyond the sensor's full scale.

    A flat plate at `full_scale` loads the sensing plane with that normal stress; a contact
    that loads it harder drives its taxels past every level a calibration covers, and what
    they read there saturates or is clipped: a reconstruction then recovers too little force.
    A sensor of the cover's displacement (reflective8x8) feels no stress: for it, each
    taxel's displacement is held against the one a full-scale plate gives it, as a
    calibration holds its reading against that plate's.
    """
    if frame.fields is None:
        return
    if sensor.quantity == "displacement":
        _warn_if_moved_beyond_full_scale(frame, sensor)
        return
    felt = float(np.max(-frame.fields.stress))
    if felt > sensor.full_scale:
        sys.stderr.write(
            f"taxel simulate: warning: the taxels feel up to {felt / 1e3:.4g} kPa at the "
            f"sensing depth, above {sensor.name}'s full scale of {sensor.full_scale / 1e3:.4g} "
            f"kPa: {_SATURATE}\n"
        )


_SATURATE = (
    "their readings saturate, and a reconstruction recovers too little force (press more "
    "lightly, or with a blunter object)"
)


def _warn_if_moved_beyond_full_scale(frame: Any, sensor: Any) -> None:
    """`_warn_if_saturated` for a sensor of the cover's displacement, taxel by taxel."""
    plate = np.full(sensor.load_grid.shape, sensor.full_scale)
    full = sensor.sensed_quantity(plate, sensor.fields(plate))
    moved = np.asarray(frame.quantity)
    beyond = moved >= full
    if np.any(beyond):
        sys.stderr.write(
            f"taxel simulate: warning: the cover moves up to {np.max(moved) * 1e3:.3g} mm at "
            f"the taxels: at {int(np.count_nonzero(beyond))} of them beyond what a plate at "
            f"{sensor.name}'s full scale of {sensor.full_scale / 1e3:.4g} kPa moves it (up to "
            f"{np.max(full) * 1e3:.3g} mm): {_SATURATE}\n"
        )


def _run(arguments: argparse.Namespace) -> int:
    from taxel.mechanics import make_indenter
    from taxel.sensor import make_sensor

    out = check_new_file(arguments.out, suffix=".npy", overwrite=arguments.overwrite, name="--out")
    truth = None
    if arguments.truth is not None:
        truth = check_new_file(
            arguments.truth, suffix=".npz", overwrite=arguments.overwrite, name="--truth"
        )
        if truth.resolve() == out.resolve():
            raise CommandLineError("--truth must differ from --out")
    sensor = make_sensor(arguments.sensor)
    if arguments.oversampling is not None:
        sensor = dataclasses.replace(sensor, oversampling=arguments.oversampling)
    indenter = make_indenter(arguments.object)
    default_x, default_y = _default_position(indenter)
    x = default_x if arguments.x is None else arguments.x
    y = default_y if arguments.y is None else arguments.y
    cell_x, cell_y = sensor.load_grid.coordinates()
    heights = indenter.heights(cell_x, cell_y, position=(x, y), angle=arguments.angle)
    _check_lowest_point_on_sensor(indenter, heights, sensor, (x, y), arguments)
    if not np.any(np.isfinite(heights)):
        raise _over_no_cell(indenter, sensor, (x, y), arguments)
    try:
        bar = not arguments.no_progress
        with solving_on(sensor.load_grid.shape, "contact", bar=bar) as progress:
            frame = sensor.press(
                indenter,
                normal_force=arguments.force,
                position=(x, y),
                angle=arguments.angle,
                rng=arguments.seed,
                progress=progress,
            )
    except ValueError as error:  # the library names its parameter; the user gave the flag
        raise ValueError(str(error).replace("`normal_force`", "--force")) from None
    contact = frame.contact
    if contact is None:  # press always solves a contact; this keeps the types honest
        raise CommandLineError("the press returned no contact")
    raw = np.asarray(frame.raw)
    meta = {
        "sensor": sensor.name,
        "object": arguments.object,
        "normal_force": arguments.force,
        "position": [x, y],
        "angle": arguments.angle,
        "seed": arguments.seed,
        "oversampling": sensor.oversampling,
        "converged": contact.converged,
        "n_iterations": contact.n_iterations,
        "residual": contact.residual,
        "contact_area": contact.contact_area,
        "message": contact.message,
        "raw_file": str(out),
    }
    _write_both(out, raw, truth, None if truth is None else _truth(frame, sensor, meta))
    _warn_if_saturated(frame, sensor)
    noise = "noise-free" if arguments.seed is None else f"noise seed {arguments.seed}"
    if arguments.force == 0:  # no contact was solved: nothing to report of it
        solved = "nothing pressed, the sensor at rest"
    else:
        solved = (
            f"contact {contact.contact_area * 1e6:.3g} mm^2, "
            f"{'converged' if contact.converged else 'NOT converged'} in "
            f"{contact.n_iterations} iterations"
        )
    sys.stdout.write(
        f"wrote {out}: {sensor.name} raw frame {' x '.join(map(str, raw.shape))} "
        f"({raw.dtype}, {noise}), {arguments.object} {arguments.force:g} N at "
        f"({x * 1e3:g}, {y * 1e3:g}) mm; {solved}"
        + (f"; truth in {truth}" if truth is not None else "")
        + "\n"
    )
    return 0


def register(commands: Any) -> None:
    """Add the ``simulate`` subcommand to the ``taxel`` parser's subcommands.

    Parameters
    ----------
    commands : argparse._SubParsersAction
        The subcommand registry of the ``taxel`` parser.
    """
    parser = commands.add_parser(
        "simulate",
        help="one raw frame of a preset sensor pressed by an object",
        description="Press a named object on a preset sensor with a given force and save "
        "the raw frame (.npy); optionally save the ground truth (.npz). "
        f"Sensors: {', '.join(PRESET_NAMES)}. Objects: "
        + "; ".join(f"{name}: {what}" for name, what in INDENTER_DESCRIPTIONS.items())
        + ".",
    )
    parser.add_argument(
        "--sensor", type=preset, required=True, metavar="PRESET", help="sensor preset"
    )
    parser.add_argument(
        "--object", required=True, type=choice(INDENTER_NAMES), metavar="NAME", help="indenter"
    )
    parser.add_argument(
        "--force",
        required=True,
        type=nonnegative_in(1e6),
        metavar="NEWTONS",
        help="normal force [N], at most 1e6; 0 writes the sensor's frame at rest (with "
        "--seed, its noise and fixed pattern), a --reference for `taxel features`",
    )
    parser.add_argument(
        "--x",
        type=finite,
        metavar="M",
        help="x of the object's origin in the sensor frame [m] (0; the can: minus its "
        "rim radius, so the rim crosses the middle)",
    )
    parser.add_argument("--y", type=finite, metavar="M", help="y of the object's origin [m] (0)")
    parser.add_argument(
        "--angle", type=_angle, default=0.0, metavar="RAD", help="rotation about z [rad] (0)"
    )
    parser.add_argument(
        "--seed", type=seed, metavar="N", help="switch the sensor's noise on, reproducibly"
    )
    parser.add_argument(
        "--oversampling",
        type=integer_in(1, _LARGEST_OVERSAMPLING),
        metavar="K",
        help="solve the contact on K x K cells per taxel (the preset's, usually 1); "
        "finer grids resolve small objects such as the can's 1 mm lip",
    )
    parser.add_argument("--out", required=True, metavar="FRAME.npy", help="raw frame to write")
    parser.add_argument(
        "--truth",
        metavar="TRUTH.npz",
        help="also write pressure, contact and taxel fields (SI units) to this file",
    )
    parser.add_argument("--overwrite", action="store_true", help="replace output files that exist")
    add_no_progress(parser)
    parser.set_defaults(handler=_run)
