"""Writers: every file taxel writes goes through here, and nothing is overwritten by accident."""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["check_new_file", "write_files", "write_frame", "write_text"]


def check_new_file(
    path: str | os.PathLike[str],
    *,
    suffix: str | None = None,
    overwrite: bool = False,
    name: str = "path",
    inputs: tuple[str | os.PathLike[str], ...] = (),
) -> Path:
    """Check that `path` may be written, and return it as a Path.

    It must have the right suffix (in any case: ``.NPY`` is a .npy file), lie in a folder
    that exists and takes new files, not be an existing file (unless `overwrite`), and
    never be one of the `inputs`. Whether the folder takes new files is tried by creating
    and removing an empty temporary file in it, so that a command finds out before its
    work, not after.

    Raises
    ------
    ValueError
        Wrong suffix, a missing folder, a folder's path, or the path of an input file.
    FileExistsError
        The file exists and `overwrite` is False.
    OSError
        The folder takes no new file (read-only, no permission, a virtual file system); the
        message names `name` and the file.

    Examples
    --------
    >>> check_new_file("frame.txt", suffix=".npy")
    Traceback (most recent call last):
    ...
    ValueError: `path` must name a .npy file, got 'frame.txt'
    """
    target = Path(path)
    label = name if name.startswith("--") else f"`{name}`"  # a flag, or a parameter
    if suffix is not None and target.suffix.lower() != suffix:
        # as given: Path("") reads as "."
        raise ValueError(f"{label} must name a {suffix} file, got {os.fspath(path)!r}")
    if not target.parent.is_dir():
        what = "a file, not a folder" if target.parent.exists() else "a folder that does not exist"
        raise ValueError(f"{label} is in {what}: {str(target.parent)!r}")
    if target.is_dir():
        raise ValueError(f"{label} {str(target)!r} is a folder; name a file")
    for source in inputs:
        if Path(source).exists() and target.exists() and target.samefile(source):
            raise ValueError(f"{label} {str(target)!r} is an input file; choose another")
    if os.path.lexists(target) and not overwrite:  # (a link to a missing file is one too)
        how = "--overwrite" if name.startswith("--") else "overwrite=True"
        raise FileExistsError(f"{label} {str(target)!r} exists; pass {how} to replace it")
    _check_folder_takes_files(target, label)
    return target


def _check_folder_takes_files(target: Path, label: str) -> None:
    """Create and remove an empty file beside `target`; an OSError naming it if that fails."""
    try:
        handle, probe = tempfile.mkstemp(prefix=f".{target.name}.", dir=target.parent)
    except OSError as error:
        why = error.strerror or error
        raise type(error)(f"{label} {target} cannot be written ({why})") from None
    os.close(handle)
    with contextlib.suppress(OSError):
        os.unlink(probe)


def _partial(target: Path) -> Path:
    """The temporary file beside `target` that is renamed to it once complete."""
    return target.with_name(f".{target.name}.partial")


def _atomic(target: Path, write: Callable[[Path], Any]) -> Path:
    """Write to a temporary file beside `target`, then rename: no half-written files."""
    write_files([(target, write)])
    return target


def write_files(jobs: list[tuple[Path, Callable[[Path], Any]]]) -> None:
    """Write several files all or none: each to a temporary file beside it, then rename.

    Each job is (target, write), where ``write(temporary)`` writes the content to the path
    it is given. The renames start only once every write has succeeded; when one fails, no
    target is touched and every temporary file is removed.

    Raises
    ------
    OSError
        From the first write or rename that fails, with the target's name (not the
        temporary one's) as its filename. Removing the temporary files afterwards never
        raises (on a read-only file system it cannot, and there is nothing to remove).
    """
    temporaries = [_partial(target) for target, _ in jobs]
    step = 0
    try:
        for step, (_, write) in enumerate(jobs):
            write(temporaries[step])
        for step, (target, _) in enumerate(jobs):
            os.replace(temporaries[step], target)
    except OSError as error:  # named by the file asked for, not the temporary one
        raise OSError(error.errno, error.strerror, str(jobs[step][0])) from None
    finally:
        for temporary in temporaries:
            with contextlib.suppress(OSError):  # EROFS: nothing was created to remove
                temporary.unlink(missing_ok=True)


def write_frame(
    path: str | os.PathLike[str],
    frame: Any,
    *,
    overwrite: bool = False,
    inputs: tuple[str | os.PathLike[str], ...] = (),
) -> Path:
    """Save one frame (or any array) as a .npy file, refusing to overwrite an existing file.

    Parameters
    ----------
    path : path
        The .npy file to write.
    frame : array_like
        The data.
    overwrite : bool, default False
        Replace an existing file.
    inputs : tuple of path
        Files the caller read from: writing over one of them is refused even with
        `overwrite`.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    target = check_new_file(path, suffix=".npy", overwrite=overwrite, inputs=inputs)
    array = np.asarray(frame)

    def save(temporary: Path) -> None:
        with open(temporary, "wb") as handle:
            np.save(handle, array)

    return _atomic(target, save)


def write_text(
    path: str | os.PathLike[str], text: str, *, overwrite: bool = False, suffix: str | None = None
) -> Path:
    """Write a text file (JSON, HTML, ...), refusing to overwrite an existing file."""
    target = check_new_file(path, suffix=suffix, overwrite=overwrite)
    return _atomic(target, lambda temporary: temporary.write_text(text, encoding="utf-8"))
