"""The files a command reads, builds and writes; their errors name the flag, not the parameter."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Mapping
from contextlib import AbstractContextManager, contextmanager
from pathlib import Path
from typing import Any

from taxel.cli._main import CommandLineError
from taxel.cli._progress import ProgressCallback, announced

__all__ = ["building", "cannot_write", "file_or_build", "reading", "writing"]


def cannot_write(error: OSError, flags: Mapping[Path, str]) -> CommandLineError:
    """The one-line error for a write that failed: ``--out FILE cannot be written (why)``.

    Parameters
    ----------
    error : OSError
        The failure, whose filename is the file asked for (`taxel.io`'s writers name it so,
        never their temporary file).
    flags : mapping of Path to str
        The option that named each file being written.
    """
    target = Path(str(error.filename))
    flag = flags.get(target)
    where = f"{flag} {target}" if flag is not None else str(target)
    return CommandLineError(f"{where} cannot be written ({error.strerror or error})")


@contextmanager
def writing(flag: str, *paths: str | os.PathLike[str]) -> Iterator[None]:
    """Turn an OSError about writing one of `paths` into a one-line error naming `flag`.

    Other errors, and OSErrors about other files, pass unchanged.
    """
    flags = {Path(path): flag for path in paths}
    try:
        yield
    except OSError as error:
        if error.filename is None or Path(str(error.filename)) not in flags:
            raise
        raise cannot_write(error, flags) from None


@contextmanager
def reading(flag: str, path: str | os.PathLike[str]) -> Iterator[None]:
    """Errors loading `path` (a --table, --model, ... file) as one line naming `flag`.

    The loaders' messages name their parameter, `` `path` ``, or begin with the file's
    name; here the flag is named. A file that does not exist is said to be missing, after
    the flag that named it.
    """
    try:
        yield
    except FileNotFoundError:
        if Path(path).exists():  # another file is missing (one it refers to): as it is
            raise
        raise FileNotFoundError(f"{flag} {path}: no such file") from None
    except IsADirectoryError:
        if not Path(path).is_dir():
            raise
        raise ValueError(f"{flag} {path}: a folder, not a file") from None
    except ValueError as error:
        message = str(error)
        if message.startswith("`path` "):
            raise ValueError(f"{flag} {message.removeprefix('`path` ')}") from None
        if message.startswith(
            tuple(f"{name}{end}" for name in {str(path), str(Path(path))} for end in (":", " "))
        ):  # (./x.json reads as x.json)
            raise ValueError(f"{flag} {message}") from None
        raise


def building(
    what: str, unit: str = "press", *, bar: bool = True
) -> AbstractContextManager[ProgressCallback]:
    """`announced` for a build: "building the `what` (this takes a while) ..." on a terminal.

    Returns the context manager, whose block gets the build's ``progress(done, total)``.
    """
    return announced(f"building the {what}", f"building the {what}", unit, bar=bar)


def file_or_build(
    path: str | None,
    load: Callable[[str], Any],
    build: Callable[[str, ProgressCallback], Any],
    what: str,
    option: str,
    built: list[str],
    *,
    unit: str = "press",
    bar: bool = True,
) -> Any:
    """Load `path` when it exists; otherwise build it there (never overwriting a file).

    Where it cannot be written (a missing folder, another suffix) is found before the
    long build, not after it. `build` is called as ``build(path, progress)``, `progress`
    driving the bar of `building` (counting `unit`; none when `bar` is False). A file
    built is noted in `built`, for the command to tell once it has succeeded: told before,
    with an error after it, an error would leave two lines on stderr.
    """
    if path is None:
        return None
    from taxel.io import check_new_file

    if Path(path).exists() and not Path(path).is_dir():
        with reading(option, path):
            return load(path)
    check_new_file(path, suffix=".json", name=option)
    with building(what, unit, bar=bar) as progress:
        made = build(path, progress)
    built.append(f"built the {what} and saved it to {path}")
    return made
