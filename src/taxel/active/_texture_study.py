"""Speed invariance of the sliding signature, and classification of the seed's textures.

One call slides a simulated finger over each texture at each speed, then scores
(a) how much each texture's signature changes with the speed and (b) leave-one-speed-out
nearest-neighbour classification: every slide at one speed is classified against the
slides at the other speeds. The same classification with the signatures computed as if
every slide had run at one reference speed (a temporal spectrum in disguise) shows what
the speed normalisation buys.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel._validation import check_positive
from taxel.active._finger import SimulatedFinger
from taxel.active._scene import ProfileObject
from taxel.active._sliding_texture import (
    Grating,
    SampledProfile,
    TextureSlide,
    TextureSliding,
    peak_spatial_frequency,
)
from taxel.active._texture_signature import texture_signature
from taxel.frames import make_pose
from taxel.mechanics import Indenter, make_indenter
from taxel.sensor import PRESET_NAMES, make_sensor

__all__ = ["TextureSpeedStudy", "texture_speed_study", "texture_surface"]

_SEED_TEXTURES = ("foam", "rasp", "screen")
_DOWN = np.diag([1.0, -1.0, -1.0])
_TOP = 0.01


def texture_surface(name: str) -> Indenter:
    """The surface called `name`: 'foam', 'rasp', 'screen' or 'grating<pitch in mm>'.

    Examples
    --------
    >>> texture_surface("grating4").pitch
    0.004
    """
    if name in _SEED_TEXTURES:
        return make_indenter(name)
    if name.startswith("grating"):
        try:
            pitch = float(name[len("grating") :]) * 1e-3
        except ValueError:
            pitch = float("nan")
        if np.isfinite(pitch) and pitch > 0:
            return Grating(pitch=pitch, amplitude=0.2e-3)
    raise ValueError(
        f"`textures` must hold foam, rasp, screen or grating<pitch mm> (e.g. grating4); "
        f"got {name!r}"
    )


@dataclass(frozen=True)
class TextureSpeedStudy:
    """Signatures of several textures at several speeds, and how well they classify.

    Attributes
    ----------
    textures : tuple of str
    speeds : tuple of float
        [m/s].
    slides : dict
        (texture, speed) -> TextureSlide.
    centroid : numpy.ndarray
        (n_textures, n_speeds) spectral centroid [cycles/m].
    peak : numpy.ndarray
        (n_textures, n_speeds) peak spatial frequency [cycles/m].
    band_level : numpy.ndarray
        (n_textures, n_speeds, n_bands) pooled band levels [dB].
    accuracy : float
        Leave-one-speed-out nearest-neighbour accuracy on the band levels.
    unnormalised_accuracy : float
        The same with every signature computed at the reference speed (no normalisation).
    confusion : numpy.ndarray
        (n_textures, n_textures) counts, true (rows) against predicted (columns).
    """

    textures: tuple[str, ...]
    speeds: tuple[float, ...]
    slides: dict[tuple[str, float], TextureSlide] = field(repr=False)
    centroid: np.ndarray
    peak: np.ndarray
    band_level: np.ndarray = field(repr=False)
    accuracy: float
    unnormalised_accuracy: float
    confusion: np.ndarray = field(repr=False)

    @property
    def level_spread(self) -> np.ndarray:
        """Largest change of a band level across the speeds, per texture [dB]."""
        return np.ptp(self.band_level, axis=1).max(axis=1)

    @property
    def centroid_spread(self) -> np.ndarray:
        """Relative range of the centroid across the speeds, per texture [-]."""
        return np.ptp(self.centroid, axis=1) / self.centroid.mean(axis=1)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (SI units)."""
        return {
            "textures": list(self.textures),
            "speeds_m_s": list(self.speeds),
            "centroid": self.centroid.tolist(),
            "peak_spatial_frequency": self.peak.tolist(),
            "band_level_db": self.band_level.tolist(),
            "level_spread_db": self.level_spread.tolist(),
            "centroid_spread": self.centroid_spread.tolist(),
            "accuracy": self.accuracy,
            "unnormalised_accuracy": self.unnormalised_accuracy,
            "confusion": self.confusion.tolist(),
        }


