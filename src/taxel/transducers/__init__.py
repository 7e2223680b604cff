"""Transducers: physical quantity -> electrical or optical signal (chapter section 25.3).

Every technology is a frozen dataclass with ``respond`` (quantity -> signal) and ``invert``
(signal -> quantity), following the `Transducer` protocol, and delegates to pure functions
on arrays in SI units that are public too. The class attributes ``quantity``,
``quantity_unit`` and ``signal_unit`` say what each one senses.

Common interface
----------------
Transducer

Resistive (eq. 25.6, Figure 25.4)
---------------------------------
ResistiveTransducer, piezoresistive_resistance, piezoresistive_pressure,
readout_voltage, readout_resistance,
scan_resistive_matrix, invert_resistive_scan, ResistiveScanInversion

Capacitive (eqs. 25.7-25.13, Figure 25.5)
-----------------------------------------
CapacitiveTransducer, plate_capacitance, detector_voltage,
capacitance_from_detector_voltage, strain_from_detector_voltage, VACUUM_PERMITTIVITY
"""

from taxel.transducers._capacitive import (
    VACUUM_PERMITTIVITY,
    CapacitiveTransducer,
    capacitance_from_detector_voltage,
    detector_voltage,
    plate_capacitance,
    strain_from_detector_voltage,
)
from taxel.transducers._common import Transducer
from taxel.transducers._resistive import (
    ResistiveTransducer,
    piezoresistive_pressure,
    piezoresistive_resistance,
    readout_resistance,
    readout_voltage,
)
from taxel.transducers._resistive_matrix import (
    ResistiveScanInversion,
    invert_resistive_scan,
    scan_resistive_matrix,
)

__all__ = [
    "VACUUM_PERMITTIVITY",
    "CapacitiveTransducer",
    "ResistiveScanInversion",
    "ResistiveTransducer",
    "Transducer",
    "capacitance_from_detector_voltage",
    "detector_voltage",
    "invert_resistive_scan",
    "piezoresistive_pressure",
    "piezoresistive_resistance",
    "plate_capacitance",
    "readout_resistance",
    "readout_voltage",
    "scan_resistive_matrix",
    "strain_from_detector_voltage",
]
