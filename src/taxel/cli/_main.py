"""Argument parsing, subcommand dispatch and the one-line error policy."""

from __future__ import annotations

import argparse
import importlib
import re
import sys
from collections.abc import Callable, Sequence
from typing import Any

import taxel

__all__ = ["CommandLineError", "main"]

EXIT_USAGE = 2

# each subcommand module (taxel/cli/_NAME.py) exposes register(commands)
_SUBCOMMANDS = (
    "_active",
    "_calibrate",
    "_demo",
    "_design",
    "_features",
    "_reconstruct",
    "_simulate",
    "_texture",
)


class CommandLineError(Exception):
    """A problem with what the user asked for; printed as one line, exit code 2."""


# a negative number as a flag's value, in any notation: argparse before Python 3.12 takes
# only "-1" and "-0.5" so, and "--x -1e-3" failed with "expected one argument"
_NEGATIVE_NUMBER = re.compile(r"^-(?:(?:\d+\.?\d*|\.\d+)(?:e[-+]?\d+)?|inf|infinity|nan)$", re.I)


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line on stderr and exit code 2."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def error(self, message: str) -> None:  # type: ignore[override]
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        raise SystemExit(EXIT_USAGE)


def _build_parser() -> _Parser:
    parser = _Parser(
        prog="taxel",
        description="Robotic tactile sensing: contact mechanics, sensors, reconstruction, "
        "tactile features and active touch.",
    )
    parser.add_argument("--version", action="version", version=f"taxel {taxel.__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name in _SUBCOMMANDS:
        importlib.import_module(f"taxel.cli.{name}").register(commands)
    return parser


# the work is small arrays in latency-bound loops: BLAS threads only add wake-up stalls
# (measured: a 65k-element dot product averaged 1.8 ms threaded on a busy 2-core machine,
# 66 us on one thread); set before NumPy loads, unless the user chose otherwise
_SINGLE_THREAD = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


# where a command's own sub-command is stored (``taxel active edge-radius``)
_SUBCOMMAND_DESTINATIONS = ("procedure", "texture_command")


def _program(arguments: argparse.Namespace) -> str:
    """The command as typed, as argparse names it in its own errors."""
    words = ["taxel", arguments.command]
    words += [getattr(arguments, d) for d in _SUBCOMMAND_DESTINATIONS if hasattr(arguments, d)]
    return " ".join(words)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line and return its exit code.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name; defaults to ``sys.argv[1:]``.

    Returns
    -------
    int
        0 on success, 2 on bad input.
    """
    import os

    for variable in _SINGLE_THREAD:
        os.environ.setdefault(variable, "1")
    parser = _build_parser()
    arguments = parser.parse_args(argv)
    handler: Callable[[argparse.Namespace], int] | None = getattr(arguments, "handler", None)
    if handler is None:  # no command: a usage error, as argparse treats a missing argument
        sys.stderr.write("taxel: error: a COMMAND is required (taxel --help lists them)\n")
        return EXIT_USAGE
    try:
        return handler(arguments)
    except BrokenPipeError:  # the reader closed the pipe (| head): stop quietly
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except (CommandLineError, ValueError, TypeError, OSError) as error:
        message = str(error).splitlines()[0] if str(error) else type(error).__name__
        sys.stderr.write(f"{_program(arguments)}: error: {message}\n")
        return EXIT_USAGE
    except MemoryError as error:  # (a fine load grid on a small machine)
        why = str(error).splitlines()[0] if str(error) else "MemoryError"
        finer = "--oversampling or " if hasattr(arguments, "oversampling") else ""
        sys.stderr.write(
            f"{_program(arguments)}: error: not enough memory ({why}); a smaller {finer}"
            "input needs less\n"
        )
        return EXIT_USAGE
    except KeyboardInterrupt:
        sys.stderr.write("taxel: interrupted\n")
        return 130
