"""``granudb pair`` says which method gave each u and shows the 95 % interval (issue 36):
the table, the JSON and the Python API render one record (``propagation_method``,
``low95_<q>``/``high95_<q>``), and a quantity without a stated u has no interval."""

from __future__ import annotations

import json
import math
import unicodedata

import granudb
from granudb.reporting.format import display
from granudb.vocabulary import DERIVED_TERMS

ARGS = ("steel", "Zerodur", "--fluid", "glycerol-37", "--diameter", "12.7 mm",
        "--angle", "30 deg")  # fmt: skip


def test_table_json_and_python_say_the_same_method_and_interval(cli, db: str, monkeypatch) -> None:
    out = cli("pair", *ARGS, "--velocity", "0.35 m/s ± 10 %", "--format", "json", db=db)
    assert out.exit_code == 0, out.stderr
    document = json.loads(out.stdout)
    method = document["propagation_method"]
    # 10 % on the speed bends μ_f of (5.8) past first order's check
    assert method.startswith("Monte Carlo (JCGM 101)") and "lubricated_friction" in method
    python = granudb.pair("steel", "Zerodur", fluid="glycerol-37", diameter="12.7 mm",
                          angle="30 deg", velocity="0.35 m/s ± 10 %", db=db)  # fmt: skip
    assert python["propagation_method"] == method
    assert python["high95_normal_stokes_number"] == document["high95_normal_stokes_number"]
    # the Monte Carlo's interval of A(c) (~ c^16) is skewed upward, St_n's (∝ v) is not
    value = document["friction_integral"]
    low, high = document["low95_friction_integral"], document["high95_friction_integral"]
    assert low < value < high and high - value > 1.15 * (value - low)
    value = document["normal_stokes_number"]
    low, high = document["low95_normal_stokes_number"], document["high95_normal_stokes_number"]
    assert abs((high - value) / (value - low) - 1) < 0.05
    monkeypatch.setenv("COLUMNS", "80")
    table = cli("pair", *ARGS, "--velocity", "0.35 m/s ± 10 %", db=db)
    text = " ".join(table.stdout.split())
    assert "u and 95 % intervals: Monte Carlo (JCGM 101)" in text
    shown = f"95 %: {display(low, 'normal_stokes_number')} – "
    assert shown in text
    # readable at 80 columns (a combining mark, as in η̂, takes no column)
    widths = [sum(not unicodedata.combining(c) for c in line) for line in table.stdout.splitlines()]
    assert max(widths) <= 80


def test_first_order_is_named_and_no_interval_without_u(cli, db: str) -> None:
    out = cli("pair", "glass", "Zerodur", "--fluid", "water", "--diameter", "12.7 mm",
              "--velocity", "0.3 m/s ± 0.5 %", "--format", "json", db=db)  # fmt: skip
    document = json.loads(out.stdout)
    assert document["propagation_method"] == "first order (GUM)"
    # the speed does not reach E*: no u, no interval (null, never 0)
    assert document["u_reduced_modulus_pa"] is None
    assert document["low95_reduced_modulus_pa"] is None
    assert not math.isnan(document["low95_normal_stokes_number"])


def test_the_report_and_the_pair_table_say_the_same_intervals_and_method(cli, db: str) -> None:
    """A scenario report and ``granudb pair`` render one record: each derived quantity's
    95 % interval and the propagation method, in the same words (from the materials'
    stored u here: the report takes no u on the speed)."""
    changed = cli("materials", "update", "steel", "--youngs-modulus", "190 GPa ± 5 %",
                  "--roughness", "23.6 ± 8 nm", db=db)  # fmt: skip
    assert changed.exit_code == 0, changed.stderr
    scenario = {"fluid": "glycerol-37", "diameter": "12.7 mm", "angle": "30 deg",
                "velocity": "0.35 m/s"}  # fmt: skip
    document = granudb.pair("steel", "Zerodur", db=db, **scenario)
    markdown = granudb.report(("steel", "Zerodur"), format="md", db=db, **scenario)
    html = granudb.report(("steel", "Zerodur"), db=db, **scenario)
    table = cli("pair", "steel", "Zerodur", *(f"--{k}={v}" for k, v in scenario.items()), db=db)
    text = " ".join(table.stdout.split())
    method = f"u and 95 % intervals: {document['propagation_method']}"
    assert "(GUM)" in document["propagation_method"]  # the seeded draws: one method, one text
    assert method in markdown and method in html and method in text
    shown = 0
    for name in ("reduced_modulus_pa", "impact_load_n", "film_parameter", "max_pressure_pa"):
        low, high = document[f"low95_{name}"], document[f"high95_{name}"]
        assert low < document[name] < high  # E's u reaches them
        words = f"95 %: {display(low, name)} – {display(high, name)}"
        assert f"({words})" in markdown and words in html and words in text, name
        shown += 1
    # the speed and the viscosity state no u: their quantities show no interval anywhere
    assert math.isnan(document["low95_normal_speed_m_s"])
    title = DERIVED_TERMS["normal_speed_m_s"].title.lower()
    row = next(line for line in markdown.splitlines() if title in line.lower())
    assert "95 %" not in row
    assert shown == 4
