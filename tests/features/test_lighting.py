"""Uneven lighting of a raw frame: `features._lighting` and the read-back's level."""

import numpy as np
import pytest

from taxel.features import extract, prepare
from taxel.features._lighting import background_tilt
from taxel.features._pressure_centre import _background
from taxel.features._response import ReadBack, light_image
from taxel.mechanics import make_indenter
from taxel.sensor import make_sensor


@pytest.fixture(scope="module")
def vhdta():
    return make_sensor("vhdta128")


def _pressed(sensor, name, force, position):
    frame = sensor.press(
        make_indenter(name), normal_force=force, position=position, angle=0.3, rng=5
    )
    x, y = sensor.load_grid.coordinates()
    pressure = frame.contact.pressure
    truth = np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()
    return frame.raw, truth


def _ramped(raw, rise):
    """`raw` under a ramp of `rise` grey levels across its columns, and 1 level of noise."""
    ramp = np.linspace(0.0, rise, raw.shape[1])[None, :]
    dither = np.random.default_rng(0).uniform(-0.5, 0.5, raw.shape)  # a ramp, not steps
    noise = np.random.default_rng(1).normal(0.0, 1.0, raw.shape)
    return np.clip(np.rint(raw + ramp + dither + noise), 0, 255).astype(np.uint8)


def _error(centroid_m, truth, sensor):
    return float(np.linalg.norm(np.subtract(centroid_m, truth)) / sensor.taxel_pitch[0])


@pytest.mark.parametrize("rise", [1.5, 6.0])
def test_a_ramp_across_the_array_leaves_an_edge_where_it_lies(vhdta, rise):
    # the contact is cut a few noise sigmas above the background's minimum: the ramp's
    # lit side joined the edge (16.7 taxels off at 6 grey levels, read as a surface; 6.5
    # at 1.5). Its tilt is taken out first (0.06 and 0.03 taxel now)
    raw, truth = _pressed(vhdta, "edge", 4.0, (1e-3, 2e-3))
    features = extract(_ramped(raw, rise), vhdta)
    assert features.contact_type == "line"
    assert _error(features.contact.centroid_m, truth, vhdta) < 0.2
    tilt = prepare(_ramped(raw, rise), vhdta).tilt
    assert tilt is not None
    assert tilt[:, -1].mean() - tilt[:, 0].mean() == pytest.approx(rise, rel=0.05)
    assert np.ptp(tilt[:, 0]) < 0.05 * rise  # no tilt down the columns


def test_a_ramp_that_lifts_most_of_the_array_over_the_cut_is_taken_out(vhdta):
    # 3 grey levels across, under a cut 3.4 above the baseline: the lit side joins the
    # edge and leaves under 15 % of the array as background, so the tilt is read away from
    # the seeds; taken out, it leaves the background again, which is how it is told from
    # a texture's faint light. It was kept only when it rose by the whole cut: the edge
    # read as a surface 27.7 taxels off (0.11 now)
    raw, truth = _pressed(vhdta, "edge", 2.0, (-4e-3, 3e-3))
    features = extract(_ramped(raw, 3.0), vhdta)
    assert features.contact_type == "line"
    assert _error(features.contact.centroid_m, truth, vhdta) < 0.2


@pytest.mark.parametrize("seed", [1, 3])
def test_a_texture_s_faint_light_read_away_from_the_seeds_is_no_tilt(vhdta, seed):
    # a screen pressed at 45 N lights the band of the array it leaves by a grey level or
    # two: too little background is left at the cut, and away from the seeds that faint
    # light looks like a tilt. Taken out, it would leave the screen over the cut still:
    # no tilt (3.3 and 4.1 taxels off when that test is skipped; 0.32 and 0.29)
    screen = make_indenter("screen", hole_diameter=3.39e-3, pitch=4.825e-3, seed=307)
    frame = vhdta.press(screen, normal_force=44.7, position=(2.815e-3, 0.319e-3), rng=seed)
    x, y = vhdta.load_grid.coordinates()
    pressure = frame.contact.pressure
    truth = np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()
    noise = np.random.default_rng(seed).normal(0.0, 0.0405 * 87.59, frame.raw.shape)
    raw = np.clip(np.rint(frame.raw + noise), 0, 255).astype(np.uint8)
    assert prepare(raw, vhdta).tilt is None
    assert _error(extract(raw, vhdta).contact.centroid_m, truth, vhdta) < 0.5


def test_a_small_ramp_is_taken_out_of_the_read_back(vhdta):
    # 1.5 grey levels across do not move the cut (no tilt taken out before it), but the
    # read-back weighs the background's light: a punch was 0.50 taxel off, 0.02 now
    raw, truth = _pressed(vhdta, "punch", 5.0, (-3e-3, 1e-3))
    ramped = _ramped(raw, 1.5)
    assert prepare(ramped, vhdta).tilt is None
    assert _error(extract(ramped, vhdta).contact.centroid_m, truth, vhdta) < 0.1


def test_an_evenly_lit_frame_has_no_tilt(vhdta):
    raw, _ = _pressed(vhdta, "edge", 4.0, (1e-3, 2e-3))
    noisy = _ramped(raw, 0.0)
    assert prepare(noisy, vhdta).tilt is None


def test_a_tilt_is_read_only_on_enough_background():
    y, x = np.mgrid[:64, :64].astype(np.float32)
    frame = 20.0 + 0.1 * x + np.random.default_rng(2).normal(0.0, 0.2, (64, 64)).astype(np.float32)
    lit = frame.copy()
    lit[4:60, 4:60] += 50.0  # a contact over all but a band 4 taxels wide: too little
    assert background_tilt(lit, 26.0, 38.0, 20.0, 0.2, 2.0) is None
    tilt = background_tilt(frame, 26.0, 38.0, 20.0, 0.2, 2.0)  # (the whole array: 6.3)
    assert tilt[0, -1] - tilt[0, 0] == pytest.approx(6.3, abs=0.1)
    # a tilt that would not move the cut is left (a quarter of the cut's 6 levels)
    small = 20.0 + 0.02 * x + np.random.default_rng(2).normal(0.0, 0.2, (64, 64))
    assert background_tilt(small.astype(np.float32), 26.0, 38.0, 20.0, 0.2, 2.0) is None


def test_a_tilt_in_noise_alone_is_not_read():
    flat = 20.0 + np.random.default_rng(3).normal(0.0, 1.0, (128, 128)).astype(np.float32)
    assert background_tilt(flat, 22.0, 30.0, 17.0, 1.0, 2.0) is None


def test_the_read_backs_level_is_a_plane(vhdta):
    # light above the unloaded level: a camera's offset of 2 grey levels and a ramp of
    # 3 across the columns, on every taxel beyond the contact's reach
    tare = np.full((128, 128), 24, np.uint8)
    cols = np.arange(128)[None, :]
    frame = (tare + np.rint(2.0 + 3.0 * cols / 127.0 + np.zeros((128, 1)))).astype(np.uint8)
    far = np.arange(frame.size)
    start, per_row, per_col = _background(
        light_image(ReadBack(vhdta.transducer, frame, tare)), far, 1.0
    )
    assert per_row == 0.0  # not significant: taken as none
    assert start == pytest.approx(2.0, abs=0.3)
    assert per_col * 127 == pytest.approx(3.0, abs=0.3)
