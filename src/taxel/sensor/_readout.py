"""The readout electronics of a sensor: non-idealities and the ADC, each switchable.

Static chain, applied to the transducer's signal in this order (the order the physics acts):
temperature -> per-taxel gain and offset -> crosstalk -> noise -> faults -> ADC. The
fixed-pattern parts (gain and offset spread, faulty taxels) belong to one manufactured unit
and are drawn once from the unit's seed; noise is drawn per frame from the caller's `rng`.
Dynamic parts (hysteresis, creep, drift) act along time and are applied by
`TactileSensor.read_sequence`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from taxel._validation import check_count, check_finite, check_positive, check_range
from taxel.transducers import (
    GainOffset,
    TaxelFaults,
    adc_codes,
    add_noise,
    draw_faults,
    draw_gain_offset,
    neighbour_crosstalk,
    temperature_dependence,
)

__all__ = ["Readout", "ReadoutChain", "UnitPattern"]


@dataclass(frozen=True)
class Readout:
    """What the electronics add between the transducer and the numbers a user reads.

    Every non-ideality is off at its zero value. Noise, spreads and loop widths are given as
    fractions of the signal range (the span of the transducer's output over the working
    range), so one `Readout` suits any transducer.

    Parameters
    ----------
    bits : int or None, default 12
        ADC resolution, 1-24 bits; None when the transducer digitises itself (a camera).
    noise : float, default 0.0
        Additive white noise, standard deviation as a fraction of the signal range [-].
    multiplicative_noise : float, default 0.0
        Relative noise proportional to the signal [-].
    gain_spread : float, default 0.0
        Per-taxel gain spread (log-normal sigma) [-].
    offset_spread : float, default 0.0
        Per-taxel offset spread, fraction of the signal range [-].
    dead, stuck, saturated : float, default 0.0
        Fractions of taxels that are dead (read the bottom of the range), stuck at a level,
        or saturated (read the top) [-].
    crosstalk : float, default 0.0
        Fraction of a taxel's signal leaking into each edge neighbour [-].
    hysteresis : float, default 0.0
        Width of the major hysteresis loop, as a fraction of the sensed quantity's working
        range [-] (a Prandtl-Ishlinskii sum of eight play operators, acting on the quantity).
    creep : float, default 0.0
        Creep fraction of a held load (the reading grows up to (1 + creep) times) [-].
    creep_time : float, default 1.0
        Creep time constant [s].
    drift_rate : float, default 0.0
        Baseline drift, fraction of the signal range per second [1/s].
    temperature_coefficient : float, default 0.0
        Relative change of sensitivity per kelvin [1/K].
    unit_seed : int, default 0
        Seed of this manufactured unit's fixed pattern (spreads and faults).

    Examples
    --------
    >>> Readout(bits=8, noise=0.01).bits
    8
    >>> Readout(bits=30)
    Traceback (most recent call last):
    ...
    ValueError: `bits` must lie in [1, 24], got 30
    """

    bits: int | None = 12
    noise: float = 0.0
    multiplicative_noise: float = 0.0
    gain_spread: float = 0.0
    offset_spread: float = 0.0
    dead: float = 0.0
    stuck: float = 0.0
    saturated: float = 0.0
    crosstalk: float = 0.0
    hysteresis: float = 0.0
    creep: float = 0.0
    creep_time: float = 1.0
    drift_rate: float = 0.0
    temperature_coefficient: float = 0.0
    unit_seed: int = 0

    def __post_init__(self) -> None:
        if self.bits is not None:
            if isinstance(self.bits, bool) or not isinstance(self.bits, int | np.integer):
                raise TypeError(f"`bits` must be an integer or None, got {self.bits!r}")
            check_range("bits", self.bits, 1, 24)
        for name in (
            "noise",
            "multiplicative_noise",
            "gain_spread",
            "offset_spread",
            "hysteresis",
            "creep",
            "drift_rate",
        ):
            check_positive(name, getattr(self, name), allow_zero=True)
        for name in ("dead", "stuck", "saturated", "crosstalk"):
            check_range(name, getattr(self, name), 0.0, 1.0, high_inclusive=False)
        check_positive("creep_time", self.creep_time)
        check_finite("temperature_coefficient", self.temperature_coefficient)
        # a NaN or text seed was stored and failed only at the first reading
        object.__setattr__(self, "unit_seed", check_count("unit_seed", self.unit_seed, minimum=0))

    @property
    def is_identity(self) -> bool:
        """True when the electronics change nothing (no ADC and every non-ideality off)."""
        return self == Readout(bits=None, unit_seed=self.unit_seed)

    def ideal(self) -> Readout:
        """The same electronics with every non-ideality off (the ADC stays)."""
        return Readout(bits=self.bits, unit_seed=self.unit_seed)


@dataclass(frozen=True)
class UnitPattern:
    """The fixed pattern of one manufactured unit: per-taxel gain/offset and faulty taxels."""

    gain_offset: GainOffset
    faults: TaxelFaults

    @classmethod
    def draw(cls, shape: tuple[int, ...], readout: Readout, span: float) -> UnitPattern:
        """Draw the pattern for an array of `shape` whose signal range is `span` wide."""
        rng = np.random.default_rng(readout.unit_seed)
        spread = draw_gain_offset(
            shape,
            gain_spread=readout.gain_spread,
            offset_spread=readout.offset_spread * span,
            rng=rng,
        )
        faults = draw_faults(
            shape, dead=readout.dead, stuck=readout.stuck, saturated=readout.saturated, rng=rng
        )
        return cls(spread, faults)


@dataclass(frozen=True)
class ReadoutChain:
    """A readout bound to one unit: its signal range and fixed pattern (built by the sensor).

    `low` and `high` bound the transducer's ideal signal over the working range; noise,
    offsets and drift are scaled by their difference. `adc_range` is the input range of the
    ADC (and the rails faulty taxels read); None uses (low, high). A unit whose gains,
    offsets and crosstalk push some taxels past `high` needs a wider ADC range, or those
    taxels clip before full scale (see `covering`).
    """

    readout: Readout
    low: float
    high: float
    shape: tuple[int, ...]
    adc_range: tuple[float, float] | None = None

    @cached_property
    def pattern(self) -> UnitPattern:
        """The unit's fixed pattern (drawn once)."""
        return UnitPattern.draw(self.shape, self.readout, self.high - self.low)

    @property
    def span(self) -> float:
        """Width of the signal range [signal unit]."""
        return self.high - self.low

    @property
    def rails(self) -> tuple[float, float]:
        """(bottom, top) of the ADC input range [signal unit]: what dead and saturated read."""
        return (self.low, self.high) if self.adc_range is None else self.adc_range

    @property
    def lsb(self) -> float | None:
        """One ADC step [signal unit]; None without an ADC."""
        if self.readout.bits is None:
            return None
        bottom, top = self.rails
        return (top - bottom) / 2**self.readout.bits

    def analog(self, signal: Any, *, temperature: float | None = None) -> np.ndarray:
        """The noise-free signal at the ADC input: temperature, gain/offset, crosstalk."""
        readout = self.readout
        y = np.asarray(signal, dtype=float)
        if temperature is not None and readout.temperature_coefficient:
            y = temperature_dependence(
                y, temperature, gain_coefficient=readout.temperature_coefficient
            )
        y = self.pattern.gain_offset.apply(y)
        if readout.crosstalk and len(self.shape) == 2:
            y = neighbour_crosstalk(y, coupling=readout.crosstalk)
        return y

    def covering(self, signals: Any, *, margin: float = 0.05) -> ReadoutChain:
        """The same chain with an ADC range wide enough for these signals on this unit.

        Parameters
        ----------
        signals : array_like, shape (n, *shape)
            Ideal signals the ADC must take without clipping (the unloaded sensor and the
            full-scale load).
        margin : float, default 0.05
            Extra room on each side, as a fraction of `span`.

        Returns
        -------
        ReadoutChain
            Itself when the signals, after this unit's gain, offset and crosstalk, stay
            within (low, high); otherwise with `adc_range` stretched past each side they
            cross to the extreme value plus the margin.
        """
        values = self.analog(signals)
        smallest, largest = float(values.min()), float(values.max())
        bottom = self.low if smallest >= self.low else smallest - margin * self.span
        top = self.high if largest <= self.high else largest + margin * self.span
        if (bottom, top) == (self.low, self.high):
            return self
        return ReadoutChain(self.readout, self.low, self.high, self.shape, (bottom, top))

    def apply(self, signal: Any, *, rng: Any = None, temperature: float | None = None) -> Any:
        """The static chain on a signal of shape (..., *shape); noise only with `rng`."""
        readout = self.readout
        if readout.is_identity:
            return np.asarray(signal)
        y = self.analog(signal, temperature=temperature)
        if rng is not None and (readout.noise or readout.multiplicative_noise):
            y = add_noise(
                y,
                additive=readout.noise * self.span,
                multiplicative=readout.multiplicative_noise,
                rng=rng,
            )
        bottom, top = self.rails
        if readout.dead or readout.stuck or readout.saturated:
            y = self.pattern.faults.apply(y, low=bottom, high=top)
        if readout.bits is None:
            return y
        return adc_codes(y, bits=readout.bits, low=bottom, high=top)
