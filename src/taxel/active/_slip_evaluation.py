"""Scoring a slip detector on simulated hold-then-slip, hold-only and steady sliding trials.

A gross-slip detection counts when the detector's first gross event comes no earlier than
`early_tolerance` frames before the true onset (an earlier one is premature: a false
alarm); its latency is event frame - onset frame. False alarms are counted on the hold-only
trials (the load stays below mu_s N) and on the steady-sliding trials (no onset to find).
Incipient slip is scored the same way against its own truth (the annulus has grown), on
the slip trials and the hold trials whose load ramps; holds at a constant load and steady
sliding give its false alarms.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any, cast

import numpy as np

from taxel._validation import check_count, check_range, is_whole
from taxel.active._slip import SlipDetection, SlipDetector
from taxel.active._slip_simulation import (
    SlipSequence,
    random_slip_scenario,
    simulate_slip,
    slip_sensors,
)
from taxel.transducers import PiezoelectricTransducer

__all__ = [
    "SlipCalibration",
    "SlipEvaluation",
    "calibrate_slip_detector",
    "evaluate_slip_detection",
    "score_slip_detection",
    "slip_trials",
]


def slip_trials(
    n_slip: int = 40, n_hold: int = 20, n_steady: int = 20, *, seed: int = 0
) -> list[SlipSequence]:
    """Simulate random slip, hold-only and steady-sliding trials (`random_slip_scenario`)."""
    rng = np.random.default_rng(check_count("seed", seed, minimum=0))
    counts = {"slip": n_slip, "hold": n_hold, "steady": n_steady}
    for name, count in counts.items():
        if not is_whole(count) or count < 0:
            raise ValueError(f"`n_{name}` must be an integer >= 0, got {count!r}")
    return [
        simulate_slip(random_slip_scenario(kind, rng))
        for kind, count in counts.items()
        for _ in range(int(count))
    ]


@dataclass(frozen=True)
class SlipEvaluation:
    """Detection rate, false alarms and latency of a slip detector over simulated trials.

    Attributes
    ----------
    n_slip, n_hold, n_steady : int
        Trials of each kind.
    detection_rate : float
        Slip trials whose gross slip was detected (not prematurely).
    detection_within : dict of int to float
        Slip trials detected with a latency <= n frames, for n = 1, 3, 5, 10.
    false_alarm_rate : float
        Hold and steady trials with a gross-slip event.
    premature_rate : float
        Slip trials with a gross event more than `early_tolerance` frames before the onset.
    latencies : numpy.ndarray
        Latency of each detection [frames].
    incipient_detection_rate, incipient_false_alarm_rate : float
        The same for incipient slip.
    incipient_latencies : numpy.ndarray
        [frames].
    frame_rate : float
        [Hz].
    """

    n_slip: int
    n_hold: int
    n_steady: int
    detection_rate: float
    detection_within: dict[int, float]
    false_alarm_rate: float
    premature_rate: float
    latencies: np.ndarray = field(repr=False)
    incipient_detection_rate: float
    incipient_false_alarm_rate: float
    incipient_latencies: np.ndarray = field(repr=False)
    frame_rate: float = 1000.0

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (latencies in frames and seconds)."""

        def summary(values: np.ndarray) -> dict[str, Any]:
            if values.size == 0:
                return {"frames": [], "median_frames": None, "p95_frames": None}
            return {
                "frames": values.tolist(),
                "median_frames": float(np.median(values)),
                "p95_frames": float(np.percentile(values, 95)),
                "median_s": float(np.median(values)) / self.frame_rate,
            }

        return {
            "n_slip": self.n_slip,
            "n_hold": self.n_hold,
            "n_steady": self.n_steady,
            "frame_rate_hz": self.frame_rate,
            "gross": {
                "detection_rate": self.detection_rate,
                "detection_within_frames": {str(k): v for k, v in self.detection_within.items()},
                "false_alarm_rate": self.false_alarm_rate,
                "premature_rate": self.premature_rate,
                "latency": summary(self.latencies),
            },
            "incipient": {
                "detection_rate": self.incipient_detection_rate,
                "false_alarm_rate": self.incipient_false_alarm_rate,
                "latency": summary(self.incipient_latencies),
            },
        }


def _default_settings() -> dict[str, Any]:
    """The simulated finger's charge-amplifier time constant (`slip_sensors`)."""
    piezo = cast(PiezoelectricTransducer, slip_sensors()[1].transducer)
    return {"piezo_time_constant": piezo.time_constant}


def score_slip_detection(
    sequences: Sequence[SlipSequence],
    detector: SlipDetector | None = None,
    *,
    early_tolerance: int = 2,
) -> SlipEvaluation:
    """Run a detector on simulated sequences and score it against their truth.

    The default detector is `SlipDetector` with its default thresholds and the time
    constant of the simulated PVDF array's charge amplifiers (`slip_sensors`).
    """
    detector = detector or SlipDetector(**_default_settings())
    if not sequences:
        raise ValueError("`sequences` must hold at least one trial")
    return _tally(sequences, [_detect(detector, s) for s in sequences], early_tolerance)


