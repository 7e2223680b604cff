"""The handlers of ``taxel active ...``: each runs one procedure of `taxel.active` in simulation.

Each prints what was measured against the truth it knows; ``--json`` prints the procedure's
result (SI units), steps included. Degrees and millimetres are converted here, at the edge.
"""

from __future__ import annotations

import argparse
import contextlib
import math
import sys
from collections.abc import Iterator, Sequence
from typing import Any

from taxel.cli._files import building, file_or_build
from taxel.cli._json import strict_json
from taxel.cli._main import CommandLineError
from taxel.cli._progress import progress_bar

__all__ = ["edge_radius", "finger_limit", "locate_corner", "probe_plane", "stiffness"]

_EDGE_FORCES = (12.0, 39.0)  # taxel.active's DEFAULT_FORCES: the seed's light and firm presses
_TOUCH = 0.5  # measure_deformation's touch_force [N], the first press of a pad calibration
_DEFAULT_OBJECT = "racquet ball"  # what `stiffness` presses unless told


def _emit(
    arguments: argparse.Namespace,
    payload: dict[str, Any],
    lines: list[str],
    built: Sequence[str] = (),
) -> int:
    """Print the result; then, on stderr, the files the command built (`built`)."""
    if arguments.json:
        sys.stdout.write(strict_json(payload) + "\n")
    else:
        sys.stdout.write("\n".join(lines) + "\n")
    for note in built:  # only now: an error before this point leaves its one line alone
        sys.stderr.write(note + "\n")
    return 0


def finger_limit(sensor: str) -> float:
    """The largest force [N] the simulated finger carrying the preset `sensor` presses with."""
    from taxel.active import finger_force_limit

    return finger_force_limit(sensor)


def _check_forces(flag: str, forces: Sequence[float], sensor: str) -> None:
    """Refuse, before any press, forces beyond what the finger with `sensor` may press.

    A light and a firm force (two given to `flag`) must come in that order.
    """
    if len(forces) == 2 and forces[0] >= forces[1]:
        raise CommandLineError(
            f"{flag} {forces[0]:g} {forces[1]:g}: give the light force first, then a firmer one"
        )
    limit = finger_limit(sensor)
    if max(forces) > limit:
        given = " ".join(f"{force:g}" for force in forces)
        # the limit to four significant digits, rounded down so that it is a force it takes
        largest = float(f"{limit:.4g}")
        if largest > limit:
            largest -= 10.0 ** (math.floor(math.log10(limit)) - 3)
        shown = f"{largest:.4g}"
        raise CommandLineError(
            f"{flag} {given}: the finger with {sensor} presses at most {shown} N (its "
            f"full-scale pressure over a quarter of its area); give {flag} of at most {shown}"
        )


def _check_made_on(flag: str, path: str, made_on: str, sensor: str) -> None:
    """Refuse a `flag` file (a table, calibration or library) made on another sensor."""
    if made_on and made_on != sensor:
        raise CommandLineError(
            f"{flag} {path} was made on {made_on}, not on --sensor {sensor}: give --sensor "
            f"{made_on} or another {flag}"
        )


_NO_OBJECT = "no object within the finger's reach"  # what a press that found nothing says


@contextlib.contextmanager
def _no_contact(flag: str, why: str) -> Iterator[None]:
    """A press that found nothing within the finger's reach, said as the fault of `flag`.

    The procedures say it as `NoContactError`, or as a ValueError naming the probe (`why`
    then names it too, from the message's start).
    """
    try:
        yield
    except ValueError as error:
        message = str(error)
        if _NO_OBJECT not in message:
            raise
        where = message.split(" at (")[0] if " at (" in message else ""
        found = f" ({where} found nothing within the finger's reach)" if where else ""
        raise CommandLineError(f"{flag}: {why}{found}") from None


