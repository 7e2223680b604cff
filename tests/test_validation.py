"""The shared checks of `taxel._validation`: messages name the parameter and the value."""

import numpy as np
import pytest

from taxel._validation import as_finite_array
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
    ],
)
def test_other_bad_arrays(value, error, message):
    with pytest.raises(error, match=message):
        as_finite_array("x", value, ndim=1)
