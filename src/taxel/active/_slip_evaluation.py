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
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel.active._slip import SlipDetector
from taxel.active._slip_simulation import SlipSequence, random_slip_scenario, simulate_slip

__all__ = ["SlipEvaluation", "evaluate_slip_detection", "score_slip_detection", "slip_trials"]


def slip_trials(
    n_slip: int = 40, n_hold: int = 20, n_steady: int = 20, *, seed: int = 0
) -> list[SlipSequence]:
    """Simulate random slip, hold-only and steady-sliding trials (`random_slip_scenario`)."""
    rng = np.random.default_rng(seed)
    counts = {"slip": n_slip, "hold": n_hold, "steady": n_steady}
    for name, count in counts.items():
        if int(count) != count or count < 0:
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


def score_slip_detection(
    sequences: Sequence[SlipSequence],
    detector: SlipDetector | None = None,
    *,
    early_tolerance: int = 2,
) -> SlipEvaluation:
    """Run a detector on simulated sequences and score it against their truth."""
    detector = detector or SlipDetector()
    if not sequences:
        raise ValueError("`sequences` must hold at least one trial")
    latencies, incipient_latencies = [], []
    counts = {"slip": 0, "hold": 0, "steady": 0}
    premature = alarms = incipient_alarms = incipient_truths = incipient_free = 0
    for sequence in sequences:
        kind = sequence.scenario.kind
        counts[kind] += 1
        found = detector.run(
            sequence.static_frames, sequence.piezo_frames, frame_rate=sequence.frame_rate
        )
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
    latencies = np.array(latencies, dtype=int)
    n_slip = counts["slip"]
    n_free = counts["hold"] + counts["steady"]
    return SlipEvaluation(
        n_slip=n_slip,
        n_hold=counts["hold"],
        n_steady=counts["steady"],
        detection_rate=latencies.size / n_slip if n_slip else float("nan"),
        detection_within={
            limit: float(np.sum(latencies <= limit) / n_slip) if n_slip else float("nan")
            for limit in (1, 3, 5, 10)
        },
        false_alarm_rate=alarms / n_free if n_free else float("nan"),
        premature_rate=premature / n_slip if n_slip else float("nan"),
        latencies=latencies,
        incipient_detection_rate=(
            len(incipient_latencies) / incipient_truths if incipient_truths else float("nan")
        ),
        incipient_false_alarm_rate=(
            incipient_alarms / incipient_free if incipient_free else float("nan")
        ),
        incipient_latencies=np.array(incipient_latencies, dtype=int),
        frame_rate=float(sequences[0].frame_rate),
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
        Default: `SlipDetector()` with its default thresholds.

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