def probe_plane(arguments: argparse.Namespace) -> int:
    from taxel.active import plane_probing_trial

    _check_forces("--force", [arguments.force], arguments.sensor)
    with progress_bar("probing", "press", enabled=not arguments.no_progress) as progress:
        trial = plane_probing_trial(
            arguments.sensor,
            n_probes=arguments.probes,
            face_tilt=math.radians(arguments.face_tilt_deg),
            pose_tilt=math.radians(arguments.pose_tilt_deg),
            normal_force=arguments.force,
            seed=arguments.seed,
            progress=progress,
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


def locate_corner(arguments: argparse.Namespace) -> int:
    from taxel.active import corner_probing_trial

    _check_forces("--force", [arguments.force], arguments.sensor)
    why = "probing from a guess this far off the corner missed the box"
    with (
        _no_contact(f"--guess-error-mm {arguments.guess_error_mm:g}", why),
        progress_bar("probing", "press", enabled=not arguments.no_progress) as progress,
    ):
        trial = corner_probing_trial(
            arguments.sensor,
            guess_error=arguments.guess_error_mm * 1e-3,
            probes_per_face=arguments.probes_per_face,
            normal_force=arguments.force,
            seed=arguments.seed,
            progress=progress,
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


def _position_flags(arguments: argparse.Namespace) -> str:
    """The flags that placed the edge, as given (those left at 0 unsaid, but one)."""
    given = [
        f"{flag} {value:g}"
        for flag, value in (("--x-mm", arguments.x_mm), ("--y-mm", arguments.y_mm))
        if value != 0
    ]
    if given and arguments.angle_deg != 0:
        given.append(f"--angle-deg {arguments.angle_deg:g}")
    return " ".join(given) or "--y-mm 0"


def _within(reach: float) -> str:
    """The distance [mm] an edge's crest must stay within, rounded down to 0.1 mm."""
    return f"{math.floor(reach * 1e4 + 1e-6) / 10:.1f}"


def _check_edge_position(arguments: argparse.Namespace, reach: float) -> None:
    """Refuse, before any build or press, an edge too far off the sensor's centre to measure.

    `reach` [m]: `largest_edge_offset` of the sensor (0 when the sensor is too small for a
    cross-section at all, which the procedure says).
    """
    angle = math.radians(arguments.angle_deg)
    offset = abs(arguments.y_mm * math.cos(angle) - arguments.x_mm * math.sin(angle))
    if reach > 0 and offset > float(_within(reach)):
        raise CommandLineError(
            f"{_position_flags(arguments)}: the edge's crest passes {offset:.3g} mm from the "
            f"sensor's centre; on {arguments.sensor} it must pass within {_within(reach)} mm "
            "(the cross-section is read 7 mm either side of it, inside the active area)"
        )


@contextlib.contextmanager
def _sensor_errors(sensor: str) -> Iterator[None]:
    """The refusal of a sensor too small for an edge's cross-section, said with --sensor.

    Said so by the table's build and by the measurement alike.
    """
    try:
        yield
    except ValueError as error:
        message = str(error)
        if message.startswith("`sensor` is too small"):
            raise CommandLineError(
                f"--sensor {sensor} {message.removeprefix('`sensor` ')}"
            ) from None
        raise


@contextlib.contextmanager
def _edge_errors(arguments: argparse.Namespace, reach: float) -> Iterator[None]:
    """The procedure's errors about its sensor and the edge's image, said with the flags."""
    try:
        with _sensor_errors(arguments.sensor):
            yield
    except ValueError as error:
        message = str(error)
        if message.startswith("`image` shows its edge"):  # past the border, seen from noise
            raise CommandLineError(
                f"{_position_flags(arguments)}: the edge's crest was imaged too near the "
                f"border of {arguments.sensor} to read its cross-section; keep it within "
                f"{_within(reach)} mm of the sensor's centre"
            ) from None
        raise


def edge_radius(arguments: argparse.Namespace) -> int:
    from taxel.active import (
        EdgeRadiusTable,
        build_edge_radius_table,
        largest_edge_offset,
        measure_edge_radius,
        sharpest_edge_radius,
    )
    from taxel.sensor import make_sensor

    forces = _EDGE_FORCES if arguments.forces is None else tuple(arguments.forces)
    _check_forces("--forces", forces, arguments.sensor)
    sharpest = sharpest_edge_radius(make_sensor(arguments.sensor))
    if arguments.radius_mm * 1e-3 <= sharpest:  # refused now, not after a table's build
        raise CommandLineError(
            f"--radius-mm {arguments.radius_mm:g}: {arguments.sensor}'s load grid resolves "
            f"edges of radius above {sharpest * 1e3:.3g} mm (half its cell), no sharper"
        )
    reach = largest_edge_offset(make_sensor(arguments.sensor))
    _check_edge_position(arguments, reach)
    built: list[str] = []
    bar = not arguments.no_progress
    with _sensor_errors(arguments.sensor):
        table = file_or_build(
            arguments.table,
            EdgeRadiusTable.load,
            lambda path, progress: build_edge_radius_table(
                sensor=arguments.sensor, forces=forces, path=path, progress=progress
            ),
            "edge-radius table",
            "--table",
            built,
            unit="edge",
            bar=bar,
        )
    if table is not None:
        _check_made_on("--table", arguments.table, table.sensor, arguments.sensor)
        made = tuple(float(force) for force in table.forces)
        if arguments.forces is not None and made != forces:
            raise CommandLineError(
                f"--forces {' '.join(f'{f:g}' for f in forces)}: the --table {arguments.table} "
                f"was made with {' '.join(f'{f:g}' for f in made)} N; give those or another "
                "--table"
            )
        forces = made
    else:  # (with no --forces, the table measure_edge_radius makes by default)
        with (
            _sensor_errors(arguments.sensor),
            building("edge-radius table", "edge", bar=bar) as progress,
        ):
            table = build_edge_radius_table(
                sensor=arguments.sensor, forces=forces, progress=progress
            )
    with _edge_errors(arguments, reach):
        result = measure_edge_radius(
            arguments.radius_mm * 1e-3,
            table=table,
            sensor=arguments.sensor,
            position=(arguments.x_mm * 1e-3, arguments.y_mm * 1e-3),
            angle=math.radians(arguments.angle_deg),
            rng=arguments.seed,
        )
    lines = [
        f"edge of radius {arguments.radius_mm:g} mm pressed at "
        + " N and ".join(f"{force:g}" for force in forces)
        + f" N on {arguments.sensor}",
        f"estimated radius: {result.radius * 1e3:.3f} mm "
        f"(+/- {result.radius_uncertainty * 1e3:.3f} mm)",
        f"nearest table entry: {result.nearest_radius * 1e3:g} mm",
        f"error: {(result.radius - arguments.radius_mm * 1e-3) * 1e3:+.3f} mm",
        f"match: {result.message}",
    ]
    # the simulated edge's radius is known here: the JSON tells it and the error, as the text
    payload: dict[str, Any] = {}
    for key, value in result.to_dict().items():
        payload[key] = value
        if key == "radius_uncertainty_m":
            payload["true_radius_m"] = arguments.radius_mm * 1e-3
            payload["error_m"] = result.radius - arguments.radius_mm * 1e-3
    return _emit(arguments, payload, lines, built)


_CUSTOM_FLAGS = (
    ("--size-mm", "size_mm"),
    ("--modulus-mpa", "modulus_mpa"),
    ("--poisson-ratio", "poisson_ratio"),
    ("--wall-mm", "wall_mm"),
    ("--gauge-kpa", "gauge_kpa"),
)
# the seed's numbers (Ellis, section 2.2) beside a named object's: heights at no load, 12 N
# and 39 N [mm]; imprint areas at 12 N and 39 N [pixels]
_SEED = {
    "racquet ball": ("57 / 53 / 47", "674 / 4681"),
    "acrylic sphere": ("12.5 / 12.5 / 12.5", "289 / 487"),
}


def _deformation_object(arguments: argparse.Namespace) -> str:
    """The name of the object `stiffness` presses: a named one as it is, or a custom one.

    ``--object`` names an object of the library, whole; ``--shape`` with ``--size-mm`` and
    ``--modulus-mpa`` (and optionally ``--poisson-ratio``) describes a custom one. Mixing the
    two is refused: a named object with a property changed is no longer the object named.
    """
    given = [
        f"{flag} {getattr(arguments, key):g}"
        for flag, key in _CUSTOM_FLAGS
        if getattr(arguments, key) is not None
    ]
    if arguments.shape is None:
        if arguments.object is not None and given:
            raise CommandLineError(
                f"--object {arguments.object!r} conflicts with {' '.join(given)}: --object "
                "presses the named object as it is; to press another, describe it whole with "
                "--shape, --size-mm and --modulus-mpa instead"
            )
        if given:
            raise CommandLineError(
                f"{' '.join(given)} describes a custom object: give --shape ball, hollow-ball "
                "(with --wall-mm) or block, with --size-mm and --modulus-mpa"
            )
        return str(arguments.object or _DEFAULT_OBJECT)
    if arguments.object is not None:
        raise CommandLineError(
            f"--object {arguments.object!r} conflicts with --shape {arguments.shape}: give "
            "either a named --object or a custom --shape with its --size-mm and --modulus-mpa"
        )
    if arguments.size_mm is None or arguments.modulus_mpa is None:
        raise CommandLineError(
            f"--shape {arguments.shape} needs its --size-mm and --modulus-mpa "
            "(and optionally --poisson-ratio)"
        )
    hollow = arguments.shape == "hollow-ball"
    if hollow and arguments.wall_mm is None:
        raise CommandLineError("--shape hollow-ball needs its --wall-mm (the wall's thickness)")
    shell_flags = [
        flag
        for flag, value in (("--wall-mm", arguments.wall_mm), ("--gauge-kpa", arguments.gauge_kpa))
        if value is not None
    ]
    if not hollow and shell_flags:
        raise CommandLineError(
            f"{' and '.join(shell_flags)} describe{'s' if len(shell_flags) == 1 else ''} a "
            f"hollow ball, not a --shape {arguments.shape}"
        )
    if hollow and not arguments.wall_mm < arguments.size_mm / 2:
        raise CommandLineError(
            f"--wall-mm {arguments.wall_mm:g} must be under half the --size-mm "
            f"{arguments.size_mm:g} (a hollow ball's radius)"
        )
    return f"custom {arguments.shape}"


def stiffness(arguments: argparse.Namespace) -> int:
    from taxel.active import PadCalibration, calibrate_pad, measure_deformation

    bar = not arguments.no_progress

    def build(path: str | None, progress: Any) -> Any:
        calibration = calibrate_pad(
            arguments.sensor, forces=(_TOUCH, *arguments.forces), progress=progress
        )
        if path is not None:
            calibration.save(path)
        return calibration

    name = _deformation_object(arguments)
    _check_forces("--forces", arguments.forces, arguments.sensor)
    if arguments.forces[0] <= _TOUCH:  # the procedure touches at _TOUCH first
        raise CommandLineError(
            f"--forces {' '.join(f'{f:g}' for f in arguments.forces)}: the light press must "
            f"exceed the {_TOUCH:g} N touch that finds the object first"
        )
    built: list[str] = []
    calibration = file_or_build(
        arguments.calibration,
        PadCalibration.load,
        build,
        "pad calibration",
        "--calibration",
        built,
        bar=bar,
    )
    if calibration is not None:
        _check_made_on(
            "--calibration", arguments.calibration, calibration.sensor, arguments.sensor
        )
        made = [float(force) for force in calibration.forces[-2:]]
        if not math.isclose(made[0], arguments.forces[0], rel_tol=1e-3) or not math.isclose(
            made[1], arguments.forces[1], rel_tol=1e-3
        ):
            raise CommandLineError(
                f"--forces {' '.join(f'{f:g}' for f in arguments.forces)}: the --calibration "
                f"{arguments.calibration} was made at {' '.join(f'{f:g}' for f in made)} N; "
                "give those or another --calibration"
            )
    # with no --calibration the pad is calibrated first (as the procedure would), the long part
    with (
        (
            building("pad calibration", bar=bar)
            if calibration is None
            else contextlib.nullcontext()
        ) as progress,
        (
            _no_contact(
                f"--size-mm {arguments.size_mm:g}",
                f"the finger found no {name}, too small for {arguments.sensor}'s load grid",
            )
            if arguments.shape
            else contextlib.nullcontext()
        ),
    ):
        if calibration is None:
            calibration = build(None, progress)
        result = measure_deformation(
            name,
            sensor=arguments.sensor,
            forces=tuple(arguments.forces),
            calibration=calibration,
            rng=arguments.seed,
            shape=None if arguments.shape is None else arguments.shape.replace("-", " "),
            size=None if arguments.size_mm is None else arguments.size_mm * 1e-3,
            youngs_modulus=None if arguments.modulus_mpa is None else arguments.modulus_mpa * 1e6,
            poisson_ratio=arguments.poisson_ratio,
            thickness=None if arguments.wall_mm is None else arguments.wall_mm * 1e-3,
            gauge_pressure=0.0 if arguments.gauge_kpa is None else arguments.gauge_kpa * 1e3,
        )
    pressed = " / ".join(f"{force:g}" for force in result.forces) + " N"
    lines = [
        f"{name} touched at {result.forces[0]:g} N, then pressed at "
        + " N and ".join(f"{force:g}" for force in result.forces[1:])
        + f" N on {arguments.sensor}",
        "verdict: " + ("deformable" if result.deformable else "rigid"),
        f"object stiffness: {result.stiffness:.3g} N/m ("
        + (
            f"pad {result.pad_stiffness:.3g} N/m)"
            if math.isfinite(result.pad_stiffness)
            else "the pad's compression did not grow between the presses: the load spread)"
        ),
        f"height at {pressed}: " + " / ".join(f"{h * 1e3:.2f}" for h in result.heights) + " mm",
        f"contact area at {pressed}: "
        + " / ".join(f"{a:.0f}" for a in result.area_pixels)
        + " pixels",
    ]
    seed_press = arguments.sensor == "vhdta128" and tuple(arguments.forces) == (12.0, 39.0)
    seed = _SEED.get(name) if seed_press else None
    if seed is not None:  # the seed's sensor and forces: its numbers beside ours
        lines.append(
            f"the seed (Ellis 2.2, its 128 x 128 sensor): height unloaded / at 12 / 39 N "
            f"{seed[0]} mm (here {result.unloaded_height * 1e3:.1f} mm unloaded); contact area "
            f"at 12 / 39 N {seed[1]} pixels"
        )
    return _emit(arguments, result.to_dict(), lines, built)
