"""The Ellis seed's passive experiments (section 2.1, figures 1-8) on the simulated VHDTA."""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel.features import extract
from taxel.mechanics import ElasticMaterial, make_indenter
from taxel.report._context import DemoContext
from taxel.report._cross_section import line_cross_section
from taxel.report._figures import figure_png, new_figure
from taxel.report._model import Experiment, Figure, Table, Verdict

__all__ = ["can_top", "edge_at_two_forces", "pen_tip", "texture_table", "washer"]

SENSOR = "vhdta128"
# the seed's texture table (section 2.1): maxima count and average height over 128 x 128
SEED_TEXTURE = {"foam": (15, 11.27), "screen": (13, 15.62), "rasp": (31, 15.19)}
# stiff conductive foam is still a foam: pressed as an elastic body, not a rigid one
FOAM = ElasticMaterial(0.3e6, 0.3)


def _feature_figure(image: np.ndarray, features, sensor, title: str) -> Figure:
    from taxel.viz import plot_features

    figure = plot_features(image, features, sensor)
    figure.set_size_inches(4.2, 3.6)
    return Figure(title, figure_png(figure))


def _raw_figure(image: np.ndarray, title: str) -> Figure:
    figure = new_figure(3.4, 3.2)
    ax = figure.add_subplot()
    ax.imshow(image, cmap="gray", vmin=0, vmax=255, interpolation="nearest")
    ax.set_xticks([])
    ax.set_yticks([])
    return Figure(title, figure_png(figure))


def pen_tip(context: DemoContext, *, indenter: str = "pen", force: float = 2.0) -> Experiment:
    """Figure 1: a ball-point pen tip pressed on the sensor is a point contact."""
    sensor = context.sensor(SENSOR)
    frame = sensor.press(make_indenter(indenter), normal_force=force, rng=context.rng(1))
    features = extract(frame.raw, sensor)
    area_mm2 = features.contact.area_m2 * 1e6 if features.contact.present else 0.0
    return Experiment(
        key="pen",
        title="Figure 1: ball-point pen tip (point contact)",
        seed_reference="Ellis, section 2.1, figure 1",
        summary=f"A pen tip (0.35 mm ball) pressed with {force:g} N on the simulated VHDTA; "
        "the contact is a point because it is compact and, at half its peak, no larger "
        "than 2.5 mm once the cover's blur is allowed for (the seed: few edges, both fits "
        "poor); the figure draws the seed's Canny edges of the image.",
        figures=(
            _raw_figure(frame.raw, "tactile image (8-bit camera frame)"),
            _feature_figure(frame.raw, features, sensor, "edges and fits"),
        ),
        verdicts=(
            Verdict(
                "contact type is point",
                features.contact_type,
                "point",
                features.contact_type == "point",
            ),
        ),
        numbers={
            "force_n": force,
            "contact_type": features.contact_type,
            "contact_area_mm2": area_mm2,
            "centroid_m": features.contact.centroid_m,
        },
    )


def _compare(firm: str, light: str, greater: bool) -> str:
    """The firm press's value against the light press's, with the true comparison sign."""
    return f"{firm} {'>' if greater else '<='} {light}"


def _edge_measures(image: np.ndarray, features, pitch: float) -> dict[str, Any]:
    """Width [m], mean intensity and cross-section area of a line contact."""
    background = float(np.percentile(image, 5))
    contact = image > background + 6  # a few camera noise levels above the background
    line = features.shape.line
    distance, profile = line_cross_section(
        image.astype(float) - background, line, pitch, half_width=4e-3
    )
    width = float(contact.sum() * pitch**2 / max(features.contact.major_axis_m, pitch))
    step = distance[1] - distance[0]
    return {
        "width_m": width,
        "mean_intensity": float(image[contact].mean()),
        "cross_section_area": float(np.nansum(profile) * step),
        "distance_m": distance,
        "profile": profile,
    }


