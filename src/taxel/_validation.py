"""Checks made once at the public boundary, with messages that name the parameter.

Every public function of `taxel` validates its inputs with these helpers, so that bad
input raises a `ValueError` or `TypeError` of the form "`name` must be ..., got value".
The command line turns these into one-line messages and exit code 2.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = [
    "as_finite_array",
    "as_rng",
    "check_choice",
    "check_count",
    "check_finite",
    "check_flag",
    "check_instance",
    "check_integer",
    "check_pair",
    "check_positive",
    "check_progress",
    "check_range",
    "check_shape",
    "is_json_number",
    "is_whole",
    "refuse_complex",
    "shown_apart",
]


def _short(value: Any) -> str:
    """Render a value for an error message, keeping arrays short."""
    if isinstance(value, np.ndarray):
        return f"array of shape {value.shape}"
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def check_finite(name: str, value: Any) -> float:
    """Return `value` as a float, or raise naming `name` when it is not a finite number.

    A bool or a string is refused: ``True`` standing for 1, or text such as "5" read from
    a file and never converted, is almost always a slip.
    """
    if type(value) is float:  # the usual case, first (a 1 kHz loop checks many)
        number = value
    else:
        if isinstance(value, bool | np.bool_ | str | bytes):
            raise TypeError(f"`{name}` must be a real number, got {value!r}")
        if isinstance(value, complex | np.complexfloating) or (
            isinstance(value, np.ndarray) and value.dtype.kind == "c"
        ):
            # float() of a NumPy complex drops its imaginary part with a warning only
            raise TypeError(f"`{name}` must be a real number, got {_short(value)}")
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise TypeError(f"`{name}` must be a real number, got {_short(value)}") from None
    if not math.isfinite(number):
        raise ValueError(f"`{name}` must be finite, got {number}")
    return number


def check_positive(name: str, value: Any, *, allow_zero: bool = False) -> float:
    """Return `value` as a float, or raise when it is not finite and > 0 (>= 0)."""
    number = check_finite(name, value)
    if number < 0 or (number == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"`{name}` must be {bound}, got {number:g}")
    return number


def shown_apart(value: float, *bounds: float, digits: int = 3) -> str:
    """`value` to `digits` significant digits, or as many more as tell it from `bounds`.

    An error that says a value lies beyond a bound must not show it as the bound.

    Examples
    --------
    >>> shown_apart(1.0001, 1.0), shown_apart(1.5, 1.0)
    ('1.0001', '1.5')
    """
    for shown in range(digits, 18):
        text = f"{value:.{shown}g}"
        if all(float(text) != float(bound) for bound in bounds if bound != value):
            return text
    return repr(float(value))


def check_range(
    name: str,
    value: Any,
    low: float,
    high: float,
    *,
    low_inclusive: bool = True,
    high_inclusive: bool = True,
) -> float:
    """Return `value` as a float, or raise when it lies outside the given interval."""
    number = check_finite(name, value)
    above = number >= low if low_inclusive else number > low
    below = number <= high if high_inclusive else number < high
    if not (above and below):
        left = "[" if low_inclusive else "("
        right = "]" if high_inclusive else ")"
        shown = shown_apart(number, low, high, digits=6)  # (as `g` shows it)
        raise ValueError(f"`{name}` must lie in {left}{low:g}, {high:g}{right}, got {shown}")
    return number


def check_choice(name: str, value: Any, choices: tuple[str, ...]) -> str:
    """Return `value` when it is one of `choices`, else raise naming the valid ones."""
    if not isinstance(value, str):
        # an array's `in` would raise NumPy's "truth value ... is ambiguous"
        raise TypeError(f"`{name}` must be one of {', '.join(choices)}; got {_short(value)}")
    if value not in choices:
        raise ValueError(f"`{name}` must be one of {', '.join(choices)}; got {value!r}")
    return str(value)


def refuse_complex(name: str, value: Any) -> None:
    """Raise TypeError naming `name` when `value` is a complex array.

    NumPy casts a complex array to real with a warning only, dropping the imaginary part.
    (A list of complex numbers fails the cast itself.)
    """
    dtype = getattr(value, "dtype", None)
    if dtype is not None and getattr(dtype, "kind", None) == "c":
        raise TypeError(f"`{name}` must be real, got a complex array ({dtype})")


def as_finite_array(name: str, value: Any, *, ndim: int | None = None) -> np.ndarray:
    """Return `value` as a float64 array, or raise when it has NaN/inf or the wrong ndim.

    A complex array is refused (NumPy would drop its imaginary part with a warning only),
    and so are text ("1" would be read as 1.0), a lone bool (True as 1.0) and a masked
    array (its mask would be dropped, its hidden values read): almost always slips. An
    array of booleans is a mask, read as 0 and 1 (a binary tactile image, a load pattern).
    """
    refuse_complex(name, value)
    if isinstance(value, str | bytes | bool | np.bool_):
        raise TypeError(f"`{name}` must be numeric, got {_short(value)}")
    if isinstance(value, np.ma.MaskedArray):  # np.asarray would drop the mask
        raise TypeError(f"`{name}` is a masked array: fill its masked values first")
    kind = getattr(getattr(value, "dtype", None), "kind", None)
    if kind is None and isinstance(value, list | tuple):
        try:
            kind = np.asarray(value).dtype.kind
        except (TypeError, ValueError):
            kind = None
    if kind in ("U", "S"):
        raise TypeError(f"`{name}` must be numeric, got text: {_short(value)}")
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as error:
        if "inhomogeneous" in str(error):  # NumPy's word for lists of unequal lengths
            raise ValueError(
                f"`{name}` must be a regular array: its nested lists differ in length, got "
                f"{_short(value)}"
            ) from None
        raise TypeError(f"`{name}` must be numeric, got {_short(value)}") from None
    if ndim is not None and array.ndim != ndim:
        raise ValueError(f"`{name}` must be {ndim}-D, got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        bad = int(np.size(array) - np.count_nonzero(np.isfinite(array)))
        raise ValueError(f"`{name}` must be finite everywhere, got {bad} NaN or inf value(s)")
    return array


def check_shape(name: str, array: np.ndarray, shape: tuple[int, ...]) -> None:
    """Raise when `array` does not have exactly `shape`."""
    if tuple(array.shape) != tuple(shape):
        raise ValueError(f"`{name}` must have shape {tuple(shape)}, got {tuple(array.shape)}")


def _two(name: str, value: Any, what: str) -> tuple[Any, Any]:
    """The two items of `value`, or raise saying `name` must be `what`."""
    try:
        first, second = value
    except (TypeError, ValueError):
        raise ValueError(f"`{name}` must be {what}, got {_short(value)}") from None
    return first, second


def check_pair(name: str, value: Any) -> tuple[float, float]:
    """Return `value` as a pair of finite floats, or raise naming `name`."""
    first, second = _two(name, value, "an (x, y) pair")
    return check_finite(name, first), check_finite(name, second)


def check_count(name: str, value: Any, *, minimum: int = 1) -> int:
    """Return `value` as an int >= `minimum`; a bool or a fractional number is refused."""
    if isinstance(value, bool | np.bool_):
        raise TypeError(f"`{name}` must be an integer, got {value!r}")
    if isinstance(value, int | np.integer):
        count = int(value)
    else:
        number = check_finite(name, value)
        if not number.is_integer():
            raise ValueError(f"`{name}` must be a whole number, got {number:g}")
        count = int(number)
    if count < minimum:
        raise ValueError(f"`{name}` must be >= {minimum}, got {count}")
    return count


def is_json_number(value: Any) -> bool:
    """True for a number as JSON gives one (int or float), not a bool, a string or a list.

    Examples
    --------
    >>> [is_json_number(v) for v in (3, 2.5, True, "3", [1])]
    [True, True, False, False, False]
    """
    return isinstance(value, int | float) and not isinstance(value, bool)


def is_whole(value: Any) -> bool:
    """True when `value` is a finite real number with no fractional part, not a bool.

    ``int(value) != value`` raises OverflowError for inf and an unnamed ValueError for NaN;
    this only answers, so that the caller's message, naming its parameter, is raised.

    Examples
    --------
    >>> [is_whole(v) for v in (3, 3.0, 3.5, float("inf"), float("nan"), "3", True)]
    [True, True, False, False, False, False, False]
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    return math.isfinite(value) and float(value).is_integer()


