"""JSON files of the active procedures (tables, calibrations, libraries): checked both ways."""

from __future__ import annotations

import json
import os
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from taxel.io import write_text

__all__ = ["parsing", "read_json", "write_json"]


def write_json(
    path: str | os.PathLike[str], data: dict[str, Any], *, overwrite: bool = False
) -> Path:
    """Write `data` as JSON; an existing file is replaced only with `overwrite`."""
    return write_text(path, json.dumps(data, indent=1), overwrite=overwrite)


def read_json(
    path: str | os.PathLike[str], file_format: str, required: Sequence[str], what: str
) -> dict[str, Any]:
    """Read a JSON file written by `write_json` and check its format tag and keys.

    Raises
    ------
    ValueError
        A folder, not JSON, another format, or a missing key: naming the file and what is
        wrong.
    """
    source = Path(path)
    if source.is_dir():
        raise ValueError(f"`path` {str(source)!r} is a folder, not {what}")
    if not source.is_file():
        raise FileNotFoundError(f"{str(source)!r} does not exist")
    try:
        data = json.loads(source.read_text(encoding="utf-8-sig"))
    except (json.JSONDecodeError, UnicodeDecodeError) as error:
        raise ValueError(f"`path` {str(source)!r} is not a JSON file: {error}") from None
    except RecursionError:
        raise ValueError(f"`path` {str(source)!r} is nested too deeply to be {what}") from None
    if not isinstance(data, dict) or data.get("format") != file_format:
        raise ValueError(f"`path` {str(source)!r} is not {what}")
    missing = [key for key in required if key not in data]
    if missing:
        keys = ", ".join(missing)
        raise ValueError(f"`path` {str(source)!r} lacks {keys}: it is not {what} made by taxel")
    return data


@contextmanager
def parsing(path: str | os.PathLike[str], what: str) -> Iterator[None]:
    """Errors making `what` from a file's values, said as the file's fault, naming it.

    A value of the wrong type or shape (text for a number, ragged lists, 1e999) fails in
    NumPy or in the checks of the object made; either way the file is what is wrong.
    """
    try:
        yield
    except (TypeError, ValueError, OverflowError) as error:
        raise ValueError(f"`path` {str(path)!r} is not {what} taxel can read: {error}") from None
