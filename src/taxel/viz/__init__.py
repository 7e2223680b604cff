"""Matplotlib figures of taxel results (imported only when used: ``import taxel`` stays light).

Figures
-------
plot_features: a tactile image with its edges, the fitted line or circle, holes and slots
(as the seed's figures 3B-5B).
"""

from taxel.viz._features import plot_features

__all__ = ["plot_features"]
