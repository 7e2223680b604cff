"""Spatial-frequency spectrum of a tactile image's ripple, by octave bands (internal).

The image is real, so its spectrum is conjugate-symmetric: OpenCV's real DFT gives each
pair of conjugate bins once, packed as "CCS" (the real and imaginary parts of a bin in
neighbouring entries), in two thirds of the time of the full complex spectrum. The band
sums, the power-weighted mean frequency and the strongest bin are read from that packed
half directly, with indices worked out once per image shape. With an even number of
columns, on an image over 32 x 32 taxels, each bin's two squared parts are first added
where they lie (`_pair_powers`), so that one gather reads the bins' powers, at two thirds
of the cost of one gather per part; on a smaller image, the pairing's several operations
cost more than the second gather saves (16 x 16: 2.5 times as much).
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import NamedTuple

import cv2
import numpy as np

from taxel.features._fitting import dot
from taxel.features._window import WHOLE_IMAGE

__all__ = ["OCTAVES", "RippleSpectrum", "ripple_spectrum"]

# Octave bands of spatial frequency, from the Nyquist limit down: [f/2, f], [f/4, f/2], ...
OCTAVES = 4


class RippleSpectrum(NamedTuple):
    """Strongest frequency, power-weighted mean frequency and octave band fractions."""

    strongest_per_m: float
    centroid_per_m: float
    band_energy: tuple[float, ...]


class _Layout(NamedTuple):
    window: np.ndarray  # Hann window, float32, the image's shape
    first: np.ndarray  # per bin: flat index of its real part in the packed spectrum
    second: np.ndarray  # per bin: of its imaginary part (0, the mean, zeroed, if it has none)
    paired: np.ndarray | None  # per bin: its power's index in `_pair_powers` (None: odd cols)
    lone: np.ndarray  # flat indices of the entries that are real bins alone (`_pair_powers`)
    share: np.ndarray  # per bin: 0.5 if it is its own conjugate (but the mean), else 1; float64
    frequency: np.ndarray  # per bin [cycles/m], float32
    shared_frequency: np.ndarray  # `frequency` times `share`, float32
    starts: np.ndarray  # where each octave band begins in the bins' order
    empty: np.ndarray | None  # bands holding no bin (tiny images), or None


def _packed_bins(rows: int, cols: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Frequency indices (ky, kx) and part (0 real, 1 imaginary) of each CCS entry.

    OpenCV packs the spectrum of a real image so: each row's transform is stored as
    Re0, Re1, Im1, Re2, Im2, ... (ending Re(N/2) when N is even); the columns holding the
    purely real Re0 and Re(N/2) are transformed again the same way down the rows, and
    every (Re k, Im k) pair of columns is transformed as one complex column.
    """
    r = np.arange(rows)[:, None] + np.zeros((1, cols), np.intp)
    c = np.zeros((rows, 1), np.intp) + np.arange(cols)[None, :]
    real_column = (c == 0) | ((cols % 2 == 0) & (c == cols - 1))
    alone = (r == 0) | ((rows % 2 == 0) & (r == rows - 1))  # Re0 and Re(M/2) down a column
    ky = np.where(real_column, np.where(alone, np.where(r == 0, 0, rows // 2), (r + 1) // 2), r)
    kx = np.where(real_column, np.where(c == 0, 0, cols // 2), (c + 1) // 2)
    part = np.where(real_column, np.where(alone, 0, (r + 1) % 2), (c + 1) % 2)
    return ky.ravel(), kx.ravel(), part.ravel()


def _lone_entries(rows: int, cols: int) -> np.ndarray:
    """Flat indices of the packed entries that hold a real bin alone (even `cols`).

    Re0 and Re(N/2) of the first row, and of the last row when `rows` is even.
    """
    entries = [0, cols - 1]
    if rows % 2 == 0:
        entries += [(rows - 1) * cols, rows * cols - 1]
    return np.array(entries, np.intp)


def _pair_positions(rows: int, cols: int, first: np.ndarray) -> np.ndarray | None:
    """Per bin (given its real part's flat index), where `_pair_powers` puts its power.

    None with an odd number of columns (see `_pair_powers`).
    """
    if cols % 2:
        return None
    half = rows * cols // 2 - 1
    end = rows - 1 if rows % 2 == 0 else rows  # rows 1 .. end - 1 of a real column pair up
    row, col = np.divmod(first, cols)
    position = np.empty(first.size, np.intp)
    inner = (col % 2 == 1) & (col < cols - 1)
    position[inner] = (first[inner] - 1) // 2
    side = ((col == 0) | (col == cols - 1)) & (row % 2 == 1) & (row < end)
    position[side] = half + row[side] - 1 + (col[side] == cols - 1)
    for index, entry in enumerate(_lone_entries(rows, cols).tolist()):
        position[first == entry] = half + (end - 1) // 2 * 2 + index
    return position


def _pair_powers(squares: np.ndarray, shape: tuple[int, int], lone: np.ndarray) -> np.ndarray:
    """The bins' powers (their squared parts added), at the places `_pair_positions` gives.

    `squares`: the packed spectrum's entries squared, flat, of an image with an even number
    of columns. Each row of the packed spectrum holds (Re, Im) pairs in columns (1, 2),
    (3, 4), ...; the rows keep that parity in the flat array, so every such pair is one
    entry of ``squares[1::2] + squares[2::2]`` (the sums across one row's last column and
    the next row's first are never read). The two real columns hold pairs down rows
    (1, 2), (3, 4), ...: their sums follow, in rows of two, then the lone real entries.
    """
    rows, cols = shape
    half = rows * cols // 2 - 1
    end = rows - 1 if rows % 2 == 0 else rows
    pairs = (end - 1) // 2
    out = np.empty(half + 2 * pairs + lone.size, squares.dtype)
    np.add(squares[1:-1:2], squares[2::2], out=out[:half])
    sides = squares.reshape(rows, cols)[:, :: cols - 1]  # the real columns 0 and cols - 1
    np.add(sides[1:end:2], sides[2:end:2], out=out[half : half + 2 * pairs].reshape(pairs, 2))
    squares.take(lone, out=out[half + 2 * pairs :])
    return out


# a sensor loop reads one shape and pitch; a layout holds ~30 bytes per taxel (65 MB at
# 1500 x 1500): the last 4 are kept
@lru_cache(maxsize=4)
def _layout(shape: tuple[int, int], pitch: tuple[float, float]) -> _Layout:
    """Window, bins and octave bands of an image shape and pitch (cached)."""
    rows, cols = shape
    ky, kx, part = _packed_bins(rows, cols)
    key = ky * cols + kx
    bins = np.unique(key)
    first = np.empty(bins.size, np.intp)
    second = np.zeros(bins.size, np.intp)
    position = np.searchsorted(bins, key)
    entries = np.arange(key.size)
    first[position[part == 0]] = entries[part == 0]
    second[position[part == 1]] = entries[part == 1]
    bin_ky, bin_kx = bins // cols, bins % cols
    fy = np.fft.fftfreq(rows, pitch[0])[bin_ky]
    fx = np.fft.fftfreq(cols, pitch[1])[bin_kx]
    frequency = np.sqrt(fy**2 + fx**2)
    nyquist = 0.5 / math.sqrt(pitch[0] * pitch[1])
    band = np.full(bins.size, OCTAVES, np.intp)
    for octave in range(OCTAVES - 1, -1, -1):
        band[frequency > nyquist / 2 ** (octave + 1)] = octave
    band[bins == 0] = OCTAVES  # the mean
    # bins in band order; within a band, in the raster order of the full spectrum
    raster = np.minimum(bins, (-bin_ky % rows) * cols + (-bin_kx % cols))
    order = np.lexsort((raster, band))
    starts = np.searchsorted(band[order], np.arange(OCTAVES + 1))
    empty = starts[1:] == starts[:-1]
    second = second[order]
    window = np.outer(np.hanning(rows), np.hanning(cols)).astype(np.float32)
    share = np.where((second == 0) & (bins[order] != 0), 0.5, 1.0)
    frequency = frequency[order].astype(np.float32)
    first = first[order]
    layout = _Layout(
        window,
        first,
        second,
        _pair_positions(rows, cols, first),
        _lone_entries(rows, cols),
        share,
        frequency,
        (frequency * share).astype(np.float32),  # (exact: halving a float32)
        starts,
        empty if empty.any() else None,
    )
    # the cached values are read-only, but for the index arrays: `take` and `reduceat` copy
    # an index array that is not writeable before using it, which costs as much as the
    # gather itself
    for array in layout:
        if isinstance(array, np.ndarray) and array.dtype.kind == "f":
            array.flags.writeable = False
    return layout


def ripple_spectrum(image: np.ndarray, pitch: tuple[float, float]) -> RippleSpectrum | None:
    """Spectrum measures of an image's ripple: mean removed, Hann-windowed (internal).

    Returns None for an image without ripple. Power is summed over the whole spectrum:
    each packed bin stands for itself and its conjugate, except the few bins that are
    their own conjugate (the mean and the Nyquist rows and columns' corners), which count
    half.
    """
    layout = _layout(image.shape, pitch)
    ripple = image - np.float32(cv2.mean(image)[0])
    np.multiply(ripple, layout.window, out=ripple)
    packed = cv2.dft(ripple)
    cv2.multiply(packed, packed, dst=packed)  # (overflows to inf without a warning)
    spectrum = _band_powers(packed.ravel(), layout)
    if not (math.isfinite(spectrum[2]) and math.isfinite(spectrum[3])):
        # a ripple of more than ~1e15 / (rows x cols) image units overflows float32's
        # squares or their sums: the measures are ratios, so the ripple is scaled to at
        # most 1 and transformed in float64 instead (rare)
        ripple64 = image - image.mean(dtype=np.float64)
        ripple64 /= np.abs(ripple64).max()
        ripple64 *= layout.window
        packed64 = cv2.dft(ripple64)
        spectrum = _band_powers(np.square(packed64, out=packed64).ravel(), layout)
    sums, total, weighted, strongest = spectrum
    if total <= 0:
        return None
    if layout.empty is not None:
        sums[:OCTAVES][layout.empty] = 0.0  # an empty band holds nothing
    bands = sums[:OCTAVES] / total
    return RippleSpectrum(strongest, weighted / total, tuple(bands.tolist()))


def _band_powers(squares: np.ndarray, layout: _Layout) -> tuple[np.ndarray, float, float, float]:
    """Power per band, the total, the frequency-weighted total, and the strongest frequency.

    `squares`: the packed spectrum's entries squared (its first entry is overwritten). A
    bin's power stands for it and its conjugate; a self-conjugate bin's counts half. Band
    sums are float64. Sums that overflow are inf (no warning).
    """
    squares[0] = 0.0  # the mean; also the missing imaginary part of the real bins
    if layout.paired is None or squares.size <= WHOLE_IMAGE:  # (see the module notes)
        power = squares.take(layout.first)
        cv2.add(power, squares.take(layout.second), dst=power)
    else:  # (the same sums, each of the same two squares)
        power = _pair_powers(squares, layout.window.shape, layout.lone).take(layout.paired)
    strongest = float(layout.frequency[cv2.minMaxLoc(power.reshape(1, -1))[3][0]])
    # the self-conjugate bins' halves, exact (in float64, as one product by 1 or 0.5; and
    # for the frequency-weighted total, on the frequencies: the products are the same)
    halved = np.multiply(power, layout.share, dtype=np.float64)
    sums = np.add.reduceat(halved, layout.starts)
    return sums, float(np.add.reduce(sums)), dot(power, layout.shared_frequency), strongest