def edge_at_two_forces(
    context: DemoContext, *, radius: float = 3.2e-3, forces: tuple[float, float] = (12.0, 39.0)
) -> Experiment:
    """Figures 2 and 3: a 3.2 mm edge at 12 N and 39 N; width, intensity and cross-section."""
    sensor = context.sensor(SENSOR)
    pitch = sensor.taxel_pitch[1]
    results, figures, types = [], [], []
    for index, force in enumerate(forces):
        frame = sensor.press(
            make_indenter("edge", radius=radius),
            normal_force=force,
            angle=0.35,
            rng=context.rng(10 + index),
        )
        features = extract(frame.raw, sensor)
        types.append(features.contact_type)
        results.append(_edge_measures(frame.raw, features, pitch))
        figures.append(
            _feature_figure(frame.raw, features, sensor, f"{force:g} N: edges and fitted line")
        )
    plot = new_figure(4.2, 3.2)
    ax = plot.add_subplot()
    for force, measure in zip(forces, results, strict=True):
        ax.plot(measure["distance_m"] * 1e3, measure["profile"], label=f"{force:g} N")
    ax.set_xlabel("distance from the fitted line [mm]")
    ax.set_ylabel("mean grey level above background")
    ax.legend()
    figures.append(Figure("average cross-sections normal to the line", figure_png(plot)))
    light, firm = results
    grows = {
        name: firm[name] > light[name]
        for name in ("width_m", "mean_intensity", "cross_section_area")
    }
    rows = [
        (
            name.replace("_m", " [mm]").replace("_", " "),
            f"{light[name] * (1e3 if name == 'width_m' else 1):.3g}",
            f"{firm[name] * (1e3 if name == 'width_m' else 1):.3g}",
        )
        for name in ("width_m", "mean_intensity", "cross_section_area")
    ]
    return Experiment(
        key="edge",
        title="Figures 2 and 3: a 3.2 mm edge at 12 N and 39 N",
        seed_reference="Ellis, section 2.2, figures 2 and 3 (and 3B, the edges)",
        summary="The same 3.2 mm-radius edge pressed lightly and firmly. The seed: the width "
        "of the edge, its mean intensity and its average cross-section are all greater in "
        "the second image.",
        figures=tuple(figures),
        tables=(
            Table(
                "measures of the two images",
                ("measure", f"{forces[0]:g} N", f"{forces[1]:g} N"),
                rows,
            ),
        ),
        verdicts=(
            Verdict(
                "line contact at both forces",
                ", ".join(types),
                "line, line",
                all(kind == "line" for kind in types),
            ),
            Verdict(
                "width greater at the higher force",
                _compare(rows[0][2], rows[0][1], grows["width_m"]) + " mm",
                "greater",
                grows["width_m"],
            ),
            Verdict(
                "mean intensity greater",
                _compare(rows[1][2], rows[1][1], grows["mean_intensity"]),
                "greater",
                grows["mean_intensity"],
            ),
            Verdict(
                "average cross-section greater",
                _compare(rows[2][2], rows[2][1], grows["cross_section_area"]),
                "greater",
                grows["cross_section_area"],
            ),
        ),
        numbers={
            "forces_n": forces,
            "radius_m": radius,
            "contact_types": types,
            "light": {k: v for k, v in light.items() if np.ndim(v) == 0},
            "firm": {k: v for k, v in firm.items() if np.ndim(v) == 0},
        },
    )


def can_top(context: DemoContext, *, rim_radius: float = 26e-3, force: float = 20.0) -> Experiment:
    """Figure 4: the top of a drink can is an arc contact; the fitted arc's radius."""
    sensor = context.sensor(SENSOR)
    # the rim's centre off the sensor, so its arc crosses the array as in figure 4A
    position = (-(rim_radius - 4e-3), 2e-3)
    frame = sensor.press(
        make_indenter("can", rim_radius=rim_radius),
        normal_force=force,
        position=position,
        rng=context.rng(20),
    )
    features = extract(frame.raw, sensor)
    circle = features.shape.circle
    radius = circle.radius_m if circle is not None else float("nan")
    error = abs(radius / rim_radius - 1)
    return Experiment(
        key="can",
        title="Figure 4: top of a drink can (arc contact)",
        seed_reference="Ellis, section 2.1, figures 4A and 4B",
        summary=f"The rolled rim of a can ({rim_radius * 2e3:g} mm across) pressed with "
        f"{force:g} N with its centre off the array; edges fitted first to a line, then to "
        "a circle; lines and arcs are told apart by the RMS errors of the fits.",
        figures=(
            _raw_figure(frame.raw, "tactile image"),
            _feature_figure(frame.raw, features, sensor, "edges and the fitted arc"),
        ),
        verdicts=(
            Verdict(
                "contact type is arc", features.contact_type, "arc", features.contact_type == "arc"
            ),
            Verdict(
                "fitted arc radius within 5 % of the rim's",
                f"{radius * 1e3:.1f} mm ({error:.1%} off)",
                f"{rim_radius * 1e3:g} mm (true)",
                bool(error <= 0.05),
            ),
        ),
        numbers={
            "force_n": force,
            "rim_radius_m": rim_radius,
            "fitted_radius_m": radius,
            "contact_type": features.contact_type,
        },
    )


