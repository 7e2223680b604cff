"""Texture of a tactile image: the seed's maxima measures and a spectral, scale-aware one."""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any, Unpack

import cv2
import numpy as np

from taxel._validation import check_range
from taxel.features._blur import gaussian_blur
from taxel.features._fitting import mean32
from taxel.features._image import Preparation, Prepared, prepare
from taxel.features._noise import noise_from_residual
from taxel.features._record import record
from taxel.features._spectrum import OCTAVES, ripple_spectrum
from taxel.features._window import WHOLE_IMAGE, contact_area, contact_box, contact_window

__all__ = ["TEXTURE_SIGMA", "Texture", "high_points", "texture_core", "texture_measures"]

# The seed smooths before counting maxima, against camera noise and glass scratches; 2
# taxels keeps bumps a few taxels apart (the rasp's teeth) and merges single-taxel specks.
TEXTURE_SIGMA = 2.0
# A high point of the object is a local maximum inside the contact that stands above every
# point of the circle of radius 2 sigma around it by 4 noise sigmas (of the texture-smoothed
# image, the noise measured inside the contact, where a camera's shot noise is larger than
# on the background): noise alone gives none, and neither do the points along a ridge (an
# edge or a rim pressed in), which the circle crosses twice at the ridge's own height. And a
# high point is a peak, curved down in every direction: the cover spreads an asperity's load
# evenly around it, so the weaker principal curvature is at least 1/4 of the stronger one;
# a ridge has almost none along its crest (what bumps a ridge's crest is noise).
_MAXIMUM_SIGMAS = 4.0
_ISOTROPY = 0.25
_RING_RADIUS = 2.0  # [sigma]
_RING_POINTS = 32
_SQUARES: dict[int, np.ndarray] = {}
_AROUND = np.array([[1, 1, 1], [1, 0, 1], [1, 1, 1]], np.uint8)  # the 8 neighbours


@record
class Texture:
    """Texture measures of a tactile image.

    Attributes
    ----------
    maxima_count : int
        High points of the contact: local maxima of the smoothed image inside the contact
        that rise clearly above their surroundings (the seed's first measure).
    mean_height : float
        Their mean height above the baseline [image units] (the seed's second measure);
        NaN (JSON null) without high points.
    maxima_density_per_m2 : float
        High points per unit contact area [1/m^2]; unlike the count, independent of the
        image size.
    dominant_wavelength_m : float or None
        Wavelength of the strongest spatial frequency of the image's ripple [m]. Over the
        whole image, as the seed measures texture: on most images it is the scale of the
        contact's own shape or of the array (a smooth face, a band, a texture's envelope),
        and a texture's own scale shows in `band_energy` and `spectral_centroid_per_m`.
    spectral_centroid_per_m : float or None
        Power-weighted mean spatial frequency [cycles/m].
    band_energy : tuple of float
        Fraction of the ripple's power in octave bands of spatial frequency, finest first:
        [f_N/2, f_N], [f_N/4, f_N/2], ... with f_N = 1 / (2 pitch) the Nyquist frequency.
        Fractions of power, so they do not depend on image size or gain.
    roughness : float
        Standard deviation of the smoothed image over contact, divided by its mean above
        the baseline [-]: 0 for a uniform face.
    """

    maxima_count: int
    mean_height: float
    maxima_density_per_m2: float
    dominant_wavelength_m: float | None
    spectral_centroid_per_m: float | None
    band_energy: tuple[float, ...]
    roughness: float


