"""The fit tables of a dataset report, with published values on the right group.

A cell is a string, or a dict ``{"text", "colour"}`` for a group name shown with the
colour its points have in every figure. The fits say what their data determine
(docs/physics.md §14): a parameter that is not determined is shown as "not determined by these
runs" with the reason, never as a number; a μ_f lower bound is labelled as a bound;
intervals are granudb's bootstrap intervals (how they were made is said once, in the
table's note), and the paper's ± is shown as printed beside them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from granudb.analysis.fits import CONFIDENCE_LEVEL
from granudb.analysis.walton_bootstrap import DEFAULT_RESAMPLES
from granudb.lazy import pyarrow, pyarrow_csv
from granudb.reporting.fit_view import GAP, value_line
from granudb.reporting.format import display, interval, is_number, plus_minus
from granudb.reporting.groups import fluid_name, fluid_names, group_label
from granudb.vocabulary import DERIVED_TERMS, TERMS
from granudb.vocabulary.escaping import spreadsheet_frame
from granudb.vocabulary.listings import REPORT_RUN_COLUMNS

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


NOT_DETERMINED = "not determined by these runs"


def _reason_for(reason: str, symbol: str) -> str:
    """The part of a fit's reason about ``symbol`` (β or μ_f); all of it if none is."""
    reason = reason.replace("(sliding_friction_lower_bound is a bound)", "(a lower bound is shown)")
    parts = [p for p in reason.split("; ") if p]
    mine = [p for p in parts if symbol in p]
    return "; ".join(mine or parts)


def parameter_cell(fit: Mapping[str, Any], name: str, symbol: str) -> str:
    """β or μ_f with its bootstrap interval, or "not determined by these runs" and why."""
    value = fit.get(name)
    if is_number(value):
        text = interval(value, fit.get(f"{name}_low"), fit.get(f"{name}_high"))
        share = fit.get(f"{name}_determined")
        if is_number(share) and share < 0.995:
            text += f" (determined in {share:.0%} of resamples)"
        return text + resamples_said(fit)
    text = NOT_DETERMINED
    why = _reason_for(str(fit.get("reason") or ""), symbol)
    if why:
        text += f": {why}"
    bound = fit.get("sliding_friction_lower_bound")
    if name == "sliding_friction" and is_number(bound):
        text += (
            f". Lower bound (2.10) at the largest Ψ_in: μ_f ≥ {bound:.2g} (a bound, not a value)"
        )
    return text


def model_cell(fit: Mapping[str, Any]) -> str:
    """The Walton model chosen and why (BIC), with its bootstrap support."""
    model = fit.get("model")
    if not model:
        return f"none: {fit.get('reason') or 'too few runs'}"
    bic = {m: fit.get(f"bic_{m}") for m in ("sticking", "sliding", "split")}
    others = [f"{m} {bic[m]:.4g}" for m in bic if m != model and is_number(bic[m])]
    text = f"{model}: smallest BIC, {bic[model]:.4g}" if is_number(bic[model]) else str(model)
    if others:
        text += f" (vs {', '.join(others)})"
    support = fit.get(f"model_support_{model}")
    if is_number(support):
        text += f"; chosen in {support:.0%} of resamples"
    return text


def resamples_said(fit: Mapping[str, Any]) -> str:
    """Beside an interval made with other than the default count (a large group under the
    resample rule, or a count asked for): that count and the seed."""
    count = fit.get("bootstrap_resamples")
    if not count or count == DEFAULT_RESAMPLES:
        return ""
    return f" ({count} resamples, seed {fit.get('bootstrap_seed')})"


def interval_method(fit: Mapping[str, Any]) -> str:
    """How a fit's intervals were made, as its own record says (``interval_method``)."""
    return str(fit.get("interval_method") or "method not recorded")


def bootstrap_note(fits: list[dict[str, Any]]) -> str:
    """How the intervals were made, said once: level, resamples and seed, and the resample
    rule when a large group was resampled fewer times."""
    made = sorted(
        {(f.get("confidence_level") or CONFIDENCE_LEVEL, interval_method(f),
          f.get("bootstrap_resamples"), f.get("bootstrap_seed"))
         for f in fits if f.get("bootstrap_resamples") and f.get("fit_method") != "bayes"}
    )  # fmt: skip
    words = [
        f"{level:.0%} intervals, {method}, {resamples} resamples, seed {seed}"
        for level, method, resamples, seed in made
    ]
    # a posterior's interval says its own level and sampler (its record's interval_method)
    words += sorted({interval_method(f) for f in fits if f.get("fit_method") == "bayes"})
    # an asymptotic interval (no resamples, bootstrap_resamples 0) says its own method
    words += sorted(
        {f"{f.get('confidence_level') or CONFIDENCE_LEVEL:.0%} intervals, {interval_method(f)}"
         for f in fits if f.get("bootstrap_resamples") == 0 and f.get("fit_method") != "bayes"
         and "no interval" not in interval_method(f)}
    )  # fmt: skip
    if not words:
        return ""
    rules = sorted(
        {f["bootstrap_rule"] for f in fits if f.get("bootstrap_rule") not in (None, "as asked")}
    )
    ruled = any(resamples_said(f) for f in fits)
    return f"Intervals in brackets: {'; '.join(words)}." + (
        f" Resamples per group: {'; '.join(rules)}." if ruled and rules else ""
    )


