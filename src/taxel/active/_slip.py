r"""Slip detection in a sequence of frames: incipient slip and gross slip, with times.

Two signals (chapter seed, section 25.3, "Piezoelectric"; Ellis seed, section 2.2):

- The displacement of the contact pattern on a static array. Each frame is registered to
  the held reference image by iterated Lucas-Kanade least squares (the shift d that best
  explains I_k = I_ref(x - d) over the whole image, the reference re-sampled at the current
  estimate by cubic splines). While the object sticks, the pattern moves only by the pad's
  tangential compliance (Cattaneo-Mindlin); once it slides, it moves at the sliding speed.
- The PVDF array (its charge amplifier sees only changes, eq. 25.17-25.18), its leak undone
  when the amplifier's time constant is known: each frame is predicted by a straight line
  through the previous frames, and the innovation is projected on the direction in which
  the pattern has been moving (`motion_innovation`). The onset of gross slip is an
  innovation of either sign along that direction: the first frames read as braking
  (backward: the friction drops from mu_s N to mu_k N, and the traction's stress under the
  pad with it), the forward innovations of the sliding pattern and of its stick-slip
  vibrations follow from about 4 frames after the onset; the CUSUM squares the innovation,
  so both count. A held or steadily loaded contact leaves only noise. The shape of the
  onset is also known: the pattern speeds up in the last frames of the stick phase (the
  stick disc vanishes), then brakes; a matched filter for that shape tests it directly.

Decisions are causal (frame k uses frames <= k). The first `warm_up` frames set each
channel's noise level and the initial state: holding (the pattern at rest) or already
sliding, in which case no onset is reported. Then:

- incipient slip: the pattern has left its held position by more than `incipient_threshold`
  noise standard deviations (averaged over 3 frames): a tangential load is building up, and
  with it the slip annulus;
- gross slip, from the PVDF array when its frames are given: a one-sided CUSUM (Page
  1954) of the squared innovation, S_k = max(0, S_{k-1} + z_k^2 - 1 - `drift`), passes
  `piezo_threshold` (channel 'piezo'); or the innovation of the last 6 frames, correlated
  with the mean onset shape `ONSET_TEMPLATE` (`matched_filter`, N(0, 1) on noise), passes
  `onset_threshold` (channel 'onset'). From the static array alone otherwise: the pattern
  runs ahead of where its recent motion would have put it (a line fitted to the positions
  of a reference window of 15 frames, ending 3 frames before, extrapolated to the current
  frame; the deviation along the direction of travel, in noise units and averaged over 2
  frames, passes `gross_threshold`; channel 'speed'). With PVDF frames the run-ahead
  decides only past the higher `backup_threshold`: at `gross_threshold` it adds premature
  alarms (the Cattaneo-Mindlin shift speeds up without bound as the stick disc vanishes,
  which looks like the start of sliding), but above it, it catches most of the slips whose
  onset the PVDF misses, 5-20 frames late. As a backup it is armed like the late channel
  (below): the start of a load ramp can pass its threshold too.
- gross slip, late: the same run-ahead against the track of a reference window that ends
  12 frames before the current frame (channel 'late', past `late_threshold`, with or
  without PVDF frames). A slow slide (10-30 mm/s) reaches its sliding speed over several
  relaxation times of the friction (2-8 ms), and the traction's stress falls with the
  friction meanwhile, which the registration reads as a step back: the short gap's track
  keeps up and its run-ahead stays below threshold, while the long gap's does not. It is
  armed only once its reference window lies wholly after the incipient decision, so that
  the track it extrapolates is that of the loaded contact, never the rest before the load
  began: the start of a load ramp also jumps from rest to a few mm/s (the
  Cattaneo-Mindlin shift starts linearly in the load), and it is incipient slip, not gross.

The default thresholds were set by `calibrate_slip_detector` on simulated calibration trials
(`slip_trials` with seeds 101 and 303, 120 slip, 60 hold and 60 steady trials, the
amplifiers' time constant given) for at most 2.5 % false alarms (half of issue 6's
budget), maximising the slips detected within 3 frames and then those detected at all
(which sets the late channel), and are scored on other trials in
`docs/benchmarks.md`. What no threshold can fix: in the first 3 frames of gross slip the
friction has dropped by only a fraction of (mu_s - mu_k) N and the stick-slip vibrations
have often not started (see the benchmark).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_positive, is_whole
from taxel.active._slip_signals import (
    _GAP,
    _LATE_GAP,
    _LEAST_WARM_UP,
    _REFERENCE,
    HELD_FRAMES,
    armed_from,
    cusum,
    matched_filter,
    motion_innovation,
    position_noise,
    register,
    restore_charge,
    run_ahead,
    step_noise,
)

__all__ = ["SlipDetection", "SlipDetector", "SlipEvent", "detect_slip"]

# set on calibration trials by `calibrate_slip_detector` (see the module notes)
GROSS_THRESHOLD = 5.0
PIEZO_THRESHOLD = 15.0
BACKUP_THRESHOLD = 8.0
LATE_THRESHOLD = 15.5
ONSET_THRESHOLD = 4.25
# the mean PVDF innovation z of the 120 calibration slip trials (seeds 101 and 303) in the
# frames onset - 2 .. onset + 3: the stick phase's last speed-up, then the braking
ONSET_TEMPLATE = (0.7, 1.2, -0.5, -2.5, -2.2, -0.3)

_DIRECTION = 20  # frames over which the PVDF pattern's direction of motion is taken


@dataclass(frozen=True)
class SlipEvent:
    """One detected slip event.

    Attributes
    ----------
    kind : str
        'incipient' or 'gross'.
    frame : int
        The frame at which it was decided (causal).
    time : float
        That frame's time [s] from the first frame.
    channel : str
        What decided it: 'displacement', 'speed', 'late', 'piezo' or 'onset'.
    """

    kind: str
    frame: int
    time: float
    channel: str

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary."""
        return {
            "kind": self.kind,
            "frame": self.frame,
            "time_s": self.time,
            "channel": self.channel,
        }


