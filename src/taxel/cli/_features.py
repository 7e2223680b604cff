"""``taxel features FILE``: the passive features of one tactile image."""

from __future__ import annotations

import argparse
import json
import math
import sys
from decimal import Decimal
from pathlib import Path
from typing import Any

import numpy as np

from taxel._validation import shown_apart
from taxel.cli._arguments import positive, positive_in, preset
from taxel.cli._files import reading, writing
from taxel.cli._pose_file import POSE_FORMATS, load_pose

__all__ = ["register"]

# taxel.features computes in single precision, where sums of squares of readings above
# about 1e17 overflow (a RuntimeWarning, then NaN or inf); no sensor reads 1e15 in any unit
_LARGEST_VALUE = 1e15
# the table shows larger numbers (a pose's translation, say) in exponent notation
_LARGEST_FIXED = 1e9


def _for_the_command(message: str) -> str:
    """`read_frame`'s message, its advice to Python users put for the command line."""
    return message.replace(
        "; read it with `read_sequence`", ": a sequence of frames, where one frame is read"
    )


def _check_magnitude(where: str, values: np.ndarray, advice: str) -> None:
    """Refuse values beyond `_LARGEST_VALUE`, the largest shown with the digits that tell it.

    The extremes are read as doubles first: the absolute value of int64's least overflows.
    """
    largest = max(abs(float(values.min())), abs(float(values.max())))
    if largest > _LARGEST_VALUE:
        # as few digits as tell the value from the limit (1.0000001e15 is no "1e+15")
        raise ValueError(
            f"{where}: values up to {shown_apart(largest, _LARGEST_VALUE)}, beyond the "
            f"{_LARGEST_VALUE:.0e} the features handle (they compute in single precision)"
            f"{advice}"
        )


def _format(value: Any, scale: float = 1.0, digits: int = 3) -> str:
    if value is None:
        return "-"
    if isinstance(value, list | tuple):
        return "(" + ", ".join(_format(v, scale, digits) for v in value) + ")"
    if isinstance(value, float) and not math.isfinite(value):
        return "-"
    shown = value * scale
    if not math.isfinite(shown):  # a finite value the scale takes past a double's range
        return f"{Decimal(value) * Decimal(scale):.{digits}e}"
    if abs(shown) >= _LARGEST_FIXED:
        return f"{shown:.{digits}e}"
    text = f"{shown:.{digits}f}"
    return text.lstrip("-") if float(text) == 0 else text  # never "-0.000"


def _direction(angle_rad: float | None) -> str:
    """An axis's direction [deg] in (-90, 90], one decimal: a line at 179.96 deg shows 0.0."""
    if angle_rad is None or not math.isfinite(angle_rad):
        return "-"
    return _format(-((-math.degrees(angle_rad) + 90.0) % 180.0 - 90.0), digits=1)


