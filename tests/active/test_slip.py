"""Hold-then-slip simulation (Cattaneo-Mindlin, Coulomb) and the slip detector."""

import numpy as np
import pytest

from taxel.active import (
    SlipDetector,
    SlipScenario,
    calibrate_slip_detector,
    detect_slip,
    random_slip_scenario,
    score_slip_detection,
    simulate_slip,
    slip_sensors,
)
from taxel.active._slip_signals import cusum, motion_innovation, register, restore_charge
from taxel.transducers import charge_amplifier_output


@pytest.fixture(scope="module")
def steady():
    return simulate_slip(SlipScenario(kind="steady", after_time=0.1, seed=3))


def _compliance(sequence):
    material = slip_sensors()[0].cover.material
    shear = material.youngs_modulus / (2 * (1 + material.poisson_ratio))
    return 3 * (2 - material.poisson_ratio) / (16 * shear * sequence.contact_radius)


def test_sensors_run_at_one_kilohertz():
    static, piezo = slip_sensors()
    assert static.name == "resistive16" and piezo.name == "piezo8x8"
    assert static.frame_rate == piezo.frame_rate == 1000.0
    assert not static.is_dynamic and piezo.is_dynamic


def test_stick_follows_cattaneo_mindlin(slip, slip_scenario):
    stuck = slip.stick_ratio > 0
    last = int(np.nonzero(stuck)[0][-1])
    assert last == 159  # the ramp ends at 160 ms
    limit = slip_scenario.friction * slip_scenario.normal_force
    # the load ramps from 0 to mu N over the 100 ms ramp, and c / a = (1 - T / mu N)^(1/3)
    assert slip.tangential_load[last] == pytest.approx(0.99 * limit, rel=1e-6)
    ratio = slip.tangential_load[stuck] / limit
    assert slip.stick_ratio[stuck] == pytest.approx((1 - ratio) ** (1 / 3), abs=1e-9)
    # the pattern moved by the pad's tangential compliance, delta = K mu N (1 - (c/a)^2)
    direction = np.array([np.cos(slip_scenario.direction), np.sin(slip_scenario.direction)])
    moved = (slip.pattern_offset[last] - slip.pattern_offset[0]) @ direction
    expected = _compliance(slip) * limit * (1 - slip.stick_ratio[last] ** 2)
    assert moved == pytest.approx(expected, rel=0.02)
    assert 0.2e-3 < expected < 0.6e-3
    assert np.all(slip.sliding_displacement[stuck] == 0)


def test_gross_slip_relaxes_friction_and_slides(slip, slip_scenario):
    onset = slip.gross_frame
    # truth: the first frame past 2 um of sliding
    assert slip.sliding_displacement[onset] > 2e-6 >= slip.sliding_displacement[onset - 1]
    # sliding = v (t - tau (1 - exp(-t / tau))) + v_0 tau (1 - exp(-t / tau)) + the pad's
    # recoil K (mu_s - mu_k) N, v_0 the mean stick-phase speed over the last tau
    after = slip.time[-1] - (slip_scenario.hold_time + slip_scenario.load_time)
    tau = slip_scenario.relaxation_time
    limit = slip_scenario.friction * slip_scenario.normal_force
    recoil = _compliance(slip) * limit * (1 - slip_scenario.kinetic_ratio)
    onset_speed = _compliance(slip) * limit * (tau / slip_scenario.load_time) ** (2 / 3) / tau
    relaxed = 1 - np.exp(-after / tau)
    expected = (
        slip_scenario.sliding_speed * (after - tau * relaxed)
        + onset_speed * tau * relaxed
        + recoil
    )
    assert slip.sliding_displacement[-1] == pytest.approx(expected, rel=0.05)
    # the object's speed is continuous at the onset: no frame-to-frame step drops by half
    direction = np.array([np.cos(slip_scenario.direction), np.sin(slip_scenario.direction)])
    steps = np.diff(slip.pattern_offset @ direction)[onset - 5 : onset + 5]
    assert np.all(steps[1:] > 0.5 * steps[:-1])
    kinetic = slip_scenario.kinetic_ratio * slip_scenario.friction * slip_scenario.normal_force
    assert np.median(slip.tangential_load[-20:]) == pytest.approx(kinetic, rel=0.02)
    # incipient: the annulus has grown by 1 % of a within a few frames of the ramp's start
    assert 60 < slip.incipient_frame < 70


