"""The probe interface: what a robot finger with a tactile sensor must offer.

A real robot driver implements `Probe` (move, press, slide, retract) and every active
procedure of `taxel.active` runs on it unchanged; `SimulatedFinger` implements it in
simulation.

Conventions: poses are 4x4 transforms of the sensor frame in the base frame (T_BS); the
sensor presses along its outward normal +z_S; a reading's `travel` is how far the finger has
moved along that normal since it left its approach pose.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np

from taxel.sensor import SensorFrame, TactileSensor

__all__ = ["NoContactError", "Probe", "ProbeReading"]


class NoContactError(ValueError):
    """Raised by `Probe.press` when no object lies within the probe's reach.

    Procedures that explore (`Recognition`) count such a press as a touch without contact;
    any other error of a press (a force beyond the probe's limit) is a real error.
    """


@dataclass(frozen=True)
class ProbeReading:
    """What one step of a probe returns.

    Attributes
    ----------
    frame : SensorFrame
        The tactile frame (`frame.raw` is what a real sensor gives).
    wrench : numpy.ndarray, shape (6,)
        Force [N] and torque [N m] the object applies to the sensor, in the base frame,
        torque about the sensor frame's origin.
    normal_force : float
        Force along the sensor normal [N], > 0 when pressing.
    travel : float
        Finger position along the pressing direction since the approach pose [m].
    pose : numpy.ndarray
        Sensor pose T_BS at the reading.
    time : float
        Time of the reading [s] since the probe started.
    """

    frame: SensorFrame = field(repr=False)
    wrench: np.ndarray = field(repr=False)
    normal_force: float
    travel: float
    pose: np.ndarray = field(repr=False)
    time: float


@runtime_checkable
class Probe(Protocol):
    """A finger carrying a tactile sensor that can be moved, pressed and slid."""

    @property
    def sensor(self) -> TactileSensor:
        """The sensor the finger carries."""
        ...

    @property
    def pose(self) -> np.ndarray:
        """The current approach pose T_BS (the sensor not pressing)."""
        ...

    def move_to(self, pose: Any) -> None:
        """Move the sensor to an approach pose; refuse one that penetrates an object."""
        ...

    def press(
        self, *, normal_force: float | None = None, depth: float | None = None
    ) -> ProbeReading:
        """Press along the sensor normal and return the reading.

        To a force [N] (force control) or to a depth past first touch [m] (position
        control). The finger stays pressed until `retract`. Raises `NoContactError` when
        no object lies within reach.
        """
        ...

    def slide(self, path: Any, *, speed: float, normal_force: float) -> list[ProbeReading]:
        """Slide pressed through base-frame points and return one reading per frame.

        The finger holds `normal_force` [N] and moves through `path` (K, 3) [m] at `speed`
        [m/s], reading one frame per sensor frame period. A slide refused on the way
        raises and leaves the finger where the slide started.
        """
        ...

    def retract(self) -> None:
        """Lift the sensor back to its approach pose."""
        ...
