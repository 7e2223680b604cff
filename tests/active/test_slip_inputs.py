"""Slip detection refuses frames and settings it cannot use, naming them."""

import warnings

import numpy as np
import pytest

from taxel.active import SlipDetector, detect_slip

RNG = np.random.default_rng(0)
FRAMES = RNG.normal(100.0, 2.0, (60, 8, 8))


@pytest.mark.parametrize("shape", [(60, 0, 8), (60, 8, 0), (60, 1, 1), (60, 1, 8)])
def test_static_frames_of_fewer_than_two_rows_or_columns_are_refused(shape):
    with pytest.raises(ValueError, match=r"`static_frames` must have at least 2 rows and 2"):
        detect_slip(np.ones(shape), frame_rate=1000.0)


def test_piezo_frames_without_taxels_are_refused():
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the mean of no taxels warned and went on
        with pytest.raises(ValueError, match=r"`piezo_frames` must have at least one taxel"):
            detect_slip(FRAMES, np.zeros((60, 0, 4)), frame_rate=1000.0)


@pytest.mark.parametrize("pitch", [[1e-3, 1e-3, 1e-3], [], "abc", [[1e-3, 1e-3]]])
def test_a_taxel_pitch_that_is_not_one_or_two_lengths_is_refused(pitch):
    with pytest.raises((ValueError, TypeError), match=r"`taxel_pitch` must be"):
        SlipDetector(taxel_pitch=pitch)


def test_a_pitch_of_one_or_two_lengths_is_taken():
    assert SlipDetector(taxel_pitch=1e-3).taxel_pitch == (1e-3, 1e-3)
    assert SlipDetector(taxel_pitch=(1e-3, 2e-3)).taxel_pitch == (1e-3, 2e-3)