def test_frames_and_truth_of_each_kind(slip, hold, steady, slip_scenario):
    n = len(slip.time)
    assert slip.static_frames.shape == (n, 16, 16) and slip.piezo_frames.shape == (n, 8, 8)
    assert n == round(
        (slip_scenario.hold_time + slip_scenario.load_time + slip_scenario.after_time) * 1000
    )
    assert hold.gross_frame is None and hold.incipient_frame is None  # constant load
    assert steady.gross_frame is None and steady.incipient_frame is None
    # the PVDF array has forgotten the press: it starts near mid-range and stays there
    piezo = hold.piezo_frames.reshape(len(hold.time), -1).astype(float)
    assert np.abs(piezo - piezo[0].mean()).max() < 60  # counts, of 4096
    # a ramp that stays below mu N: incipient slip without gross slip
    ramp = simulate_slip(SlipScenario(kind="hold", load_time=0.08, plateau=0.7, seed=1))
    assert ramp.gross_frame is None and ramp.incipient_frame is not None
    assert ramp.tangential_load.max() == pytest.approx(0.7 * 0.8 * 4.0, rel=0.01)


def _detector(**settings):
    return SlipDetector(piezo_time_constant=slip_sensors()[1].transducer.time_constant, **settings)


def test_detector_finds_the_onsets(slip):
    found = _detector().run(slip.static_frames, slip.piezo_frames, frame_rate=1000.0)
    assert found.initial_state == "holding"
    incipient, gross = found.first("incipient"), found.first("gross")
    assert 0 <= incipient.frame - slip.incipient_frame <= 10
    assert gross.channel == "piezo" and 0 <= gross.frame - slip.gross_frame <= 3
    assert gross.time == pytest.approx(gross.frame / 1000.0)
    assert [event["kind"] for event in found.to_dict()["events"]] == ["incipient", "gross"]
    # the static array alone: the pattern's run-ahead; an alarm up to 2 frames before the
    # 2-um truth threshold is at the onset, not premature (as `score_slip_detection` counts)
    alone = _detector().run(slip.static_frames, frame_rate=1000.0).first("gross")
    assert alone.channel == "speed" and -2 <= alone.frame - slip.gross_frame <= 10
    assert found.position_noise == pytest.approx(found.position_noise)  # set, not NaN
    assert 1e-7 < found.position_noise < 2e-5


def test_static_backup_catches_what_the_piezo_misses(slip):
    # PVDF thresholds no innovation reaches: only the static run-ahead can decide
    deaf = _detector(piezo_threshold=1e9, onset_threshold=None, backup_threshold=5.0)
    gross = deaf.run(slip.static_frames, slip.piezo_frames, frame_rate=1000.0).first("gross")
    alone = _detector(gross_threshold=5.0).run(slip.static_frames, frame_rate=1000.0)
    assert gross.channel == "speed" and gross.frame == alone.first("gross").frame
    # left out, nothing decides; and the earlier of the two channels wins
    off = _detector(
        piezo_threshold=1e9, onset_threshold=None, backup_threshold=None, late_threshold=None
    )
    assert off.run(slip.static_frames, slip.piezo_frames, frame_rate=1000.0).first("gross") is None
    # the late channel alone (the long gap's run-ahead) still finds the slide, after the onset
    late = _detector(piezo_threshold=1e9, onset_threshold=None, backup_threshold=None)
    slide = late.run(slip.static_frames, slip.piezo_frames, frame_rate=1000.0).first("gross")
    assert slide.channel == "late" and -2 <= slide.frame - slip.gross_frame <= 20
    both = _detector(backup_threshold=5.0).run(
        slip.static_frames, slip.piezo_frames, frame_rate=1000.0
    )
    piezo = _detector(backup_threshold=None).run(
        slip.static_frames, slip.piezo_frames, frame_rate=1000.0
    )
    first = min(piezo.first("gross").frame, gross.frame)
    assert both.first("gross").frame == first
    with pytest.raises(ValueError, match="`backup_threshold` must be > 0"):
        SlipDetector(backup_threshold=-1.0)


