"""What every active procedure reports: the steps it took, in order.

Procedures are classes holding their settings with a ``run(probe, ...)`` method, wrapped by a
one-call function; their frozen results carry ``steps``, a tuple of `ProcedureStep`, so a
user (or the report) can see exactly what the finger did and what it measured.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel.active._probe import ProbeReading

__all__ = ["ProcedureStep", "step_from_reading"]


@dataclass(frozen=True)
class ProcedureStep:
    """One step of a procedure.

    Attributes
    ----------
    action : str
        What the finger did, in words ("press 12 N", "move to (x, y, z)", ...).
    normal_force : float
        Force along the sensor normal at the end of the step [N] (0 when not pressing).
    travel : float
        Finger travel along the pressing direction [m].
    position : numpy.ndarray, shape (3,)
        Base-frame position of the sensor origin at the end of the step [m].
    measurements : Mapping[str, float]
        What the step measured (names from docs/nomenclature.md, SI units).
    """

    action: str
    normal_force: float = 0.0
    travel: float = 0.0
    position: np.ndarray = field(default_factory=lambda: np.zeros(3), repr=False)
    measurements: Mapping[str, float] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary."""
        return {
            "action": self.action,
            "normal_force_n": self.normal_force,
            "travel_m": self.travel,
            "position_m": [float(v) for v in self.position],
            "measurements": {key: float(value) for key, value in self.measurements.items()},
        }


def step_from_reading(action: str, reading: ProbeReading, **measurements: float) -> ProcedureStep:
    """A step from a probe reading plus named measurements.

    Examples
    --------
    >>> step = ProcedureStep("move to the start")
    >>> step.to_dict()["normal_force_n"]
    0.0
    """
    return ProcedureStep(
        action=action,
        normal_force=reading.normal_force,
        travel=reading.travel,
        position=reading.pose[:3, 3].copy(),
        measurements=measurements,
    )
