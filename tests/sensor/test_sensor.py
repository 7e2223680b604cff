"""The sensor model: presets, the mechanics -> transducer -> readout chain, noise switching."""

import numpy as np
import pytest

from taxel.mechanics import ElasticMaterial, hertz_sphere, make_indenter
from taxel.sensor import (
    PRESET_NAMES,
    ArrayGeometry,
    Cover,
    Readout,
    make_sensor,
    taxel_fields,
)

SILICONE = ElasticMaterial(1e6, 0.49)


@pytest.fixture(scope="module")
def presets():
    return {name: make_sensor(name) for name in PRESET_NAMES}


@pytest.mark.parametrize("name", PRESET_NAMES)
def test_every_preset_reads_a_press(presets, name):
    sensor = presets[name]
    frame = sensor.press(make_indenter("sphere"), normal_force=1.0, rng=0)
    expected = (sensor.shape[0] + sensor.shape[1],) if name == "microbend16" else sensor.shape
    assert frame.raw.shape == expected
    assert np.all(np.isfinite(frame.raw))
    low, high = sensor.signal_range
    assert low < high
    # the same seed gives the same frame; no seed gives the noise-free frame
    again = sensor.press(make_indenter("sphere"), normal_force=1.0, rng=0)
    assert np.array_equal(frame.raw, again.raw)


def test_vhdta128_is_the_ellis_seed_sensor(presets):
    sensor = presets["vhdta128"]
    assert sensor.shape == (128, 128)
    assert sensor.geometry.extent[0] == pytest.approx(33e-3)
    assert sensor.density_class == "VHDTA"
    assert sensor.full_scale == pytest.approx(60 * 6894.757)
    frame = sensor.press(make_indenter("sphere"), normal_force=12.0, rng=1)
    assert frame.raw.dtype == np.uint8  # an 8-bit camera image, as in the seed
    assert frame.raw.min() >= 20 and frame.raw.max() <= 130  # the seed's images: 24 to 120


def test_pressure_cells_feel_the_stress_transmitted_to_their_depth(presets):
    sensor = presets["resistive16"]
    frame = sensor.press(make_indenter("sphere", radius=5e-3), normal_force=2.0)
    assert np.allclose(frame.quantity, np.clip(-frame.fields.stress, 0, None))
    # the total of the stress at depth equals the applied force (equilibrium)
    cell = np.prod(sensor.taxel_pitch)
    assert -frame.fields.stress.sum() * cell == pytest.approx(2.0, rel=0.03)
    assert frame.fields.pressure.sum() * cell == pytest.approx(2.0, rel=1e-6)


def test_a_frame_computes_the_sensed_field_and_leaves_the_others_nan(presets):
    # vhdta128's FTIR cells read the stress at their depth; its displacement is not computed
    sensor = presets["vhdta128"]
    frame = sensor.press(make_indenter("sphere", radius=5e-3), normal_force=2.0)
    assert np.isfinite(frame.fields.stress).all() and np.isfinite(frame.fields.pressure).all()
    assert np.isnan(frame.fields.strain).all() and np.isnan(frame.fields.displacement).all()
    every = taxel_fields(frame.contact.pressure, sensor.load_grid, sensor.cover)
    assert np.array_equal(every.stress, frame.fields.stress)
    assert every.displacement.max() > 0  # the cover gives under the sphere
    assert np.isfinite(every.strain).all() and every.strain.min() < 0  # compressed


def test_contact_on_the_sensor_matches_hertz_when_well_resolved():
    sensor = make_sensor("vhdta128")
    frame = sensor.press(make_indenter("sphere", radius=6.25e-3), normal_force=1.0)
    # a 1 mm pad on glass is stiffer than a half-space: the contact is smaller than Hertz's
    hertz = hertz_sphere(1.0, 6.25e-3, sensor.cover.material.plane_strain_modulus)
    radius = np.sqrt(frame.contact.contact_area / np.pi)
    assert 0.5 * hertz.contact_radius < radius < hertz.contact_radius
    assert frame.contact.converged


def test_noise_is_switched_by_rng(presets):
    sensor = presets["resistive16"]
    indenter = make_indenter("edge")
    clean = sensor.press(indenter, normal_force=3.0)
    noisy = sensor.press(indenter, normal_force=3.0, rng=5)
    assert not np.array_equal(clean.raw, noisy.raw)
    assert np.abs(clean.raw.astype(float) - noisy.raw).max() < 50  # a few LSB of 4096


def test_dynamic_sensor_sees_only_change(presets):
    sensor = presets["piezo8x8"]
    frame = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 5e4))
    steps = np.repeat(frame.quantity[None], 2000, axis=0)  # a load held for 2 s at 1 kHz
    raw = sensor.read_sequence(steps)
    rest = sensor.readout_chain.apply(sensor.respond(np.zeros(sensor.shape)))
    # right after the step the output jumps; a second later the held load has faded
    assert np.abs(raw[0].astype(float) - rest).max() > 100
    assert np.abs(raw[-1].astype(float) - rest).max() <= 2


