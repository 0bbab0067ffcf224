"""One record, one rendering: the lab report's fit tables say each quantity in exactly
the words ``granudb fit walton|restitution|gap-viscosity`` print for it.

Every record here is made by the real fit on synthetic runs of known truth
(``granudb.analysis.synthetic``), chosen for the awkward cases: a value with its interval,
a value without one and the reason, an interval refused (few runs; a Bayesian interval
refused), a value not determined (with a lower bound), a least-squares standard error, a
fixed e_dry, a Bayesian record whose method states its own level, a resample count other
than the default, and a gap temperature whose interval leaves the fluid's μ(T) data. From
THE SAME record the command's lines (``api.fit_people_view``, what ``granudb fit`` prints)
and the report's table row are built and compared quantity by quantity.
"""

from __future__ import annotations

import html as htmllib
import json
import re

import numpy as np
import pytest

from granudb import api
from granudb.analysis import bayesian, fits
from granudb.analysis.synthetic import (
    measured,
    restitution_runs,
    sliding_runs,
    walton_frame,
)
from granudb.physics.viscosity import TabulatedViscosity
from granudb.reporting import figures, tables
from granudb.vocabulary.escaping import markdown_text

#: A short chain that converges on these 12 runs (autocorrelation time about 15 steps).
SHORT_CHAIN = bayesian.Settings(walkers=16, steps=1200, burn_in=200)

#: Each table's column and the command's line that say the same quantity.
WALTON_PAIRS = {
    "model (why)": "model",
    "β": "β (rotational restitution)",
    "μ_f": "μ_f (sliding friction)",
    "ē": "ē (mean normal restitution)",
    "sticking / sliding runs": "runs (sticking / sliding)",
}
RESTITUTION_PAIRS = {"e_dry (source)": "e_dry (dry restitution)", "runs": "runs"}
GAP_PAIRS = {
    "μ₀": "μ₀ (gap viscosity)",
    "ambient μ": "ambient μ",
    "gap temperature": "gap temperature",
    "sliding runs used": "sliding runs used",
}


def _curve(low: float, high: float) -> TabulatedViscosity:
    temperatures = np.linspace(low, high, 6)
    return TabulatedViscosity(temperatures, 3.0e-3 * np.exp(-0.025 * (temperatures - 20)))


@pytest.fixture(scope="module")
def walton_records() -> list[dict]:
    split = walton_frame(60, seed=1)
    records = fits.walton(split)  # intervals; β determined in 99 % of resamples
    records += fits.walton(split, resamples=303)  # a count asked for: said beside each
    records += fits.walton(walton_frame(8, seed=2))  # all slide: no β; t-intervals
    sticking = walton_frame(30, psi_range=(0.05, 0.2), friction=0.4, noise=0.002, seed=3)
    records += fits.walton(sticking)  # all stick: μ_f's lower bound
    records += fits.walton(walton_frame(4, seed=5))  # neither β nor μ_f
    # three runs on the sticking line of a split: β's interval refused, its standard error
    records += fits.walton(walton_frame(25, seed=6), asymptotic_from=20)
    records += fits.walton(walton_frame(12, seed=5), method="bayes", settings=SHORT_CHAIN)
    return records


@pytest.fixture(scope="module")
def restitution_records() -> list[dict]:
    records = []
    for dry in (0, 1, 5):  # e_dry fitted; fixed to one dry run; fixed, redrawn
        records += fits.restitution(restitution_runs(0.95, "exponential", 35.0, dry=dry))
    records += fits.restitution(restitution_runs(0.95, "exponential", 35.0, n=6))  # profile
    one_st = restitution_runs(0.95, "exponential", 35.0, n=10).assign(normal_stokes_number=50.0)
    records += fits.restitution(one_st)  # not determined
    records += fits.restitution(
        restitution_runs(0.95, "threshold", 20.0, n=25), "threshold", asymptotic_from=20
    )
    records += fits.restitution(restitution_runs(0.95, "exponential", 35.0, n=12),
                                method="bayes", settings=SHORT_CHAIN)  # fmt: skip
    refused = measured(0, n=bayesian.STATED_REFUSED_FROM)  # its Bayesian interval refused
    records += fits.restitution(refused, method="bayes")
    return records


