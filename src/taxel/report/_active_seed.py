"""The Ellis seed's active experiments (section 2.2): deformation, and edge radius."""

from __future__ import annotations

import numpy as np

from taxel.active import (
    DEFAULT_EDGE_RADII,
    SimulatedFinger,
    build_edge_radius_table,
    calibrate_pad,
    make_deformation_object,
    measure_deformation,
    measure_edge_radius,
)
from taxel.features import extract
from taxel.frames import make_pose
from taxel.report._context import DemoContext
from taxel.report._figures import figure_png, new_figure
from taxel.report._model import Experiment, Figure, Table, Verdict

__all__ = ["deformation", "edge_radius"]

SENSOR = "vhdta128"
# the seed, section 2.2
SEED_BALL = {"heights_mm": (57.0, 53.0, 47.0), "areas_px": (674, 4681)}
SEED_SPHERE = {"areas_px": (289, 487)}


def _imprints(
    context: DemoContext, name: str, forces: tuple[float, float], *, draw: bool = True
) -> tuple[list[Figure], list[float]]:
    """The object's imprints with their edges, and its true contact area at each force.

    The imprints are drawn as the seed's figures 9 and 10; the true contact areas [m^2] are
    known in simulation and explain the imprints' growth.
    """
    from taxel.viz import plot_features

    sensor = context.sensor(SENSOR)
    item = make_deformation_object(name)
    down = make_pose(np.diag([1.0, -1.0, -1.0]), [0.0, 0.0, item.top + 2e-3])
    finger = SimulatedFinger(sensor, [item], down, rng=context.rng(80))
    figures, areas = [], []
    for force in forces:
        reading = finger.press(normal_force=force)
        assert reading.frame.contact is not None  # a pressed frame carries its contact
        areas.append(reading.frame.contact.contact_area)
        if draw:
            features = extract(reading.frame.raw, sensor)
            figure = plot_features(reading.frame.raw, features, sensor)
            figure.set_size_inches(4.0, 3.5)
            figures.append(
                Figure(f"{name}, {force:g} N, with the extracted edges", figure_png(figure))
            )
        finger.retract()
    return figures, areas


def deformation(context: DemoContext, *, forces: tuple[float, float] = (12.0, 39.0)) -> Experiment:
    """Figures 9 and 10: a racquet ball against a 12.5 mm acrylic sphere, pressed twice."""
    radii = (3e-3, 12e-3, 40e-3) if context.quick else None
    calibration = calibrate_pad(SENSOR, forces=(0.5, *forces), rng=context.seed, radii=radii)
    ball = measure_deformation(
        "racquet ball", sensor=SENSOR, forces=forces, calibration=calibration, rng=context.seed
    )
    sphere = measure_deformation(
        "acrylic sphere",
        sensor=SENSOR,
        forces=forces,
        calibration=calibration,
        rng=context.seed + 1,
    )
    ball_heights = np.array(ball.heights) * 1e3
    sphere_change = abs(sphere.height_change) * 1e3
    ball_areas, sphere_areas = ball.area_pixels[-2:], sphere.area_pixels[-2:]
    ball_growth = ball_areas[1] / ball_areas[0]
    sphere_growth = sphere_areas[1] / sphere_areas[0]
    hertz_growth = (forces[1] / forces[0]) ** (2 / 3)
    ball_figures, ball_true = _imprints(context, "racquet ball", forces)
    _, sphere_true = _imprints(context, "acrylic sphere", forces, draw=False)
    true_growth = (ball_true[1] / ball_true[0], sphere_true[1] / sphere_true[0])
    rows = [
        (
            "racquet ball: height at 0.5 / 12 / 39 N [mm]",
            " / ".join(f"{h:.1f}" for h in ball_heights),
            "57 / 53 / 47",
        ),
        (
            "racquet ball: area at 12 -> 39 N [pixels]",
            f"{ball_areas[0]} -> {ball_areas[1]} (x{ball_areas[1] / ball_areas[0]:.2f})",
            "674 -> 4681 (x6.95)",
        ),
        ("acrylic sphere: change in height [mm]", f"{sphere_change:.2f}", "no change"),
        (
            "acrylic sphere: area at 12 -> 39 N [pixels]",
            f"{sphere_areas[0]} -> {sphere_areas[1]} (x{sphere_areas[1] / sphere_areas[0]:.2f})",
            "289 -> 487 (x1.69)",
        ),
        ("stiffness [N/m]", f"ball {ball.stiffness:.3g}, sphere {sphere.stiffness:.3g}", "-"),
    ]
    return Experiment(
        key="deformation",
        title="Figures 9 and 10: racquet ball against acrylic sphere (deformation)",
        seed_reference="Ellis, section 2.2, figures 9 and 10 and the deformation numbers",
        summary="Each object lies on the table and is pressed slightly (0.5 N), then at "
        f"{forces[0]:g} N and {forces[1]:g} N; the finger's travel along the force, the pad's "
        "own compression (calibrated once on rigid references, read from the imprint's core "
        "area), and the imprints give the object's deformation, stiffness and a "
        f"rigid/deformable verdict. The ball's imprint grows x{ball_growth:.2f} here against "
        f"x6.95 in the seed, and its true contact x{true_growth[0]:.2f}. The ball is hollow "
        "(a 4 mm rubber wall, sealed): its wall bends and its air is compressed, and the "
        "sensor flattens it into a disc whose area grows with the deflection, about as fast "
        f"as the force, where a solid ball's Hertz contact grows as F^(2/3), "
        f"x{hertz_growth:.2f} for these forces. The seed's wide, low-pressure imprint at the "
        "lighter force fell largely below the 1985 sensor's threshold. The sphere's true "
        f"contact grows x{true_growth[1]:.2f} "
        f"(seed x1.69 for its imprint); its imprint here grows x{sphere_growth:.2f} and is "
        "larger than the contact because the 1 mm pad spreads the load and the camera "
        "saturates.",
        figures=tuple(ball_figures),
        tables=(Table("the seed's numbers beside ours", ("quantity", "taxel", "seed"), rows),),
        verdicts=(
            Verdict(
                "the racquet ball is deformable",
                "deformable" if ball.deformable else "rigid",
                "deformable",
                bool(ball.deformable),
            ),
            Verdict(
                "the acrylic sphere is rigid",
                "deformable" if sphere.deformable else "rigid",
                "rigid",
                not sphere.deformable,
            ),
            Verdict(
                "ball height at 12 N within 1 mm of the seed's 53 mm",
                f"{ball_heights[1]:.1f} mm",
                "53 mm",
                abs(ball_heights[1] - 53.0) <= 1.0,
            ),
            Verdict(
                "ball height at 39 N within 2 mm of the seed's 47 mm",
                f"{ball_heights[2]:.1f} mm",
                "47 mm",
                abs(ball_heights[2] - 47.0) <= 2.0,
            ),
            Verdict(
                "the sphere shows no change in height (< 0.1 mm)",
                f"{sphere_change:.2f} mm",
                "no change",
                sphere_change < 0.1,
            ),
        ),
        numbers={"ball": ball.to_dict(), "sphere": sphere.to_dict()},
    )