@dataclass(frozen=True)
class SlipDetection:
    """The slip events of a sequence and the statistics behind them.

    Attributes
    ----------
    events : tuple of SlipEvent
        In time order: at most one incipient and one gross event.
    initial_state : str
        'holding' or 'sliding' (then no onset is reported).
    displacement : numpy.ndarray
        (n_frames, 2) pattern displacement from the held reference (x, y) [m].
    velocity : numpy.ndarray
        (n_frames, 2) pattern velocity (central differences of the displacement) [m/s].
    speed_statistic : numpy.ndarray
        (n_frames,) run-ahead of the pattern in noise units (NaN during the warm-up).
    late_statistic : numpy.ndarray
        (n_frames,) the same against the track of a reference window ending 12 frames
        before (NaN during the warm-up; armed by the decision, after incipient slip).
    piezo_statistic : numpy.ndarray
        (n_frames,) CUSUM of the squared PVDF innovation (NaN during the warm-up, or all NaN
        without piezo frames).
    frame_rate : float
        [Hz].
    position_noise : float
        Standard deviation of one frame's pattern position over the warm-up [m].
    onset_statistic : numpy.ndarray
        (n_frames,) the PVDF innovation's matched filter for the onset shape (NaN during
        the warm-up; empty, or all NaN, without piezo frames).
    """

    events: tuple[SlipEvent, ...]
    initial_state: str
    displacement: np.ndarray = field(repr=False)
    velocity: np.ndarray = field(repr=False)
    speed_statistic: np.ndarray = field(repr=False)
    late_statistic: np.ndarray = field(repr=False)
    piezo_statistic: np.ndarray = field(repr=False)
    frame_rate: float = 1000.0
    position_noise: float = float("nan")
    onset_statistic: np.ndarray = field(repr=False, default_factory=lambda: np.empty(0))

    def first(self, kind: str) -> SlipEvent | None:
        """The event of `kind` ('incipient' or 'gross'), or None."""
        return next((event for event in self.events if event.kind == kind), None)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (events and the initial state)."""
        return {
            "initial_state": self.initial_state,
            "frame_rate_hz": self.frame_rate,
            "events": [event.to_dict() for event in self.events],
        }


class SlipDetector:
    """Detect incipient and gross slip in a sequence of tactile frames.

    Parameters
    ----------
    taxel_pitch : float or (float, float), default 2e-3
        Pitch of the static array [m] ((row, col) pitch for a pair).
    warm_up : int, default 40
        Frames that set the noise levels and the initial state.
    incipient_threshold : float, default 5.0
        Displacement from the held position (mean of 3 frames), in its noise standard
        deviations.
    gross_threshold : float, default 5.0
        Run-ahead of the pattern past its extrapolated track, in noise standard deviations
        (decides gross slip without PVDF frames).
    piezo_threshold : float, default 15.0
        CUSUM threshold h of the piezo channel.
    backup_threshold : float or None, default 8.0
        With PVDF frames, the run-ahead still decides gross slip past this threshold (a
        backup for onsets the PVDF misses), counted once its reference window lies wholly
        after the incipient decision; None leaves it out.
    late_threshold : float or None, default 15.5
        Run-ahead past the track of a reference window ending 12 frames before, in noise
        standard deviations, counted once that window lies wholly after the incipient
        decision (decides gross slip with or without PVDF frames: slow slides that the
        other channels miss); None leaves it out.
    onset_threshold : float or None, default 4.25
        With PVDF frames, the matched filter of the innovation for the onset shape
        (`ONSET_TEMPLATE`, in noise standard deviations) decides gross slip past this
        threshold; None leaves it out.
    drift : float, default 2.0
        CUSUM drift nu: the squared innovation, in excess of its mean 1, that does not
        accumulate.
    cutoff : float, default 160.0
        The piezo channel's straight-line predictor spans frame_rate / cutoff frames (at
        least 3): motion slower than about `cutoff` [Hz] is predicted, faster is innovation.
    rest_speed : float, default 5e-3
        Largest warm-up pattern speed of a holding contact [m/s].
    piezo_time_constant : float, optional
        R_f C_f of the PVDF charge amplifiers [s]; when given, their leak is undone
        (`restore_charge`) before the innovation is formed.

    Notes
    -----
    See the module notes. The position noise sigma is measured over the warm-up about a
    fitted line (whose slope also decides whether the contact is held). The direction of
    travel is that of the displacement from the held position (while that is within
    3 sigma, the size of the deviation is used instead). The PVDF noise is measured over
    the warm-up from frame-to-frame changes (median absolute deviation over all taxels).
    """

    def __init__(
        self,
        *,
        taxel_pitch: Any = 2e-3,
        warm_up: int = 40,
        incipient_threshold: float = 5.0,
        gross_threshold: float = GROSS_THRESHOLD,
        piezo_threshold: float = PIEZO_THRESHOLD,
        backup_threshold: float | None = BACKUP_THRESHOLD,
        late_threshold: float | None = LATE_THRESHOLD,
        onset_threshold: float | None = ONSET_THRESHOLD,
        drift: float = 2.0,
        cutoff: float = 160.0,
        rest_speed: float = 5e-3,
        piezo_time_constant: float | None = None,
    ) -> None:
        pitch = as_finite_array("taxel_pitch", taxel_pitch).ravel()
        if np.ndim(taxel_pitch) > 1 or pitch.size not in (1, 2):
            raise ValueError(f"`taxel_pitch` must be one or two lengths [m], got {taxel_pitch!r}")
        for value in np.broadcast_to(pitch, (2,)):
            check_positive("taxel_pitch", value)
        self.taxel_pitch = (float(pitch[0]), float(pitch[-1]))
        # the late channel's first reference window must start within the sequence
        if not is_whole(warm_up) or warm_up < _LEAST_WARM_UP:
            raise ValueError(f"`warm_up` must be an integer >= {_LEAST_WARM_UP}, got {warm_up!r}")
        self.warm_up = int(warm_up)
        self.incipient_threshold = check_positive("incipient_threshold", incipient_threshold)
        self.gross_threshold = check_positive("gross_threshold", gross_threshold)
        self.piezo_threshold = check_positive("piezo_threshold", piezo_threshold)
        self.backup_threshold = (
            None
            if backup_threshold is None
            else check_positive("backup_threshold", backup_threshold)
        )
        self.late_threshold = (
            None if late_threshold is None else check_positive("late_threshold", late_threshold)
        )
        self.onset_threshold = (
            None if onset_threshold is None else check_positive("onset_threshold", onset_threshold)
        )
        self.drift = check_positive("drift", drift, allow_zero=True)
        self.cutoff = check_positive("cutoff", cutoff)
        self.rest_speed = check_positive("rest_speed", rest_speed)
        self.piezo_time_constant = (
            None
            if piezo_time_constant is None
            else check_positive("piezo_time_constant", piezo_time_constant)
        )

    def run(
        self, static_frames: Any, piezo_frames: Any = None, *, frame_rate: float
    ) -> SlipDetection:
        """Detect slip in a sequence.

        Parameters
        ----------
        static_frames : array_like
            (n_frames, rows, cols) frames of a static array (raw counts or pressure).
        piezo_frames : array_like, optional
            (n_frames, rows', cols') frames of a PVDF array taken at the same instants.
        frame_rate : float
            [Hz].

        Returns
        -------
        SlipDetection
        """
        frames = as_finite_array("static_frames", static_frames, ndim=3)
        if min(frames.shape[1:]) < 2:  # the pattern's gradient needs two taxels each way
            raise ValueError(
                "`static_frames` must have at least 2 rows and 2 columns of taxels, got "
                f"frames of {frames.shape[1]} x {frames.shape[2]}"
            )
        rate = check_positive("frame_rate", frame_rate)
        n = frames.shape[0]
        if n <= self.warm_up:
            raise ValueError(
                f"`static_frames` must hold more than `warm_up` = {self.warm_up} frames, got {n}"
            )
        reference = frames[self.warm_up - HELD_FRAMES : self.warm_up].mean(axis=0)
        displacement = register(frames, reference, self.taxel_pitch)
        # per-frame noise of the position, from the warm-up about its own trend
        sigma, trend = position_noise(displacement, self.warm_up)
        sliding = float(np.linalg.norm(trend)) * rate > self.rest_speed
        speed_statistic = run_ahead(displacement, sigma, self.warm_up, _REFERENCE, _GAP)
        late_statistic = run_ahead(displacement, sigma, self.warm_up, _REFERENCE, _LATE_GAP)
        piezo_statistic, onset_statistic = np.full(n, np.nan), np.full(n, np.nan)
        if piezo_frames is not None:
            piezo = as_finite_array("piezo_frames", piezo_frames, ndim=3)
            if piezo.shape[1] * piezo.shape[2] == 0:
                raise ValueError(f"`piezo_frames` must have at least one taxel, got {piezo.shape}")
            if piezo.shape[0] != n:
                raise ValueError(
                    f"`piezo_frames` has {piezo.shape[0]} frames but `static_frames` has {n}"
                )
            z = self.piezo_innovation(piezo, rate)
            piezo_statistic = cusum(np.nan_to_num(z**2 - 1.0), self.warm_up, self.drift)
            onset_statistic = matched_filter(z, ONSET_TEMPLATE, self.warm_up)
        statistics = SlipDetection(
            events=(),
            initial_state="sliding" if sliding else "holding",
            displacement=displacement,
            velocity=np.gradient(displacement, axis=0) * rate,
            speed_statistic=speed_statistic,
            late_statistic=late_statistic,
            piezo_statistic=piezo_statistic,
            frame_rate=rate,
            position_noise=sigma,
            onset_statistic=onset_statistic,
        )
        return self.decide(statistics)

    def decide(self, detection: SlipDetection) -> SlipDetection:
        """The events this detector's thresholds give on the statistics of a detection.

        The statistics do not depend on the thresholds (only on `drift`, `cutoff`, the
        warm-up and the time constant), so thresholds can be tried on one run's statistics
        (`calibrate_slip_detector` does).
        """
        events: list[SlipEvent] = []
        if detection.initial_state == "holding":
            events = self._events(detection)
        return replace(detection, events=tuple(events))

    def piezo_innovation(self, piezo: np.ndarray, rate: float) -> np.ndarray:
        """The PVDF innovation z_k of each frame (`motion_innovation`), (n_frames,)."""
        flat = piezo.reshape(piezo.shape[0], -1).astype(float)
        if self.piezo_time_constant is not None:
            flat = restore_charge(flat, frame_rate=rate, time_constant=self.piezo_time_constant)
        sigma = step_noise(flat[: self.warm_up])
        prediction = max(3, int(round(rate / self.cutoff)))
        return motion_innovation(
            flat, window=_DIRECTION, prediction=prediction, sigma=max(sigma, 1e-12)
        )

    def piezo_cusum(self, piezo: np.ndarray, rate: float) -> np.ndarray:
        """The piezo channel's CUSUM of z_k^2 - 1, from the end of the warm-up, (n_frames,)."""
        z = self.piezo_innovation(piezo, rate)
        return cusum(np.nan_to_num(z**2 - 1.0), self.warm_up, self.drift)

    def held_position(self, detection: SlipDetection) -> np.ndarray:
        """(x, y) [m]: the mean displacement of the last `HELD_FRAMES` warm-up frames."""
        return detection.displacement[self.warm_up - HELD_FRAMES : self.warm_up].mean(axis=0)

    def _incipient_frame(self, detection: SlipDetection) -> int | None:
        """The first frame whose 3-frame mean displacement passes the incipient limit."""
        displacement = detection.displacement
        cumulative = np.cumsum(displacement - self.held_position(detection), axis=0)
        mean3 = np.full(displacement.shape[0], 0.0)
        mean3[3:] = np.linalg.norm(cumulative[3:] - cumulative[:-3], axis=1) / 3.0
        limit = self.incipient_threshold * detection.position_noise / np.sqrt(3.0)
        moved = np.nonzero(mean3[self.warm_up :] > limit)[0]
        return int(moved[0]) + self.warm_up if moved.size else None

    def channels(self, detection: SlipDetection) -> list[tuple[str, np.ndarray, float, int]]:
        """The gross-slip channels decided on, in the order that breaks ties between them.

        (channel, statistic, threshold, first frame it counts from): the static run-ahead
        as a backup and the late channel count once their reference window starts at or
        after the incipient decision (the track they extrapolate is the loaded contact's,
        not the rest before the load began); never (the number of frames) without one.
        """
        return self._channels(detection, self._incipient_frame(detection))

    def _channels(
        self, detection: SlipDetection, incipient: int | None
    ) -> list[tuple[str, np.ndarray, float, int]]:
        n = detection.displacement.shape[0]
        statistics = {
            "piezo": detection.piezo_statistic,
            "onset": detection.onset_statistic,
            "speed": detection.speed_statistic,
            "late": detection.late_statistic,
        }
        with_piezo = not np.all(np.isnan(detection.piezo_statistic))
        return [
            (channel, statistics[channel], threshold, armed_from(incipient, gap, n))
            for channel, threshold, gap in self.channel_plan(with_piezo)
            if statistics[channel].size == n
        ]

    def channel_plan(self, with_piezo: bool) -> list[tuple[str, float, int | None]]:
        """(channel, threshold, arming gap or None) of the gross-slip channels, in tie order.

        A channel with a gap counts once its reference window, ending that many frames
        before, starts at or after the incipient decision (`armed_from`).
        """
        # with PVDF frames the static run-ahead decides only past the backup threshold: at
        # its own threshold it adds premature alarms (the Cattaneo-Mindlin shift speeds up)
        plan: list[tuple[str, float, int | None]] = [("speed", self.gross_threshold, None)]
        if with_piezo:
            plan = [("piezo", self.piezo_threshold, None)]
            if self.onset_threshold is not None:
                plan.append(("onset", self.onset_threshold, None))
            if self.backup_threshold is not None:
                plan.append(("speed", self.backup_threshold, _GAP))
        if self.late_threshold is not None:
            plan.append(("late", self.late_threshold, _LATE_GAP))
        return plan

    def _events(self, detection: SlipDetection) -> list[SlipEvent]:
        incipient = self._incipient_frame(detection)
        gross: tuple[int, str] | None = None  # the earliest; a tie goes to the first channel
        for channel, statistic, threshold, start in self._channels(detection, incipient):
            above = np.nonzero(np.nan_to_num(statistic[start:]) > threshold)[0]
            if above.size and (gross is None or start + int(above[0]) < gross[0]):
                gross = (start + int(above[0]), channel)
        if incipient is not None and gross is not None and incipient > gross[0]:
            incipient = None  # gross slip came first: no separate warning
        rate = detection.frame_rate
        events = [] if incipient is None else [(incipient, "incipient", "displacement")]
        if gross is not None:
            events.append((gross[0], "gross", gross[1]))
        return [SlipEvent(kind, frame, frame / rate, channel) for frame, kind, channel in events]


