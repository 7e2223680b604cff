"""The centre of pressure read through an FTIR sensor's response (`features._pressure_centre`)."""

from dataclasses import replace

import cv2
import numpy as np
import pytest
from scipy import special

import taxel.features._contact as contact_module
from taxel.features import contact_regions, extract, prepare
from taxel.features._pressure_centre import _background, _box_counts, _box_sums, _grown
from taxel.features._response import (
    ReadBack,
    forward_model,
    light_image,
    read_back,
    signed_pressure,
)
from taxel.mechanics import make_indenter
from taxel.reconstruction import extend_readings, spec_from_sensor
from taxel.sensor import ArrayGeometry, make_sensor


@pytest.fixture(scope="module")
def vhdta():
    return make_sensor("vhdta128")


def _pressed(sensor, name, force, position, seed=5):
    frame = sensor.press(
        make_indenter(name), normal_force=force, position=position, angle=0.3, rng=seed
    )
    x, y = sensor.load_grid.coordinates()
    pressure = frame.contact.pressure
    truth = np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()
    return frame.raw, truth


def _error(centroid_m, truth, sensor):
    return float(np.linalg.norm(np.subtract(centroid_m, truth)) / sensor.taxel_pitch[0])


def test_the_table_read_back_is_the_transducers_inverse(vhdta):
    raw, _ = _pressed(vhdta, "punch", 5.0, (1e-3, 0.0))
    wanted = vhdta.transducer.invert(raw, keep_sign=True)
    fast = signed_pressure(read_back(vhdta, raw, calibrated=False))
    assert fast.dtype == np.float32
    np.testing.assert_allclose(fast, wanted, rtol=1e-6, atol=1e-3)
    assert np.any(fast < 0) and np.any(fast > 1e4)  # noise below the level, contact above
    for dtype in (np.uint16, np.int64, np.float64):  # a 16-bit table, the law itself
        other = read_back(vhdta, raw.astype(dtype), calibrated=False)
        np.testing.assert_allclose(signed_pressure(other), wanted, rtol=1e-6, atol=1e-3)


def test_a_texture_is_centred_on_its_pressure_not_on_its_image(vhdta):
    # foam presses lightly over much of the array, beyond the contact mask, and its
    # grey level saturates where it presses hard
    raw, truth = _pressed(vhdta, "foam", 20.0, (1e-3, -2e-3))
    through = extract(raw, vhdta).contact
    weighed = extract(raw, vhdta.taxel_pitch, defects=True).contact  # the image weighed
    assert _error(through.centroid_m, truth, vhdta) < 0.2  # 0.12 taxel
    assert _error(weighed.centroid_m, truth, vhdta) > 1.0  # 1.15 taxel
    # with 4 grey levels of noise (4 % of the span) every window past the mask is noisier:
    # 0.10-0.91 taxel on these draws, still closer than the image's 0.78-1.54
    through, weighed = [], []
    for seed in range(4):
        noise = np.random.default_rng(seed).normal(0.0, 4.0, raw.shape)
        noisy = np.clip(raw + noise, 0, 255).round().astype(np.uint8)
        through.append(_error(extract(noisy, vhdta).contact.centroid_m, truth, vhdta))
        image = extract(noisy, vhdta.taxel_pitch, defects=True).contact.centroid_m
        weighed.append(_error(image, truth, vhdta))
    assert np.mean(through) < 0.8 * np.mean(weighed)


def test_a_tared_frame_reads_back_its_step_above_the_tare(vhdta):
    raw, truth = _pressed(vhdta, "foam", 20.0, (1e-3, -2e-3))
    unloaded = vhdta.frame_from_pressure(np.zeros(vhdta.load_grid.shape), rng=7).raw
    mean = np.mean(
        [vhdta.frame_from_pressure(np.zeros(vhdta.load_grid.shape), rng=s).raw for s in range(4)],
        axis=0,
    )
    for tare in (unloaded, mean):  # one frame (integer steps, a table) or a mean of four
        read = prepare(raw, vhdta, reference=tare).read_back
        assert read is not None and read.tare is tare
        light = (raw.astype(float) - tare) / 96.0  # the step above the tare, of the span
        top = 1.0 - 0.5 / 96.0
        wanted = 1330000.0 * 0.35 / np.sqrt(2.0) * special.erfinv(np.clip(light, -top, top))
        np.testing.assert_allclose(signed_pressure(read), wanted, rtol=1e-5, atol=1e-2)
        tared = extract(raw, vhdta, reference=tare).contact
        assert _error(tared.centroid_m, truth, vhdta) < 0.3


