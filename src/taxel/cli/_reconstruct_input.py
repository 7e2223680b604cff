"""What ``taxel reconstruct`` reads: the frame, through the sensor's calibration if given."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from taxel.cli._files import reading

if TYPE_CHECKING:
    from taxel.sensor import Calibration, TactileSensor

__all__ = ["LARGEST_PRESSURE", "load_readings"]

LARGEST_PRESSURE = 1e12  # [Pa]
# a reflective sensor's power peaks at a gap h_min: pressed closer, it reads low again
_PAST_PEAK = " Or pressed past the peak of its response, where its reading falls again?"


def load_readings(
    path: Path, sensor_name: str, calibration_path: str | None
) -> tuple[np.ndarray, list[str], np.ndarray | None]:
    """The readings of FRAME in the forward model's quantity, checked in range.

    Raw codes go through --calibration (`taxel.reconstruction.calibrated_readings`): to the
    pressure felt at depth [Pa], or for a displacement sensor to the surface displacement
    [m]. Real numbers without a calibration are taken as readings already. Also returns the
    warnings about raw readings the calibration does not cover: at or beyond its full scale,
    or below its no-load level (none without a calibration), and the taxels the calibration
    excluded (dead, stuck or saturated: NaN in the readings, left out of the fit), a
    boolean mask, or None without a calibration.
    """
    from taxel.sensor import make_sensor

    sensor = make_sensor(sensor_name)
    frame = _load_frame(path)
    stored = frame.dtype
    if sensor.is_dynamic and (calibration_path is not None or np.issubdtype(stored, np.integer)):
        raise ValueError(
            f"--sensor {sensor_name} senses only changes of load ({sensor.quantity}): no "
            "static calibration maps its raw codes (`taxel calibrate` cannot make one); give "
            f"FRAME {str(path)!r} as the stress change each taxel felt [Pa], in real numbers"
        )
    warnings: list[str] = []
    excluded = None
    if calibration_path is not None:
        from taxel.reconstruction import calibrated_readings
        from taxel.sensor import Calibration

        _check_archive(Path(calibration_path))
        with reading("--calibration", calibration_path):
            calibration = Calibration.load(calibration_path)
        if calibration.sensor_name != sensor_name:  # before the frame: the likelier mistake
            raise ValueError(
                f"--calibration {calibration_path} was made for {calibration.sensor_name}, "
                f"not --sensor {sensor_name}"
            )
        if calibration.shape != sensor.shape:  # a damaged or hand-made file
            raise ValueError(
                f"--calibration {calibration_path} is of {sensor_name} but calibrates frames "
                f"of {calibration.shape}, not {sensor.shape}"
            )
        _check_shape(path, frame, sensor)
        excluded = ~calibration.valid
        if excluded.all():  # (before any reading: NumPy warns of its empty means)
            raise ValueError(
                f"--calibration {calibration_path} excludes every taxel of {sensor_name} "
                "(none responds to load): there is nothing to reconstruct from"
            )
        warnings = _uncovered(path, frame, calibration, sensor)
        frame = calibrated_readings(frame, calibration, sensor)
    elif np.issubdtype(stored, np.integer):
        raise ValueError(
            f"`FRAME` {str(path)!r} holds raw codes ({stored}); give the sensor's "
            "calibration with --calibration CAL.npz (made by `taxel calibrate`)"
        )
    _check_shape(path, frame, sensor)
    _check_range(path, frame, sensor)
    return frame, warnings, excluded


def _uncovered(
    path: Path, raw: np.ndarray, calibration: Calibration, sensor: TactileSensor
) -> list[str]:
    """Warnings about raw readings beyond the calibration's full scale or below no load."""
    warnings = []
    saturated = int(np.count_nonzero(calibration.beyond_full_scale(raw)))
    if saturated:
        warnings.append(
            f"{saturated} taxel readings of {path} are at or beyond the calibration's full "
            "scale: the load there is lost, and the force recovered is too small"
        )
    below = calibration.below_rest(raw)
    if np.any(below):
        rest = calibration.readings[0][calibration.valid]
        falls = calibration.direction < 0  # (microbend fibres: load lowers the reading)
        side, worst = ("above", np.max) if falls else ("below", np.min)
        most = float(worst(raw[below]))
        code = " (a code below 0, which no ADC outputs)" if most < 0 else ""
        warnings.append(
            f"{int(np.count_nonzero(below))} taxel readings of {path} are {side} the "
            f"calibration's no-load level ({'up' if falls else 'down'} to {most:.6g}{code}; "
            f"no load reads {float(rest.min()):.6g} to {float(rest.max()):.6g}): they read "
            "as a negative pressure, and the force recovered is wrong (is FRAME a raw frame "
            f"of this {calibration.sensor_name}?"
            + (_PAST_PEAK if sensor.quantity == "displacement" else "")
            + ")"
        )
    return warnings


