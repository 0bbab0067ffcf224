"""The fit tables of a dataset report, with published values on the right group.

A cell is a string, or a dict ``{"text", "colour"}`` for a group name shown with the
colour its points have in every figure. Every cell of a fit says its quantity in the words
``granudb fit walton|restitution|gap-viscosity`` print for it (``granudb.reporting.fit_view``,
one function per quantity): the fits say what their data determine (docs/physics.md §14),
a parameter that is not determined is shown as "not determined by these runs" with the
reason, never as a number; a μ_f lower bound is labelled as a bound; how the intervals were
made is said once, in the table's note, as the command's "intervals" line says it; and the
paper's ± is shown as printed beside them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from granudb.lazy import pyarrow, pyarrow_csv
from granudb.reporting.fit_view import (
    GAP,
    WALTON,
    ambient_viscosity,
    e_dry_words,
    gap_method,
    gap_runs,
    group_words,
    method_line,
    parameter_label,
    resamples_remark,
    restitution_model,
    restitution_parameter,
    restitution_runs,
    stokes_number,
    value_line,
    walton_model,
    walton_runs,
)
from granudb.reporting.format import display
from granudb.reporting.groups import fluid_name, fluid_names, group_label
from granudb.vocabulary import DERIVED_TERMS, TERMS
from granudb.vocabulary.escaping import spreadsheet_frame
from granudb.vocabulary.listings import REPORT_RUN_COLUMNS

WALTON_PUBLISHED = ("rotational_restitution", "sliding_friction", "normal_restitution_mean")


def group_cell(fit: Mapping[str, Any], colours: Mapping[str, str]) -> dict[str, str]:
    """The group's name as ``granudb fit`` heads it, in the colour of its points."""
    label = group_label(fit["particle"], fit["wall"], fit.get("fluid"))
    return {"text": group_words(fit), "colour": colours.get(label, ""), "group": label}


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


def bootstrap_note(fits: list[dict[str, Any]]) -> str:
    """How the intervals were made, said once: each distinct method as ``granudb fit``'s
    "intervals" line says it (``fit_view.method_line``: level, method, resamples and
    seed), and the resample rule when a large group was resampled fewer times."""
    words = sorted({w for w in map(method_line, fits) if w and "no interval" not in w})
    if not words:
        return ""
    rules = sorted(
        {f["bootstrap_rule"] for f in fits if f.get("bootstrap_rule") not in (None, "as asked")}
    )
    ruled = any(resamples_remark(f) for f in fits)
    return f"Intervals in brackets: {'; '.join(words)}." + (
        f" Resamples per group: {'; '.join(rules)}." if ruled and rules else ""
    )


def walton_table(
    walton: list[dict[str, Any]], published: list[dict[str, Any]], colours: Mapping[str, str]
) -> dict[str, Any]:
    """The Walton fits, each cell in ``granudb fit walton``'s words (``fit_view``)."""
    beta, friction, mean_e = WALTON
    return {
        "id": "walton-fits",
        "heading": "Walton fits (figures 4, 6, 9)",
        "note": "Runs folded by the sign of v_T,in; the model (all sticking: Ψ_out = −βΨ_in; "
        "all sliding: Ψ_out = Ψ_in − μ_f(1+e)B; or a split) is the one of smallest BIC = "
        "n ln(S/n) + p ln n (p = 2, 2, 4), and only what it determines is given: β from a "
        "sticking line and μ_f from a sliding line of at least 3 runs each. "
        + bootstrap_note(walton)
        + " The model and split are re-decided in every resample. ē: mean e over all runs "
        "of the group. Published: the values Joseph & Hunt (2004) printed for the same "
        "particle, wall and fluid, as printed (their ± are correlation values of the line "
        "fits, not granudb's intervals).",
        "columns": [
            "group",
            "model (why)",
            "β",
            "μ_f",
            "ē",
            "sticking / sliding runs",
            "published, as printed",
        ],  # fmt: skip
        "rows": [
            [
                group_cell(r, colours),
                walton_model(r),
                value_line(r, beta),
                value_line(r, friction),
                value_line(r, mean_e),
                walton_runs(r),
                published_for(published, r),
            ]
            for r in walton
        ],
    }


