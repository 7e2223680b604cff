"""The chapter's forward problem: the mechanics against closed forms (section 25.2)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from taxel import mechanics
from taxel.report._context import DemoContext
from taxel.report._figures import figure_png, new_figure
from taxel.report._model import Experiment, Figure, Table, Verdict

__all__ = ["forward_problem"]


@dataclass(frozen=True)
class _Check:
    """One number computed by taxel next to its closed form, with its relative tolerance."""

    case: str
    quantity: str
    unit: str
    expected: float
    computed: float
    tolerance: float

    @property
    def error(self) -> float:
        return abs(self.computed - self.expected) / abs(self.expected)

    @property
    def passed(self) -> bool:
        return self.error <= self.tolerance


def _sphere_checks() -> list[_Check]:
    cover = mechanics.ElasticMaterial(1e6, 0.5)
    shape, spacing, radius, force = (128, 128), 0.1e-3, 10e-3, 1.0
    result = mechanics.solve_contact(
        mechanics.Sphere(radius).on_grid(shape, spacing), spacing, cover, normal_force=force
    )
    hertz = mechanics.hertz_sphere(force, radius, cover.plane_strain_modulus)
    measured_radius = np.sqrt(result.contact_area / np.pi)
    case = "sphere R=10 mm, 1 N, 128x128"
    return [
        _Check(case, "indentation", "mm", hertz.indentation * 1e3, result.indentation * 1e3, 0.01),
        _Check(
            case,
            "contact radius",
            "mm",
            hertz.contact_radius * 1e3,
            measured_radius * 1e3,
            spacing / hertz.contact_radius,
        ),
        _Check(
            case,
            "peak pressure",
            "kPa",
            hertz.peak_pressure / 1e3,
            result.pressure.max() / 1e3,
            0.01,
        ),
    ]


def _punch_checks() -> list[_Check]:
    cover = mechanics.ElasticMaterial(1e6, 0.5)
    radius, depth, spacing = 2e-3, 20e-6, 0.05e-3
    heights = mechanics.FlatPunch(radius).on_grid((96, 96), spacing)
    result = mechanics.solve_contact(heights, spacing, cover, indentation=depth)
    expected = mechanics.flat_punch(depth, radius, cover.plane_strain_modulus).normal_force
    return [
        _Check(
            "flat punch a=2 mm, 20 um",
            "force",
            "mN",
            expected * 1e3,
            result.normal_force * 1e3,
            0.02,
        )
    ]


def _plane_strain_checks() -> list[_Check]:
    cover = mechanics.ElasticMaterial(1e6, 0.3)
    case = "line load 100 N/m, d=2 mm"
    return [
        _Check(
            case,
            "eps_z(0)",
            "-",
            -2.896620e-2,
            100 * float(mechanics.line_load_strain(0.0, 2e-3, cover)),
            5e-7,
        ),
        _Check(
            case,
            "eps_z(d)",
            "-",
            -4.138029e-3,
            100 * float(mechanics.line_load_strain(2e-3, 2e-3, cover)),
            5e-7,
        ),
    ]


def _layer_checks() -> list[_Check]:
    cover = mechanics.ElasticMaterial(1e6, 0.3)
    thickness = 0.1e-3
    operator = mechanics.depth_strain_operator(
        (64, 64), 0.25e-3, thickness / 2, cover, thickness=thickness
    )
    load = np.zeros((64, 64))
    load[16:48, 16:48] = 1e4
    strain = operator.apply(load)[32, 32]
    return [
        _Check(
            "thin bonded layer, 10 kPa",
            "eps_z",
            "-",
            -1e4 / cover.constrained_modulus,
            float(strain),
            0.01,
        )
    ]


def _kernel_figure() -> Figure:
    cover = mechanics.ElasticMaterial(1e6, 0.3)
    depth = 2e-3
    x = np.linspace(-8e-3, 8e-3, 401)
    figure = new_figure(4.4, 3.0)
    ax = figure.add_subplot()
    ax.plot(x * 1e3, 100 * mechanics.line_load_strain(x, depth, cover), label="h_z, eq. 25.2")
    ax.axhline(0, color="0.6", lw=0.8)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("eps_z at d = 2 mm (P = 100 N/m)")
    ax.legend()
    return Figure(
        "the chapter's strain kernel h_z (eq. 25.2): compression under the load, "
        "a tensile side lobe beyond x = d sqrt((1 - nu)/nu)",
        figure_png(figure),
    )


def forward_problem(context: DemoContext) -> Experiment:
    """Plane-strain kernels, Hertz, the flat punch and the bonded layer against closed forms."""
    checks = _plane_strain_checks() + _sphere_checks() + _punch_checks() + _layer_checks()
    rows = [
        (
            check.case,
            f"{check.quantity} [{check.unit}]",
            f"{check.expected:.6g}",
            f"{check.computed:.6g}",
            f"{check.error:.2e}",
            f"{check.tolerance:.0e}",
        )
        for check in checks
    ]
    verdicts = tuple(
        Verdict(
            f"{check.case}: {check.quantity}",
            f"{check.computed:.6g}",
            f"{check.expected:.6g} (closed form)",
            check.passed,
        )
        for check in checks
    )
    return Experiment(
        key="forward",
        title="The forward problem: the cover's mechanics against closed forms",
        seed_reference="Saad et al., section 25.2, eqs. 25.1-25.5; Johnson, Contact Mechanics",
        summary="The chapter's plane-strain kernel and element-integrated T, the contact "
        "solver against Hertz and the flat punch, and a thin bonded cover against its "
        "oedometric limit.",
        figures=(_kernel_figure(),),
        tables=(
            Table(
                "solver results against closed forms",
                ("case", "quantity", "closed form", "taxel", "relative error", "tolerance"),
                rows,
            ),
        ),
        verdicts=verdicts,
        numbers={
            f"{c.case} / {c.quantity}": {"expected": c.expected, "computed": c.computed}
            for c in checks
        },
    )