def _check_shape(path: Path, frame: np.ndarray, sensor: TactileSensor) -> None:
    """Refuse a FRAME whose frames are not the sensor's, naming the file and the sensor."""
    if frame.ndim < 2:
        raise ValueError(
            f"`FRAME` {str(path)!r} holds an array of shape {frame.shape}, not frames of "
            f"--sensor {sensor.name}, which are {sensor.shape}"
        )
    if frame.shape[-2:] != sensor.shape:
        raise ValueError(
            f"`FRAME` {str(path)!r} holds frames of {frame.shape[-2:]}, but --sensor "
            f"{sensor.name}'s frames are {sensor.shape}"
        )


def _load_frame(path: Path) -> np.ndarray:
    """The readings of FRAME, a .npy file of real numbers (NaN marks dead taxels)."""
    from taxel.io import read_array

    if not path.is_file():
        what = "a folder" if path.is_dir() else "not an existing file"
        raise ValueError(f"`FRAME` must be an existing .npy file; {str(path)!r} is {what}")
    try:
        frame = read_array(path)
    except ValueError as error:
        raise ValueError(f"`FRAME` {error}") from None
    if not (np.issubdtype(frame.dtype, np.integer) or np.issubdtype(frame.dtype, np.floating)):
        raise ValueError(f"`FRAME` {str(path)!r} holds {frame.dtype} values, not real numbers")
    return frame


def _check_range(path: Path, readings: np.ndarray, sensor: TactileSensor) -> None:
    """Refuse readings beyond any contact (the solvers' squares would overflow)."""
    from taxel.reconstruction import spec_from_sensor

    finite = readings[np.isfinite(readings)]  # NaN marks a dead taxel
    largest = float(np.abs(finite).max()) if finite.size else 0.0
    spec = spec_from_sensor(sensor)
    if spec.quantity == "stress":
        if largest > LARGEST_PRESSURE:
            raise ValueError(
                f"`FRAME` {str(path)!r} holds pressures up to {largest:.3g} Pa, beyond any "
                f"contact (at most {LARGEST_PRESSURE:.0e} Pa, well past the strength of any "
                "material)"
            )
        return
    # a displacement [m] or strain [-]: the reading of a plate at that pressure
    limit = LARGEST_PRESSURE * float(spec.full_scale or 0.0) / sensor.full_scale
    unit = " m" if spec.quantity == "displacement" else ""
    if largest > limit:
        raise ValueError(
            f"`FRAME` {str(path)!r} holds {spec.quantity} readings up to {largest:.3g}{unit}, "
            f"beyond any contact (at most {limit:.3g}{unit}, that of a plate pressing "
            f"{LARGEST_PRESSURE:.0e} Pa, well past the strength of any material)"
        )


def _check_archive(path: Path) -> None:
    """Refuse a --calibration that is no zip archive (numpy would offer to unpickle it)."""
    if not path.is_file():
        return  # Calibration.load names what is missing
    with path.open("rb") as handle:
        if handle.read(4) != b"PK\x03\x04":
            raise ValueError(
                f"--calibration {path}: not a taxel calibration file (not an .npz archive; "
                "`taxel calibrate` makes one)"
            )