def _table(data: dict[str, Any]) -> str:
    contact, line, circle = data["contact"], data["line"], data["circle"]
    rows = [
        ("contact", "yes" if contact["present"] else "no"),
        ("contact type", f"{data['contact_type']} ({data['contact_rule']}, "
         f"confidence {data['contact_confidence']:.2f})"),
        ("regions", str(len(data["regions"]))),
        ("centroid (x, y) [mm]", _format(contact["centroid_m"], 1e3)),
        ("centroid (row, col) [taxels]", _format(contact["centroid_index"], 1.0, 2)),
        ("area [mm^2]", _format(contact["area_m2"], 1e6)),
        ("total force [N]", _format(contact["total_force_n"])),
        ("orientation [deg]", _direction(contact["orientation_rad"])),
        ("centroid (x, y, z), base [mm]", _format(contact["centroid_base_m"], 1e3)),
        ("edges", str(data["n_edges"])),
        ("edge / corner score", f"{data['edge_score']:.2f} / {data['corner_score']:.2f}"),
        ("line angle [deg]", _direction(line["angle_rad"])),
        ("line rms [mm]", _format(line["rms_m"], 1e3)),
        ("circle centre (x, y) [mm]", _format(circle["center_m"], 1e3)),
        ("circle radius [mm]", _format(circle["radius_m"], 1e3)),
        ("circle rms [mm]", _format(circle["rms_m"], 1e3)),
        ("holes", f"{data['holes']['count']} (seed's diameter test: "
         f"{'yes' if data['holes']['diameter_test'] else 'no'})"),
    ]  # fmt: skip
    for hole in data["holes"]["items"]:
        rows.append(
            ("  hole", f"centre {_format(hole['center_m'], 1e3)} mm, "
             f"radius {_format(hole['radius_m'], 1e3)} mm")
        )  # fmt: skip
    rows.append(("slots", str(data["slots"]["count"])))
    for slot in data["slots"]["items"]:
        rows.append(
            ("  slot", f"centre {_format(slot['center_m'], 1e3)} mm, "
             f"direction {_direction(slot['angle_rad'])} deg, "
             f"width {_format(slot['width_m'], 1e3)} mm, "
             f"length {_format(slot['length_m'], 1e3)} mm"
             + (" (runs off the array)" if slot["truncated"] else ""))
        )  # fmt: skip
    texture = data["texture"]
    rows += [
        ("planarity", _format(data["planarity"], 1.0, 2)),
        ("normal", _format(data["normal"])),
        ("tilt [deg]", _format(data["tilt_rad"], 180.0 / math.pi, 2)),
        ("texture maxima", str(texture["maxima_count"])),
        ("texture mean height", _format(texture["mean_height"], 1.0, 2)),
        ("texture wavelength [mm]", _format(texture["dominant_wavelength_m"], 1e3)),
    ]
    width = max(len(name) for name, _ in rows)
    return "\n".join(f"{name:<{width}}  {value}" for name, value in rows)


def _pitch(arguments: argparse.Namespace) -> Any:
    """The taxel pitch [m] from --pitch, or the preset sensor named by --sensor.

    A preset is handed to the features whole: besides its pitch they use its cover (defect
    removal, the blur allowed for when judging sizes).
    """
    if arguments.sensor is not None and arguments.pitch is not None:
        raise ValueError("give either --sensor PRESET or --pitch METRES, not both")
    if arguments.sensor is not None:
        from taxel.sensor import make_sensor

        return make_sensor(arguments.sensor)
    if arguments.pitch is None:
        raise ValueError("give the taxel pitch with --pitch METRES or a preset with --sensor")
    return arguments.pitch


def _noise(text: str) -> float | str:
    """--noise: a positive number, or "sensor" for the preset's own noise."""
    if text == "sensor":
        return text
    try:
        float(text)
    except ValueError:
        message = f"must be a number > 0 or 'sensor', got {text!r}"
        raise argparse.ArgumentTypeError(message) from None
    return positive(text)


def _check_noise(arguments: argparse.Namespace) -> None:
    """Refuse --noise sensor without a --sensor, or on a --calibrated image."""
    if arguments.noise != "sensor":
        return
    if arguments.sensor is None:
        raise ValueError("--noise sensor needs the sensor named with --sensor PRESET")
    if arguments.calibrated:
        raise ValueError(
            "--noise sensor is the noise of the sensor's raw frames, not of a --calibrated "
            "image: give the image's noise in Pa, or leave it to be estimated"
        )


def _check_images(arguments: argparse.Namespace, sensor: Any) -> None:
    """Refuse a --sensor whose raw frames are not images (microbend16 reads fibres)."""
    if arguments.sensor is None or arguments.calibrated:
        return
    rows, cols = sensor.shape
    signal = np.shape(sensor.mean_reading(np.zeros((rows, cols))))
    if len(signal) != 2:
        raise ValueError(
            f"--sensor {arguments.sensor} reads {signal[0]} fibres, not an image of its "
            f"{rows} x {cols} crossings: the features need an image; turn the fibres into a "
            "pressure map first (taxel.transducers.separable_pressure) and give it with "
            "--pitch and --calibrated"
        )