@lru_cache(maxsize=64)
def _padded_offsets(
    radius: float, step: int, width: int
) -> tuple[int, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Padding, flat offsets (ring, curvatures' neighbours, square), flat place (cached).

    The ring at `radius` has `_RING_POINTS` points, given after the point itself (offset
    0); the eight neighbours lie `step` away (E, W, S, N, SE, SW, NE, NW); the square is
    the (2 ceil(radius) + 1)^2 taxels around the point. Offsets are into an image `width`
    columns wide padded by the returned number of taxels on every side (at least
    ceil(radius)), flattened, from the place of its first taxel (the padding's offset is in
    them); each is a read-only (1, n) row. The place is the read-only column (1, row
    length): points (x, y) times it are their flat indices less the padding's (see
    `_ring_test`).
    """
    angles = np.arange(_RING_POINTS) * (2 * math.pi / _RING_POINTS)
    ring_rows = np.rint(radius * np.sin(angles)).astype(np.intp)
    ring_cols = np.rint(radius * np.cos(angles)).astype(np.intp)
    near_rows = np.array([0, 0, step, -step, step, step, -step, -step], np.intp)
    near_cols = np.array([step, -step, 0, 0, step, -step, step, -step], np.intp)
    half = math.ceil(radius)
    pad = int(max(np.abs(ring_rows).max(), np.abs(ring_cols).max(), step, half))
    stride = width + 2 * pad
    first = pad * (stride + 1)  # the image's first taxel in the padded one
    ring = np.concatenate(([0], ring_rows * stride + ring_cols))[None, :] + first
    near = (near_rows * stride + near_cols)[None, :] + first
    across = np.arange(-half, half + 1)
    square = (across[:, None] * stride + across[None, :]).reshape(1, -1) + first
    place = np.array([[1], [stride]], np.intp)
    for offsets in (ring, near, square, place):
        offsets.flags.writeable = False
    return pad, ring, near, square, place


def _square(size: int) -> np.ndarray:
    """A size x size square structuring element (cached)."""
    kernel = _SQUARES.get(size)
    if kernel is None:
        kernel = _SQUARES[size] = np.ones((size, size), np.uint8)
    return kernel


def _first_of_each(points: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """The first of the points in each labelled plateau, in the order of the labels.

    What ``points[np.unique(labels at points, return_index=True)[1]]`` gives, without
    np.unique's sorting machinery (the points are few).
    """
    first: dict[int, int] = {}
    for index, label in enumerate(labels[points[:, 1], points[:, 0]].tolist()):
        first.setdefault(label, index)
    return points[[first[label] for label in sorted(first)]]


def _contact_residual(prepared: Prepared) -> np.ndarray:
    """The noise residual of `prepare` at the contact's taxels, in raster order.

    Read in the contact's window: row i of the residual is row 1 + i * step of the image,
    and column j is column 1 + j.
    """
    step, residual, mask = prepared.residual_step, prepared.residual, prepared.mask
    assert residual is not None
    if mask.size <= WHOLE_IMAGE:
        return residual[mask[1:-1:step, 1:-1].view(bool)]
    rows, cols = contact_window(prepared)
    first, last = max(-((1 - rows.start) // step), 0), -((1 - rows.stop) // step)
    left, right = max(cols.start - 1, 0), cols.stop - 1
    residual = residual[first:last, left:right]
    on_rows = mask[1 + first * step :: step, 1 + left : 1 + right]
    return residual[on_rows[: residual.shape[0], : residual.shape[1]].view(bool)]


def _margin(noise: float, sigma: float, contrast: float) -> np.float32:
    """How far a high point rises above its surroundings, for taxel noise `noise`."""
    # white noise of sigma n leaves n / (2 sqrt(pi) sigma) after a Gaussian of sigma
    smoothed = noise / (2.0 * math.sqrt(math.pi) * sigma)
    return np.float32(max(_MAXIMUM_SIGMAS * smoothed, 1e-9 * contrast, 1e-30))


def _standing(heights: np.ndarray, lowest: np.ndarray, margin: np.float32) -> np.ndarray:
    """Which maxima (their `heights`) rise `margin` above `lowest`, the least of their squares."""
    return heights > lowest + margin


def _peaks(points: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    """An image (uint8) of `shape`: 1 at the points (x, y), 0 elsewhere."""
    peaks = np.zeros(shape, np.uint8)
    peaks[points[:, 1], points[:, 0]] = 1
    return peaks


def _ring_test(
    padded: np.ndarray,
    place: np.ndarray,
    points: np.ndarray,
    ring_offsets: np.ndarray,
    margin: np.float32,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Which points stand `margin` above every point of their ring.

    `padded`: the smoothed image padded on every side, flattened, its rows ``place[1, 0]``
    long; `place` and `ring_offsets` (the point, then its ring): see `_padded_offsets`.
    Returns the points' flat indices less the padding's offset (as a column), their
    heights, and the test's answers.
    """
    # y stride + x, in one product (whole numbers: exact in any order); the point and its
    # ring in one gather
    centres = points @ place
    values = padded.take(centres + ring_offsets)
    heights = values[:, 0]
    return centres, heights, heights > np.maximum.reduce(values[:, 1:], axis=1) + margin


def _contact_noise(prepared: Prepared) -> float:
    """Noise sigma of the taxels in the contact, from every 4th of their residuals (0 if none)."""
    if prepared.residual is None:
        return 0.0
    residual = _contact_residual(prepared)[::4]
    return noise_from_residual(residual, quantum=prepared.residual_quantum)


# From this many high points on, their places (x, y) are kept in ``prepared.memo``
_KEEP_PLACES = 3


def high_points(prepared: Prepared, *, sigma: float = TEXTURE_SIGMA) -> tuple[int, float]:
    """Number and mean height above the baseline of the contact's high points (internal).

    (Analysing the smoothed image on every other taxel would be 4 times cheaper, but a
    peak's height is then read up to a taxel off its top, which loses the weakest teeth of
    a rasp pressed hard.)
    """
    if not prepared.present:
        return 0, 0.0
    # maxima are sought in the contact only: work on its bounding box, grown by the reach of
    # the smoothing and of the ring, so that the crop's edges do not change the result
    reach = 2 * math.ceil(3 * sigma) + 1
    radius = _RING_RADIUS * sigma
    grow = reach // 2 + math.ceil(radius) + 2
    left, top, width, height = contact_box(prepared)
    rows, cols = prepared.image.shape
    r0, r1 = max(top - grow, 0), min(top + height + grow, rows)
    c0, c1 = max(left - grow, 0), min(left + width + grow, cols)
    image, mask = prepared.image[r0:r1, c0:c1], prepared.mask[r0:r1, c0:c1]
    smooth = gaussian_blur(image, sigma)
    # the largest of the 8 neighbours: a maximum is >= it, and equal to it beside another
    around = cv2.dilate(smooth, _AROUND)
    maxima = cv2.findNonZero((smooth >= around).view(np.uint8) & mask)
    if maxima is None:
        return 0, 0.0
    maxima = maxima.reshape(-1, 2)  # the contact's local maxima (x, y), in raster order
    # the margin is set by the noise inside the contact where it exceeds the image's (a
    # camera's shot noise): the image's alone gives the least margin, and when no maximum
    # stands out by even that one, above its ring and its square, none is a high point and
    # the contact's noise (a median over its taxels) is not needed. (Every maximum is
    # tested, before a plateau is reduced to one taxel: a high point is one of them.) On a
    # small array the median costs less than the second test it may need: taken first.
    contact_noise = None
    if prepared.mask.size <= WHOLE_IMAGE:
        contact_noise = _contact_noise(prepared)
    noise = prepared.raw_noise if contact_noise is None else max(contact_noise, prepared.raw_noise)
    margin = _margin(noise, sigma, prepared.contrast)
    # the ring and the neighbours are read in a copy padded by replication, as clipping
    # each index to the image would, with one flat index per value
    pad, ring_offsets, near_offsets, square_offsets, place = _padded_offsets(
        radius, max(int(round(sigma)), 1), smooth.shape[1]
    )
    padded = cv2.copyMakeBorder(smooth, pad, pad, pad, pad, cv2.BORDER_REPLICATE).ravel()
    every = _ring_test(padded, place, maxima, ring_offsets, margin)
    if not np.count_nonzero(every[2]):
        return 0, 0.0  # (no maximum above its ring, as on a ridge: no erosion needed)
    # the least value of each maximum's square: the erosion's there. With few maxima, the
    # least of their squares read in the padded copy, which repeats the border's taxels
    # (already in each square that reaches past the border: the same least value)
    if maxima.shape[0] * square_offsets.size <= smooth.size:
        lowest = np.minimum.reduce(padded.take(every[0] + square_offsets), axis=1)
    else:
        lowest = cv2.erode(smooth, _square(2 * math.ceil(radius) + 1))[maxima[:, 1], maxima[:, 0]]
    standing = _standing(every[1], lowest, margin)
    kept = np.count_nonzero(standing)
    if not kept:
        return 0, 0.0
    # (where every one stands, the usual case, the arrays as they are: not copies of them)
    points, (centres, heights, high) = maxima, every
    if kept < standing.size:
        points = maxima[standing]
        centres, heights, high = (values[standing] for values in every)
    strong = np.count_nonzero(high)
    if not strong:
        return 0, 0.0
    retest = False
    if contact_noise is None:
        contact_noise = _contact_noise(prepared)
    if contact_noise > noise:
        margin = _margin(contact_noise, sigma, prepared.contrast)
        standing = _standing(every[1], lowest, margin)
        if not np.count_nonzero(standing):
            return 0, 0.0
        points = maxima[standing]
        retest = True
    point_rows, point_cols = points[:, 1], points[:, 0]
    # a plateau of equal values is one maximum, not many: one taxel per connected plateau,
    # the first in the order of the plateaus' labels; two maxima touch only where one
    # equals a neighbour, so without such a tie each maximum is its own plateau
    tied = points.shape[0] > 1 and np.count_nonzero(
        around[point_rows, point_cols] == smooth[point_rows, point_cols]
    )
    if tied:
        points = _first_of_each(points, cv2.connectedComponents(_peaks(points, smooth.shape))[1])
        point_rows, point_cols = points[:, 1], points[:, 0]
    if tied or retest:
        centres, heights, high = _ring_test(padded, place, points, ring_offsets, margin)
        strong = np.count_nonzero(high)
        if not strong:
            return 0, 0.0
    # principal curvatures by central differences one sigma each way, on the points that
    # stand above their ring (all of them, mostly: then not copied)
    if strong < high.size:
        heights, centres = heights[high], centres[high]
    near = padded.take(centres + near_offsets)
    near -= heights[:, None]  # E, W, S, N, SE, SW, NE, NW
    fxx, fyy = near[:, 0] + near[:, 1], near[:, 2] + near[:, 3]
    fxy = 0.25 * (near[:, 4] - near[:, 5] - near[:, 6] + near[:, 7])
    half_trace, root = 0.5 * (fxx + fyy), np.sqrt(0.25 * (fxx - fyy) ** 2 + fxy**2)
    peaked = half_trace + root <= _ISOTROPY * (half_trace - root)  # weak vs strong, both < 0
    count = int(np.count_nonzero(peaked))
    if not count:
        return 0, 0.0
    if count >= _KEEP_PLACES:  # (a texture's, or a few corners': see `_textured`)
        kept = points[high] if strong < high.size else points
        prepared.memo[("high points", sigma)] = kept[peaked] + np.array([c0, r0])
    if count < peaked.size:
        heights = heights[peaked]
    if count > 1 and not tied:
        # the mean height sums the high points in the order of their plateaus' labels (the
        # rounding depends on it); labelled only now that few points are left
        chosen = np.flatnonzero(high)[peaked]
        labels = cv2.connectedComponents(_peaks(points, smooth.shape))[1]
        labels = labels[point_rows[chosen], point_cols[chosen]]
        heights = heights[np.argsort(labels)]
    return count, mean32(heights) - prepared.baseline


def texture_core(prepared: Prepared, *, sigma: float = TEXTURE_SIGMA) -> Texture:
    """Texture measures of a prepared image (internal core of `texture_measures`)."""
    if not prepared.present:
        return Texture(0, math.nan, 0.0, None, None, (0.0,) * OCTAVES, 0.0)
    n_maxima, mean_height = high_points(prepared, sigma=sigma)
    if not n_maxima:
        mean_height = math.nan  # no high points: no mean height (0 would read as one)
    area = float(contact_area(prepared)) * prepared.taxel_area
    density = n_maxima / area
    window = contact_window(prepared)
    mean, deviation = cv2.meanStdDev(prepared.smooth[window], mask=prepared.mask[window])
    above = float(mean[0, 0]) - prepared.baseline
    roughness = float(deviation[0, 0]) / above if above > 0 else 0.0
    # ripple: the whole image minus its mean, Hann-windowed (the seed measures texture over
    # the entire image)
    spectrum = ripple_spectrum(prepared.image, prepared.pitch)
    if spectrum is None:
        return Texture(n_maxima, mean_height, density, None, None, (0.0,) * OCTAVES, roughness)
    strongest, centroid, bands = spectrum
    wavelength = 1.0 / strongest if strongest > 0 else math.inf
    return Texture(n_maxima, mean_height, density, wavelength, centroid, bands, roughness)


def texture_measures(
    image: Any,
    sensor_or_pitch: Any,
    *,
    sigma: float = TEXTURE_SIGMA,
    **preparation: Unpack[Preparation],
) -> Texture:
    """Texture of a tactile image: the seed's two measures and a spectral one.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m], or a sensor description.
    sigma : float, default 2.0
        Gaussian smoothing before the maxima are counted [taxels].
    **preparation
        `calibrated`, `smoothing`, `baseline`, `defects`, `noise` and `reference`, passed
        on to `prepare` with its defaults (so that this agrees with `extract`).

    Returns
    -------
    Texture

    Notes
    -----
    Seed, section 2.1: after Gaussian smoothing, count the local maxima (the object's high
    points) and average their height. Here a maximum counts when it lies in the contact
    and rises by 4 noise sigmas above every point of the circle of radius 2 sigma around
    it (so that a ridge is not a high point), and is curved down in every direction. Count
    and height depend on the image's size and gain; the maxima density and the spectral
    measures do not. The spectrum is that of the image's ripple
    (mean removed, Hann window); its band fractions are in octaves of spatial frequency in
    cycles per metre.

    Examples
    --------
    >>> y, x = np.mgrid[:64, :64]
    >>> bumps = 1.0 + 0.5 * np.cos(2 * np.pi * x / 8) * np.cos(2 * np.pi * y / 8)
    >>> texture = texture_measures(bumps, 1e-3)
    >>> round(texture.dominant_wavelength_m * 1e3, 2)  # 8 mm along x and y: 8/sqrt(2)
    5.66
    """
    sigma = check_range("sigma", sigma, 0.0, 20.0, low_inclusive=False)
    return texture_core(prepare(image, sensor_or_pitch, **preparation), sigma=sigma)