def _blob_frames(centre):
    rows, cols = np.mgrid[:16, :16] * 2e-3
    frames = np.array(
        [
            1000 * np.exp(-((cols - 0.012 - c) ** 2 + (rows - 0.015) ** 2) / 2 / 0.004**2)
            for c in centre
        ]
    )
    return frames + np.random.default_rng(0).normal(0, 2, frames.shape)


def test_late_channel_is_armed_by_incipient_slip_and_sees_a_speed_change():
    frame = np.arange(260)
    late = SlipDetector(gross_threshold=1e9)  # static frames: only the late channel decides
    # from rest to 5 mm/s at frame 60 (a load ramp starting): incipient slip, not gross,
    # though the long gap's run-ahead is far past its threshold there
    ramp = 5e-3 * np.clip(frame - 60, 0, None) / 1000
    found = late.run(_blob_frames(ramp), frame_rate=1000.0)
    assert found.first("gross") is None and 60 < found.first("incipient").frame <= 65
    assert np.nanmax(found.late_statistic[60:90]) > late.late_threshold
    # the backup is armed the same way: the static run-ahead alone calls the ramp's start
    # gross slip, the backup behind a (deaf) PVDF array does not
    frames, piezo = _blob_frames(ramp), np.random.default_rng(1).normal(0, 1, (260, 4, 4))
    alone = SlipDetector(gross_threshold=5.0).run(frames, frame_rate=1000.0).first("gross")
    assert alone.channel == "speed" and 60 < alone.frame <= 70
    backup = SlipDetector(piezo_threshold=1e9, backup_threshold=5.0, late_threshold=None)
    assert backup.run(frames, piezo, frame_rate=1000.0).first("gross") is None
    # the same track speeding up to 20 mm/s at frame 160: gross slip, from the late channel
    slide = ramp + 15e-3 * np.clip(frame - 160, 0, None) / 1000
    gross = late.run(_blob_frames(slide), frame_rate=1000.0).first("gross")
    assert gross.channel == "late" and 160 <= gross.frame <= 165
    with pytest.raises(ValueError, match="`late_threshold` must be > 0"):
        SlipDetector(late_threshold=0.0)


def test_no_alarm_on_a_hold_or_on_steady_sliding(hold, steady):
    held = detect_slip(hold.static_frames, hold.piezo_frames, frame_rate=1000.0)
    assert held.initial_state == "holding" and held.events == ()
    assert np.nanmax(held.piezo_statistic) < SlipDetector().piezo_threshold
    sliding = detect_slip(steady.static_frames, steady.piezo_frames, frame_rate=1000.0)
    assert sliding.initial_state == "sliding" and sliding.events == ()
    # the pattern's speed is measured: 30 mm/s, the default sliding speed
    assert np.median(np.linalg.norm(sliding.velocity[10:-10], axis=1)) == pytest.approx(
        0.03, rel=0.2
    )


def test_score_counts_detections_and_false_alarms(slip, hold, steady):
    evaluation = score_slip_detection([slip, hold, steady])
    assert (evaluation.n_slip, evaluation.n_hold, evaluation.n_steady) == (1, 1, 1)
    assert evaluation.detection_rate == 1.0 and evaluation.false_alarm_rate == 0.0
    assert evaluation.incipient_detection_rate == 1.0
    summary = evaluation.to_dict()
    assert summary["gross"]["latency"]["frames"] == evaluation.latencies.tolist()


