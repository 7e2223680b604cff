"""Reflective optical taxels (Figure 25.8): two fibers under a mirrored membrane.

Light leaves the emitting fiber in a cone of half-angle theta (sin theta = NA), reflects from
the membrane at height h, and returns to the fiber plane as a disc of radius
R(h) = a + 2 h tan(theta), as if from the emitter's mirror image at 2h. The receiving fiber,
of the same core radius a at centre distance s, collects the part of the disc it overlaps.
With the disc uniformly lit, the collected power is

    P(h) = P_0 rho A_overlap(R(h), a, s) / (pi R(h)^2).

P is zero while the disc misses the receiver (R < s - a), rises as it sweeps over it, peaks
at h_min and then falls as 1/R^2 once the receiver is inside the disc (R >= s + a): the curve
of Figure 25.8(b). The chapter's remedy for its ambiguity is to operate at h > h_min only,
where P falls monotonically with h; the inverse here is defined only on that branch.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from scipy import optimize

from taxel._validation import as_finite_array, check_positive, check_range

__all__ = [
    "ReflectiveOpticalTransducer",
    "reflective_gap",
    "reflective_peak_gap",
    "reflective_power",
]


def _geometry(
    core_radius: float, fiber_separation: float, numerical_aperture: float
) -> tuple[float, float, float]:
    core_radius = check_positive("core_radius", core_radius)
    fiber_separation = check_positive("fiber_separation", fiber_separation)
    if fiber_separation < 2 * core_radius:
        raise ValueError(
            f"`fiber_separation` must be >= 2 core_radius = {2 * core_radius:g} m "
            f"(cores cannot overlap), got {fiber_separation:g}"
        )
    numerical_aperture = check_range(
        "numerical_aperture",
        numerical_aperture,
        0.0,
        1.0,
        low_inclusive=False,
        high_inclusive=False,
    )
    slope = numerical_aperture / math.sqrt(1.0 - numerical_aperture**2)
    return core_radius, fiber_separation, slope


def _overlap(radius: np.ndarray, core: float, distance: float) -> np.ndarray:
    """Area shared by a disc of `radius` and one of radius `core`, centres `distance` apart."""
    radius = np.asarray(radius, dtype=float)
    area = np.zeros_like(radius)
    inside = distance <= np.abs(radius - core)
    area[inside] = np.pi * np.minimum(radius[inside], core) ** 2
    lens = (~inside) & (distance < radius + core)
    r = radius[lens]
    cos_a = np.clip((distance**2 + r**2 - core**2) / (2 * distance * r), -1.0, 1.0)
    cos_b = np.clip((distance**2 + core**2 - r**2) / (2 * distance * core), -1.0, 1.0)
    kite = (-distance + r + core) * (distance + r - core) * (distance - r + core)
    kite = kite * (distance + r + core)
    area[lens] = (
        r**2 * np.arccos(cos_a) + core**2 * np.arccos(cos_b) - 0.5 * np.sqrt(np.maximum(kite, 0))
    )
    return area


def _power(gap: np.ndarray, core: float, distance: float, slope: float) -> np.ndarray:
    """Collected fraction of the emitted power at gap h (P_0 rho = 1)."""
    spot = core + 2.0 * gap * slope
    return _overlap(spot, core, distance) / (np.pi * spot**2)


def reflective_power(
    gap: Any,
    *,
    core_radius: float,
    fiber_separation: float,
    numerical_aperture: float,
    source_power: float = 1.0,
    reflectance: float = 1.0,
) -> np.ndarray:
    r"""Optical power collected by the receiving fiber at membrane gap h [W].

    Parameters
    ----------
    gap : array_like
        Distance h from the fiber ends to the reflecting membrane [m], > 0.
    core_radius : float
        Core radius a of both fibers [m], > 0.
    fiber_separation : float
        Centre distance s between the two cores [m], >= 2a.
    numerical_aperture : float
        NA of the fibers, in (0, 1) (the cone half-angle in air is arcsin NA).
    source_power : float, default 1.0
        P_0 launched by the emitting fiber [W], > 0.
    reflectance : float, default 1.0
        rho of the membrane [-], in (0, 1].

    Returns
    -------
    numpy.ndarray
        P(h) [W].

    Notes
    -----
    .. math:: P(h) = P_0 \rho \frac{A(R, a, s)}{\pi R^2},\qquad R = a + 2 h \tan\theta

    with A the area of the lens shared by two discs (radii R and a, centres s apart). The
    uniform-disc spot is the simplest physically motivated form of Figure 25.8(b) of the
    chapter; a Gaussian far field rounds the curve but keeps its shape.

    Examples
    --------
    >>> kw = dict(core_radius=0.25e-3, fiber_separation=0.6e-3, numerical_aperture=0.37)
    >>> np.round(reflective_power([0.1e-3, 0.4e-3, 2e-3], **kw), 4).tolist()
    [0.0, 0.0727, 0.0184]
    """
    gap = as_finite_array("gap", gap)
    if np.any(gap <= 0):
        raise ValueError(f"`gap` must be > 0, got {float(np.min(gap)):g}")
    core, distance, slope = _geometry(core_radius, fiber_separation, numerical_aperture)
    source_power = check_positive("source_power", source_power)
    reflectance = check_range("reflectance", reflectance, 0.0, 1.0, low_inclusive=False)
    return source_power * reflectance * _power(gap, core, distance, slope)


def _peak(core: float, distance: float, slope: float) -> tuple[float, float]:
    """(h_min, peak fraction); the peak lies where the spot sweeps over the receiver."""
    start = (distance - 2 * core) / (2 * slope)  # the spot first touches the receiver
    full = distance / (2 * slope)  # the receiver is wholly inside the spot
    found = optimize.minimize_scalar(
        lambda h: -float(_power(np.array([h]), core, distance, slope)[0]),
        bounds=(start, full),
        method="bounded",
        options={"xatol": 1e-12 * full},
    )
    return float(found.x), -float(found.fun)


def reflective_peak_gap(
    *, core_radius: float, fiber_separation: float, numerical_aperture: float
) -> float:
    """h_min of Figure 25.8(b): the gap of greatest collected power [m].

    Parameters
    ----------
    core_radius, fiber_separation, numerical_aperture : float
        The fiber pair, as in `reflective_power`.

    Returns
    -------
    float
        h_min [m]. Collected power rises with h below it and falls above it.

    Examples
    --------
    >>> h = reflective_peak_gap(core_radius=0.25e-3, fiber_separation=0.6e-3,
    ...                         numerical_aperture=0.37)
    >>> print(f"{h:.4e}")
    6.3449e-04
    """
    core, distance, slope = _geometry(core_radius, fiber_separation, numerical_aperture)
    return _peak(core, distance, slope)[0]


def reflective_gap(
    power: Any,
    *,
    core_radius: float,
    fiber_separation: float,
    numerical_aperture: float,
    source_power: float = 1.0,
    reflectance: float = 1.0,
) -> np.ndarray:
    r"""Membrane gap from collected power, on the monotonic branch h >= h_min only [m].

    Parameters
    ----------
    power : array_like
        Collected power P [W].
    core_radius, fiber_separation, numerical_aperture, source_power, reflectance
        The fiber pair and source, as in `reflective_power`.

    Returns
    -------
    numpy.ndarray
        The unique h >= h_min with P(h) = `power` [m]; NaN where `power` is not in
        (0, P(h_min)], since no gap on the operating branch produces it.

    Notes
    -----
    Once the receiver lies inside the spot (R >= s + a) the inverse is closed-form,
    :math:`R = a \sqrt{P_0 \rho / P}`; between h_min and there it is found by bisection,
    which is safe because P is monotonic on the branch.

    Examples
    --------
    >>> kw = dict(core_radius=0.25e-3, fiber_separation=0.6e-3, numerical_aperture=0.37)
    >>> h = np.array([0.7e-3, 1e-3, 3e-3])
    >>> bool(np.allclose(reflective_gap(reflective_power(h, **kw), **kw), h))
    True
    >>> float(reflective_gap(0.2, **kw))  # brighter than the peak: no gap gives it
    nan
    """
    power = as_finite_array("power", power)
    core, distance, slope = _geometry(core_radius, fiber_separation, numerical_aperture)
    source_power = check_positive("source_power", source_power)
    reflectance = check_range("reflectance", reflectance, 0.0, 1.0, low_inclusive=False)
    fraction = power / (source_power * reflectance)
    h_min, peak = _peak(core, distance, slope)
    full = distance / (2 * slope)
    at_full = float(_power(np.array([full]), core, distance, slope)[0])
    gap = np.full(fraction.shape, np.nan)
    valid = (fraction > 0) & (fraction <= peak)
    far = valid & (fraction <= at_full)
    gap[far] = (core * np.sqrt(1.0 / fraction[far]) - core) / (2 * slope)
    near = valid & ~far
    if np.any(near):
        low = np.full(np.count_nonzero(near), h_min)
        high = np.full_like(low, full)
        target = fraction[near]
        for _ in range(64):  # halves the bracket to below 1e-19 of its width
            middle = 0.5 * (low + high)
            brighter = _power(middle, core, distance, slope) > target
            low = np.where(brighter, middle, low)
            high = np.where(brighter, high, middle)
        gap[near] = 0.5 * (low + high)
    return gap


@dataclass(frozen=True)
class ReflectiveOpticalTransducer:
    """A reflective fiber-pair taxel (Figure 25.8) operated on its monotonic branch.

    Senses the ``displacement`` of the membrane towards the fibers [m] (positive under
    compression, as the cover's surface moves into the layer), so h = h0 - u; the signal is
    the collected optical power [W]. Its inverse returns NaN for powers the operating branch
    cannot produce (beyond the peak at h_min, or non-positive).

    Parameters
    ----------
    core_radius : float, default 0.25e-3
        a [m].
    fiber_separation : float, default 0.6e-3
        s [m].
    numerical_aperture : float, default 0.37
        NA [-].
    unloaded_gap : float, default 1.5e-3
        h0 [m]; must exceed h_min so that the unloaded taxel sits on the monotonic branch.
    source_power : float, default 1e-3
        P_0 [W].
    reflectance : float, default 0.9
        rho [-].

    Examples
    --------
    >>> taxel = ReflectiveOpticalTransducer()
    >>> print(f"h_min = {taxel.peak_gap:.3e} m, full scale = {taxel.full_scale:.3e} m")
    h_min = 6.345e-04 m, full scale = 8.655e-04 m
    >>> u = np.array([0.0, 0.4e-3, 0.8e-3])
    >>> bool(np.allclose(taxel.invert(taxel.respond(u)), u))
    True
    >>> ReflectiveOpticalTransducer(unloaded_gap=0.5e-3)
    Traceback (most recent call last):
    ...
    ValueError: `unloaded_gap` must be > h_min = 0.000634486 m, got 0.0005
    """

    quantity: ClassVar[str] = "displacement"
    quantity_unit: ClassVar[str] = "m"
    signal_unit: ClassVar[str] = "W"

    core_radius: float = 0.25e-3
    fiber_separation: float = 0.6e-3
    numerical_aperture: float = 0.37
    unloaded_gap: float = 1.5e-3
    source_power: float = 1e-3
    reflectance: float = 0.9

    def __post_init__(self) -> None:
        core, distance, slope = _geometry(
            self.core_radius, self.fiber_separation, self.numerical_aperture
        )
        unloaded_gap = check_positive("unloaded_gap", self.unloaded_gap)
        h_min = _peak(core, distance, slope)[0]
        if unloaded_gap <= h_min:
            raise ValueError(f"`unloaded_gap` must be > h_min = {h_min:g} m, got {unloaded_gap:g}")
        for name in ("core_radius", "fiber_separation", "numerical_aperture", "unloaded_gap"):
            object.__setattr__(self, name, float(getattr(self, name)))
        object.__setattr__(self, "source_power", check_positive("source_power", self.source_power))
        object.__setattr__(
            self,
            "reflectance",
            check_range("reflectance", self.reflectance, 0.0, 1.0, low_inclusive=False),
        )

    def _optics(self) -> dict[str, float]:
        return {
            "core_radius": self.core_radius,
            "fiber_separation": self.fiber_separation,
            "numerical_aperture": self.numerical_aperture,
            "source_power": self.source_power,
            "reflectance": self.reflectance,
        }

    @property
    def peak_gap(self) -> float:
        """h_min [m]."""
        return reflective_peak_gap(
            core_radius=self.core_radius,
            fiber_separation=self.fiber_separation,
            numerical_aperture=self.numerical_aperture,
        )

    @property
    def full_scale(self) -> float:
        """Largest displacement on the monotonic branch, h0 - h_min [m]."""
        return self.unloaded_gap - self.peak_gap

    def respond(self, displacement: Any, /) -> np.ndarray:
        """Collected power [W] at membrane displacement u [m] (gap h0 - u must stay > 0).

        Past the full scale (h < h_min) the power is still computed, but it lies on the
        rising branch and `invert` will map it to the wrong, mirrored gap.
        """
        displacement = as_finite_array("displacement", displacement)
        gap = self.unloaded_gap - displacement
        if np.any(gap <= 0):
            raise ValueError(
                f"`displacement` must be < unloaded_gap = {self.unloaded_gap:g} m, "
                f"got {float(np.max(displacement)):g}"
            )
        return reflective_power(gap, **self._optics())

    def invert(self, signal: Any, /) -> np.ndarray:
        """Displacement u [m] from collected power [W]; NaN off the operating branch."""
        return self.unloaded_gap - reflective_gap(signal, **self._optics())
