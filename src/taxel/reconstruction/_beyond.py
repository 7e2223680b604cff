"""Readings beyond the array's edges, from the load that explains the array's own.

The cover spreads a load over a few cover depths: near an edge, part of what it spreads
falls beyond the array, where no taxel feels it, and a centre weighed over the array alone
is pulled inwards (even the exact, noise-free felt pressure, by over half a taxel in 85 of
the features benchmark's 1008 vhdta128 frames, up to 1.3: plates and textures the edge
cuts). With no load beyond the array, the readings there are the forward model's of the
load on the array, and that load is the one that explains the array's readings: the
zero-boundary Tikhonov problem min |A x - b|^2 + lambda^2 |A|^2 |x|^2, solved by
conjugate gradients on its normal equations (scipy), preconditioned by the same problem
with the load mirrored about the edges, which the DCT diagonalizes (exact but near the
edges; `taxel.reconstruction._spectral`; not with a finer load grid), then the forward model of
the array grown by the margin applied to it. Its readings outside the array are smooth
sums of the load near the edge: the small lambda and the early stop of the iterations
keep the deconvolution's noise out of them.
"""

from __future__ import annotations

import functools
from dataclasses import replace
from typing import Any

import numpy as np
from scipy.sparse import linalg

from taxel._validation import as_finite_array, check_integer, check_positive
from taxel.reconstruction._operator import SensorOperator, forward_operator
from taxel.reconstruction._spec import ForwardModelSpec, as_forward_model_spec
from taxel.reconstruction._spectral import Spectrum, build_spectrum

__all__ = ["extend_readings"]

# lambda (relative, see the package's glossary) and the conjugate gradients' stop (relative
# residual of the normal equations). On the 1008 vhdta128 frames of the features benchmark
# the centre of pressure (`taxel.features`) is as good for lambda from 0.01 to 0.1 (p95
# 0.44-0.46 taxel, plain conjugate gradients stopped at 1e-2); preconditioned, 1e-3 takes
# 5-10 iterations there
_REGULARIZATION = 0.03
_TOLERANCE = 1e-3
_MAX_ITERATIONS = 200


@functools.lru_cache(maxsize=8)
def _operators(
    spec: ForwardModelSpec, margin: int
) -> tuple[SensorOperator, SensorOperator, float, Spectrum | None]:
    """The operators and factors `extend_readings` needs for a sensor (built once).

    The array's zero-boundary operator, the grown array's, |A|^2, and the reflecting
    model's DCT factorization (`build_spectrum`), whose inverse is the preconditioner (None
    when the load grid is finer than the taxels).
    """
    # FFT-based: a dense matrix (`forward_operator`'s choice up to 4096 cells) costs more
    # per product from about 32 x 32 cells on
    inner = forward_operator(spec, boundary="zero", representation="fast")
    rows, cols = spec.shape
    grown = replace(spec, shape=(rows + 2 * margin, cols + 2 * margin), dead_taxels=())
    outer = forward_operator(grown, boundary="zero", representation="fast")
    # |A| is its largest singular value, a uniform load's reading far from the edges
    # (a stress reading of a uniform pressure is that pressure: 1)
    norm = float(np.abs(outer.apply(np.ones(grown.load_shape))).max())
    # with a finer load grid the mirrored problem is no sure preconditioner (two reviews,
    # oversampling 2: the same tolerance lands further from the solution; slower on a
    # plate, faster on a spot); plain conjugate gradients there
    spectrum = None
    if spec.oversampling == 1:
        reflecting = forward_operator(spec, boundary="reflect", representation="fast")
        spectrum = build_spectrum(reflecting, 0)
    return inner, outer, norm**2, spectrum


def extend_readings(
    sensor: Any,
    readings: Any,
    margin: int,
    *,
    regularization: float = _REGULARIZATION,
    tolerance: float = _TOLERANCE,
) -> np.ndarray:
    """The readings on the array grown by `margin` taxels on every side.

    Inside, the array's own readings; outside, those of the load on the array that
    explains them (the zero-boundary Tikhonov solution, see the module notes): what taxels
    there would read, were there no load beyond the array. The sensor's dead taxels are
    left out of the fit (their readings are kept inside as given).

    Parameters
    ----------
    sensor : ForwardModelSpec or str or object with ``forward_model_spec()``
        The sensor (see `forward_operator`).
    readings : array_like, shape (rows, cols)
        One frame of readings in the forward model's quantity.
    margin : int
        Taxels added on every side, >= 1.
    regularization : float, default 0.03
        lambda, relative (the penalty is lambda^2 |A|^2 |x|^2), > 0.
    tolerance : float, default 1e-3
        Relative residual of the normal equations at which the iterations stop, > 0.

    Returns
    -------
    numpy.ndarray, shape (rows + 2 margin, cols + 2 margin)

    Examples
    --------
    A plate over the array's left half, read with no noise: the grown array reads what
    the cover spreads beyond the left edge, as the forward model of the grown array does.

    >>> from dataclasses import replace
    >>> import numpy as np
    >>> from taxel.reconstruction import forward_model_preset, forward_operator
    >>> spec = forward_model_preset("resistive16", shape=(12, 12))
    >>> load = np.zeros((12, 12)); load[:, :6] = 10e3
    >>> readings = forward_operator(spec, boundary="zero").apply(load)
    >>> grown = extend_readings(spec, readings, 3)
    >>> grown.shape, bool(np.allclose(grown[3:-3, 3:-3], readings))
    ((18, 18), True)
    >>> truth = forward_operator(replace(spec, shape=(18, 18)), boundary="zero")
    >>> truth = truth.apply(np.pad(load, 3))
    >>> print(np.round(grown[9, :3] / 1e3, 2), np.round(truth[9, :3] / 1e3, 2))
    [0.11 0.26 1.04] [0.11 0.26 1.04]
    """
    spec = as_forward_model_spec(sensor)
    margin = check_integer("margin", margin)
    lam = check_positive("regularization", regularization)
    tolerance = check_positive("tolerance", tolerance)
    readings = as_finite_array("readings", readings, ndim=2)
    if readings.shape != spec.shape:
        raise ValueError(
            f"`readings` must have the sensor's shape {spec.shape}, got {readings.shape}"
        )
    inner, outer, norm2, spectrum = _operators(spec, margin)
    shape = inner.input_shape
    penalty = lam**2 * norm2
    size = shape[0] * shape[1]

    live = spec.live_taxels  # a dead taxel's reading is left out of the fit

    def normal(load: np.ndarray) -> np.ndarray:
        load = load.reshape(shape)
        return (inner.adjoint(live * inner.apply(load)) + penalty * load).ravel()

    preconditioner = None
    if spectrum is not None:
        mirrored = spectrum

        def reflecting(residual: np.ndarray) -> np.ndarray:  # exact but near the edges
            return mirrored.shifted_solve(residual.reshape(shape), 0.0, penalty).ravel()

        preconditioner = linalg.LinearOperator((size, size), matvec=reflecting, dtype=float)
    operator = linalg.LinearOperator((size, size), matvec=normal, dtype=float)
    right = inner.adjoint(live * readings.astype(float)).ravel()
    load, _ = linalg.cg(operator, right, rtol=tolerance, maxiter=_MAX_ITERATIONS, M=preconditioner)
    cells = margin * spec.oversampling
    padded = np.pad(load.reshape(shape), cells)
    grown = outer.apply(padded)
    grown[margin:-margin, margin:-margin] = readings
    return grown
