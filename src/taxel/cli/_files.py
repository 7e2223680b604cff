"""The files a command reads and writes: their errors name the flag, not the API's parameter."""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path

from taxel.cli._main import CommandLineError

__all__ = ["cannot_write", "reading", "writing"]


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
    name; here the flag is named.
    """
    try:
        yield
    except ValueError as error:
        message = str(error)
        if message.startswith("`path` "):
            raise ValueError(f"{flag} {message.removeprefix('`path` ')}") from None
        if message.startswith((f"{path}:", f"{Path(path)}:")):  # (./x.json reads as x.json)
            raise ValueError(f"{flag} {message}") from None
        raise
