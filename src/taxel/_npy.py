"""Reading .npy and .npz files without trusting them (internal: `taxel.io` and `taxel.sensor`).

`numpy.load` trusts the header of a .npy file: one claiming a shape of a million frames
makes it allocate terabytes (a MemoryError) before it finds that the data are missing, and
a text or image file is taken for a pickle (with a hint to load it unsafely). These readers
check the header against the bytes the file holds first. They live at the package's top
level because the sensor layer, which reads its calibration files, may not import `io`.
"""

from __future__ import annotations

import ast
import math
import zipfile
import zlib
from collections.abc import Callable
from typing import IO, Any

import numpy as np

__all__ = ["NPY_MAGIC", "ZIP_MAGIC", "check_header", "read_npz"]

NPY_MAGIC = b"\x93NUMPY"
ZIP_MAGIC = b"PK\x03\x04"
# the end-of-archive record with which an archive of no members begins
_EMPTY_ZIP_MAGIC = b"PK\x05\x06"
# what a damaged archive raises besides BadZipFile: a corrupt deflate stream, a truncated
# member, an unknown compression method, an encrypted member
_ARCHIVE_ERRORS = (zipfile.BadZipFile, zlib.error, EOFError, NotImplementedError, RuntimeError)


def check_header(stream: IO[bytes], size: int) -> None:
    """Raise ValueError when the .npy header in `stream` claims more data than `size` bytes.

    Leaves `stream` at its start. Headers of other versions are left to `numpy.load`.
    """
    start = stream.read(len(NPY_MAGIC))
    stream.seek(0)
    if not start:
        raise ValueError("the file is empty")
    if start.startswith(ZIP_MAGIC):
        raise ValueError("it is an .npz archive; save one array with np.save")
    if start != NPY_MAGIC:
        raise ValueError("no NumPy header: a text or image file?")
    version = np.lib.format.read_magic(stream)
    readers: dict[tuple[int, int], Callable[[IO[bytes]], tuple[Any, bool, np.dtype]]] = {
        (1, 0): np.lib.format.read_array_header_1_0,
        (2, 0): np.lib.format.read_array_header_2_0,
        (3, 0): _read_header_3_0,
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


def _read_header_3_0(stream: IO[bytes]) -> tuple[tuple[int, ...], bool, np.dtype]:
    """(shape, fortran order, dtype) of a version 3.0 header: 2.0's, in UTF-8.

    NumPy has no public reader of it (np.save writes it for non-Latin-1 field names).
    """
    length = int.from_bytes(stream.read(4), "little")
    try:
        header = ast.literal_eval(stream.read(length).decode("utf-8"))
        shape = tuple(int(size) for size in header["shape"])
        dtype = np.lib.format.descr_to_dtype(header["descr"])
        return shape, bool(header["fortran_order"]), dtype
    except (SyntaxError, ValueError, TypeError, KeyError, UnicodeDecodeError):
        raise ValueError("corrupt: its version 3.0 header cannot be read") from None


def read_npz(stream: IO[bytes]) -> dict[str, np.ndarray]:
    """Every array of the .npz archive in `stream`, by name, each header checked first.

    Members that are not .npy files (metadata stored beside the arrays) are left out. A
    stream that is no zip archive, or a member that cannot be read, raises ValueError
    saying why; the caller names the file.
    """
    start = stream.read(len(ZIP_MAGIC))
    stream.seek(0)
    if not start:
        raise ValueError("the file is empty")
    if start == NPY_MAGIC[: len(ZIP_MAGIC)]:
        raise ValueError("one array (.npy), not an .npz archive")
    if start == _EMPTY_ZIP_MAGIC:
        return {}  # a zip archive of no members: `np.savez(path)` with no arrays
    if start != ZIP_MAGIC:
        raise ValueError("not an .npz archive: a text or image file?")
    arrays = {}
    try:
        with zipfile.ZipFile(stream) as archive:
            for member in archive.infolist():
                if not member.filename.endswith(".npy"):
                    continue  # another file stored beside the arrays (a note, metadata)
                name = member.filename.removesuffix(".npy")
                with archive.open(member) as handle:
                    check_header(handle, member.file_size)
                    arrays[name] = np.lib.format.read_array(handle, allow_pickle=False)
    except _ARCHIVE_ERRORS as error:
        raise ValueError(str(error) or type(error).__name__) from None
    return arrays