def test_channels_say_what_decides_and_from_when():
    # the blob slides from frame 60: incipient at 61; the late channel counts from the
    # first reference window (15 frames) that ends 12 frames before, after that decision
    rows, cols = np.mgrid[:16, :16] * 2e-3
    centre = np.where(np.arange(120) < 60, 0.0, 30e-3 * (np.arange(120) - 60) / 1000)
    blob = np.exp(-((cols - 15e-3 - centre[:, None, None]) ** 2 + (rows - 15e-3) ** 2) / 32e-6)
    detector = SlipDetector()
    detection = detector.run(blob, frame_rate=1000.0)
    channels = detector.channels(detection)
    assert [(name, threshold, start) for name, _, threshold, start in channels] == [
        ("speed", 5.0, 0),
        ("late", 15.5, 61 + 15 + 12 - 1),
    ]
    assert channels[0][1] is detection.speed_statistic
    assert np.allclose(detector.held_position(detection), detection.displacement[30:40].mean(0))
    assert detection.events[-1].frame == int(np.argmax(detection.speed_statistic > 5.0))


def test_bad_inputs_raise():
    with pytest.raises(ValueError, match="`warm_up` must be an integer >= 26, got 5"):
        SlipDetector(warm_up=5)
    # the late channel's first reference window (15 frames, ending 12 before) must start
    # within the sequence: 25 failed in `run` with NumPy's matmul message
    with pytest.raises(ValueError, match="`warm_up` must be an integer >= 26, got 25"):
        SlipDetector(warm_up=25)
    rows, cols = np.mgrid[:16, :16] * 2e-3
    centre = np.where(np.arange(120) < 60, 0.0, 30e-3 * (np.arange(120) - 60) / 1000)
    blob = np.exp(-((cols - 15e-3 - centre[:, None, None]) ** 2 + (rows - 15e-3) ** 2) / 32e-6)
    events = SlipDetector(warm_up=26).run(blob, frame_rate=1000.0).events
    assert [(event.kind, event.frame) for event in events] == [("incipient", 61), ("gross", 61)]
    with pytest.raises(ValueError, match="`gross_threshold` must be > 0"):
        SlipDetector(gross_threshold=0.0)
    with pytest.raises(ValueError, match="more than `warm_up` = 40 frames, got 30"):
        detect_slip(np.zeros((30, 4, 4)), frame_rate=1000.0)
    with pytest.raises(ValueError, match="`piezo_frames` has 50 frames"):
        detect_slip(np.zeros((60, 4, 4)), np.zeros((50, 2, 2)), frame_rate=1000.0)
    with pytest.raises(ValueError, match="`kind` must be one of slip, hold, steady"):
        random_slip_scenario("drop", 0)
    with pytest.raises(TypeError, match="`rng` must be None, a numpy.random.Generator"):
        random_slip_scenario("slip", "x")


def test_restore_charge_undoes_the_amplifier_leak():
    # a press held for 0.3 s fades from a charge amplifier (tau = 20 ms); restored, it stays
    time = np.arange(400) * 1e-3
    stress = -2e4 * np.clip((time - 0.02) / 0.05, 0.0, 1.0)[:, None] * np.array([1.0, 0.5])
    amplifier = dict(area=4e-6, feedback_capacitance=1e-10, feedback_resistance=2e8)
    output = charge_amplifier_output(stress.T, 1e-3, **amplifier).T
    assert abs(output[-1, 0]) < 1e-4 * abs(output[70, 0])  # faded
    restored = restore_charge(output, frame_rate=1000.0, time_constant=0.02)
    d33 = -3.3e-11  # PVDF, C/N
    expected = -d33 * 4e-6 * stress / 1e-10  # V = -d33 A sigma / C_f, no leak
    assert restored == pytest.approx(expected, rel=1e-9, abs=1e-12)