def detect_slip(
    static_frames: Any,
    piezo_frames: Any = None,
    *,
    frame_rate: float,
    taxel_pitch: Any = 2e-3,
    **settings: Any,
) -> SlipDetection:
    """Detect incipient and gross slip in a sequence (one call of `SlipDetector`).

    Parameters
    ----------
    static_frames : array_like
        (n_frames, rows, cols) frames of a static array.
    piezo_frames : array_like, optional
        (n_frames, rows', cols') frames of a PVDF array at the same instants.
    frame_rate : float
        [Hz].
    taxel_pitch : float or (float, float), default 2e-3
        Static array pitch [m].
    **settings
        Other `SlipDetector` settings.

    Returns
    -------
    SlipDetection

    Examples
    --------
    A blob that sits still for 60 frames and then slides at 30 mm/s (1 kHz, 2 mm pitch):

    >>> rows, cols = np.mgrid[:16, :16] * 2e-3
    >>> centre = np.where(np.arange(120) < 60, 0.0, 30e-3 * (np.arange(120) - 60) / 1000)
    >>> frames = np.array([1000 * np.exp(-((cols - 0.014 - c) ** 2 + (rows - 0.015) ** 2)
    ...                    / 2 / 0.004**2) for c in centre])
    >>> frames += np.random.default_rng(0).normal(0, 2, frames.shape)
    >>> found = detect_slip(frames, frame_rate=1000.0)
    >>> found.initial_state, [(e.kind, e.frame) for e in found.events]
    ('holding', [('incipient', 61), ('gross', 61)])
    """
    detector = SlipDetector(taxel_pitch=taxel_pitch, **settings)
    return detector.run(static_frames, piezo_frames, frame_rate=frame_rate)
