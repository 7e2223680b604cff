"""Rendering figures to PNG bytes (matplotlib, Agg, no pyplot state)."""

from __future__ import annotations

import io
from typing import Any

import numpy as np

__all__ = ["figure_png", "new_figure"]


def new_figure(width: float = 4.0, height: float = 3.2) -> Any:
    """A matplotlib Figure not tied to any GUI backend."""
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), dpi=110, layout="constrained")


def figure_png(figure: Any) -> bytes:
    """The figure as PNG bytes."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png")
    return buffer.getvalue()


def image_panel(image: np.ndarray, title: str, *, cmap: str = "gray", ax: Any = None) -> Any:
    """Show a tactile image as the seed's figures do (row 0 at the top)."""
    figure = None
    if ax is None:
        figure = new_figure(3.2, 3.2)
        ax = figure.add_subplot()
    ax.imshow(image, cmap=cmap, interpolation="nearest")
    ax.set_title(title, fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])
    return figure if figure is not None else ax
