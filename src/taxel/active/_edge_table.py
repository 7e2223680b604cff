"""The empirical edge-radius table of the Ellis seed (section 2.2), saved as JSON.

"A good estimate of the edge radius for known applied forces can be found empirically. The
method is to take some preferred application forces ..., and press known edge radii against
the sensor. Once such a table is constructed, selecting the best fit is a simple matter."

The table holds, for each known radius and each force, the cross-section descriptors of
`edge_cross_section` as a straight line in the logarithm of the line load (the force over
the length of edge that carries it, which changes with the edge's angle and position on a
square sensor), and the spread of each descriptor about those lines (its noise).
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy.interpolate import PchipInterpolator

from taxel._validation import as_finite_array
from taxel.active._edge_section import SECTION_DESCRIPTORS, EdgeCrossSection
from taxel.active._json_files import parsing, read_json, write_json

__all__ = ["EdgeRadiusTable", "fit_edge_radius_table"]

_FORMAT = "taxel.edge_radius_table"
_VERSION = 2  # 1: line loads over the chord, not the loaded length; not comparable
_DEGREE = 3  # of the polynomial in ln(radius) through the table's radii
_GRID = 2001  # points of the log-radius grid searched between the table's ends
_FLOOR = 1e-3  # smallest descriptor spread, as a fraction of the descriptor's range


def _smooth(log_radii: np.ndarray, values: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """Descriptors between the table's radii: a least-squares cubic in ln(radius).

    With fewer radii than the cubic needs, a monotone cubic (PCHIP) through them.
    """
    if log_radii.size <= _DEGREE + 1:
        return PchipInterpolator(log_radii, values, axis=0)(grid)
    centre, half = log_radii.mean(), max(np.ptp(log_radii) / 2, 1e-12)
    basis = np.polynomial.legendre.legvander((log_radii - centre) / half, _DEGREE)
    coefficients, *_ = np.linalg.lstsq(basis, values, rcond=None)
    return np.polynomial.legendre.legvander((grid - centre) / half, _DEGREE) @ coefficients


@dataclass(frozen=True, eq=False)
class EdgeRadiusTable:
    """Cross-section descriptors of known edge radii at chosen forces.

    Build it with `fit_edge_radius_table` (from measured cross-sections) or
    `build_edge_radius_table` (in simulation), or `EdgeRadiusTable.load`.

    Attributes
    ----------
    radii : numpy.ndarray
        (n_radii,) the known edge radii, increasing [m].
    forces : numpy.ndarray
        (n_forces,) the pressing forces [N], increasing.
    reference_loads : numpy.ndarray
        (n_forces,) the line load each force's lines are centred on [N/m].
    intercepts : numpy.ndarray
        (n_radii, n_forces, n_descriptors) descriptor at the reference load.
    slopes : numpy.ndarray
        (n_radii, n_forces, n_descriptors) change per unit of ln(load / reference load).
    spreads : numpy.ndarray
        (n_forces, n_descriptors) residual standard deviation of each descriptor.
    sensor : str
        Name of the sensor the table was made on; it is valid for that sensor only.
    n_presses : int
        Presses the table was fitted from.
    correlation : numpy.ndarray, optional
        (n_forces * n_descriptors, n_forces * n_descriptors) correlation of the
        standardised residuals (forces outer, descriptors inner). The widths, area and peak
        of one cross-section move together, so they carry less than independent evidence;
        None treats them as independent (tables saved before it was stored).
    """

    radii: np.ndarray
    forces: np.ndarray
    reference_loads: np.ndarray
    intercepts: np.ndarray
    slopes: np.ndarray
    spreads: np.ndarray
    sensor: str = ""
    n_presses: int = 0
    correlation: np.ndarray | None = None

    def __post_init__(self) -> None:
        radii = as_finite_array("radii", self.radii, ndim=1)
        if radii.size < 2:
            raise ValueError(f"`radii` must hold at least 2 known radii, got {radii.size}")
        if np.any(radii <= 0) or np.any(np.diff(radii) <= 0):
            raise ValueError(f"`radii` must be positive and increasing, got {radii.tolist()}")
        forces = as_finite_array("forces", self.forces, ndim=1)
        if forces.size < 1 or np.any(forces <= 0) or np.any(np.diff(forces) <= 0):
            raise ValueError(f"`forces` must be positive and increasing, got {forces.tolist()}")
        shape = (radii.size, forces.size, len(SECTION_DESCRIPTORS))
        for name in ("intercepts", "slopes"):
            array = as_finite_array(name, getattr(self, name), ndim=3)
            if array.shape != shape:
                raise ValueError(f"`{name}` must have shape {shape}, got {array.shape}")
            object.__setattr__(self, name, array)
        spreads = as_finite_array("spreads", self.spreads, ndim=2)
        if spreads.shape != shape[1:] or np.any(spreads <= 0):
            raise ValueError(f"`spreads` must be positive with shape {shape[1:]}")
        loads = as_finite_array("reference_loads", self.reference_loads, ndim=1)
        if loads.shape != forces.shape or np.any(loads <= 0):
            raise ValueError("`reference_loads` must be positive, one per force")
        object.__setattr__(self, "radii", radii)
        object.__setattr__(self, "forces", forces)
        object.__setattr__(self, "spreads", spreads)
        object.__setattr__(self, "reference_loads", loads)
        if self.correlation is not None:
            size = forces.size * len(SECTION_DESCRIPTORS)
            correlation = as_finite_array("correlation", self.correlation, ndim=2)
            if (
                correlation.shape != (size, size)
                or not np.allclose(correlation, correlation.T)
                or not np.allclose(np.diag(correlation), 1.0)
                or np.linalg.eigvalsh(correlation).min() < -1e-9
            ):
                raise ValueError(
                    f"`correlation` must be a ({size}, {size}) correlation matrix "
                    "(symmetric, unit diagonal, positive semi-definite)"
                )
            object.__setattr__(self, "correlation", correlation)

    # ---------------------------------------------------------------------- prediction
    def predict(self, force_per_length: Any) -> np.ndarray:
        """Descriptors of every table radius at the given line loads.

        Parameters
        ----------
        force_per_length : array_like
            (n_forces,) the line load of each press [N/m].

        Returns
        -------
        numpy.ndarray
            (n_radii, n_forces, n_descriptors).
        """
        loads = as_finite_array("force_per_length", force_per_length, ndim=1)
        if loads.shape != self.forces.shape or np.any(loads <= 0):
            raise ValueError(
                f"`force_per_length` must hold {self.forces.size} positive line loads, "
                f"got {loads.tolist()}"
            )
        shift = np.log(loads / self.reference_loads)
        return self.intercepts + self.slopes * shift[None, :, None]

    def distances(self, sections: Sequence[EdgeCrossSection]) -> np.ndarray:
        """Mean squared standardised difference of the sections from each table radius."""
        measured, loads = self._measured(sections)
        predicted = self.predict(loads)
        return (((predicted - measured) / self.spreads) ** 2).mean(axis=(1, 2))

    def estimate(self, sections: Sequence[EdgeCrossSection]) -> tuple[float, float, float]:
        """Interpolated radius [m], its standard uncertainty [m] and the residual.

        Each descriptor is carried between the table's radii by a least-squares cubic in
        ln(radius) (a monotone PCHIP through them when the table has four radii or
        fewer), which smooths the noise of single entries; the estimate minimises the mean
        squared standardised difference (the residual) over ln(radius) between the
        smallest and largest radius.
        The uncertainty is that of this weighted least-squares estimate when the descriptors'
        errors are correlated as in the table's residuals (`correlation`): with g the
        change of the standardised descriptors per unit of ln(radius) at the estimate,
        var(ln R) = g' C g / (g' g)^2, which is 1 / (g' g) for independent descriptors.
        When the residual exceeds 1 the descriptors differ from the nearest table edge by
        more than the table's spreads, and the uncertainty is multiplied by its square root.
        """
        measured, loads = self._measured(sections)
        predicted = self.predict(loads)
        log_radii = np.log(self.radii)
        flat = predicted.reshape(self.radii.size, -1)
        grid = np.linspace(log_radii[0], log_radii[-1], _GRID)
        standardised = (_smooth(log_radii, flat, grid) - measured.ravel()) / self.spreads.ravel()
        total = (standardised**2).sum(axis=1)
        best = int(np.argmin(total))
        log_radius = float(grid[best])
        uncertainty = math.inf
        if 0 < best < _GRID - 1:  # parabolic refinement of the minimum
            left, centre, right = total[best - 1 : best + 2]
            step = grid[1] - grid[0]
            curvature = (left - 2 * centre + right) / step**2
            if curvature > 0:
                log_radius -= (right - left) / (2 * step) / curvature
            gradient = (standardised[best + 1] - standardised[best - 1]) / (2 * step)
            information = float(gradient @ gradient)
            if information > 0:
                correlated = (
                    information
                    if self.correlation is None
                    else float(gradient @ self.correlation @ gradient)
                )
                uncertainty = math.sqrt(max(correlated, 0.0)) / information
        radius = math.exp(log_radius)
        residual = float(total[best] / standardised.shape[1])
        # cross-sections unlike every table radius's (a glass scratch along the edge, an
        # array too coarse for its phase on the taxels to average out) err by more than
        # the table's spreads say: widen the uncertainty by the square root of the
        # residual (the Birge ratio) when it exceeds 1
        uncertainty *= math.sqrt(max(residual, 1.0))
        return radius, radius * uncertainty, residual

    def _measured(self, sections: Sequence[EdgeCrossSection]) -> tuple[np.ndarray, np.ndarray]:
        sections = list(sections)
        if len(sections) != self.forces.size:
            raise ValueError(
                f"`sections` must hold one cross-section per table force "
                f"({self.forces.size}), got {len(sections)}"
            )
        measured = np.stack([section.vector() for section in sections])
        loads = np.array([section.force_per_length for section in sections])
        return measured, loads

    # ---------------------------------------------------------------------------- files
    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (the file layout of `save`)."""
        return {
            "format": _FORMAT,
            "version": _VERSION,
            "sensor": self.sensor,
            "n_presses": self.n_presses,
            "descriptors": list(SECTION_DESCRIPTORS),
            "radii_m": self.radii.tolist(),
            "forces_n": self.forces.tolist(),
            "reference_loads_n_per_m": self.reference_loads.tolist(),
            "intercepts": self.intercepts.tolist(),
            "slopes": self.slopes.tolist(),
            "spreads": self.spreads.tolist(),
            "correlation": None if self.correlation is None else self.correlation.tolist(),
        }

    def save(self, path: str | os.PathLike[str], *, overwrite: bool = False) -> Path:
        """Write the table as JSON (an existing file only with `overwrite`)."""
        return write_json(path, self.to_dict(), overwrite=overwrite)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> EdgeRadiusTable:
        """Read a table written by `save`."""
        source = Path(path)
        data = read_json(
            source,
            _FORMAT,
            (
                "radii_m",
                "forces_n",
                "reference_loads_n_per_m",
                "intercepts",
                "slopes",
                "spreads",
                "descriptors",
            ),
            "an edge radius table",
        )
        if data.get("version", 1) != _VERSION:
            raise ValueError(
                f"`path` {str(source)!r} holds a version {data.get('version', 1)!r} table, this "
                f"is version {_VERSION}: its line loads are the force over the edge's chord, "
                "not over the length that carries it; build the table again"
            )
        if data.get("descriptors") != list(SECTION_DESCRIPTORS):
            raise ValueError(f"`path` {str(source)!r} holds other descriptors than this version")
        with parsing(source, "an edge radius table"):
            return cls(
                radii=np.array(data["radii_m"], float),
                forces=np.array(data["forces_n"], float),
                reference_loads=np.array(data["reference_loads_n_per_m"], float),
                intercepts=np.array(data["intercepts"], float),
                slopes=np.array(data["slopes"], float),
                spreads=np.array(data["spreads"], float),
                sensor=str(data.get("sensor", "")),
                n_presses=int(data.get("n_presses", 0)),
                correlation=None
                if data.get("correlation") is None
                else np.array(data["correlation"], float),
            )


def fit_edge_radius_table(
    radii: Any,
    sections: Sequence[Sequence[EdgeCrossSection]],
    *,
    sensor: str = "",
) -> EdgeRadiusTable:
    """Fit the table from cross-sections of edges of known radius.

    Parameters
    ----------
    radii : array_like
        (n_presses,) the known radius of the edge of each press pair [m]; at least two
        distinct radii, each pressed at two or more line loads.
    sections : sequence of sequences of EdgeCrossSection
        For each press pair, one cross-section per force, forces in increasing order and the
        same forces for every pair.
    sensor : str, optional
        Name of the sensor, stored with the table.

    Returns
    -------
    EdgeRadiusTable

    Notes
    -----
    For each force and descriptor, with x = ln(q / q_ref), q the press's line load
    (`EdgeCrossSection.force_per_length`) and q_ref the geometric mean of the table
    presses' line loads, the model is
    ``descriptor = a(R) + (s0 + s1 ln R) x``: one intercept per radius and a slope that
    changes smoothly with the radius, fitted by least squares over all presses. The
    descriptor's spread is the residual standard deviation (floored at 0.1 % of its range
    over the table). The correlation of the standardised residuals over all forces and
    descriptors is pooled with one press's worth of independent errors, so a table of few
    presses, whose sample correlation has low rank, still gives a positive uncertainty.
    """
    radius_per_press = as_finite_array("radii", radii, ndim=1)
    sections = [list(pair) for pair in sections]
    if len(sections) != radius_per_press.size or not sections:
        raise ValueError(
            f"`sections` must hold one press pair per radius, got {len(sections)} for "
            f"{radius_per_press.size} radii"
        )
    forces = np.array([s.normal_force for s in sections[0]])
    for pair in sections:
        if len(pair) != forces.size or not np.allclose(
            [s.normal_force for s in pair], forces, rtol=1e-3
        ):
            raise ValueError("`sections` must use the same forces for every press pair")
    if np.any(np.diff(forces) <= 0):
        raise ValueError(f"`sections` must be in increasing force, got {forces.tolist()}")
    table_radii = np.unique(radius_per_press)
    if table_radii.size < 2:
        raise ValueError(f"`radii` must hold at least 2 distinct radii, got {table_radii.size}")
    measured = np.array([[s.vector() for s in pair] for pair in sections])  # (P, F, D)
    loads = np.array([[s.force_per_length for s in pair] for pair in sections])  # (P, F)
    reference = np.exp(np.log(loads).mean(axis=0))
    shift = np.log(loads / reference)
    index = np.searchsorted(table_radii, radius_per_press)
    n_radii, n_presses = table_radii.size, radius_per_press.size
    intercepts = np.zeros((n_radii, forces.size, len(SECTION_DESCRIPTORS)))
    slopes = np.zeros_like(intercepts)
    spreads = np.zeros((forces.size, len(SECTION_DESCRIPTORS)))
    residuals = np.zeros_like(measured)
    for f in range(forces.size):
        design = np.zeros((n_presses, n_radii + 2))
        design[np.arange(n_presses), index] = 1.0
        design[:, n_radii] = shift[:, f]
        design[:, n_radii + 1] = shift[:, f] * np.log(radius_per_press)
        if np.linalg.matrix_rank(design) < design.shape[1]:
            raise ValueError(
                "`sections` must press every radius at two or more line loads (edge angles)"
            )
        coefficients, *_ = np.linalg.lstsq(design, measured[:, f, :], rcond=None)
        residual = measured[:, f, :] - design @ coefficients
        residuals[:, f] = residual
        dof = max(n_presses - design.shape[1], 1)
        spread = np.sqrt((residual**2).sum(axis=0) / dof)
        span = np.ptp(coefficients[:n_radii], axis=0)
        spreads[f] = np.maximum(spread, _FLOOR * np.maximum(span, 1e-30))
        intercepts[:, f] = coefficients[:n_radii]
        slopes[:, f] = (
            coefficients[n_radii] + coefficients[n_radii + 1] * np.log(table_radii)[:, None]
        )
    return EdgeRadiusTable(
        correlation=_residual_correlation(residuals / spreads, dof),
        radii=table_radii,
        forces=forces,
        reference_loads=reference,
        intercepts=intercepts,
        slopes=slopes,
        spreads=spreads,
        sensor=sensor,
        n_presses=n_presses,
    )


def _residual_correlation(standardised: np.ndarray, dof: int) -> np.ndarray:
    """Correlation of (n_presses, n_forces, n_descriptors) residuals, shrunk to identity.

    The sample covariance over `dof` degrees of freedom is pooled with an identity of the
    weight of one more degree of freedom (independent errors), then normalised.
    """
    flat = standardised.reshape(standardised.shape[0], -1)
    size = flat.shape[1]
    pooled = (flat.T @ flat + np.eye(size)) / (dof + 1)
    scale = np.sqrt(np.diag(pooled))
    correlation = pooled / np.outer(scale, scale)
    return (correlation + correlation.T) / 2
