r"""In-plane stresses at depth in a half-space, for photoelastic sensing (Figure 25.12).

Light crossing a photoelastic layer along z sees the secondary principal stress difference
in the x-y plane, :math:`\sqrt{(\sigma_{xx}-\sigma_{yy})^2 + 4\tau_{xy}^2}`. Under a normal
surface pressure :math:`\hat p(\mathbf{k})` a half-space carries (tension positive)

.. math:: \sigma_{xx} - \sigma_{yy} = -\hat p\,\frac{k_x^2 - k_y^2}{k^2}(1 - kz - 2\nu)e^{-kz},
          \qquad \tau_{xy} = -\hat p\,\frac{k_x k_y}{k^2}(1 - kz - 2\nu)e^{-kz}

(derived from Boussinesq's solution; checked against its sigma_r - sigma_theta in the tests).
These decay like 1/r^2 away from a load, so the field is computed on a zero-padded grid.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import fft

from taxel._validation import as_finite_array, check_count, check_instance, check_positive
from taxel.mechanics._materials import ElasticMaterial
from taxel.mechanics._operators import as_spacing

__all__ = ["inplane_stress_difference"]


def inplane_stress_difference(
    pressure: Any,
    spacing: Any,
    depth: float,
    material: ElasticMaterial,
    *,
    padding: int = 2,
) -> np.ndarray:
    r"""Secondary principal stress difference in the x-y plane at depth d [Pa].

    Parameters
    ----------
    pressure : array_like, shape (rows, cols)
        Normal surface pressure on each cell [Pa].
    spacing : float or tuple of float
        Cell size, or (dy, dx) [m].
    depth : float
        Depth z [m], > 0.
    material : ElasticMaterial
        The half-space (only nu matters).
    padding : int, default 2
        The grid is zero-padded to `padding` times its size before the FFT.

    Returns
    -------
    numpy.ndarray
        :math:`\sqrt{(\sigma_{xx}-\sigma_{yy})^2 + 4\tau_{xy}^2}` [Pa], >= 0.

    Examples
    --------
    >>> load = np.zeros((32, 32))
    >>> load[12:20, 12:20] = 1e4
    >>> field = inplane_stress_difference(load, 0.25e-3, 1e-3, ElasticMaterial(1e6, 0.5))
    >>> bool(field[16, 16] < field[16, 11])  # small under the centre, large at the rim
    True
    """
    pressure = as_finite_array("pressure", pressure, ndim=2)
    dy, dx = as_spacing(spacing)
    if pressure.size == 0:
        raise ValueError(f"`pressure` must have at least one cell, got shape {pressure.shape}")
    depth = check_positive("depth", depth)
    check_instance("material", material, ElasticMaterial)
    padding = check_count("padding", padding)
    rows, cols = pressure.shape
    shape = (fft.next_fast_len(padding * rows), fft.next_fast_len(padding * cols, True))
    ky = 2 * np.pi * fft.fftfreq(shape[0], dy)[:, None]
    kx = 2 * np.pi * fft.rfftfreq(shape[1], dx)[None, :]
    k = np.hypot(kx, ky)
    safe = np.where(k > 0, k, 1.0)
    # a piecewise-constant load on cells: include the cell's box factor
    box = np.sinc(ky * dy / (2 * np.pi)) * np.sinc(kx * dx / (2 * np.pi))
    common = -(1 - k * depth - 2 * material.poisson_ratio) * np.exp(-k * depth) * box
    common = np.where(k > 0, common / safe**2, 0.0)
    transformed = fft.rfft2(pressure, s=shape)
    difference = fft.irfft2(transformed * common * (kx**2 - ky**2), s=shape)[:rows, :cols]
    shear = fft.irfft2(transformed * common * (kx * ky), s=shape)[:rows, :cols]
    return np.sqrt(difference**2 + 4 * shear**2)
