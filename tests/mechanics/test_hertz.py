"""Closed-form contacts against the fact sheet's check values (E = 1 MPa)."""

import numpy as np
import pytest

from taxel.mechanics import ElasticMaterial, flat_punch, hertz_cylinder, hertz_sphere


def test_sphere_reference_values():
    cover = ElasticMaterial(1e6, 0.5)
    contact = hertz_sphere(1.0, 10e-3, cover.plane_strain_modulus)
    # printed to 7 significant digits in ../shared/reference/mechanics.md
    assert contact.contact_radius == pytest.approx(1.778447e-3, rel=5e-7)
    assert contact.peak_pressure == pytest.approx(1.509592e5, rel=5e-7)
    assert contact.indentation == pytest.approx(0.316287e-3, abs=0.5e-9)  # 6 digits printed
    # and exact relations to 1e-12
    a = (3 * 1.0 * 10e-3 / (4 * cover.plane_strain_modulus)) ** (1 / 3)
    assert contact.contact_radius == pytest.approx(a, rel=1e-12)
    total = np.trapezoid(2 * np.pi * (r := np.linspace(0, a, 200001)) * contact.pressure(r), r)
    assert total == pytest.approx(1.0, rel=1e-6)


def test_cylinder_reference_values():
    contact = hertz_cylinder(100.0, 5e-3, 1e6 / 0.75)
    assert contact.half_width == pytest.approx(0.690988e-3, rel=5e-7)
    assert contact.peak_pressure == pytest.approx(9.213177e4, rel=5e-7)
    x = np.linspace(-contact.half_width, contact.half_width, 400001)
    assert np.trapezoid(contact.pressure(x), x) == pytest.approx(100.0, rel=1e-6)


def test_flat_punch():
    punch = flat_punch(0.1e-3, 2e-3, 1e6 / 0.75)
    assert punch.normal_force == pytest.approx(2 * 2e-3 * (1e6 / 0.75) * 0.1e-3, rel=1e-12)
    r = np.array([0.0, 1e-3, 2e-3, 3e-3])
    p = punch.pressure(r)
    assert p[0] == pytest.approx(punch.normal_force / (2 * np.pi * 2e-3**2))
    assert np.isinf(p[2]) and p[3] == 0


def test_bad_inputs():
    with pytest.raises(ValueError, match="`normal_force` must be > 0, got -1"):
        hertz_sphere(-1.0, 1e-3, 1e6)
    with pytest.raises(ValueError, match="`radius` must be > 0"):
        hertz_cylinder(1.0, 0.0, 1e6)