def _leave_one_speed_out(features: np.ndarray) -> tuple[float, np.ndarray]:
    """1-NN accuracy and confusion; features (n_textures, n_speeds, n_features)."""
    n_textures, n_speeds, _ = features.shape
    confusion = np.zeros((n_textures, n_textures), dtype=int)
    for speed in range(n_speeds):
        others = [index for index in range(n_speeds) if index != speed]
        examples = features[:, others].reshape(-1, features.shape[2])
        labels = np.repeat(np.arange(n_textures), len(others))
        for texture in range(n_textures):
            distance = np.nansum((examples - features[texture, speed]) ** 2, axis=1)
            confusion[texture, labels[np.argmin(distance)]] += 1
    return float(np.trace(confusion) / confusion.sum()), confusion


def texture_speed_study(
    textures: tuple[str, ...] = _SEED_TEXTURES,
    speeds: tuple[float, ...] = (0.02, 0.04, 0.08),
    *,
    sensor: str = "resistive16",
    length: float = 0.03,
    normal_force: float = 3.0,
    segment_length: float | None = None,
    seed: int = 0,
) -> TextureSpeedStudy:
    """Slide over each texture at each speed and score speed invariance and classification.

    Parameters
    ----------
    textures : tuple of str, default ('foam', 'rasp', 'screen')
        Surfaces (see `texture_surface`); at least two.
    speeds : tuple of float, default (0.02, 0.04, 0.08)
        Sliding speeds [m/s]; at least two.
    sensor : str, default 'resistive16'
        A static sensor preset.
    length : float, default 0.03
        Slide length [m].
    normal_force : float, default 3.0
        [N].
    segment_length : float, optional
        Travel per spectral segment [m]; default the smaller of 10 mm and half the length.
    seed : int, default 0
        Sensor noise.

    Returns
    -------
    TextureSpeedStudy

    Examples
    --------
    >>> study = texture_speed_study(("grating3", "grating6"), (0.05, 0.1), length=0.016)
    >>> study.accuracy, bool(study.centroid_spread.max() < 0.1)
    (1.0, True)
    """
    if sensor not in PRESET_NAMES:
        raise ValueError(f"`sensor` must be one of {', '.join(PRESET_NAMES)}; got {sensor!r}")
    surfaces = [texture_surface(name) for name in textures]
    if len(textures) < 2 or len(speeds) < 2:
        raise ValueError(
            f"`textures` and `speeds` must each hold at least two, got {len(textures)} and "
            f"{len(speeds)}"
        )
    speeds = tuple(check_positive("speeds", speed) for speed in speeds)
    probe_sensor = make_sensor(sensor)
    length = check_positive("length", length)
    if segment_length is None:
        segment_length = min(0.01, length / 2)
    procedure = TextureSliding(
        normal_force=normal_force, length=length, segment_length=segment_length
    )
    half = max(probe_sensor.geometry.extent) / 2 + 0.005
    extent = (-half, length + half, -half, half)
    reference = float(np.median(speeds))
    slides, unnormalised = {}, []
    for name, surface in zip(textures, surfaces, strict=True):
        plate = ProfileObject(name, profile=SampledProfile(surface, extent=extent), top=_TOP)
        row = []
        for speed in speeds:
            start = make_pose(_DOWN, [0.0, 0.0, _TOP + 0.5e-3])
            finger = SimulatedFinger(probe_sensor, [plate], start, rng=seed)
            slide = procedure.run(finger, speed=speed)
            slides[(name, speed)] = slide
            wrong = texture_signature(
                slide.readings,
                slide.time,
                reference,
                band_edges=procedure.band_edges,
                segment_length=procedure.segment_length * reference / speed,
                trim_fraction=procedure.trim_fraction,
            )
            row.append(wrong.pooled_band_level)
        unnormalised.append(row)
    centroid = np.array([[slides[(t, v)].signature.centroid for v in speeds] for t in textures])
    peak = np.array(
        [[peak_spatial_frequency(slides[(t, v)].signature) for v in speeds] for t in textures]
    )
    levels = np.array([[slides[(t, v)].band_level for v in speeds] for t in textures])
    accuracy, confusion = _leave_one_speed_out(levels)
    baseline, _ = _leave_one_speed_out(np.array(unnormalised))
    return TextureSpeedStudy(
        textures=tuple(textures),
        speeds=speeds,
        slides=slides,
        centroid=centroid,
        peak=peak,
        band_level=levels,
        accuracy=accuracy,
        unnormalised_accuracy=baseline,
        confusion=confusion,
    )
