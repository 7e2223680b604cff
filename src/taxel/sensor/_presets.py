"""Named sensors: the Ellis seed's VHDTA, Harmon's suggested array, and one of each technology.

Parameters are physically plausible values for each kind of sensor, chosen once here; the
reconstruction benchmark and the report use these exact sensors.
"""

from __future__ import annotations

from collections.abc import Callable

from taxel._validation import check_choice
from taxel.mechanics import ElasticMaterial
from taxel.sensor._cover import Cover
from taxel.sensor._geometry import ArrayGeometry
from taxel.sensor._readout import Readout
from taxel.sensor._sensor import TactileSensor
from taxel.transducers import (
    CapacitiveTransducer,
    FtirTransducer,
    MicrobendTransducer,
    PhotoelasticTransducer,
    PiezoelectricTransducer,
    ReflectiveOpticalTransducer,
    ResistiveTransducer,
)

__all__ = ["PRESET_NAMES", "as_sensor", "make_sensor"]

SILICONE = ElasticMaterial(1.0e6, 0.49)
SOFT_SILICONE = ElasticMaterial(0.5e6, 0.49)
PSI = 6894.757  # [Pa]


def _vhdta128() -> TactileSensor:
    # Ellis seed section 1 and [Begej 1984]: 128 x 128 taxels on 3.3 cm, 8 bits, FTIR read by
    # a camera, fingertip-like pad, 60 psi working range; the membrane rests on glass plate
    return TactileSensor(
        name="vhdta128",
        geometry=ArrayGeometry(128, 128, 33e-3 / 128),
        cover=Cover(SOFT_SILICONE, depth=1.0e-3, thickness=1.0e-3),
        transducer=FtirTransducer(scratch_count=12, scratch_seed=1985),
        readout=Readout(bits=None, unit_seed=1),  # the camera digitises; noise is its own
        frame_rate=30.0,
        full_scale=60 * PSI,
        # a grey level spans 2.5-3 % of full scale at the corners and at full scale: plates
        # 5 % apart (21) cannot place the steps, so each taxel's map errs by up to 2.5 %
        calibration_levels=81,
        description="Ellis seed VHDTA: 128 x 128 optical FTIR, camera, 8 bits, 3.3 cm square",
    )


def _harmon10x20() -> TactileSensor:
    # Harmon (1980): 1-2 mm resolution, 10 x 20 points, 1000:1, 100 Hz - 1 kHz, monotonic.
    # p_ref = 250 kPa keeps the 5 V transimpedance stage at 4.5 V at full scale (with
    # 50 kPa it was asked for 20.5 V, four times its supply)
    return TactileSensor(
        name="harmon10x20",
        geometry=ArrayGeometry(10, 20, 1.5e-3),
        cover=Cover(SILICONE, depth=1.0e-3, thickness=1.0e-3),
        transducer=ResistiveTransducer(reference_pressure=2.5e5, exponent=1.0),
        readout=Readout(bits=12, noise=3e-4, gain_spread=0.03, hysteresis=0.01, unit_seed=2),
        frame_rate=1000.0,
        full_scale=2.0e6,
        description="Harmon's suggested array: 10 x 20 piezoresistive taxels at 1.5 mm",
    )


def _resistive16() -> TactileSensor:
    return TactileSensor(
        name="resistive16",
        geometry=ArrayGeometry(16, 16, 2.0e-3),
        cover=Cover(SILICONE, depth=1.5e-3, thickness=1.5e-3),
        transducer=ResistiveTransducer(
            reference_pressure=2e4, exponent=1.0, series_resistance=50.0
        ),
        readout=Readout(
            bits=12,
            noise=2e-3,
            gain_spread=0.05,
            offset_spread=0.01,
            crosstalk=0.01,
            hysteresis=0.02,
            unit_seed=3,
        ),
        frame_rate=500.0,
        full_scale=200e3,
        description="16 x 16 piezoresistive array at 2 mm under a 1.5 mm silicone pad",
    )


def _capacitive4x4() -> TactileSensor:
    return TactileSensor(
        name="capacitive4x4",
        geometry=ArrayGeometry(4, 4, 5.0e-3),
        cover=Cover(ElasticMaterial(0.3e6, 0.49), depth=2.0e-3, thickness=2.0e-3),
        transducer=CapacitiveTransducer(
            plate_width=4e-3,
            plate_length=4e-3,
            gap=0.1e-3,
            relative_permittivity=3.0,
            stray_capacitance=2e-12,
        ),
        readout=Readout(bits=16, noise=5e-4, temperature_coefficient=2e-3, unit_seed=4),
        frame_rate=100.0,
        full_scale=50e3,
        cell_modulus=1.0e6,
        description="4 x 4 capacitive pads at 5 mm (a fingertip sensor)",
    )


