"""Feature variants evaluated on FabricSlide for issue 7, kept or not (used by bench_texture).

Each variant has a physical reason stated beside it. They are all computed from
`texture_signature` outputs; the ones that were not kept live only here.
"""

from __future__ import annotations

import numpy as np

from taxel.active import DEFAULT_BAND_EDGES, band_power, texture_features, texture_signature

# (normalization, decorrelate_load) of each signature family
FAMILIES = {
    "readings": ("static", False),
    "readings, load-coherent part removed": ("static", True),
    "load shares": ("load", False),
    "load shares, load-coherent part removed": ("load", True),
}
RIG_LINES_HZ = ((1.9, 2.7), (4.2, 5.2))  # the ~2.3 Hz line and its harmonic, seen on the data


def signatures(recordings) -> dict[str, list]:
    """The signature of every recording in every family, with the default settings."""
    return {
        family: [
            texture_signature(
                recording.readings,
                recording.time,
                recording.sliding_velocity,
                normalization=normalization,
                decorrelate_load=decorrelate,
            )
            for recording in recordings
        ]
        for family, (normalization, decorrelate) in FAMILIES.items()
    }


def _decibels(power):
    return 10.0 * np.log10(power)


def _taxel_means(recordings, trim_fraction=0.1):
    means = []
    for recording in recordings:
        drop = int(round(trim_fraction * recording.n_steps))
        means.append(recording.readings[drop : recording.n_steps - drop].mean(axis=0))
    return means


def _with_pooled(levels, power):
    return np.concatenate([levels.T.ravel(), _decibels(power.mean(axis=1))])


def _slope_and_centroid(power):
    """Scale-free shape of the pooled spectrum: log-log slope and centroid [cycles/m]."""
    edges = DEFAULT_BAND_EDGES
    centre = np.sqrt(edges[:-1] * edges[1:])
    density = power.mean(axis=1) / np.diff(edges)
    slope = np.polyfit(np.log10(centre), np.log10(density), 1)[0]
    centroid = float(centre @ power.mean(axis=1) / power.mean(axis=1).sum())
    return [slope, centroid]


def _notched_power(signature):
    """Band power with the rig's temporal lines replaced by their neighbours (diagnostic)."""
    frequency = signature.spatial_frequency * signature.sliding_speed
    bad = np.zeros(frequency.size, dtype=bool)
    for low, high in RIG_LINES_HZ:
        bad |= (frequency >= low) & (frequency <= high)
    psd = signature.spatial_psd.copy()
    if bad.any() and np.count_nonzero(~bad) > 2:
        k = signature.spatial_frequency
        for column in range(psd.shape[1]):
            psd[bad, column] = np.exp(np.interp(k[bad], k[~bad], np.log(psd[~bad, column])))
    return band_power(signature.spatial_frequency, psd, signature.band_edges)


def variants(recordings, families) -> list[tuple[str, str, np.ndarray]]:
    """(name, physical reason, features) of every variant tried."""
    static = families["readings"]
    shares = families["load shares"]
    means = _taxel_means(recordings)
    rows = [
        (
            "v1: readings, levels re the squared mean reading",
            "a harder press scales the vibration with the contact level",
            np.array([texture_features(s) for s in static]),
        ),
        (
            "readings, each taxel re its own squared mean",
            "each taxel's contact level scales its own vibration",
            np.array(
                [
                    _with_pooled(_decibels(s.band_power / m**2), s.band_power / m**2)
                    for s, m in zip(static, means, strict=True)
                ]
            ),
        ),
        (
            "readings, absolute levels",
            "(reference: no normalisation)",
            np.array([_with_pooled(_decibels(s.band_power), s.band_power) for s in static]),
        ),
        (
            "readings, spectral shape only",
            "levels re each taxel's in-band total: free of any gain",
            np.array(
                [
                    _with_pooled(_decibels(s.band_power / s.band_power.sum(axis=0)), s.band_power)
                    for s in static
                ]
            ),
        ),
        (
            "readings + log-log slope and centroid",
            "scale-free descriptors of the spectrum's shape",
            np.array(
                [
                    np.concatenate([texture_features(s), _slope_and_centroid(s.band_power)])
                    for s in static
                ]
            ),
        ),
        (
            "readings, rig lines notched (diagnostic)",
            "upper bound of removing the ~2.3 Hz line; its frequency was read off this data",
            np.array(
                [
                    _with_pooled(
                        _decibels(_notched_power(s) / s.mean_reading**2),
                        _notched_power(s) / s.mean_reading**2,
                    )
                    for s in static
                ]
            ),
        ),
        (
            "readings, load-coherent part removed",
            "a load fluctuation moves every taxel with a gain of its own",
            np.array(
                [texture_features(s) for s in families["readings, load-coherent part removed"]]
            ),
        ),
        (
            "load shares",
            "a load change scales every taxel alike; texture moves load between taxels",
            np.array([texture_features(s) for s in shares]),
        ),
        (
            "load shares, pooled only",
            "independent of how taxels are numbered or mounted",
            np.array([texture_features(s, per_taxel=False) for s in shares]),
        ),
        (
            "load shares, 4 taxel groups by static level",
            "taxels pooled by how firmly they touch, not by their index",
            np.array([_groups(s.band_power, m) for s, m in zip(shares, means, strict=True)]),
        ),
        (
            "load shares + log-log slope and centroid",
            "scale-free descriptors of the spectrum's shape",
            np.array(
                [
                    np.concatenate([texture_features(s), _slope_and_centroid(s.band_power)])
                    for s in shares
                ]
            ),
        ),
        (
            "load shares, band-level differences",
            "differences of adjacent levels cancel any remaining gain",
            np.array(
                [np.diff(texture_features(s).reshape(-1, 7), axis=1).ravel() for s in shares]
            ),
        ),
        (
            "load shares, rig lines notched (diagnostic)",
            "upper bound of removing the ~2.3 Hz line; its frequency was read off this data",
            np.array(
                [_with_pooled(_decibels(_notched_power(s)), _notched_power(s)) for s in shares]
            ),
        ),
        (
            "load shares, load-coherent part removed",
            "a firmer press also widens the contact: edge taxels gain more than in proportion",
            np.array(
                [texture_features(s) for s in families["load shares, load-coherent part removed"]]
            ),
        ),
    ]
    return rows


def _groups(power, taxel_mean, n_groups=4):
    order = np.argsort(taxel_mean)
    pooled = power[:, order].reshape(power.shape[0], n_groups, -1).mean(axis=2)
    return _with_pooled(_decibels(pooled), power)


def candidates(families) -> dict[str, np.ndarray]:
    """The feature sets among which nested cross-validation chooses, preferred first."""
    sets = {}
    for family in (
        "load shares",
        "load shares, load-coherent part removed",
        "readings",
        "readings, load-coherent part removed",
    ):
        sets[family] = np.array([texture_features(s) for s in families[family]])
        sets[f"{family}, pooled only"] = np.array(
            [texture_features(s, per_taxel=False) for s in families[family]]
        )
    return sets