def _detect(detector: SlipDetector, sequence: SlipSequence) -> SlipDetection:
    return detector.run(
        sequence.static_frames, sequence.piezo_frames, frame_rate=sequence.frame_rate
    )


def _tally(
    sequences: Sequence[SlipSequence], detections: Sequence[SlipDetection], early_tolerance: int
) -> SlipEvaluation:
    """Score the detections of a detector against the truth of their sequences."""
    latencies, incipient_latencies = [], []
    counts = {"slip": 0, "hold": 0, "steady": 0}
    premature = alarms = incipient_alarms = incipient_truths = incipient_free = 0
    for sequence, found in zip(sequences, detections, strict=True):
        counts[sequence.scenario.kind] += 1
        gross, incipient = found.first("gross"), found.first("incipient")
        if sequence.gross_frame is not None:
            if gross is not None and gross.frame < sequence.gross_frame - early_tolerance:
                premature += 1
            elif gross is not None:
                latencies.append(gross.frame - sequence.gross_frame)
        elif gross is not None:
            alarms += 1
        if sequence.incipient_frame is not None:
            incipient_truths += 1
            onset = sequence.incipient_frame
            if incipient is not None and incipient.frame >= onset - early_tolerance:
                incipient_latencies.append(incipient.frame - onset)
        else:
            incipient_free += 1
            incipient_alarms += incipient is not None or gross is not None
    gross_latencies = np.array(latencies, dtype=int)
    n_slip = counts["slip"]
    n_free = counts["hold"] + counts["steady"]
    return SlipEvaluation(
        n_slip=n_slip,
        n_hold=counts["hold"],
        n_steady=counts["steady"],
        detection_rate=gross_latencies.size / n_slip if n_slip else float("nan"),
        detection_within={
            limit: float(np.sum(gross_latencies <= limit) / n_slip) if n_slip else float("nan")
            for limit in (1, 3, 5, 10)
        },
        false_alarm_rate=alarms / n_free if n_free else float("nan"),
        premature_rate=premature / n_slip if n_slip else float("nan"),
        latencies=gross_latencies,
        incipient_detection_rate=(
            len(incipient_latencies) / incipient_truths if incipient_truths else float("nan")
        ),
        incipient_false_alarm_rate=(
            incipient_alarms / incipient_free if incipient_free else float("nan")
        ),
        incipient_latencies=np.array(incipient_latencies, dtype=int),
        frame_rate=float(sequences[0].frame_rate),
    )