def test_a_small_contact_in_noise_keeps_to_its_mask(vhdta):
    # a pen tip: every window past the mask adds noise and no pressure, and Lepski's rule
    # keeps the mask; with a region, its centroid is the contact's
    raw, truth = _pressed(vhdta, "pen", 1.0, (2e-3, 1e-3))
    noisy = np.clip(raw + np.random.default_rng(2).normal(0.0, 4.0, raw.shape), 0, 255)
    contact = extract(noisy.round().astype(np.uint8), vhdta).contact
    assert _error(contact.centroid_m, truth, vhdta) < 0.1
    assert contact.regions[0].centroid_m == contact.centroid_m


def test_frames_the_model_does_not_read_back_weigh_the_image(vhdta):
    raw, _ = _pressed(vhdta, "punch", 5.0, (1e-3, 0.0))
    assert prepare(raw, vhdta).read_back is not None
    assert prepare(raw.astype(float), vhdta, calibrated=True).read_back is None
    with pytest.raises(ValueError, match=r"`image` holds integers \(uint8\), the sensor's raw"):
        prepare(raw, vhdta, calibrated=True)
    assert prepare(raw, vhdta.taxel_pitch).read_back is None
    resistive = make_sensor("resistive16")
    assert prepare(np.zeros(resistive.shape), resistive).read_back is None
    flat = replace(vhdta, transducer=replace(vhdta.transducer, textured=False))
    assert prepare(raw, flat).read_back is None
    # a background darker than the camera's unloaded level: not the model's frame
    frame = np.full((128, 128), 20, np.uint8)
    frame[40, 30:90] = 200
    with_sensor = extract(frame, vhdta, defects=False).contact
    image_only = extract(frame, vhdta.taxel_pitch, defects=False).contact
    assert with_sensor.centroid_m == image_only.centroid_m
    assert with_sensor.centroid_index == pytest.approx((40.0, 59.5), abs=0.01)


def test_a_contact_the_edge_cuts_is_centred_on_its_pressure(vhdta):
    # a punch pressed half off the array and a washer at its edge: the cover spreads part
    # of their load beyond the edge, where no taxel feels it, so that weighing the exact
    # (noise-free) felt pressure over the whole array is 0.90 and 0.53 taxel off; the
    # windows run on into the array grown by what the load on the array presses there
    for name, position, felt_error in (
        ("punch", (16e-3, 3e-3), 0.8),
        ("washer", (0.0, 15.5e-3), 0.5),
    ):
        frame = vhdta.press(
            make_indenter(name), normal_force=10.0, position=position, angle=0.3, rng=5
        )
        x, y = vhdta.load_grid.coordinates()
        pressure, felt = frame.contact.pressure, frame.quantity
        truth = np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()
        taxel_x, taxel_y = vhdta.geometry.positions()
        felt_centre = np.array([(felt * taxel_x).sum(), (felt * taxel_y).sum()]) / felt.sum()
        assert _error(felt_centre, truth, vhdta) > felt_error
        assert _error(extract(frame.raw, vhdta).contact.centroid_m, truth, vhdta) < 0.25


@pytest.mark.parametrize("reach", [13, 14])  # odd or even: blocks straddle the array's edge
def test_the_grown_array_on_blocks_keeps_the_centre(vhdta, reach):
    # solved on 2 x 2 blocks of taxels, beyond the edges it holds 94-96 % of what the
    # solution on every taxel holds; the centres of the two grown arrays are 0.02 taxel apart
    for name, position in (("punch", (16e-3, 3e-3)), ("washer", (0.0, 15.5e-3))):
        frame = vhdta.press(
            make_indenter(name), normal_force=10.0, position=position, angle=0.3, rng=5
        )
        read = prepare(frame.raw, vhdta).read_back
        pressure, model = signed_pressure(read), forward_model(read)
        blocks = _grown(model, pressure, reach)
        fine = extend_readings(model, cv2.medianBlur(pressure, 3), reach)  # as `_grown` does
        fine[reach:-reach, reach:-reach] = pressure
        assert blocks.shape == fine.shape == (128 + 2 * reach,) * 2
        np.testing.assert_array_equal(blocks[reach:-reach, reach:-reach], pressure)
        beyond = (blocks.sum() - pressure.sum()) / (fine.sum() - pressure.sum())
        assert 0.9 < beyond < 1.0

        def centre(grown):
            rows, cols = np.indices(grown.shape)
            return np.array([(grown * rows).sum(), (grown * cols).sum()]) / grown.sum()

        assert np.abs(centre(blocks) - centre(fine)).max() < 0.05


