"""The shared checks of `taxel._validation`: messages name the parameter and the value."""

import numpy as np
import pytest

from taxel._validation import (
    as_finite_array,
    as_rng,
    check_choice,
    check_count,
    check_finite,
    check_flag,
    check_instance,
    check_integer,
    check_pair,
)
from taxel.frames import as_pose
from taxel.reconstruction import reconstruct


def test_a_real_array_passes_as_float64():
    array = as_finite_array("x", np.arange(4, dtype=np.int16), ndim=1)
    assert array.dtype == np.float64 and array.tolist() == [0.0, 1.0, 2.0, 3.0]


@pytest.mark.parametrize("dtype", [np.complex64, np.complex128])
def test_a_complex_array_is_refused_not_cast(dtype):
    with pytest.raises(TypeError, match=r"`x` must be real, got a complex array \(complex"):
        as_finite_array("x", np.ones(3, dtype=dtype))


def test_public_functions_refuse_complex_arrays():
    with pytest.raises(TypeError, match="`pose` must be real"):
        as_pose(np.eye(4) + 0j)
    with pytest.raises(TypeError, match="`frame` must be real"):
        reconstruct(np.zeros((16, 16)) + 3j, "resistive16")


@pytest.mark.parametrize(
    ("value", "error", "message"),
    [
        ([1.0, np.nan], ValueError, r"`x` must be finite everywhere, got 1 NaN or inf value\(s\)"),
        (["a"], TypeError, "`x` must be numeric, got"),
        (np.zeros((2, 2)), ValueError, r"`x` must be 1-D, got shape \(2, 2\)"),
        # its mask would be dropped and the values under it read
        (np.ma.masked_invalid([1.0, np.nan]), TypeError, "`x` is a masked array: fill its"),
    ],
)
def test_other_bad_arrays(value, error, message):
    with pytest.raises(error, match=message):
        as_finite_array("x", value, ndim=1)


@pytest.mark.parametrize("value", [True, np.bool_(False), "5", b"5"])
def test_a_bool_or_text_is_not_a_number(value):
    with pytest.raises(TypeError, match="`x` must be a real number, got"):
        check_finite("x", value)


def test_a_pair_names_the_parameter():
    assert check_pair("position", np.array([1, 2])) == (1.0, 2.0)
    for bad in [(0,), 0.0, (1, 2, 3), "abc"]:
        with pytest.raises(ValueError, match=r"`position` must be an \(x, y\) pair, got"):
            check_pair("position", bad)
    with pytest.raises(ValueError, match="`position` must be finite"):
        check_pair("position", (0.0, np.nan))
    with pytest.raises(TypeError, match="`position` must be a real number, got 'a'"):
        check_pair("position", "ab")


def test_counts_are_whole_numbers():
    assert check_count("n", 3) == 3 and check_count("n", np.int64(4)) == 4
    assert check_count("n", 2.0) == 2
    with pytest.raises(ValueError, match="`n` must be a whole number, got 2.5"):
        check_count("n", 2.5)
    with pytest.raises(ValueError, match="`n` must be >= 1, got 0"):
        check_count("n", 0)
    with pytest.raises(TypeError, match="`n` must be an integer, got True"):
        check_count("n", True)
    with pytest.raises(ValueError, match="`n` must be finite"):
        check_count("n", np.nan)


@pytest.mark.parametrize("value", ["no", 1, np.nan, None])
def test_a_flag_must_be_a_bool(value):
    with pytest.raises(TypeError, match="`periodic` must be True or False, got"):
        check_flag("periodic", value)
    assert check_flag("periodic", np.bool_(True)) is True


def test_an_instance_check_names_the_type():
    with pytest.raises(TypeError, match="`material` must be a float, got 'rubber'"):
        check_instance("material", "rubber", float)
    with pytest.raises(TypeError, match="`error` must be an Exception, got None"):
        check_instance("error", None, Exception)


