r"""Slip detection in a sequence of frames: incipient slip and gross slip, with times.

Two signals (chapter seed, section 25.3, "Piezoelectric"; Ellis seed, section 2.2):

- The displacement of the contact pattern on a static array. Each frame is registered to
  the held reference image by iterated Lucas-Kanade least squares (the shift d that best
  explains I_k = I_ref(x - d) over the whole image, the reference re-sampled at the current
  estimate by cubic splines). While the object sticks, the pattern moves only by the pad's
  tangential compliance (Cattaneo-Mindlin); once it slides, it moves at the sliding speed.
- The high-pass signal of a PVDF array (its charge amplifier already sees only changes,
  eq. 25.17-25.18): the energy above `cutoff` per frame, which jumps when stick-slip
  vibrations start.

Decisions are causal (frame k uses frames <= k). The first `warm_up` frames set each
channel's noise level and the initial state: holding (the pattern at rest) or already
sliding, in which case no onset is reported. Then:

- incipient slip: the pattern has left its held position by more than `incipient_threshold`
  noise standard deviations (averaged over 3 frames): a tangential load is building up, and
  with it the slip annulus;
- gross slip: the pattern runs ahead of where its recent motion would have put it. A line
  fitted to the positions of a reference window (15 frames, ending 3 frames before) is
  extrapolated to the current frame; the deviation along the direction of travel, in noise
  units and averaged over 2 frames, passes `gross_threshold`. Or the piezo channel: a
  one-sided CUSUM (Page 1954) of its standardised high-pass energy,
  S_k = max(0, S_{k-1} + z_k - `drift`), passes `piezo_threshold`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import ndimage, signal

from taxel._validation import as_finite_array, check_positive

__all__ = ["SlipDetection", "SlipDetector", "SlipEvent", "detect_slip"]

_REFERENCE = 15  # frames in the reference window of the speed and the energy
_GAP = 3  # frames between the reference window and the current frame


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
        What decided it: 'displacement', 'speed' or 'piezo'.
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
    piezo_statistic : numpy.ndarray
        (n_frames,) CUSUM of the piezo energy (NaN during the warm-up, or all NaN without
        piezo frames).
    frame_rate : float
        [Hz].
    """

    events: tuple[SlipEvent, ...]
    initial_state: str
    displacement: np.ndarray = field(repr=False)
    velocity: np.ndarray = field(repr=False)
    speed_statistic: np.ndarray = field(repr=False)
    piezo_statistic: np.ndarray = field(repr=False)
    frame_rate: float = 1000.0

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


def register(frames: np.ndarray, reference: np.ndarray, pitch: tuple[float, float]) -> np.ndarray:
    """Shift (x, y) [m] of the pattern of each frame from the reference image, (n, 2).

    Iterated Lucas-Kanade: the reference is re-sampled (cubic splines) at the current estimate
    and the residual shift solved by least squares over the image; each frame starts from
    the previous frame's estimate, so the pattern is followed over many taxels.
    """
    shifts = np.zeros((frames.shape[0], 2))
    estimate = np.zeros(2)  # (columns, rows) in taxels
    for index, frame in enumerate(frames):
        for _ in range(4):
            moved = ndimage.shift(reference, (estimate[1], estimate[0]), order=3, mode="nearest")
            grad_y, grad_x = np.gradient(moved)
            a = np.array(
                [
                    [(grad_x * grad_x).sum(), (grad_x * grad_y).sum()],
                    [(grad_x * grad_y).sum(), (grad_y * grad_y).sum()],
                ]
            )
            if np.linalg.det(a) <= 1e-12 * max(np.trace(a), 1e-300) ** 2:
                break  # no contact pattern to follow
            change = frame - moved
            step = np.linalg.solve(a, [(grad_x * change).sum(), (grad_y * change).sum()])
            estimate = estimate - step
            if np.abs(step).max() < 1e-3:
                break
        shifts[index] = estimate
    return shifts * np.array([pitch[1], pitch[0]])


def _robust_sigma(values: np.ndarray, axis: int = 0) -> np.ndarray:
    deviation = np.abs(values - np.median(values, axis=axis, keepdims=True))
    return np.median(deviation, axis=axis) / 0.6745


