r"""The spatial-frequency signature of a texture, from a sensor sliding over it.

A taxel sliding at speed |v| over a surface whose profile varies along the path as g(x)
reads r(t) = g(x0 + v t) plus its static contact level. A spatial period lambda [m] then
appears at the temporal frequency f = |v| / lambda [Hz], so the temporal spectrum of the
same texture moves with the speed, while the spectrum over the spatial frequency
k = f / |v| [cycles/m] does not: that is the speed-invariant signature used here. Reversing
the direction reverses r in time, which leaves a power spectrum unchanged, so the signature
is invariant to the direction as well. Texture is best measured actively (seed, section 2.2
and the introduction: "texture ... probably is better measured actively").

The force is the third condition that should not matter. A firmer press scales the readings;
``normalization="static"`` divides the band power by the squared mean reading of the whole
recording, ``normalization="load"`` divides every step's readings by their mean over the
taxels (`load_shares`), which also cancels a force that fluctuates while sliding.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from taxel._validation import (
    as_finite_array,
    check_choice,
    check_finite,
    check_positive,
    check_range,
)
from taxel.active._load_normalization import load_shares, remove_load_coherent
from taxel.active._spatial_spectrum import (
    MIN_STEPS,
    as_readings,
    band_power,
    band_weights,
    check_band_edges,
    spatial_power_spectrum,
)

__all__ = [
    "DEFAULT_BAND_EDGES",
    "NORMALIZATIONS",
    "TextureSignature",
    "texture_features",
    "texture_signature",
]

#: Half-octave bands from 10 to 113 cycles/m (spatial periods of 100 mm down to 8.8 mm):
#: the band a 35 Hz capacitive finger resolves at sliding speeds up to 150 mm/s.
DEFAULT_BAND_EDGES = 10.0 * 2.0 ** (np.arange(8) / 2.0)

#: How readings are made independent of the contact level: "static" divides the band power by
#: the squared mean reading of the recording; "load" divides each step's readings by their mean
#: over the taxels before the spectrum (`load_shares`), which also cancels load fluctuations.
NORMALIZATIONS = ("static", "load")

_SILENT_LEVEL = -120.0  # dB: rounding noise of float64, far below any sensor's noise


@dataclass(frozen=True)
class TextureSignature:
    """The spatial-frequency signature of one sliding recording.

    Attributes
    ----------
    spatial_frequency : numpy.ndarray
        (n_frequencies,) spatial frequency k [cycles/m], from 0 to the Nyquist frequency.
    spatial_psd : numpy.ndarray
        (n_frequencies, n_taxels) one-sided power spectral density over spatial frequency
        [reading^2 m], i.e. reading^2 per cycle/m; it integrates to the variance. Of the
        load shares [m] when `normalization` is ``"load"``.
    band_edges : numpy.ndarray
        (n_bands + 1,) edges of the analysis bands [cycles/m].
    band_power : numpy.ndarray
        (n_bands, n_taxels) variance of each taxel's reading in each band [reading^2]
        (of its load share [-] when `normalization` is ``"load"``); NaN for a band that
        reaches above `nyquist_spatial_frequency` (not observed).
    mean_reading : float
        Mean reading over the analysed steps and all taxels, the static contact level
        [reading].
    sliding_speed : float
        |v| [m/s].
    sampling_rate : float
        Mean sampling rate [Hz].
    normalization : str
        One of `NORMALIZATIONS`: what the spectra were made of, and so what the levels are
        relative to (the squared mean reading for ``"static"``, 1 for the dimensionless
        load shares of ``"load"``).
    load_decorrelated : bool
        Whether the part of each taxel's signal that follows the load was removed
        (`remove_load_coherent`) before the spectrum.
    """

    spatial_frequency: np.ndarray
    spatial_psd: np.ndarray
    band_edges: np.ndarray
    band_power: np.ndarray
    mean_reading: float
    sliding_speed: float
    sampling_rate: float
    normalization: str = "static"
    load_decorrelated: bool = False

    @property
    def level_reference(self) -> float:
        """What band levels are relative to: mean reading ("static") or 1 ("load")."""
        return self.mean_reading if self.normalization == "static" else 1.0

    @property
    def nyquist_spatial_frequency(self) -> float:
        """Highest spatial frequency the sampling resolves, fs / (2 |v|) [cycles/m]."""
        return self.sampling_rate / (2.0 * self.sliding_speed)

    @property
    def pooled_psd(self) -> np.ndarray:
        """Spatial PSD averaged over the taxels, (n_frequencies,) [reading^2 m]."""
        return self.spatial_psd.mean(axis=1)

    @property
    def band_level(self) -> np.ndarray:
        """Band power re the squared `level_reference`, (n_bands, n_taxels) [dB]."""
        return _decibels(self.band_power, self.level_reference)

    @property
    def pooled_band_level(self) -> np.ndarray:
        """Taxel-averaged band power re the squared `level_reference`, (n_bands,) [dB]."""
        return _decibels(self.band_power.mean(axis=1), self.level_reference)

    @property
    def rms(self) -> np.ndarray:
        """Roughness: RMS of each taxel's reading within the bands, (n_taxels,) [reading].

        Of the load share [-] when `normalization` is ``"load"``.
        """
        return np.sqrt(self.band_power.sum(axis=0))

    @property
    def rms_gradient(self) -> np.ndarray:
        """RMS spatial gradient within the bands, (n_taxels,) [reading/m].

        sqrt(integral of (2 pi k)^2 S(k) dk) over the bands: how steeply the reading varies
        per metre of travel, a speed-invariant counterpart of the temporal derivative.
        """
        weight = band_weights(self.spatial_frequency, self.band_edges).sum(axis=0)
        slope = (2.0 * np.pi * self.spatial_frequency) ** 2 * weight
        return np.sqrt(slope @ self.spatial_psd)

    @property
    def centroid(self) -> float:
        """Spectral centroid of the pooled PSD within the bands [cycles/m]."""
        weight = band_weights(self.spatial_frequency, self.band_edges).sum(axis=0)
        power = weight * self.pooled_psd
        return float(power @ self.spatial_frequency / power.sum())


def _decibels(power: np.ndarray, reference: float) -> np.ndarray:
    if reference <= 0:
        return np.full_like(power, np.nan)
    with np.errstate(divide="ignore"):
        return 10.0 * np.log10(power / reference**2)


def texture_signature(
    readings: Any,
    time: Any,
    sliding_velocity: float,
    *,
    band_edges: Any = DEFAULT_BAND_EDGES,
    segment_length: float = 0.2,
    trim_fraction: float = 0.1,
    normalization: str = "static",
    decorrelate_load: bool = False,
) -> TextureSignature:
    """The spatial-frequency signature of a sensor sliding at constant velocity.

    Parameters
    ----------
    readings : array_like
        (n_steps,) or (n_steps, n_taxels) readings (raw counts or any unit).
    time : array_like
        (n_steps,) time of each step [s], non-decreasing; the steps are taken as uniform
        at the mean rate (a jitter of a few percent, as from a millisecond clock, is fine).
    sliding_velocity : float
        Commanded sliding velocity v [m/s], nonzero; its sign (direction) does not matter.
    band_edges : array_like
        (n_bands + 1,) increasing band edges [cycles/m]; default `DEFAULT_BAND_EDGES`.
    segment_length : float
        Travel per spectral segment [m]; the resolution is 1 / segment_length [cycles/m].
    trim_fraction : float
        Fraction of the steps dropped at each end, in [0, 0.45], to keep only the steady
        sliding between the acceleration and deceleration of the motion.
    normalization : {"static", "load"}
        ``"static"``: spectra of the readings, levels relative to the squared mean reading
        of the recording. ``"load"``: spectra of the `load_shares` (each reading divided by
        the mean over the taxels at the same step), dimensionless, which a change of the
        load, steady or fluctuating, leaves unchanged to first order; needs >= 2 taxels.
    decorrelate_load : bool
        Remove from each taxel's signal the part that follows the relative fluctuation of
        the load (the mean reading over the taxels), `remove_load_coherent`; needs >= 2
        taxels.

    Returns
    -------
    TextureSignature

    Notes
    -----
    The signature is `spatial_power_spectrum` of the trimmed readings; `band_power`
    integrates it over the bands. Its descriptors, all independent of the speed and
    direction for a texture fixed in space: `band_level` (dB re the squared mean reading,
    so that a stronger contact, which scales both, changes it less), `rms` [reading],
    `rms_gradient` [reading/m] and the `centroid` [cycles/m].

    A press that scales every reading by a factor a(t) leaves the ``"load"`` signature
    unchanged even when a varies while sliding (a force loop or a rig that oscillates),
    while ``"static"`` removes only a constant factor. On the FabricSlide recordings the
    rig oscillates at about 2.3 Hz at the two highest force settings; see
    ``docs/benchmarks.md`` for what each option does there.

    Examples
    --------
    The same grating (period 25 mm) at 20 and 100 mm/s gives the same signature:

    >>> import numpy as np
    >>> def slide(speed, seconds):
    ...     time = np.arange(0.0, seconds, 1 / 35.0)
    ...     return time, 150 + 4 * np.sin(2 * np.pi * speed * time / 0.025)
    >>> time, readings = slide(0.02, 25.0)
    >>> slow = texture_signature(readings, time, 0.02)
    >>> time, readings = slide(0.1, 5.0)
    >>> fast = texture_signature(readings, time, -0.1)  # and the other way
    >>> round(slow.centroid, 1), round(fast.centroid, 1)
    (40.0, 40.0)
    >>> np.round(slow.rms, 2), np.round(fast.rms, 2)
    (array([2.83]), array([2.83]))
    """
    readings = as_readings(readings)
    time = as_finite_array("time", time, ndim=1)
    if time.shape[0] != readings.shape[0]:
        raise ValueError(
            f"`time` has {time.shape[0]} steps but `readings` has {readings.shape[0]}"
        )
    if np.any(np.diff(time) < 0):
        raise ValueError("`time` must be non-decreasing")
    trim_fraction = check_range("trim_fraction", trim_fraction, 0.0, 0.45)
    normalization = check_choice("normalization", normalization, NORMALIZATIONS)
    if not isinstance(decorrelate_load, bool | np.bool_):
        raise TypeError(f"`decorrelate_load` must be a bool, got {decorrelate_load!r}")
    uses_load = normalization == "load" or bool(decorrelate_load)
    if uses_load and readings.shape[1] < 2:
        raise ValueError(
            f"normalization={normalization!r}, decorrelate_load={decorrelate_load} need at "
            f"least two taxels, got {readings.shape[1]}"
        )
    edges = as_finite_array("band_edges", band_edges, ndim=1)
    check_band_edges(edges)
    n_recorded = time.shape[0]
    if n_recorded < MIN_STEPS:
        raise ValueError(f"`readings` must have at least {MIN_STEPS} steps, got {n_recorded}")
    drop = int(round(trim_fraction * n_recorded))
    keep = slice(drop, n_recorded - drop)
    time, readings = time[keep], readings[keep]
    if time.shape[0] < MIN_STEPS:
        raise ValueError(
            f"`trim_fraction` {trim_fraction:g} leaves {time.shape[0]} of the record's "
            f"{n_recorded} steps, fewer than the {MIN_STEPS} a spectrum needs"
        )
    duration = time[-1] - time[0]
    if duration <= 0:
        raise ValueError("`time` must advance over the recording")
    sampling_rate = (time.shape[0] - 1) / duration
    _check_trimmed_travel(
        n_recorded, time.shape[0], sampling_rate, sliding_velocity, segment_length, trim_fraction
    )
    analysed = load_shares(readings) if normalization == "load" else readings
    if decorrelate_load:
        analysed = remove_load_coherent(analysed, readings.mean(axis=1))
    frequency, psd = spatial_power_spectrum(
        analysed, sampling_rate, sliding_velocity, segment_length=segment_length
    )
    return TextureSignature(
        spatial_frequency=frequency,
        spatial_psd=psd,
        band_edges=edges,
        band_power=band_power(frequency, psd, edges),
        mean_reading=float(readings.mean()),
        sliding_speed=abs(float(sliding_velocity)),
        sampling_rate=float(sampling_rate),
        normalization=normalization,
        load_decorrelated=bool(decorrelate_load),
    )


def _check_trimmed_travel(
    n_recorded: int,
    n_kept: int,
    sampling_rate: float,
    sliding_velocity: Any,
    segment_length: Any,
    trim_fraction: float,
) -> None:
    """Refuse a segment longer than the travel, naming the trim when it is the cause.

    `spatial_power_spectrum` sees only the trimmed record, so its own error would blame
    `segment_length` and show the trimmed travel as the record's. Here a segment longer
    than the whole record is `segment_length`'s error; one that the record holds but the
    trimmed record does not is the trim's, and the error names both values.
    """
    segment_length = check_positive("segment_length", segment_length)
    speed = abs(check_finite("sliding_velocity", sliding_velocity))
    if speed == 0:  # the spectrum's own error
        return
    samples = segment_length * float(sampling_rate) / speed  # as the spectrum counts them
    if not math.isfinite(samples) or round(samples) > n_recorded:
        raise ValueError(
            f"`segment_length` must be at most the record's travel "
            f"({n_recorded * speed / sampling_rate:.4g} m: {n_recorded} steps at {speed:g} m/s "
            f"and {sampling_rate:g} Hz), got {segment_length:g}"
        )
    if round(samples) > n_kept:
        raise ValueError(
            f"`trim_fraction` {trim_fraction:g} leaves {n_kept * speed / sampling_rate:.4g} m "
            f"of the record's {n_recorded * speed / sampling_rate:.4g} m travel ({n_kept} of "
            f"{n_recorded} steps at {speed:g} m/s and {sampling_rate:g} Hz), less than "
            f"`segment_length` {segment_length:g}"
        )


def texture_features(signature: TextureSignature, *, per_taxel: bool = True) -> np.ndarray:
    """The feature vector of a signature, for a texture classifier.

    Parameters
    ----------
    signature : TextureSignature
    per_taxel : bool
        Include each taxel's band levels (the default); False keeps only the pooled ones,
        which do not depend on how the taxels are numbered or placed.

    Returns
    -------
    numpy.ndarray
        (n_taxels * n_bands + n_bands,) the band levels [dB] of taxel 0 (all bands), taxel
        1, ..., then the pooled band levels [dB]; (n_bands,) the pooled ones alone when
        `per_taxel` is False. NaN marks a band above the Nyquist frequency;
        `TextureClassifier` compares features over the bands both sides observed.

    Raises
    ------
    ValueError
        When the mean reading is not positive (the levels are relative to it) or a band
        holds no measurable power (below -120 dB).

    Examples
    --------
    >>> import numpy as np
    >>> time = np.arange(0.0, 10.0, 1 / 35.0)
    >>> grating = 100 + np.sin(2 * np.pi * 0.05 * time / 0.025)
    >>> rough = np.random.default_rng(0).normal(0, 0.1, (time.size, 2))
    >>> signature = texture_signature(grating[:, None] + rough, time, 0.05)
    >>> texture_features(signature).shape, texture_features(signature, per_taxel=False).shape
    ((21,), (7,))
    """
    if signature.mean_reading <= 0:
        raise ValueError(
            "texture features are relative to the mean reading, which must be > 0, got "
            f"{signature.mean_reading:g}"
        )
    if not isinstance(per_taxel, bool | np.bool_):
        raise TypeError(f"`per_taxel` must be a bool, got {per_taxel!r}")
    parts = [signature.band_level.T.ravel()] if per_taxel else []
    features = np.concatenate([*parts, signature.pooled_band_level])
    if np.any(features < _SILENT_LEVEL):
        raise ValueError(
            f"a band holds no measurable power (below {_SILENT_LEVEL:g} dB re the "
            f"{'mean reading' if signature.normalization == 'static' else 'load'}; "
            "a constant reading?)"
        )
    return features
