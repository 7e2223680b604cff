"""Readers of single tactile frames and of frame sequences (npy, npz, png, tif, csv).

A *frame* is one tactile image: a 2-D array of readings indexed (row, col), as in
`docs/architecture.md`. A *sequence* is a series of readings over time: a frame, or a
vector of channels, per time step, with a time stamp per step.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np

from taxel._validation import check_flag, check_positive
from taxel.io._arrays import read_archive, read_array
from taxel.io._table import check_file, read_numeric_table

__all__ = ["TactileSequence", "read_frame", "read_sequence"]

_IMAGE_SUFFIXES = (".png", ".tif", ".tiff")
_FRAME_SUFFIXES = (".npy", ".npz", ".csv", *_IMAGE_SUFFIXES)
_TIME_COLUMNS = ("timestamp", "time")


@dataclass(frozen=True)
class TactileSequence:
    """Readings over time, as read from a file.

    Attributes
    ----------
    time : numpy.ndarray
        (n_steps,) time of each step [s], non-decreasing.
    readings : numpy.ndarray
        (n_steps, ...) float64 readings per step: (n_steps, n_channels) for channel data,
        (n_steps, rows, cols) for frames. Units are those of the file (raw counts for
        most sensors).
    channel_names : tuple of str
        Names of the channels (the csv header without the time column); empty for frames.
    """

    time: np.ndarray
    readings: np.ndarray
    channel_names: tuple[str, ...] = ()

    @property
    def n_steps(self) -> int:
        """Number of time steps."""
        return int(self.time.shape[0])


def _finite(path: Path, array: np.ndarray, what: str) -> np.ndarray:
    """Return `array` as float64, or raise naming the file when it is not finite numbers."""
    if array.dtype == object or not (
        np.issubdtype(array.dtype, np.integer) or np.issubdtype(array.dtype, np.floating)
    ):
        raise ValueError(f"{path}: {what} holds {array.dtype} data, not real numbers")
    array = np.asarray(array, dtype=np.float64)
    if array.size == 0:
        raise ValueError(f"{path}: {what} is empty (shape {array.shape})")
    if not np.all(np.isfinite(array)):
        bad = int(array.size - np.count_nonzero(np.isfinite(array)))
        raise ValueError(f"{path}: {what} has {bad} NaN or infinite value(s)")
    return array


def _pick(path: Path, arrays: dict[str, np.ndarray], key: str | None) -> tuple[str, np.ndarray]:
    """The array named `key`, or the only one; a clear error when that is ambiguous."""
    names = ", ".join(sorted(arrays)) or "none"
    if key is not None:
        if key not in arrays:
            raise ValueError(f"{path}: no array named {key!r}; the file holds: {names}")
        return key, arrays[key]
    if not arrays:
        raise ValueError(f"{path}: the archive holds no arrays")
    if len(arrays) != 1:
        raise ValueError(f"{path}: holds {len(arrays)} arrays ({names}); choose one with `key`")
    return next(iter(arrays.items()))


# what OpenCV's unchanged read gives per channel count (a palette image is read as colour)
_CHANNELS = {
    2: " (grayscale with alpha)",
    3: " (colour, or a palette image)",
    4: " (colour or grayscale, with alpha)",
}


def _stored_bits(path: Path) -> int | None:
    """Bits per sample a PNG or (first page of a) TIFF stores, from its header; else None.

    OpenCV (through libpng and libtiff) scales 1-, 2- and 4-bit images to 8 bits: a 0/1
    image reads 0/255, so such a file cannot be read as stored.
    """
    with open(path, "rb") as stream:
        head = stream.read(32)
        if head.startswith(b"\x89PNG\r\n\x1a\n") and head[12:16] == b"IHDR":
            return head[24]
        if head[:4] not in (b"II*\x00", b"MM\x00*"):
            return None
        order: Literal["little", "big"] = "little" if head[:2] == b"II" else "big"
        stream.seek(int.from_bytes(head[4:8], order))
        count = int.from_bytes(stream.read(2), order)
        for _ in range(min(count, 4096)):
            entry = stream.read(12)
            if len(entry) < 12:
                return None
            if int.from_bytes(entry[:2], order) == 258:  # BitsPerSample, a SHORT
                if int.from_bytes(entry[4:8], order) != 1:
                    return None  # one per channel: a colour image, refused later
                return int.from_bytes(entry[8:10], order)
        return 1 if count <= 4096 else None  # (TIFF's default: a bilevel image omits it)


def _read_image(path: Path) -> np.ndarray:
    import cv2  # heavy; imported only when an image is read
    from cv2.utils import logging as cv_logging

    name = str(path)
    try:
        name.encode("utf-8")
    except UnicodeEncodeError:  # (OpenCV crashes on such a name, without a word)
        raise ValueError(
            f"{name!r}: the file's name is not valid UTF-8, which OpenCV cannot open; rename it"
        ) from None
    # OpenCV logs a corrupt file's problems to stderr itself; the ValueError below says it
    previous = cv_logging.getLogLevel()
    cv_logging.setLogLevel(cv_logging.LOG_LEVEL_SILENT)
    try:
        image = cv2.imread(name, cv2.IMREAD_UNCHANGED)
        tiff = path.suffix.lower() in (".tif", ".tiff")
        pages = cv2.imcount(name) if tiff and image is not None else 1
    except cv2.error as error:  # e.g. a header of more pixels than OpenCV reads (2^30)
        reason = str(getattr(error, "err", "") or error).strip().splitlines()[-1]
        if "MAX_IMAGE_PIXELS" in reason:
            reason = "its header claims more pixels than OpenCV reads (2^30)"
        raise ValueError(f"{path}: OpenCV cannot read the image: {reason}") from None
    finally:
        cv_logging.setLogLevel(previous)
    if image is None:
        raise ValueError(f"{path}: cannot decode the image (corrupt or truncated file?)")
    bits = _stored_bits(path)
    if bits is not None and bits < 8:
        raise ValueError(
            f"{path}: stores {bits}-bit samples, which OpenCV reads scaled to 8 bits (a 0/1 "
            "image reads 0/255); save the frame with 8 or 16 bits"
        )
    if pages > 1:
        raise ValueError(f"{path}: holds {pages} pages; a frame is one page")
    if image.ndim != 2:
        count = image.shape[2]
        raise ValueError(
            f"{path}: a tactile frame must be a grayscale image, got {count} channels"
            f"{_CHANNELS.get(count, '')}"
        )
    return image


def read_frame(
    path: str | os.PathLike[str], *, key: str | None = None, as_stored: bool = False
) -> np.ndarray:
    r"""Read one tactile frame from a .npy, .npz, .png, .tif or .csv file.

    Parameters
    ----------
    path : str or path-like
        The file; its suffix selects the format.
    key : str, optional
        For .npz archives holding several arrays, the name of the frame's array (refused
        for other formats).
    as_stored : bool, default False
        Return the values in the type the file stores them in (the integers of a raw
        frame: an image, or an .npy or .npz of integers; a csv is always float64) instead
        of float64, checked alike.

    Returns
    -------
    numpy.ndarray
        (rows, cols) float64 frame (or as stored, with `as_stored`), in the file's units
        (8- and 16-bit images keep their integer values, 0..255 and 0..65535).

    Raises
    ------
    FileNotFoundError
        When `path` does not exist.
    ValueError
        Naming the file (and line, for csv) when the format is unknown, the file is empty,
        truncated, corrupt, ragged or non-numeric (booleans included), holds NaN or inf, is
        not 2-D, is a colour image, an .npz holds several arrays and `key` is not given (or
        `key` is given for another format), or a csv has a time column (that is a sequence:
        use `read_sequence`).

    Notes
    -----
    Images are read with OpenCV (``cv2.imread(path, cv2.IMREAD_UNCHANGED)``) so that 16-bit
    PNG and TIFF keep their full depth; a frame must be grayscale and, for TIFF, one page.
    A csv frame is a grid of numbers, one image row per line, without a header: a header
    of words is refused, but one of numbers cannot be told from a row and is read as one
    (write a frame with pandas' ``to_csv(header=False, index=False)`` or ``np.savetxt``).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "frame.csv").write_text("0, 1, 2\n3, 4, 5\n")
    >>> read_frame(folder / "frame.csv")
    array([[0., 1., 2.],
           [3., 4., 5.]])
    """
    path = check_file(path)
    suffix = path.suffix.lower()
    if suffix not in _FRAME_SUFFIXES:
        raise ValueError(f"{path}: unknown frame format {suffix!r}; use one of {_FRAME_SUFFIXES}")
    if key is not None and suffix != ".npz":
        raise ValueError(
            f"{path}: `key` names an array of an .npz archive, not of a {suffix} file"
        )
    if suffix == ".npy":
        frame = read_array(path)
    elif suffix == ".npz":
        frame = _pick(path, read_archive(path), key)[1]
    elif suffix == ".csv":
        table = read_numeric_table(path)
        if table.header is not None:
            if any(name.lower() in _TIME_COLUMNS for name in table.header):
                raise ValueError(f"{path}: has a time column; read it with `read_sequence`")
            raise ValueError(f"{path}, line 1: a frame csv has no header, got {table.header}")
        frame = table.values
    else:
        frame = _read_image(path)
    checked = _finite(path, frame, "the frame")
    if checked.ndim != 2:
        raise ValueError(f"{path}: a frame must be 2-D, got shape {checked.shape}")
    return np.asarray(frame) if check_flag("as_stored", as_stored) else checked


def _check_time(path: Path, time: np.ndarray, lines: np.ndarray | None = None) -> None:
    steps = np.diff(time)
    if np.any(steps < 0):
        index = int(np.argmax(steps < 0)) + 1
        where = f"line {lines[index]}" if lines is not None else f"step {index}"
        raise ValueError(
            f"{path}, {where}: time goes backwards ({time[index - 1]:g} -> " f"{time[index]:g})"
        )


def read_sequence(
    path: str | os.PathLike[str],
    *,
    time_scale: float = 1.0,
    key: str = "readings",
) -> TactileSequence:
    r"""Read readings over time from a .csv (with a time column) or an .npz file.

    Parameters
    ----------
    path : str or path-like
        A csv whose header has a ``timestamp`` (or ``time``) column and one column per
        channel, one row per time step; or an npz holding ``time`` (n_steps,) and the array
        named `key` (n_steps, ...).
    time_scale : float
        Seconds per unit of the file's time values (1e-3 for milliseconds), > 0.
    key : str
        Name of the readings array in an npz archive.

    Returns
    -------
    TactileSequence
        `time` in seconds (as stored times `time_scale`), readings as float64.

    Raises
    ------
    FileNotFoundError
        When `path` does not exist.
    ValueError
        Naming the file and line when the csv has no time column, is empty, truncated,
        ragged or non-numeric; when time goes backwards; when the npz lacks ``time`` or
        `key`, or their lengths differ.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "log.csv").write_text("timestamp, a, b\n0, 1, 2\n20, 3, 4\n")
    >>> sequence = read_sequence(folder / "log.csv", time_scale=1e-3)
    >>> sequence.time, sequence.channel_names
    (array([0.  , 0.02]), ('a', 'b'))
    >>> sequence.readings
    array([[1., 2.],
           [3., 4.]])
    """
    time_scale = check_positive("time_scale", time_scale)
    path = check_file(path)
    suffix = path.suffix.lower()
    if suffix == ".csv":
        table = read_numeric_table(path, header=True)
        lowered = [name.lower() for name in table.header or ()]
        column = next((lowered.index(name) for name in _TIME_COLUMNS if name in lowered), None)
        if column is None:
            raise ValueError(f"{path}, line 1: no 'timestamp' column in the header")
        if table.values.shape[1] < 2:
            raise ValueError(f"{path}, line 1: no reading column beside the time column")
        time = table.values[:, column] * time_scale
        _check_time(path, time, table.line_numbers)
        readings = np.delete(table.values, column, axis=1)
        names = tuple(name for index, name in enumerate(table.header or ()) if index != column)
        return TactileSequence(time, readings, names)
    if suffix == ".npz":
        arrays = read_archive(path)
        if "time" not in arrays:
            raise ValueError(f"{path}: no array named 'time'; the file holds: {sorted(arrays)}")
        time = _finite(path, arrays["time"], "'time'") * time_scale
        readings = _finite(path, _pick(path, arrays, key)[1], repr(key))
        if time.ndim != 1 or readings.ndim < 2 or readings.shape[0] != time.shape[0]:
            raise ValueError(
                f"{path}: 'time' {time.shape} and {key!r} {readings.shape} must be (n_steps,) "
                "and (n_steps, ...)"
            )
        _check_time(path, time)
        return TactileSequence(time, readings)
    raise ValueError(f"{path}: unknown sequence format {suffix!r}; use .csv or .npz")
