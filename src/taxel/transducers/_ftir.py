"""Frustrated total internal reflection (Figure 25.9): the camera-read sensor of the Ellis seed.

Light travels along a glass plate by total internal reflection. Where the rubber membrane
touches the glass the reflection is frustrated and light escapes towards the camera: a flat
membrane gives a binary contact image, a textured one a brightness that follows the real
contact area, which grows with the local pressure and saturates at full contact. The image
is an 8-bit camera frame with shot and read noise; scratches on the glass scatter light
too and show as fixed bright streaks. The seed's images span about 24 to 120 in pixel
value, which sets the default no-contact and full-contact levels.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from scipy import special

from taxel._validation import (
    as_finite_array,
    check_flag,
    check_integer,
    check_positive,
    check_range,
)
from taxel.transducers._camera import camera_image, glass_scratches

__all__ = [
    "FtirTransducer",
    "contact_area_fraction",
    "critical_angle",
    "is_totally_reflected",
    "pressure_from_contact_fraction",
]


def _indices(waveguide_index: float, surrounding_index: float) -> tuple[float, float]:
    waveguide_index = check_positive("waveguide_index", waveguide_index)
    surrounding_index = check_positive("surrounding_index", surrounding_index)
    return waveguide_index, surrounding_index


def is_totally_reflected(
    incidence_angle: Any, *, waveguide_index: float, surrounding_index: float = 1.0
) -> np.ndarray:
    r"""Whether a ray inside the waveguide is totally reflected at its face (eq. 25.19).

    Parameters
    ----------
    incidence_angle : array_like
        Angle alpha between the ray and the face's normal [rad], in [0, pi/2].
    waveguide_index : float
        n_2 of the glass [-], > 0.
    surrounding_index : float, default 1.0
        n_1 of the medium outside the face [-]: about 1 for air, about 1.4 for silicone.

    Returns
    -------
    numpy.ndarray of bool
        True where :math:`n_2 \sin\alpha \ge n_1`.

    Notes
    -----
    Snell's law, :math:`n_2 \sin\alpha = n_1 \sin\beta`, has a real refracted angle beta
    only while :math:`n_2 \sin\alpha \le n_1`. Eq. 25.19 as printed in the seed chapter,
    :math:`n_2 \sin\alpha \le n_1`, is therefore the condition for the light to *escape*;
    total internal reflection needs the reverse inequality (alpha measured from the normal,
    the chapter's "angle of incidence"). At equality the refracted ray grazes the face and
    no power crosses, so it counts as reflected.

    Examples
    --------
    >>> angles = np.radians([30.0, 45.0, 60.0, 75.0])
    >>> is_totally_reflected(angles, waveguide_index=1.5).tolist()  # against air
    [False, True, True, True]
    >>> is_totally_reflected(angles, waveguide_index=1.5, surrounding_index=1.41).tolist()
    [False, False, False, True]
    """
    angle = as_finite_array("incidence_angle", incidence_angle)
    if np.any((angle < 0) | (angle > np.pi / 2)):
        raise ValueError(
            f"`incidence_angle` must lie in [0, pi/2] rad, got {float(angle.flat[0]):g}"
            if angle.size == 1
            else "`incidence_angle` must lie in [0, pi/2] rad everywhere"
        )
    n2, n1 = _indices(waveguide_index, surrounding_index)
    return n2 * np.sin(angle) >= n1


def critical_angle(*, waveguide_index: float, surrounding_index: float = 1.0) -> float:
    """Smallest incidence angle of total internal reflection, arcsin(n_1 / n_2) [rad].

    Parameters
    ----------
    waveguide_index, surrounding_index : float
        n_2 and n_1 [-]; n_2 must exceed n_1, or no angle reflects totally.

    Returns
    -------
    float
        The critical angle [rad].

    Examples
    --------
    >>> round(math.degrees(critical_angle(waveguide_index=1.5)), 2)
    41.81
    """
    n2, n1 = _indices(waveguide_index, surrounding_index)
    if n2 <= n1:
        raise ValueError(
            f"`waveguide_index` must exceed surrounding_index = {n1:g} for total internal "
            f"reflection, got {n2:g}"
        )
    return math.asin(n1 / n2)


def contact_area_fraction(
    pressure: Any, *, contact_modulus: float, rms_slope: float
) -> np.ndarray:
    r"""Real contact area fraction of a textured membrane on glass under pressure [-].

    Parameters
    ----------
    pressure : array_like
        Nominal contact pressure on the glass [Pa]; values <= 0 give no contact.
    contact_modulus : float
        E* of the membrane on rigid glass, E / (1 - nu^2) [Pa], > 0.
    rms_slope : float
        Root-mean-square slope of the membrane's texture [-], > 0; steeper texture needs
        more pressure for the same contact.

    Returns
    -------
    numpy.ndarray
        A / A_0 in [0, 1].

    Notes
    -----
    Persson's theory of contact between randomly rough surfaces (B. N. J. Persson,
    J. Chem. Phys. 115, 3840, 2001) gives, when the whole roughness spectrum is resolved,

    .. math:: \frac{A}{A_0} = \operatorname{erf}\left(\frac{\sqrt{2}\, p}{E^* h'_{rms}}\right)

    linear in p at light load (slope :math:`\sqrt{8/\pi} / (E^* h'_{rms})`, the known
    proportionality of real contact area to load) and saturating at full contact. The
    chapter states only that the output is proportional to the area of contact.

    Examples
    --------
    >>> f = contact_area_fraction([0.0, 1e4, 1e5, 1e6], contact_modulus=1e6, rms_slope=0.2)
    >>> np.round(f, 4).tolist()
    [0.0, 0.0797, 0.6827, 1.0]
    """
    pressure = as_finite_array("pressure", pressure)
    contact_modulus = check_positive("contact_modulus", contact_modulus)
    rms_slope = check_positive("rms_slope", rms_slope)
    return special.erf(math.sqrt(2.0) * np.maximum(pressure, 0.0) / (contact_modulus * rms_slope))


def pressure_from_contact_fraction(
    contact_fraction: Any, *, contact_modulus: float, rms_slope: float
) -> np.ndarray:
    """Pressure from the real contact area fraction, the inverse of `contact_area_fraction` [Pa].

    Parameters
    ----------
    contact_fraction : array_like
        A / A_0 in [0, 1); 1 (full contact) maps to inf.
    contact_modulus, rms_slope : float
        As in `contact_area_fraction`.

    Returns
    -------
    numpy.ndarray
        p = E* h'_rms erfinv(A / A_0) / sqrt(2) [Pa].

    Examples
    --------
    >>> float(pressure_from_contact_fraction(0.5, contact_modulus=1e6, rms_slope=0.2))
    67448.97...
    """
    contact_fraction = as_finite_array("contact_fraction", contact_fraction)
    if np.any((contact_fraction < 0) | (contact_fraction > 1)):
        raise ValueError("`contact_fraction` must lie in [0, 1] everywhere")
    contact_modulus = check_positive("contact_modulus", contact_modulus)
    rms_slope = check_positive("rms_slope", rms_slope)
    return contact_modulus * rms_slope * special.erfinv(contact_fraction) / math.sqrt(2.0)


_SIXTY_DEGREES = math.pi / 3


@functools.lru_cache(maxsize=16)
def _scratch_pattern(shape: tuple[int, int], seed: int, count: int, strength: float) -> np.ndarray:
    pattern = glass_scratches(shape, rng=seed, count=count, strength=strength)
    pattern.setflags(write=False)  # shared by every frame of this glass
    return pattern


@dataclass(frozen=True)
class FtirTransducer:
    """A camera-read frustrated-TIR sensor (Figure 25.9), flat or textured membrane.

    Senses the contact ``pressure`` between membrane and glass [Pa], one value per camera
    pixel (a 2-D image); the signal is the camera frame [DN]. Flat membranes give a binary
    contact image; textured ones a brightness that grows with pressure and saturates.

    Parameters
    ----------
    waveguide_index : float, default 1.49
        n_2 of the plate [-] (acrylic).
    membrane_index : float, default 1.41
        Refractive index of the rubber [-] (silicone).
    ray_angle : float, default radians(60)
        Incidence angle of the guided light on the plate's faces [rad]. It must be trapped by
        air and not by the rubber, or the sensor cannot work; checked on construction.
    textured : bool, default True
        Textured membrane (grey levels) or flat (binary contact).
    contact_modulus : float, default 1.33e6
        E* of the membrane on glass [Pa] (E = 1 MPa, nu = 0.5).
    rms_slope : float, default 0.35
        RMS slope of the texture [-]. With the default E* the image saturates near 650 kPa,
        1.6 times the seed sensor's working pressure of 60 psi (414 kPa), so that the grey
        level still grows by a step per 2.5 % of 60 psi there; at 0.2 it would saturate at
        372 kPa and read every pressure above it alike. A larger slope would grade the top
        of the range more finely but dim every contact (fewer levels for the features).
    dark_level, bright_level, conversion_gain, read_noise, bits
        The camera, as in `camera_image`.
    scratch_count : int, default 0
        Scratches on the glass; their pattern is fixed by `scratch_seed`.
    scratch_seed : int, default 0
        Seed of the scratch pattern: one seed is one piece of glass.
    scratch_strength : float, default 0.25
        Peak scratch brightness as a fraction of full contact [-].

    Examples
    --------
    >>> sensor = FtirTransducer()
    >>> pressure = np.array([[0.0, 2e4], [1e5, 1e6]])
    >>> sensor.respond(pressure).tolist()
    [[24, 31], [56, 120]]
    >>> np.round(sensor.invert(sensor.respond(pressure)) / 1e3).tolist()  # kPa, 8-bit steps
    [[0.0, 21.0], [100.0, 650.0]]
    >>> round(sensor.saturation_pressure / 1e3)  # 1 MPa reads as the saturation pressure
    650
    >>> FtirTransducer(textured=False).respond(pressure).tolist()  # binary contact image
    [[24, 120], [120, 120]]
    """

    quantity: ClassVar[str] = "pressure"
    quantity_unit: ClassVar[str] = "Pa"
    signal_unit: ClassVar[str] = "DN"

    waveguide_index: float = 1.49
    membrane_index: float = 1.41
    ray_angle: float = _SIXTY_DEGREES
    textured: bool = True
    contact_modulus: float = 1.33e6
    rms_slope: float = 0.35
    dark_level: float = 24.0
    bright_level: float = 120.0
    conversion_gain: float = 0.025
    read_noise: float = 10.0
    bits: int = 8
    scratch_count: int = 0
    scratch_seed: int = 0
    scratch_strength: float = 0.25

    def __post_init__(self) -> None:
        for name in ("waveguide_index", "membrane_index", "contact_modulus", "rms_slope"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        angle = check_range("ray_angle", self.ray_angle, 0.0, math.pi / 2)
        trapped = bool(is_totally_reflected(angle, waveguide_index=self.waveguide_index))
        escapes = not bool(
            is_totally_reflected(
                angle,
                waveguide_index=self.waveguide_index,
                surrounding_index=self.membrane_index,
            )
        )
        if not (trapped and escapes):
            low = critical_angle(waveguide_index=self.waveguide_index)
            high = (
                critical_angle(
                    waveguide_index=self.waveguide_index, surrounding_index=self.membrane_index
                )
                if self.waveguide_index > self.membrane_index
                else math.pi / 2
            )
            raise ValueError(
                f"`ray_angle` must lie in [{low:.4g}, {high:.4g}) rad so that air traps the "
                f"light and the membrane frustrates it, got {angle:.4g}"
            )
        camera_image(0.0, **self._camera())  # validates the camera fields
        check_integer("scratch_count", self.scratch_count, 0)
        # the other scratch fields; count=0, since drawing them all here could take forever
        glass_scratches((1, 1), rng=self.scratch_seed, count=0, strength=self.scratch_strength)

    def _camera(self) -> dict[str, Any]:
        return {
            "dark_level": self.dark_level,
            "bright_level": self.bright_level,
            "conversion_gain": self.conversion_gain,
            "read_noise": self.read_noise,
            "bits": self.bits,
        }

    @property
    def saturation_pressure(self) -> float:
        """Pressure at which the mean image is within half a level of full contact [Pa]."""
        top = 1.0 - 0.5 / (self.bright_level - self.dark_level)
        return float(self._pressure(np.array(top)))

    def _pressure(self, fraction: np.ndarray) -> np.ndarray:
        return pressure_from_contact_fraction(
            fraction, contact_modulus=self.contact_modulus, rms_slope=self.rms_slope
        )

    def scratches(self, shape: tuple[int, int]) -> np.ndarray:
        """The fixed scratch pattern of this glass for an image of `shape` [-] (read-only).

        Drawn once per glass and image shape: drawing it costs more than the rest of a
        frame (11 of 12 ms for a 128 x 128 image).
        """
        rows, cols = shape
        return _scratch_pattern(
            (int(rows), int(cols)),
            self.scratch_seed,
            self.scratch_count,
            self.scratch_strength,
        )

    def light_fraction(self, pressure: Any) -> np.ndarray:
        """Escaping light per pixel, 0 (no contact) to 1 (full contact), before the glass [-]."""
        pressure = as_finite_array("pressure", pressure)
        if not self.textured:
            return (pressure > 0).astype(float)
        return contact_area_fraction(
            pressure, contact_modulus=self.contact_modulus, rms_slope=self.rms_slope
        )

    def respond(self, pressure: Any, /, *, rng: Any = None) -> np.ndarray:
        """Camera frame [DN] of a 2-D pressure image [Pa]; `rng` switches the noise on."""
        pressure = as_finite_array("pressure", pressure, ndim=2)
        fraction = self.light_fraction(pressure)
        if self.scratch_count:
            fraction = fraction + self.scratches(pressure.shape)
        return camera_image(fraction, rng=rng, **self._camera())

    def invert(
        self, signal: Any, /, *, subtract_scratches: bool = True, keep_sign: bool = False
    ) -> np.ndarray:
        """Pressure image [Pa] from a camera frame [DN].

        Textured: the contact fraction read off the grey level, clipped to [0, saturation],
        so saturated pixels return `saturation_pressure`. Flat: 0 where there is no contact
        and NaN where there is, since a binary image carries no pressure. The known scratch
        pattern is subtracted first (a flat-field correction) unless told otherwise.

        `keep_sign` (textured only): a grey level below the unloaded one reads as a negative
        pressure, the law mirrored (erfinv is odd), instead of 0. Noise about the unloaded
        level then averages to 0 over the background rather than adding a positive bias,
        which sums and centroids over many background pixels need.

        Examples
        --------
        >>> ftir = FtirTransducer()
        >>> frame = np.full((2, 2), ftir.dark_level - 2.0)  # below the unloaded level
        >>> ftir.invert(frame, subtract_scratches=False).tolist()
        [[0.0, 0.0], [0.0, 0.0]]
        >>> signed = ftir.invert(frame, subtract_scratches=False, keep_sign=True)
        >>> mirrored = ftir.invert(frame + 4.0, subtract_scratches=False)
        >>> bool(np.allclose(signed, -mirrored)), bool(signed[0, 0] < 0)
        (True, True)
        """
        keep_sign = check_flag("keep_sign", keep_sign)
        image = as_finite_array("signal", signal, ndim=2)
        fraction = (image - self.dark_level) / (self.bright_level - self.dark_level)
        if subtract_scratches and self.scratch_count:
            fraction = fraction - self.scratches(image.shape)
        if not self.textured:
            return np.where(fraction > 0.5, np.nan, 0.0)
        top = 1.0 - 0.5 / (self.bright_level - self.dark_level)
        if keep_sign:
            return self._pressure(np.clip(np.abs(fraction), 0.0, top)) * np.sign(fraction)
        return self._pressure(np.clip(fraction, 0.0, top))
