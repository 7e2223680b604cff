"""The inverse problem in one figure: truth, naive inverse, regularized inverse, L-curve, GCV."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from taxel.viz._saving import save_figure

__all__ = ["plot_reconstruction"]


def plot_reconstruction(
    path: str | Path,
    *,
    sensor: Any = None,
    noise_fraction: float = 0.001,
    order: int = 1,
    rng: int | np.random.Generator = 0,
) -> Path:
    """Write a figure comparing the naive and the regularized inverse of one frame.

    Panels: the true pressure (a sphere and a flat punch), the naive inverse
    (lambda = 0), the Tikhonov inverse with lambda chosen by GCV, the L-curve with the GCV
    and L-curve choices marked, and the GCV function.

    Parameters
    ----------
    path : str or pathlib.Path
        Output file, in the format its suffix names (.png, .svg, .pdf, ...; PNG for a
        suffix matplotlib does not know).
    sensor : ForwardModelSpec or str, optional
        Default: the vhdta128 geometry (d = 3.9 taxel pitches) on a 40 x 40 patch.
    noise_fraction : float, default 0.001
        Noise std as a fraction of the sensor's full scale (or of the peak reading); >= 0.
    order : {0, 1, 2}, default 1
        Tikhonov order of the regularized inverse.
    rng : int or numpy.random.Generator, default 0
        Seed of the noise.

    Returns
    -------
    pathlib.Path
        The PNG written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     written = plot_reconstruction(pathlib.Path(folder) / "inverse.png")
    ...     written.stat().st_size > 10_000
    True
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure  # no pyplot: no GUI backend, no global state

    from taxel._validation import as_rng, check_positive
    from taxel.reconstruction import (
        TikhonovSolver,
        as_forward_model_spec,
        forward_model_preset,
        naive_inverse,
    )

    if not isinstance(path, str | os.PathLike):
        raise TypeError(f"`path` must be a file path, got {path!r}")
    noise_fraction = check_positive("noise_fraction", noise_fraction, allow_zero=True)
    generator = as_rng("rng", rng, allow_none=False)  # the figure shows noise
    assert generator is not None
    spec = (
        forward_model_preset("vhdta128", shape=(40, 40))
        if sensor is None
        else as_forward_model_spec(sensor)
    )
    truth = _scene(spec)
    solver = TikhonovSolver(spec, order=order)
    clean = solver.operator.apply(truth)
    scale = spec.full_scale if spec.full_scale is not None else float(np.abs(clean).max())
    frame = clean + generator.normal(0.0, noise_fraction * scale, clean.shape)
    naive = naive_inverse(frame, spec)
    regularized = solver.solve(frame, regularization="gcv")
    corner = solver.solve(frame, regularization="lcurve")
    curve = regularized.curve
    assert curve is not None  # a lambda chosen by GCV for one frame keeps its curve

    figure = Figure(figsize=(13, 7.5), layout="constrained")
    FigureCanvasAgg(figure)
    grid = figure.subplots(2, 3)
    limit = float(truth.max())
    extent = np.array([-0.5, spec.load_shape[1] - 0.5, spec.load_shape[0] - 0.5, -0.5])
    extent = extent * spec.load_pitch * 1e3
    panels = [
        (truth, "true pressure", limit),
        (naive.pressure, f"naive inverse (noise {noise_fraction:.1%} of full scale)", None),
        (
            regularized.pressure,
            f"Tikhonov order {order}, GCV lambda = " f"{regularized.regularization:.3g}",
            limit,
        ),
    ]
    for axis, (field, title, top) in zip(grid[0], panels, strict=True):
        bound = top if top is not None else float(np.abs(field).max())
        image = axis.imshow(
            field / 1e3,
            cmap="viridis" if top else "RdBu_r",
            vmin=0 if top else -bound / 1e3,
            vmax=bound / 1e3,
            extent=extent,
        )
        error = np.linalg.norm(field - truth) / np.linalg.norm(truth)
        axis.set_title(f"{title}\nrelative L2 error {error:.2g}", fontsize=9)
        axis.set_xlabel("x [mm]")
        figure.colorbar(image, ax=axis, label="pressure [kPa]", shrink=0.8)
    grid[0, 0].set_ylabel("y [mm]")

    lcurve, gcv_axis, profile = grid[1]
    lcurve.loglog(curve.residual_norm, curve.solution_norm, color="0.3")
    for result, label, marker in ((regularized, "GCV", "o"), (corner, "L-curve corner", "s")):
        lcurve.loglog(result.residual_norm, result.solution_norm, marker, label=label)
    reading_unit = {"stress": "Pa", "strain": "strain", "displacement": "m"}[spec.quantity]
    lcurve.set_xlabel(f"residual norm |A x - b| [{reading_unit}]")
    # L: identity, or differences between neighbouring load cells: pressures all the same
    lcurve.set_ylabel(f"solution seminorm |L x| [Pa] (order {order})")
    lcurve.set_title("L-curve", fontsize=9)
    lcurve.legend(fontsize=8)
    gcv_axis.loglog(curve.regularization, curve.gcv, color="0.3")
    gcv_axis.axvline(regularized.regularization, color="C0", linestyle="--", label="GCV minimum")
    gcv_axis.axvline(corner.regularization, color="C1", linestyle=":", label="L-curve corner")
    gcv_axis.set_xlabel("lambda (relative: 1 weighs the penalty like the data's largest term)")
    gcv_axis.set_ylabel("GCV function")
    gcv_axis.set_title("generalized cross-validation", fontsize=9)
    gcv_axis.legend(fontsize=8)
    row = spec.load_shape[0] // 2
    x = (np.arange(spec.load_shape[1]) - (spec.load_shape[1] - 1) / 2) * spec.load_pitch * 1e3
    profile.plot(x, truth[row] / 1e3, "k", label="truth")
    profile.plot(x, regularized.pressure[row] / 1e3, "C0", label="GCV")
    profile.plot(x, corner.pressure[row] / 1e3, "C1", label="L-curve")
    profile.set_ylim(-0.3 * limit / 1e3, 1.3 * limit / 1e3)
    profile.set_xlabel("x [mm]")
    profile.set_ylabel("pressure [kPa]")
    profile.set_title("profile through the middle row", fontsize=9)
    profile.legend(fontsize=8)
    figure.suptitle(
        f"zeta = T F is ill-posed: taxels at depth d = {spec.depth * 1e3:g} mm, "
        f"pitch {spec.taxel_pitch * 1e3:.3g} mm (d / pitch = {spec.depth / spec.taxel_pitch:.1f})"
    )
    path = Path(path)
    save_figure(figure, path)
    return path


def _scene(spec) -> np.ndarray:
    """A Hertz-like dome and a flat disc on the load grid [Pa], scaled to 40 % of full scale."""
    rows, cols = spec.load_shape
    y, x = np.mgrid[:rows, :cols] * spec.load_pitch
    width = cols * spec.load_pitch
    peak = 0.4 * (spec.full_scale or 100e3)
    dome_r = np.hypot(x - 0.3 * width, y - 0.5 * width) / (0.12 * width)
    disc_r = np.hypot(x - 0.7 * width, y - 0.5 * width) / (0.12 * width)
    dome = peak * np.sqrt(np.clip(1 - dome_r**2, 0, None))
    disc = np.where(disc_r < 1, 0.6 * peak, 0.0)
    return dome + disc
