"""Texture of a tactile image: the seed's maxima measures and a spectral, scale-aware one."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import cv2
import numpy as np

from taxel._validation import check_range
from taxel.features._image import Prepared, prepare

__all__ = ["Texture", "texture_core", "texture_measures"]

# The seed smooths before counting maxima, against camera noise and glass scratches; 2
# taxels keeps bumps a few taxels apart (the rasp's teeth) and merges single-taxel specks.
_TEXTURE_SIGMA = 2.0
# A maximum counts when it stands 4 noise sigmas (of the texture-smoothed image) above both
# the baseline and the lowest point within 3 sigma around it: noise alone gives none, and
# the ripples of noise on a face are not high points of the object.
_MAXIMUM_SIGMAS = 4.0
# Octave bands of spatial frequency, from the Nyquist limit down: [f/2, f], [f/4, f/2], ...
_OCTAVES = 4
_WINDOW_CACHE: dict[tuple[int, int], np.ndarray] = {}


@dataclass(frozen=True)
class Texture:
    """Texture measures of a tactile image.

    Attributes
    ----------
    maxima_count : int
        Local maxima of the smoothed image above the noise (the seed's first measure).
    mean_height : float
        Their mean height above the baseline [image units] (the seed's second measure).
    maxima_density_per_m2 : float
        Maxima per unit contact area [1/m^2]; unlike the count, independent of image size.
    dominant_wavelength_m : float or None
        Wavelength of the strongest spatial frequency of the image's ripple [m].
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


def _hann(shape: tuple[int, int]) -> np.ndarray:
    window = _WINDOW_CACHE.get(shape)
    if window is None:
        window = np.outer(np.hanning(shape[0]), np.hanning(shape[1])).astype(np.float32)
        _WINDOW_CACHE[shape] = window
    return window


def texture_core(prepared: Prepared, *, sigma: float = _TEXTURE_SIGMA) -> Texture:
    """Texture measures of a prepared image (internal core of `texture_measures`)."""
    image = prepared.image
    smooth = cv2.GaussianBlur(image, (0, 0), sigma, borderType=cv2.BORDER_REFLECT)
    dilated = cv2.dilate(smooth, np.ones((3, 3), np.uint8))
    reach = 2 * math.ceil(3 * sigma) + 1
    lowest = cv2.erode(smooth, cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (reach, reach)))
    # white noise of sigma n leaves n / (2 sqrt(pi) sigma) after a Gaussian of sigma
    noise = prepared.raw_noise / (2.0 * math.sqrt(math.pi) * sigma)
    margin = _MAXIMUM_SIGMAS * max(noise, 1e-9 * abs(prepared.contrast), 1e-30)
    peaks = (
        (smooth >= dilated) & (smooth > prepared.baseline + margin) & (smooth > lowest + margin)
    )
    # a plateau of equal values is one maximum, not many: count connected plateaus
    count, labels = cv2.connectedComponents(peaks.view(np.uint8), connectivity=8)
    n_maxima = count - 1
    if n_maxima:
        heights = np.bincount(labels.ravel(), smooth.ravel(), minlength=count)[1:]
        sizes = np.bincount(labels.ravel(), minlength=count)[1:]
        mean_height = float(np.mean(heights / sizes)) - prepared.baseline
    else:
        mean_height = 0.0
    contact = prepared.mask.view(bool)
    area = float(np.count_nonzero(contact)) * prepared.taxel_area
    density = n_maxima / area if area > 0 else 0.0
    if not prepared.present:
        return Texture(n_maxima, mean_height, density, None, None, (0.0,) * _OCTAVES, 0.0)
    values = prepared.smooth[contact]
    above = float(values.mean()) - prepared.baseline
    roughness = float(values.std()) / above if above > 0 else 0.0
    # ripple: the whole image minus its mean, Hann-windowed (the seed measures texture over
    # the entire image)
    ripple = image - np.float32(image.mean())
    power = np.abs(np.fft.rfft2(ripple * _hann(image.shape))) ** 2
    rows, cols = image.shape
    fy = np.fft.fftfreq(rows, prepared.pitch[0])[:, None]
    fx = np.fft.rfftfreq(cols, prepared.pitch[1])[None, :]
    frequency = np.sqrt(fy**2 + fx**2)
    power[0, 0] = 0.0
    total = float(power.sum())
    nyquist = 0.5 / prepared.mean_pitch
    if total <= 0:
        return Texture(n_maxima, mean_height, density, None, None, (0.0,) * _OCTAVES, roughness)
    bands = []
    for octave in range(_OCTAVES):
        high, low = nyquist / 2**octave, nyquist / 2 ** (octave + 1)
        inside = (frequency > low) & (frequency <= high) if octave else (frequency > low)
        bands.append(float(power[inside].sum()) / total)
    strongest = float(frequency.flat[int(np.argmax(power))])
    centroid = float((power * frequency).sum()) / total
    wavelength = 1.0 / strongest if strongest > 0 else math.inf
    return Texture(n_maxima, mean_height, density, wavelength, centroid, tuple(bands), roughness)


def texture_measures(
    image: Any, sensor_or_pitch: Any, *, sigma: float = _TEXTURE_SIGMA
) -> Texture:
    """Texture of a tactile image: the seed's two measures and a spectral one.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m].
    sigma : float, default 2.0
        Gaussian smoothing before the maxima are counted [taxels].

    Returns
    -------
    Texture

    Notes
    -----
    Seed, section 2.1: after Gaussian smoothing, count the local maxima (the object's high
    points) and average their height. Both depend on the image's size and gain; the
    maxima density and the spectral measures do not. The spectrum is that of the image's
    ripple (mean removed, Hann window); its band fractions are in octaves of spatial
    frequency in cycles per metre.

    Examples
    --------
    >>> y, x = np.mgrid[:64, :64]
    >>> bumps = 1.0 + 0.5 * np.cos(2 * np.pi * x / 8) * np.cos(2 * np.pi * y / 8)
    >>> texture = texture_measures(bumps, 1e-3)
    >>> round(texture.dominant_wavelength_m * 1e3, 2)  # 8 mm along x and y: 8/sqrt(2)
    5.66
    """
    sigma = check_range("sigma", sigma, 0.0, 20.0, low_inclusive=False)
    return texture_core(prepare(image, sensor_or_pitch), sigma=sigma)
