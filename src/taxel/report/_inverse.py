"""The chapter's inverse problem: the naive inverse against the regularized one (25.2)."""

from __future__ import annotations

import numpy as np

from taxel.mechanics import ElasticMaterial, make_indenter, plane_strain_strain_matrix
from taxel.reconstruction import naive_inverse, reconstruct
from taxel.report._context import DemoContext
from taxel.report._figures import figure_png, new_figure
from taxel.report._model import Experiment, Figure, Table, Verdict

__all__ = ["inverse_problem"]

# ../shared/reference/mechanics.md: condition number of the sampled operator against pitch
REFERENCE_CONDITION = {1.0: "~2-4", 0.5: "~50", 0.25: "~1e4", 0.1: "~1e12"}


def _condition_numbers() -> dict[float, float]:
    """Condition of the chapter's T (eq. 25.5) for 64 taxels at pitch/depth ratios."""
    cover, depth = ElasticMaterial(1e6, 0.3), 1e-3
    numbers = {}
    for ratio in REFERENCE_CONDITION:
        pitch = ratio * depth
        x = np.arange(64) * pitch
        matrix = plane_strain_strain_matrix(x, x, pitch, depth, cover)
        numbers[ratio] = float(np.linalg.cond(matrix))
    return numbers


def inverse_problem(
    context: DemoContext, *, noise_levels: tuple[float, ...] = (0.001, 0.01, 0.05)
) -> Experiment:
    """Naive against regularized reconstruction at rising noise, and the L-curve."""
    sensor = context.sensor("vhdta128")
    frame = sensor.press(make_indenter("sphere", radius=6.25e-3), normal_force=12.0)
    assert frame.contact is not None and frame.fields is not None  # as a pressed frame does
    truth = frame.contact.pressure
    clean = -frame.fields.stress  # what a calibrated taxel reads: the pressure at its depth
    rng = context.rng(60)
    rows, naive_errors, regular_errors, kept = [], [], [], {}
    for level in noise_levels:
        reading = clean + rng.normal(0.0, level * sensor.full_scale, clean.shape)
        naive = naive_inverse(reading, sensor)
        regular = reconstruct(reading, sensor, order=1, regularization="gcv")
        naive_error = float(np.linalg.norm(naive.pressure - truth) / np.linalg.norm(truth))
        regular_error = float(np.linalg.norm(regular.pressure - truth) / np.linalg.norm(truth))
        force = regular.normal_force / frame.contact.normal_force
        naive_errors.append(naive_error)
        regular_errors.append(regular_error)
        kept[level] = (reading, naive, regular)
        rows.append(
            (
                f"{level:.1%}",
                f"{naive_error:.3g}",
                f"{regular_error:.3f}",
                f"{float(regular.regularization):.3g}",
                f"{force:.3f}",
            )
        )
    level = 0.01 if 0.01 in kept else noise_levels[len(noise_levels) // 2]
    reading, naive, regular = kept[level]
    figure = new_figure(8.8, 2.6)
    panels = figure.subplots(1, 4)
    scale = truth.max() / 1e3
    for ax, (image, title) in zip(
        panels[:3],
        (
            (truth / 1e3, "true pressure [kPa]"),
            (naive.pressure / 1e3, f"naive inverse ({level:.0%} noise)"),
            (regular.pressure / 1e3, f"regularized, GCV ({level:.0%} noise)"),
        ),
        strict=True,
    ):
        shown = ax.imshow(image, cmap="magma", vmin=0, vmax=scale)
        ax.set_title(title, fontsize=8)
        ax.set_xticks([])
        ax.set_yticks([])
    figure.colorbar(shown, ax=panels[2], shrink=0.8)
    curve = regular.curve
    assert curve is not None  # a lambda chosen by GCV for one frame keeps its curve
    ax = panels[3]
    ax.loglog(curve.residual_norm, curve.solution_norm, lw=1)
    chosen = np.argmin(np.abs(curve.regularization - regular.regularization))
    ax.loglog(curve.residual_norm[chosen], curve.solution_norm[chosen], "o", label="GCV choice")
    ax.set_xlabel("residual norm", fontsize=8)
    ax.set_ylabel("solution norm", fontsize=8)
    ax.set_title("L-curve", fontsize=8)
    ax.legend(fontsize=7)
    conditions = _condition_numbers()
    condition_rows = [
        (f"{ratio:g} d", f"{value:.3g}", REFERENCE_CONDITION[ratio])
        for ratio, value in conditions.items()
    ]
    monotone = all(
        a < b
        for a, b in zip(list(conditions.values()), list(conditions.values())[1:], strict=False)
    )
    return Experiment(
        key="inverse",
        title="The inverse problem: naive against regularized reconstruction",
        seed_reference="Saad et al., section 25.2: the inverse problem is ill-posed and "
        "needs regularization; taxels spaced at the depth d or closer",
        summary="A 12.5 mm sphere pressed with 12 N on the simulated VHDTA (taxels 0.26 mm "
        "apart, 1 mm under the surface). The calibrated readings (pressure felt at the "
        "depth of the taxels) get Gaussian noise of the stated fraction of full scale and "
        "are inverted without regularization and with first-order Tikhonov, its parameter "
        "chosen by generalized cross-validation.",
        figures=(
            Figure(
                f"truth, naive and regularized at {level:.0%} noise, and the L-curve",
                figure_png(figure),
            ),
        ),
        tables=(
            Table(
                "relative L2 error of the pressure",
                (
                    "noise (of full scale)",
                    "naive inverse",
                    "regularized (GCV)",
                    "lambda",
                    "force recovered / true",
                ),
                rows,
            ),
            Table(
                "condition number of the chapter's T (eq. 25.5), 64 taxels",
                ("taxel pitch", "taxel", "reference"),
                condition_rows,
            ),
        ),
        verdicts=(
            Verdict(
                "regularization beats the naive inverse at every noise level",
                ", ".join(
                    f"{r:.2f} < {n:.3g}" for r, n in zip(regular_errors, naive_errors, strict=True)
                ),
                "ill-posed: needs regularization",
                all(r < n for r, n in zip(regular_errors, naive_errors, strict=True)),
            ),
            Verdict(
                "the naive inverse blows up at 1 % noise (error > 1)",
                f"{naive_errors[list(kept).index(level)]:.3g}",
                "susceptible to noise",
                naive_errors[list(kept).index(level)] > 1.0,
            ),
            Verdict(
                "T becomes worse conditioned as taxels get closer than d",
                " < ".join(f"{v:.2g}" for v in conditions.values()),
                "aliasing below d",
                monotone,
            ),
        ),
        numbers={
            "noise_levels": noise_levels,
            "naive_error": naive_errors,
            "regularized_error": regular_errors,
            "condition_numbers": {str(k): v for k, v in conditions.items()},
        },
    )
