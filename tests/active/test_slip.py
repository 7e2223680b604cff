"""Hold-then-slip simulation (Cattaneo-Mindlin, Coulomb) and the slip detector."""

import numpy as np
import pytest

from taxel.active import (
    SlipDetector,
    SlipScenario,
    detect_slip,
    random_slip_scenario,
    score_slip_detection,
    simulate_slip,
    slip_sensors,
)

SLIP = SlipScenario(
    kind="slip",
    normal_force=2.0,
    radius=0.05,
    friction=0.8,
    kinetic_ratio=0.8,
    initial_load=0.0,
    hold_time=0.06,
    load_time=0.1,
    sliding_speed=0.04,
    relaxation_time=2e-3,
    direction=0.5,
    seed=7,
)


@pytest.fixture(scope="module")
def slip():
    return simulate_slip(SLIP)


@pytest.fixture(scope="module")
def hold():
    return simulate_slip(SlipScenario(kind="hold", load_time=0.0, seed=3))


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


def test_stick_follows_cattaneo_mindlin(slip):
    stuck = slip.stick_ratio > 0
    last = int(np.nonzero(stuck)[0][-1])
    assert last == 159  # the ramp ends at 160 ms
    limit = SLIP.friction * SLIP.normal_force
    # the load ramps from 0 to mu N over the 100 ms ramp, and c / a = (1 - T / mu N)^(1/3)
    assert slip.tangential_load[last] == pytest.approx(0.99 * limit, rel=1e-6)
    ratio = slip.tangential_load[stuck] / limit
    assert slip.stick_ratio[stuck] == pytest.approx((1 - ratio) ** (1 / 3), abs=1e-9)
    # the pattern moved by the pad's tangential compliance, delta = K mu N (1 - (c/a)^2)
    direction = np.array([np.cos(SLIP.direction), np.sin(SLIP.direction)])
    moved = (slip.pattern_offset[last] - slip.pattern_offset[0]) @ direction
    expected = _compliance(slip) * limit * (1 - slip.stick_ratio[last] ** 2)
    assert moved == pytest.approx(expected, rel=0.02)
    assert 0.2e-3 < expected < 0.6e-3
    assert np.all(slip.sliding_displacement[stuck] == 0)


def test_gross_slip_relaxes_friction_and_slides(slip):
    onset = slip.gross_frame
    # truth: the first frame past 2 um of sliding
    assert slip.sliding_displacement[onset] > 2e-6 >= slip.sliding_displacement[onset - 1]
    # sliding = v (t - tau (1 - exp(-t / tau))) + v_0 tau (1 - exp(-t / tau)) + the pad's
    # recoil K (mu_s - mu_k) N, v_0 the mean stick-phase speed over the last tau
    after = slip.time[-1] - (SLIP.hold_time + SLIP.load_time)
    tau = SLIP.relaxation_time
    limit = SLIP.friction * SLIP.normal_force
    recoil = _compliance(slip) * limit * (1 - SLIP.kinetic_ratio)
    onset_speed = _compliance(slip) * limit * (tau / SLIP.load_time) ** (2 / 3) / tau
    relaxed = 1 - np.exp(-after / tau)
    expected = SLIP.sliding_speed * (after - tau * relaxed) + onset_speed * tau * relaxed + recoil
    assert slip.sliding_displacement[-1] == pytest.approx(expected, rel=0.05)
    # the object's speed is continuous at the onset: no frame-to-frame step drops by half
    direction = np.array([np.cos(SLIP.direction), np.sin(SLIP.direction)])
    steps = np.diff(slip.pattern_offset @ direction)[onset - 5 : onset + 5]
    assert np.all(steps[1:] > 0.5 * steps[:-1])
    kinetic = SLIP.kinetic_ratio * SLIP.friction * SLIP.normal_force
    assert np.median(slip.tangential_load[-20:]) == pytest.approx(kinetic, rel=0.02)
    # incipient: the annulus has grown by 1 % of a within a few frames of the ramp's start
    assert 60 < slip.incipient_frame < 70


def test_frames_and_truth_of_each_kind(slip, hold, steady):
    n = len(slip.time)
    assert slip.static_frames.shape == (n, 16, 16) and slip.piezo_frames.shape == (n, 8, 8)
    assert n == round((SLIP.hold_time + SLIP.load_time + SLIP.after_time) * 1000)
    assert hold.gross_frame is None and hold.incipient_frame is None  # constant load
    assert steady.gross_frame is None and steady.incipient_frame is None
    # the PVDF array has forgotten the press: it starts near mid-range and stays there
    piezo = hold.piezo_frames.reshape(len(hold.time), -1).astype(float)
    assert np.abs(piezo - piezo[0].mean()).max() < 60  # counts, of 4096
    # a ramp that stays below mu N: incipient slip without gross slip
    ramp = simulate_slip(SlipScenario(kind="hold", load_time=0.08, plateau=0.7, seed=1))
    assert ramp.gross_frame is None and ramp.incipient_frame is not None
    assert ramp.tangential_load.max() == pytest.approx(0.7 * 0.8 * 4.0, rel=0.01)


def test_detector_finds_the_onsets(slip):
    found = SlipDetector().run(slip.static_frames, slip.piezo_frames, frame_rate=1000.0)
    assert found.initial_state == "holding"
    incipient, gross = found.first("incipient"), found.first("gross")
    assert 0 <= incipient.frame - slip.incipient_frame <= 10
    assert 0 <= gross.frame - slip.gross_frame <= 10
    assert gross.time == pytest.approx(gross.frame / 1000.0)
    assert [event["kind"] for event in found.to_dict()["events"]] == ["incipient", "gross"]


def test_no_alarm_on_a_hold_or_on_steady_sliding(hold, steady):
    held = detect_slip(hold.static_frames, hold.piezo_frames, frame_rate=1000.0)
    assert held.initial_state == "holding" and held.events == ()
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


def test_bad_inputs_raise():
    with pytest.raises(ValueError, match="`warm_up` must be an integer >= 20, got 5"):
        SlipDetector(warm_up=5)
    with pytest.raises(ValueError, match="`gross_threshold` must be > 0"):
        SlipDetector(gross_threshold=0.0)
    with pytest.raises(ValueError, match="more than `warm_up` = 40 frames, got 30"):
        detect_slip(np.zeros((30, 4, 4)), frame_rate=1000.0)
    with pytest.raises(ValueError, match="`piezo_frames` has 50 frames"):
        detect_slip(np.zeros((60, 4, 4)), np.zeros((50, 2, 2)), frame_rate=1000.0)
    with pytest.raises(ValueError, match="`kind` must be one of slip, hold, steady"):
        random_slip_scenario("drop", 0)