def washer(context: DemoContext, *, indenter: str = "washer", force: float = 20.0) -> Experiment:
    """Figure 5: a washer, and its hole found by the seed's diameter test."""
    sensor = context.sensor(SENSOR)
    frame = sensor.press(
        make_indenter(indenter),
        normal_force=force,
        position=(1e-3, -1.5e-3),
        angle=0.2,
        rng=context.rng(30),
    )
    features = extract(frame.raw, sensor)
    holes = features.holes
    radius = holes.items[0].radius_m if holes.items else float("nan")
    return Experiment(
        key="washer",
        title="Figure 5: a washer, with its hole found",
        seed_reference="Ellis, section 2.1, figures 5A and 5B",
        summary="An M8 washer pressed flat. The seed's test: fit the edges to a circle; a "
        "hole exists if diameters of the fitted circle cross four edges. A second test "
        "looks for a round gap enclosed by contact.",
        figures=(
            _raw_figure(frame.raw, "tactile image"),
            _feature_figure(frame.raw, features, sensor, "edges, fitted circle and hole"),
        ),
        verdicts=(
            Verdict(
                "hole found by the diameter test",
                str(holes.diameter_test),
                "yes",
                bool(holes.diameter_test),
            ),
            Verdict(
                "hole found by the enclosed-gap test",
                f"{holes.count} hole(s)",
                "one hole",
                holes.count == 1,
            ),
        ),
        numbers={
            "force_n": force,
            "holes": holes.count,
            "diameter_test": holes.diameter_test,
            "hole_radius_m": radius,
            "true_hole_radius_m": 4.2e-3,
        },
    )


def texture_table(context: DemoContext, *, force: float = 30.0) -> Experiment:
    """Figures 6-8: stiff foam, wood rasp and metal screen; the seed's two texture measures."""
    sensor = context.sensor(SENSOR)
    measures, figures = {}, []
    for index, name in enumerate(("foam", "rasp", "screen")):
        material = FOAM if name == "foam" else None
        frame = sensor.press(
            make_indenter(name),
            normal_force=force,
            indenter_material=material,
            rng=context.rng(40 + index),
        )
        texture = extract(frame.raw, sensor).texture
        measures[name] = (texture.maxima_count, texture.mean_height)
        figures.append(_raw_figure(frame.raw, f"{name} ({force:g} N)"))
    rows = [
        (
            name,
            str(measures[name][0]),
            f"{measures[name][1]:.2f}",
            str(SEED_TEXTURE[name][0]),
            f"{SEED_TEXTURE[name][1]:.2f}",
        )
        for name in ("foam", "screen", "rasp")
    ]
    most = max(measures, key=lambda name: measures[name][0])
    foam_height = measures["foam"][1]
    return Experiment(
        key="texture",
        title="Figures 6-8: texture of foam, wood rasp and metal screen",
        seed_reference="Ellis, section 2.1, figures 6-8 and the texture table",
        summary="Each surface pressed over the whole array; the image smoothed with a "
        "Gaussian (against noise and glass scratches); the number of local maxima and their "
        "average height above the background, as in the seed.",
        figures=tuple(figures),
        tables=(
            Table(
                "texture measures",
                (
                    "object",
                    "maxima (taxel)",
                    "average height (taxel)",
                    "maxima (seed)",
                    "average height (seed)",
                ),
                rows,
            ),
        ),
        verdicts=(
            Verdict("the rasp has the most maxima", most, "rasp", most == "rasp"),
            Verdict(
                "screen higher on average than foam",
                f"{measures['screen'][1]:.2f} vs {foam_height:.2f}",
                "15.62 vs 11.27",
                measures["screen"][1] > foam_height,
            ),
            Verdict(
                "rasp higher on average than foam",
                f"{measures['rasp'][1]:.2f} vs {foam_height:.2f}",
                "15.19 vs 11.27",
                measures["rasp"][1] > foam_height,
            ),
        ),
        numbers={
            "force_n": force,
            "measures": {k: list(v) for k, v in measures.items()},
            "seed": {k: list(v) for k, v in SEED_TEXTURE.items()},
        },
    )