def _past_the_turn(arguments: argparse.Namespace, sensor: Any, frame: np.ndarray) -> bool:
    """Whether a raw frame of a --sensor has passed the reading where it turns back."""
    if arguments.calibrated or getattr(sensor, "reaches_turn", None) is None:
        return False
    return bool(sensor.reaches_turn(frame))


def _write_figure(path: Path, figure: Any) -> None:
    """Save the --figure PNG beside `path` and rename it: a failed write keeps an old one."""
    from taxel.io import write_files

    with writing("--figure", path):
        write_files([(path, lambda temporary: figure.savefig(temporary, dpi=120, format="png"))])


def _load_map(
    arguments: argparse.Namespace, flag: str, path: str, shape: tuple[int, ...]
) -> np.ndarray:
    """A --reference frame or --depth map: finite (as `read_frame` checks), FILE's shape."""
    from taxel.io import read_frame

    with reading(flag, path):
        try:
            values = read_frame(path, as_stored=True)
        except ValueError as error:  # (--key chooses FILE's array, not this one's)
            what = f"{flag} of one {'frame' if flag == '--reference' else 'map'}"
            message = _for_the_command(str(error))
            message = message.replace("; choose one with `key`", f"; give a {what}")
            raise ValueError(f"{flag}: {message}") from None
    _check_magnitude(f"{flag} {path}", values, "")
    if values.shape != shape:
        raise ValueError(
            f"{flag} {path}: a {' x '.join(map(str, values.shape))} "
            f"frame, but {arguments.file} is {shape[0]} x {shape[1]}"
        )
    return values


def _warn_if_defects_erased(
    arguments: argparse.Namespace,
    features: Any,
    image: np.ndarray,
    pitch: Any,
    preparation: dict[str, Any],
) -> None:
    """Warn when an explicit --defects removed every contact the image shows without it."""
    if arguments.defects is not True or features.contact.present:
        return
    from taxel.features import find_contact

    if find_contact(image, pitch, **{**preparation, "defects": False}).present:
        sys.stderr.write(
            f"taxel features: warning: --defects removed the only contact in "
            f"{arguments.file} (it removes everything bright narrower than 3 taxels, as a "
            "scratch or a hot pixel is); --no-defects keeps it\n"
        )


def _warn_if_pressed_all_over(
    arguments: argparse.Namespace, features: Any, image: np.ndarray, sensor: Any
) -> None:
    """Warn when even a raw frame's least pressed taxels read well above its sensor's rest.

    The features' baseline is the smoothed minimum, which then lies under the load (a
    plate over the whole array, a frame saturated everywhere): the contact found, or none,
    is measured from the wrong level, and a raw frame alone cannot show it.
    """
    if arguments.calibrated or arguments.reference is not None:
        return
    if not hasattr(sensor, "frame_from_pressure"):
        return
    from taxel.features import sensor_noise

    # noise-free frames at rest and under a plate at full scale; the least pressed taxels
    # are the lowest readings, or the highest where the reading falls with pressure
    grid = sensor.load_grid.shape
    rest = sensor.frame_from_pressure(np.zeros(grid)).raw
    full = sensor.frame_from_pressure(np.full(grid, sensor.full_scale)).raw
    quantile = 98 if getattr(sensor, "reading_falls_with_pressure", False) else 2
    least = float(np.percentile(image, quantile)) - float(np.percentile(rest, quantile))
    span = float(np.median(full)) - float(np.median(rest))
    # a real unit at rest may stand a few per cent of full scale from the model's
    if not (least / span > 0.05 and abs(least) > 3.0 * sensor_noise(sensor)):
        return
    found = "" if features.contact.present else "no contact found, but "
    sys.stderr.write(
        f"taxel features: warning: {found}even the least pressed taxels of {arguments.file} "
        f"read {least / span:.0%} of full scale above {arguments.sensor} at rest: it is "
        "pressed all over (a plate, or a frame saturated everywhere), and the features "
        "measure from a level under the load, which a raw frame cannot show by itself; give "
        "--reference REST.npy, a frame of the sensor at rest\n"
    )


