"""Reading .npy and .npz files safely: a corrupt file is a ValueError naming it, never a crash.

`numpy.load` trusts the header of a .npy file: one claiming a shape of a million frames
makes it allocate terabytes (a MemoryError) before it finds that the data are missing, and
a text or image file is taken for a pickle (with a hint to load it unsafely). These readers
check the header against the bytes the file holds first.
"""

from __future__ import annotations

import os

import numpy as np

from taxel._npy import check_header, read_npz
from taxel.io._table import check_file

__all__ = ["read_archive", "read_array"]


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
            check_header(handle, path.stat().st_size)
            array = np.load(handle, allow_pickle=False)
    except (ValueError, EOFError, OSError) as error:
        raise ValueError(f"{path}: not a readable .npy file ({error})") from None
    return np.asarray(array)


def read_archive(path: str | os.PathLike[str]) -> dict[str, np.ndarray]:
    """Every array of an .npz file, by name, each checked as `read_array` checks a .npy.

    Members that are not .npy files (metadata stored beside the arrays) are left out.

    Parameters
    ----------
    path : str or path-like
        The .npz file.

    Returns
    -------
    dict of str to numpy.ndarray
        Empty for an archive of no arrays.

    Raises
    ------
    FileNotFoundError
        When `path` does not exist.
    ValueError
        Naming the file when it is not a zip archive, or one of its arrays is unreadable.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "slide.npz"
    >>> np.savez(path, static=np.zeros((50, 16, 16)), piezo=np.ones((50, 8, 8)))
    >>> {name: array.shape for name, array in sorted(read_archive(path).items())}
    {'piezo': (50, 8, 8), 'static': (50, 16, 16)}
    """
    path = check_file(path)
    try:
        with path.open("rb") as handle:
            return read_npz(handle)
    except (ValueError, OSError) as error:
        raise ValueError(f"{path}: not a readable .npz file ({error})") from None
