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
"""

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
    "ResistiveScanInversion",
    "ResistiveTransducer",
    "Transducer",
    "invert_resistive_scan",
    "piezoresistive_pressure",
    "piezoresistive_resistance",
    "readout_resistance",
    "readout_voltage",
    "scan_resistive_matrix",
]
