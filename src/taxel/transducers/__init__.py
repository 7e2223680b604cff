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

Piezoelectric (eqs. 25.14-25.18, Figures 25.6-25.7)
---------------------------------------------------
PiezoelectricTransducer, piezoelectric_charge, piezoelectric_voltage,
charge_amplifier_output, charge_amplifier_stress,
current_amplifier_output, current_amplifier_stress, PVDF_D33, PVDF_RELATIVE_PERMITTIVITY

Optical, reflective (Figure 25.8)
---------------------------------
ReflectiveOpticalTransducer, reflective_power, reflective_peak_gap, reflective_gap
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
from taxel.transducers._piezoelectric import (
    PVDF_D33,
    PVDF_RELATIVE_PERMITTIVITY,
    PiezoelectricTransducer,
    charge_amplifier_output,
    charge_amplifier_stress,
    current_amplifier_output,
    current_amplifier_stress,
    piezoelectric_charge,
    piezoelectric_voltage,
)
from taxel.transducers._reflective import (
    ReflectiveOpticalTransducer,
    reflective_gap,
    reflective_peak_gap,
    reflective_power,
)
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
    "PVDF_D33",
    "PVDF_RELATIVE_PERMITTIVITY",
    "VACUUM_PERMITTIVITY",
    "CapacitiveTransducer",
    "PiezoelectricTransducer",
    "ReflectiveOpticalTransducer",
    "ResistiveScanInversion",
    "ResistiveTransducer",
    "Transducer",
    "capacitance_from_detector_voltage",
    "charge_amplifier_output",
    "charge_amplifier_stress",
    "current_amplifier_output",
    "current_amplifier_stress",
    "detector_voltage",
    "invert_resistive_scan",
    "piezoelectric_charge",
    "piezoelectric_voltage",
    "piezoresistive_pressure",
    "piezoresistive_resistance",
    "plate_capacitance",
    "readout_resistance",
    "readout_voltage",
    "reflective_gap",
    "reflective_peak_gap",
    "reflective_power",
    "scan_resistive_matrix",
    "strain_from_detector_voltage",
]
