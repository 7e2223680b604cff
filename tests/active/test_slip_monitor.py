"""SlipMonitor: slip detection one frame at a time, the same as SlipDetector.run."""

import numpy as np
import pytest

from taxel.active import SlipDetector, SlipMonitor, slip_sensors, slip_trials

STATISTICS = ("speed_statistic", "late_statistic", "piezo_statistic", "onset_statistic")


def _time_constant():
    return slip_sensors()[1].transducer.time_constant


# each decides gross slip on the first slip trial through its own channel: (detector,
# with PVDF frames?, that channel)
DETECTORS = {
    "pvdf": (lambda: SlipDetector(piezo_time_constant=_time_constant()), True, "piezo"),
    "pvdf, amplifier leak not undone": (lambda: SlipDetector(), True, "piezo"),
    "static only": (lambda: SlipDetector(), False, "speed"),
    "onset filter alone": (
        lambda: SlipDetector(
            piezo_time_constant=_time_constant(),
            piezo_threshold=1e9,
            backup_threshold=None,
            late_threshold=None,
        ),
        True,
        "onset",
    ),
    "late channel, static only": (lambda: SlipDetector(gross_threshold=1e9), False, "late"),
    "backup channel": (  # the second slip trial: the backup run-ahead decides
        lambda: SlipDetector(
            piezo_time_constant=_time_constant(), piezo_threshold=1e9, onset_threshold=None
        ),
        True,
        "late",
    ),
    "gross before incipient": (  # the incipient warning would come late: left out
        lambda: SlipDetector(piezo_time_constant=_time_constant(), incipient_threshold=300.0),
        True,
        "piezo",
    ),
}


@pytest.fixture(scope="module")
def trials():
    """Two slip trials, a hold and a steady slide (seed 2, about 1 s to simulate)."""
    return slip_trials(2, 1, 1, seed=2)


def _stream(detector, sequence, with_piezo, every=None):
    """Push the frames one by one: (monitor, events as returned, statistics per frame)."""
    monitor = SlipMonitor(detector, frame_rate=sequence.frame_rate)
    decided, statistics = [], []
    for index, frame in enumerate(sequence.static_frames):
        piezo = sequence.piezo_frames[index] if with_piezo else None
        if every and index % every == 0:  # a refused frame changes nothing
            with pytest.raises(ValueError):
                monitor.push(np.full_like(frame, np.nan, dtype=float), piezo)
        decided.extend(monitor.push(frame, piezo))
        statistics.append([getattr(monitor, name) for name in STATISTICS])
    return monitor, decided, np.array(statistics)


def _check_same(detector, sequence, with_piezo, every=None):
    piezo = sequence.piezo_frames if with_piezo else None
    batch = detector.run(sequence.static_frames, piezo, frame_rate=sequence.frame_rate)
    monitor, decided, statistics = _stream(detector, sequence, with_piezo, every)
    assert monitor.events == batch.events
    assert tuple(decided) == batch.events
    assert monitor.initial_state == batch.initial_state
    assert monitor.position_noise == batch.position_noise
    warm_up = detector.warm_up
    for column, name in enumerate(STATISTICS):  # the same numbers, to the last bit
        np.testing.assert_array_equal(statistics[warm_up:, column], getattr(batch, name)[warm_up:])
    np.testing.assert_array_equal(monitor.displacement, batch.displacement[-1])
    return batch


@pytest.mark.parametrize("name", list(DETECTORS))
def test_online_events_are_the_batch_events(trials, name):
    make, with_piezo, channel = DETECTORS[name]
    detector = make()
    assert [trial.scenario.kind for trial in trials] == ["slip", "slip", "hold", "steady"]
    selected = trials if name in ("pvdf", "static only") else trials[:2]
    results = [_check_same(detector, trial, with_piezo) for trial in selected]
    first, second = (result.events for result in results[:2])
    assert first[-1].kind == "gross" and first[-1].channel == channel
    if name == "backup channel":
        assert second[-1].channel == "speed"
    if name == "gross before incipient":
        assert [event.kind for event in first + second] == ["gross", "gross"]
    else:
        assert first[0].kind == "incipient"


