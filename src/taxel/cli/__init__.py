"""The ``taxel`` command line: one subcommand per module of this package.

Every subcommand validates its arguments; bad input prints one line naming the problem
to stderr and exits with code 2, never a traceback.
"""

from taxel.cli._main import main

__all__ = ["main"]
