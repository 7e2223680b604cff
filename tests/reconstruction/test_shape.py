"""Shape recovery from surface displacement, against contacts solved with known indenters.

The truth is `solve_contact` of a sphere (R = 10 mm), a finite edge (R = 3.2 mm, 8 mm long)
and a flat punch (6 mm across), each pressed with 1 N into a 3 mm cover (E = 1 MPa,
nu = 0.49) read by 32 x 32 displacement taxels of 0.5 mm; readings are the forward model of
the solved pressure plus Gaussian noise of 0.5 % or 1 % of a 0.5 mm full scale (sigma =
2.5 um, 5 um; the sphere indents 200 um).
"""

from functools import lru_cache

import numpy as np
import pytest

from taxel.mechanics import ElasticMaterial, make_indenter, solve_contact
from taxel.reconstruction import (
    ForwardModelSpec,
    forward_operator,
    recover_shape,
    spec_from_sensor,
)
from taxel.sensor import make_sensor

SPEC = ForwardModelSpec(
    (32, 32),
    0.5e-3,
    ElasticMaterial(1e6, 0.49),
    0.0,
    thickness=3e-3,
    quantity="displacement",
    full_scale=0.5e-3,
)
INDENTERS = {
    "sphere": ("sphere", {"radius": 10e-3}),
    "edge": ("edge", {"length": 8e-3}),
    "punch": ("punch", {}),
}
RADIUS = 10e-3  # [m] of the sphere
OFF_GRID = (0.2e-3, -0.1e-3)  # [m]: the indenters' axes between cell centres


@lru_cache(maxsize=8)
def _pressed(name, position=OFF_GRID):
    """(indenter heights, solved contact, noise-free frame) of a 1 N press, on SPEC's grid."""
    kind, parameters = INDENTERS[name]
    heights = make_indenter(kind, **parameters).on_grid(
        SPEC.load_shape, SPEC.load_pitch, position=position
    )
    contact = solve_contact(
        heights, SPEC.load_pitch, SPEC.material, thickness=SPEC.thickness, normal_force=1.0
    )
    return heights, contact, forward_operator(SPEC).apply(contact.pressure)


def _noisy(frame, fraction, seed):
    rng = np.random.default_rng(seed)
    return frame + rng.normal(0.0, fraction * SPEC.full_scale, frame.shape)


def _iou(found, true):
    return (found & true).sum() / (found | true).sum()


def _paraboloid_radius(heights, contact, pitch):
    """R of h = c + a x + b y + (x^2 + y^2) / 2R fitted to the heights in contact [m]."""
    y, x = np.nonzero(contact)
    x, y = x * pitch, y * pitch
    design = np.column_stack([np.ones(x.size), x, y, x**2 + y**2])
    coefficients, *_ = np.linalg.lstsq(design, heights[contact], rcond=None)
    return 1.0 / (2.0 * coefficients[3])


@pytest.mark.parametrize("name", ["sphere", "edge", "punch"])
def test_noise_free_contacts_are_recovered_exactly(name):
    heights, truth, frame = _pressed(name)
    shape = recover_shape(frame, SPEC)
    inside = truth.contact
    assert np.array_equal(shape.contact, inside)  # 41, 48 and 118 cells
    # indentations 200, 113 and 37 um; found to 0.1-0.23 um, the heights with them
    assert abs(shape.indentation - truth.indentation) < 0.5e-6
    assert np.abs(shape.heights[inside] - heights[inside]).max() < 0.5e-6
    assert np.all(np.isinf(shape.heights[~inside]))
    assert np.allclose(shape.surface, -truth.displacement, atol=1e-9)


def test_noise_free_sphere_radius():
    heights, truth, frame = _pressed("sphere")
    shape = recover_shape(frame, SPEC)
    radius = _paraboloid_radius(shape.heights, shape.contact, SPEC.load_pitch)
    # the cap is not quite a paraboloid: the same fit to the true heights gives 9.92 mm
    assert radius == pytest.approx(RADIUS, rel=0.01)