def test_rng_accepts_none_a_seed_or_a_generator():
    generator = np.random.default_rng(3)
    assert as_rng("rng", None) is None and as_rng("rng", generator) is generator
    assert as_rng("rng", 5).random() == np.random.default_rng(5).random()
    with pytest.raises(ValueError, match="`rng` seed must be >= 0, got -1"):
        as_rng("rng", -1)
    for bad in ["x", 1.5, True]:
        with pytest.raises(TypeError, match="`rng` must be None, a numpy.random.Generator, an"):
            as_rng("rng", bad)
    # what numpy.random.default_rng takes as a seed: a 0-d integer array, a SeedSequence,
    # a BitGenerator
    seeded = np.random.default_rng(7).random()
    for seed in [np.array(7), np.random.SeedSequence(7), np.random.PCG64(7)]:
        assert as_rng("rng", seed).random() == seeded
    with pytest.raises(TypeError, match=r"^`rng` must be a numpy.random.Generator, an int"):
        as_rng("rng", None, allow_none=False)


def test_grid_shapes_and_broadcasting_pairs():
    from taxel._validation import check_broadcast, check_grid_shape

    assert check_grid_shape("shape", (4, np.int64(3))) == (4, 3)
    with pytest.raises(ValueError, match=r"`shape` must be a \(rows, cols\) pair, got \(4,\)"):
        check_grid_shape("shape", (4,))
    with pytest.raises(ValueError, match="`shape` must be a whole number, got 2.5"):
        check_grid_shape("shape", (2.5, 3))
    check_broadcast(("x", "y"), np.zeros((1, 3)), np.zeros((4, 1)))
    with pytest.raises(ValueError, match=r"`x` and `y` .* together, got \(3,\) and \(4,\)"):
        check_broadcast(("x", "y"), np.zeros(3), np.zeros(4))
    check_broadcast(("a", "b", "c"), np.zeros(3), np.zeros(()), np.zeros((2, 1)))
    with pytest.raises(
        ValueError, match=r"`a`, `b` and `c` .* together, got \(3,\), \(\) and \(2,\)"
    ):
        check_broadcast(("a", "b", "c"), np.zeros(3), np.zeros(()), np.zeros(2))


@pytest.mark.parametrize("value", [np.complex128(1.0), np.complex64(2 + 1j), 1 + 0j])
def test_a_complex_number_is_not_a_real_number(value):
    # float() of a NumPy complex dropped the imaginary part with a ComplexWarning only
    with pytest.raises(TypeError, match="`x` must be a real number, got"):
        check_finite("x", value)


@pytest.mark.parametrize(
    ("value", "what"),
    [
        ("1.5", "'1.5'"),
        (np.array(["1", "2"]), "text"),
        (["1", "2"], "text"),
        (True, "True"),
    ],
)
def test_text_and_a_lone_bool_are_not_numeric_arrays(value, what):
    # "1.5" was read as 1.5 without a word
    with pytest.raises(TypeError, match=f"`x` must be numeric, got {what}"):
        as_finite_array("x", value)


@pytest.mark.parametrize("mask", [np.array([[True, False], [False, True]]), [[True, False]]])
def test_an_array_of_booleans_is_a_mask_of_zeros_and_ones(mask):
    array = as_finite_array("x", mask)
    assert array.dtype == np.float64
    assert np.array_equal(array, np.asarray(mask, dtype=float))


def test_a_choice_must_be_text():
    # an array in `choices` raised NumPy's "truth value of an array ... is ambiguous"
    with pytest.raises(TypeError, match="`field` must be one of dark, light; got array"):
        check_choice("field", np.array(["dark", "light"]), ("dark", "light"))
    assert check_choice("field", "dark", ("dark", "light")) == "dark"


@pytest.mark.parametrize(
    "value", [np.nan, np.inf, -np.inf, 2.5, 0, True, None, "3", 1 + 0j, [3], np.ones(2)]
)
def test_an_integer_parameter_names_itself(value):
    # int(nan) and int(inf) raised "cannot convert float NaN to integer" or OverflowError
    with pytest.raises(ValueError, match=r"`bits` must be an integer in 1\.\.16, got"):
        check_integer("bits", value, 1, 16)


def test_an_integer_parameter_passes():
    assert check_integer("bits", 12.0, 1, 16) == 12
    assert check_integer("n", np.int64(3)) == 3
    with pytest.raises(ValueError, match="`n` must be a positive integer, got 0"):
        check_integer("n", 0)
