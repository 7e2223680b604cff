"""Reading .npy and .npz files safely: a corrupt file is a ValueError naming it, never a crash.

`numpy.load` trusts the header of a .npy file: one claiming a shape of a million frames
makes it allocate terabytes (a MemoryError) before it finds that the data are missing, and
a text or image file is taken for a pickle (with a hint to load it unsafely). These readers
check the header against the bytes the file holds first.
"""

from __future__ import annotations

import math
import os
import zipfile
from typing import IO

import numpy as np

from taxel.io._table import check_file

__all__ = ["read_archive", "read_array"]

_NPY_MAGIC = b"\x93NUMPY"
_ZIP_MAGIC = b"PK\x03\x04"


def _check_header(stream: IO[bytes], size: int) -> None:
    """Raise ValueError when the .npy header in `stream` claims more data than `size` bytes.

    Leaves `stream` at its start. Headers of other versions are left to `numpy.load`.
    """
    start = stream.read(len(_NPY_MAGIC))
    stream.seek(0)
    if not start:
        raise ValueError("the file is empty")
    if start.startswith(_ZIP_MAGIC):
        raise ValueError("it is an .npz archive; save one array with np.save")
    if start != _NPY_MAGIC:
        raise ValueError("no NumPy header: a text or image file?")
    version = np.lib.format.read_magic(stream)
    readers = {
        (1, 0): np.lib.format.read_array_header_1_0,
        (2, 0): np.lib.format.read_array_header_2_0,
    }
    if version in readers:
        shape, _, dtype = readers[version](stream)
        claimed = math.prod(shape) * dtype.itemsize
        held = size - stream.tell()
        if not dtype.hasobject and claimed > held:
            raise ValueError(
                f"truncated or corrupt: its header claims shape {shape} of {dtype} "
                f"({claimed} bytes), but {held} bytes follow"
            )
    stream.seek(0)


def read_array(path: str | os.PathLike[str]) -> np.ndarray:
    r"""The array in a .npy file, as stored (its dtype and shape), without pickles.

    Parameters
    ----------
    path : str or path-like
        The .npy file.

    Returns
    -------
    numpy.ndarray

    Raises
    ------
    FileNotFoundError
        When `path` does not exist.
    ValueError
        Naming the file when it is empty, truncated, an .npz archive, not a .npy file at
        all, holds objects, or its header claims more data than the file holds.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "frame.npy"
    >>> np.save(path, np.arange(4).reshape(2, 2))
    >>> read_array(path)
    array([[0, 1],
           [2, 3]])
    >>> _ = path.write_text("1, 2\n3, 4\n")
    >>> read_array(path)
    Traceback (most recent call last):
    ...
    ValueError: ...frame.npy: not a readable .npy file (no NumPy header: a text or image file?)
    """
    path = check_file(path)
    try:
        with path.open("rb") as handle:
            _check_header(handle, path.stat().st_size)
            array = np.load(handle, allow_pickle=False)
    except (ValueError, EOFError, OSError) as error:
        raise ValueError(f"{path}: not a readable .npy file ({error})") from None
    return np.asarray(array)


def read_archive(path: str | os.PathLike[str]) -> dict[str, np.ndarray]:
    """Every array of an .npz file, by name, each checked as `read_array` checks a .npy.

    Members that are not .npy files (metadata stored beside the arrays) are left out.

    Raises
    ------
    FileNotFoundError
        When `path` does not exist.
    ValueError
        Naming the file when it is not a zip archive, or one of its arrays is unreadable.
    """
    path = check_file(path)
    arrays = {}
    # numpy leaves the file open when the archive is corrupt, so we own the handle
    try:
        with path.open("rb") as handle, zipfile.ZipFile(handle) as archive:
            for member in archive.infolist():
                if not member.filename.endswith(".npy"):
                    continue  # another file stored beside the arrays (a note, metadata)
                name = member.filename.removesuffix(".npy")
                with archive.open(member) as stream:
                    _check_header(stream, member.file_size)
                    arrays[name] = np.lib.format.read_array(stream, allow_pickle=False)
    except (ValueError, EOFError, OSError, zipfile.BadZipFile) as error:
        raise ValueError(f"{path}: not a readable .npz file ({error})") from None
    return arrays
