r"""Frictionless contact of a rigid or elastic indenter with the cover, contact area unknown.

The gap between the bodies is :math:`g = h - \delta + u(p)` (h the indenter's height map, delta
the rigid approach, u the normal displacement of both surfaces under the pressure p). Contact
requires :math:`p \ge 0`, :math:`g \ge 0`, :math:`p g = 0`, and either a total force
:math:`\sum p\,dA = F` or a given delta. This is a convex quadratic programme (Kalker); it
is solved by the projected conjugate-gradient method of Polonsky & Keer (Wear 231, 1999),
with one pair of FFT convolutions per iteration.

Speed: the solver first works on a window of the grid that holds the contact, then
checks the whole grid for penetration outside the window and grows the window if needed.
A previous result (the last frame of a press or a slide) warm-starts it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel._validation import (
    check_count,
    check_flag,
    check_instance,
    check_positive,
    check_progress,
    check_shape,
)
from taxel.mechanics._compliance import cover_operator, gap_operator, window_to_grid
from taxel.mechanics._materials import ElasticMaterial
from taxel.mechanics._operators import ConvolutionOperator, as_spacing

__all__ = ["ContactResult", "solve_contact"]

# the windowed solve is worth it only when the window is clearly smaller than the grid
_WINDOW_FRACTION = 0.5
# recompute the displacement from scratch this often, so carried-forward rounding stays small
_REFRESH = 25
# a geometric overlap of area A at approach delta carries about 0.47 * 2 E* sqrt(A/pi) delta;
# exact for a Hertz sphere, an overestimate of delta (a larger, safe window) for flatter shapes
_OVERLAP_FACTOR = 2.0 / (3.0 * np.sqrt(2.0))


@dataclass(frozen=True)
class ContactResult:
    """The solved contact. Arrays are on the full grid.

    Attributes
    ----------
    pressure : numpy.ndarray
        Contact pressure on each cell [Pa], >= 0.
    displacement : numpy.ndarray
        Normal surface displacement of the cover at cell centres [m], positive into the cover.
    contact : numpy.ndarray of bool
        Cells in contact (pressure > 0).
    indentation : float
        Rigid approach delta of the indenter past first touch (height 0) [m].
    normal_force : float
        Total force sum(p) dA [N].
    spacing : tuple of float
        (dy, dx) cell size [m].
    converged : bool
        Whether the relative pressure change fell below the tolerance.
    n_iterations : int
        Conjugate-gradient iterations, over all windows tried.
    residual : float
        Last relative pressure change sum|p - p_prev| / sum(p).
    message : str
        How the solve ended.
    """

    pressure: np.ndarray = field(repr=False)
    displacement: np.ndarray = field(repr=False)
    contact: np.ndarray = field(repr=False)
    indentation: float
    normal_force: float
    spacing: tuple[float, float]
    converged: bool
    n_iterations: int
    residual: float
    message: str

    @property
    def contact_area(self) -> float:
        """Area of the cells in contact [m^2]."""
        return float(np.count_nonzero(self.contact) * self.spacing[0] * self.spacing[1])


@dataclass
class _Loop:
    """The state of one Polonsky-Keer run on one window."""

    pressure: np.ndarray
    approach: float = 0.0
    iterations: int = 0
    residual: float = np.inf
    converged: bool = False


def _polonsky_keer(
    heights: np.ndarray,
    operator: ConvolutionOperator,
    cell_area: float,
    pressure: np.ndarray,
    *,
    force: float | None,
    approach: float | None,
    tolerance: float,
    max_iterations: int,
    progress: Callable[[int], object] | None = None,
) -> _Loop:
    """Polonsky & Keer's projected CG on one grid; force- or approach-controlled.

    `progress`, if given, is called with the iteration's number after each iteration.
    """
    spectrum = operator._spectrum
    loop = _Loop(pressure=pressure.copy())
    p = loop.pressure
    direction = np.zeros_like(p)
    displacement: np.ndarray | None = None
    previous_norm, conjugate = 1.0, False
    # masked whole-window arithmetic: the direction is zero off the contact set, so plain dot
    # products equal the sums over the set, and small windows avoid fancy-indexing costs
    for iteration in range(1, max_iterations + 1):
        if displacement is None or iteration % _REFRESH == 0:
            displacement = operator._convolve(p, spectrum)
        if not p.any():  # lost all contact: restart from the lowest point
            p[np.unravel_index(np.argmin(heights), heights.shape)] = 1.0
            displacement = operator._convolve(p, spectrum)
        gap = displacement + heights
        mask = (p > 0).astype(float)
        count = float(mask.sum())
        if force is not None:
            loop.approach = float(np.vdot(np.where(mask > 0, gap, 0.0), mask)) / count
            gap -= loop.approach
        else:
            gap -= approach
        masked_gap = np.where(mask > 0, gap, 0.0)
        norm = float(np.vdot(masked_gap, masked_gap))
        if conjugate:
            direction *= norm / previous_norm
            direction += masked_gap
            direction *= mask
        else:
            direction = masked_gap.copy()
        previous_norm = max(norm, np.finfo(float).tiny)
        response = operator._convolve(direction, spectrum)
        curvature = float(np.vdot(response, direction))
        if force is not None:  # remove the mean over the set: sum(direction) * mean
            curvature -= float(np.vdot(response, mask)) / count * float(direction.sum())
        step = float(np.vdot(masked_gap, direction)) / curvature if curvature else 0.0
        old = p.copy()
        p -= step * direction
        clipped = bool((p < 0).any())
        np.maximum(p, 0.0, out=p)
        # cells that penetrate without pressure enter the contact set; CG restarts
        entering = (p == 0) & (gap < 0)
        conjugate = not entering.any()
        if not conjugate:
            p[entering] -= step * gap[entering]
        # while the contact set holds still the update is linear: carry u forward, saving
        # one convolution per iteration; otherwise recompute it from p
        displacement = None if clipped or not conjugate else displacement - step * response
        total = float(p.sum())
        if force is not None and total > 0:
            scale = force / (cell_area * total)
            p *= scale
            if displacement is not None:
                displacement *= scale
            total = force / cell_area
        loop.iterations = iteration
        loop.residual = float(np.abs(p - old).sum() / total) if total > 0 else 0.0
        if progress is not None:
            progress(iteration)
        if loop.residual < tolerance:
            loop.converged = True
            break
    if approach is not None:
        loop.approach = approach
    return loop


def _overlap_approach(
    heights: np.ndarray, cell_area: float, force: float, modulus: float
) -> float:
    """A first guess of delta from the geometric overlap (see _OVERLAP_FACTOR)."""
    finite = np.sort(heights[np.isfinite(heights)].ravel())
    lowest = finite[0]
    counts = np.arange(1, finite.size + 1)
    carried = (
        _OVERLAP_FACTOR * 2 * modulus * np.sqrt(counts * cell_area / np.pi) * (finite - lowest)
    )
    index = int(np.searchsorted(carried, force))
    if index >= finite.size:  # even full overlap of the grid is not enough: extrapolate
        return float(
            lowest
            + force / (_OVERLAP_FACTOR * 2 * modulus * np.sqrt(finite.size * cell_area / np.pi))
        )
    return float(finite[index])


def _window_around(mask: np.ndarray, margin: int) -> tuple[slice, slice]:
    """Bounding box of a mask grown by `margin` cells, clipped to the grid."""
    rows = np.flatnonzero(mask.any(axis=1))
    cols = np.flatnonzero(mask.any(axis=0))
    if rows.size == 0:
        return slice(0, mask.shape[0]), slice(0, mask.shape[1])
    return (
        slice(max(rows[0] - margin, 0), min(rows[-1] + margin + 1, mask.shape[0])),
        slice(max(cols[0] - margin, 0), min(cols[-1] + margin + 1, mask.shape[1])),
    )


_ROUNDING = 1e-12  # [m] heights this far below 0 are taken as 0


def _check_heights(heights: Any) -> np.ndarray:
    try:
        array = np.asarray(heights, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError("`heights` must be a numeric 2-D array") from None
    if array.ndim != 2:
        raise ValueError(f"`heights` must be 2-D, got shape {array.shape}")
    bad = np.isnan(array) | (array == -np.inf)
    if bad.any():
        raise ValueError(
            f"`heights` must not contain NaN or -inf, got {int(bad.sum())} such value(s)"
        )
    finite = array[np.isfinite(array)]
    if finite.size == 0:
        raise ValueError("`heights` must have at least one finite value (some material)")
    # a gap cannot be negative: a negative minimum means the zero (first touch) is misplaced;
    # a picometre below zero is rounding (a vertex computed as 1e-19 m below it)
    lowest = float(finite.min())
    if lowest < -_ROUNDING:
        raise ValueError(
            "`heights` must be >= 0 (0 at the indenter's lowest point), "
            f"got a minimum of {lowest:g} m"
        )
    return array


def _unloaded(shape: tuple[int, ...], spacing: tuple[float, float]) -> ContactResult:
    """The contact at zero force or approach: the indenter rests at first touch."""
    return ContactResult(
        pressure=np.zeros(shape),
        displacement=np.zeros(shape),
        contact=np.zeros(shape, dtype=bool),
        indentation=0.0,
        normal_force=0.0,
        spacing=spacing,
        converged=True,
        n_iterations=0,
        residual=0.0,
        message="no load: the indenter rests at first touch, with no contact",
    )


def solve_contact(
    heights: Any,
    spacing: Any,
    material: ElasticMaterial,
    *,
    normal_force: float | None = None,
    indentation: float | None = None,
    indenter_material: ElasticMaterial | None = None,
    thickness: float | None = None,
    periodic: bool = False,
    tolerance: float = 1e-8,
    max_iterations: int = 2000,
    initial: ContactResult | None = None,
    progress: Callable[[int, int], object] | None = None,
) -> ContactResult:
    r"""Solve the frictionless normal contact of an indenter with the sensor's cover.

    Parameters
    ----------
    heights : array_like, shape (rows, cols)
        Gap between the undeformed cover and the indenter at each cell centre [m], 0 at the
        indenter's lowest point, +inf where there is no indenter material.
    spacing : float or tuple of float
        Cell size, or (dy, dx) [m].
    material : ElasticMaterial
        The cover.
    normal_force : float, optional
        Total force F [N], >= 0 (force control). Give this or `indentation`.
    indentation : float, optional
        Rigid approach delta [m], >= 0 (position control). A zero force or approach leaves
        the indenter resting at first touch: no pressure, no contact, the cover undeformed.
    indenter_material : ElasticMaterial, optional
        An elastic indenter (treated as a half-space); None for rigid.
    thickness : float, optional
        Cover thickness over a rigid backing [m]; None for a half-space.
    periodic : bool, default False
        Periodic contact (a repeating texture); the default is an isolated contact.
    tolerance : float, default 1e-8
        Relative change of the pressure field at which iteration stops.
    max_iterations : int, default 2000
        Budget of conjugate-gradient iterations.
    initial : ContactResult, optional
        A previous result on the same grid to start from (the last frame of a sequence).
    progress : callable, optional
        Called as ``progress(done, total)`` after each iteration, with ``total`` the budget
        `max_iterations` and ``done`` the iterations so far (over all windows); a solve
        that ends before its budget (converged, or nothing to solve) calls it last with
        ``done = total``. None (the default) reports nothing.

    Returns
    -------
    ContactResult
        Not converging is reported by ``converged=False``, not raised.

    Raises
    ------
    ValueError
        For bad arguments, naming the parameter, and for a load so large (1e300 N) that the
        pressure overflows a double.

    Notes
    -----
    Polonsky & Keer's projected conjugate gradient; the gap operator is the exact linear
    convolution of Love's cell-integrated kernel (of both bodies when the indenter is elastic,
    i.e. with the effective modulus :math:`1/E^* = \sum (1-\nu_i^2)/E_i`).

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.mechanics import ElasticMaterial, hertz_sphere
    >>> cover = ElasticMaterial(1e6, 0.5)
    >>> x = (np.arange(64) - 31.5) * 0.1e-3
    >>> r2 = x[None, :] ** 2 + x[:, None] ** 2
    >>> result = solve_contact(r2 / (2 * 10e-3), 0.1e-3, cover, normal_force=0.1)
    >>> hertz = hertz_sphere(0.1, 10e-3, cover.plane_strain_modulus)
    >>> result.converged, round(result.indentation / hertz.indentation, 2)
    (True, 1.0)

    With a progress callback (a command line draws a bar with it):

    >>> calls = []
    >>> result = solve_contact(
    ...     r2 / (2 * 10e-3), 0.1e-3, cover, normal_force=0.1, max_iterations=500,
    ...     progress=lambda done, total: calls.append((done, total)),
    ... )
    >>> calls[0], calls[-1], len(calls) == result.n_iterations + 1
    ((1, 500), (500, 500), True)
    """
    heights = _check_heights(heights)
    spacing = as_spacing(spacing)
    if (normal_force is None) == (indentation is None):
        raise ValueError("give exactly one of `normal_force` and `indentation`")
    if normal_force is not None:
        normal_force = check_positive("normal_force", normal_force, allow_zero=True)
    if indentation is not None:
        indentation = check_positive("indentation", indentation, allow_zero=True)
    if thickness is not None:
        thickness = check_positive("thickness", thickness)
    tolerance = check_positive("tolerance", tolerance)
    max_iterations = check_count("max_iterations", max_iterations)
    periodic = check_flag("periodic", periodic)
    check_instance("material", material, ElasticMaterial)
    if indenter_material is not None:
        check_instance("indenter_material", indenter_material, ElasticMaterial)
    if initial is not None:
        check_instance("initial", initial, ContactResult)
        check_shape("initial.pressure", initial.pressure, heights.shape)
    check_progress(progress)

    if not (normal_force or indentation):  # nothing to solve (and F = 0 would divide by 0)
        if progress is not None:
            progress(max_iterations, max_iterations)
        return _unloaded(heights.shape, spacing)
    if initial is not None and not initial.normal_force > 0:
        initial = None  # a contact at rest says nothing of the next one (its F would divide)

    shape = heights.shape
    cell_area = spacing[0] * spacing[1]
    configuration = (spacing, material, indenter_material, thickness)
    full = gap_operator(shape, *configuration, periodic)
    modulus = material.plane_strain_modulus
    if indenter_material is not None:
        modulus = 1.0 / (1.0 / modulus + 1.0 / indenter_material.plane_strain_modulus)

    # the first guess of the approach and the window that should hold the contact
    if initial is not None and normal_force is not None:
        guess = initial.indentation * (normal_force / initial.normal_force) ** (2.0 / 3.0)
    elif normal_force is not None:
        guess = _overlap_approach(heights, cell_area, normal_force, modulus)
    else:
        guess = indentation
    if initial is not None and initial.contact.any():
        # the contact moves little between frames; the full-grid check below catches more
        extent = max(np.ptp(np.nonzero(initial.contact), axis=1))
        window = _window_around(initial.contact, margin=max(3, int(0.1 * extent)))
    else:
        lowest = float(np.min(heights))
        window = _window_around(heights <= lowest + 1.2 * (guess - lowest) + 1e-12, margin=2)

    iterations, attempts = 0, 0
    report: Callable[[int], None] | None = None
    if progress is not None:
        call = progress

        def _report(done: int) -> None:  # done: of this window's run, after `iterations`
            call(iterations + done, max_iterations)

        report = _report

    total_pressure = np.zeros(shape)
    full_response: np.ndarray | None = None
    while True:
        attempts += 1
        window_shape = (window[0].stop - window[0].start, window[1].stop - window[1].start)
        small_enough = window_shape[0] * window_shape[1] <= _WINDOW_FRACTION * heights.size
        if periodic or not small_enough:
            window = (slice(0, shape[0]), slice(0, shape[1]))
            operator = full
        else:
            operator = gap_operator(shape, *configuration, False, window_shape)
        local = heights[window]
        if initial is not None:
            start = initial.pressure[window].copy()
        else:
            start = np.sqrt(np.clip(guess - local, 0.0, None))
        if normal_force is not None and not start.any():
            start[np.unravel_index(np.argmin(local), local.shape)] = 1.0
        if normal_force is not None:
            start *= normal_force / (cell_area * start.sum())
        loop = _polonsky_keer(
            local,
            operator,
            cell_area,
            start,
            force=normal_force,
            approach=indentation,
            tolerance=tolerance,
            max_iterations=max_iterations - iterations,
            progress=report,
        )
        iterations += loop.iterations
        total_pressure[:] = 0.0
        total_pressure[window] = loop.pressure
        whole_grid = operator is full
        if whole_grid or not loop.converged or iterations >= max_iterations:
            break
        # any penetration outside the window means the window was too small
        box = (window[0].start, window[1].start, *window_shape)
        full_response = window_to_grid(shape, *configuration, box).apply(loop.pressure)
        gap = full_response + heights - loop.approach
        scale = max(float(np.max(np.abs(gap[window]))), abs(loop.approach), 1e-300)
        inside = np.zeros(shape, dtype=bool)
        inside[window] = True
        penetrating = (gap < -tolerance * scale) & ~inside
        if not penetrating.any():
            break
        window = _window_around(inside | penetrating | (gap < 0.05 * scale), margin=3)
        full_response = None
        initial = None
        guess = loop.approach

    if progress is not None and iterations < max_iterations:
        progress(max_iterations, max_iterations)
    if not np.isfinite(total_pressure).all():  # a load past what a double holds (1e300 N)
        if normal_force is not None:
            load = f"`normal_force` {normal_force:g} N"
        else:
            load = f"`indentation` {indentation:g} m"
        raise ValueError(f"{load} is too large to solve: the contact's pressure overflows")
    if loop.converged:
        message = f"converged in {iterations} iterations ({attempts} window(s))"
    else:
        message = f"not converged after {iterations} iterations: residual {loop.residual:.2e}"
    if full_response is not None and indenter_material is None:
        displacement = full_response  # the gap operator is the cover's own: already applied
    else:
        displacement = cover_operator(shape, spacing, material, thickness, periodic).apply(
            total_pressure
        )
    return ContactResult(
        pressure=total_pressure,
        displacement=displacement,
        contact=total_pressure > 0,
        indentation=float(loop.approach),
        normal_force=float(total_pressure.sum() * cell_area),
        spacing=spacing,
        converged=loop.converged,
        n_iterations=iterations,
        residual=loop.residual,
        message=message,
    )
