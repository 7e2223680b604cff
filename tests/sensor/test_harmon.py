"""Harmon's criteria measured on simulated sensors: resolution, sensitivity, hysteresis."""

import dataclasses
import math

import numpy as np
import pytest

from taxel.mechanics import ElasticMaterial
from taxel.sensor import (
    ArrayGeometry,
    Cover,
    Readout,
    TactileSensor,
    calibrate,
    harmon_table,
    make_sensor,
    reading_step,
    two_point_resolution,
)
from taxel.sensor._harmon_measures import (
    hysteresis_width,
    monotonic_fraction,
    sensitivity_force,
    stability_change,
)
from taxel.transducers import ResistiveTransducer


@pytest.fixture(scope="module")
def tables():
    return {name: harmon_table(make_sensor(name), rng=0) for name in ("vhdta128", "harmon10x20")}


def _linear_resistive(**readout):
    return TactileSensor(
        name="linear",
        geometry=ArrayGeometry(8, 8, 2e-3),
        cover=Cover(ElasticMaterial(1e6, 0.49), depth=1e-3, thickness=1e-3),
        transducer=ResistiveTransducer(),  # V = R_f V_cc (1 + p / p_ref) / R_0
        readout=Readout(bits=12, **readout),
        full_scale=1e5,
    )


def test_vhdta128_resolution_is_measured_in_mm(tables):
    row = tables["vhdta128"].row("spatial resolution")
    assert row.unit == "m"
    # 1 mm of pad over 0.26 mm taxels: the pad, not the pitch, sets it
    assert row.value == pytest.approx(1.16e-3, abs=0.13e-3)
    assert row.value > 4 * make_sensor("vhdta128").taxel_pitch[1]
    assert row.passed is True
    assert tables["vhdta128"].resolution.resolved[-4:].all()


def test_harmon_array_just_misses_its_own_resolution(tables):
    # two peaks need a taxel between them: 1.5 mm pitch resolves 2.25 mm, not 2
    table = tables["harmon10x20"]
    assert table.row("spatial resolution").value == pytest.approx(2.25e-3)
    assert table.row("spatial resolution").passed is False
    assert table.row("array size").value == 200 and table.row("array size").passed
    assert table.row("sampling rate").value == 1000 and table.row("sampling rate").passed
    assert table.row("hysteresis").passed is False  # its readout has a 1 % loop
    assert table.row("dynamic range").value > 1000 and table.row("dynamic range").passed
    assert table.row("monotonic response").value == 1.0
    assert table.density_class == "HDTA"


def test_vhdta128_against_harmon(tables):
    table = tables["vhdta128"]
    assert table.row("sampling rate").passed is False  # a 30 Hz camera
    # 8-bit camera, 24 DN dark to 120 DN at full contact; at 60 psi the membrane's contact
    # fraction is erf(sqrt(2) p / (E* s)) of full contact
    ftir = make_sensor("vhdta128").transducer
    fraction = math.erf(math.sqrt(2) * 60 * 6894.757 / (ftir.contact_modulus * ftir.rms_slope))
    assert table.row("reliable levels").value == pytest.approx(96 * fraction, abs=1.5)
    assert table.row("dynamic range").value < 100  # a 0.26 mm element under a 1 mm pad
    assert table.row("working taxels").value == 1.0
    assert table.to_dict()["rows"][0]["criterion"] == "spatial resolution"
    assert table.n_passed + table.n_failed == 9
    with pytest.raises(ValueError, match="`criterion` must be one of spatial resolution"):
        table.row("speed")


def test_resolution_grows_with_the_cover_depth():
    sensor = make_sensor("resistive16")
    deep = dataclasses.replace(sensor, cover=Cover(sensor.cover.material, depth=4e-3))
    shallow = two_point_resolution(sensor, calibration=calibrate(sensor))
    coarse = two_point_resolution(deep, calibration=calibrate(deep))
    assert shallow.resolution == pytest.approx(3.0e-3)
    assert coarse.resolution > shallow.resolution + 2e-3
    assert shallow.separations[1] - shallow.separations[0] == pytest.approx(0.25e-3)


