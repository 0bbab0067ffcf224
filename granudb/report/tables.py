"""The fit tables of a dataset report, with published values on the right group.

A cell is a string, or a dict ``{"text", "colour"}`` for a group name shown with the
colour its points have in every figure. Fit dicts may carry more keys than the ones
used here (intervals, model choice, limits): an interval is shown when present, other
keys are ignored.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from granudb.report.format import display, interval, plus_minus
from granudb.report.groups import fluid_name, group_label

WALTON_PUBLISHED = ("rotational_restitution", "sliding_friction", "normal_restitution_mean")


def _interval_of(fit: Mapping[str, Any], name: str) -> tuple[Any, Any] | None:
    """An interval the fit carries for ``name``, under any of the spellings in use."""
    pair = fit.get(f"{name}_interval") or fit.get(f"{name}_ci")
    if isinstance(pair, list | tuple) and len(pair) == 2:
        return pair[0], pair[1]
    for low, high in (("_low", "_high"), ("_ci_low", "_ci_high"), ("_lower", "_upper")):
        if f"{name}{low}" in fit and f"{name}{high}" in fit:
            return fit[f"{name}{low}"], fit[f"{name}{high}"]
    return None


def fit_cell(fit: Mapping[str, Any], name: str, error: str | None = None) -> str:
    """A fitted value: with its interval when the fit has one, else ± its standard error."""
    bounds = _interval_of(fit, name)
    if bounds is not None:
        return interval(fit.get(name), *bounds)
    return plus_minus(fit.get(name), fit.get(error or f"{name}_stderr"))


def group_cell(fit: Mapping[str, Any], colours: Mapping[str, str]) -> dict[str, str]:
    label = group_label(fit["particle"], fit["wall"], fit.get("fluid"))
    prefix = f"{fit['dataset']}: " if fit.get("dataset") else ""
    return {"text": prefix + label, "colour": colours.get(label, ""), "group": label}


def published_for(published: list[dict[str, Any]], fit: Mapping[str, Any]) -> str:
    """The values the paper printed for exactly this group: same particle, wall and
    fluid (a dry fit only matches dry rows). A row stored without a fluid counts as dry
    only when its condition says so, so an older database whose immersed rows still lack
    their fluid never puts immersed values on the dry group."""
    fluid = fluid_name(fit.get("fluid"))

    def dry_row(p: dict[str, Any]) -> bool:
        return p["fluid"] is not None or "dry" in (p.get("condition") or "dry")

    matches = [
        p
        for p in published
        if p["particle"] == fit["particle"]
        and p["wall"] == fit["wall"]
        and fluid_name(p["fluid"]) == fluid
        and p["quantity"] in WALTON_PUBLISHED
        and dry_row(p)
    ]
    return (
        "; ".join(
            f"{p['value_as_printed']} ({p['source']}, {p['source_locator']})" for p in matches
        )
        or "—"
    )


def walton_table(
    walton: list[dict[str, Any]], published: list[dict[str, Any]], colours: Mapping[str, str]
) -> dict[str, Any]:
    return {
        "id": "walton-fits",
        "heading": "Walton fits (figures 4, 6, 9)",
        "note": "β from the sticking runs (Ψ_out = −βΨ_in), μ_f from the sliding runs, each "
        "± its standard error (or its interval, where the fit gives one); ē ± std over all "
        "runs of the group. Published: the values Joseph & Hunt (2004) printed for the same "
        "particle, wall and fluid.",
        "columns": ["group", "β", "μ_f", "ē", "sticking / sliding runs", "published"],
        "rows": [
            [
                group_cell(r, colours),
                fit_cell(r, "rotational_restitution"),
                fit_cell(r, "sliding_friction"),
                fit_cell(r, "normal_restitution_mean", "normal_restitution_std"),
                f"{r.get('n_sticking', '—')} / {r.get('n_sliding', '—')}",
                published_for(published, r),
            ]
            for r in walton
        ],
    }


def restitution_table(restitution: list[dict[str, Any]], formula: str, source: str) -> dict:
    return {
        "id": "restitution-fit",
        "heading": "Restitution against Stokes number (figure 5)",
        "note": f"Threshold form {formula} ({source}).",
        "columns": ["group", "e_dry", "St_c", "runs"],
        "rows": [
            [
                f"{r['dataset']}: {r['particle']}/{r['wall']}",
                fit_cell(r, "e_dry"),
                fit_cell(r, "parameter"),
                str(r.get("n_runs", "—")),
            ]
            for r in restitution
        ],
    }


def gap_table(gap: list[dict[str, Any]], colours: Mapping[str, str]) -> dict[str, Any]:
    def temperature(r: Mapping[str, Any]) -> str:
        value = r.get("gap_temperature_c")
        if isinstance(value, int | float) and not math.isnan(value):
            return display(value, "temperature_c")
        return r.get("note") or "—"

    return {
        "id": "gap-viscosity",
        "heading": "Gap viscosity and temperature (figure 14, table 2)",
        "note": "μ₀ that makes (5.10) match each smooth sliding run's μ_f; the gap "
        "temperature follows from the fluid's μ(T).",
        "columns": ["group", "μ₀", "ambient μ", "gap temperature", "runs"],
        "rows": [
            [
                group_cell(r, colours),
                display(r.get("gap_viscosity_pa_s"), "viscosity_pa_s"),
                display(r.get("ambient_viscosity_pa_s"), "viscosity_pa_s"),
                temperature(r),
                str(r.get("n_runs", "—")),
            ]
            for r in gap
        ],
    }
