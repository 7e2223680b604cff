"""Run the command line as ``python -m taxel``."""

import sys

from taxel.cli import main

sys.exit(main())
