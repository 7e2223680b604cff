"""lcurve_curvature names bad input instead of broadcasting errors or silent zeros."""

import numpy as np
import pytest

from taxel.reconstruction import lcurve_curvature

GOOD = (np.array([1e-3, 1e-2, 1e-1]), np.ones(3), np.ones(3), -np.ones(3))
NAMES = ("regularization", "residual", "seminorm", "seminorm_derivative")


@pytest.mark.parametrize("index", range(4))
@pytest.mark.parametrize(
    ("bad", "error", "message"),
    [
        (np.array([1.0, np.nan, 1.0]), ValueError, "must be finite everywhere"),
        (np.ones(2), ValueError, "must have shapes that broadcast together"),
        (np.array([]), ValueError, "must not be empty"),
        (np.array(["a", "b", "c"]), TypeError, "must be numeric"),
        (np.ones(3) + 1j, TypeError, "must be real"),
    ],
)
def test_bad_curves_are_named(index, bad, error, message):
    # a NaN gave a curvature of 0 without a word; other shapes raised NumPy's broadcast error
    args = list(GOOD)
    args[index] = bad
    with pytest.raises(error, match=message) as caught:
        lcurve_curvature(*args)
    assert f"`{NAMES[index]}`" in str(caught.value)


def test_good_curves_still_work():
    assert np.all(np.isfinite(lcurve_curvature(*GOOD)))