def test_window_sums_from_the_integral_image():
    rng = np.random.default_rng(1)
    pressure = rng.normal(size=(20, 30)).astype(np.float32)
    boxes = [(0, 0, 20, 30), (3, 4, 9, 17), (5, 5, 6, 6), (0, 2, 20, 3)]
    y, x = np.indices(pressure.shape)
    # on the array itself, and on it grown by 2 taxels, whose indices start at -2
    for origin in (0, 2):
        shifted = [tuple(v - origin for v in box) for box in boxes]
        sums = _box_sums(pressure, shifted, origin)
        for column, (r0, c0, r1, c1) in enumerate(boxes):
            w, yy, xx = (a[r0:r1, c0:c1] for a in (pressure.astype(float), y - origin, x - origin))
            wanted = [w.sum(), (w * yy).sum(), (w * xx).sum()]
            np.testing.assert_allclose(sums[column], wanted, rtol=1e-9, atol=1e-9)
            counts = [w.size, yy.sum(), xx.sum(), (yy**2 + xx**2).sum()]
            np.testing.assert_array_equal(_box_counts(shifted[column]), counts)


def test_oblong_taxels_are_refused_after_the_defects_are_removed(vhdta):
    # the defect removal once marked every opened frame as a resampled hexagonal one,
    # which let oblong taxels through to the contact type
    oblong = replace(
        vhdta, geometry=ArrayGeometry(128, 128, (0.25e-3, 0.3e-3), layout="rectangular")
    )
    raw, _ = _pressed(vhdta, "punch", 5.0, (1e-3, 0.0))
    prepared = prepare(raw, oblong)
    assert prepared.defects_removed and not prepared.hexagonal
    with pytest.raises(ValueError, match="square taxels for the contact type"):
        extract(raw, oblong)


def test_a_brighter_camera_or_a_hot_pixel_far_away_leaves_the_centre(vhdta):
    # a camera 3 grey levels brighter than the model everywhere: its background, flat
    # beyond the contact's reach, is taken out; a hot pixel there is out of every window
    pen, _ = _pressed(vhdta, "pen", 1.0, (2e-3, 1e-3))
    border, _ = _pressed(vhdta, "punch", 5.0, (15.5e-3, 0.0))  # cut by the array's edge
    for raw in (pen, border):
        centre = np.array(extract(raw, vhdta).contact.centroid_index)
        brighter = np.clip(raw.astype(int) + 3, 0, 255).astype(np.uint8)
        hot = raw.copy()
        hot[5, 5 if raw is border else 120] = 255
        for frame in (brighter, hot):
            moved = np.array(extract(frame, vhdta).contact.centroid_index) - centre
            assert np.hypot(*moved) < 0.1


def test_a_duck_typed_sensor_may_give_its_shape_as_an_array(vhdta):
    raw, _ = _pressed(vhdta, "pen", 1.0, (2e-3, 1e-3))

    class Camera:
        taxel_pitch = vhdta.taxel_pitch
        cover = vhdta.cover
        transducer = vhdta.transducer
        readout = vhdta.readout
        shape = np.array(vhdta.shape)

    read = read_back(Camera(), raw, calibrated=False)
    assert read is not None
    with_array = extract(raw, Camera()).contact.centroid_index
    assert with_array == pytest.approx(extract(raw, vhdta).contact.centroid_index, abs=1e-9)