@dataclass(frozen=True)
class SlipCalibration:
    """Thresholds of a slip detector set on calibration trials for a false-alarm budget.

    Attributes
    ----------
    detector : SlipDetector
        The detector with the chosen `gross_threshold`, `piezo_threshold`,
        `onset_threshold`, `backup_threshold` and `late_threshold`.
    evaluation : SlipEvaluation
        Its score on the calibration trials, with their PVDF frames.
    static_evaluation : SlipEvaluation
        Its score on the same trials without the PVDF frames (the static channel alone).
    false_alarm_budget : float
        The largest false-alarm rate allowed on the calibration trials.
    latency : int
        The latency [frames] whose detections were maximised.
    """

    detector: SlipDetector
    evaluation: SlipEvaluation
    static_evaluation: SlipEvaluation
    false_alarm_budget: float
    latency: int

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (the thresholds and both scores)."""
        return {
            "gross_threshold": self.detector.gross_threshold,
            "piezo_threshold": self.detector.piezo_threshold,
            "onset_threshold": self.detector.onset_threshold,
            "backup_threshold": self.detector.backup_threshold,
            "late_threshold": self.detector.late_threshold,
            "false_alarm_budget": self.false_alarm_budget,
            "latency_frames": self.latency,
            "evaluation": self.evaluation.to_dict(),
            "static_evaluation": self.static_evaluation.to_dict(),
        }


def calibrate_slip_detector(
    sequences: Sequence[SlipSequence],
    *,
    false_alarm_budget: float = 0.05,
    latency: int = 3,
    early_tolerance: int = 2,
    gross_thresholds: Any = None,
    piezo_thresholds: Any = None,
    onset_thresholds: Any = None,
    backup_thresholds: Any = None,
    late_thresholds: Any = None,
    **settings: Any,
) -> SlipCalibration:
    """Set a slip detector's thresholds on calibration trials for a false-alarm budget.

    Parameters
    ----------
    sequences : sequence of SlipSequence
        Calibration trials (slip, hold and steady), never the trials the detector is then
        scored on.
    false_alarm_budget : float, default 0.05
        Largest fraction of hold and steady trials with a gross-slip event.
    latency : int, default 3
        The thresholds maximise the slip trials detected within `latency` frames of the
        onset, then those detected at all, then the threshold itself (the largest of equals).
    early_tolerance : int, default 2
        As in `score_slip_detection`.
    gross_thresholds, piezo_thresholds, backup_thresholds, late_thresholds : array_like, optional
        Candidates; default 3-20 in steps of 0.5, 4-60 in steps of 1, 3-20 in steps
        of 0.5 and 3-40 in steps of 0.5 (the backup and the late channel left out, None,
        are always candidates too).
    onset_thresholds : array_like, optional
        Candidates for the onset matched filter; default 2.5-8 in steps of 0.25 (left out,
        None, is always a candidate too).
    **settings
        Other `SlipDetector` settings (fixed); `piezo_time_constant` defaults to that of
        `slip_sensors`' PVDF array.

    Returns
    -------
    SlipCalibration

    Notes
    -----
    The statistics of each trial are computed once; the thresholds only decide on them
    (`SlipDetector.decide`). `gross_threshold` is set on the static channel alone (it
    decides without PVDF frames), then `piezo_threshold` with the PVDF frames and neither
    the onset filter nor the backup, then `onset_threshold`, then `backup_threshold`, each
    without the late channel; then
    `late_threshold` with all of them (it decides late, so it adds to the slips detected
    at all rather than within `latency`, unless it brings alarms).
    Candidates over the budget are kept only if none is within it (then the one with the
    fewest false alarms wins).
    """
    budget = check_range("false_alarm_budget", false_alarm_budget, 0.0, 1.0)
    if not sequences:
        raise ValueError("`sequences` must hold at least one trial")
    gross_grid = np.arange(3.0, 20.01, 0.5) if gross_thresholds is None else gross_thresholds
    piezo_grid = np.arange(4.0, 60.01, 1.0) if piezo_thresholds is None else piezo_thresholds
    onset_grid = np.arange(2.5, 8.01, 0.25) if onset_thresholds is None else onset_thresholds
    backup_grid = np.arange(3.0, 20.01, 0.5) if backup_thresholds is None else backup_thresholds
    late_grid = np.arange(3.0, 40.01, 0.5) if late_thresholds is None else late_thresholds
    settings = {**_default_settings(), **settings}
    fused = [_detect(SlipDetector(**settings), s) for s in sequences]
    static = [
        replace(
            f,
            piezo_statistic=np.full_like(f.piezo_statistic, np.nan),
            onset_statistic=np.full_like(f.onset_statistic, np.nan),
        )
        for f in fused
    ]

    def best(name: str, grid: Any, statistics: list[SlipDetection], fixed: dict) -> tuple:
        ranked = []
        for value in np.asarray(grid, dtype=float):
            # an infinite threshold is no threshold (the backup left out)
            threshold = None if np.isinf(value) else float(value)
            detector = SlipDetector(**{**settings, **fixed, name: threshold})
            result = _tally(sequences, [detector.decide(f) for f in statistics], early_tolerance)
            quick = int(np.sum(result.latencies <= latency))
            over = max(result.false_alarm_rate - budget, 0.0)
            ranked.append(((-over, quick, result.latencies.size, value), detector, result))
        return max(ranked, key=lambda item: item[0])

    gross = best("gross_threshold", gross_grid, static, {"late_threshold": None})
    chosen = {
        "gross_threshold": gross[1].gross_threshold,
        "onset_threshold": None,
        "backup_threshold": None,
        "late_threshold": None,
    }
    piezo = best("piezo_threshold", piezo_grid, fused, chosen)
    chosen["piezo_threshold"] = piezo[1].piezo_threshold
    # left out (inf) wins a tie: it is the largest candidate
    onset_candidates = np.append(np.asarray(onset_grid, dtype=float), np.inf)
    onset = best("onset_threshold", onset_candidates, fused, chosen)
    chosen["onset_threshold"] = onset[1].onset_threshold
    # the backup left out (inf) wins a tie: it is the largest candidate
    candidates = np.append(np.asarray(backup_grid, dtype=float), np.inf)
    backup = best("backup_threshold", candidates, fused, chosen)
    chosen["backup_threshold"] = backup[1].backup_threshold
    late = best(
        "late_threshold", np.append(np.asarray(late_grid, dtype=float), np.inf), fused, chosen
    )
    detector = late[1]
    return SlipCalibration(
        detector=detector,
        evaluation=late[2],
        static_evaluation=_tally(sequences, [detector.decide(f) for f in static], early_tolerance),
        false_alarm_budget=budget,
        latency=int(latency),
    )


def evaluate_slip_detection(
    n_slip: int = 40,
    n_hold: int = 20,
    n_steady: int = 20,
    *,
    seed: int = 0,
    detector: SlipDetector | None = None,
) -> SlipEvaluation:
    """Simulate trials and score a slip detector on them (one call).

    Parameters
    ----------
    n_slip, n_hold, n_steady : int
        Trials of each kind (see `random_slip_scenario`).
    seed : int, default 0
        Seeds the scenarios, vibrations and noise.
    detector : SlipDetector, optional
        Default: `SlipDetector` with its default thresholds and the time constant of the
        simulated PVDF array's charge amplifiers.

    Returns
    -------
    SlipEvaluation

    Examples
    --------
    >>> evaluation = evaluate_slip_detection(2, 1, 1, seed=3)
    >>> evaluation.n_slip, sorted(evaluation.to_dict()["gross"])[:2]
    (2, ['detection_rate', 'detection_within_frames'])
    """
    return score_slip_detection(slip_trials(n_slip, n_hold, n_steady, seed=seed), detector)