def test_readout_bits_and_faults():
    sensor = make_sensor("resistive16")
    faulty = type(sensor)(**{**sensor.__dict__, "readout": Readout(bits=8, dead=0.1, unit_seed=9)})
    frame = faulty.press(make_indenter("sphere"), normal_force=2.0)
    assert frame.raw.max() <= 255
    dead = faulty.readout_chain.pattern.faults.dead
    assert dead.sum() == round(0.1 * 256)
    assert np.all(frame.raw[dead] == 0)


def test_bad_sensor_specifications():
    with pytest.raises(ValueError, match="`name` must be one of vhdta128"):
        make_sensor("nonexistent")
    with pytest.raises(ValueError, match="`bits` must lie in \\[1, 24\\]"):
        Readout(bits=0)
    with pytest.raises(ValueError, match="`pitch` must be > 0"):
        from taxel.sensor import ArrayGeometry

        ArrayGeometry(4, 4, 0.0)
    sensor = make_sensor("resistive16")
    with pytest.raises(ValueError, match="`frame_rate` must be > 0"):
        type(sensor)(**{**sensor.__dict__, "frame_rate": 0.0})
    for levels in (3, 20.5, True):
        with pytest.raises(ValueError, match="`calibration_levels` must be an integer >= 4"):
            type(sensor)(**{**sensor.__dict__, "calibration_levels": levels})


def test_capacitive_cells_with_their_own_modulus_feel_the_stress(presets):
    # a dielectric of constrained modulus M is strained by sigma_z / M at the cell's depth
    sensor = presets["capacitive4x4"]
    frame = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 2e4))
    assert np.allclose(frame.quantity, frame.fields.stress / 1.0e6)
    assert frame.quantity.max() < -0.01  # compressed by more than 1 % everywhere
    rest = sensor.frame_from_pressure(np.zeros(sensor.load_grid.shape))
    assert np.all(frame.raw > rest.raw + 1000)  # 16-bit codes move with the load


@pytest.mark.parametrize("name", ["harmon10x20", "resistive16"])
def test_no_working_taxel_clips_below_full_scale(presets, name):
    # the ADC range covers the unit's gains, offsets and crosstalk (81 of resistive16's 256
    # taxels read the top code at full scale when it covered only the ideal signal)
    sensor = presets[name]
    top = 2**sensor.readout.bits - 1
    full = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, sensor.full_scale))
    rest = sensor.frame_from_pressure(np.zeros(sensor.load_grid.shape))
    assert full.raw.max() < top and rest.raw.min() > 0
    bottom, high = sensor.readout_chain.rails
    assert bottom <= sensor.signal_range[0] and high > sensor.signal_range[1]
    assert sensor.readout_chain.lsb == pytest.approx((high - bottom) / 4096)


@pytest.mark.parametrize(
    ("build", "error", "match"),
    [
        (lambda: ArrayGeometry(4, 4, 0.0), ValueError, "`pitch` must be > 0, got 0"),
        (lambda: ArrayGeometry(4, 4, (1e-3, -1e-3), "rectangular"), ValueError, "`pitch`"),
        (lambda: Readout(bits=25), ValueError, "`bits` must lie in \\[1, 24\\], got 25"),
        (lambda: Readout(bits=0), ValueError, "`bits` must lie in \\[1, 24\\], got 0"),
        (lambda: Readout(bits=8.5), TypeError, "`bits` must be an integer or None"),
        (lambda: Cover(SILICONE, depth=0.0), ValueError, "`depth` must be > 0, got 0"),
        (lambda: Cover(SILICONE, depth=-1e-3), ValueError, "`depth` must be > 0, got -0.001"),
        (lambda: make_sensor("vhdta256"), ValueError, "`name` must be one of vhdta128"),
        (lambda: make_indenter("cup"), ValueError, "`name` must be one of pen, sphere"),
    ],
)
def test_bad_specifications_name_the_parameter_and_value(build, error, match):
    with pytest.raises(error, match=match):
        build()


def test_harmon_array_output_stays_within_its_supply(presets):
    sensor = presets["harmon10x20"]
    low, high = sensor.signal_range  # the ideal output from rest to full scale, +-5 %
    assert high < sensor.transducer.supply_voltage
    assert sensor.transducer.respond(sensor.full_scale) == pytest.approx(4.5)


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda s: s.read(np.zeros((5, 5))), r"`quantity` must have shape \(\.\.\., 16, 16\)"),
        (lambda s: s.read(np.zeros(16)), r"got \(16,\)"),
        (lambda s: s.mean_reading(np.zeros((5, 5))), "`quantity` must have shape"),
        (lambda s: s.respond(np.zeros((16, 8))), "`quantity` must have shape"),
        (lambda s: s.read_sequence(np.zeros((16, 16))), r"`quantities` must have shape \(frames"),
        (lambda s: s.read_sequence(np.zeros((0, 16, 16))), "at least one frame, got 0"),
        (lambda s: s.read(np.ones((16, 16)) + 1j), "`quantity` must be real"),
    ],
)
def test_readings_of_frames_that_are_not_the_taxels_are_refused(call, match):
    sensor = make_sensor("resistive16")
    with pytest.raises((ValueError, TypeError), match=match):
        call(sensor)


