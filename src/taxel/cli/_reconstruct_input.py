"""What ``taxel reconstruct`` reads: the frame, through the sensor's calibration if given."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from taxel.cli._files import reading

__all__ = ["LARGEST_PRESSURE", "load_readings"]

LARGEST_PRESSURE = 1e12  # [Pa]


def load_readings(path: Path, calibration_path: str | None) -> np.ndarray:
    """The readings of FRAME, calibrated with --calibration when given; checked in range."""
    frame = _load_frame(path)
    stored = frame.dtype
    if calibration_path is not None:
        from taxel.sensor import Calibration

        _check_archive(Path(calibration_path))
        with reading("--calibration", calibration_path):
            calibration = Calibration.load(calibration_path)
        if frame.shape[-2:] != tuple(calibration.shape):
            raise ValueError(
                f"`FRAME` {str(path)!r} holds frames of {frame.shape[-2:]}, but --calibration "
                f"is of {calibration.sensor_name}, whose frames are {tuple(calibration.shape)}"
            )
        frame = calibration.felt_pressure(frame)
    elif np.issubdtype(stored, np.integer):
        raise ValueError(
            f"`FRAME` {str(path)!r} holds raw codes ({stored}); give the sensor's "
            "calibration with --calibration CAL.npz (made by `taxel calibrate`)"
        )
    _check_range(path, frame)
    return frame


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


def _check_range(path: Path, pressure: np.ndarray) -> None:
    """Refuse readings beyond any contact pressure (the solvers' squares would overflow)."""
    finite = pressure[np.isfinite(pressure)]  # NaN marks a dead taxel
    largest = float(np.abs(finite).max()) if finite.size else 0.0
    if largest > LARGEST_PRESSURE:
        raise ValueError(
            f"`FRAME` {str(path)!r} holds pressures up to {largest:.3g} Pa, beyond any contact "
            f"(at most {LARGEST_PRESSURE:.0e} Pa, well past the strength of any material)"
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
