"""A slot, a corner and a surface normal, located in the robot's base frame (Ellis 2, 2.2)."""

from __future__ import annotations

import numpy as np

from taxel.active import corner_probing_trial, plane_probing_trial
from taxel.features import extract
from taxel.frames import make_pose, transform_points
from taxel.mechanics import make_indenter
from taxel.report._context import DemoContext
from taxel.report._figures import figure_png, new_figure
from taxel.report._model import Experiment, Figure, Table, Verdict

__all__ = ["slot_corner_normal"]

SENSOR = "vhdta128"


def _sensor_pose(rng: np.random.Generator) -> np.ndarray:
    """A sensor facing down at a random place over the table, turned about the vertical."""
    turn = rng.uniform(-np.pi, np.pi)
    rotation = np.array(
        [[np.cos(turn), np.sin(turn), 0.0], [np.sin(turn), -np.cos(turn), 0.0], [0, 0, -1.0]]
    )
    return make_pose(rotation, [rng.uniform(0.3, 0.6), rng.uniform(-0.2, 0.2), 0.05])


def slot_corner_normal(context: DemoContext) -> Experiment:
    """Slot and corner from single touches; a face's normal and a box corner from probing."""
    sensor = context.sensor(SENSOR)
    rng = context.rng(70)
    # a slot: a plate with a 3 x 15 mm slot, placed on the sensor, the sensor at a known pose
    slot_angle, slot_centre = 0.6, np.array([1.5e-3, -2.0e-3])
    pose = _sensor_pose(rng)
    frame = sensor.press(
        make_indenter("slot"),
        normal_force=25.0,
        position=tuple(slot_centre),
        angle=slot_angle,
        rng=context.rng(71),
    )
    features = extract(frame.raw, sensor, pose=pose)
    slots = features.slots
    found = slots.items[0] if slots.items else None
    true_base = transform_points(pose, [*slot_centre, 0.0])
    if found is not None:
        found_base = transform_points(pose, [*found.center_m, 0.0])
        slot_error = float(np.linalg.norm(found_base - true_base))
        angle_error = abs((found.angle_rad - slot_angle + np.pi / 2) % np.pi - np.pi / 2)
    else:
        found_base, slot_error, angle_error = None, float("inf"), float("inf")
    # a corner (vertex) of a box, one touch
    corner_frame = sensor.press(
        make_indenter("box-corner"), normal_force=15.0, angle=0.4, rng=context.rng(72)
    )
    corner_features = extract(corner_frame.raw, sensor)
    # a surface normal from 5 probes, and a box corner from probing three faces
    trials = 2 if context.quick else 10
    planes = [
        plane_probing_trial("resistive16", n_probes=5, seed=context.seed + i)
        for i in range(trials)
    ]
    corners = [corner_probing_trial("resistive16", seed=context.seed + i) for i in range(trials)]
    normal_errors = np.degrees([trial.normal_error for trial in planes])
    corner_errors = np.array([trial.corner_error for trial in corners]) * 1e3

    from taxel.viz import plot_features

    slot_figure = plot_features(frame.raw, features, sensor)
    slot_figure.set_size_inches(4.2, 3.6)
    corner_figure = plot_features(corner_frame.raw, corner_features, sensor)
    corner_figure.set_size_inches(4.2, 3.6)
    plane = planes[0]
    points = np.asarray(plane.estimate.contact_points)
    scatter = new_figure(4.4, 3.6)
    ax = scatter.add_subplot(projection="3d")
    ax.scatter(*(points * 1e3).T, color="C1", label="contact points")
    centre = points.mean(axis=0) * 1e3
    # the normal drawn half as long as the probes' spread, in a cube that holds it all, so
    # that right angles look right
    half = max(float(np.ptp(points, axis=0).max()) * 1e3 / 2, 1.0)
    ax.quiver(
        *centre, *(np.asarray(plane.estimate.normal) * half), color="C0", label="fitted normal"
    )
    for set_limits, middle in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre, strict=True):
        set_limits(middle - 1.2 * half, middle + 1.2 * half)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x [mm]", fontsize=7)
    ax.set_ylabel("y [mm]", fontsize=7)
    ax.set_zlabel("z [mm]", fontsize=7)
    ax.legend(fontsize=7)
    rows = [
        (
            "slot centre (base frame)",
            "-" if found_base is None else ", ".join(f"{v * 1e3:.2f}" for v in found_base) + " mm",
            ", ".join(f"{v * 1e3:.2f}" for v in true_base) + " mm",
        ),
        (
            "slot direction",
            "-" if found is None else f"{np.degrees(found.angle_rad):.1f} deg",
            f"{np.degrees(slot_angle):.1f} deg",
        ),
        ("slot width", "-" if found is None else f"{found.width_m * 1e3:.2f} mm", "3 mm"),
        (
            "plane normal error, 5 probes",
            f"median {np.median(normal_errors):.3f} deg, " f"worst {normal_errors.max():.3f} deg",
            "<= 1 deg",
        ),
        (
            "box corner error, 3 faces x 3 probes",
            f"median {np.median(corner_errors):.3f} mm, " f"worst {corner_errors.max():.3f} mm",
            "<= 1 mm",
        ),
    ]
    return Experiment(
        key="probing",
        title="A slot, a corner and a surface normal in the robot's base frame",
        seed_reference="Ellis, section 2: slots; corner or vertex; surface normal of a plane; "
        "3-D position of the contact relative to the robot's base frame",
        summary="A plate with a slot and the corner of a box pressed on the VHDTA held at a "
        "known pose; the slot is located in the base frame. A large tilted box face probed "
        f"at 5 random poses ({trials} trials, 16 x 16 resistive sensor) gives its normal; "
        "three faces probed near a corner give the corner.",
        figures=(
            Figure("plate with a slot: edges, slot", figure_png(slot_figure)),
            Figure("corner of a box", figure_png(corner_figure)),
            Figure("contact points of 5 probes and the fitted normal", figure_png(scatter)),
        ),
        tables=(Table("located features", ("feature", "taxel", "truth / target"), rows),),
        verdicts=(
            Verdict(
                "slot found, its centre within 1 mm in the base frame",
                f"{slots.count} slot(s), {slot_error * 1e3:.2f} mm",
                "slots present",
                found is not None and slot_error <= 1e-3,
            ),
            Verdict(
                "slot direction within 5 degrees",
                "-" if found is None else f"{np.degrees(angle_error):.1f} deg off",
                "-",
                bool(np.degrees(angle_error) <= 5.0),
            ),
            Verdict(
                "a box corner reads as a corner (vertex)",
                corner_features.contact_type,
                "corner",
                corner_features.contact_type == "corner",
            ),
            Verdict(
                "surface normal within 1 degree from 5 probes",
                f"worst {normal_errors.max():.3f} deg",
                "<= 1 deg (taxel's target)",
                bool(normal_errors.max() <= 1.0),
            ),
            Verdict(
                "box corner within 1 mm by probing",
                f"worst {corner_errors.max():.3f} mm",
                "<= 1 mm (taxel's target)",
                bool(corner_errors.max() <= 1.0),
            ),
        ),
        numbers={
            "slot_error_m": slot_error,
            "slot_angle_error_rad": angle_error,
            "corner_type": corner_features.contact_type,
            "normal_errors_deg": normal_errors,
            "corner_errors_mm": corner_errors,
        },
    )