def test_without_a_forward_model_the_windows_stop_at_the_array_s_edges(vhdta):
    frame = vhdta.press(
        make_indenter("punch"), normal_force=10.0, position=(16e-3, 3e-3), angle=0.3, rng=5
    )
    x, y = vhdta.load_grid.coordinates()
    pressure = frame.contact.pressure
    truth = np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()

    class Camera:  # a camera of its own: no forward model
        taxel_pitch = vhdta.taxel_pitch
        cover = vhdta.cover
        transducer = vhdta.transducer
        readout = vhdta.readout
        shape = vhdta.shape

    class ModelledCamera(Camera):
        def forward_model_spec(self):
            return spec_from_sensor(vhdta)

    assert forward_model(read_back(Camera(), frame.raw, calibrated=False)) is None
    assert _error(extract(frame.raw, Camera()).contact.centroid_m, truth, vhdta) > 0.5  # 0.78
    modelled = extract(frame.raw, ModelledCamera()).contact.centroid_m
    assert modelled == pytest.approx(extract(frame.raw, vhdta).contact.centroid_m, abs=1e-12)
    assert _error(modelled, truth, vhdta) < 0.25


def test_a_hot_pixel_is_not_load_at_the_edge_or_in_the_windows(vhdta):
    # an edge near the array's bottom edge: a hot pixel on the edge row was carried beyond
    # it by the load that explains it (0.46 taxel off), one far up among the windows
    # weighed as load (0.22 off); both are defects the cover cannot make (0.03 off)
    pitch = vhdta.taxel_pitch[0]
    frame = vhdta.press(
        make_indenter("edge"), normal_force=13.0, position=(14 * pitch, 61.5 * pitch),
        angle=1.2, rng=1,
    )  # fmt: skip
    x, y = vhdta.load_grid.coordinates()
    pressure = frame.contact.pressure
    truth = np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()
    clean = _error(extract(frame.raw, vhdta).contact.centroid_m, truth, vhdta)
    assert clean < 0.05
    for row in (127, 126, 0):
        hot = frame.raw.copy()
        hot[row, 88] = 255
        assert _error(extract(hot, vhdta).contact.centroid_m, truth, vhdta) < clean + 0.02


def _truth(sensor, frame):
    x, y = sensor.load_grid.coordinates()
    pressure = frame.contact.pressure
    return np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()


def test_a_noise_free_float_frame_at_the_edge_is_read_back(vhdta):
    # its noise is 0: the background's checks take a grey level's rounding noise (they
    # divided by zero)
    frame = vhdta.press(make_indenter("pen"), normal_force=5.0, position=(15.5e-3, 3e-3), rng=1)
    ftir = vhdta.transducer
    quantity = np.asarray(frame.quantity, float)
    light = ftir.light_fraction(quantity) + ftir.scratches(quantity.shape)
    image = ftir.dark_level + (ftir.bright_level - ftir.dark_level) * light
    assert _error(extract(image, vhdta).contact.centroid_m, _truth(vhdta, frame), vhdta) < 0.1


def test_a_camera_offset_under_a_grey_level_leaves_a_large_contact(vhdta):
    # a washer whose reach covers half the array: 0.2-0.7 grey levels of offset moved it
    # 0.34-1.11 taxels when a faintly lit background added the whole array as a window
    frame = vhdta.press(make_indenter("washer"), normal_force=40.0, position=(4e-3, -3e-3), rng=0)
    noise = np.random.default_rng(0).normal(0.0, 1.0, frame.raw.shape)
    for offset in (0.2, 0.7):
        raw = np.clip(np.rint(frame.raw + offset + noise), 0, 255).astype(np.uint8)
        centroid = extract(raw, vhdta).contact.centroid_m
        assert _error(centroid, _truth(vhdta, frame), vhdta) < 0.1  # 0.04


def test_under_a_thin_cover_a_lone_bright_taxel_is_a_contact(vhdta):
    # a 0.3 mm cover on 1 mm taxels: a pen lights about one taxel, which is no defect
    # (taken for one and replaced by its neighbours' median: 0.23 taxel off in the middle,
    # 0.57 at the edge; 0.01 and 0.04 now)
    thin = replace(
        vhdta,
        geometry=ArrayGeometry(32, 32, (1e-3, 1e-3), layout="square"),
        cover=replace(vhdta.cover, depth=0.3e-3, thickness=0.3e-3),
        transducer=replace(vhdta.transducer, scratch_count=0),
    )
    for position in ((0.0, 0.0), (15.4e-3, 3e-3)):
        frame = thin.press(make_indenter("pen"), normal_force=1.0, position=position, rng=0)
        centroid = extract(frame.raw, thin).contact.centroid_m
        assert _error(centroid, _truth(thin, frame), thin) < 0.1