def test_motion_innovation_is_zero_on_a_straight_track_and_unit_on_noise():
    rng = np.random.default_rng(1)
    blob = np.exp(-(np.linspace(-2, 2, 30) ** 2))
    # a pattern sliding steadily (to first order): each frame on the line through the last
    frames = blob - 0.05 * np.arange(80)[:, None] * np.gradient(blob)
    steady = motion_innovation(frames, window=20, prediction=6, sigma=1e-3)
    assert np.all(np.isnan(steady[:27])) and np.nanmax(np.abs(steady)) < 0.05
    # it stops dead at frame 60: the innovation along its direction of motion is negative
    stopped = frames.copy()
    stopped[60:] = stopped[60]
    jump = motion_innovation(stopped, window=20, prediction=6, sigma=1e-3)
    assert jump[61] < -10 and np.nanargmin(jump) >= 60
    # white noise alone: z is standard normal
    noise = motion_innovation(rng.normal(0.0, 2.0, (4000, 30)), window=20, prediction=6, sigma=2.0)
    assert np.nanmean(noise**2) == pytest.approx(1.0, abs=0.06)


def test_cusum_and_register_known_values():
    assert cusum(np.array([0.0, 3.0, 3.0, -4.0, 5.0]), 1, 1.0).tolist()[1:] == [2.0, 4.0, 0.0, 4.0]
    rows, cols = np.mgrid[:16, :16]
    blob = np.exp(-((cols - 7.3) ** 2 + (rows - 8.1) ** 2) / 8.0)
    moved = np.exp(-((cols - 7.3 - 0.37) ** 2 + (rows - 8.1 + 0.21) ** 2) / 8.0)
    shift = register(moved[None], blob, (2e-3, 2e-3))[0]
    assert shift == pytest.approx([0.37 * 2e-3, -0.21 * 2e-3], abs=2e-6)


def test_calibration_keeps_the_false_alarm_budget(slip, hold, steady):
    trials = [slip, hold, steady]
    statistics = _detector().run(hold.static_frames, hold.piezo_frames, frame_rate=1000.0)
    worst = float(np.nanmax(statistics.piezo_statistic))  # the hold's largest CUSUM
    candidates = [0.5 * worst, 1.5 * worst, 1e9]
    calibration = calibrate_slip_detector(
        trials, false_alarm_budget=0.0, piezo_thresholds=candidates, gross_thresholds=[5.0]
    )
    # below the hold's maximum is a false alarm; 1e9 detects nothing: 1.5 x worst it is
    assert calibration.detector.piezo_threshold == pytest.approx(1.5 * worst)
    assert calibration.evaluation.false_alarm_rate == 0.0
    assert calibration.evaluation.detection_rate == 1.0
    assert calibration.to_dict()["static_evaluation"]["n_slip"] == 1
    with pytest.raises(ValueError, match="`false_alarm_budget` must lie in"):
        calibrate_slip_detector(trials, false_alarm_budget=2.0)


@pytest.mark.parametrize(
    ("settings", "message"),
    [
        ({"friction": -1.0}, "`friction` must be > 0, got -1"),
        ({"friction": np.nan}, "`friction` must be finite"),
        ({"hold_time": -1.0}, "`hold_time` must be > 0"),
        ({"kinetic_ratio": 2.0}, r"`kinetic_ratio` must lie in \(0, 1\], got 2"),
        ({"plateau": 5.0}, r"`plateau` must lie in \(0, 1\)"),
        ({"sliding_speed": -0.01}, "`sliding_speed` must be > 0"),
        ({"start": (0.0,)}, r"`start` must be an \(x, y\) pair"),
        ({"vibration_band": (400.0, 80.0)}, "`vibration_band` must be"),
        ({"vibration_band": (1.0, 2.0, 3.0)}, "`vibration_band` must be"),
        ({"seed": -3}, "`seed` must be >= 0"),
    ],
)
def test_scenario_settings_are_checked(settings, message):
    with pytest.raises((ValueError, TypeError), match=message):
        SlipScenario(**settings)
