"""The FabricSlide recordings' CPM-Finger as a `TactileSensor`: what is known, what is assumed.

Known (FabricSlide README, the authors' acquisition code, the recordings):

- capacitive transduction, 16 taxels (``channel1..channel16``), finger-shaped;
- each channel arrives as two bytes: 16-bit counts;
- the logger subtracts each channel's mean over 500 frames at rest before writing, so the
  recorded readings are counts above rest (42 to 263 while sliding in
  ``BeigeCotton_F120_V-100mmps_0``);
- about 35.6 frames per second (the reader's `sampling_rate` over the recordings);
- rms noise of about 1.2 counts: the quietest channels' frame-to-frame change over
  sqrt(2) while sliding is 1.1 to 1.3 counts, an upper bound of the white noise.

Assumed (not published in the README; plausible for a fingertip): the 16 taxels as a flat
4 x 4 patch at 4 mm pitch (the finger's curvature and true positions are unknown, hence
`CPM_FINGER['taxel_positions']` is None); 3 mm square plates 0.2 mm apart with a
dielectric of permittivity 3 and constrained modulus 1 MPa; a 2 mm silicone pad
(E = 0.5 MPa); a 50 kPa working range. The two proximity channels are not modelled.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from taxel.io._fabricslide import CPM_FINGER

if TYPE_CHECKING:
    from taxel.sensor import TactileSensor

__all__ = ["CPM_FINGER_ASSUMED", "cpm_finger_sensor"]

_COUNTS_NOISE = 1.2  # rms counts of 16-bit readings (see the module notes)

#: The parameters of `cpm_finger_sensor` that are assumed rather than known.
CPM_FINGER_ASSUMED: tuple[str, ...] = (
    "layout (flat 4 x 4)",
    "taxel_pitch (4 mm)",
    "plate size (3 x 3 mm) and gap (0.2 mm)",
    "dielectric permittivity (3) and modulus (1 MPa)",
    "cover (2 mm silicone, E = 0.5 MPa)",
    "full_scale (50 kPa)",
)


def cpm_finger_sensor() -> TactileSensor:
    """The CPM-Finger of the FabricSlide recordings as a planar capacitive sensor model.

    Returns
    -------
    TactileSensor
        16 capacitive taxels, 16-bit readout with about 1.2 counts of noise, 35.6 frames
        per second. Its raw codes include the rest level; FabricSlide's readings are
        these codes minus each taxel's mean code at rest.

    Notes
    -----
    Which parameters are facts and which are assumptions is set out in the module
    docstring and `CPM_FINGER_ASSUMED`. Use it to simulate recordings with the same
    channel count, word size, rate and noise as FabricSlide, not to reproduce its
    absolute readings: the counts per pascal of the real finger are not published.

    Examples
    --------
    >>> sensor = cpm_finger_sensor()
    >>> sensor.shape, sensor.quantity, sensor.readout.bits, sensor.frame_rate
    ((4, 4), 'strain', 16, 35.6)
    """
    # imported here so that reading files does not load the sensor models (scipy and all)
    from taxel.mechanics import ElasticMaterial
    from taxel.sensor import ArrayGeometry, Cover, Readout, TactileSensor
    from taxel.transducers import CapacitiveTransducer

    rows, cols = 4, 4
    if rows * cols != CPM_FINGER["n_taxels"]:  # the README's count is the one fact we reuse
        raise AssertionError("CPM_FINGER no longer has 16 taxels")
    # noise as a fraction of the signal range: 1.2 counts of 2^16 over the ADC's span
    return TactileSensor(
        name="cpm-finger",
        geometry=ArrayGeometry(rows, cols, 4e-3),
        cover=Cover(ElasticMaterial(0.5e6, 0.49), depth=2e-3, thickness=2e-3),
        transducer=CapacitiveTransducer(
            plate_width=3e-3,
            plate_length=3e-3,
            gap=0.2e-3,
            relative_permittivity=3.0,
            stray_capacitance=2e-12,
        ),
        readout=Readout(bits=16, noise=_COUNTS_NOISE / 2**16, unit_seed=16),
        frame_rate=35.6,
        full_scale=50e3,
        cell_modulus=1.0e6,
        description="FabricSlide's CPM-Finger: 16 capacitive taxels, 16-bit, 35.6 Hz "
        "(layout, cover and plates assumed)",
    )
