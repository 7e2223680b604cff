r"""Closed-form contacts (Johnson, *Contact Mechanics*, chapter 4 and section 5.2).

The Hertz sphere and cylinder and the flat circular punch, on a body of effective modulus
E* (use `effective_modulus` for two elastic bodies). Used to check the contact solver and
as fast first guesses.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_positive

__all__ = [
    "CylinderContact",
    "PunchContact",
    "SphereContact",
    "flat_punch",
    "hertz_cylinder",
    "hertz_sphere",
]


@dataclass(frozen=True)
class SphereContact:
    """Hertz contact of a sphere: radius a [m], peak pressure p0 [Pa], indentation [m]."""

    contact_radius: float
    peak_pressure: float
    indentation: float
    normal_force: float

    def pressure(self, radius: Any) -> np.ndarray:
        """Pressure p(r) = p0 sqrt(1 - r^2/a^2) inside the contact, 0 outside [Pa]."""
        ratio = as_finite_array("radius", radius) / self.contact_radius
        return self.peak_pressure * np.sqrt(np.clip(1.0 - ratio**2, 0.0, None))


@dataclass(frozen=True)
class CylinderContact:
    """Hertz contact of a cylinder: half-width b [m], peak pressure p0 [Pa]."""

    half_width: float
    peak_pressure: float
    force_per_length: float

    def pressure(self, offset: Any) -> np.ndarray:
        """Pressure p(x) = p0 sqrt(1 - x^2/b^2) inside the strip, 0 outside [Pa]."""
        ratio = as_finite_array("offset", offset) / self.half_width
        return self.peak_pressure * np.sqrt(np.clip(1.0 - ratio**2, 0.0, None))


@dataclass(frozen=True)
class PunchContact:
    """A rigid flat circular punch: radius a [m], indentation [m], force [N]."""

    contact_radius: float
    indentation: float
    normal_force: float

    def pressure(self, radius: Any) -> np.ndarray:
        """Pressure F / (2 pi a sqrt(a^2 - r^2)) inside, 0 outside; inf at the rim [Pa]."""
        r = np.abs(as_finite_array("radius", radius))
        a = self.contact_radius
        with np.errstate(divide="ignore", invalid="ignore"):
            inside = self.normal_force / (2 * np.pi * a * np.sqrt(a**2 - r**2))
        return np.where(r < a, inside, np.where(r == a, np.inf, 0.0))


def hertz_sphere(normal_force: float, radius: float, contact_modulus: float) -> SphereContact:
    r"""Hertz contact of a sphere of radius R pressed with force F on a flat body.

    Parameters
    ----------
    normal_force : float
        F [N], > 0.
    radius : float
        Radius R of the sphere [m], > 0.
    contact_modulus : float
        Effective modulus E* [Pa] (E/(1-nu^2) for a rigid sphere on an elastic body).

    Returns
    -------
    SphereContact

    Notes
    -----
    .. math:: a = \left(\frac{3 F R}{4 E^*}\right)^{1/3}, \quad
              p_0 = \frac{3 F}{2 \pi a^2}, \quad \delta = \frac{a^2}{R}

    Examples
    --------
    >>> contact = hertz_sphere(1.0, 10e-3, 1e6 / 0.75)  # E = 1 MPa, nu = 0.5
    >>> print(f"{contact.contact_radius:.6e} {contact.peak_pressure:.6e}")
    1.778447e-03 1.509592e+05
    """
    force = check_positive("normal_force", normal_force)
    radius = check_positive("radius", radius)
    modulus = check_positive("contact_modulus", contact_modulus)
    a = (3.0 * force * radius / (4.0 * modulus)) ** (1.0 / 3.0)
    return SphereContact(a, 3.0 * force / (2.0 * np.pi * a**2), a**2 / radius, force)


def hertz_cylinder(
    force_per_length: float, radius: float, contact_modulus: float
) -> CylinderContact:
    r"""Hertz contact of a cylinder of radius R pressed with force per length F' [N/m].

    Notes
    -----
    .. math:: b = \sqrt{\frac{4 F' R}{\pi E^*}}, \quad p_0 = \frac{2 F'}{\pi b}

    The indentation of a cylinder on a half-space is not defined (it depends on where the
    displacement is referred to), so none is returned.

    Examples
    --------
    >>> contact = hertz_cylinder(100.0, 5e-3, 1e6 / 0.75)
    >>> print(f"{contact.half_width:.6e} {contact.peak_pressure:.6e}")
    6.909883e-04 9.213177e+04
    """
    load = check_positive("force_per_length", force_per_length)
    radius = check_positive("radius", radius)
    modulus = check_positive("contact_modulus", contact_modulus)
    b = np.sqrt(4.0 * load * radius / (np.pi * modulus))
    return CylinderContact(float(b), float(2.0 * load / (np.pi * b)), load)


def flat_punch(indentation: float, radius: float, contact_modulus: float) -> PunchContact:
    r"""Rigid flat circular punch of radius a pressed to a depth delta.

    Notes
    -----
    .. math:: F = 2 a E^* \delta, \qquad p(r) = \frac{F}{2 \pi a \sqrt{a^2 - r^2}}

    Examples
    --------
    >>> punch = flat_punch(0.1e-3, 2e-3, 1e6 / 0.75)
    >>> print(f"{punch.normal_force:.6f}")
    0.533333
    """
    depth = check_positive("indentation", indentation)
    radius = check_positive("radius", radius)
    modulus = check_positive("contact_modulus", contact_modulus)
    return PunchContact(radius, depth, 2.0 * radius * modulus * depth)