def test_indentation_is_the_apex_of_a_fit_not_the_largest_displacement():
    # the sphere's apex on a corner of four cells, 0.35 mm from their centres: the largest
    # displacement falls short of delta by r^2 / 2R = 6.25 um
    heights, truth, frame = _pressed("sphere", position=(0.0, 0.0))
    shape = recover_shape(frame, SPEC)
    largest = -shape.surface[shape.contact].min()
    assert truth.indentation - largest == pytest.approx(6.25e-6, abs=0.1e-6)
    assert abs(shape.indentation - truth.indentation) < 0.3e-6
    assert shape.heights[truth.contact].min() == pytest.approx(6.25e-6, abs=0.3e-6)


@pytest.mark.parametrize(("noise", "tolerance"), [(0.005, 0.08), (0.01, 0.15)])
@pytest.mark.parametrize("seed", range(3))
def test_sphere_radius_under_noise(noise, tolerance, seed):
    # seeds 0-2 give 9.88-10.47 mm at 0.5 % and 9.92-10.94 mm at 1 %; the rule of 5 % of
    # the peak pressure on the non-negative order-1 map gave 12.6-13.1 and 14.0-15.6 mm
    _, _, frame = _pressed("sphere")
    shape = recover_shape(_noisy(frame, noise, seed), SPEC)
    radius = _paraboloid_radius(shape.heights, shape.contact, SPEC.load_pitch)
    assert radius == pytest.approx(RADIUS, rel=tolerance)


@pytest.mark.parametrize(
    ("name", "bound"),
    # seeds 0-2 give IoU >= 0.86, 0.68 and 0.93; the 5 % rule gave 0.62, 0.37 and 0.35.
    # The edge's outer row carries < 5 % of its peak pressure, below 1 % noise: lost
    [("sphere", 0.8), ("edge", 0.6), ("punch", 0.9)],
)
@pytest.mark.parametrize("seed", range(3))
def test_contact_and_heights_at_one_percent_noise(name, bound, seed):
    heights, truth, frame = _pressed(name)
    shape = recover_shape(_noisy(frame, 0.01, seed), SPEC)
    assert _iou(shape.contact, truth.contact) > bound
    assert shape.contact.sum() <= 1.05 * truth.contact.sum()  # not grown by the blur
    both = shape.contact & truth.contact
    error = shape.heights[both] - heights[both]
    sigma = 0.01 * SPEC.full_scale
    # seeds 0-9: at most 5.4, 9.3 and 8.1 um for sigma = 5 um, most of it the error of delta
    # (the 5 % rule: 9.7, 16.2 and 8.3 um on average over seeds 0-2)
    assert np.sqrt(np.mean(error**2)) < 2.0 * sigma


def test_linear_and_nonneg_methods_test_the_pressure_against_its_noise():
    heights, truth, frame = _pressed("edge")
    pressure = truth.pressure
    weak = truth.contact & (pressure < 0.05 * pressure.max())
    assert weak.sum() == 14  # the outer row of the edge's three
    significant = recover_shape(frame, SPEC, method="nonneg")
    assert np.array_equal(significant.contact, truth.contact)
    fraction = recover_shape(frame, SPEC, method="nonneg", contact_fraction=0.05)
    assert fraction.contact.sum() == 34 and not (fraction.contact & weak).any()
    kept = fraction.reconstruction.pressure
    assert np.array_equal(fraction.contact, kept > 0.05 * kept.max())