def edge_radius(context: DemoContext, *, radius: float = 3.2e-3) -> Experiment:
    """Edge radius from a light and a firm press against an empirical table."""
    table_radii = (2.2e-3, 3.3e-3, 4.7e-3) if context.quick else DEFAULT_EDGE_RADII
    table = build_edge_radius_table(
        table_radii, sensor=SENSOR, orientations=2 if context.quick else 4, rng=context.seed
    )
    unknown = (radius,) if context.quick else (radius, 1.8e-3, 5.6e-3, 8.2e-3)
    results = [
        measure_edge_radius(r, table=table, sensor=SENSOR, angle=0.35 + i, rng=context.seed + i)
        for i, r in enumerate(unknown)
    ]
    errors = [abs(result.radius - r) for result, r in zip(results, unknown, strict=True)]
    first = results[0]
    figure = new_figure(4.4, 3.2)
    ax = figure.add_subplot()
    for section in first.sections:
        ax.plot(section.positions * 1e3, section.profile, label=f"{section.normal_force:g} N")
    ax.set_xlabel("distance from the fitted line [mm]")
    ax.set_ylabel("average cross-section [grey level]")
    ax.legend()
    rows = [
        (
            f"{r * 1e3:.1f}",
            f"{res.radius * 1e3:.2f} +/- {res.radius_uncertainty * 1e3:.2f}",
            f"{res.nearest_radius * 1e3:g}",
            f"{abs(res.radius - r) * 1e3:.3f}",
        )
        for res, r in zip(results, unknown, strict=True)
    ]
    nearest = min(table_radii, key=lambda value: abs(value - radius))
    return Experiment(
        key="edge-radius",
        title="Edge radius from the empirical table (12 N and 39 N)",
        seed_reference="Ellis, section 2.2: press light then heavy, average cross-section "
        "normal to the fitted line, nearest entry of an empirical table",
        summary="An empirical table is built by pressing edges of known radius ("
        + ", ".join(f"{r * 1e3:g}" for r in table_radii)
        + " mm) at 12 N and 39 N. An unknown edge is pressed the same way; its edges are "
        "extracted, a line fitted, the cross-section averaged normal to the line, its widths "
        "measured and fitted to an arc; the nearest table entry and an interpolated radius "
        "are returned.",
        figures=(
            Figure(f"average cross-sections of the {radius * 1e3:g} mm edge", figure_png(figure)),
        ),
        tables=(
            Table(
                "edges not in the table",
                ("true radius [mm]", "estimate [mm]", "nearest entry [mm]", "error [mm]"),
                rows,
            ),
        ),
        verdicts=(
            Verdict(
                f"the {radius * 1e3:g} mm edge's nearest entry is {nearest * 1e3:g} mm",
                f"{first.nearest_radius * 1e3:g} mm",
                "- (the seed's table is not published)",
                abs(first.nearest_radius - nearest) < 1e-9,
            ),
            Verdict(
                "interpolated radii within 0.25 mm (taxel's target)",
                f"worst {max(errors) * 1e3:.3f} mm",
                "-",
                max(errors) <= 0.25e-3,
            ),
        ),
        numbers={
            "table_radii_m": table_radii,
            "results": [result.to_dict() for result in results],
        },
    )
