"""Shape recovery: the indenter's surface from surface displacement (optical sensors).

Displacement-sensing sensors (a camera watching the cover deform) read u_z at the taxels.
The pressure is recovered first, regularized and non-negative; the displacement is then
re-synthesized on the load grid from it (a physically based, super-resolved interpolation).
Inside the contact the cover follows the indenter: gap g = h - delta + u = 0, so the
indenter's height above its lowest point is h = delta - u, with delta = max u in contact.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from taxel._validation import check_range
from taxel.mechanics import surface_displacement_operator
from taxel.reconstruction._reconstruct import reconstruct
from taxel.reconstruction._result import ReconstructionResult
from taxel.reconstruction._spec import as_forward_model_spec

__all__ = ["ShapeResult", "recover_shape"]


@dataclass(frozen=True)
class ShapeResult:
    """The recovered indenter surface.

    Attributes
    ----------
    heights : numpy.ndarray
        Indenter height above its lowest point on the load grid [m] inside the contact,
        +inf outside (not touching: the shape there is not observed).
    surface : numpy.ndarray
        Deformed cover surface, -u_z, on the load grid [m] (0 undeformed, < 0 pressed in).
    contact : numpy.ndarray of bool
        Load cells judged in contact.
    indentation : float
        delta, the deepest displacement in contact [m].
    reconstruction : ReconstructionResult
        The pressure solve behind it.
    """

    heights: np.ndarray = field(repr=False)
    surface: np.ndarray = field(repr=False)
    contact: np.ndarray = field(repr=False)
    indentation: float
    reconstruction: ReconstructionResult = field(repr=False)


def recover_shape(
    frame: Any,
    sensor: Any,
    *,
    method: str = "nonneg",
    order: int = 1,
    regularization: float | str = "discrepancy",
    contact_fraction: float = 0.05,
    **options: Any,
) -> ShapeResult:
    """Recover the indenter's surface from a frame of surface displacements.

    Parameters
    ----------
    frame : array_like, shape (rows, cols)
        Normal surface displacement at the taxels [m] (positive into the cover).
    sensor : ForwardModelSpec or str or object with ``forward_model_spec()``
        A sensor whose quantity is "displacement".
    method, order, regularization, **options
        Passed to `reconstruct` (non-negative order-1 Tikhonov by default).
    contact_fraction : float, default 0.05
        Cells whose recovered pressure exceeds this fraction of the peak are in contact.

    Returns
    -------
    ShapeResult

    Examples
    --------
    >>> import numpy as np
    >>> from taxel.mechanics import ElasticMaterial
    >>> from taxel.reconstruction import ForwardModelSpec, forward_operator
    >>> spec = ForwardModelSpec((12, 12), 1e-3, ElasticMaterial(1e6, 0.49), 0.0,
    ...                         thickness=3e-3, quantity="displacement")
    >>> pressure = np.zeros((12, 12)); pressure[5:7, 5:7] = 20e3
    >>> shape = recover_shape(forward_operator(spec).apply(pressure), spec)
    >>> bool(shape.contact[5:7, 5:7].all()), float(shape.heights[5:7, 5:7].min())
    (True, 0.0)
    """
    spec = as_forward_model_spec(sensor)
    if spec.quantity != "displacement":
        raise ValueError(
            f"`sensor` must sense displacement for shape recovery, got {spec.quantity!r}"
        )
    fraction = check_range("contact_fraction", contact_fraction, 0.0, 1.0, low_inclusive=False)
    result = reconstruct(
        frame, spec, method=method, order=order, regularization=regularization, **options
    )
    pressure = np.asarray(result.pressure)
    if pressure.ndim != 2:
        raise ValueError(f"`frame` must be one frame {spec.shape}, got a batch")
    displacement = surface_displacement_operator(
        spec.load_shape, spec.load_pitch, spec.material, thickness=spec.thickness
    ).apply(pressure)
    peak = float(pressure.max())
    contact = pressure > fraction * peak if peak > 0 else np.zeros(pressure.shape, bool)
    indentation = float(displacement[contact].max()) if contact.any() else 0.0
    heights = np.where(contact, indentation - displacement, np.inf)
    return ShapeResult(
        heights=heights,
        surface=-displacement,
        contact=contact,
        indentation=indentation,
        reconstruction=result,
    )