def restitution_table(restitution: list[dict[str, Any]]) -> dict:
    """The restitution fits, with the form, its parameter and how the intervals were made
    said from the fits' own records, each cell in ``granudb fit restitution``'s words."""
    first = restitution[0] if restitution else {}
    stokes = stokes_number(first) or "the normal Stokes number St_n"
    parameter = parameter_label(first)
    threshold = (
        " The fitted St_c is the no-rebound threshold of these runs, not the St_c of the "
        "rebound verdict."
        if first.get("parameter_name") == "fitted_critical_stokes"
        else ""
    )
    note = (
        f"The {restitution_model(first)}; Stokes number: {stokes}.{threshold} e_dry ≤ 1, "
        "fixed to the mean e of the group's dry runs where it has any. Without an interval, "
        "± is the asymptotic standard error of the least squares. " + bootstrap_note(restitution)
    )
    return {
        "id": "restitution-fit",
        "heading": "Restitution against Stokes number (figure 5)",
        "note": note.strip(),
        "columns": ["group", "e_dry (source)", parameter, "runs"],
        "rows": [
            [
                group_words(r),
                e_dry_words(r),
                value_line(r, restitution_parameter(r)),
                restitution_runs(r),
            ]
            for r in restitution
        ],  # fmt: skip
    }


def gap_table(gap: list[dict[str, Any]], colours: Mapping[str, str]) -> dict[str, Any]:
    """The gap viscosity fits, each cell in ``granudb fit gap-viscosity``'s words."""
    method = "; ".join(sorted({gap_method(r) for r in gap} - {""})) or "least squares of (5.8)"
    return {
        "id": "gap-viscosity",
        "heading": "Gap viscosity and temperature (figure 14, table 2)",
        "note": f"μ₀ by {method}; the gap temperature from the fluid's μ(T) (the interval's "
        "ends swap: a higher μ₀ is a lower temperature). " + bootstrap_note(gap),
        "columns": ["group", "μ₀", "ambient μ", "gap temperature", "sliding runs used"],
        "rows": [
            [
                group_cell(r, colours),
                value_line(r, GAP[0]),
                ambient_viscosity(r),
                value_line(r, GAP[1]),
                gap_runs(r),
            ]
            for r in gap
        ],
    }


#: A dataset report shows at most this many runs in its own run table (HTML and Markdown);
#: the full table of a larger set is the CSV written beside the report.
RUN_TABLE_LIMIT = 200


def run_frame(frame: Any, branches: Any, fluids: Any = None) -> Any:
    """Every run as the run table lists it (``REPORT_RUN_COLUMNS``, SI, machine names):
    the rows of the CSV beside a report, and the source of its run table. ``fluids``: the
    frame's ``fluid_names``, where the caller has them."""
    runs = frame.reindex(columns=[c for c in REPORT_RUN_COLUMNS if c != "walton_branch"])
    runs["fluid"] = fluid_names(runs["fluid"]) if fluids is None else fluids
    runs.insert(REPORT_RUN_COLUMNS.index("walton_branch"), "walton_branch", branches)
    return runs


def run_table(runs: Any, limit: int = RUN_TABLE_LIMIT) -> dict[str, Any]:
    """The report's table of runs: every run up to ``limit``, else the first ``limit``
    (the CSV beside the report holds them all); numbers for people, "—" for none."""
    shown = runs.head(limit)
    titles = {"walton_branch": "Walton branch", "derivation_note": "assumed (derivation note)"}
    columns = [titles.get(c) or _column_title(c) for c in REPORT_RUN_COLUMNS]
    rows = [
        [_run_cell(value, column) for value, column in zip(row, REPORT_RUN_COLUMNS, strict=True)]
        for row in shown.itertuples(index=False, name=None)
    ]
    return {
        "id": "runs",
        "heading": "Runs",
        "note": "Each run as derived, with the branch its group's Walton fit counts it on "
        "(the classification of every figure and table) and what its derivation assumed.",
        "columns": columns,
        "names": list(REPORT_RUN_COLUMNS),
        "rows": rows,
        "count": len(runs),
        "limit": limit,
        "frame": runs,  # the CSV's rows; ``write_report`` writes them beside a capped table
        "file": None,
    }


def _column_title(column: str) -> str:
    term = TERMS.get(column) or DERIVED_TERMS.get(column)
    if term is None:
        return column.replace("_", " ")
    return f"{term.symbol} ({term.title})" if term.symbol else term.title


def _run_cell(value: Any, column: str) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "—"
    return display(value, column, 3)


def runs_csv(runs: Any) -> bytes:
    """The CSV of every run beside a report: machine names and SI values as stored (the
    shortest text that reads back as the same float, as every CSV granudb writes), text
    quoted, empty where there is no value. Written by Arrow's CSV writer: pandas' took
    longer than the whole report's bound for 100,000 runs. A file for people's
    spreadsheets: a text cell that would run as a formula is prefixed with ``'``
    (``granudb.vocabulary.escaping.spreadsheet_frame``)."""
    table = pyarrow.Table.from_pandas(spreadsheet_frame(runs), preserve_index=False)
    out = pyarrow.BufferOutputStream()
    pyarrow_csv.write_csv(table, out, pyarrow_csv.WriteOptions(quoting_style="needed"))
    return out.getvalue().to_pybytes()  # UTF-8
