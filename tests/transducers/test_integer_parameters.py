"""Integer parameters of the transducers name themselves for NaN, infinity and non-numbers."""

import numpy as np
import pytest

from taxel.transducers import (
    FtirTransducer,
    MicrobendTransducer,
    PhotoelasticTransducer,
    PiezoelectricTransducer,
    adc_codes,
    camera_image,
    charge_amplifier_output,
    invert_resistive_scan,
    photoelastic_retardation,
    play_hysteresis,
    scan_resistive_matrix,
)

SCAN = scan_resistive_matrix(np.full((3, 3), 1e4), supply_voltage=5.0, feedback_resistance=1e4)
CALLS = {
    "bits": [
        lambda v: adc_codes([1.0], bits=v, low=0.0, high=2.0),
        lambda v: camera_image([0.5], bits=v),
        lambda v: FtirTransducer(bits=v),
    ],
    "rows": [lambda v: MicrobendTransducer(rows=v)],
    "passes": [
        lambda v: PhotoelasticTransducer(passes=v),
        lambda v: photoelastic_retardation(
            [1.0], layer_thickness=1e-3, stress_optic_coefficient=1e-10, wavelength=5e-7, passes=v
        ),
    ],
    "reset_interval": [
        lambda v: PiezoelectricTransducer(reset_interval=v),
        lambda v: charge_amplifier_output(
            [1.0, 2.0], 1e-3, area=1e-6, feedback_capacitance=1e-11, reset_interval=v
        ),
    ],
    "n_operators": [lambda v: play_hysteresis([1.0, 2.0], loop_width=0.1, n_operators=v)],
    "max_iterations": [
        lambda v: invert_resistive_scan(
            SCAN, supply_voltage=5.0, feedback_resistance=1e4, max_iterations=v
        )
    ],
    "scratch_count": [lambda v: FtirTransducer(scratch_count=v)],
}
CASES = [(name, call) for name, calls in CALLS.items() for call in calls]


@pytest.mark.parametrize(("name", "call"), CASES)
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf, None, 1 + 1j, [2], np.ones(2), 2.5])
def test_a_bad_integer_names_its_parameter(name, call, bad):
    # int(nan) raised "cannot convert float NaN to integer", int(inf) an OverflowError,
    # int(None) "int() argument must be ...": none named the parameter
    if bad is None and name == "reset_interval":
        return  # None is its "never reset"
    with pytest.raises(ValueError, match=f"`{name}` must be"):
        call(bad)


def test_a_huge_scratch_count_is_taken_without_drawing_the_scratches():
    # the constructor drew every scratch on a 1x1 image to check the fields: 1e12 never ended
    assert FtirTransducer(scratch_count=10**12).scratch_count == 10**12


def test_a_camera_image_of_one_pixel_with_noise():
    # a 0-d mean drew a plain int from poisson: 'int' object has no attribute 'astype'
    assert camera_image(0.5, rng=1).shape == ()