@pytest.fixture(scope="module")
def gap_records() -> list[dict]:
    runs = sliding_runs(1.6e-3, n=30, seed=2)
    records = fits.gap_viscosity(runs, {"glycerol-37": _curve(40.0, 50.0)})  # T's ends out
    records += fits.gap_viscosity(runs, {"glycerol-37": _curve(10.0, 60.0)})
    records += fits.gap_viscosity(runs, {"glycerol-37": None})  # no μ(T): no temperature
    records += fits.gap_viscosity(runs, {}, asymptotic_from=20)
    few = sliding_runs(1.6e-3, n=6, seed=2)
    records += fits.gap_viscosity(few, {"glycerol-37": _curve(10.0, 60.0)})  # t-interval
    records += fits.gap_viscosity(sliding_runs(1.6e-3, n=2, seed=2), {})  # no μ₀
    # 1,500 sliding runs stating no u: the interval refused, the value kept
    records += fits.gap_viscosity(sliding_runs(1.6e-3, n=1500, seed=3), {}, resamples=200)
    return records


def _text(cell) -> str:
    return cell["text"] if isinstance(cell, dict) else cell


#: The command's lines a report table says once, in its note (the same words, checked
#: there); "chain converged": a Bayesian fit's, which a report (bootstrap fits) never has.
IN_NOTE = {
    "walton": {"intervals", "chain converged"},
    "restitution": {"model", "Stokes number", "intervals", "chain converged"},
    "gap_viscosity": {"method", "intervals"},
}


def _compare(kind: str, table: dict, records: list[dict], pairs: dict[str, str]) -> list[str]:
    """Assert every paired cell equals the command's line; the group cell its heading and
    the note holds the command's "intervals" line; the command has no other line. Returns
    every line compared."""
    said = []
    for record, row in zip(records, table["rows"], strict=True):
        heading, lines = api.fit_people_view(kind, record)
        lines = dict(lines)
        cells = {c: _text(v) for c, v in zip(table["columns"], row, strict=True)}
        assert cells["group"] == heading
        assert set(lines) - set(pairs.values()) <= IN_NOTE[kind], set(lines)
        for column, line in pairs.items():
            assert cells[column] == lines[line], (column, record.get("reason"))
            said.append(lines[line])
        if "no interval" not in lines.get("intervals", "no interval"):
            assert lines["intervals"] in table["note"]
        said.append(lines.get("intervals", ""))
    return said


def test_walton_table_says_what_fit_walton_says(walton_records) -> None:
    table = tables.walton_table(walton_records, [], {})
    said = " | ".join(_compare("walton", table, walton_records, WALTON_PAIRS))
    for case in (
        "] (determined in 99% of resamples)",  # a value with its interval, and the share
        "(303 resamples, seed 0)",  # a count other than the default, beside the interval
        "not determined by these runs: all runs slide: β is not determined",
        "(a bound, not a value)",  # μ_f's lower bound: in both, in the μ_f words
        "(standard error; interval not determined: fewer than 10 runs on the sticking line",
        "not determined by these runs: 2 sticking runs (< 3): no β",
        "posterior median and 95 % equal-tailed credible interval",  # its own level
        "t-interval of the per-run values",
    ):
        assert case in said, case
    assert "95% posterior" not in said  # a level the method states is not said twice


def test_restitution_table_says_what_fit_restitution_says(restitution_records) -> None:
    records = restitution_records
    for model in ("exponential", "threshold"):  # one table per form, as a report has
        chosen = [r for r in records if r["model"] == model]
        table = tables.restitution_table(chosen)
        parameter = table["columns"][2]  # "fitted k", "fitted St_c"
        symbol = parameter.removeprefix("fitted ")
        said = _compare("restitution", table, chosen, {**RESTITUTION_PAIRS, parameter: symbol})
        for record in chosen:
            lines = dict(api.fit_people_view("restitution", record)[1])
            assert f"The {lines['model']};" in table["note"] or record is not chosen[0]
            assert f"Stokes number: {lines['Stokes number']}" in table["note"]
        if model == "exponential":
            said_all = " | ".join(said)
            for case in (
                "; source: fitted, bounded 0 ≤ e_dry ≤ 1",
                "(interval not determined: not fitted); source: mean e of the group's 1 dry run "
                "(fixed)",
                "redrawn in the bootstrap",
                "not determined by these runs: St_n must take ≥ 3 distinct values",
                "interval not determined: Bayesian interval refused from "
                f"{bayesian.STATED_REFUSED_FROM:,} runs",
                "profile likelihood",
                "posterior median and 95 % equal-tailed credible interval",
            ):
                assert case in said_all, case


