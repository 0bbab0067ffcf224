"""The validation gallery: one Markdown page per reference dataset, with its figures.

``page(shown, result)`` takes what ``granudb.reference_show`` and
``granudb.reference_reproduce`` return and gives the page's Markdown and its figures (SVG
text, deterministic: ``granudb.reporting.svg``). ``tools/build_reference_docs.py`` writes
them to ``docs/reference/``; ``tests/reference/test_gallery.py`` checks the committed pages
are what it writes, so a page always says what the code computes today.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from granudb.reporting.svg import Plot, Style

DATA = Style("#1f77b4", marker="o", size=4.0)
MODEL = Style("#d62728", width=1.4)
PREDICTED = Style("#d62728", marker="s", size=4.5, hollow=True)

#: Axis labels of the quantities the figures show.
LABELS = {
    "tangential_restitution": "tangential restitution e_t",
    "angular_velocity_out_rad_s": "spin after impact ω_out [rad/s]",
    "rebound_angle_centre_deg": "centre-of-mass rebound angle [°]",
    "rebound_angle_contact_deg": "contact-point rebound angle [°]",
    "normal_restitution": "normal restitution e",
}


def _number(value: Any) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "—"
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def _cell(text: Any) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _figure_points(shown: dict, quantity: str) -> tuple[list[float], list[float], list[float]]:
    """(θ in degrees, value, u) of one figure's points in a Kharaz-like dataset."""
    points: dict[str, dict] = {}
    for row in shown["values"]:
        points.setdefault(row["point"], {})[row["quantity"]] = row
    x, y, u = [], [], []
    for rows in points.values():
        if quantity in rows and "incidence_angle_deg" in rows:
            x.append(float(rows["incidence_angle_deg"]["value"]))
            y.append(float(rows[quantity]["value"]))
            u.append(float(rows[quantity]["u"]))
    return x, y, u


def _figures(shown: dict, result: dict) -> dict[str, str]:
    name = shown["name"]
    curves = result.get("curves", {})
    figures = {}
    for quantity, curve in curves.items():
        if quantity == "cases":
            continue
        if quantity == "normal_restitution":
            plot = Plot(
                xlog=True,
                xlabel="Stokes number with added mass St_am",
                ylabel=LABELS[quantity],
                title=f"{name}: Legendre et al.'s e(St) and the cases' predictions",
            )
            plot.line(curve["x"], curve["y"], MODEL, label="e = 0.97 exp(−35/St_am)")
            cases = curves.get("cases")
            if cases:
                plot.points(cases["x"], cases["y"], PREDICTED, label="cases (predicted)")
        else:
            x, y, u = _figure_points(shown, quantity)
            plot = Plot(
                xlabel="incidence angle θ from the normal [°]",
                ylabel=LABELS[quantity],
                title=f"{name}: {LABELS[quantity]} against θ",
            )
            plot.errorbars(x, y, np.zeros(len(x)), u, DATA)
            plot.points(x, y, DATA, label="experiment (mean of the digitisations, ±u)")
            plot.line(curve["x"], curve["y"], MODEL, label="granudb's Walton fit")
        figures[f"{name}-{quantity}.svg"] = plot.svg(f"{name}-{quantity}")
    return figures


def page(shown: dict[str, Any], result: dict[str, Any]) -> tuple[str, dict[str, str]]:
    """The Markdown page of one reference dataset and its figures ({file name: SVG})."""
    figures = _figures(shown, result)
    lines = [
        f"# {shown['name']} {shown['version']}",
        "",
        "<!-- written by tools/build_reference_docs.py; do not edit -->",
        "",
        shown["title"] + ".",
        "",
        "Reproduce it: `granudb reference reproduce " + shown["name"] + "` "
        f"(Python: `granudb.reference_reproduce({shown['name']!r})`); its values: "
        f"`granudb reference show {shown['name']}`.",
        "",
        "## Sources and licences",
        "",
    ]
    lines += [f"- {s}" for s in shown["sources"]]
    lines += [f"- licence: {licence}" for licence in shown["licences"]]
    provenance = sorted(
        {(v["digitiser"], v["repository"], v["file"], v["commit"]) for v in shown["values"]}
    )
    lines += ["", "Where the numbers were read:", ""]
    lines += ["| digitiser | repository | file | commit |", "|---|---|---|---|"]
    lines += [
        f"| {_cell(d)} | {_cell(r) or '—'} | {_cell(f) or '—'} | {_cell(c) or '—'} |"
        for d, r, f, c in provenance
    ]
    if shown["meanings"]:
        lines += ["", "## What each quantity is", ""]
        lines += [f"- `{q}`: {text}" for q, text in shown["meanings"].items()]
    lines += ["", "## Reproduction by granudb", ""]
    lines += [f"- {line}" for line in result["summary"]]
    for file in figures:
        lines += ["", f"![{file.removesuffix('.svg')}]({file})"]
    counts: dict[str, int] = {}
    for check in result["checks"]:
        key = check["verdict"].split(" (")[0]
        counts[key] = counts.get(key, 0) + 1
    lines += [
        "",
        "## Checks",
        "",
        "Verdict: *agrees* when |computed − reported| ≤ 2 u_c, u_c = √(u_reported² + "
        "u_computed²); *prediction only* where the public source holds no measured value. "
        + ", ".join(f"{n} {k}" for k, n in counts.items())
        + ".",
        "",
        "| check | point | quantity | reported | u | computed | residual | verdict |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for c in result["checks"]:
        cells = [
            c["check"],
            c["point"],
            c["quantity"],
            _number(c["reported"]),
            _number(c["u_reported"]),
            _number(c["computed"]),
            _number(c["residual"]),
            c["verdict"],
        ]
        lines.append("| " + " | ".join(_cell(x) for x in cells) + " |")
    return "\n".join(lines) + "\n", figures
