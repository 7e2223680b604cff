"""The report as one self-contained HTML page (images embedded, no external resources)."""

from __future__ import annotations

import base64
import html
import platform
from collections.abc import Sequence

import taxel
from taxel.report._model import Experiment

__all__ = ["render_html"]

_STYLE = """
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 70em; color: #222;
       line-height: 1.45; padding: 0 1em; }
h1 { margin-bottom: 0.2em; } h2 { margin-top: 2em; border-bottom: 1px solid #ccc; }
.meta { color: #666; font-size: 0.9em; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 0.92em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; }
th { background: #f3f3f3; }
.pass { color: #176b2c; font-weight: 600; } .fail { color: #b3261e; font-weight: 600; }
.figures { display: flex; flex-wrap: wrap; gap: 1em; }
figure { margin: 0; max-width: 30em; } figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { font-size: 0.85em; color: #444; }
.seed { color: #555; font-size: 0.9em; font-style: italic; }
"""


def _verdict_cell(passed: bool) -> str:
    return '<td class="pass">pass</td>' if passed else '<td class="fail">FAIL</td>'


def _table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    head = "".join(f"<th>{html.escape(str(cell))}</th>" for cell in header)
    body = "".join(
        "<tr>" + "".join(f"<td>{html.escape(str(cell))}</td>" for cell in row) + "</tr>"
        for row in rows
    )
    return f"<table><tr>{head}</tr>{body}</table>"


def _experiment(experiment: Experiment) -> str:
    parts = [
        f'<h2 id="{html.escape(experiment.key)}">{html.escape(experiment.title)}</h2>',
        f'<p class="seed">Reproduces: {html.escape(experiment.seed_reference)}</p>',
        f"<p>{html.escape(experiment.summary)}</p>",
    ]
    if experiment.figures:
        parts.append('<div class="figures">')
        for figure in experiment.figures:
            data = base64.b64encode(figure.png).decode("ascii")
            caption = html.escape(figure.caption)
            parts.append(
                f'<figure><img alt="{caption}" src="data:image/png;base64,{data}">'
                f"<figcaption>{caption}</figcaption></figure>"
            )
        parts.append("</div>")
    for table in experiment.tables:
        parts.append(f"<h3>{html.escape(table.title)}</h3>")
        parts.append(_table(table.header, table.rows))
    if experiment.verdicts:
        rows = "".join(
            f"<tr><td>{html.escape(v.claim)}</td><td>{html.escape(v.ours)}</td>"
            f"<td>{html.escape(v.seed)}</td>{_verdict_cell(v.passed)}</tr>"
            for v in experiment.verdicts
        )
        parts.append(
            "<table><tr><th>claim</th><th>taxel</th><th>seed</th><th>verdict</th></tr>"
            f"{rows}</table>"
        )
    return "\n".join(parts)


def render_html(
    experiments: Sequence[Experiment], *, quick: bool, seconds: float, seed: int
) -> str:
    """The whole report page."""
    passed = sum(experiment.passed for experiment in experiments)
    summary_rows = "".join(
        f'<tr><td><a href="#{html.escape(e.key)}">{html.escape(e.title)}</a></td>'
        f"<td>{sum(v.passed for v in e.verdicts)} / {len(e.verdicts)}</td>"
        f"{_verdict_cell(e.passed)}<td>{e.seconds:.1f} s</td></tr>"
        for e in experiments
    )
    mode = "quick run" if quick else "full run"
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>taxel: the seeds' experiments</title><style>{_STYLE}</style></head>
<body>
<h1>taxel: the seeds' experiments, end to end</h1>
<p class="meta">taxel {html.escape(taxel.__version__)}, {mode}, {seconds:.0f} s on
{html.escape(platform.machine())}, Python {html.escape(platform.python_version())}, random
seed {seed} (noise, positions and presses are drawn from it: another seed moves the numbers
a little).
Every experiment runs through the real pipeline (contact mechanics, sensor simulation,
calibration, reconstruction, features, active procedures); every verdict is computed from
its numbers.</p>
<p>Seeds: R. E. Ellis, "Extraction of tactile features by passive and active sensing";
R. E. Saad, A. Bonen, K. C. Smith, B. Benhabib, "Tactile Sensing".</p>
<h2>Summary: {passed} of {len(experiments)} experiments pass every check</h2>
<table><tr><th>experiment</th><th>checks passed</th><th>verdict</th><th>time</th></tr>
{summary_rows}</table>
{"".join(_experiment(experiment) for experiment in experiments)}
</body></html>
"""