def _run(arguments: argparse.Namespace) -> int:
    from taxel.features import extract
    from taxel.io import read_frame

    pitch = _pitch(arguments)
    _check_noise(arguments)
    _check_images(arguments, pitch)
    if arguments.figure is not None:
        from taxel.io import check_new_file

        check_new_file(
            arguments.figure,
            suffix=".png",
            overwrite=arguments.overwrite,
            name="--figure",
            inputs=tuple(
                path
                for path in (arguments.file, arguments.reference, arguments.depth, arguments.pose)
                if path
            ),
        )
    try:
        stored = read_frame(arguments.file, key=arguments.key, as_stored=True)
    except ValueError as error:  # read_frame names its parameter; here it is the flag
        raise ValueError(_for_the_command(str(error)).replace("`key`", "--key")) from None
    if arguments.calibrated and np.issubdtype(stored.dtype, np.integer):
        # as `taxel reconstruct` judges its FRAME: integers are an output's codes, not Pa
        raise ValueError(
            f"{arguments.file} holds raw codes ({stored.dtype}), not pressure [Pa]: leave out "
            "--calibrated for a raw frame, or give a pressure map (`taxel reconstruct "
            "FRAME --calibration CAL.npz` makes one)"
        )
    image = np.asarray(stored, dtype=np.float64)  # (as read_frame gives it)
    _check_magnitude(arguments.file, image, "; rescale the image")
    shape = getattr(pitch, "shape", None)
    if shape is not None and image.shape != tuple(shape):
        raise ValueError(
            f"{arguments.file}: a {image.shape[0]} x {image.shape[1]} image, but "
            f"{arguments.sensor} frames are {shape[0]} x {shape[1]}; for a map on another "
            "grid, give its pitch with --pitch"
        )
    pose = None if arguments.pose is None else load_pose(Path(arguments.pose))
    reference = None
    if arguments.reference is not None:
        reference = _load_map(arguments, "--reference", arguments.reference, image.shape)
    depth = None
    if arguments.depth is not None:
        depth = _load_map(arguments, "--depth", arguments.depth, image.shape).astype(float)
    integers = np.issubdtype(stored.dtype, np.integer)  # (their noise is read in code steps)
    given = stored if integers else image
    preparation = {
        "calibrated": arguments.calibrated,
        "noise": arguments.noise,
        "defects": arguments.defects,
        "reference": reference,
    }
    if _past_the_turn(arguments, pitch, given):
        sys.stderr.write(
            f"taxel features: warning: {arguments.file} reaches the first fringe of the "
            f"{arguments.sensor} layer (a reading of {pitch.reading_turns_at:.4g}); past it "
            "the reading turns back as the load grows, so the contact found is where the "
            "stress is about half a fringe, not where it is highest: press lighter\n"
        )
    try:
        features = extract(given, pitch, pose=pose, depth=depth, **preparation)
    except ValueError as error:  # ("`image` must be at least 3x3 taxels"): the file is named
        message = str(error).replace("`image`", f"{arguments.file}: the image")
        message = message.replace("`noise`", "--noise").replace("a sensor description", "--sensor")
        for flag in ("depth", "reference"):  # (their files are named too)
            message = message.replace(f"`{flag}`", f"--{flag} {getattr(arguments, flag)}")
        raise ValueError(message) from None
    _warn_if_defects_erased(arguments, features, given, pitch, preparation)
    _warn_if_pressed_all_over(arguments, features, image, pitch)
    if arguments.figure is not None:  # first: a figure that cannot be written stops all output
        from taxel.viz import plot_features

        figure = plot_features(given, features, pitch, **preparation)
        _write_figure(Path(arguments.figure), figure)
    data = features.to_dict()
    if arguments.json:
        sys.stdout.write(json.dumps(data, indent=2) + "\n")
    else:
        sys.stdout.write(_table(data) + "\n")
    return 0