def test_the_figure_caption_says_the_fit_as_its_table_does(restitution_records) -> None:
    """The restitution figure's grey line is named with the words of its table's row: its
    e_dry cell and its parameter cell, for every record with a value."""
    for model in ("exponential", "threshold"):
        chosen = [r for r in restitution_records if r["model"] == model]
        table = tables.restitution_table(chosen)
        for record, row in zip(chosen, table["rows"], strict=True):
            if (
                not isinstance(record.get("parameter"), float)
                or record["parameter"] != record["parameter"]
            ):
                continue  # no value: the figure draws no line
            caption = figures.fit_said(record)
            assert f"e_dry {_text(row[1])};" in caption, (caption, row[1])
            assert f"; {table['columns'][2]} {_text(row[2])}" in caption, (caption, row[2])


def test_gap_table_says_what_fit_gap_viscosity_says(gap_records) -> None:
    table = tables.gap_table(gap_records, {})
    said = " | ".join(_compare("gap_viscosity", table, gap_records, GAP_PAIRS))
    for record in gap_records:  # how μ₀ was fitted: the note says each record's method
        method = dict(api.fit_people_view("gap_viscosity", record)[1])["method"]
        assert method in table["note"].split("; the gap temperature")[0]
    outside = gap_records[0]
    assert np.isnan(outside["gap_temperature_low_c"]) and np.isfinite(outside["gap_temperature_c"])
    for case in (
        "] mPa·s",  # the unit after the interval, as for every quantity with a unit
        "] °C",
        "°C (interval not determined: μ₀'s interval reaches",
        "outside the fluid's μ(T) data (40–50 °C)",
        "not determined by these runs: the fluid has no μ(T) model",
        "not determined by these runs: 2 runs: too few",
        "mPa·s (interval not determined: at 1500 sliding runs",
        "asymptotic normal interval",
    ):
        assert case in said, case


def _html_cells(html: str, table_id: str) -> dict[str, dict[str, str]]:
    """A report table's cells by row (its group cell's text) and column heading."""
    section = html[html.index(f'id="{table_id}"') :]
    section = section[: section.index("</table>")]
    columns = [htmllib.unescape(c) for c in re.findall(r"<th[^>]*>(.*?)</th>", section, re.S)]
    rows = {}
    for row in re.findall(r"<tr>(.*?)</tr>", section, re.S):
        cells = [
            htmllib.unescape(re.sub(r"<[^>]+>", "", c))
            for c in re.findall(r"<td[^>]*>(.*?)</td>", row, re.S)
        ]
        if cells:
            rows[cells[0]] = dict(zip(columns, cells, strict=True))
    return rows


@pytest.mark.parametrize("fmt", ["html", "md"])
def test_the_report_file_says_what_the_commands_print(cli, paper_db, tmp_path, fmt) -> None:
    """End to end: ``granudb report`` and ``granudb fit`` on the same runs; every fit cell
    of the written report (escaped for its format, never bypassed) is the command's line,
    and every such line is printed by the command."""
    out = tmp_path / f"report.{fmt}"
    made = cli("report", "--dataset", "paper", "--format", fmt, "--output", str(out), db=paper_db)
    assert made.exit_code == 0, made.stderr
    text = out.read_text(encoding="utf-8")
    compared = 0
    threshold = {**RESTITUTION_PAIRS, "fitted St_c": "St_c"}  # the report's form
    for command, kind, table_id, pairs, *given in (
        ("walton", "walton", "walton-fits", WALTON_PAIRS),
        ("gap-viscosity", "gap_viscosity", "gap-viscosity", GAP_PAIRS),
        ("restitution", "restitution", "restitution-fit", threshold, "--model", "threshold"),
    ):
        asked = ("fit", command, "--dataset", "paper", *given)
        printed = " ".join(cli(*asked, db=paper_db).stdout.split())
        records = json.loads(cli(*asked, "--format", "json", db=paper_db).stdout)
        cells = _html_cells(text, table_id) if fmt == "html" else {}
        for record in records:
            heading, lines = api.fit_people_view(kind, record)
            lines = dict(lines)
            for column, line in pairs.items():
                words = lines[line]
                assert " ".join(f"{line} {words}".split()) in printed  # the command says it
                if fmt == "html":
                    assert cells[heading][column] == words, (heading, column)
                else:
                    assert f"| {markdown_text(words)} |" in text, (heading, column)
                compared += 1
    assert compared >= 25