def check_integer(name: str, value: Any, low: int = 1, high: int | None = None) -> int:
    """Return `value` as an int in `low`..`high`, or raise a ValueError naming `name`.

    Like `check_count`, but one message for every refusal ("a positive integer" or "an
    integer in low..high"), so a NaN, an infinity, a bool or 2.5 all read the same.
    """
    if high is not None:
        what = f"an integer in {low}..{high}"
    else:
        what = "a positive integer" if low == 1 else f"an integer >= {low}"
    try:
        if isinstance(value, bool | np.bool_):
            raise ValueError
        number = check_count(name, value, minimum=low)
    except (TypeError, ValueError):
        raise ValueError(f"`{name}` must be {what}, got {_short(value)}") from None
    if high is not None and number > high:
        raise ValueError(f"`{name}` must be {what}, got {_short(value)}")
    return number


def check_grid_shape(name: str, value: Any) -> tuple[int, int]:
    """Return (rows, cols) from a pair of whole numbers >= 1, or raise naming `name`."""
    rows, cols = _two(name, value, "a (rows, cols) pair")
    return check_count(name, rows), check_count(name, cols)


def check_broadcast(names: tuple[str, ...], *arrays: np.ndarray) -> None:
    """Raise naming the arrays (one name each) when their shapes do not broadcast together."""
    shapes = [array.shape for array in arrays]
    try:
        np.broadcast_shapes(*shapes)
    except ValueError:
        quoted = [f"`{name}`" for name in names]
        listed = [str(shape) for shape in shapes]
        raise ValueError(
            f"{', '.join(quoted[:-1])} and {quoted[-1]} must have shapes that broadcast "
            f"together, got {', '.join(listed[:-1])} and {listed[-1]}"
        ) from None