def walton_table(
    walton: list[dict[str, Any]], published: list[dict[str, Any]], colours: Mapping[str, str]
) -> dict[str, Any]:
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
                model_cell(r),
                parameter_cell(r, "rotational_restitution", "β"),
                parameter_cell(r, "sliding_friction", "μ_f"),
                interval(
                    r.get("normal_restitution_mean"),
                    r.get("normal_restitution_low"),
                    r.get("normal_restitution_high"),
                ),
                f"{r.get('n_sticking', '—')} / {r.get('n_sliding', '—')}",
                published_for(published, r),
            ]
            for r in walton
        ],
    }


def _restitution_cells(r: Mapping[str, Any]) -> tuple[str, str]:
    if not is_number(r.get("e_dry")):
        why = r.get("reason") or "the fit gave no value"
        return f"{NOT_DETERMINED}: {why}", NOT_DETERMINED
    source = r.get("e_dry_source") or "fitted"
    if is_number(r.get("e_dry_stderr")):
        e_dry = f"{plus_minus(r['e_dry'], r['e_dry_stderr'])}: {source}"
    else:
        e_dry = f"{r['e_dry']:.3g}: {source}"
    return e_dry, fit_cell(r, "parameter")


#: What a restitution form's parameter is called in a table.
PARAMETER_LABELS = {"fitted_critical_stokes": "fitted St_c", "k": "fitted k"}


def model_said(fit: Mapping[str, Any]) -> str:
    """A restitution fit's form in words, from its record: name, formula, citation and
    why it was chosen ("The threshold form e = … (…), the report's choice, …")."""
    words = f"The {fit.get('model', 'fitted')} form {fit.get('formula', '')}"
    if fit.get("citation"):
        words += f" ({fit['citation']})"
    if fit.get("model_reason"):
        words += f", {fit['model_reason']}"
    return words


def restitution_table(restitution: list[dict[str, Any]]) -> dict:
    """The restitution fits, with the form, its parameter and how the intervals were made
    said from the fits' own records."""
    first = restitution[0] if restitution else {}
    stokes = first.get("stokes_number") or "the normal Stokes number St_n"
    parameter = PARAMETER_LABELS.get(first.get("parameter_name", ""), "fitted parameter")
    threshold = (
        " The fitted St_c is the no-rebound threshold of these runs, not the St_c of the "
        "rebound verdict."
        if first.get("parameter_name") == "fitted_critical_stokes"
        else ""
    )
    note = (
        f"{model_said(first)}; Stokes number: {stokes}.{threshold} e_dry ≤ 1, fixed to the "
        "mean e of the group's dry runs where it has any. Without an interval, ± is the "
        "asymptotic standard error of the least squares. " + bootstrap_note(restitution)
    )
    return {
        "id": "restitution-fit",
        "heading": "Restitution against Stokes number (figure 5)",
        "note": note.strip(),
        "columns": ["group", "e_dry (source)", parameter, "runs"],
        "rows": [
            [
                f"{r['dataset']}: {r['particle']}/{r['wall']}",
                *_restitution_cells(r),
                str(r.get("n_runs", "—")),
            ]
            for r in restitution
        ],  # fmt: skip
    }


def _gap_cells(r: Mapping[str, Any]) -> tuple[str, str]:
    reason = r.get("reason") or r.get("note") or "not computed"
    mu0 = r.get("gap_viscosity_pa_s")
    if not is_number(mu0):
        return f"{NOT_DETERMINED}: {reason}", "not determined"
    low, high = r.get("gap_viscosity_low_pa_s"), r.get("gap_viscosity_high_pa_s")
    scaled = [v * 1e3 if is_number(v) else v for v in (mu0, low, high)]
    viscosity = f"{interval(*scaled)} mPa·s" + resamples_said(r)
    t = r.get("gap_temperature_c")
    if not is_number(t):
        return viscosity, f"not determined: {reason}"
    low_t, high_t = r.get("gap_temperature_low_c"), r.get("gap_temperature_high_c")
    if not (is_number(low_t) and is_number(high_t)):  # why, in the fit's words
        return viscosity, value_line(r, GAP[1])  # as the command's line says it
    return viscosity, f"{interval(t, low_t, high_t)} °C"


def gap_table(gap: list[dict[str, Any]], colours: Mapping[str, str]) -> dict[str, Any]:
    method = next((r["method"] for r in gap if r.get("method")), "least squares of (5.8)")
    return {
        "id": "gap-viscosity",
        "heading": "Gap viscosity and temperature (figure 14, table 2)",
        "note": f"μ₀ by {method}; the gap temperature from the fluid's μ(T) (the interval's "
        "ends swap: a higher μ₀ is a lower temperature). " + bootstrap_note(gap),
        "columns": ["group", "μ₀", "ambient μ", "gap temperature", "sliding runs used"],
        "rows": [
            [
                group_cell(r, colours),
                _gap_cells(r)[0],
                display(r.get("ambient_viscosity_pa_s"), "viscosity_pa_s"),
                _gap_cells(r)[1],
                str(r.get("n_runs", "—")),
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
