"""Matplotlib figures of taxel results (imported only when used: ``import taxel`` stays light).

Figures
-------
plot_features: a tactile image with its edges, the fitted line or circle, holes and slots
(as the seed's figures 3B-5B).
plot_reconstruction: the naive against the regularized inverse, with the L-curve and GCV
curve of the parameter choice.
plot_slip: a slip detection: the pattern's displacement, the statistics against their
thresholds, the events and the truth.
"""

from taxel.viz._features import plot_features
from taxel.viz._reconstruction import plot_reconstruction
from taxel.viz._slip import plot_slip

__all__ = ["plot_features", "plot_reconstruction", "plot_slip"]
