"""Static non-idealities: noise, ADC, gain/offset spread, faults, crosstalk."""

import numpy as np
import pytest

from taxel.transducers import (
    adc_codes,
    adc_values,
    add_noise,
    draw_faults,
    draw_gain_offset,
    neighbour_crosstalk,
    quantize,
)


def test_noise_off_is_identity_and_needs_no_rng():
    x = np.linspace(-1, 1, 7)
    assert np.array_equal(add_noise(x), x)
    with pytest.raises(TypeError, match="`rng` is required"):
        add_noise(x, additive=0.1)


def test_noise_statistics_and_reproducibility():
    state = np.random.get_state()[1].copy()  # noqa: NPY002 (checking it is untouched)
    x = np.full((400, 500), 3.0)
    y = add_noise(x, additive=0.02, multiplicative=0.01, rng=np.random.default_rng(8))
    assert y.mean() == pytest.approx(3.0, abs=3e-4)
    assert y.std() == pytest.approx(np.hypot(0.02, 0.03), rel=0.01)
    assert np.array_equal(y, add_noise(x, additive=0.02, multiplicative=0.01, rng=8))
    assert np.array_equal(np.random.get_state()[1], state)  # noqa: NPY002


@pytest.mark.parametrize("bits", [1, 8, 12, 24])
def test_adc_error_is_at_most_half_an_lsb_inside_the_range(bits):
    x = np.linspace(-0.5, 2.5, 10_001)
    lsb = 2.0 / 2**bits
    codes = adc_codes(x, bits=bits, low=-0.5, high=1.5)
    assert codes.min() == 0 and codes.max() == 2**bits - 1
    inside = x < 1.5
    error = quantize(x, bits=bits, low=-0.5, high=1.5) - x
    assert np.max(np.abs(error[inside])) <= lsb / 2 * (1 + 1e-9)
    # saturation: everything above the range reads the top mid-point
    top = adc_values(2**bits - 1, bits=bits, low=-0.5, high=1.5)
    assert np.all(quantize(x[x >= 1.5], bits=bits, low=-0.5, high=1.5) == top)
    assert top == pytest.approx(1.5 - lsb / 2)


def test_adc_errors_name_the_parameter():
    for bad in (0, 25, 2.5):
        with pytest.raises(ValueError, match=f"`bits` must be an integer in 1..24, got {bad}"):
            adc_codes(0.1, bits=bad, low=0.0, high=1.0)
    with pytest.raises(ValueError, match="`bits` must be an integer in 1..24, got True"):
        quantize(0.1, bits=True, low=0.0, high=1.0)
    with pytest.raises(ValueError, match="`high` must exceed low = 1, got 1"):
        quantize(0.1, bits=8, low=1.0, high=1.0)
    with pytest.raises(ValueError, match=r"`codes` must be integers in 0..3"):
        adc_values([4], bits=2, low=0.0, high=1.0)


def test_gain_offset_spread_is_fixed_and_removable():
    spread = draw_gain_offset((16, 16), gain_spread=0.1, offset_spread=0.05, rng=3)
    assert np.all(spread.gain > 0)
    frames = np.random.default_rng(0).uniform(0, 1, size=(5, 16, 16))
    measured = spread.apply(frames)
    assert np.allclose(measured[2], spread.gain * frames[2] + spread.offset)
    assert np.allclose(spread.remove(measured), frames, rtol=1e-12)
    again = draw_gain_offset((16, 16), gain_spread=0.1, offset_spread=0.05, rng=3)
    assert np.array_equal(spread.gain, again.gain)
    ideal = draw_gain_offset((4, 4))
    assert np.all(ideal.gain == 1) and np.all(ideal.offset == 0)


def test_faults_have_exact_counts_and_stick_across_frames():
    faults = draw_faults((20, 20), dead=0.05, stuck=0.02, saturated=0.01, rng=4)
    assert (faults.dead.sum(), faults.stuck.sum(), faults.saturated.sum()) == (20, 8, 4)
    assert not np.any(faults.dead & faults.stuck) and not np.any(faults.stuck & faults.saturated)
    assert faults.working.sum() == 400 - 32
    frames = np.random.default_rng(1).uniform(0.2, 0.8, size=(3, 20, 20))
    out = faults.apply(frames, low=0.0, high=1.0)
    assert np.all(out[:, faults.dead] == 0.0) and np.all(out[:, faults.saturated] == 1.0)
    assert np.all(out[0, faults.stuck] == out[2, faults.stuck])
    assert np.array_equal(out[:, faults.working], frames[:, faults.working])
    none = draw_faults((3, 3))
    assert none.working.all()
    with pytest.raises(ValueError, match="`dead \\+ stuck \\+ saturated` must be <= 1"):
        draw_faults((3, 3), dead=0.6, stuck=0.6, rng=0)
    with pytest.raises(ValueError, match=r"`stuck` must lie in \[0, 1\], got 1.5"):
        draw_faults((3, 3), stuck=1.5, rng=0)


def test_crosstalk_is_self_adjoint_and_local():
    rng = np.random.default_rng(6)
    x, y = rng.normal(size=(2, 7, 9))
    forward = neighbour_crosstalk(x, coupling=0.08, diagonal_coupling=0.03)
    assert np.vdot(forward, y) == pytest.approx(
        np.vdot(x, neighbour_crosstalk(y, coupling=0.08, diagonal_coupling=0.03)), rel=1e-12
    )
    impulse = np.zeros((5, 5))
    impulse[0, 0] = 1.0  # a corner taxel leaks only inwards
    leaked = neighbour_crosstalk(impulse, coupling=0.1)
    assert leaked.sum() == pytest.approx(1.2) and leaked[0, 1] == pytest.approx(0.1)
    batch = neighbour_crosstalk(np.stack([impulse, 2 * impulse]), coupling=0.1)
    assert np.allclose(batch[1], 2 * leaked)
    assert np.array_equal(neighbour_crosstalk(x), x)
    with pytest.raises(ValueError, match=r"`coupling` must lie in \[0, 1\), got 1"):
        neighbour_crosstalk(x, coupling=1.0)


def test_a_unit_pattern_has_whole_positive_sizes_on_any_number_of_axes():
    assert draw_faults((32,), dead=0.1, rng=0).dead.shape == (32,)  # a fibre sensor's signals
    with pytest.raises(ValueError, match="`shape` must be a whole number, got 4.5"):
        draw_faults((4.5, 4), dead=0.1, rng=0)
    with pytest.raises(ValueError, match="`shape` must be >= 1, got -4"):
        draw_gain_offset((-4, 4), gain_spread=0.1, offset_spread=0.1, rng=0)
    with pytest.raises(ValueError, match="`shape` must be a sequence of sizes, got 5"):
        draw_faults(5, dead=0.1, rng=0)
