r"""Slip detection online, one frame at a time, for a robot's sensor loop.

`SlipMonitor` takes the frames of `SlipDetector.run` one by one and decides at each frame
what the batch detector decides at that frame: the same events (kind, frame, time, channel)
on any sequence, with the same statistics to the last bit. Every statistic of the batch
detector is causal once the warm-up is over (frame k >= `warm_up` uses frames <= k), so
nothing had to change:

- the reference image (the mean of the last 10 warm-up frames), the position noise, the
  initial state and the PVDF noise are the batch's warm-up fits, made once, at the last
  warm-up frame; the warm-up frames are then registered in order (each frame's
  Lucas-Kanade iteration starts from the previous estimate, as in `register`);
- recursions are kept as state: the registration's estimate, the running sum of the
  displacement from the held position (its 3-frame mean decides incipient slip), the
  charge restored by `restore_charge` and the CUSUM;
- windows are kept in bounded buffers of the most recent values: 28 positions (the
  reference windows of the run-ahead: 15 frames ending 3 or 12 frames back), the last
  prediction + 22 restored PVDF frames (`motion_innovation`), the last 6 innovations
  (`matched_filter`) and the last 4 running sums.

So each frame costs the same however many came before, except the last warm-up frame,
which registers all the warm-up frames at once (the reference they are registered to is
known only then). Two parts of `SlipDetection` are not causal and are not reproduced:
`velocity` (central differences use the next frame; the decisions never read it), and
the displacement and PVDF rest level of the warm-up frames themselves, which depend on
later warm-up frames (the reference image; the first 5 frames' mean); no decision is made
before the warm-up ends.
"""

from __future__ import annotations

import copy
import math
import sys
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_positive, is_whole
from taxel.active._slip import _DIRECTION, ONSET_TEMPLATE, SlipDetector, SlipEvent
from taxel.active._slip_signals import (
    _GAP,
    _LATE_GAP,
    _LEAST_WARM_UP,
    _REFERENCE,
    HELD_FRAMES,
    armed_from,
    charge_leak,
    motion_innovation,
    position_noise,
    register_frame,
    step_noise,
    track_deviation,
)
from taxel.active._spline_shift import spline_shifter

__all__ = ["SlipMonitor"]


def _nan_to_num(value: float) -> float:
    """`np.nan_to_num` of one float, as the batch detector applies it, 50 times quicker.

    NaN reads as 0 and an infinity as the largest double of its sign.
    """
    if value != value:
        return 0.0
    if value in (math.inf, -math.inf):
        return math.copysign(sys.float_info.max, value)
    return value


class _Recent:
    """The last `capacity` rows pushed, oldest first, in one contiguous array."""

    def __init__(self, capacity: int, shape: tuple[int, ...] = ()) -> None:
        self._array = np.empty((capacity, *shape))
        self.count = 0

    def push(self, row: Any) -> None:
        if self.count < self._array.shape[0]:
            self._array[self.count] = row
            self.count += 1
        else:
            self._array[:-1] = self._array[1:]
            self._array[-1] = row

    @property
    def rows(self) -> np.ndarray:
        return self._array[: self.count]

    @property
    def full(self) -> bool:
        return self.count == self._array.shape[0]


