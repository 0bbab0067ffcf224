"""Issues 13 and 15: what the physics now knows, said in words by the verdicts (terminal
and reports), shown in the dataset report's fit tables and figures. Each test fails on
the report code before these words existed."""

from __future__ import annotations

import math
import re
from pathlib import Path

from granudb.reporting import tables
from granudb.reporting.values import qualified_value
from granudb.reporting.verdicts import verdicts
from granudb.vocabulary import DERIVED_TERMS


def _scenario(**changes):
    """A derived row of an immersed scenario (steel on Zerodur), film and in range."""
    row = {
        "normal_stokes_number": 300.0,
        "added_mass_stokes_number": 320.0,
        "rebound_expected": True,
        "predicted_restitution": 0.97 * math.exp(-35 / 320.0),
        "composite_roughness_m": 28e-9,
        "elastic_length_m": 100e-9,
        "min_gap_m": 100e-9 / 3,
        "film_parameter": (100e-9 / 3) / 28e-9,
        "roughness_exceeds_gap": False,
        "roughness_regime": "uncertain",
        "lubricated_friction": 0.02,
        "lubricated_friction_state": "in_range",
        "friction_coefficient_used": 0.02,
        "maw_psi_in": 12.0,
        "maw_chi": 1.5,
        "tangential_regime": "gross_slip",
        "quasi_static_ratio": 6e-4,
        "quasi_static_valid": True,
        "max_pressure_pa": 1.4e9,
        "yield_speed_m_s": math.nan,
        "normal_speed_m_s": 0.3,
        "elastic_state": "unknown",
    }
    row.update(changes)
    return row


def _by_key(rows, **kwargs):
    return {v.key: v for v in verdicts(rows, 10.0, **kwargs)}


def _no_nan(found) -> None:
    for verdict in found.values():
        assert not re.search(r"\bnan\b", verdict.text, re.I), verdict.text
        assert not re.search(r"\binf\b", verdict.text, re.I), verdict.text


def test_roughness_verdict_has_three_states_consistent_with_table() -> None:
    # Λ = 1.19: before, the verdict said "mixed lubrication" while the table defined 1–3
    # as mixed and the map called Λ > 1 "full film"; now all three say "uncertain".
    found = _by_key(_scenario())
    rough = found["roughness_regime"]
    assert rough.raised and "uncertain" in rough.name
    assert "mixed" not in rough.text and "full film" not in rough.text
    assert "x₁/4 … x₁/3" in rough.text
    table = DERIVED_TERMS["film_parameter"].description
    assert "uncertain" in table and "mixed" not in table and "4/3" in table
    assert "uncertain" in qualified_value(_scenario(), "roughness_regime")
    film = _by_key(_scenario(roughness_regime="film", film_parameter=2.0))["roughness_regime"]
    assert not film.raised and "film" in film.name
    contact = _by_key(_scenario(roughness_regime="asperity_contact", film_parameter=0.6))
    assert (
        contact["roughness_regime"].raised
        and "asperity contact" in contact["roughness_regime"].name
    )


def test_friction_above_its_bound_is_outside_the_range_not_a_prediction() -> None:
    row = _scenario(
        roughness_regime="film",
        lubricated_friction=169.0,
        lubricated_friction_state="above_limit",
        friction_coefficient_used=0.1,
    )
    found = _by_key(row)
    friction = found["lubricated_friction_state"]
    assert friction.raised
    assert "outside the model's range, not used" in friction.text
    assert "not a prediction" in friction.text
    assert "cap" in found["tangential_regime"].text
    cell = qualified_value(row, "lubricated_friction")
    assert cell.startswith("outside the model's range, not used")


def test_water_missing_pressure_coefficient_is_named_and_regime_explained() -> None:
    row = _scenario(
        lubricated_friction=math.nan,
        lubricated_friction_state="no_pressure_coefficient",
        friction_coefficient_used=0.1,
        maw_psi_in=3.12,
        tangential_regime="undetermined",
        eta_hat_pa_inv=math.nan,
    )
    found = _by_key(row, fluid_name="water")
    friction = found["lubricated_friction_state"]
    assert friction.raised and "water has no pressure–viscosity coefficient" in friction.text
    assert "Decided" in friction.text
    regime = found["tangential_regime"]
    assert regime.raised and regime.text.startswith("undetermined")
    assert "slip, then stick" in regime.text and "gross slip" in regime.text
    assert "no pressure–viscosity coefficient" in qualified_value(row, "eta_hat_pa_inv")
    _no_nan(found)


def test_yield_exceeded_is_a_raised_verdict_with_the_yield_speed() -> None:
    row = _scenario(
        elastic_state="yield_exceeded",
        yield_speed_m_s=0.4205,
        normal_speed_m_s=5.0,
        max_pressure_pa=4.07e9,
        quasi_static_valid=False,
    )
    steel = {"name": "steel", "yield_stress_pa": 1.0e9}
    zerodur = {"name": "Zerodur", "yield_stress_pa": None}
    found = _by_key(row, materials=(steel, zerodur))
    verdict = found["elastic_state"]
    assert verdict.raised and "above the onset of yield (V_y = 420 mm/s" in verdict.text
    assert "outside their range" in verdict.text
    hertz = found["quasi_static_valid"]
    assert hertz.raised and "yield" in hertz.text
    _no_nan(found)


