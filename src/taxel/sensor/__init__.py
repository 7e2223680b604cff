"""Tactile array sensors: geometry, cover, transducer and readout, frame by frame.

Sensor model
    TactileSensor, SensorFrame, ArrayGeometry, LoadGrid, Cover, Readout, ReadoutChain,
    TaxelFields, taxel_fields, FIELD_NAMES, density_class, DENSITY_CLASSES
Presets
    make_sensor, as_sensor, PRESET_NAMES
Calibration (flat-plate presses; dead and stuck taxels masked)
    calibrate, Calibration, calibration_error, CalibrationError
Harmon's criteria (chapter section 25.2), measured
    harmon_table, HarmonTable, HarmonRow, two_point_resolution, TwoPointResolution,
    reading_step, ReadingStep
"""

from taxel.sensor._calibrate import calibrate
from taxel.sensor._calibration import Calibration
from taxel.sensor._calibration_error import CalibrationError, calibration_error
from taxel.sensor._cover import Cover
from taxel.sensor._fields import FIELD_NAMES, TaxelFields, taxel_fields
from taxel.sensor._geometry import DENSITY_CLASSES, ArrayGeometry, LoadGrid, density_class
from taxel.sensor._harmon import HarmonRow, HarmonTable, harmon_table
from taxel.sensor._harmon_measures import ReadingStep, reading_step
from taxel.sensor._presets import PRESET_NAMES, as_sensor, make_sensor
from taxel.sensor._readout import Readout, ReadoutChain
from taxel.sensor._resolution import TwoPointResolution, two_point_resolution
from taxel.sensor._sensor import SensorFrame, TactileSensor

__all__ = [
    "DENSITY_CLASSES",
    "FIELD_NAMES",
    "PRESET_NAMES",
    "ArrayGeometry",
    "Calibration",
    "CalibrationError",
    "Cover",
    "HarmonRow",
    "HarmonTable",
    "LoadGrid",
    "ReadingStep",
    "Readout",
    "ReadoutChain",
    "SensorFrame",
    "TactileSensor",
    "TaxelFields",
    "TwoPointResolution",
    "as_sensor",
    "calibrate",
    "calibration_error",
    "density_class",
    "harmon_table",
    "make_sensor",
    "reading_step",
    "taxel_fields",
    "two_point_resolution",
]
