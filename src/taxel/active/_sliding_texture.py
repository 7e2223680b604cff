"""Texture measured actively: slide the finger over a surface and read its spatial spectrum.

The Ellis seed (section 2): "texture, while it can be measured passively, probably is
better measured actively". Sliding at speed |v| turns a spatial period lambda into the
temporal frequency |v| / lambda; `texture_signature` maps the taxels' time series back onto
spatial frequency, so the same surface gives the same signature at any speed.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import ndimage

from taxel._validation import as_finite_array, check_instance, check_positive, check_range
from taxel.active._probe import Probe
from taxel.active._procedure import ProcedureStep
from taxel.active._spatial_spectrum import check_band_edges
from taxel.active._texture_signature import TextureSignature, texture_signature
from taxel.mechanics import Indenter

__all__ = [
    "SLIDING_BAND_EDGES",
    "Grating",
    "SampledProfile",
    "TextureSlide",
    "TextureSliding",
    "slide_texture",
]

#: Half-octave bands from 100 to 1600 cycles/m (spatial periods of 10 mm down to 0.6 mm):
#: the scale of the seed's foam cells, rasp teeth and screen holes.
SLIDING_BAND_EDGES = 100.0 * 2.0 ** (np.arange(9) / 2.0)


@dataclass(frozen=True)
class Grating(Indenter):
    """Parallel sinusoidal ridges across u: heights A (1 - cos(2 pi u / pitch)) / 2 [m].

    Parameters
    ----------
    pitch : float
        Ridge spacing [m].
    amplitude : float
        Peak-to-valley depth A [m].

    Examples
    --------
    >>> grating = Grating(pitch=4e-3, amplitude=0.2e-3)
    >>> grating.local_heights(np.array([0.0, 2e-3]), np.zeros(2)).round(6).tolist()
    [0.0, 0.0002]
    """

    pitch: float = 4e-3
    amplitude: float = 0.2e-3

    def __post_init__(self) -> None:
        check_positive("pitch", self.pitch)
        check_positive("amplitude", self.amplitude)

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        u, _ = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        return self.amplitude * (1.0 - np.cos(2 * np.pi * u / self.pitch)) / 2.0


@dataclass(frozen=True, eq=False)
class SampledProfile(Indenter):
    """Another indenter sampled once on a grid over a region, then interpolated (bilinear).

    The texture indenters of `taxel.mechanics` re-read their whole periodic tile on every
    call; a slide asks for heights a few thousand times, so sampling the swept region once
    makes it fast. Outside the region there is no material (+inf).

    Parameters
    ----------
    source : Indenter
        The profile to sample.
    extent : (float, float, float, float)
        (u_min, u_max, v_min, v_max) of the region [m].
    spacing : float, default 50e-6
        Sample spacing [m].
    """

    source: Indenter | None = None
    extent: tuple[float, float, float, float] = (-0.05, 0.05, -0.03, 0.03)
    spacing: float = 50e-6
    _finite: np.ndarray = field(init=False, repr=False)
    _holes: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.source, Indenter):
            raise TypeError(f"`source` must be an Indenter, got {self.source!r}")
        check_positive("spacing", self.spacing)
        u_min, u_max, v_min, v_max = (float(value) for value in self.extent)
        if not (u_max > u_min and v_max > v_min):
            raise ValueError(f"`extent` must be (u_min, u_max, v_min, v_max), got {self.extent}")
        u = np.arange(u_min, u_max + self.spacing / 2, self.spacing)
        v = np.arange(v_min, v_max + self.spacing / 2, self.spacing)
        heights = self.source.local_heights(*np.meshgrid(u, v))
        solid = np.isfinite(heights)
        object.__setattr__(self, "_finite", np.where(solid, heights, 0.0))
        object.__setattr__(self, "_holes", (~solid).astype(float))

    def local_heights(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        rows = (v.ravel() - self.extent[2]) / self.spacing
        cols = (u.ravel() - self.extent[0]) / self.spacing
        heights = ndimage.map_coordinates(self._finite, [rows, cols], order=1, cval=np.nan)
        holes = ndimage.map_coordinates(self._holes, [rows, cols], order=1, cval=1.0)
        return np.where(np.isnan(heights) | (holes >= 0.5), np.inf, heights).reshape(u.shape)


@dataclass(frozen=True)
class TextureSlide:
    """One slide over a surface and its spatial-frequency signature.

    Attributes
    ----------
    signature : TextureSignature
        From `texture_signature` on the raw readings of every taxel.
    peak_spatial_frequency : float
        Spatial frequency of the largest pooled PSD value within the bands [cycles/m].
    readings : numpy.ndarray
        (n_steps, n_taxels) raw readings.
    time : numpy.ndarray
        (n_steps,) [s].
    sliding_speed : float
        [m/s].
    steps : tuple of ProcedureStep
    """

    signature: TextureSignature = field(repr=False)
    peak_spatial_frequency: float
    readings: np.ndarray = field(repr=False)
    time: np.ndarray = field(repr=False)
    sliding_speed: float
    steps: tuple[ProcedureStep, ...] = field(repr=False)

    @property
    def band_level(self) -> np.ndarray:
        """Taxel-averaged band levels [dB re the squared mean reading], (n_bands,)."""
        return self.signature.pooled_band_level

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (SI units)."""
        return {
            "sliding_speed_m_s": self.sliding_speed,
            "n_steps": int(self.time.size),
            "peak_spatial_frequency": self.peak_spatial_frequency,
            "centroid": self.signature.centroid,
            "band_edges": self.signature.band_edges.tolist(),
            "band_level_db": self.band_level.tolist(),
            "steps": [step.to_dict() for step in self.steps],
        }


