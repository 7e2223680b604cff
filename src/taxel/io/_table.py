"""A strict reader of numeric text tables, whose errors name the file and the line.

NumPy's text readers stop at the first problem with messages that do not always say which
file or line is wrong, and some of them pad or skip short rows. Every reader of `taxel.io`
that reads text goes through `read_numeric_table` instead, so that an empty, truncated,
ragged or non-numeric file raises a `ValueError` of the form
``"<file>, line <n>: <problem>"``.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["NumericTable", "check_file", "read_numeric_table"]


@dataclass(frozen=True)
class NumericTable:
    """The content of a numeric text table.

    Attributes
    ----------
    header : tuple of str or None
        Column names of the first line, stripped, or None when the file has no header.
    values : numpy.ndarray
        (n_rows, n_columns) float64 values, all finite.
    line_numbers : numpy.ndarray
        (n_rows,) 1-based line number of each row in the file, for later error messages.
    """

    header: tuple[str, ...] | None
    values: np.ndarray
    line_numbers: np.ndarray


def check_file(path: str | os.PathLike[str]) -> Path:
    """Return `path` as a Path, or raise FileNotFoundError naming it when it is no file."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"no such file: {path}")
    if not path.is_file():
        raise IsADirectoryError(f"not a regular file: {path}")
    return path


def _is_number(field: str) -> bool:
    try:
        float(field)
    except ValueError:
        return False
    return True


_OTHER_SEPARATORS = {";": "semicolons", "\t": "tabs"}


def _separator_hint(field: str, delimiter: str) -> str:
    """A note on a field that holds another separator (a spreadsheet's export), or ''."""
    for separator, name in _OTHER_SEPARATORS.items():
        if separator != delimiter and separator in field.strip():
            return (
                f" (fields must be separated by {delimiter!r}, with '.' for decimals; this line "
                f"has {name})"
            )
    return ""


def read_numeric_table(
    path: str | os.PathLike[str], *, delimiter: str = ",", header: bool | None = None
) -> NumericTable:
    """Read a delimited table of finite numbers, checking every line.

    Parameters
    ----------
    path : str or path-like
        The text file.
    delimiter : str
        Field separator.
    header : bool or None
        True: the first non-blank line is a header; False: there is none; None: the first
        non-blank line is a header when none of its fields is a number.

    Returns
    -------
    NumericTable

    Raises
    ------
    FileNotFoundError
        When `path` does not exist.
    ValueError
        Naming the file and line when the file is not text, is empty, has no data rows, has a
        row with a different number of fields than the first (ragged, or cut short at the end
        of a truncated file), or a field that is not a finite number.
    """
    path = check_file(path)
    try:
        # (utf-8-sig: a spreadsheet's byte-order mark is not part of the first field)
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError:
        raise ValueError(f"{path}: not a text file (cannot decode it as UTF-8)") from None
    lines = text.splitlines()
    numbered = [(number, line) for number, line in enumerate(lines, 1) if line.strip()]
    if not numbered:
        raise ValueError(f"{path}: the file is empty")
    names: tuple[str, ...] | None = None
    first_number, first_line = numbered[0]
    first_fields = [field.strip() for field in first_line.split(delimiter)]
    if header is None:
        header = not any(_is_number(field) for field in first_fields)
        hint = _separator_hint(first_line, delimiter)
        if header and len(first_fields) == 1 and hint:
            # numbers with another separator are no header
            raise ValueError(f"{path}, line {first_number}: one field, {first_fields[0]!r}{hint}")
    if header:
        names = tuple(first_fields)
        numbered = numbered[1:]
        if not numbered:
            raise ValueError(f"{path}, line {first_number}: a header but no data rows")
    width = len(names) if names is not None else len(numbered[0][1].split(delimiter))
    rows = []
    last_line = numbered[-1][0]
    cut_short = not text.endswith(("\n", "\r"))
    for number, line in numbered:
        fields = line.split(delimiter)
        problem = None
        if len(fields) != width:
            problem = f"{len(fields)} fields, expected {width}"
        else:
            try:
                row = [float(field) for field in fields]
            except ValueError:
                bad = next(field for field in fields if not _is_number(field))
                problem = f"not a number: {bad.strip()!r}" if bad.strip() else "empty field"
                problem += _separator_hint(bad, delimiter)
            else:
                if not all(math.isfinite(value) for value in row):
                    problem = "NaN or infinite value"
        if problem is not None:
            if number == last_line and cut_short:
                problem = f"truncated row: {problem}"
            elif len(fields) != width:
                problem = f"ragged row: {problem}"
            raise ValueError(f"{path}, line {number}: {problem}")
        rows.append(row)
    values = np.array(rows, dtype=np.float64).reshape(len(rows), width)
    line_numbers = np.array([number for number, _ in numbered], dtype=np.int64)
    return NumericTable(names, values, line_numbers)