def test_a_forward_model_that_does_not_fit_the_sensor_is_not_used(vhdta):
    raw, _ = _pressed(vhdta, "punch", 5.0, (1e-3, 0.0))

    class Camera:
        taxel_pitch = vhdta.taxel_pitch
        cover = vhdta.cover
        transducer = vhdta.transducer
        readout = vhdta.readout
        shape = vhdta.shape
        spec = spec_from_sensor(vhdta)

        def forward_model_spec(self):
            if self.spec is None:
                raise NotImplementedError("no model of this camera")
            return self.spec

    camera = Camera()
    assert forward_model(read_back(camera, raw, calibrated=False)) == camera.spec
    camera.spec = None  # asked for each time: a duck-typed sensor may change
    assert forward_model(read_back(camera, raw, calibrated=False)) is None
    extract(raw, camera)
    camera.spec = spec_from_sensor(vhdta).with_changes(taxel_pitch=0.2578125)  # in mm
    assert forward_model(read_back(camera, raw, calibrated=False)) is None


def test_a_reference_from_the_same_camera_takes_its_offset_under_a_texture(vhdta):
    # foam over the array leaves no background to show a brighter camera: read against the
    # model's dark level the offset is light contact, read against the camera's own
    # unloaded frame it is gone
    raw, truth = _pressed(vhdta, "foam", 20.0, (1e-3, -2e-3))
    rest = vhdta.frame_from_pressure(np.zeros(vhdta.load_grid.shape), rng=9).raw
    brighter, reference = (
        np.clip(a.astype(int) + 6, 0, 255).astype(np.uint8) for a in (raw, rest)
    )
    assert _error(extract(brighter, vhdta).contact.centroid_m, truth, vhdta) > 1.0  # 1.65
    tared = extract(brighter, vhdta, reference=reference).contact
    assert _error(tared.centroid_m, truth, vhdta) < 0.2  # 0.10


def _image_weighed(frame, sensor):
    prepared = prepare(frame, sensor)
    return contact_regions(replace(prepared, read_back=None)).centroid_index


def test_another_glass_is_not_read_back(vhdta):
    # the model's scratches subtracted where this glass has none read as dark streaks in
    # the background, which light contact cannot make: the image is weighed
    other = replace(vhdta, transducer=replace(vhdta.transducer, scratch_seed=1986))
    raw, _ = _pressed(other, "punch", 5.0, (1e-3, 0.0))
    assert extract(raw, vhdta).contact.centroid_index == _image_weighed(raw, vhdta)
    own, _ = _pressed(vhdta, "punch", 5.0, (1e-3, 0.0))
    assert extract(own, vhdta).contact.centroid_index != _image_weighed(own, vhdta)


def test_a_texture_lighting_the_background_is_not_another_glass(vhdta):
    # light contact only brightens: beyond a texture's reach most taxels are lit (here
    # by 5 grey levels) and the noise leaves a few a grey level below the unloaded one,
    # which are no dark streaks; 10 levels below it they are
    tare = np.full((128, 128), 24, np.uint8)
    frame = tare + np.uint8(5)
    frame.flat[::50] = 23
    far = np.arange(frame.size)
    assert _background(light_image(ReadBack(vhdta.transducer, frame, tare)), far, 1.0) == (
        5.0,
        0.0,
        0.0,
    )
    frame.flat[::50] = 14
    assert _background(light_image(ReadBack(vhdta.transducer, frame, tare)), far, 1.0) is None


