r"""Readings relative to the normal load, so that texture spectra do not depend on the load.

A change of the normal load, whether the force setting of a recording or a fluctuation of
the force loop or of the rig while sliding, scales the pressure over the whole contact, and
so, to first order, multiplies every taxel's reading by the same factor. Texture passing under
the finger instead moves pressure from one taxel to another. Dividing the readings at each
step by their mean over the taxels (the load) keeps the second and cancels the first: the
*load shares* of the taxels do not change when the load is scaled, at any instant.

The cancellation is only to first order: a firmer press also widens the contact, so taxels
near its edge gain more than in proportion. That part of a share follows the load
fluctuation linearly, with a gain of its own for each taxel, and `remove_load_coherent`
removes it.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import signal

from taxel._validation import as_finite_array

__all__ = ["load_shares", "remove_load_coherent"]

_QUIET_LOAD = 1e-12  # relative load variance below which there is nothing to remove


def load_shares(readings: Any) -> np.ndarray:
    r"""Each taxel's reading divided by the mean reading over the taxels at the same step.

    Parameters
    ----------
    readings : array_like
        (n_steps, n_taxels) readings with n_taxels >= 2, whose mean over the taxels is
        > 0 at every step (a contact).

    Returns
    -------
    numpy.ndarray
        (n_steps, n_taxels) load shares q [-]; they average to 1 over the taxels at each
        step.

    Raises
    ------
    ValueError
        When `readings` is not 2-D with at least two taxels (one taxel's share is always
        1), or its mean over the taxels is not > 0 at some step.

    Notes
    -----
    With the load L(t) = mean_i r_i(t), the share is q_i(t) = r_i(t) / L(t). Readings that
    scale with the load, r_i(t) = a(t) g_i(t), give q_i = g_i / mean_i g_i whatever the
    factor a(t): a stronger press and an oscillating force leave the shares unchanged.

    Examples
    --------
    >>> import numpy as np
    >>> pattern = np.array([[1.0, 3.0], [2.0, 2.0]])
    >>> load_shares(pattern).tolist()
    [[0.5, 1.5], [1.0, 1.0]]
    >>> np.array_equal(load_shares(7.0 * pattern), load_shares(pattern))
    True
    """
    readings = as_finite_array("readings", readings, ndim=2)
    if readings.shape[1] < 2:
        raise ValueError(
            f"load shares need at least two taxels, got `readings` of shape {readings.shape}"
        )
    load = readings.mean(axis=1)
    if np.any(load <= 0):
        step = int(np.argmax(load <= 0))
        raise ValueError(
            "load shares need a mean reading over the taxels > 0 at every step, got "
            f"{load[step]:g} at step {step}"
        )
    return readings / load[:, None]


def remove_load_coherent(signals: Any, load: Any) -> np.ndarray:
    r"""Remove from each signal the part that follows the relative load fluctuation.

    Parameters
    ----------
    signals : array_like
        (n_steps, n_channels) signals, e.g. the `load_shares` or the readings of each taxel.
    load : array_like
        (n_steps,) the load, e.g. the mean reading over the taxels at each step; its mean
        must be > 0.

    Returns
    -------
    numpy.ndarray
        (n_steps, n_channels) the signals less beta_i times the relative load.

    Raises
    ------
    ValueError
        When the shapes disagree or the mean load is not > 0.

    Notes
    -----
    With the relative load l(t) = L(t) / mean(L), each channel's gain is the least-squares
    slope of the signal on l after a straight line is removed from both (the spectra
    ignore offsets and drift),

    .. math:: \beta_i = \frac{\sum_t \tilde y_i(t) \tilde l(t)}{\sum_t \tilde l(t)^2},
              \qquad y_i \leftarrow y_i - \beta_i l,

    one gain per channel over the whole record. A load that does not vary beyond a straight
    line leaves the signals unchanged. Texture that changes the load and the shares
    together loses its load-coherent part too: this trades some texture for robustness to
    the load, which is why it is an option.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 50)
    >>> load = 100.0 + 10.0 * np.sin(2 * np.pi * 3 * t)
    >>> texture = np.cos(2 * np.pi * 7 * t)
    >>> mixed = np.stack([texture + 0.02 * load, texture - 0.01 * load], axis=1)
    >>> cleaned = remove_load_coherent(mixed, load)
    >>> bool(np.allclose(cleaned - cleaned.mean(axis=0), texture[:, None] - texture.mean(),
    ...      atol=0.05))
    True
    """
    signals = as_finite_array("signals", signals, ndim=2)
    load = as_finite_array("load", load, ndim=1)
    if load.shape[0] != signals.shape[0]:
        raise ValueError(f"`load` has {load.shape[0]} steps but `signals` has {signals.shape[0]}")
    if load.mean() <= 0:
        raise ValueError(f"the mean of `load` must be > 0, got {load.mean():g}")
    relative = load / load.mean()
    fluctuation = signal.detrend(relative)
    variance = float(fluctuation @ fluctuation)
    if variance <= _QUIET_LOAD * load.shape[0]:
        return signals.copy()
    gains = signal.detrend(signals, axis=0).T @ fluctuation / variance
    return signals - np.outer(relative, gains)
