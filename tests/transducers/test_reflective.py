"""Reflective optical taxel (Figure 25.8): the intensity curve, its peak and the inverse."""

import math

import numpy as np
import pytest

from taxel.transducers import (
    ReflectiveOpticalTransducer,
    Transducer,
    reflective_gap,
    reflective_peak_gap,
    reflective_power,
)
from taxel.transducers._reflective import _overlap

PAIR = dict(core_radius=0.25e-3, fiber_separation=0.6e-3, numerical_aperture=0.37)
SLOPE = 0.37 / math.sqrt(1 - 0.37**2)


@pytest.mark.parametrize("radius", [0.1e-3, 0.3e-3, 0.5e-3, 0.8e-3])
def test_lens_area_against_pixel_count(radius):
    core, distance = 0.25e-3, 0.6e-3
    grid = np.linspace(-1.2e-3, 1.5e-3, 1501)
    x, y = np.meshgrid(grid, grid)
    inside = (x**2 + y**2 <= radius**2) & ((x - distance) ** 2 + y**2 <= core**2)
    counted = inside.sum() * (grid[1] - grid[0]) ** 2
    assert _overlap(np.array([radius]), core, distance)[0] == pytest.approx(
        counted, rel=1e-2, abs=1e-10
    )


def test_curve_has_the_shape_of_figure_25_8b():
    dark_until = (0.6e-3 - 0.5e-3) / (2 * SLOPE)
    assert np.all(reflective_power([0.5 * dark_until, 0.99 * dark_until], **PAIR) == 0)
    # past the point where the receiver sits inside the spot: P = (a / R)^2 exactly
    gap = np.array([0.8e-3, 2e-3, 5e-3])
    spot = 0.25e-3 + 2 * gap * SLOPE
    assert np.allclose(reflective_power(gap, **PAIR), (0.25e-3 / spot) ** 2, rtol=1e-12)


def test_monotonic_only_past_h_min():
    h_min = reflective_peak_gap(**PAIR)
    dark_until = (0.6e-3 - 0.5e-3) / (2 * SLOPE)
    rising = np.linspace(dark_until * 1.01, h_min * 0.999, 400)
    falling = np.linspace(h_min * 1.001, 10e-3, 400)
    assert np.all(np.diff(reflective_power(rising, **PAIR)) > 0)
    assert np.all(np.diff(reflective_power(falling, **PAIR)) < 0)
    peak = float(reflective_power(h_min, **PAIR))
    nearby = reflective_power(h_min * np.array([0.98, 1.02]), **PAIR)
    assert np.all(nearby < peak)


def test_inverse_on_the_branch_and_nan_outside():
    h_min = reflective_peak_gap(**PAIR)
    gap = np.geomspace(h_min * 1.0001, 20e-3, 60)
    power = reflective_power(gap, source_power=2e-3, reflectance=0.8, **PAIR)
    back = reflective_gap(power, source_power=2e-3, reflectance=0.8, **PAIR)
    assert np.allclose(back, gap, rtol=1e-9)
    # a gap below h_min is mapped to its mirror image on the branch, never to itself
    mirrored = reflective_gap(reflective_power(0.5e-3, **PAIR), **PAIR)
    assert mirrored > h_min
    assert reflective_power(mirrored, **PAIR) == pytest.approx(
        reflective_power(0.5e-3, **PAIR), rel=1e-9
    )
    peak = float(reflective_power(h_min, **PAIR))
    assert np.all(np.isnan(reflective_gap([peak * 1.01, 0.0, -1e-3], **PAIR)))


def test_transducer_round_trip_within_full_scale():
    taxel = ReflectiveOpticalTransducer()
    assert isinstance(taxel, Transducer)
    assert (taxel.quantity, taxel.quantity_unit, taxel.signal_unit) == ("displacement", "m", "W")
    displacement = np.linspace(0.0, 0.99 * taxel.full_scale, 50)
    error = np.abs(taxel.invert(taxel.respond(displacement)) - displacement)
    assert np.max(error) < 1e-9 * taxel.full_scale
    # beyond full scale the reading folds back onto the branch: a large error
    beyond = taxel.unloaded_gap - 0.5e-3
    assert abs(taxel.invert(taxel.respond(beyond)) - beyond) > 0.1 * taxel.full_scale


def test_errors_name_the_parameter():
    with pytest.raises(ValueError, match="`gap` must be > 0, got 0"):
        reflective_power([1e-3, 0.0], **PAIR)
    with pytest.raises(ValueError, match=r"`unloaded_gap` must be > h_min = 0.000634\d* m"):
        ReflectiveOpticalTransducer(unloaded_gap=0.6e-3)
    with pytest.raises(ValueError, match="`fiber_separation` must be >= 2 core_radius"):
        reflective_power(
            1e-3, core_radius=0.25e-3, fiber_separation=0.4e-3, numerical_aperture=0.3
        )
    with pytest.raises(ValueError, match=r"`numerical_aperture` must lie in \(0, 1\), got 1.2"):
        reflective_peak_gap(core_radius=0.25e-3, fiber_separation=0.6e-3, numerical_aperture=1.2)
    with pytest.raises(ValueError, match="`displacement` must be < unloaded_gap"):
        ReflectiveOpticalTransducer().respond(2e-3)
