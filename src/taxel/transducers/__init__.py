"""Transducers: physical quantity -> electrical or optical signal (chapter section 25.3).

Every technology is a frozen dataclass with ``respond`` (quantity -> signal) and ``invert``
(signal -> quantity), following the `Transducer` protocol, and delegates to pure functions
on arrays in SI units that are public too. The class attributes ``quantity``,
``quantity_unit`` and ``signal_unit`` say what each one senses:

===========================  ==============================================  ================
transducer                   senses (``respond`` input)                      signal
===========================  ==============================================  ================
ResistiveTransducer          ``pressure`` on the cell [Pa]                   V_o [V]
CapacitiveTransducer         ``strain`` eps_z of the dielectric [-]          abs(V_d) [V]
PiezoelectricTransducer      ``stress`` series, tension positive [Pa]        V_o [V]
ReflectiveOpticalTransducer  membrane ``displacement`` towards fibers [m]    power [W]
FtirTransducer               contact ``pressure`` image [Pa]                 frame [DN]
MicrobendTransducer          ``pressure`` per fiber crossing [Pa]            power [W]
PhotoelasticTransducer       ``stress_difference`` sigma_1 - sigma_2 [Pa]    intensity [W/m^2]
===========================  ==============================================  ================

Strain and stress are positive in tension, as in `taxel.mechanics`; the piezoelectric
film is the only one that needs a ``time_step`` and sees changes only.

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

Optical, frustrated total internal reflection (eq. 25.19, Figure 25.9)
----------------------------------------------------------------------
FtirTransducer, is_totally_reflected, critical_angle, contact_area_fraction,
pressure_from_contact_fraction, camera_image, glass_scratches

Optical fiber, microbend (Figure 25.11)
---------------------------------------
MicrobendTransducer, microbend_power, microbend_line_loads, separable_pressure

Photoelastic (Figure 25.12)
---------------------------
PhotoelasticTransducer, principal_stress_difference, photoelastic_retardation,
polariscope_intensity, unwrap_retardation, fit_load_scale, PhotoelasticFit

Non-idealities (each the identity when switched off; randomness only through ``rng``)
------------------------------------------------------------------------------------
add_noise, adc_codes, adc_values, quantize, draw_gain_offset, GainOffset,
draw_faults, TaxelFaults, neighbour_crosstalk,
play_hysteresis, first_order_lag, creep, add_drift, temperature_dependence

A physically ordered chain for one taxel signal is: transducer ``respond`` -> creep and
hysteresis (they act on the mechanics) -> temperature dependence -> gain/offset spread ->
neighbour crosstalk -> drift -> noise -> faults -> ADC.
"""

from taxel.transducers._camera import camera_image, glass_scratches
from taxel.transducers._capacitive import (
    VACUUM_PERMITTIVITY,
    CapacitiveTransducer,
    plate_capacitance,
)
from taxel.transducers._capacitive_detector import (
    capacitance_from_detector_voltage,
    detector_voltage,
    strain_from_detector_voltage,
)
from taxel.transducers._common import Transducer
from taxel.transducers._dynamics import (
    add_drift,
    creep,
    first_order_lag,
    play_hysteresis,
    temperature_dependence,
)
from taxel.transducers._ftir import (
    FtirTransducer,
    contact_area_fraction,
    critical_angle,
    is_totally_reflected,
    pressure_from_contact_fraction,
)
from taxel.transducers._microbend import (
    MicrobendTransducer,
    microbend_line_loads,
    microbend_power,
    separable_pressure,
)
from taxel.transducers._noise import (
    GainOffset,
    TaxelFaults,
    adc_codes,
    adc_values,
    add_noise,
    draw_faults,
    draw_gain_offset,
    neighbour_crosstalk,
    quantize,
)
from taxel.transducers._photoelastic import PhotoelasticTransducer
from taxel.transducers._photoelastic_optics import (
    photoelastic_retardation,
    polariscope_intensity,
    principal_stress_difference,
)
from taxel.transducers._photoelastic_recovery import (
    PhotoelasticFit,
    fit_load_scale,
    unwrap_retardation,
)
from taxel.transducers._piezo_amplifiers import (
    charge_amplifier_output,
    charge_amplifier_stress,
    current_amplifier_output,
    current_amplifier_stress,
)
from taxel.transducers._piezo_film import (
    PVDF_D33,
    PVDF_RELATIVE_PERMITTIVITY,
    piezoelectric_charge,
    piezoelectric_voltage,
)
from taxel.transducers._piezoelectric import PiezoelectricTransducer
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
    "FtirTransducer",
    "GainOffset",
    "MicrobendTransducer",
    "PhotoelasticFit",
    "PhotoelasticTransducer",
    "PiezoelectricTransducer",
    "ReflectiveOpticalTransducer",
    "ResistiveScanInversion",
    "ResistiveTransducer",
    "TaxelFaults",
    "Transducer",
    "adc_codes",
    "adc_values",
    "add_drift",
    "add_noise",
    "camera_image",
    "capacitance_from_detector_voltage",
    "charge_amplifier_output",
    "charge_amplifier_stress",
    "contact_area_fraction",
    "creep",
    "critical_angle",
    "current_amplifier_output",
    "current_amplifier_stress",
    "detector_voltage",
    "draw_faults",
    "draw_gain_offset",
    "first_order_lag",
    "fit_load_scale",
    "glass_scratches",
    "invert_resistive_scan",
    "is_totally_reflected",
    "microbend_line_loads",
    "microbend_power",
    "neighbour_crosstalk",
    "photoelastic_retardation",
    "piezoelectric_charge",
    "piezoelectric_voltage",
    "piezoresistive_pressure",
    "piezoresistive_resistance",
    "plate_capacitance",
    "play_hysteresis",
    "polariscope_intensity",
    "pressure_from_contact_fraction",
    "principal_stress_difference",
    "quantize",
    "readout_resistance",
    "readout_voltage",
    "reflective_gap",
    "reflective_peak_gap",
    "reflective_power",
    "scan_resistive_matrix",
    "separable_pressure",
    "strain_from_detector_voltage",
    "temperature_dependence",
    "unwrap_retardation",
]
