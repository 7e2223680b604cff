"""Fiber-optic microbend sensing (Figure 25.11): two orthogonal layers of active fibers.

A rows x cols grid of crossings. Row fiber i crosses every column fiber j once, and both are
squeezed between corrugation layers at the crossing: a force f_ij deflects each by
delta_ij = f_ij / k. Light leaks out of a bent fiber, so a fiber's transmission falls
exponentially with the summed microbend deflection along it,

    P_i = P_0 T_0 exp(-beta sum_j delta_ij) = P_0 T_0 exp(-(beta / k) F_i),

with F_i the total force on row fiber i (its line load); the same holds for the columns
with the column sums. Each detector therefore reads one projection of the load, and the two
layers give the row and column sums of the force image: the inverse recovers those sums
exactly. A full image is not determined by its two projections; `separable_pressure` gives
the estimate that assumes none but them (exact for loads that factor as g(x) h(y)).

Signals are arrays of shape (..., rows + cols): the row fibers first, then the columns.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from taxel._validation import (
    as_finite_array,
    check_count,
    check_integer,
    check_positive,
    check_range,
)

__all__ = [
    "MicrobendTransducer",
    "microbend_line_loads",
    "microbend_power",
    "separable_pressure",
]


def _check_optics(
    stiffness: float, bend_loss: float, source_power: float, transmission: float
) -> tuple[float, float, float, float]:
    return (
        check_positive("stiffness", stiffness),
        check_positive("bend_loss", bend_loss),
        check_positive("source_power", source_power),
        check_range("transmission", transmission, 0.0, 1.0, low_inclusive=False),
    )


def microbend_power(
    pressure: Any,
    *,
    crossing_area: float,
    stiffness: float,
    bend_loss: float,
    source_power: float = 1.0,
    transmission: float = 1.0,
) -> np.ndarray:
    r"""Power reaching the detector of every active fiber [W].

    Parameters
    ----------
    pressure : array_like, shape (..., rows, cols)
        Normal pressure on each crossing [Pa], >= 0.
    crossing_area : float
        Area of the sensor served by one crossing, the pitch squared [m^2], > 0.
    stiffness : float
        k, force per unit microbend deflection at a crossing [N/m], > 0.
    bend_loss : float
        beta, the attenuation per unit deflection [1/m] (nepers per metre of deflection;
        0.1 dB per micrometre is 2.3e4 /m), > 0.
    source_power : float, default 1.0
        P_0 of each LED [W], > 0.
    transmission : float, default 1.0
        T_0, the unloaded transmission of a fiber [-], in (0, 1].

    Returns
    -------
    numpy.ndarray, shape (..., rows + cols)
        Detected power: the row fibers, then the column fibers.

    Notes
    -----
    :math:`P_i = P_0 T_0 \exp(-\beta F_i / k)` with :math:`F_i = A_c \sum_j p_{ij}`, and
    the same with the column sums. The attenuation in decibels,
    :math:`10 \log_{10}(P_0 T_0 / P_i)`, is linear in the line load.

    Examples
    --------
    >>> p = np.zeros((3, 4))
    >>> p[1, 2] = 4e4  # one pressed crossing: 1 N on 25 mm^2
    >>> power = microbend_power(p, crossing_area=2.5e-5, stiffness=1e5, bend_loss=2.3e4)
    >>> np.round(power, 4).tolist()  # row 1 and column 2 lose 1 - exp(-0.23)
    [1.0, 0.7945, 1.0, 1.0, 1.0, 0.7945, 1.0]
    """
    pressure = as_finite_array("pressure", pressure)
    if pressure.ndim < 2:
        raise ValueError(
            f"`pressure` must be at least 2-D (rows, cols), got shape {pressure.shape}"
        )
    if np.any(pressure < 0):
        raise ValueError(f"`pressure` must be >= 0, got {float(np.min(pressure)):g}")
    crossing_area = check_positive("crossing_area", crossing_area)
    stiffness, bend_loss, source_power, transmission = _check_optics(
        stiffness, bend_loss, source_power, transmission
    )
    force = pressure * crossing_area
    loads = np.concatenate([force.sum(axis=-1), force.sum(axis=-2)], axis=-1)
    return source_power * transmission * np.exp(-bend_loss * loads / stiffness)


def microbend_line_loads(
    power: Any,
    *,
    stiffness: float,
    bend_loss: float,
    source_power: float = 1.0,
    transmission: float = 1.0,
) -> np.ndarray:
    """Total force along each active fiber from its detected power, the inverse [N].

    Parameters
    ----------
    power : array_like, shape (..., rows + cols)
        Detected power [W], > 0.
    stiffness, bend_loss, source_power, transmission : float
        As in `microbend_power`.

    Returns
    -------
    numpy.ndarray, shape (..., rows + cols)
        F = (k / beta) ln(P_0 T_0 / P) [N]: the row sums, then the column sums of the force.
        A power above P_0 T_0 (detector noise on an unloaded fiber) gives a negative load,
        kept so that averaging stays unbiased; `separable_pressure` clips it to zero.

    Examples
    --------
    >>> kw = dict(stiffness=1e5, bend_loss=2.3e4)
    >>> round(float(microbend_line_loads(np.exp(-0.23), **kw)), 12)
    1.0
    """
    power = as_finite_array("power", power)
    if np.any(power <= 0):
        raise ValueError(f"`power` must be > 0, got {float(np.min(power)):g}")
    stiffness, bend_loss, source_power, transmission = _check_optics(
        stiffness, bend_loss, source_power, transmission
    )
    return stiffness / bend_loss * np.log(source_power * transmission / power)


def separable_pressure(
    line_loads: Any, *, rows: int, crossing_area: float, cols: int | None = None
) -> np.ndarray:
    r"""Pressure image from its row and column sums, assuming it factors as g(row) h(col) [Pa].

    Parameters
    ----------
    line_loads : array_like, shape (..., rows + cols)
        Row sums then column sums of the force [N], as from `microbend_line_loads`.
    rows : int
        Number of row fibers.
    crossing_area : float
        Area per crossing [m^2], > 0.
    cols : int, optional
        Number of column fibers; when given, `line_loads` must hold ``rows + cols`` values
        along its last axis. Without it the columns are whatever follows the `rows` values,
        so give it whenever it is known: a row count off by one is otherwise read as one
        more or one fewer column.

    Returns
    -------
    numpy.ndarray, shape (..., rows, cols)
        :math:`p_{ij} = F^{row}_i F^{col}_j / (F_{total} A_c)`, with negative sums (noise)
        clipped to zero and the total taken as the mean of the two layers' totals. This is
        the maximum-entropy image with the measured projections; it is exact for a single
        contact whose load factors, and smears two contacts into four.

    Examples
    --------
    >>> p = np.outer([0, 1, 2], [1, 0, 3, 0]) * 1e3
    >>> loads = np.concatenate([p.sum(1), p.sum(0)]) * 1e-4
    >>> bool(np.allclose(separable_pressure(loads, rows=3, cols=4, crossing_area=1e-4), p))
    True
    """
    loads = np.maximum(as_finite_array("line_loads", line_loads), 0.0)
    if loads.ndim == 0 or loads.shape[-1] < 2:
        raise ValueError(
            "`line_loads` must hold rows + cols >= 2 values along its last axis, got shape "
            f"{loads.shape}"
        )
    count = loads.shape[-1]
    try:
        n_rows = check_count("rows", rows)
    except (TypeError, ValueError):
        n_rows = 0  # refused below, naming the range
    if not 1 <= n_rows < count:
        raise ValueError(f"`rows` must be an integer in 1..{count - 1}, got {rows!r}")
    if cols is not None and n_rows + (n_cols := check_count("cols", cols)) != count:
        raise ValueError(
            f"`line_loads` must hold rows + cols = {n_rows} + {n_cols} = {n_rows + n_cols} "
            f"values along its last axis, got shape {loads.shape}"
        )
    crossing_area = check_positive("crossing_area", crossing_area)
    row_loads, column_loads = loads[..., :n_rows], loads[..., n_rows:]
    total = 0.5 * (row_loads.sum(axis=-1) + column_loads.sum(axis=-1))
    safe = np.where(total > 0, total, 1.0)[..., None, None]
    image = row_loads[..., :, None] * column_loads[..., None, :] / safe
    return np.where(total[..., None, None] > 0, image, 0.0) / crossing_area


@dataclass(frozen=True)
class MicrobendTransducer:
    """A two-layer microbend fiber array (Figure 25.11) with one detector per fiber.

    Senses the normal ``pressure`` on each crossing [Pa], shape (..., rows, cols); the
    signal is the detected power of every fiber [W], shape (..., rows + cols), rows first.
    `line_loads` inverts exactly to the row and column force sums; `invert` adds the
    separable (maximum-entropy) estimate of the pressure image.

    Parameters
    ----------
    rows, cols : int, default 8
        Number of row and column fibers.
    crossing_area : float, default 2.5e-5
        Area per crossing [m^2] (5 mm pitch).
    stiffness : float, default 1e5
        k [N/m]: 1 N deflects a crossing by 10 um.
    bend_loss : float, default 2.3e4
        beta [1/m] (0.1 dB per um of deflection).
    source_power : float, default 1e-3
        P_0 [W].
    transmission : float, default 0.8
        T_0 [-].

    Examples
    --------
    >>> array = MicrobendTransducer(rows=3, cols=4)
    >>> p = np.outer([0.0, 1.0, 0.5], [0.0, 2.0, 1.0, 0.0]) * 1e4
    >>> signal = array.respond(p)
    >>> signal.shape
    (7,)
    >>> np.round(array.line_loads(signal), 6).tolist()  # [N]
    [0.0, 0.75, 0.375, 0.0, 0.75, 0.375, 0.0]
    >>> bool(np.allclose(array.invert(signal), p))
    True
    """

    quantity: ClassVar[str] = "pressure"
    quantity_unit: ClassVar[str] = "Pa"
    signal_unit: ClassVar[str] = "W"

    rows: int = 8
    cols: int = 8
    crossing_area: float = 2.5e-5
    stiffness: float = 1e5
    bend_loss: float = 2.3e4
    source_power: float = 1e-3
    transmission: float = 0.8

    def __post_init__(self) -> None:
        for name in ("rows", "cols"):
            value = getattr(self, name)
            object.__setattr__(self, name, check_integer(name, value))
        object.__setattr__(
            self, "crossing_area", check_positive("crossing_area", self.crossing_area)
        )
        values = _check_optics(
            self.stiffness, self.bend_loss, self.source_power, self.transmission
        )
        for name, value in zip(
            ("stiffness", "bend_loss", "source_power", "transmission"), values, strict=True
        ):
            object.__setattr__(self, name, value)

    def _optics(self) -> dict[str, float]:
        return {
            "stiffness": self.stiffness,
            "bend_loss": self.bend_loss,
            "source_power": self.source_power,
            "transmission": self.transmission,
        }

    def respond(self, pressure: Any, /) -> np.ndarray:
        """Detected power of every fiber [W] for a pressure image [Pa] of shape (rows, cols)."""
        pressure = as_finite_array("pressure", pressure)
        if pressure.shape[-2:] != (self.rows, self.cols):
            raise ValueError(
                f"`pressure` must end in shape ({self.rows}, {self.cols}), got {pressure.shape}"
            )
        return microbend_power(pressure, crossing_area=self.crossing_area, **self._optics())

    def attenuation(self, signal: Any) -> np.ndarray:
        """Load-induced attenuation of every fiber [dB], 10 log10(P_0 T_0 / P)."""
        loads = self.line_loads(signal)
        return 10.0 / np.log(10.0) * self.bend_loss / self.stiffness * loads

    def line_loads(self, signal: Any) -> np.ndarray:
        """Row then column sums of the force [N] from the detected powers [W]."""
        signal = as_finite_array("signal", signal)
        if signal.ndim == 0 or signal.shape[-1] != self.rows + self.cols:
            raise ValueError(
                f"`signal` must end in length rows + cols = {self.rows + self.cols}, "
                f"got shape {signal.shape}"
            )
        return microbend_line_loads(signal, **self._optics())

    def invert(self, signal: Any, /) -> np.ndarray:
        """Separable estimate of the pressure image [Pa] from the detected powers [W]."""
        return separable_pressure(
            self.line_loads(signal),
            rows=self.rows,
            cols=self.cols,
            crossing_area=self.crossing_area,
        )