def test_integer_frames_a_reset_and_a_longer_warm_up(trials):
    # raw ADC codes in a driver's narrower integers, a second grasp on the same monitor
    # after reset(), and a warm-up other than the default: still the batch's events
    slip = trials[0]
    codes, charges = slip.static_frames.astype(np.int32), slip.piezo_frames.astype(np.int16)
    assert np.array_equal(charges, slip.piezo_frames)  # (12-bit codes: no overflow)
    detector = SlipDetector(piezo_time_constant=_time_constant(), warm_up=60)
    batch = detector.run(codes, charges, frame_rate=slip.frame_rate)
    assert batch.events and batch.events[-1].kind == "gross"
    monitor = SlipMonitor(detector, frame_rate=slip.frame_rate)
    for grasp in range(2):
        for frame, charge in zip(codes, charges, strict=True):
            monitor.push(frame, charge)
        assert monitor.events == batch.events, grasp
        monitor.reset()
        assert monitor.state == "warming up" and monitor.events == ()


@pytest.mark.parametrize("with_piezo", [True, False])
def test_fixture_trials_and_refused_frames(slip, hold, with_piezo):
    # the shared slip trial (its onset channel is pinned in test_slip_onset) and a hold,
    # with a NaN frame refused every 50 frames: nothing changes
    detector = SlipDetector(piezo_time_constant=_time_constant())
    found = _check_same(detector, slip, with_piezo, every=50)
    assert [event.kind for event in found.events] == ["incipient", "gross"]
    assert _check_same(detector, hold, with_piezo).events == ()


def test_states_from_warm_up_to_gross(trials):
    detector = SlipDetector(piezo_time_constant=_time_constant())
    sequence = trials[0]
    monitor = SlipMonitor(detector, frame_rate=1000.0)
    states = []
    for frame, piezo in zip(sequence.static_frames, sequence.piezo_frames, strict=True):
        monitor.push(frame, piezo)
        states.append(monitor.state)
    incipient, gross = (event.frame for event in monitor.events)
    assert set(states[: detector.warm_up - 1]) == {"warming up"}
    assert set(states[detector.warm_up - 1 : incipient]) == {"holding"}
    assert set(states[incipient:gross]) == {"incipient"}
    assert set(states[gross:]) == {"gross"}
    assert monitor.n_frames == sequence.static_frames.shape[0]
    monitor.reset()  # a new grasp: warm-up again, any frame shape
    assert (monitor.state, monitor.n_frames, monitor.events) == ("warming up", 0, ())
    assert monitor.initial_state is None and monitor.displacement is None
    assert monitor.push(np.ones((4, 4))) == ()


def test_steady_sliding_is_sliding_from_the_start(trials):
    steady = trials[3]
    monitor = SlipMonitor(SlipDetector(), frame_rate=1000.0)
    for frame, piezo in zip(steady.static_frames, steady.piezo_frames, strict=True):
        assert monitor.push(frame, piezo) == ()
    assert monitor.state == "sliding" and monitor.events == ()


def test_default_detector_and_settings_read_when_made():
    detector = SlipDetector(warm_up=30)
    monitor = SlipMonitor(detector, frame_rate=500.0)
    detector.warm_up = 60  # a later change does not reach the monitor
    assert monitor.detector.warm_up == 30 and monitor.frame_rate == 500.0
    assert SlipMonitor(frame_rate=1000.0).detector.warm_up == 40