def test_a_texture_s_faint_light_beyond_its_reach_is_not_an_offset(vhdta):
    # coarse foam at 30 N lights the 23 % of the array beyond its reach by 1.2 grey
    # levels on average, under 2.4 levels of noise: flat as a camera's offset, but taken out
    # as one it put the centre 3.1 taxels off (1.2 now: the texture's light contact reaches
    # farther than its mask's reach, and so beyond the windows)
    foam = make_indenter("foam", cell_size=2.12e-3, depth=0.484e-3, seed=779)
    frame = vhdta.press(foam, normal_force=30.0, position=(6.6e-3, 0.74e-3), angle=3.1, rng=5)
    x, y = vhdta.load_grid.coordinates()
    pressure = frame.contact.pressure
    truth = np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()
    noise = np.random.default_rng(1).normal(0.0, 2.0, frame.raw.shape)
    raw = np.clip(frame.raw + noise, 0, 255).round().astype(np.uint8)
    assert _error(extract(raw, vhdta).contact.centroid_m, truth, vhdta) < 1.5


def _two_pens(sensor):
    """The pressure of two pens far apart, its centroid [m], and its frame (float)."""
    x, y = sensor.load_grid.coordinates()
    pressure = sum(
        sensor.press(make_indenter("pen"), normal_force=force, position=at, rng=0).contact.pressure
        for force, at in ((1.0, (-13e-3, -13e-3)), (0.5, (13e-3, 13e-3)))
    )
    truth = np.array([(pressure * x).sum(), (pressure * y).sum()]) / pressure.sum()
    return truth, sensor.frame_from_pressure(pressure, rng=3).raw.astype(float)


def test_a_camera_s_small_offset_under_two_pens_is_taken_out(vhdta):
    # two pens far apart: under the union of their windows a camera offset weighs as much
    # as the pens. Levels over 3 standard errors of their mean are taken out: offsets of
    # -0.2 to 0.45 grey levels put the pair 2.65-8.0 taxels off when only those over 0.5
    # were (2.01 without an offset)
    truth, unlit = _two_pens(vhdta)
    clean = extract(unlit, vhdta).contact.centroid_m
    assert _error(clean, truth, vhdta) < 2.1
    for offset in (-0.2, 0.1, 0.2, 0.3, 0.45, 0.7):
        moved = extract(unlit + offset, vhdta).contact.centroid_m
        assert moved == pytest.approx(clean, abs=0.01 * vhdta.taxel_pitch[0])
    # under half a grey level of tilt (left in: see `_OFFSET`), the level where the
    # background lies is still taken out: 0.3 and a ramp of 0.15 across, 9.5 -> 1.6
    ramped = unlit + 0.3 + np.linspace(0.0, 0.15, unlit.shape[1])[None, :]
    assert _error(extract(ramped, vhdta).contact.centroid_m, truth, vhdta) < 2.0


def test_a_level_without_a_tilt_is_taken_out_when_significant(vhdta):
    # 0.2 grey levels on 16384 taxels (every 3rd read) of 1 level of noise: 0.014 of
    # standard error
    tare = np.full((128, 128), 24.0)
    noise = np.random.default_rng(4).normal(0.0, 1.0, tare.shape)
    far = np.arange(tare.size)
    lit = light_image(ReadBack(vhdta.transducer, tare + 0.2 + noise, tare))
    start, per_row, per_col = _background(lit, far, 1.0)
    assert (per_row, per_col) == (0.0, 0.0)
    assert start == pytest.approx(0.2, abs=0.03)
    # a level within 3 standard errors is none: 0.05 on 900 taxels (300 read: 0.058)
    few = _background(
        light_image(ReadBack(vhdta.transducer, tare + 0.05 + noise, tare)), far[:900], 1.0
    )
    assert few == (0.0, 0.0, 0.0)


def test_a_read_back_far_from_the_image_centre_is_not_kept(vhdta, monkeypatch):
    # the same contact weighed two ways: a read-back more than two cover depths (7.8
    # taxels) from the image's centre weighs what the frame's model gets wrong, not the
    # contact: the image's centre is kept; within them, the read-back's
    pen, _ = _pressed(vhdta, "pen", 1.0, (2e-3, 1e-3))
    weighed = _image_weighed(pen, vhdta)
    for shift, kept in ((9.0, weighed), (6.0, (weighed[0] + 6.0, weighed[1]))):
        centre = (weighed[0] + shift, weighed[1])
        monkeypatch.setattr(contact_module, "pressure_centre", lambda *_, c=centre: c)
        assert extract(pen, vhdta).contact.centroid_index == pytest.approx(kept)
