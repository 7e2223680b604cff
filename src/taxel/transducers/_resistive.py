"""Resistive cells: a pressure-dependent resistance and the scanning readout of eq. 25.6.

The cell law is a power law in pressure, the form that fits conductive-elastomer and
force-sensing-resistor (FSR) cells over two to three decades of load: the resistance falls
monotonically and non-linearly, and the conductance grows roughly in proportion to the load
when the exponent is near one. The readout is the inverting transimpedance stage of Figure
25.4 of the chapter, with the multiplexer's series resistance and the supply voltage as the
two error sources the chapter names.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from taxel._validation import as_finite_array, check_positive

__all__ = [
    "ResistiveTransducer",
    "piezoresistive_pressure",
    "piezoresistive_resistance",
    "readout_resistance",
    "readout_voltage",
]


def piezoresistive_resistance(
    pressure: Any,
    *,
    unloaded_resistance: float,
    reference_pressure: float,
    exponent: float,
) -> np.ndarray:
    r"""Resistance of a pressure-sensitive cell [Ohm].

    Parameters
    ----------
    pressure : array_like
        Compressive normal pressure on the cell [Pa], >= 0.
    unloaded_resistance : float
        R_0, the resistance with no load [Ohm], > 0.
    reference_pressure : float
        p_ref, the pressure at which the law turns from flat to a power law [Pa], > 0.
    exponent : float
        n, the power-law exponent [-], > 0. Near 1 for FSR-like cells (conductance about
        proportional to load); below 1 for conductive elastomers whose contact area saturates.

    Returns
    -------
    numpy.ndarray
        R = R_0 (1 + p / p_ref)^(-n) [Ohm].

    Notes
    -----
    .. math:: R(p) = R_0 \left(1 + \frac{p}{p_\mathrm{ref}}\right)^{-n}

    The chapter (section 25.3, "Resistive") describes the two mechanisms, particle density and
    contact area, without a formula; this smooth, monotonic power law is our choice. It is
    finite at p = 0 (real cells read a large but finite resistance there) and tends to the
    pure power law R_0 (p / p_ref)^(-n) of FSR data sheets for p >> p_ref.

    Examples
    --------
    >>> r = piezoresistive_resistance(
    ...     [0.0, 1e4, 1e5], unloaded_resistance=1e5, reference_pressure=1e4, exponent=1.0
    ... )
    >>> np.round(r).tolist()
    [100000.0, 50000.0, 9091.0]
    """
    pressure = as_finite_array("pressure", pressure)
    if np.any(pressure < 0):
        raise ValueError(f"`pressure` must be >= 0, got {float(np.min(pressure)):g}")
    unloaded_resistance = check_positive("unloaded_resistance", unloaded_resistance)
    reference_pressure = check_positive("reference_pressure", reference_pressure)
    exponent = check_positive("exponent", exponent)
    return unloaded_resistance * (1.0 + pressure / reference_pressure) ** (-exponent)


def piezoresistive_pressure(
    resistance: Any,
    *,
    unloaded_resistance: float,
    reference_pressure: float,
    exponent: float,
) -> np.ndarray:
    r"""Pressure from the resistance of a cell, the inverse of `piezoresistive_resistance` [Pa].

    Parameters
    ----------
    resistance : array_like
        Measured resistance [Ohm], > 0. Values above R_0 (which a biased readout can give)
        map to negative pressures rather than being clipped, so that bias stays visible.
    unloaded_resistance, reference_pressure, exponent : float
        The cell law, as in `piezoresistive_resistance`.

    Returns
    -------
    numpy.ndarray
        p = p_ref ((R / R_0)^(-1/n) - 1) [Pa].

    Examples
    --------
    >>> p = piezoresistive_pressure(
    ...     5e4, unloaded_resistance=1e5, reference_pressure=1e4, exponent=1.0
    ... )
    >>> float(p)
    10000.0
    """
    resistance = as_finite_array("resistance", resistance)
    if np.any(resistance <= 0):
        raise ValueError(f"`resistance` must be > 0, got {float(np.min(resistance)):g}")
    unloaded_resistance = check_positive("unloaded_resistance", unloaded_resistance)
    reference_pressure = check_positive("reference_pressure", reference_pressure)
    exponent = check_positive("exponent", exponent)
    return reference_pressure * ((resistance / unloaded_resistance) ** (-1.0 / exponent) - 1.0)


def readout_voltage(
    resistance: Any,
    *,
    supply_voltage: Any,
    feedback_resistance: float,
    series_resistance: float = 0.0,
) -> np.ndarray:
    r"""Output of the transimpedance readout of one selected cell, eq. 25.6 [V].

    Parameters
    ----------
    resistance : array_like
        Cell resistance R_ij [Ohm], > 0.
    supply_voltage : float or array_like
        The bias V_cc actually applied [V], > 0. Pass an array (broadcasting against
        `resistance`) to model ripple or drift of the supply.
    feedback_resistance : float
        R_f of the output amplifier [Ohm], > 0.
    series_resistance : float, default 0.0
        Everything in series with the cell [Ohm], >= 0: the on-resistance of the row and the
        column multiplexer switches (two switches, so twice one switch's value) and wiring.

    Returns
    -------
    numpy.ndarray
        V_o = R_f V_cc / (R_ij + R_s) [V], the magnitude of the inverting stage's output.

    Notes
    -----
    Eq. 25.6 of the seed chapter, V_o = (R_f / R_ij) V_cc, is the case R_s = 0. The chapter
    names the multiplexer's internal resistance and the variation of the supply as the two
    things that spoil it; both enter here. Crosstalk through unselected cells of a passive
    matrix is modelled by `scan_resistive_matrix`.

    Examples
    --------
    >>> float(readout_voltage(1e4, supply_voltage=5.0, feedback_resistance=2e3))
    1.0
    >>> float(readout_voltage(1e4, supply_voltage=5.0, feedback_resistance=2e3,
    ...                       series_resistance=100.0))
    0.990099...
    """
    resistance = as_finite_array("resistance", resistance)
    if np.any(resistance <= 0):
        raise ValueError(f"`resistance` must be > 0, got {float(np.min(resistance)):g}")
    supply_voltage = as_finite_array("supply_voltage", supply_voltage)
    if np.any(supply_voltage <= 0):
        raise ValueError(f"`supply_voltage` must be > 0, got {float(np.min(supply_voltage)):g}")
    feedback_resistance = check_positive("feedback_resistance", feedback_resistance)
    series_resistance = check_positive("series_resistance", series_resistance, allow_zero=True)
    return feedback_resistance * supply_voltage / (resistance + series_resistance)


def readout_resistance(
    output_voltage: Any,
    *,
    supply_voltage: float,
    feedback_resistance: float,
    series_resistance: float = 0.0,
) -> np.ndarray:
    r"""Cell resistance from the readout voltage, eq. 25.6 solved for R_ij [Ohm].

    Parameters
    ----------
    output_voltage : array_like
        V_o [V], > 0.
    supply_voltage : float
        The *nominal* V_cc assumed by the inversion [V], > 0. A real supply that differs
        from it scales the estimate by V_cc,nominal / V_cc,actual.
    feedback_resistance : float
        R_f [Ohm], > 0.
    series_resistance : float, default 0.0
        The series resistance the inversion corrects for [Ohm], >= 0. Leaving it at 0 when
        the circuit has R_s > 0 biases every estimate up by exactly R_s.

    Returns
    -------
    numpy.ndarray
        R_ij = R_f V_cc / V_o - R_s [Ohm].

    Examples
    --------
    >>> v = readout_voltage(1e4, supply_voltage=5.0, feedback_resistance=2e3,
    ...                     series_resistance=100.0)
    >>> float(readout_resistance(v, supply_voltage=5.0, feedback_resistance=2e3))
    10100.0...
    """
    output_voltage = as_finite_array("output_voltage", output_voltage)
    if np.any(output_voltage <= 0):
        raise ValueError(f"`output_voltage` must be > 0, got {float(np.min(output_voltage)):g}")
    supply_voltage = check_positive("supply_voltage", supply_voltage)
    feedback_resistance = check_positive("feedback_resistance", feedback_resistance)
    series_resistance = check_positive("series_resistance", series_resistance, allow_zero=True)
    return feedback_resistance * supply_voltage / output_voltage - series_resistance


@dataclass(frozen=True)
class ResistiveTransducer:
    """A pressure-sensitive resistive cell read by the transimpedance stage of Figure 25.4.

    Senses the compressive normal ``pressure`` on the cell [Pa]; the signal is the readout
    voltage V_o [V]. Illustrative defaults describe an FSR-like cell, not a product.

    Parameters
    ----------
    unloaded_resistance : float, default 1e5
        R_0 [Ohm].
    reference_pressure : float, default 1e4
        p_ref [Pa].
    exponent : float, default 1.0
        n [-].
    supply_voltage : float, default 5.0
        Nominal V_cc [V].
    feedback_resistance : float, default 1e4
        R_f [Ohm].
    series_resistance : float, default 0.0
        Multiplexer and wiring resistance in series with the cell [Ohm]; the inversion
        corrects for it (it is a known design value).

    Examples
    --------
    >>> cell = ResistiveTransducer()
    >>> v = cell.respond([0.0, 1e4, 1e5])
    >>> np.round(v, 4).tolist()
    [0.5, 1.0, 5.5]
    >>> np.round(cell.invert(v), 6).tolist()
    [0.0, 10000.0, 100000.0]
    >>> # a supply 2 % high, unseen by the inversion, reads 4 % high at p = p_ref
    >>> float(cell.invert(cell.respond(1e4, supply_voltage=5.1)))
    10400.0...
    """

    quantity: ClassVar[str] = "pressure"
    quantity_unit: ClassVar[str] = "Pa"
    signal_unit: ClassVar[str] = "V"

    unloaded_resistance: float = 1e5
    reference_pressure: float = 1e4
    exponent: float = 1.0
    supply_voltage: float = 5.0
    feedback_resistance: float = 1e4
    series_resistance: float = 0.0

    def __post_init__(self) -> None:
        for name in (
            "unloaded_resistance",
            "reference_pressure",
            "exponent",
            "supply_voltage",
            "feedback_resistance",
        ):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        object.__setattr__(
            self,
            "series_resistance",
            check_positive("series_resistance", self.series_resistance, allow_zero=True),
        )

    def resistance(self, pressure: Any) -> np.ndarray:
        """Cell resistance under `pressure` [Pa] -> [Ohm]."""
        return piezoresistive_resistance(
            pressure,
            unloaded_resistance=self.unloaded_resistance,
            reference_pressure=self.reference_pressure,
            exponent=self.exponent,
        )

    def respond(self, pressure: Any, /, *, supply_voltage: Any = None) -> np.ndarray:
        """Readout voltage [V] for `pressure` [Pa]; `supply_voltage` overrides the nominal."""
        supply = self.supply_voltage if supply_voltage is None else supply_voltage
        return readout_voltage(
            self.resistance(pressure),
            supply_voltage=supply,
            feedback_resistance=self.feedback_resistance,
            series_resistance=self.series_resistance,
        )

    def invert(self, signal: Any, /) -> np.ndarray:
        """Pressure [Pa] from the readout voltage `signal` [V], assuming the nominal supply."""
        resistance = readout_resistance(
            signal,
            supply_voltage=self.supply_voltage,
            feedback_resistance=self.feedback_resistance,
            series_resistance=self.series_resistance,
        )
        if np.any(resistance <= 0):
            raise ValueError(
                f"`signal` up to {float(np.max(signal)):g} V implies a non-positive resistance"
            )
        return piezoresistive_pressure(
            resistance,
            unloaded_resistance=self.unloaded_resistance,
            reference_pressure=self.reference_pressure,
            exponent=self.exponent,
        )
