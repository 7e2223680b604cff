"""The camera of an optical tactile sensor: digitised frames with noise, and scratched glass.

Used by the FTIR sensor (Figure 25.9); any camera-read transducer can use it.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel._validation import (
    as_finite_array,
    check_count,
    check_grid_shape,
    check_integer,
    check_positive,
    check_range,
)
from taxel.transducers._common import as_generator

__all__ = ["camera_image", "glass_scratches"]


def glass_scratches(
    shape: tuple[int, int],
    *,
    rng: Any,
    count: int = 6,
    strength: float = 0.25,
    width: float = 0.8,
) -> np.ndarray:
    """A fixed pattern of scratches on the glass plate, as extra light fraction per pixel [-].

    Parameters
    ----------
    shape : tuple of int
        (rows, cols) of the camera image.
    rng : numpy.random.Generator or int
        Source of the pattern; the same seed gives the same glass.
    count : int, default 6
        Number of straight scratches.
    strength : float, default 0.25
        Peak extra brightness of a scratch, as a fraction of full contact [-], in [0, 1].
    width : float, default 0.8
        Half-width of a scratch's triangular profile [pixel], > 0.

    Returns
    -------
    numpy.ndarray, shape `shape`
        Extra light fraction in [0, strength]: scratches scatter guided light out of the
        glass just as contact does, so they read as bright streaks.

    Examples
    --------
    >>> a = glass_scratches((32, 32), rng=5)
    >>> b = glass_scratches((32, 32), rng=5)
    >>> bool(np.array_equal(a, b)), bool(a.max() <= 0.25), bool((a > 0).mean() < 0.3)
    (True, True, True)
    """
    rows, cols = check_grid_shape("shape", shape)
    generator = as_generator("rng", rng)
    count = check_count("count", count, minimum=0)
    strength = check_range("strength", strength, 0.0, 1.0)
    width = check_positive("width", width)
    y, x = np.mgrid[0:rows, 0:cols].astype(float)
    pattern = np.zeros((rows, cols))
    size = max(rows, cols)
    for _ in range(int(count)):
        centre = generator.uniform((0, 0), (cols, rows))
        angle = generator.uniform(0.0, np.pi)
        half = 0.5 * generator.uniform(0.1, 0.6) * size
        depth = generator.uniform(0.5, 1.0)
        direction = np.array([np.cos(angle), np.sin(angle)])
        along = np.clip(
            (x - centre[0]) * direction[0] + (y - centre[1]) * direction[1], -half, half
        )
        distance = np.hypot(
            x - centre[0] - along * direction[0], y - centre[1] - along * direction[1]
        )
        pattern = np.maximum(pattern, depth * np.clip(1.0 - distance / width, 0.0, None))
    return strength * pattern


def camera_image(
    light_fraction: Any,
    *,
    dark_level: float = 24.0,
    bright_level: float = 120.0,
    conversion_gain: float = 0.025,
    read_noise: float = 10.0,
    bits: int = 8,
    rng: Any = None,
) -> np.ndarray:
    r"""Digitised camera frame of a light pattern, with shot and read noise [DN].

    Parameters
    ----------
    light_fraction : array_like
        Escaping light per pixel, 0 for no contact and 1 for full contact [-], >= 0.
    dark_level, bright_level : float, default 24, 120
        Mean pixel value at no contact and at full contact [DN] (the seed's 24 to 120).
    conversion_gain : float, default 0.025
        Digital numbers per photo-electron [DN/e-], > 0 (here 120 DN is 4800 e-).
    read_noise : float, default 10.0
        Read noise [e- rms], >= 0.
    bits : int, default 8
        ADC resolution, 1 to 16.
    rng : numpy.random.Generator or int, optional
        Noise source; None gives the noise-free, rounded image.

    Returns
    -------
    numpy.ndarray of uint8 (bits <= 8) or uint16
        The frame, clipped to [0, 2^bits - 1].

    Notes
    -----
    Mean signal :math:`\mu = D + (B - D) f` [DN]; with noise, the photo-electrons are
    Poisson with mean :math:`\mu / g`, read noise adds a Gaussian of ``read_noise``
    electrons, and the sum times g is rounded and clipped.

    Examples
    --------
    >>> camera_image([0.0, 0.5, 1.0]).tolist()
    [24, 72, 120]
    >>> frame = camera_image(np.full(10000, 0.5), rng=1)
    >>> round(float(frame.mean())), round(float(frame.std()), 1)  # shot noise ~ 1.35 DN
    (72, 1.4)
    """
    fraction = as_finite_array("light_fraction", light_fraction)
    if np.any(fraction < 0):
        raise ValueError(f"`light_fraction` must be >= 0, got {float(np.min(fraction)):g}")
    dark_level = check_positive("dark_level", dark_level, allow_zero=True)
    bright_level = check_positive("bright_level", bright_level)
    if bright_level <= dark_level:
        raise ValueError(
            f"`bright_level` must exceed dark_level = {dark_level:g}, got {bright_level:g}"
        )
    conversion_gain = check_positive("conversion_gain", conversion_gain)
    read_noise = check_positive("read_noise", read_noise, allow_zero=True)
    bits = check_integer("bits", bits, 1, 16)
    mean = dark_level + (bright_level - dark_level) * fraction
    if rng is None:
        value = mean
    else:
        generator = as_generator("rng", rng)
        # np.asarray: a 0-d mean draws a plain int
        electrons = np.asarray(generator.poisson(mean / conversion_gain), dtype=float)
        electrons += generator.normal(0.0, 1.0, size=mean.shape) * read_noise
        value = electrons * conversion_gain
    top = 2 ** int(bits) - 1
    dtype = np.uint8 if bits <= 8 else np.uint16
    return np.clip(np.rint(value), 0, top).astype(dtype)