def _piezo8x8() -> TactileSensor:
    return TactileSensor(
        name="piezo8x8",
        geometry=ArrayGeometry(8, 8, 2.5e-3),
        cover=Cover(SILICONE, depth=1.0e-3, thickness=1.0e-3),
        transducer=PiezoelectricTransducer(
            area=4e-6, feedback_capacitance=1e-10, feedback_resistance=1e9
        ),
        readout=Readout(bits=12, noise=1e-3, unit_seed=5),
        frame_rate=1000.0,
        full_scale=100e3,
        description="8 x 8 PVDF film array with charge amplifiers (dynamic: slip, vibration)",
    )


def _photoelastic64() -> TactileSensor:
    return TactileSensor(
        name="photoelastic64",
        geometry=ArrayGeometry(64, 64, 0.25e-3),
        cover=Cover(SILICONE, depth=1.0e-3),
        # a soft photoelastic urethane: fringe value ~0.12 kN/m, C = lambda / f ~ 4.6e-9 1/Pa
        transducer=PhotoelasticTransducer(layer_thickness=3e-3, stress_optic_coefficient=4.6e-9),
        readout=Readout(bits=8, noise=2e-3, unit_seed=6),
        frame_rate=60.0,
        full_scale=200e3,
        description="reflective circular polariscope under a 1 mm pad, 64 x 64 camera",
    )


def _microbend16() -> TactileSensor:
    return TactileSensor(
        name="microbend16",
        geometry=ArrayGeometry(16, 16, 3.0e-3),
        cover=Cover(SILICONE, depth=2.0e-3, thickness=2.0e-3),
        transducer=MicrobendTransducer(rows=16, cols=16, crossing_area=9e-6),
        readout=Readout(bits=12, noise=1e-3, unit_seed=7),
        frame_rate=200.0,
        full_scale=100e3,
        description="two orthogonal layers of 16 microbend fibres at 3 mm",
    )


def _reflective8x8() -> TactileSensor:
    return TactileSensor(
        name="reflective8x8",
        geometry=ArrayGeometry(8, 8, 3.0e-3),
        cover=Cover(ElasticMaterial(0.2e6, 0.49), depth=0.5e-3),
        transducer=ReflectiveOpticalTransducer(),
        readout=Readout(bits=12, noise=1e-3, unit_seed=8),
        frame_rate=100.0,
        full_scale=4e3,
        description="8 x 8 reflective fibre pairs under a soft membrane (displacement)",
    )


_PRESETS: dict[str, Callable[[], TactileSensor]] = {
    "vhdta128": _vhdta128,
    "harmon10x20": _harmon10x20,
    "resistive16": _resistive16,
    "capacitive4x4": _capacitive4x4,
    "piezo8x8": _piezo8x8,
    "photoelastic64": _photoelastic64,
    "microbend16": _microbend16,
    "reflective8x8": _reflective8x8,
}

PRESET_NAMES: tuple[str, ...] = tuple(_PRESETS)


def make_sensor(name: str) -> TactileSensor:
    """Build a named preset sensor.

    Parameters
    ----------
    name : str
        One of `PRESET_NAMES`: vhdta128, harmon10x20, resistive16, capacitive4x4, piezo8x8,
        photoelastic64, microbend16, reflective8x8.

    Returns
    -------
    TactileSensor

    Examples
    --------
    >>> sensor = make_sensor("vhdta128")
    >>> sensor.shape, sensor.density_class
    ((128, 128), 'VHDTA')
    """
    check_choice("name", name, PRESET_NAMES)
    return _PRESETS[name]()


def as_sensor(sensor: str | TactileSensor) -> TactileSensor:
    """A sensor given as itself or by preset name.

    Examples
    --------
    >>> as_sensor("resistive16").shape
    (16, 16)
    """
    if isinstance(sensor, TactileSensor):
        return sensor
    if not isinstance(sensor, str):
        raise TypeError(f"`sensor` must be a TactileSensor or a preset name, got {sensor!r}")
    check_choice("sensor", sensor, PRESET_NAMES)
    return make_sensor(sensor)
