r"""Shape recovery: the indenter's surface from surface displacement (optical sensors).

Displacement-sensing sensors (a camera watching the cover deform) read u_z at the taxels.
The pressure is recovered first, non-negative; the displacement is then re-synthesized on
the load grid from it (a physically based, super-resolved interpolation). Inside the
contact the cover follows the indenter: the gap g = h - delta + u is 0, so the indenter's
height above its lowest point is h = delta - u.

Two things decide the result, and both are estimated, not assumed:

contact
    The cells whose pressure is significant: non-zero in the non-negative fit restricted
    to a support (method "support", whose support is chosen against the noise, see
    `SupportSolver`), or above kappa times the pressure's own noise std (the other
    methods), with the universal threshold kappa = sqrt(2 ln n) of n load cells, plus
    the linear filter's ringing about a sharp contact (`recover_shape`). A fixed
    fraction of the peak is not a test of anything: a map regularized against the noise
    is blurred, the more so the larger the noise, and a 5 % threshold grows the contact
    with the blur (a 10 mm sphere at 1 N on 32 x 32 taxels of 0.5 mm, noise 1 % of a
    0.5 mm full scale: 63 cells for 41, a flat punch 319 for 118), while it drops true
    rim cells that carry less than 5 % of the peak (an edge's outer row, noise-free).
    A blurred map stays blurred whatever the test, so the default method is "support".
delta
    The rigid approach, the displacement at the indenter's lowest point: the maximum of a
    quadratic fitted to u over the contact cells around its largest value, not the largest
    value itself, which falls short by the apex's height above the nearest cell centre
    (r^2 / 2R: 6.2 um for R = 10 mm with the apex at a corner of 0.5 mm cells) and, with
    noise, is biased upwards by the largest of many noisy values.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel._validation import check_positive, check_range
from taxel.mechanics import surface_displacement_operator
from taxel.reconstruction._frames import one_frame
from taxel.reconstruction._reconstruct import reconstruct, solver_for
from taxel.reconstruction._result import ReconstructionResult
from taxel.reconstruction._spec import ForwardModelSpec, as_forward_model_spec, with_dead_taxels
from taxel.reconstruction._tikhonov import TikhonovSolver

__all__ = ["ShapeResult", "recover_shape"]

# pressures below this fraction of the peak are rounding (an active-set solve leaves 1e-14)
_NUMERICAL_ZERO = float(np.sqrt(np.finfo(float).eps))
# the apex fit: contact cells within this many cells of the largest displacement
_APEX_REACH = 2
# and at least this many of them: twice the quadratic's six coefficients
_APEX_CELLS = 12


@dataclass(frozen=True)
class ShapeResult:
    """The recovered indenter surface.

    Attributes
    ----------
    heights : numpy.ndarray
        Indenter height above its lowest point on the load grid [m] inside the contact,
        +inf outside (not touching: the shape there is not observed). The lowest point is
        that of the fit behind `indentation`, so a cell beside it may be slightly negative.
    surface : numpy.ndarray
        Deformed cover surface, -u_z, on the load grid [m] (0 undeformed, < 0 pressed in).
    contact : numpy.ndarray of bool
        Load cells judged in contact (significant pressure, see `recover_shape`).
    indentation : float
        delta, the displacement at the indenter's lowest point [m]: the peak of a quadratic
        fitted to the displacement in contact around its largest value.
    reconstruction : ReconstructionResult
        The pressure solve behind it.
    threshold : numpy.ndarray or float
        The pressure above which a cell counted as in contact [Pa]: per cell (kappa times
        the pressure's noise std, plus the estimate's ringing), or one value for
        `contact_fraction` and for method "support" (what the solve leaves of a zero: its
        support is already tested against the noise).
    """

    heights: np.ndarray = field(repr=False)
    surface: np.ndarray = field(repr=False)
    contact: np.ndarray = field(repr=False)
    indentation: float
    reconstruction: ReconstructionResult = field(repr=False)
    threshold: np.ndarray | float = field(default=0.0, repr=False)


def recover_shape(
    frame: Any,
    sensor: Any,
    *,
    method: str = "support",
    order: int = 1,
    regularization: float | str = "discrepancy",
    contact_fraction: float | None = None,
    significance: float | None = None,
    **options: Any,
) -> ShapeResult:
    r"""Recover the indenter's surface from a frame of surface displacements.

    Parameters
    ----------
    frame : array_like, shape (rows, cols)
        Normal surface displacement at the taxels [m] (positive into the cover); NaN only
        at dead taxels.
    sensor : ForwardModelSpec or str or object with ``forward_model_spec()``
        A sensor whose quantity is "displacement".
    method : str, default "support"
        The pressure solve (see `reconstruct`). "support" fits the non-negative pressure on
        a support chosen against the noise, whose cells are the contact; "nonneg" (the
        default before) blurs the contact's edge by the regularization's width.
    order, regularization, **options
        Passed to `reconstruct` (for "support", the order of its first stage).
    contact_fraction : float, optional
        Judge cells in contact when their pressure exceeds this fraction of the peak, in
        (0, 1], instead of by significance (the rule before; it over-grows the contact
        with the noise, see the module docstring).
    significance : float, optional
        kappa: a cell is in contact when its pressure exceeds kappa times its noise std
        (plus the estimate's ringing, see Notes); default sqrt(2 ln n) for n load cells.
        Not used by method "support" (its support is found with the same threshold) nor
        with `contact_fraction`.

    Returns
    -------
    ShapeResult

    Raises
    ------
    ValueError
        When `sensor` does not sense displacement, `frame` is not one finite frame of the
        sensor's shape, or an option is out of range; the message names it.

    Notes
    -----
    In contact the gap :math:`g = h - \delta + u` vanishes (the contact problem solved by
    `taxel.mechanics.solve_contact`), so :math:`h = \delta - u` there; outside it only
    :math:`h > \delta - u` is known. The contact is the support of the pressure, decided
    by a significance test against the reading noise propagated to each cell,
    :math:`p_i > \kappa \sigma_i + b` with
    :math:`\sigma_i = \sigma \sqrt{\sum_k (f_k v_{ik} / s_k)^2}` (singular values s_k,
    vectors v_k, filter factors f_k of the linear filter of the same order and lambda;
    the universal threshold of D. L. Donoho and I. M. Johnstone, Biometrika 81, 1994).
    b is the filter's ringing about a sharp contact, which no noise level measures (a
    clean frame has none): how far that linear estimate dips below
    :math:`-\sqrt{2 \ln n}\,\sigma_i`, as far as it rises outside the contact. Values
    below an iterative solve's last relative change times the peak are its leftovers,
    not load. For method "support" the contact is the cells its restricted
    non-negative fit leaves loaded.

    delta is the maximum of a least-squares quadratic in (x, y) over the contact cells
    within two cells of the largest u (at least 12 of them, else the largest u): exact for
    a sphere, whose Hertzian u is a paraboloid in contact, and for a punch. With noise it
    carries the noise of the apex: at 1 % of full scale (sigma = 5 um) it is off by
    -2 +- 2 um for the sphere and +3 +- 1.5 um for the punch of the tests, the larger
    part of the height error.

    What a coarse array cannot give. On `reflective8x8` (3 mm pitch, its own load grid)
    the 12.5 mm sphere pressed centrally with 0.2-0.5 N touches the 4 middle cells, each
    2.1 mm from its apex: the contact is found (4 cells, at 1 % noise too), but the cells'
    common height above the apex, 0.36 mm, is not in the readings, so their heights read
    0 and delta is short by as much. On a 0.75 mm load grid (oversampling 4) the sphere
    at 0.2 N touches 14 load cells, more detail than 64 readings hold: the contact's IoU
    is 0.4-0.65 at 0.5-1 % noise and a paraboloid through the heights gives 8-28 mm for
    the 6.25 mm radius.

    Examples
    --------
    A 10 mm sphere pressed with 1 N into a 3 mm cover, read on a 32 x 32 array:

    >>> import numpy as np
    >>> from taxel.mechanics import ElasticMaterial, make_indenter, solve_contact
    >>> from taxel.reconstruction import ForwardModelSpec, forward_operator
    >>> spec = ForwardModelSpec((32, 32), 0.5e-3, ElasticMaterial(1e6, 0.49), 0.0,
    ...                         thickness=3e-3, quantity="displacement")
    >>> heights = make_indenter("sphere", radius=10e-3).on_grid((32, 32), 0.5e-3)
    >>> truth = solve_contact(heights, 0.5e-3, spec.material, thickness=3e-3,
    ...                       normal_force=1.0)
    >>> shape = recover_shape(forward_operator(spec).apply(truth.pressure), spec)
    >>> int(shape.contact.sum()), int(truth.contact.sum())
    (44, 44)
    >>> inside = truth.contact
    >>> error = np.abs(shape.heights[inside] - heights[inside]).max()
    >>> print(f"delta {shape.indentation * 1e6:.1f} um (true {truth.indentation * 1e6:.1f}),"
    ...       f" height error < {error * 1e6:.1f} um")
    delta 201.8 um (true 201.7), height error < 0.1 um
    """
    spec = as_forward_model_spec(sensor)
    if spec.quantity != "displacement":
        raise ValueError(
            f"`sensor` must sense displacement for shape recovery, got {spec.quantity!r}"
        )
    fraction = None
    if contact_fraction is not None:
        fraction = check_range("contact_fraction", contact_fraction, 0.0, 1.0, low_inclusive=False)
    kappa = None if significance is None else check_positive("significance", significance)
    # one frame, finite at the live taxels: checked before any solve
    one_frame(frame, with_dead_taxels(spec, options.get("dead_taxels")), "shape recovery")
    result = reconstruct(
        frame, spec, method=method, order=order, regularization=regularization, **options
    )
    pressure = np.asarray(result.pressure)
    displacement = surface_displacement_operator(
        spec.load_shape, spec.load_pitch, spec.material, thickness=spec.thickness
    ).apply(pressure)
    peak = float(pressure.max())
    # what the solve leaves of a zero: rounding, or an iterative solve's last relative
    # change (total variation's ADMM leaves ~1e-5 of the peak over a clean frame's array)
    numerical = max(_NUMERICAL_ZERO, float(result.residual)) * peak
    threshold: np.ndarray | float
    if peak <= 0:
        threshold = np.inf
    elif fraction is not None:
        threshold = fraction * peak
    elif result.support is not None:
        threshold = numerical
    else:
        threshold = np.maximum(
            _significance_threshold(frame, spec, result, kappa, options), numerical
        )
    contact = pressure > threshold
    indentation = _apex(displacement, contact) if contact.any() else 0.0
    heights = np.where(contact, indentation - displacement, np.inf)
    return ShapeResult(
        heights=heights,
        surface=-displacement,
        contact=contact,
        indentation=indentation,
        reconstruction=result,
        threshold=threshold,
    )


def _significance_threshold(
    frame: Any,
    spec: ForwardModelSpec,
    result: ReconstructionResult,
    kappa: float | None,
    options: dict[str, Any],
) -> np.ndarray:
    """The contact threshold [Pa]: kappa times each cell's noise std, plus the ringing.

    The std is that of the linear estimate behind `result`: the Tikhonov (or TSVD) filter
    of the result's order at its lambda; for total variation, whose mu has no linear
    counterpart, the order-1 filter at the lambda the discrepancy principle gives for the
    same noise (the same data fit). The ringing is that estimate's deepest dip below
    -sqrt(2 ln n) std, which its noise alone almost never reaches.
    """
    layout = {key: options[key] for key in ("boundary", "representation") if key in options}
    truncated = result.method == "tsvd"
    order = 1 if result.method == "tv" else result.order
    linear = solver_for(
        spec,
        method="tsvd" if truncated else "tikhonov",
        order=order,
        dead_taxels=options.get("dead_taxels"),
        **layout,
    )
    assert isinstance(linear, TikhonovSolver)
    noise = result.noise_level
    if noise is None:  # a given lambda, GCV or the L-curve: the noise is still needed
        noise = linear.estimate_noise_level(frame)
    noise = float(np.asarray(noise))
    lam = float(np.asarray(result.regularization))
    if result.method == "tv":
        lam = float(linear.solve(frame, noise_level=max(noise, 1e-300)).regularization)
    factors = linear.filter_factors(np.atleast_1d(lam))[0]
    std = noise * np.sqrt(linear.spectrum.cell_variance(factors))
    universal = float(np.sqrt(2 * np.log(spec.load_shape[0] * spec.load_shape[1])))
    # ... plus the filter's own ringing about a sharp contact, which the noise does not
    # measure (a clean frame has none): how far the linear estimate dips below what its
    # noise explains, as far as it rises outside the contact
    estimate = result.pressure
    if result.method not in ("tikhonov", "tsvd"):  # (a constrained fit shows no dips)
        estimate = linear.solve(frame, regularization=lam).pressure
    ringing = max(float(np.max(-estimate - universal * std)), 0.0)
    return np.asarray((universal if kappa is None else kappa) * std + ringing)


def _apex(displacement: np.ndarray, contact: np.ndarray) -> float:
    """The peak of a quadratic fitted to u over the contact cells near its largest value.

    The contact cells within `_APEX_REACH` cells of the largest u in contact; the peak is
    sought within their bounding box (the fit says nothing further out). Fewer than
    `_APEX_CELLS` such cells, or cells on one line: the largest u itself.
    """
    inside = np.where(contact, displacement, -np.inf)
    row, col = np.unravel_index(int(np.argmax(inside)), inside.shape)
    largest = float(inside[row, col])
    top, left = max(int(row) - _APEX_REACH, 0), max(int(col) - _APEX_REACH, 0)
    rows = slice(top, int(row) + _APEX_REACH + 1)
    cols = slice(left, int(col) + _APEX_REACH + 1)
    near = contact[rows, cols]
    y, x = np.nonzero(near)
    y = y + (top - int(row))
    x = x + (left - int(col))
    if y.size < _APEX_CELLS:
        return largest
    design = np.column_stack([np.ones(y.size), x, y, x * x, x * y, y * y])
    coefficients, _, rank, _ = np.linalg.lstsq(design, displacement[rows, cols][near], rcond=None)
    if rank < design.shape[1]:
        return largest
    # the quadratic's maximum over the box of the cells fitted: at its stationary point
    # when that is a maximum inside the box, else on a fine sampling of the box
    c0, cx, cy, cxx, cxy, cyy = coefficients

    def quadratic(px: Any, py: Any) -> Any:
        return c0 + cx * px + cy * py + cxx * px * px + cxy * px * py + cyy * py * py

    gx, gy = np.meshgrid(
        np.linspace(x.min(), x.max(), 8 * int(np.ptp(x)) + 1),
        np.linspace(y.min(), y.max(), 8 * int(np.ptp(y)) + 1),
    )
    best = float(quadratic(gx, gy).max())
    hessian = np.array([[2 * cxx, cxy], [cxy, 2 * cyy]])
    if np.all(np.linalg.eigvalsh(hessian) < 0):
        sx, sy = np.linalg.solve(hessian, [-cx, -cy])
        if x.min() <= sx <= x.max() and y.min() <= sy <= y.max():
            best = max(best, float(quadratic(sx, sy)))
    return best