def test_uniform_sensitivity_is_one_adc_level_through_the_transfer_slope():
    sensor = _linear_resistive()
    step = reading_step(sensor)  # noise-free: one level
    assert step.step == 1.0 and step.noise == 0.0
    slope = 5.0 * 1e4 / (1e5 * 1e4)  # dV/dp [V/Pa]
    felt = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 1.0)).quantity.max()
    expected = sensor.readout_chain.lsb / (slope * felt) * 4e-6  # [N] per 2 mm element
    uniform = sensitivity_force(sensor, step.step, spread="uniform")
    assert uniform == pytest.approx(expected, rel=1e-6)
    single = sensitivity_force(sensor, step.step, spread="element")
    assert single > uniform  # the pad spreads a load on one element over its neighbours


def test_hysteresis_and_creep_are_measured_from_sequences():
    assert hysteresis_width(_linear_resistive()) == 0.0
    sensor = _linear_resistive(hysteresis=0.02)
    # the play operator's loop is 2 % of the largest quantity; the edge taxel feels least
    full = sensor.frame_from_pressure(np.full(sensor.load_grid.shape, 1e5)).quantity
    expected = 0.02 * full.max() / full.min()
    assert hysteresis_width(sensor) == pytest.approx(expected, rel=0.02)
    creeping = _linear_resistive(creep=0.05, creep_time=0.1)
    # the reading grows by f (1 - exp(-t / tau)) over a 1 s hold, from the first frame's
    assert stability_change(creeping) == pytest.approx(0.05 * (1 - 0.05), abs=0.004)
    assert stability_change(_linear_resistive()) == 0.0


def test_monotonic_response():
    assert monotonic_fraction(_linear_resistive()) == 1.0
    # fringes: the intensity of a photoelastic pixel goes up and down with stress
    assert monotonic_fraction(make_sensor("photoelastic64")) < 0.5


def test_dynamic_and_photoelastic_sensors_get_a_table():
    piezo = harmon_table(make_sensor("piezo8x8"), rng=1)
    assert piezo.calibration is None
    assert piezo.row("hysteresis").value is None and piezo.row("hysteresis").passed is None
    assert piezo.row("stability").value > 0.99  # a held load fades away
    photo = harmon_table(make_sensor("photoelastic64"), rng=1)
    assert photo.row("spatial resolution").value is None
    assert photo.row("monotonic response").passed is False


def test_bad_arguments():
    with pytest.raises(TypeError, match="`sensor` must be a TactileSensor"):
        harmon_table("vhdta128")
    with pytest.raises(TypeError, match="`sensor` must be a TactileSensor, got 'resistive16'"):
        reading_step("resistive16")
    with pytest.raises(TypeError, match="`rng` must be None, a numpy.random.Generator"):
        reading_step(make_sensor("capacitive4x4"), rng="x")
    with pytest.raises(ValueError, match="`dip` must lie in"):
        two_point_resolution(make_sensor("capacitive4x4"), dip=1.5)
    with pytest.raises(ValueError, match="photoelastic: its frames are fringes"):
        two_point_resolution(make_sensor("photoelastic64"))
    with pytest.raises(ValueError, match="reads frames of shape \\(4, 4\\), but 'resistive16'"):
        harmon_table(
            make_sensor("resistive16"), calibration=calibrate(make_sensor("capacitive4x4"))
        )
    with pytest.raises(TypeError, match="`calibration` must be a Calibration"):
        two_point_resolution(make_sensor("capacitive4x4"), calibration="cal.npz")
    with pytest.raises(ValueError, match="`spread` must be one of element, uniform"):
        sensitivity_force(make_sensor("capacitive4x4"), 1.0, spread="line")
