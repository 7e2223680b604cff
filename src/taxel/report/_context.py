"""Shared state of one demo run: sensors built once, the seed, quick or full."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from taxel.sensor import TactileSensor, make_sensor

__all__ = ["DemoContext"]


@dataclass
class DemoContext:
    """Settings and caches of a demo run.

    Attributes
    ----------
    quick : bool
        Fewer trials and smaller sweeps (the report says so).
    seed : int
        Seed of every random draw, so a run is reproducible.
    """

    quick: bool = False
    seed: int = 1985
    _sensors: dict[str, TactileSensor] = field(default_factory=dict, repr=False)

    def sensor(self, name: str) -> TactileSensor:
        """A preset sensor, built once per run."""
        if name not in self._sensors:
            self._sensors[name] = make_sensor(name)
        return self._sensors[name]

    def rng(self, offset: int = 0) -> np.random.Generator:
        """A generator derived from the run's seed (different per experiment offset)."""
        return np.random.default_rng(self.seed + offset)
