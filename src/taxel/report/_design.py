"""Harmon's criteria (chapter section 25.2) measured on the VHDTA and a 16 x 16 array."""

from __future__ import annotations

import numpy as np

from taxel.report._context import DemoContext
from taxel.report._figures import figure_png, new_figure
from taxel.report._model import Experiment, Figure, Table, Verdict
from taxel.sensor import harmon_table

__all__ = ["harmon_criteria"]


def _rows(table) -> list[tuple[str, str, str, str]]:
    verdict = {True: "pass", False: "FAIL", None: "info"}
    return [(row.criterion, *row.display(), verdict[row.passed]) for row in table.rows]


def _resolution_figure(tables: dict) -> Figure:
    figure = new_figure(4.6, 3.2)
    ax = figure.add_subplot()
    for name, table in tables.items():
        measured = table.resolution
        if measured is None:
            continue
        line = ax.plot(measured.separations * 1e3, measured.dips, "o-", ms=3, label=name)[0]
        if measured.resolution is not None:
            ax.axvline(measured.resolution * 1e3, color=line.get_color(), ls=":", lw=1)
        threshold = measured.dip
    ax.axhline(threshold, color="0.4", lw=0.8, ls="--", label="resolved above this dip")
    ax.set_xlabel("separation of two point loads [mm]")
    ax.set_ylabel("dip between the peaks (fraction)")
    ax.legend(fontsize=7)
    return Figure(
        "two-point test in the calibrated frame: the dotted lines mark each sensor's "
        "measured spatial resolution",
        figure_png(figure),
    )


def harmon_criteria(
    context: DemoContext, *, sensors: tuple[str, ...] = ("vhdta128", "resistive16")
) -> Experiment:
    """Harmon's table for the Ellis seed's sensor and for a 16 x 16 resistive array."""
    tables = {name: harmon_table(context.sensor(name), rng=context.seed) for name in sensors}
    first = context.sensor(sensors[0])
    resolution = tables[sensors[0]].row("spatial resolution")
    levels = tables[sensors[0]].row("reliable levels").value
    bits = float(np.log2(levels)) if levels else 0.0
    depth = first.cover.depth
    density = first.geometry.density
    return Experiment(
        key="harmon",
        title="Harmon's criteria for the VHDTA and the 16 x 16 array",
        seed_reference="Saad et al., section 25.2 (Harmon's list); Ellis, section 1",
        summary="Each sensor simulated and measured against Harmon's list: spatial resolution "
        "is the smallest separation at which two point loads give two peaks in the "
        "calibrated frame; sensitivity the smallest force on one element that changes the "
        "reading beyond its noise; dynamic range full scale over that; hysteresis from a "
        "loading-unloading cycle; monotonic response from a load sweep.",
        figures=(_resolution_figure(tables),),
        tables=tuple(
            Table(
                f"{name} ({table.density_class})",
                ("criterion", "measured", "Harmon's target", "verdict"),
                _rows(table),
            )
            for name, table in tables.items()
        ),
        verdicts=(
            Verdict(
                "the seed's sensor is a VHDTA of about 1504 taxels per cm^2",
                f"{density:.0f} /cm^2, {first.density_class}",
                "~1504 /cm^2, VHDTA",
                first.density_class == "VHDTA" and abs(density / 1504 - 1) < 0.01,
            ),
            Verdict(
                "two points are resolved at about the cover depth d (0.5 d to 2 d), "
                "not at the taxel pitch",
                f"{resolution.display()[0]} = " f"{(resolution.value or 0) / depth:.2f} d",
                f"d = {depth * 1e3:g} mm, pitch {first.taxel_pitch[0] * 1e3:.3f} mm",
                resolution.value is not None and 0.5 <= resolution.value / depth <= 2.0,
            ),
            Verdict(
                "5 to 8 bits of reliable levels over the working range",
                f"{bits:.1f} bits ({levels:.0f} levels)",
                "5 to 8 bits over 60 psi",
                5.0 <= bits <= 8.0,
            ),
        ),
        numbers={name: table.to_dict() for name, table in tables.items()},
    )