class SlipMonitor:
    """Detect incipient and gross slip online: push each frame, learn at once what it decided.

    Parameters
    ----------
    detector : SlipDetector, optional
        Its settings (thresholds, warm-up, PVDF time constant) are read when the monitor is
        made; default `SlipDetector()`. Its `warm_up` must still be at least 26 frames (the
        least a `SlipDetector` takes) if it was changed after the detector was made.
    frame_rate : float
        [Hz].

    Attributes
    ----------
    n_frames : int
        Frames pushed so far (the next frame's index).
    initial_state : str or None
        'holding' or 'sliding' (then no onset is reported), decided at the last warm-up
        frame; None before.
    position_noise : float
        Standard deviation of one frame's pattern position over the warm-up [m] (NaN before).
    displacement : numpy.ndarray or None
        (2,) the last frame's pattern displacement from the held reference (x, y) [m];
        None during the warm-up.
    speed_statistic, late_statistic, piezo_statistic, onset_statistic : float
        The last frame's statistics, as in `SlipDetection` (NaN during the warm-up, and the
        PVDF ones without PVDF frames).

    Notes
    -----
    The first frame fixes the frame shapes and whether PVDF frames come with the static
    ones: every later frame must match. A refused frame leaves the monitor as it was.
    The frames pushed give the same events, at the same frames, as `SlipDetector.run` on
    the whole sequence (see the module notes). The first `warm_up` frames are held; the
    last of them costs the registration of all of them, every later frame about one
    registration (a few Lucas-Kanade iterations on the static frame) and the PVDF
    innovation, independent of the number of frames before.

    Examples
    --------
    A blob that sits still for 60 frames and then slides at 30 mm/s (1 kHz, 2 mm pitch):

    >>> rows, cols = np.mgrid[:16, :16] * 2e-3
    >>> centre = np.where(np.arange(80) < 60, 0.0, 30e-3 * (np.arange(80) - 60) / 1000)
    >>> frames = np.array([1000 * np.exp(-((cols - 0.014 - c) ** 2 + (rows - 0.015) ** 2)
    ...                    / 2 / 0.004**2) for c in centre])
    >>> frames += np.random.default_rng(0).normal(0, 2, frames.shape)
    >>> monitor = SlipMonitor(SlipDetector(), frame_rate=1000.0)
    >>> for frame in frames:
    ...     for event in monitor.push(frame):
    ...         print(event.kind, event.frame, event.channel)
    incipient 61 displacement
    gross 61 speed
    >>> monitor.state, monitor.initial_state, monitor.n_frames
    ('gross', 'holding', 80)
    """

    def __init__(self, detector: SlipDetector | None = None, *, frame_rate: float) -> None:
        if detector is None:
            detector = SlipDetector()
        if not isinstance(detector, SlipDetector):
            raise TypeError(f"`detector` must be a SlipDetector, got {detector!r}")
        if not is_whole(detector.warm_up) or detector.warm_up < _LEAST_WARM_UP:
            # (changed after the detector was made, which checks it)
            raise ValueError(
                f"`detector` must have an integer `warm_up` >= {_LEAST_WARM_UP} frames, "
                f"got {detector.warm_up!r}"
            )
        self.detector = copy.copy(detector)
        self.frame_rate = check_positive("frame_rate", frame_rate)
        self.reset()

    def reset(self) -> None:
        """Forget every frame (a new grasp): the next frame starts a new warm-up."""
        self.n_frames = 0
        self.initial_state: str | None = None
        self.position_noise = float("nan")
        self.displacement: np.ndarray | None = None
        self.speed_statistic = self.late_statistic = float("nan")
        self.piezo_statistic = self.onset_statistic = float("nan")
        self._events: list[SlipEvent] = []
        self._static_shape: tuple[int, ...] | None = None
        self._piezo_shape: tuple[int, ...] | None = None
        self._incipient: int | None = None

    @property
    def events(self) -> tuple[SlipEvent, ...]:
        """The events so far, in time order: at most one incipient and one gross event."""
        return tuple(self._events)

    @property
    def state(self) -> str:
        """'warming up', 'holding', 'sliding' (from the start), 'incipient' or 'gross'."""
        if self.initial_state is None:
            return "warming up"
        if self.initial_state == "sliding" or not self._events:
            return self.initial_state
        return self._events[-1].kind

    def push(self, static_frame: Any, piezo_frame: Any = None) -> tuple[SlipEvent, ...]:
        """Take the next frame; return the events decided at it (usually none).

        Parameters
        ----------
        static_frame : array_like
            (rows, cols) frame of the static array (raw counts or pressure).
        piezo_frame : array_like, optional
            (rows', cols') frame of the PVDF array at the same instant: with every frame if
            with the first, else never.

        Returns
        -------
        tuple of SlipEvent
        """
        frame, piezo = self._check(static_frame, piezo_frame)
        index = self.n_frames
        warm_up = self.detector.warm_up
        if index == 0:
            self._warm_static = np.empty((warm_up, *frame.shape))
            self._warm_piezo = None if piezo is None else np.empty((warm_up, piezo.size))
            self._static_shape = frame.shape
            self._piezo_shape = None if piezo is None else piezo.shape
        self.n_frames += 1
        if index < warm_up:
            self._warm_static[index] = frame
            if self._warm_piezo is not None and piezo is not None:
                self._warm_piezo[index] = piezo.ravel()
            if index == warm_up - 1:
                self._finish_warm_up()
            return ()
        return self._step(index, frame, piezo)

    def _check(self, static_frame: Any, piezo_frame: Any) -> tuple[np.ndarray, Any]:
        frame = as_finite_array("static_frame", static_frame, ndim=2)
        if self._static_shape is None:
            if min(frame.shape) < 2:  # the pattern's gradient needs two taxels each way
                raise ValueError(
                    "`static_frame` must have at least 2 rows and 2 columns of taxels, got "
                    f"shape {frame.shape}"
                )
        elif frame.shape != self._static_shape:
            raise ValueError(
                f"`static_frame` must have shape {self._static_shape}, that of the first "
                f"frame, got {frame.shape}"
            )
        started = self.n_frames > 0
        if piezo_frame is None:
            if started and self._piezo_shape is not None:
                raise ValueError(
                    "`piezo_frame` must be given: the monitor was started with PVDF frames, "
                    "got None"
                )
            return frame, None
        piezo = as_finite_array("piezo_frame", piezo_frame, ndim=2)
        if started and self._piezo_shape is None:
            raise ValueError(
                "`piezo_frame` must be None: the monitor was started without PVDF frames, "
                f"got an array of shape {piezo.shape}"
            )
        if not started and piezo.size == 0:
            raise ValueError(f"`piezo_frame` must have at least one taxel, got {piezo.shape}")
        if started and piezo.shape != self._piezo_shape:
            raise ValueError(
                f"`piezo_frame` must have shape {self._piezo_shape}, that of the first "
                f"frame, got {piezo.shape}"
            )
        return frame, piezo

    def _finish_warm_up(self) -> None:
        """The batch detector's warm-up fits, and the recursions brought up to date."""
        detector, rate = self.detector, self.frame_rate
        warm_up = detector.warm_up
        pitch = detector.taxel_pitch
        self._scale = np.array([pitch[1], pitch[0]])
        reference = self._warm_static[warm_up - HELD_FRAMES : warm_up].mean(axis=0)
        self._shifted = spline_shifter(reference)
        shifts = np.zeros((warm_up, 2))
        estimate = np.zeros(2)
        for index, frame in enumerate(self._warm_static):
            estimate = register_frame(frame, self._shifted, estimate)
            shifts[index] = estimate
        self._estimate = estimate
        displacement = shifts * self._scale
        sigma, trend = position_noise(displacement, warm_up)
        sliding = float(np.linalg.norm(trend)) * rate > detector.rest_speed
        self.initial_state = "sliding" if sliding else "holding"
        self.position_noise = sigma
        self._held = displacement[warm_up - HELD_FRAMES : warm_up].mean(axis=0)
        self._limit = detector.incipient_threshold * sigma / np.sqrt(3.0)
        self._positions = _Recent(_REFERENCE + _LATE_GAP + 1, (2,))
        self._sums = _Recent(4, (2,))
        for position, total in zip(
            displacement, np.cumsum(displacement - self._held, axis=0), strict=True
        ):
            self._positions.push(position)
            self._sums.push(total)
        self._ahead: dict[int, float] = {}
        del self._warm_static
        if self._warm_piezo is not None:
            self._start_piezo(self._warm_piezo)
            self._warm_piezo = None

    def _start_piezo(self, flat: np.ndarray) -> None:
        detector, rate = self.detector, self.frame_rate
        self._time_constant = detector.piezo_time_constant
        if self._time_constant is not None:
            self._decay, self._gain = charge_leak(
                frame_rate=rate, time_constant=self._time_constant
            )
            self._rest = flat[: min(5, flat.shape[0])].mean(axis=0)
            self._level: np.ndarray | None = None
            flat = np.array([self._restore(row) for row in flat])
        self._prediction = max(3, int(round(rate / detector.cutoff)))
        self._piezo_sigma = max(step_noise(flat), 1e-12)
        z = self._innovation(flat)
        self._restored = _Recent(self._prediction + _DIRECTION + 2, (flat.shape[1],))
        for row in flat[-(self._prediction + _DIRECTION + 2) :]:
            self._restored.push(row)
        self._template = np.asarray(ONSET_TEMPLATE, dtype=float)
        self._template_norm = np.linalg.norm(self._template)
        self._innovations = _Recent(self._template.size)
        for value in np.nan_to_num(z[-self._template.size :]):
            self._innovations.push(value)
        self._cusum = 0.0

    def _restore(self, row: np.ndarray) -> np.ndarray:
        """One frame of `restore_charge`: the running sum of the charge steps."""
        level = row - self._rest
        if self._level is None:
            self._charge = level
        else:
            self._charge = self._charge + (level - self._decay * self._level)
        self._level = level
        return self._charge / self._gain

    def _innovation(self, restored: np.ndarray) -> np.ndarray:
        return motion_innovation(
            restored,
            window=_DIRECTION,
            prediction=self._prediction,
            sigma=self._piezo_sigma,
        )

    def _step(
        self, index: int, frame: np.ndarray, piezo: np.ndarray | None
    ) -> tuple[SlipEvent, ...]:
        self._estimate = register_frame(frame, self._shifted, self._estimate)
        position = self._estimate * self._scale
        self.displacement = position
        self._positions.push(position)
        self._sums.push(self._sums.rows[-1] + (position - self._held))
        self.speed_statistic = self._run_ahead(index, _GAP)
        self.late_statistic = self._run_ahead(index, _LATE_GAP)
        if piezo is not None:
            self._piezo_step(piezo)
        if self.initial_state != "holding" or any(e.kind == "gross" for e in self._events):
            return ()
        found = []
        if self._incipient is None:
            sums = self._sums.rows
            mean3 = np.linalg.norm((sums[3] - sums[0])[None, :], axis=1)[0] / 3.0
            if mean3 > self._limit:
                self._incipient = index
                found.append(
                    SlipEvent("incipient", index, index / self.frame_rate, "displacement")
                )
        for channel, value, threshold in self._channels(index, piezo is not None):
            if value > threshold:  # NaN never passes
                found.append(SlipEvent("gross", index, index / self.frame_rate, channel))
                break
        self._events.extend(found)
        return tuple(found)

    def _run_ahead(self, index: int, gap: int) -> float:
        """The run-ahead of `run_ahead` at this frame: 2-frame mean of `track_deviation`."""
        rows = self._positions.rows
        end = rows.shape[0] - gap
        window = rows[end - _REFERENCE : end]
        ahead = track_deviation(window, rows[-1], self._held, self.position_noise, _REFERENCE, gap)
        before = self._ahead.get(gap)
        self._ahead[gap] = ahead
        return ahead if before is None else 0.5 * (ahead + before)

    def _piezo_step(self, piezo: np.ndarray) -> None:
        row = piezo.ravel().astype(float)
        if self._time_constant is not None:
            row = self._restore(row)
        self._restored.push(row)
        z = self._innovation(self._restored.rows)[-1] if self._restored.full else np.nan
        z = float(z)
        self._cusum = max(0.0, self._cusum + _nan_to_num(z * z - 1.0) - self.detector.drift)
        self.piezo_statistic = float(self._cusum)
        self._innovations.push(_nan_to_num(z))
        values = self._innovations.rows
        total = sum(weight * values[i] for i, weight in enumerate(self._template))
        self.onset_statistic = float(total / self._template_norm)

    def _channels(self, index: int, with_piezo: bool) -> list[tuple[str, float, float]]:
        """`SlipDetector.channel_plan` at this frame: (channel, value, threshold), tie order."""
        values = {
            "piezo": self.piezo_statistic,
            "onset": self.onset_statistic,
            "speed": self.speed_statistic,
            "late": self.late_statistic,
        }
        never = index + 1  # (not armed yet: no incipient decision)
        return [
            (channel, values[channel], threshold)
            for channel, threshold, gap in self.detector.channel_plan(with_piezo)
            if index >= armed_from(self._incipient, gap, never)
        ]