def test_unknown_yield_stress_is_said_in_words_with_a_brittle_note() -> None:
    """The brittle note follows the stored brittleness, never a missing yield stress."""
    found = _by_key(
        _scenario(),
        materials=(
            {"name": "glass", "yield_stress_pa": None, "brittleness": "brittle"},
            {"name": "PTFE"},
        ),
    )
    verdict = found["elastic_state"]
    assert "yield stress not known for glass and PTFE" in verdict.text
    assert "glass is stored as brittle" in verdict.text and "Hertzian cone cracks" in verdict.text
    ductile = _by_key(_scenario(), materials=({"name": "PTFE"}, {"name": "PEEK"}))
    assert "brittle" not in ductile["elastic_state"].text
    assert qualified_value(_scenario(), "yield_speed_m_s") == "not known (no yield stress)"
    _no_nan(found)


def test_no_nan_reaches_any_sentence() -> None:
    nan = math.nan
    row = {k: nan for k in _scenario()}
    row.update(
        roughness_regime="film",
        lubricated_friction_state="in_range",
        tangential_regime="stick",
        elastic_state="unknown",
    )
    _no_nan(_by_key(row))


def test_predicted_restitution_names_its_form_and_stokes_number() -> None:
    found = _by_key(_scenario())
    verdict = found["predicted_restitution"]
    assert "e ≈ 0.87" in verdict.text
    assert "exp(−35/St)" in verdict.text and "Legendre" in verdict.text
    assert "added-mass Stokes number" in verdict.text and "(ρ_p + ρ_f/2)" in verdict.text
    none = _by_key(_scenario(rebound_expected=False, predicted_restitution=0.0))
    assert none["predicted_restitution"].text.startswith("e = 0: no rebound expected")


def test_terminal_pair_shows_the_new_verdicts(cli, db) -> None:
    result = cli(
        "pair", "steel", "Zerodur", "--fluid", "water", "--diameter", "12.7 mm",
        "--velocity", "0.3 m/s", "--angle", "20 deg", db=db,
    )  # fmt: skip
    assert result.exit_code == 0, result.stderr
    out = " ".join(result.stdout.split())
    assert "Predicted restitution: e ≈" in out and "Legendre" in out
    assert "water has no pressure–viscosity coefficient" in out
    assert "undetermined" in out and "yield stress not known" in out
    verdict_lines = out[out.index("Verdicts") :]
    assert not re.search(r"\bnan\b", verdict_lines, re.I)
    assert "not known (no yield stress)" in out  # V_y's value cell, in words


def test_pair_report_shows_predicted_restitution_and_three_state_map(
    cli, db, tmp_path: Path
) -> None:
    out = tmp_path / "pair.html"
    result = cli(
        "report", "--pair", "steel", "Zerodur", "--fluid", "water", "--diameter", "12.7 mm",
        "--velocity", "0.3 m/s", "--angle", "20 deg", "--output", str(out), db=db,
    )  # fmt: skip
    assert result.exit_code == 0, result.stderr
    html = out.read_text(encoding="utf-8")
    assert "Predicted restitution:</strong>" in html and "Legendre" in html
    assert "uncertain (x₁/4 &lt; σ ≤ x₁/3" in html  # the regime map's legend and caption
    assert "full film" not in html and "mixed lubrication" not in html
    references = html[html.index("<h3>References</h3>") :]
    for doi in (
        "10.1016/j.ces.2005.12.018",
        "10.1115/1.3453342",
        "10.1017/CBO9781139171731",
        "10.1017/S0022112086002392",
    ):  # Legendre, Bair & Winer, Johnson, Davis
        assert references.count(doi) == 1, doi


# --- the dataset report: fits said honestly ------------------------------------------


def _walton_row(**changes):
    row = {
        "dataset": "d",
        "particle": "steel",
        "wall": "Zerodur",
        "fluid": "dry",
        "model": "sticking",
        "model_reason": "sticking: smallest BIC -50 (next sliding -10; BIC = n ln(S/n) + p ln n, "
        "p = 2 sticking, 2 sliding, 4 split)",
        "bic_sticking": -50.0,
        "bic_sliding": -10.0,
        "bic_split": math.inf,
        "model_support_sticking": 0.97,
        "interval_method": "studentized bootstrap (bootstrap-t) over runs",
        "rotational_restitution_interval_method": "studentized bootstrap (bootstrap-t) over runs",
        "rotational_restitution": 0.34,
        "rotational_restitution_low": 0.31,
        "rotational_restitution_high": 0.37,
        "rotational_restitution_determined": 1.0,
        "sliding_friction": math.nan,
        "sliding_friction_low": math.nan,
        "sliding_friction_high": math.nan,
        "sliding_friction_lower_bound": 0.091,
        "normal_restitution_mean": 0.97,
        "normal_restitution_low": 0.96,
        "normal_restitution_high": 0.98,
        "n_sticking": 8,
        "n_sliding": 0,
        "confidence_level": 0.95,
        "bootstrap_resamples": 1000,
        "bootstrap_seed": 0,
        "reason": "all runs stick: μ_f is not determined (sliding_friction_lower_bound is a bound)",
    }
    row.update(changes)
    return row