def test_refusals_name_the_parameter():
    with pytest.raises(TypeError, match="`detector` must be a SlipDetector, got 'fast'"):
        SlipMonitor("fast", frame_rate=1000.0)
    with pytest.raises(ValueError, match="`frame_rate` must be > 0, got 0"):
        SlipMonitor(SlipDetector(), frame_rate=0.0)
    detector = SlipDetector()
    detector.warm_up = 20  # (SlipDetector(warm_up=20) is refused when made)
    with pytest.raises(ValueError, match="an integer `warm_up` >= 26 frames, got 20"):
        SlipMonitor(detector, frame_rate=1000.0)
    detector.warm_up = 30.5
    with pytest.raises(ValueError, match="an integer `warm_up` >= 26 frames, got 30.5"):
        SlipMonitor(detector, frame_rate=1000.0)
    monitor = SlipMonitor(frame_rate=1000.0)
    with pytest.raises(ValueError, match="`static_frame` must have at least 2 rows"):
        monitor.push(np.ones((1, 16)))
    with pytest.raises(ValueError, match="`static_frame` must be 2-D, got shape"):
        monitor.push(np.ones((2, 16, 16)))
    with pytest.raises(TypeError, match="`static_frame` must be numeric, got text"):
        monitor.push([["1", "2"], ["3", "4"]])
    with pytest.raises(ValueError, match="`piezo_frame` must have at least one taxel"):
        monitor.push(np.ones((16, 16)), np.ones((0, 8)))
    assert monitor.n_frames == 0  # nothing was taken
    monitor.push(np.ones((16, 16)), np.zeros((8, 8)))
    with pytest.raises(
        ValueError, match=r"`static_frame` must have shape \(16, 16\), .* \(8, 8\)"
    ):
        monitor.push(np.ones((8, 8)), np.zeros((8, 8)))
    bad = np.ones((16, 16))
    bad[3, 4] = np.nan
    with pytest.raises(ValueError, match="`static_frame` must be finite everywhere, got 1 NaN"):
        monitor.push(bad, np.zeros((8, 8)))
    with pytest.raises(ValueError, match="`piezo_frame` must be given: .* with PVDF frames"):
        monitor.push(np.ones((16, 16)))
    with pytest.raises(ValueError, match=r"`piezo_frame` must have shape \(8, 8\), .* \(4, 4\)"):
        monitor.push(np.ones((16, 16)), np.zeros((4, 4)))
    with pytest.raises(ValueError, match="`piezo_frame` must be finite everywhere"):
        monitor.push(np.ones((16, 16)), np.full((8, 8), np.inf))
    assert monitor.n_frames == 1
    static_only = SlipMonitor(frame_rate=1000.0)
    static_only.push(np.ones((16, 16)))
    with pytest.raises(ValueError, match=r"`piezo_frame` must be None: .* shape \(8, 8\)"):
        static_only.push(np.ones((16, 16)), np.zeros((8, 8)))


def test_spline_shifter_is_ndimage_shift_to_the_last_bit(monkeypatch):
    from scipy import ndimage
    from scipy.ndimage import _nd_image

    from taxel.active._spline_shift import spline_shifter

    rng = np.random.default_rng(5)
    reference = rng.normal(500.0, 100.0, (16, 12))
    shifted = spline_shifter(reference)
    assert shifted.__qualname__ == "spline_shifter.<locals>.shifted"  # the fast path
    for rows, cols in rng.normal(0.0, 3.0, (200, 2)):
        expected = ndimage.shift(reference, (rows, cols), order=3, mode="nearest")
        np.testing.assert_array_equal(shifted(rows, cols), expected)

    def changed(*arguments):
        raise TypeError("zoom_shift() takes 10 arguments")

    monkeypatch.setattr(_nd_image, "zoom_shift", changed)  # a SciPy whose kernel changed
    slow = spline_shifter(reference)
    monkeypatch.undo()
    assert slow.__qualname__ == "_slow.<locals>.shifted"
    expected = ndimage.shift(reference, (0.3, -1.2), order=3, mode="nearest")
    np.testing.assert_array_equal(slow(0.3, -1.2), expected)