@pytest.mark.parametrize(
    ("method", "rule"),
    [("tikhonov", "gcv"), ("tikhonov", "lcurve"), ("tikhonov", None), ("tsvd", None),
     ("nonneg", None), ("tv", None)],
)  # fmt: skip
def test_a_clean_frame_does_not_light_up_the_array(method, rule):
    # no noise to test against: the linear estimate's ringing and an iterative solve's
    # leftovers set the threshold (they read 180-758 of 1024 cells for the sphere's 44)
    _, truth, frame = _pressed("sphere", (0.0, 0.0))
    options = {} if rule is None else {"regularization": rule}
    for noisy in (frame, _noisy(frame, 1e-4, 0)):
        shape = recover_shape(noisy, SPEC, method=method, **options)
        assert shape.contact.sum() <= 1.25 * truth.contact.sum()
        assert _iou(shape.contact, truth.contact) >= 0.8


def test_the_threshold_is_kappa_times_the_noise_std():
    _, _, frame = _pressed("punch")
    noisy = _noisy(frame, 0.01, 0)
    loose = recover_shape(noisy, SPEC, method="tikhonov", significance=1.0)
    strict = recover_shape(noisy, SPEC, method="tikhonov", significance=4.0)
    assert np.allclose(strict.threshold, 4.0 * loose.threshold)
    assert strict.contact.sum() < loose.contact.sum()
    assert np.array_equal(loose.contact, loose.reconstruction.pressure > loose.threshold)


def test_coarse_array_finds_the_contact_but_not_the_heights():
    # reflective8x8: 3 mm taxels; a 12.5 mm sphere pressed centrally with 0.2 N touches the
    # 4 middle cells, each 2.1 mm from its apex (the 5 % rule found 13 cells at 1 % noise)
    sensor = make_sensor("reflective8x8")
    spec = spec_from_sensor(sensor)
    indenter = make_indenter("sphere")
    pressed = sensor.press(indenter, normal_force=0.2)
    truth = pressed.contact
    rng = np.random.default_rng(0)
    frame = pressed.quantity + rng.normal(0.0, 0.01 * spec.full_scale, spec.shape)
    shape = recover_shape(frame, spec)
    assert np.array_equal(shape.contact, truth.contact) and truth.contact.sum() == 4
    # the cells' common height above the apex is not in the readings: they read ~0
    true_heights = indenter.on_grid(spec.load_shape, spec.load_pitch)[truth.contact]
    assert np.allclose(true_heights, 0.36e-3, rtol=0.05)
    assert np.abs(shape.heights[truth.contact]).max() < 0.02e-3


def test_dead_taxels_may_read_nan():
    _, truth, frame = _pressed("sphere")
    frame = frame.copy()
    frame[0, 0] = np.nan
    shape = recover_shape(frame, SPEC, dead_taxels=[(0, 0)])
    assert np.array_equal(shape.contact, truth.contact)


def test_an_unloaded_frame_has_no_contact():
    shape = recover_shape(np.zeros(SPEC.shape), SPEC)
    assert not shape.contact.any() and shape.indentation == 0.0
    assert np.all(np.isinf(shape.heights))


@pytest.mark.parametrize(
    ("frame", "sensor", "options", "match"),
    [
        (np.zeros((32, 32)), SPEC.with_changes(quantity="stress", depth=1e-3), {}, "`sensor`"),
        (np.full((32, 32), np.nan), SPEC, {}, "`frame` must be finite"),
        (np.zeros((2, 32, 32)), SPEC, {}, "`frame` must be one frame"),
        (np.zeros((16, 16)), SPEC, {}, "`frame` must have shape"),
        (np.zeros((32, 32)), SPEC, {"contact_fraction": 0.0}, "`contact_fraction`"),
        (np.zeros((32, 32)), SPEC, {"contact_fraction": 1.5}, "`contact_fraction`"),
        (np.zeros((32, 32)), SPEC, {"significance": -1.0}, "`significance`"),
        (np.zeros((32, 32)), SPEC, {"method": "magic"}, "`method`"),
    ],
    ids=[
        "stress",
        "nan",
        "batch",
        "shape",
        "fraction-0",
        "fraction-1.5",
        "significance",
        "method",
    ],
)
def test_bad_input_names_the_parameter(frame, sensor, options, match):
    with pytest.raises(ValueError, match=match):
        recover_shape(frame, sensor, **options)
