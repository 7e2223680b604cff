"""Matplotlib figures of taxel results (imported only when used: ``import taxel`` stays light).

Figures
-------
plot_reconstruction: the naive against the regularized inverse, with the L-curve and GCV
curve of the parameter choice.
"""

from taxel.viz._reconstruction import plot_reconstruction

__all__ = ["plot_reconstruction"]
