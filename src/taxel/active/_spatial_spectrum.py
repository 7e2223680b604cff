"""Power spectra over spatial frequency, and their integrals over bands.

A sensor sliding at speed |v| turns a spatial period lambda [m] into the temporal frequency
f = |v| / lambda [Hz]; these functions undo that mapping, so that spectra of the same
surface taken at different speeds coincide.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy import signal

from taxel._validation import as_finite_array, check_finite, check_positive

# as_readings, band_weights, check_band_edges and MIN_STEPS are shared with _texture_signature
__all__ = ["band_power", "spatial_power_spectrum"]

MIN_STEPS = 16
_MIN_SEGMENT = 8  # samples in a Welch segment, at least


def band_weights(spatial_frequency: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """(n_bands, n_frequencies) length of each frequency bin that lies inside each band."""
    step = spatial_frequency[1] - spatial_frequency[0]
    left = np.maximum(spatial_frequency - step / 2.0, 0.0)
    right = spatial_frequency + step / 2.0
    low, high = edges[:-1, None], edges[1:, None]
    return np.clip(np.minimum(right, high) - np.maximum(left, low), 0.0, None)


def as_readings(readings: Any) -> np.ndarray:
    array = as_finite_array("readings", readings)
    if array.ndim == 1:
        return array[:, None]
    if array.ndim < 1 or array.shape[0] < 1:
        raise ValueError(f"`readings` must be (n_steps, ...), got shape {array.shape}")
    return array.reshape(array.shape[0], -1)


def spatial_power_spectrum(
    readings: Any,
    sampling_rate: float,
    sliding_velocity: float,
    *,
    segment_length: float = 0.2,
) -> tuple[np.ndarray, np.ndarray]:
    r"""Power spectral density of each taxel over spatial frequency.

    Parameters
    ----------
    readings : array_like
        (n_steps,) or (n_steps, n_taxels) readings at uniform time steps (extra trailing
        axes are flattened into taxels).
    sampling_rate : float
        fs [Hz], > 0.
    sliding_velocity : float
        v [m/s], nonzero; the sign (direction) does not matter.
    segment_length : float
        Travel per Welch segment [m], > 0 and at most the record's travel; sets the
        resolution 1 / `segment_length` [cycles/m] whatever the speed.

    Returns
    -------
    spatial_frequency : numpy.ndarray
        (n_frequencies,) k [cycles/m].
    spatial_psd : numpy.ndarray
        (n_frequencies, n_taxels) S_x(k) [reading^2 m].

    Notes
    -----
    Welch's estimate of the temporal PSD S_t(f) [reading^2/Hz] (Hann window, segments
    spread evenly over the whole record with at least 50 % overlap, a straight line removed
    from each segment, which removes the static contact level and slow drift) is mapped
    onto spatial frequency by

    .. math:: k = f / |v|, \qquad S_x(k) = |v| \, S_t(k |v|),

    which keeps the variance: the integral of S_x over k equals that of S_t over f. A
    segment spans `segment_length` of travel, round(segment_length fs / |v|) samples; a
    segment longer than the record is an error, since the record cannot give that
    resolution, and so is one shorter than 8 samples, too few for a spectrum.

    Examples
    --------
    A grating of period 25 mm (40 cycles/m) slid at 20 mm/s, sampled at 50 Hz:

    >>> import numpy as np
    >>> t = np.arange(1500) / 50.0
    >>> k, psd = spatial_power_spectrum(np.sin(2 * np.pi * 40 * 0.02 * t), 50.0, 0.02)
    >>> float(k[np.argmax(psd[:, 0])]), float(k[1])
    (40.0, 5.0)
    """
    readings = as_readings(readings)
    sampling_rate = check_positive("sampling_rate", sampling_rate)
    speed = abs(check_finite("sliding_velocity", sliding_velocity))
    if speed == 0:
        raise ValueError("`sliding_velocity` must be nonzero, got 0")
    segment_length = check_positive("segment_length", segment_length)
    n_steps = readings.shape[0]
    if n_steps < MIN_STEPS:
        raise ValueError(f"`readings` must have at least {MIN_STEPS} steps, got {n_steps}")
    samples_per_segment = segment_length * sampling_rate / speed
    if not math.isfinite(samples_per_segment) or round(samples_per_segment) > n_steps:
        travel = n_steps * speed / sampling_rate
        raise ValueError(
            f"`segment_length` must be at most the record's travel ({travel:.4g} m: "
            f"{n_steps} steps at {speed:g} m/s and {sampling_rate:g} Hz), got {segment_length:g}"
        )
    samples = round(samples_per_segment)
    if samples < _MIN_SEGMENT:
        shortest = _MIN_SEGMENT * speed / sampling_rate
        raise ValueError(
            f"`segment_length` must span at least {_MIN_SEGMENT} samples ({shortest:.4g} m at "
            f"{speed:g} m/s and {sampling_rate:g} Hz), got {segment_length:g}"
        )
    frequency, psd = _welch(readings, sampling_rate, samples)
    return frequency / speed, psd * speed


def _welch(readings: np.ndarray, sampling_rate: float, samples: int) -> tuple[Any, Any]:
    """Welch's one-sided PSD with segments spread evenly from the first to the last step.

    scipy.signal.welch drops the steps after its last whole segment, which loses up to half
    a segment and makes the estimate depend on the direction of time; spreading the
    segments evenly (overlap >= 50 %) uses every step, and the set of segments maps onto
    itself under time reversal.
    """
    n_steps = readings.shape[0]
    count = 1 if samples >= n_steps else int(np.ceil(2 * (n_steps - samples) / samples)) + 1
    starts = np.round(np.linspace(0, n_steps - samples, count)).astype(int)
    window = signal.windows.hann(samples, sym=True)  # symmetric: reversal-invariant
    segments = np.stack([readings[start : start + samples] for start in starts])
    segments = signal.detrend(segments, axis=1, type="linear") * window[None, :, None]
    spectrum = np.abs(np.fft.rfft(segments, axis=1)) ** 2 / (sampling_rate * np.sum(window**2))
    spectrum[:, 1 : (samples + 1) // 2] *= 2.0  # one-sided: fold the negative frequencies
    return np.fft.rfftfreq(samples, 1.0 / sampling_rate), spectrum.mean(axis=0)


def band_power(spatial_frequency: Any, spatial_psd: Any, band_edges: Any) -> np.ndarray:
    """Integrate a PSD over bands, splitting frequency bins that straddle a band edge.

    Parameters
    ----------
    spatial_frequency : array_like
        (n_frequencies,) uniformly spaced frequencies from 0 [cycles/m].
    spatial_psd : array_like
        (n_frequencies, ...) PSD [reading^2 m].
    band_edges : array_like
        (n_bands + 1,) increasing band edges [cycles/m], >= 0.

    Returns
    -------
    numpy.ndarray
        (n_bands, ...) power in each band [reading^2]; NaN for a band reaching above the
        highest frequency (the Nyquist frequency).

    Notes
    -----
    Bin j stands for the interval k_j +- dk / 2 (clipped at 0); the band integral is the sum
    of S(k_j) times the length of that interval inside the band. Bands narrower than the
    bin width therefore still get their share, so the same bands can be used at any
    resolution.

    Examples
    --------
    >>> import numpy as np
    >>> k = np.arange(11.0)  # 0..10 cycles/m, flat PSD of 2 reading^2 m
    >>> band_power(k, np.full(11, 2.0), [1.0, 2.5, 4.0, 12.0]).tolist()
    [3.0, 3.0, nan]
    """
    frequency = as_finite_array("spatial_frequency", spatial_frequency, ndim=1)
    psd = as_finite_array("spatial_psd", spatial_psd)
    edges = as_finite_array("band_edges", band_edges, ndim=1)
    if frequency.size < 2 or psd.shape[0] != frequency.size:
        raise ValueError(
            f"`spatial_psd` {psd.shape} must be (n_frequencies, ...) with n_frequencies = "
            f"{frequency.size} >= 2"
        )
    if np.any(psd < 0):
        raise ValueError(f"`spatial_psd` must be >= 0 (a power), got {float(psd.min()):g}")
    check_band_edges(edges)
    weights = band_weights(frequency, edges)
    power = np.tensordot(weights, psd, axes=(1, 0))
    top = frequency[-1] * (1.0 + 1e-9)
    power[edges[1:] > top] = np.nan
    return power


def check_band_edges(edges: np.ndarray) -> None:
    if edges.size < 2 or np.any(edges < 0) or np.any(np.diff(edges) <= 0):
        raise ValueError(
            f"`band_edges` must be at least two increasing values >= 0, got {edges.tolist()}"
        )
