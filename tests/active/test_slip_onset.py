"""The slip detector's onset channel: a matched filter of the PVDF innovation."""

import numpy as np
import pytest

from taxel.active import (
    SlipDetector,
    calibrate_slip_detector,
    slip_sensors,
)
from taxel.active._slip import ONSET_TEMPLATE, ONSET_THRESHOLD
from taxel.active._slip_signals import matched_filter


def _detector(**settings):
    return SlipDetector(piezo_time_constant=slip_sensors()[1].transducer.time_constant, **settings)


def test_matched_filter_known_values_and_noise_units():
    z = np.array([0.0, 1.0, -2.0, 0.0, np.nan])
    result = matched_filter(z, [1.0, -2.0], 2)
    assert np.isnan(result[:2]).all()  # before `start`
    # (1 * -2 - 2 * 0) / sqrt(5), then NaN counts as 0
    assert result[2:].tolist() == pytest.approx([5 / 5**0.5, -2 / 5**0.5, 0.0])
    assert np.isnan(matched_filter(np.ones(3), ONSET_TEMPLATE, 0)).all()  # shorter than it
    # white N(0, 1) in, N(0, 1) out: the threshold is in noise standard deviations
    noise = np.random.default_rng(4).standard_normal(40000)
    filtered = matched_filter(noise, ONSET_TEMPLATE, 0)
    assert np.nanmean(filtered) == pytest.approx(0.0, abs=0.02)
    assert np.nanvar(filtered) == pytest.approx(1.0, abs=0.03)


def test_onset_channel_decides_within_three_frames(slip, hold):
    assert len(ONSET_TEMPLATE) == 6 and ONSET_THRESHOLD == 4.25
    # the PVDF CUSUM, the backup and the late channel left out: the onset filter decides
    alone = _detector(piezo_threshold=1e9, backup_threshold=None, late_threshold=None)
    found = alone.run(slip.static_frames, slip.piezo_frames, frame_rate=1000.0)
    gross = found.first("gross")
    assert slip.gross_frame == 161
    assert gross.channel == "onset" and gross.frame == 163  # 2 frames after the 2 um truth
    assert found.onset_statistic[163] == pytest.approx(6.08, abs=0.01)
    assert np.isnan(found.onset_statistic[: alone.warm_up]).all()
    # a constant hold stays below it: largest value 3.0 noise standard deviations
    held = alone.run(hold.static_frames, hold.piezo_frames, frame_rate=1000.0)
    assert held.events == ()
    assert np.nanmax(held.onset_statistic) == pytest.approx(3.01, abs=0.01)
    # left out, nothing decides; without PVDF frames there is no onset statistic
    off = _detector(
        piezo_threshold=1e9, onset_threshold=None, backup_threshold=None, late_threshold=None
    )
    assert off.run(slip.static_frames, slip.piezo_frames, frame_rate=1000.0).first("gross") is None
    static = alone.run(slip.static_frames, frame_rate=1000.0)
    assert np.isnan(static.onset_statistic).all()
    with pytest.raises(ValueError, match="`onset_threshold` must be > 0"):
        SlipDetector(onset_threshold=0.0)


def test_calibration_sets_the_onset_threshold(slip, hold):
    statistics = _detector().run(hold.static_frames, hold.piezo_frames, frame_rate=1000.0)
    worst = float(np.nanmax(statistics.onset_statistic))  # the hold's largest value, 3.01
    calibration = calibrate_slip_detector(
        [slip, hold],
        false_alarm_budget=0.0,
        gross_thresholds=[5.0],
        piezo_thresholds=[1e9],
        onset_thresholds=[0.5 * worst, 1.5 * worst, 1e9],
        backup_thresholds=[],
        late_thresholds=[],
    )
    # below the hold's maximum is a false alarm; 1e9 detects nothing: 1.5 x worst it is
    assert calibration.detector.onset_threshold == pytest.approx(1.5 * worst)
    assert calibration.to_dict()["onset_threshold"] == pytest.approx(4.52, abs=0.01)
    assert calibration.evaluation.detection_within[3] == 1.0
    assert calibration.evaluation.false_alarm_rate == 0.0