def peak_spatial_frequency(signature: TextureSignature) -> float:
    """Spatial frequency [cycles/m] of the largest pooled PSD value within the bands."""
    edges = signature.band_edges
    inside = (signature.spatial_frequency >= edges[0]) & (signature.spatial_frequency <= edges[-1])
    frequencies = signature.spatial_frequency[inside]
    return float(frequencies[np.argmax(signature.pooled_psd[inside])])


class TextureSliding:
    """Slide pressed over a surface in a straight line and compute its texture signature.

    Parameters
    ----------
    normal_force : float, default 3.0
        Force held while sliding [N].
    length : float, default 0.03
        Length of the slide [m].
    band_edges : array_like, default SLIDING_BAND_EDGES
        Analysis bands [cycles/m].
    segment_length : float, default 0.01
        Travel per spectral segment [m] (resolution 1 / segment_length).
    trim_fraction : float, default 0.05
        Fraction of the steps dropped at each end.
    """

    def __init__(
        self,
        *,
        normal_force: float = 3.0,
        length: float = 0.03,
        band_edges: Any = SLIDING_BAND_EDGES,
        segment_length: float = 0.01,
        trim_fraction: float = 0.05,
    ) -> None:
        self.normal_force = check_positive("normal_force", normal_force)
        self.length = check_positive("length", length)
        self.band_edges = as_finite_array("band_edges", band_edges, ndim=1)
        check_band_edges(self.band_edges)  # now, not after the slide
        self.segment_length = check_positive("segment_length", segment_length)
        if self.segment_length > self.length / 2:
            raise ValueError(
                f"`segment_length` must be <= half the slide's `length` ({self.length / 2:g} m), "
                f"got {self.segment_length:g}"
            )
        self.trim_fraction = check_range("trim_fraction", trim_fraction, 0.0, 0.45)

    def run(self, probe: Probe, *, speed: float, direction: Any = (1.0, 0.0, 0.0)) -> TextureSlide:
        """Slide from the probe's approach pose along a base-frame `direction` at `speed`.

        Parameters
        ----------
        probe : Probe
        speed : float
            Sliding speed [m/s].
        direction : array_like, default (1, 0, 0)
            Base-frame direction of the slide (made unit length).

        Returns
        -------
        TextureSlide
        """
        check_instance("probe", probe, Probe)
        speed = check_positive("speed", speed)
        direction = as_finite_array("direction", direction, ndim=1)
        if direction.shape != (3,) or not np.linalg.norm(direction) > 0:
            raise ValueError(f"`direction` must be a nonzero 3-vector, got {direction.tolist()}")
        direction = direction / np.linalg.norm(direction)
        start = probe.pose[:3, 3]
        path = np.array([start, start + self.length * direction])
        try:
            readings = probe.slide(path, speed=speed, normal_force=self.normal_force)
        finally:
            probe.retract()
        raw = np.array([reading.frame.raw for reading in readings], dtype=float)
        raw = raw.reshape(raw.shape[0], -1)
        time = np.array([reading.time for reading in readings])
        signature = texture_signature(
            raw,
            time,
            speed,
            band_edges=self.band_edges,
            segment_length=self.segment_length,
            trim_fraction=self.trim_fraction,
        )
        peak = peak_spatial_frequency(signature)
        force = float(np.mean([reading.normal_force for reading in readings]))
        step = ProcedureStep(
            action=f"slide {self.length * 1e3:g} mm at {speed * 1e3:g} mm/s",
            normal_force=force,
            travel=float(readings[-1].travel),
            position=readings[-1].pose[:3, 3].copy(),
            measurements={
                "sliding_speed": speed,
                "peak_spatial_frequency": peak,
                "centroid": signature.centroid,
                "mean_reading": signature.mean_reading,
            },
        )
        return TextureSlide(signature, peak, raw, time, speed, (step,))


def slide_texture(
    probe: Probe,
    *,
    speed: float,
    direction: Any = (1.0, 0.0, 0.0),
    normal_force: float = 3.0,
    length: float = 0.03,
    **settings: Any,
) -> TextureSlide:
    """Slide over a surface and measure its texture (one call of `TextureSliding`).

    Parameters
    ----------
    probe : Probe
        A finger at an approach pose just above the surface.
    speed : float
        Sliding speed [m/s].
    direction : array_like, default (1, 0, 0)
        Base-frame direction of the slide.
    normal_force : float, default 3.0
        [N].
    length : float, default 0.03
        [m].
    **settings
        `band_edges`, `segment_length`, `trim_fraction` of `TextureSliding`.

    Returns
    -------
    TextureSlide

    Examples
    --------
    A 4 mm grating read at 80 mm/s peaks at 1 / 4 mm = 250 cycles/m:

    >>> from taxel.active import ProfileObject, SimulatedFinger
    >>> from taxel.frames import make_pose
    >>> from taxel.sensor import make_sensor
    >>> plate = ProfileObject("grating", profile=Grating(4e-3, 0.2e-3), top=0.01)
    >>> down = make_pose(np.diag([1.0, -1.0, -1.0]), [0.0, 0.0, 0.0105])
    >>> finger = SimulatedFinger(make_sensor("resistive16"), [plate], down, rng=0)
    >>> slide = slide_texture(finger, speed=0.08, length=0.02, segment_length=0.008)
    >>> round(slide.peak_spatial_frequency, 6)
    250.0
    """
    procedure = TextureSliding(normal_force=normal_force, length=length, **settings)
    return procedure.run(probe, speed=speed, direction=direction)