def test_walton_table_says_not_determined_and_labels_the_bound() -> None:
    published = [
        {"particle": "steel", "wall": "Zerodur", "fluid": None, "quantity": "sliding_friction",
         "value_as_printed": "μ_f = 0.11 ± 0.003", "source": "jh", "source_locator": "§3",
         "condition": "dry (air)"},
    ]  # fmt: skip
    table = tables.walton_table([_walton_row()], published, {"steel/Zerodur dry": "#000"})
    row = table["rows"][0]
    assert row[1].startswith("sticking: smallest BIC") and "97%" in row[1]
    assert row[2] == "0.34 [0.31, 0.37]"
    assert row[3].startswith("not determined by these runs: all runs stick")
    assert "μ_f ≥ 0.091 (a bound, not a value)" in row[3]
    assert "0.091" not in row[3].split("Lower bound")[0]
    assert "μ_f = 0.11 ± 0.003" in row[6]  # the paper's ± as printed, beside ours
    assert "95% studentized bootstrap (bootstrap-t) over runs" in table["note"]
    assert "1000 resamples, seed 0" in table["note"]
    assert table["note"].count("1000 resamples") == 1


def test_gap_table_shows_interval_and_reason() -> None:
    fitted = {"dataset": "d", "particle": "steel", "wall": "Zerodur", "fluid": "glycerol-37",
              "gap_viscosity_pa_s": 1.6e-3, "gap_viscosity_low_pa_s": 1.5e-3,
              "gap_viscosity_high_pa_s": 1.7e-3, "gap_temperature_c": 45.0,
              "gap_temperature_low_c": 43.0, "gap_temperature_high_c": 47.0,
              "ambient_viscosity_pa_s": 3.1e-3, "n_runs": 5, "bootstrap_resamples": 1000,
              "bootstrap_seed": 0, "confidence_level": 0.95, "reason": "",
              "interval_method": "studentized bootstrap (bootstrap-t) over runs"}  # fmt: skip
    reason = "the fluid has no pressure–viscosity coefficient: (5.8) needs η̂ = C/16"
    empty = {**fitted, "fluid": "water", "gap_viscosity_pa_s": math.nan, "n_runs": 0,
             "reason": reason}  # fmt: skip
    table = tables.gap_table([fitted, empty], {})
    assert table["rows"][0][1] == "1.60 [1.50, 1.70] mPa·s"  # the unit after the interval
    assert table["rows"][0][3] == "45.0 [43.0, 47.0] °C"
    assert table["rows"][1][1].startswith("not determined by these runs: the fluid has no")
    assert "1000 resamples, seed 0" in table["note"]


def test_restitution_table_names_e_dry_source_and_fitted_st_c() -> None:
    fit = {"dataset": "d", "particle": "glass", "wall": "Zerodur", "e_dry": 0.968,
           "e_dry_stderr": math.nan, "e_dry_source": "mean e of the group's 10 dry runs (fixed)",
           "parameter": 33.0, "parameter_stderr": 3.0, "n_runs": 10, "reason": "",
           "stokes_number": "St_n", "model": "threshold",
           "parameter_name": "fitted_critical_stokes"}  # fmt: skip
    empty = {**fit, "e_dry": math.nan, "parameter": math.nan, "reason": "St_n must take ≥ 2"}
    table = tables.restitution_table([fit, empty])
    assert (
        "fitted St_c" in table["columns"]
        and "not the St_c of the rebound verdict" in (table["note"])
    )
    assert "mean e of the group's 10 dry runs" in table["rows"][0][1]
    assert table["rows"][1][1] == "not determined by these runs: St_n must take ≥ 2"


def test_dataset_report_shows_measured_e_against_predicted_curve(
    cli, paper_db, tmp_path: Path
) -> None:
    out = tmp_path / "paper.html"
    result = cli("report", "--dataset", "paper", "--output", str(out), db=paper_db)
    assert result.exit_code == 0, result.stderr
    html = out.read_text(encoding="utf-8")
    figure = html[html.index('id="fig-restitution-figure"') :]
    figure = figure[: figure.index("</figure>")]
    words = " ".join(re.sub(r"<[^>]+>", " ", figure).split())  # a long legend label wraps
    assert "predicted, e_dry exp(−35/St)" in words and "Legendre" in figure
    assert "fitted St_c" in figure
    walton = html[html.index('id="walton-fits"') :]
    walton = walton[: walton.index("</table>")]
    assert "not determined by these runs" in walton  # steel in glycerol-37: all slide
    assert "smallest BIC" in walton and "seed 0" in walton
    assert not re.search(r"\bnan\b", html.split("<svg")[0], re.I)