def test_a_batch_of_frames_reads_as_each_frame():
    sensor = make_sensor("resistive16")
    quantities = np.stack([np.zeros(sensor.shape), np.full(sensor.shape, 0.5)])
    expected = [sensor.mean_reading(quantity) for quantity in quantities]
    np.testing.assert_allclose(sensor.mean_reading(quantities), expected)


@pytest.mark.parametrize("name", PRESET_NAMES)
def test_a_press_at_zero_force_reads_the_sensor_at_rest(presets, name):
    sensor = presets[name]
    rest = sensor.press(make_indenter("sphere"), normal_force=0.0, rng=5)
    assert rest.contact is not None and not rest.contact.contact.any()
    assert rest.contact.normal_force == 0.0 and rest.contact.converged
    # the raw frame of no pressure, through the same readout as a loaded press
    unloaded = sensor.frame_from_pressure(np.zeros(sensor.load_grid.shape), rng=5)
    np.testing.assert_array_equal(rest.raw, unloaded.raw)
    assert rest.raw.dtype == sensor.press(make_indenter("sphere"), normal_force=1.0).raw.dtype
    np.testing.assert_array_equal(rest.quantity, sensor.sensed_quantity(*_at_rest(sensor)))


def _at_rest(sensor):
    pressure = np.zeros(sensor.load_grid.shape)
    return pressure, sensor.fields(pressure)


@pytest.mark.parametrize(
    ("changes", "error", "match"),
    [
        ({"normal_force": -0.5}, ValueError, "`normal_force` must be >= 0, got -0.5"),
        ({"indenter": "sphere"}, TypeError, "`indenter` must be an Indenter, got 'sphere'"),
        ({"indenter": None}, TypeError, "`indenter` must be an Indenter, got None"),
        ({"position": (0,)}, ValueError, r"`position` must be an \(x, y\) pair, got \(0,\)"),
        ({"initial": 3}, TypeError, "`initial` must be a ContactResult, got 3"),
        ({"rng": "x"}, TypeError, "`rng` must be None, a numpy.random.Generator, an int seed"),
        ({"rng": -1}, ValueError, "`rng` seed must be >= 0, got -1"),
        ({"rng": 1.5}, TypeError, "`rng` must be None"),
    ],
)
def test_bad_press_arguments_name_the_parameter(changes, error, match):
    arguments = {"indenter": make_indenter("sphere"), "normal_force": 1.0} | changes
    with pytest.raises(error, match=match):
        make_sensor("resistive16").press(**arguments)


@pytest.mark.parametrize(
    ("name", "load", "match"),
    [
        (
            "reflective8x8",
            {"normal_force": 2.0, "position": (0.003, -0.002)},
            r"^pressing with 2 N closes reflective8x8's 1\.5 mm gap \(the cover would move "
            r"1\.53 mm\): `normal_force` must be smaller$",
        ),
        (
            "reflective8x8",
            {"indentation": 3e-3},
            r"^pressing with an indentation of 3 mm closes reflective8x8's 1\.5 mm gap .*: "
            r"`indentation` must be smaller$",
        ),
        (
            "capacitive4x4",
            {"normal_force": 500.0},
            r"^pressing with 500 N squeezes capacitive4x4's 0\.1 mm dielectric flat \(it would "
            r"be compressed by 464\.9 % of its thickness, and 100 % closes the gap\): "
            r"`normal_force` must be smaller$",
        ),
    ],
)
def test_a_press_past_the_transducers_end_names_the_load(name, load, match):
    # the transducers refused their own input (`displacement` < unloaded_gap, `strain` > -1)
    with pytest.raises(ValueError, match=match):
        make_sensor(name).press(make_indenter("sphere"), **load)


def test_press_reports_the_contact_solves_progress(presets):
    calls = []
    sensor = presets["resistive16"]
    sphere = make_indenter("sphere", radius=5e-3)
    frame = sensor.press(sphere, normal_force=2.0, progress=lambda *pair: calls.append(pair))
    iterations = frame.contact.n_iterations
    assert calls[:iterations] == [(k, 2000) for k in range(1, iterations + 1)]
    assert calls[-1] == (2000, 2000)  # converged early: the last call says done
    assert np.array_equal(frame.raw, sensor.press(sphere, normal_force=2.0).raw)
