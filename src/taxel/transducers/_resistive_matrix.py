"""Scanning a passive row-column matrix of resistive cells: ghost paths and their cure.

Every cell of an ``rows x cols`` matrix joins one row line to one column line, so the
network has ``rows + cols`` nodes and ``rows * cols`` edges. Selecting row i (driven at
V_cc) and column j (held at the virtual ground of the transimpedance amplifier of Figure
25.4) measures R_ij only if no other current reaches column j. With the unselected lines
left floating, current also flows through chains row i -> column l -> row k -> column j of
unselected cells: the "ghost" paths that make a high-resistance cell read low when its
neighbours are loaded. Grounding every unselected line (the zero-potential method) leaves
those chains with no voltage across their last link, and the crosstalk vanishes when the
multiplexer switches are ideal. With a finite switch resistance a residue remains: the
selected row sags and the grounded lines sit slightly above 0 V, which matters when the
selected cell is much more resistive than its neighbours.

Both readout modes are solved exactly by nodal analysis, and both can be inverted by Newton's
method on the network model with its analytic Jacobian.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, check_choice, check_integer, check_positive

__all__ = ["ResistiveScanInversion", "invert_resistive_scan", "scan_resistive_matrix"]

_MODES = ("floating", "grounded")
_MAX_LOG_STEP = 3.0  # at most a factor e^3 per Newton step in any conductance


def _laplacian(conductance: np.ndarray) -> np.ndarray:
    """Nodal matrix of the bipartite row-column network; rows first, then columns."""
    rows, cols = conductance.shape
    lap = np.zeros((rows + cols, rows + cols))
    lap[:rows, rows:] = -conductance
    lap[rows:, :rows] = -conductance.T
    lap[np.arange(rows), np.arange(rows)] = conductance.sum(axis=1)
    lap[np.arange(rows, rows + cols), np.arange(rows, rows + cols)] = conductance.sum(axis=0)
    return lap


def _edge_differences(field: np.ndarray, rows: int) -> np.ndarray:
    """f[row k] - f[column l] for every cell (k, l), for each trailing index of `field`."""
    return field[:rows, None, ...] - field[None, rows:, ...]


def _floating(conductance: np.ndarray, switch_resistance: float) -> tuple[np.ndarray, Any]:
    """Apparent conductance and its Jacobian with the unselected lines floating."""
    rows, cols = conductance.shape
    lap = _laplacian(conductance)
    # Pseudo-inverse of a connected Laplacian: (L + a J/n)^-1 - J/(a n), a of the scale of L.
    n = rows + cols
    scale = float(np.mean(np.diag(lap)))
    pinv = np.linalg.inv(lap + scale / n) - 1.0 / (scale * n)
    cross = pinv[:rows, rows:]
    effective = np.diag(pinv)[:rows, None] + np.diag(pinv)[None, rows:] - 2.0 * cross
    apparent = 1.0 / (effective + 2.0 * switch_resistance)

    def jacobian() -> np.ndarray:
        # Unit current in at row i, out at column j: u = pinv[:, i] - pinv[:, rows + j].
        # d(driving-point conductance)/dG_kl = (Y * (u_k - u_l))^2 (Rayleigh's principle).
        injected = pinv[:, :rows, None] - pinv[:, None, rows:]  # (node, i, j)
        drop = _edge_differences(injected, rows)  # (k, l, i, j)
        return (apparent[None, None] * drop) ** 2

    return apparent, jacobian


def _grounded(conductance: np.ndarray, switch_resistance: float) -> tuple[np.ndarray, Any]:
    """Apparent conductance and its Jacobian with the unselected lines grounded."""
    rows, cols = conductance.shape
    if switch_resistance == 0.0:
        # Every node is held: row i at V_cc, all else at 0 V; only G_ij feeds column j.
        return conductance.copy(), lambda: np.eye(rows * cols).reshape(rows, cols, rows, cols)
    switch = 1.0 / switch_resistance
    inverse = np.linalg.inv(_laplacian(conductance) + switch * np.eye(rows + cols))
    apparent = switch**2 * inverse[rows:, :rows].T

    def jacobian() -> np.ndarray:
        # Y_ij = g^2 W[rows + j, i]; dW = -W dA W with dA = (e_k - e_l)(e_k - e_l)^T.
        drive = _edge_differences(inverse[:, :rows], rows)  # (k, l, i)
        sense = _edge_differences(inverse[:, rows:], rows)  # (k, l, j)
        return -(switch**2) * drive[:, :, :, None] * sense[:, :, None, :]

    return apparent, jacobian


def _network(conductance: np.ndarray, switch_resistance: float, unselected: str) -> Any:
    solver = _floating if unselected == "floating" else _grounded
    return solver(conductance, switch_resistance)


def _check_common(
    supply_voltage: float, feedback_resistance: float, switch_resistance: float, unselected: str
) -> tuple[float, float, float]:
    check_choice("unselected", unselected, _MODES)
    return (
        check_positive("supply_voltage", supply_voltage),
        check_positive("feedback_resistance", feedback_resistance),
        check_positive("switch_resistance", switch_resistance, allow_zero=True),
    )


def scan_resistive_matrix(
    resistance: Any,
    *,
    supply_voltage: float,
    feedback_resistance: float,
    switch_resistance: float = 0.0,
    unselected: str = "grounded",
) -> np.ndarray:
    r"""Readout voltage of every cell of a passive resistive matrix, network solved [V].

    Parameters
    ----------
    resistance : array_like, shape (rows, cols)
        Cell resistances R_ij [Ohm], finite and > 0.
    supply_voltage : float
        V_cc applied to the selected row [V], > 0.
    feedback_resistance : float
        R_f of the transimpedance amplifier on the selected column [Ohm], > 0.
    switch_resistance : float, default 0.0
        On-resistance of each multiplexer switch [Ohm], >= 0. Every line has one; the
        selected cell's path goes through two.
    unselected : {'grounded', 'floating'}
        What the unselected row and column lines are connected to: ground through their
        switches (the zero-potential method), or nothing.

    Returns
    -------
    numpy.ndarray, shape (rows, cols)
        V_o(i, j) = R_f V_cc Y_ij [V], with Y_ij the current into column j's amplifier per
        volt on row i, from the whole network.

    Notes
    -----
    Floating lines: the measurement sees the two-terminal resistance of the whole network
    between row i and column j, :math:`Y_{ij}^{-1} = 2 R_{sw} + (e_i - e_j)^T L^+ (e_i - e_j)`
    with L the nodal (Laplacian) matrix of the cell conductances. Grounded lines: every line
    reaches its source or ground through :math:`g_{sw} = 1/R_{sw}`, the nodal matrix is
    :math:`A = L + g_{sw} I`, and :math:`Y_{ij} = g_{sw}^2 (A^{-1})_{j i}`; as
    :math:`R_{sw} \to 0`, :math:`Y_{ij} \to G_{ij}` and eq. 25.6 holds exactly for every cell.

    Examples
    --------
    >>> r = np.full((3, 3), 1e3)
    >>> r[1, 0] = 1e5  # R_21 of Figure 25.4, unloaded among loaded cells
    >>> kw = dict(supply_voltage=5.0, feedback_resistance=1e3)
    >>> v_grounded = scan_resistive_matrix(r, **kw)
    >>> float(5.0 * 1e3 / v_grounded[1, 0])  # eq. 25.6 read back: exact
    100000.0
    >>> v_floating = scan_resistive_matrix(r, unselected="floating", **kw)
    >>> round(float(5.0 * 1e3 / v_floating[1, 0]))  # ghost paths: reads ~1.2 kOhm
    1235
    """
    resistance = as_finite_array("resistance", resistance, ndim=2)
    if np.any(resistance <= 0):
        raise ValueError(f"`resistance` must be > 0, got {float(np.min(resistance)):g}")
    supply_voltage, feedback_resistance, switch_resistance = _check_common(
        supply_voltage, feedback_resistance, switch_resistance, unselected
    )
    apparent, _ = _network(1.0 / resistance, switch_resistance, unselected)
    return feedback_resistance * supply_voltage * apparent


@dataclass(frozen=True)
class ResistiveScanInversion:
    """Outcome of `invert_resistive_scan`.

    Attributes
    ----------
    resistance : numpy.ndarray, shape (rows, cols)
        Cell resistances that reproduce the scan [Ohm] (the last iterate if not converged).
    converged : bool
        Whether the relative residual fell below the tolerance.
    n_iterations : int
        Newton steps taken.
    residual : float
        Largest relative mismatch between the measured and the modelled readout [-].
    message : str
        What happened, in words.
    """

    resistance: np.ndarray
    converged: bool
    n_iterations: int
    residual: float
    message: str


def invert_resistive_scan(
    output_voltage: Any,
    *,
    supply_voltage: float,
    feedback_resistance: float,
    switch_resistance: float = 0.0,
    unselected: str = "floating",
    tolerance: float = 1e-10,
    max_iterations: int = 50,
) -> ResistiveScanInversion:
    r"""Recover the cell resistances of a passive matrix from a full scan, ghost paths included.

    Parameters
    ----------
    output_voltage : array_like, shape (rows, cols)
        The scan, V_o for every selected (row, column) pair [V], > 0.
    supply_voltage, feedback_resistance, switch_resistance, unselected
        The readout, as in `scan_resistive_matrix`.
    tolerance : float, default 1e-10
        Stop when the largest relative readout mismatch is below this [-].
    max_iterations : int, default 50
        Most Newton steps.

    Returns
    -------
    ResistiveScanInversion
        The resistances and how the iteration ended.

    Notes
    -----
    Newton's method on :math:`\theta = \ln G` (conductances stay positive) solves
    :math:`Y(G) = V_o / (R_f V_{cc})` for all cells at once, with the exact Jacobian: for
    floating lines :math:`\partial Y_{ij} / \partial G_{kl} = (Y_{ij} \Delta u_{kl})^2`, the
    squared voltage across cell (k, l) per volt of drive (Rayleigh's principle for a
    driving-point conductance); for grounded lines the adjoint form
    :math:`-g_{sw}^2 \Delta W_{kl,j} \Delta W_{kl,i}`. A backtracking line search keeps
    every step a decrease of the residual. Cost: one dense solve of size rows * cols per
    step, so this is for arrays up to a few hundred cells. Noisy scans may have no exact
    positive solution (a cell would need a negative conductance); the iteration then ends
    unconverged with the closest network it found, and `residual` says how far off it is.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> r = rng.uniform(1e3, 1e5, size=(4, 5))
    >>> kw = dict(supply_voltage=5.0, feedback_resistance=1e3, unselected="floating")
    >>> fit = invert_resistive_scan(scan_resistive_matrix(r, **kw), **kw)
    >>> fit.converged, bool(np.allclose(fit.resistance, r, rtol=1e-8))
    (True, True)
    """
    output_voltage = as_finite_array("output_voltage", output_voltage, ndim=2)
    if np.any(output_voltage <= 0):
        raise ValueError(f"`output_voltage` must be > 0, got {float(np.min(output_voltage)):g}")
    supply_voltage, feedback_resistance, switch_resistance = _check_common(
        supply_voltage, feedback_resistance, switch_resistance, unselected
    )
    tolerance = check_positive("tolerance", tolerance)
    max_iterations = check_integer("max_iterations", max_iterations)
    measured = output_voltage / (feedback_resistance * supply_voltage)
    if switch_resistance > 0 and np.any(measured * 2.0 * switch_resistance >= 1.0):
        raise ValueError(
            "`output_voltage` exceeds what the switch resistance allows: "
            f"max {float(np.max(output_voltage)):g} V"
        )
    size = measured.size
    log_g = np.log(measured)  # start from eq. 25.6 read naively, cell by cell

    def misfit(log_conductance: np.ndarray) -> tuple[np.ndarray, Any]:
        apparent, jacobian = _network(np.exp(log_conductance), switch_resistance, unselected)
        return apparent / measured - 1.0, jacobian

    relative, jacobian = misfit(log_g)
    residual = float(np.max(np.abs(relative)))
    for iteration in range(1, int(max_iterations) + 1):
        if residual < tolerance:
            return ResistiveScanInversion(
                np.exp(-log_g), True, iteration - 1, residual, "converged"
            )
        # d(relative_ij)/d(theta_kl) = J[k, l, i, j] G_kl / measured_ij
        jac = jacobian().reshape(size, size).T * np.exp(log_g).ravel()[None, :]
        jac /= measured.ravel()[:, None]
        # lstsq rather than solve: with noisy data a cell may be driven towards zero
        # conductance, where the Jacobian loses rank; the step is then the least-norm one.
        step = np.linalg.lstsq(jac, -relative.ravel(), rcond=None)[0].reshape(measured.shape)
        step = np.clip(step, -_MAX_LOG_STEP, _MAX_LOG_STEP)
        length = 1.0
        while True:
            trial = log_g + length * step
            trial_relative, trial_jacobian = misfit(trial)
            trial_residual = float(np.max(np.abs(trial_relative)))
            if trial_residual < residual or length < 1e-6:
                break
            length /= 2.0
        log_g, relative, jacobian, residual = trial, trial_relative, trial_jacobian, trial_residual
    converged = residual < tolerance
    message = "converged" if converged else f"no convergence in {int(max_iterations)} steps"
    return ResistiveScanInversion(
        np.exp(-log_g), converged, int(max_iterations), residual, message
    )