def register(commands: Any) -> None:
    """Add the ``features`` subcommand to the ``taxel`` parser's subcommands."""
    parser = commands.add_parser(
        "features",
        help="passive tactile features of one image (contact, type, holes, slots, texture)",
        description="Extract the passive tactile features of one image (.npy, .npz, .png/.tif of "
        "8 or 16 bit, .csv) and print them as a table or as JSON.",
    )
    parser.add_argument("file", help="the tactile image")
    parser.add_argument(
        "--key", metavar="NAME", help="the frame's array in an .npz holding several"
    )
    parser.add_argument(
        "--pitch", type=positive_in(1e-9, 1.0), metavar="METRES", help="taxel pitch [m], 1e-9 to 1"
    )
    parser.add_argument(
        "--sensor",
        type=preset,
        metavar="PRESET",
        help="the sensor preset the image comes from (e.g. vhdta128, resistive16): its "
        "pitch and cover",
    )
    parser.add_argument(
        "--pose",
        metavar="POSE.json",
        help="sensor pose T_BS in the base frame [m]: a JSON file holding "
        + POSE_FORMATS
        + " (a 3x3 list of rows; the quaternion scalar-last; the rotation vector in "
        "radians); no other key",
    )
    parser.add_argument(
        "--calibrated",
        action="store_true",
        help="the image holds pressure [Pa] (real numbers: an image of integers holds raw codes "
        "and is refused), so the contact carries a total force [N]",
    )
    parser.add_argument(
        "--noise",
        type=_noise,
        metavar="UNITS|sensor",
        help="the noise standard deviation of one taxel, in the image's units, when it is "
        "known; 'sensor': the --sensor preset's own noise in raw codes, for a raw frame (only "
        "as right as the preset's model: a noisier frame then shows contacts in its noise). "
        "By default estimated from the image, which takes a texture as fine as the taxels "
        "over the whole array for noise; a raw frame of a --sensor with fewer than 16 "
        "interior taxels (capacitive4x4), too small for the estimate, takes the preset's; "
        "given --pitch, such an image needs --noise",
    )
    parser.add_argument(
        "--defects",
        action=argparse.BooleanOptionalAction,
        help="remove (or, with --no-defects, keep) bright defects narrower than 3 taxels, "
        "such as an FTIR sensor's glass scratches and hot pixels, before finding the contact. "
        "By default they are removed from a raw frame of a sensor whose cover is 3 or more "
        "taxels deep (--sensor vhdta128 or photoelastic64) and kept otherwise: never removed "
        "from a --calibrated image, whose calibration has removed the sensor's fixed defects, "
        "and which as a "
        "pressure map from `taxel reconstruct` can be as sparse as the load, nor when a "
        "--reference is subtracted",
    )
    parser.add_argument(
        "--reference",
        metavar="FILE",
        help="the sensor's unloaded frame (or the mean of several), subtracted first: it "
        "removes the fixed pattern no contact makes (an FTIR glass's scratches, each taxel's "
        "offset), so that a frame at rest reads as no contact",
    )
    parser.add_argument(
        "--depth",
        metavar="FILE",
        help="the cover's indentation at each taxel [m], positive into the cover, from a "
        "sensor that measures displacement or depth (an optical one): it gives the contact "
        "plane's normal (JSON 'normal', 'tilt_rad') and the contact's depth (JSON "
        "'position_sensor_m', its z; in the table, through the base frame's z given --pose)",
    )
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")
    parser.add_argument("--figure", metavar="PNG", help="also draw the features to this file")
    parser.add_argument("--overwrite", action="store_true", help="replace an existing --figure")
    parser.set_defaults(handler=_run)
