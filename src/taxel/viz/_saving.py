"""Saving a figure as a file the way every figure of `taxel.viz` does (internal)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

__all__ = ["save_figure"]


def save_figure(figure: Any, path: Path, *, dpi: int = 110) -> None:
    """Write `figure` to `path` in the format its suffix names (PNG for an unknown suffix).

    It is written beside `path` and renamed once complete (`taxel.io.write_files`; the
    temporary file's name has no suffix to tell the format): a failed write keeps an old
    file.
    """
    from taxel.io import write_files

    kind = path.suffix[1:].lower()
    kind = kind if kind in figure.canvas.get_supported_filetypes() else "png"
    write_files([(path, lambda temporary: figure.savefig(temporary, dpi=dpi, format=kind))])
