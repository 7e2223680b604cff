"""``taxel active slip SEQUENCE.npz``: incipient and gross slip in a recorded sequence.

The archive holds the static array's frames (n_frames, rows, cols) and, optionally, a PVDF
array's frames taken at the same instants; `taxel.active.detect_slip` finds the events,
printed as a table (times in ms) or, with ``--json``, as strict JSON in SI units.
``--figure`` draws `taxel.viz.plot_slip`.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np

from taxel.cli._arguments import positive, positive_in
from taxel.cli._files import reading, writing
from taxel.cli._json import strict_json
from taxel.cli._main import CommandLineError

__all__ = ["register", "slip"]

_STATIC_KEY = "static"  # the static frames' array, unless told (or the only array)


def register(group: argparse._SubParsersAction) -> None:
    """Add ``slip`` to the ``taxel active`` procedures."""
    help_text = (
        "incipient and gross slip in a recorded sequence of frames (an .npz archive), "
        "from the contact pattern's displacement and, when given, a PVDF array"
    )
    parser = group.add_parser("slip", help=help_text, description=help_text)
    parser.add_argument("file", metavar="SEQUENCE.npz", help="the frames, (n, rows, cols)")
    parser.add_argument(
        "--frame-rate", type=positive, required=True, metavar="HZ", help="frame rate [Hz]"
    )
    parser.add_argument(
        "--static-key",
        metavar="K",
        help="the static frames' array ('static' if the archive holds one, else its only "
        "other array)",
    )
    parser.add_argument(
        "--piezo-key", metavar="K", help="the PVDF frames' array, at the same instants (none)"
    )
    parser.add_argument(
        "--pitch",
        type=positive_in(1e-6, 1.0),
        default=2e-3,
        metavar="METRES",
        help="taxel pitch of the static array [m] (0.002)",
    )
    parser.add_argument(
        "--piezo-time-constant",
        type=positive,
        metavar="S",
        help="R_f C_f of the PVDF charge amplifiers [s]: their leak is undone",
    )
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    parser.add_argument("--figure", metavar="OUT.png", help="also draw the detection here")
    parser.add_argument("--overwrite", action="store_true", help="replace an existing --figure")
    parser.set_defaults(handler=slip)


def slip(arguments: argparse.Namespace) -> int:
    """Detect slip in the frames of ``arguments.file`` and print the events."""
    from taxel.active import SlipDetector

    if arguments.piezo_time_constant is not None and arguments.piezo_key is None:
        raise CommandLineError(
            f"--piezo-time-constant {arguments.piezo_time_constant:g}: it is the PVDF "
            "amplifiers'; give their frames with --piezo-key"
        )
    if arguments.figure is not None:  # before the work: a figure that cannot be written stops here
        from taxel.io import check_new_file

        check_new_file(
            arguments.figure,
            suffix=".png",
            overwrite=arguments.overwrite,
            name="--figure",
            inputs=(arguments.file,),
        )
    detector = SlipDetector(
        taxel_pitch=arguments.pitch, piezo_time_constant=arguments.piezo_time_constant
    )
    static_key, static, piezo_key, piezo = _read(arguments, detector.warm_up)
    detection = detector.run(static, piezo, frame_rate=arguments.frame_rate)
    if arguments.figure is not None:
        from taxel.viz import plot_slip

        with writing("--figure", arguments.figure):
            plot_slip(detection, detector, path=arguments.figure, overwrite=arguments.overwrite)
    if arguments.json:
        payload = {
            "file": str(arguments.file),
            "static_key": static_key,
            "piezo_key": piezo_key,
            "n_frames": int(static.shape[0]),
            **detection.to_dict(),
            "position_noise_m": detection.position_noise,
        }
        text = strict_json(payload)
        sys.stdout.write(text + "\n")
    else:
        sys.stdout.write(_table(arguments, static_key, static, piezo_key, piezo, detection))
    return 0


def _table(
    arguments: argparse.Namespace,
    static_key: str,
    static: np.ndarray,
    piezo_key: str | None,
    piezo: np.ndarray | None,
    detection: Any,
) -> str:
    n, rows, cols = static.shape
    pvdf = "none" if piezo is None else f"{piezo_key!r}, {piezo.shape[1]} x {piezo.shape[2]}"
    lines = [
        f"{arguments.file}: {n} frames of {rows} x {cols} taxels ({static_key!r}) at "
        f"{arguments.frame_rate:g} Hz; PVDF frames: {pvdf}",
        f"initial state: {detection.initial_state} (position noise "
        f"{detection.position_noise * 1e6:.3g} um)",
    ]
    if not detection.events:
        why = "" if detection.initial_state == "holding" else " (no onset is reported)"
        return "\n".join([*lines, f"no slip detected{why}"]) + "\n"
    lines.append(f"{'kind':<10} {'frame':>6} {'time [ms]':>10}  channel")
    for event in detection.events:
        lines.append(
            f"{event.kind:<10} {event.frame:>6} {event.time * 1e3:>10.1f}  {event.channel}"
        )
    return "\n".join(lines) + "\n"


def _read(
    arguments: argparse.Namespace, warm_up: int
) -> tuple[str, np.ndarray, str | None, np.ndarray | None]:
    """The static frames and the PVDF frames (or None), each checked, with their keys."""
    from taxel.io import read_archive  # every array of an .npz, checked

    name = arguments.file
    if Path(name).suffix.lower() != ".npz":
        raise CommandLineError(f"SEQUENCE {name!r} must be an .npz archive of frames")
    with reading("SEQUENCE", name):
        arrays = read_archive(name)
    names = ", ".join(sorted(arrays)) or "no arrays"
    piezo_key = arguments.piezo_key
    static_key = arguments.static_key
    for flag, key in (("--static-key", static_key), ("--piezo-key", piezo_key)):
        if key is not None and key not in arrays:
            raise CommandLineError(
                f"{flag} {key!r}: {name} holds no such array (it holds {names})"
            )
    if static_key is None:
        others = [key for key in arrays if key != piezo_key]
        if _STATIC_KEY in arrays:
            static_key = _STATIC_KEY
        elif len(others) == 1:
            static_key = others[0]
        else:
            raise CommandLineError(
                f"{name} holds {names} and none named {_STATIC_KEY!r}: choose the static "
                "frames with --static-key"
            )
    if static_key == piezo_key:
        raise CommandLineError(f"--piezo-key {piezo_key!r} names the static frames too")
    static = _frames(name, "--static-key", static_key, arrays[static_key])
    if static.shape[0] <= warm_up:
        raise CommandLineError(
            f"{name}: {static_key!r} holds {static.shape[0]} frames; slip detection needs more "
            f"than its warm-up of {warm_up}"
        )
    if min(static.shape[1:]) < 2:
        raise CommandLineError(
            f"{name}: {static_key!r} frames are {static.shape[1]} x {static.shape[2]}; the "
            "pattern's displacement needs at least 2 x 2 taxels"
        )
    if piezo_key is None:
        return static_key, static, None, None
    piezo = _frames(name, "--piezo-key", piezo_key, arrays[piezo_key])
    if piezo.shape[0] != static.shape[0]:
        raise CommandLineError(
            f"--piezo-key {piezo_key!r}: {name} holds {piezo.shape[0]} PVDF frames but "
            f"{static.shape[0]} static frames ({static_key!r}); they must be taken at the "
            "same instants"
        )
    return static_key, static, piezo_key, piezo


def _frames(name: str, flag: str, key: str, array: np.ndarray) -> np.ndarray:
    """`array` as float frames (n, rows, cols) of finite numbers, or a one-line error."""
    if not (np.issubdtype(array.dtype, np.integer) or np.issubdtype(array.dtype, np.floating)):
        raise CommandLineError(f"{flag} {key!r}: {name} holds {array.dtype} data, not numbers")
    if array.ndim != 3 or array.size == 0:
        raise CommandLineError(
            f"{flag} {key!r}: {name} holds an array of shape {array.shape}, not frames "
            "(n_frames, rows, cols)"
        )
    frames = np.asarray(array, dtype=np.float64)
    bad = int(frames.size - np.count_nonzero(np.isfinite(frames)))
    if bad:
        raise CommandLineError(f"{flag} {key!r}: {name} holds {bad} NaN or infinite value(s)")
    return frames
