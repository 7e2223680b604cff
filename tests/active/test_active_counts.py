"""Whole-number settings given as inf, NaN or text: a ValueError naming the setting."""

import math

import numpy as np
import pytest

from taxel.active import (
    Box,
    CornerProbing,
    SlipDetector,
    box_corner_frame,
    plane_probing_trial,
    slip_trials,
)


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan, "5", True, 4.5])
@pytest.mark.parametrize(
    ("name", "call"),
    [
        ("n_probes", lambda bad: plane_probing_trial(n_probes=bad)),
        ("probes_per_face", lambda bad: CornerProbing(probes_per_face=bad)),
        ("warm_up", lambda bad: SlipDetector(warm_up=bad)),
        ("n_slip", lambda bad: slip_trials(n_slip=bad)),
        ("index", lambda bad: box_corner_frame(Box("box"), bad)),
    ],
)
def test_a_count_that_is_not_a_whole_number_is_refused_naming_it(name, call, bad):
    with pytest.raises(ValueError, match=f"`{name}` must be an integer"):
        call(bad)


def test_whole_numbers_of_any_real_type_are_taken():
    assert CornerProbing(probes_per_face=np.int64(4)).probes_per_face == 4
    assert SlipDetector(warm_up=40.0).warm_up == 40
