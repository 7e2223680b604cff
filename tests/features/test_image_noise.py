"""The noise the contact thresholds count in, and the unloaded reference frame (tare)."""

import math
from dataclasses import astuple

import numpy as np
import pytest

from taxel.features import (
    classify_contact,
    contact_plane,
    detect_edges,
    detect_holes,
    detect_slots,
    extract,
    find_contact,
    prepare,
    texture_measures,
)
from taxel.features._noise import noise_from_residual
from taxel.mechanics import make_indenter
from taxel.sensor import make_sensor


def test_grouped_median_of_quantised_residuals():
    # |r| sorted: 0, 0, 0, 1/4, 1/2; the median falls in the class of 0, which stands
    # for [0, 1/8): 2.5 of its 3 values lie below the median -> 1/8 * 2.5 / 3
    residual = np.array([0.0, -0.25, 0.0, 0.5, 0.0])
    expected = 1.4826 * (0.125 * 2.5 / 3) / math.sqrt(1.25)
    assert noise_from_residual(residual, quantum=0.25) == pytest.approx(expected, rel=1e-12)
    assert noise_from_residual(residual) == 0.0  # the plain median of the values


@pytest.mark.parametrize("sigma", [0.75, 1.0, 1.3, 2.0, 3.0])
def test_noise_of_an_integer_image_is_not_held_to_quarter_steps(sigma):
    # an 8-bit frame's Laplacian residual is a multiple of 1/4: its plain median jumps
    # between multiples (white noise of 0.75 codes read as 0.66 or 0.99 before)
    rng = np.random.default_rng(7)
    analog = 40.0 + sigma * rng.standard_normal((128, 128))
    image = np.round(analog)
    truth = float(np.std(image - 40.0))  # the rounding's own noise included
    estimate = prepare(image.astype(np.uint8), 0.25e-3).raw_noise
    assert estimate == pytest.approx(truth, rel=0.05)
    # a float image: the plain median, its residual is not quantised
    assert prepare(analog, 0.25e-3).raw_noise == pytest.approx(sigma, rel=0.05)


@pytest.fixture(scope="module")
def vhdta():
    return make_sensor("vhdta128")


@pytest.fixture(scope="module")
def unloaded(vhdta):
    rest = np.zeros(vhdta.load_grid.shape)
    frames = [vhdta.frame_from_pressure(rest, rng=100 + seed).raw for seed in range(28)]
    return np.mean(frames[:8], axis=0), frames[8:]


def test_a_reference_frame_makes_blank_frames_blank(vhdta, unloaded):
    # where two scratches of the glass cross, a patch wider than the 3 x 3 opening stays
    # bright: a fixed pattern only the unloaded frame can take away
    reference, blank = unloaded
    assert sum(extract(frame, vhdta).contact.present for frame in blank) >= 2
    for frame in blank:
        features = extract(frame, vhdta, reference=reference)
        assert not features.contact.present and features.contact_type == "none"


def test_a_reference_frame_keeps_the_contact_and_its_detail(vhdta, unloaded):
    reference = unloaded[0]
    pressed = vhdta.press(
        make_indenter("box-edge"), normal_force=10.0, position=(2e-3, 1e-3), angle=0.7, rng=0
    )
    frame, pressure = pressed.raw, pressed.contact.pressure
    x, y = vhdta.load_grid.coordinates()
    truth = np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()
    plain = extract(frame, vhdta)
    tared = extract(frame, vhdta, reference=reference)
    assert tared.contact_type == plain.contact_type == "line"
    angle = abs((tared.shape.line.angle_rad - 0.7 + math.pi / 2) % math.pi - math.pi / 2)
    assert math.degrees(angle) < 2.0
    # weighing the image, the opening that removes scratches also trims the contact's fine
    # detail (0.38 taxel off the centre of pressure here); the reference takes the
    # scratches alone, and so does the sensor's read-back of the frame to pressure
    pitch = vhdta.taxel_pitch[0]
    opened = extract(frame, vhdta.taxel_pitch, defects=True)
    assert np.linalg.norm(np.subtract(opened.contact.centroid_m, truth)) > 0.3 * pitch
    assert np.linalg.norm(np.subtract(tared.contact.centroid_m, truth)) < 0.1 * pitch
    assert np.linalg.norm(np.subtract(plain.contact.centroid_m, truth)) < 0.1 * pitch
    assert not prepare(frame, vhdta, reference=reference).defects_removed
    assert prepare(frame, vhdta, reference=reference, defects=True).defects_removed


def test_a_reference_of_another_shape_or_with_nan_is_refused(vhdta):
    frame = np.zeros((128, 128), np.uint8)
    with pytest.raises(ValueError, match=r"`reference` must have the image's shape \(128, 128\)"):
        extract(frame, vhdta, reference=np.zeros((64, 64)))
    bad = np.zeros((128, 128))
    bad[3, 4] = np.nan
    with pytest.raises(ValueError, match="`reference` must be finite everywhere, got 1 NaN"):
        extract(frame, vhdta, reference=bad)


def test_each_feature_takes_the_reference_and_agrees_with_extract(vhdta, unloaded):
    reference, blank = unloaded
    frame = next(f for f in blank if extract(f, vhdta).contact.present)
    assert find_contact(frame, vhdta).present  # the glass's pattern, as read
    assert not find_contact(frame, vhdta, reference=reference).present
    assert classify_contact(frame, vhdta, reference=reference).contact_type == "none"
    assert detect_edges(frame, vhdta, reference=reference).n_edges == 0
    pressed = vhdta.press(
        make_indenter("washer"), normal_force=10.0, position=(1e-3, -1e-3), rng=3
    ).raw
    whole = extract(pressed, vhdta, reference=reference)
    assert whole.holes.count == 1
    assert find_contact(pressed, vhdta, reference=reference) == whole.contact
    shape = classify_contact(pressed, vhdta, reference=reference)
    # the same type and fits (extract shares the band's sums between the fits: rounding)
    assert (shape.contact_type, shape.n_edges) == (whole.contact_type, whole.shape.n_edges)
    for found, expected in ((shape.line, whole.shape.line), (shape.circle, whole.shape.circle)):
        flat, flat_expected = (np.hstack(astuple(fit)).astype(float) for fit in (found, expected))
        np.testing.assert_allclose(flat, flat_expected, rtol=1e-9)
    assert detect_holes(pressed, vhdta, reference=reference) == whole.holes
    assert detect_slots(pressed, vhdta, reference=reference) == whole.slots
    assert contact_plane(pressed, vhdta, reference=reference) == whole.plane
    assert texture_measures(pressed, vhdta, reference=reference) == whole.texture


def test_edges_of_a_blurred_rim_come_whole_given_the_sensor(vhdta, unloaded):
    # a washer's rims, blurred by the 1 mm cover (3 taxels at half height): Canny's ridge
    # lies up to that far inside the contact's outline, which a band of 2 taxels cut up
    reference = unloaded[0]
    frame = vhdta.press(make_indenter("washer"), normal_force=10.0, rng=3).raw
    edges = detect_edges(frame, vhdta, reference=reference)
    assert edges.n_edges == 2  # the outer rim and the hole's wall
    assert detect_edges(frame - reference, vhdta.taxel_pitch).n_edges >= 8  # a bare pitch
