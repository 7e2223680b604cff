"""``taxel demo``: the solvers against closed forms (the main-job report replaces this)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from taxel import mechanics

__all__ = ["register"]


@dataclass(frozen=True)
class _Check:
    """One number computed by taxel next to its closed form, with the tolerance it must meet."""

    case: str
    quantity: str
    unit: str
    expected: float
    computed: float
    tolerance: float  # relative

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


_SECTIONS: list[Callable[[], list[_Check]]] = [
    _plane_strain_checks,
    _sphere_checks,
    _punch_checks,
    _layer_checks,
]


def _run(arguments: argparse.Namespace) -> int:
    checks: list[_Check] = []
    for index, section in enumerate(_SECTIONS, start=1):
        sys.stderr.write(f"\r[{index}/{len(_SECTIONS)}] {section.__name__.strip('_')}")
        sys.stderr.flush()
        checks.extend(section())
    sys.stderr.write("\n")
    header = f"{'case':30} {'quantity':15} {'closed form':>13} {'taxel':>13} {'error':>9}  verdict"
    print(header)
    print("-" * len(header))
    for check in checks:
        verdict = "pass" if check.passed else "FAIL"
        print(
            f"{check.case:30} {check.quantity + ' [' + check.unit + ']':15} "
            f"{check.expected:13.6g} {check.computed:13.6g} {check.error:9.2e}  {verdict}"
        )
    failed = sum(not check.passed for check in checks)
    print(f"\n{len(checks) - failed} of {len(checks)} checks within tolerance")
    return 0 if failed == 0 else 1


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``taxel demo`` to the command line."""
    parser = commands.add_parser("demo", help="run the solvers against closed forms")
    parser.add_argument("--out", metavar="DIR", help="output folder (used by the full report)")
    parser.set_defaults(handler=_run)