def _cusum(z: np.ndarray, start: int, drift: float) -> np.ndarray:
    statistic = np.full(z.shape, np.nan)
    total = 0.0
    for k in range(start, z.size):
        total = max(0.0, total + z[k] - drift)
        statistic[k] = total
    return statistic


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
    gross_threshold : float, default 6.0
        Run-ahead of the pattern past its extrapolated track, in noise standard deviations.
    piezo_threshold : float, default 12.0
        CUSUM threshold h of the piezo channel.
    drift : float, default 1.0
        CUSUM drift nu: the standardised energy increase that does not accumulate.
    cutoff : float, default 100.0
        High-pass corner of the piezo channel [Hz].
    rest_speed : float, default 5e-3
        Largest warm-up pattern speed of a holding contact [m/s].

    Notes
    -----
    See the module notes. The position noise sigma is measured over the warm-up about a
    fitted line (whose slope also decides whether the contact is held). The direction of
    travel is that of the displacement from the held position (while that is within
    3 sigma, the size of the deviation is used instead). The piezo score is the mean over
    taxels of the squared high-passed signal in noise units, standardised against its
    reference window.
    """

    def __init__(
        self,
        *,
        taxel_pitch: Any = 2e-3,
        warm_up: int = 40,
        incipient_threshold: float = 5.0,
        gross_threshold: float = 6.0,
        piezo_threshold: float = 12.0,
        drift: float = 1.0,
        cutoff: float = 100.0,
        rest_speed: float = 5e-3,
    ) -> None:
        pitch = np.broadcast_to(np.asarray(taxel_pitch, float), (2,))
        for value in pitch:
            check_positive("taxel_pitch", value)
        self.taxel_pitch = (float(pitch[0]), float(pitch[1]))
        if int(warm_up) != warm_up or warm_up < _REFERENCE + _GAP + 2:
            raise ValueError(
                f"`warm_up` must be an integer >= {_REFERENCE + _GAP + 2}, got {warm_up!r}"
            )
        self.warm_up = int(warm_up)
        self.incipient_threshold = check_positive("incipient_threshold", incipient_threshold)
        self.gross_threshold = check_positive("gross_threshold", gross_threshold)
        self.piezo_threshold = check_positive("piezo_threshold", piezo_threshold)
        self.drift = check_positive("drift", drift, allow_zero=True)
        self.cutoff = check_positive("cutoff", cutoff)
        self.rest_speed = check_positive("rest_speed", rest_speed)

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
        rate = check_positive("frame_rate", frame_rate)
        n = frames.shape[0]
        if n <= self.warm_up:
            raise ValueError(
                f"`static_frames` must hold more than `warm_up` = {self.warm_up} frames, got {n}"
            )
        reference = frames[self.warm_up - 10 : self.warm_up].mean(axis=0)
        displacement = register(frames, reference, self.taxel_pitch)
        # per-frame noise of the position, from the warm-up about its own trend
        held = displacement[1 : self.warm_up]
        trend = np.polynomial.polynomial.polyfit(np.arange(held.shape[0]), held, 1)
        residual = held - np.polynomial.polynomial.polyval(np.arange(held.shape[0]), trend).T
        sigma = max(float(np.sqrt(np.mean(_robust_sigma(residual) ** 2))), 1e-9)
        sliding = float(np.linalg.norm(trend[1])) * rate > self.rest_speed
        speed_statistic = self._run_ahead(displacement, sigma)
        piezo_statistic = np.full(n, np.nan)
        if piezo_frames is not None:
            piezo = as_finite_array("piezo_frames", piezo_frames, ndim=3)
            if piezo.shape[0] != n:
                raise ValueError(
                    f"`piezo_frames` has {piezo.shape[0]} frames but `static_frames` has {n}"
                )
            piezo_statistic = _cusum(self._piezo_scores(piezo, rate), self.warm_up, self.drift)
        events: list[SlipEvent] = []
        if not sliding:
            events = self._events(displacement, sigma, speed_statistic, piezo_statistic, rate)
        return SlipDetection(
            events=tuple(events),
            initial_state="sliding" if sliding else "holding",
            displacement=displacement,
            velocity=np.gradient(displacement, axis=0) * rate,
            speed_statistic=speed_statistic,
            piezo_statistic=piezo_statistic,
            frame_rate=rate,
        )

    def _run_ahead(self, displacement: np.ndarray, sigma: float) -> np.ndarray:
        """How far the pattern runs ahead of its extrapolated track, in noise units."""
        n = displacement.shape[0]
        steps = np.arange(_REFERENCE) - (_REFERENCE - 1) / 2
        lever = (_REFERENCE - 1) / 2 + _GAP
        held = displacement[self.warm_up - 10 : self.warm_up].mean(axis=0)
        ahead = np.full(n, np.nan)
        for k in range(self.warm_up, n):
            window = displacement[k - _GAP - _REFERENCE + 1 : k - _GAP + 1]
            slope = steps @ window / (steps @ steps)
            deviation = displacement[k] - (window.mean(axis=0) + lever * slope)
            moved = displacement[k] - held
            if np.linalg.norm(moved) > 3 * sigma:
                ahead[k] = deviation @ moved / np.linalg.norm(moved) / sigma
            else:  # no direction of travel yet: the size of the deviation, centred (2 dof)
                ahead[k] = np.linalg.norm(deviation) / sigma - 1.25
        smooth = ahead.copy()
        smooth[self.warm_up + 1 :] = 0.5 * (ahead[self.warm_up + 1 :] + ahead[self.warm_up : -1])
        return smooth

    def _piezo_scores(self, piezo: np.ndarray, rate: float) -> np.ndarray:
        flat = piezo.reshape(piezo.shape[0], -1)
        corner = min(self.cutoff / (0.5 * rate), 0.99)
        b, a = signal.butter(2, corner, btype="high")
        filtered = signal.lfilter(b, a, flat - flat[0], axis=0)
        start = min(10, self.warm_up // 4)
        sigma = np.maximum(_robust_sigma(filtered[start : self.warm_up]), 1e-12)
        energy = np.mean((filtered / sigma) ** 2, axis=1)
        taxels = flat.shape[1]
        z = np.zeros(energy.size)
        for k in range(self.warm_up, energy.size):
            ref = max(float(energy[k - _GAP - _REFERENCE + 1 : k - _GAP + 1].mean()), 1.0)
            z[k] = (energy[k] - ref) / (ref * np.sqrt(2.0 / taxels))
        return z

    def _events(
        self,
        displacement: np.ndarray,
        sigma: float,
        speed_statistic: np.ndarray,
        piezo_statistic: np.ndarray,
        rate: float,
    ) -> list[SlipEvent]:
        held = displacement[self.warm_up - 10 : self.warm_up].mean(axis=0)
        cumulative = np.cumsum(displacement - held, axis=0)
        mean3 = np.full(displacement.shape[0], 0.0)
        mean3[3:] = np.linalg.norm(cumulative[3:] - cumulative[:-3], axis=1) / 3.0
        limit = self.incipient_threshold * sigma / np.sqrt(3.0)
        found = []
        moved = np.nonzero(mean3[self.warm_up :] > limit)[0]
        if moved.size:
            found.append(("incipient", int(moved[0]) + self.warm_up, "displacement"))
        for channel, statistic, threshold in (
            ("speed", speed_statistic, self.gross_threshold),
            ("piezo", piezo_statistic, self.piezo_threshold),
        ):
            above = np.nonzero(np.nan_to_num(statistic) > threshold)[0]
            if above.size:
                found.append(("gross", int(above[0]), channel))
        gross = min(
            (item for item in found if item[0] == "gross"), default=None, key=lambda item: item[1]
        )
        incipient = next((item for item in found if item[0] == "incipient"), None)
        if incipient and gross and incipient[1] > gross[1]:
            incipient = None  # gross slip came first: no separate warning
        return [
            SlipEvent(item[0], item[1], item[1] / rate, item[2])
            for item in (incipient, gross)
            if item is not None
        ]


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