def check_flag(name: str, value: Any) -> bool:
    """Return `value` when it is a bool; a truthy string such as "no" is refused."""
    if not isinstance(value, bool | np.bool_):
        raise TypeError(f"`{name}` must be True or False, got {_short(value)}")
    return bool(value)


def check_instance(name: str, value: Any, kind: type) -> None:
    """Raise TypeError naming `name` when `value` is not an instance of `kind`."""
    if not isinstance(value, kind):
        article = "an" if kind.__name__[0] in "AEIOU" else "a"
        raise TypeError(f"`{name}` must be {article} {kind.__name__}, got {_short(value)}")


def check_progress(
    progress: Callable[[int, int], object] | None,
) -> Callable[[int, int], object] | None:
    """`progress` itself when it is None or callable; else a TypeError naming it.

    `progress` is the ``progress(done, total)`` callback of a long computation.
    """
    if progress is not None and not callable(progress):
        raise TypeError(f"`progress` must be a callable (done, total) or None, got {progress!r}")
    return progress


def as_rng(name: str, rng: Any, *, allow_none: bool = True) -> np.random.Generator | None:
    """Return `rng` as a NumPy Generator, or None for None (no noise).

    A Generator is used as it is; an int >= 0 (also a 0-d integer array), a SeedSequence
    or a BitGenerator seeds a new one, as `numpy.random.default_rng` does. Anything else
    (a float, a string, a bool, a negative seed; None when not `allow_none`) is refused.
    """
    if rng is None and allow_none:
        return None
    if isinstance(rng, np.random.Generator):
        return rng
    if isinstance(rng, np.random.SeedSequence | np.random.BitGenerator):
        return np.random.default_rng(rng)
    if isinstance(rng, np.ndarray) and rng.ndim == 0 and rng.dtype.kind in "iu":
        rng = rng.item()
    if isinstance(rng, int | np.integer) and not isinstance(rng, bool | np.bool_):
        if rng < 0:
            raise ValueError(f"`{name}` seed must be >= 0, got {int(rng)}")
        return np.random.default_rng(int(rng))
    kinds = "None, " if allow_none else ""
    raise TypeError(
        f"`{name}` must be {kinds}a numpy.random.Generator, an int seed or a SeedSequence, "
        f"got {rng!r}"
    )
