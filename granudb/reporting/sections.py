"""The report's text blocks: property tables with sources, the scenario, derived
quantities with symbols and units, and the roughness flag.

Labels are for people (``E*, reduced modulus``) and keep the machine name beside them
(``reduced_modulus_pa``, shown small and as a tooltip), so a reader can find the same
number in JSON or CSV output.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from granudb.reporting.format import display, engineering, is_number, unicode_math
from granudb.reporting.values import interval_text, qualified_value
from granudb.reporting.verdicts import GAP_DEFINITION, roughness_verdict
from granudb.scenario.dry_values import material_dry_source
from granudb.scenario.pair import TARGET_WORDS
from granudb.vocabulary import DERIVED_TERMS, MATERIAL_PROPERTIES, TERMS

#: A material's stored properties, in the catalogue's own order.
PROPERTY_COLUMNS = MATERIAL_PROPERTIES


def _title(column: str) -> str:
    term = TERMS.get(column) or DERIVED_TERMS.get(column)
    return term.title if term else column.replace("_", " ")


def _source(record: dict[str, Any]) -> str:
    key = record.get("source")
    if not key:
        return "—"
    where = f", {record['source_locator']}" if record.get("source_locator") else ""
    return f"{key}{where}"  # the full citation is in the references


def _row(label: str, value: str, source: str, name: str | None = None) -> dict[str, Any]:
    return {"label": label, "value": value, "source": source, "name": name, "symbol": None}


#: The material's own dry values: their source is the material's dry provenance.
DRY_COLUMNS = ("dry_restitution", "dry_friction")


def material_section(
    role: str, record: dict[str, Any], used: Mapping[str, Any] | None = None
) -> dict[str, Any]:
    """A material's stored properties, each with where it comes from: the entry's source
    and locator, and for its own dry e and μ the provenance ``materials show`` gives
    (``material_dry_source``). With ``used`` (a pair's ``DryValues.record()``), a dry
    value the pair does not use says which value applies to the pair instead."""
    source = _source(record)
    rows = []
    for column in PROPERTY_COLUMNS:
        note = source
        if column == "shear_modulus_pa" and record.get("shear_modulus_derived"):
            note = "derived: G = E / (2(1 + ν))"
        elif column in DRY_COLUMNS:
            note = material_dry_source(record)
            if used is not None and is_number(record.get(column)):
                note += _which_applies(record, column, used)
        rows.append(_row(_title(column), display(record.get(column), column), note, column))
    return {"heading": f"{role}: {record['name']}", "rows": rows + _conditions(record, source)}


#: The heading of a pair report's block of the dry values it uses.
DRY_USED_HEADING = "Dry values used for the pair"


def _which_applies(record: Mapping[str, Any], column: str, used: Mapping[str, Any]) -> str:
    """What a material's own dry value is to the pair: the one used, or not."""
    if used[f"{column}_basis"] == "materials" and used[column] == record[column]:
        return f". {record['name']}'s own value: the one this pair uses"
    basis = BASIS_WORDS.get(used[f"{column}_basis"], used[f"{column}_basis"])
    return (
        f". {record['name']}'s own value; this pair uses {display(used[column], column)}, "
        f"{basis} (see {DRY_USED_HEADING.lower()})"
    )


#: A dry value's basis in words.
BASIS_WORDS = {
    "pair": "measured for the pair",
    "materials": "from the two materials' own values",
    "borrowed": "borrowed",
}


#: Each dry value of the pair: its record's prefix and label.
_DRY_USED = (
    ("dry_restitution", "e_dry, dry restitution"),
    ("dry_friction", "μ_dry, dry friction"),
    ("immersed_friction", "μ where asperities touch in a liquid"),
)


def dry_used_section(pair: str, used: Mapping[str, Any]) -> dict[str, Any]:
    """The dry e and μ every prediction of ``pair`` uses, each with its basis and source
    as ``granudb pair`` and ``pairs show`` give them (``DryValues.record()``)."""
    rows = [
        _row(
            label,
            display(used[name], name),
            f"{used[f'{name}_basis']}: {used[f'{name}_source']}",
            name,
        )  # fmt: skip
        for name, label in _DRY_USED
    ]
    return {"heading": f"{DRY_USED_HEADING}: {pair}", "rows": rows}


def _conditions(record: dict[str, Any], source: str) -> list[dict[str, Any]]:
    """The conditions of an entry's values (temperature, method) as its source gives
    them: one row, or none when not stated."""
    text = record.get("conditions")
    return [_row(_title("conditions"), text, source, "conditions")] if text else []


def fluid_section(record: dict[str, Any], state: Any | None = None) -> dict[str, Any]:
    """A fluid's properties; with ``state``, the viscosity and density actually used."""
    source = _source(record)
    rows = []
    if state is not None:
        rows += [
            _row(
                "Viscosity used",
                display(state.viscosity_pa_s, "viscosity_pa_s"),
                state.basis,
                "viscosity_pa_s",
            ),
            _row(
                "Density used",
                display(state.density_kg_m3, "density_kg_m3"),
                record.get("density_source") or source,
                "density_kg_m3",
            ),
            _row(
                "Temperature",
                display(state.temperature_c, "temperature_c"),
                "given" if state.basis.startswith("interpolated") else "reference",
                "temperature_c",
            ),
        ]
    else:
        rows += [
            _row(
                "Density",
                display(record.get("reference_density_kg_m3"), "density_kg_m3"),
                record.get("density_source") or source,
                "reference_density_kg_m3",
            ),
            _row(
                "Reference temperature",
                display(record.get("reference_temperature_c"), "temperature_c"),
                source,
                "reference_temperature_c",
            ),
        ]
    rows += [
        _row(
            "Reference viscosity",
            display(record["reference_viscosity_pa_s"], "viscosity_pa_s"),
            source,
            "reference_viscosity_pa_s",
        ),
        _row(
            "Pressure–viscosity coefficient C",
            display(record.get("pressure_viscosity_pa_inv"), "pressure_viscosity_pa_inv"),
            record.get("pressure_viscosity_source") or "—",
            "pressure_viscosity_pa_inv",
        ),
        _row(
            "Glycerol mass fraction",
            display(record.get("glycerol_mass_fraction"), "glycerol_mass_fraction"),
            source,
            "glycerol_mass_fraction",
        ),
    ]
    return {"heading": f"Fluid: {record['name']}", "rows": rows + _conditions(record, source)}


def unit_label(name: str) -> str:
    """The unit a person reads for a derived column (``GPa`` is in the value; here the
    SI unit or "–" for a number)."""
    term = DERIVED_TERMS.get(name)
    return term.unit if term and term.unit else "–"


def derived_rows(derived: dict[str, Any]) -> list[dict[str, Any]]:
    """Every derived quantity present, as symbol, title, value with unit, its 95 % interval
    (``interval_text``; "" without u) and relation."""
    rows = []
    for name, term in DERIVED_TERMS.items():
        if name not in derived or name == "incidence_angle_rad":
            continue
        rows.append(
            {
                "symbol": term.symbol or name,
                "label": f"{term.symbol}, {term.title.lower()}" if term.symbol else term.title,
                "title": term.title.lower(),
                "name": name,
                "unit": unit_label(name),
                "value": qualified_value(derived, name),
                "interval": interval_text(derived, name),
                "relation": unicode_math(term.description),
            }
        )
    return rows


def scenario_rows(inputs: dict[str, Any], assumed: set[str]) -> list[dict[str, Any]]:
    """The scenario's inputs, each marked given or assumed (not given: a default)."""
    rows = []
    scenario: tuple[tuple[str, str, str | None], ...] = (
        ("diameter_m", "Particle diameter", "diameter_m"),
        ("wall_diameter_m", "Second sphere diameter", "diameter_m"),
        ("target", "Target", None),
        ("impact_speed_m_s", "Impact speed", "impact_speed_m_s"),
        ("incidence_angle_rad", "Incidence angle", "incidence_angle_rad"),
    )
    for name, label, column in scenario:
        value = inputs.get(name)
        if value is None and name == "wall_diameter_m":
            continue
        how = "assumed (not given; granudb's default)" if name in assumed else "given"
        if name == "target" and value == "wall":
            how = "no second sphere given"
        rows.append(
            {
                "symbol": None,
                "label": label,
                "name": name,
                "unit": "",
                "value": TARGET_WORDS[str(value)] if column is None else display(value, column),
                "relation": how,
            }  # fmt: skip
        )
    return rows


def pair_flag(
    derived: dict[str, Any], immersed: bool, materials: Sequence[Mapping[str, Any]] = ()
) -> dict[str, Any]:
    """The prominent flag of a scenario: σ against Davis's band of the gap, with Λ
    (``materials``, the particle and wall records, name a roughness not stated)."""
    verdict = roughness_verdict(derived, immersed, materials)
    headlines = {
        "Roughness exceeds the gap: asperity contact": (
            "Roughness exceeds the EHD gap (σ > x₁/3): asperity contact, dry-like friction expected"
        ),
        "Roughness within the gap's uncertainty: uncertain": (
            "Roughness within the uncertainty of the EHD gap (x₁/4 < σ ≤ x₁/3): asperity "
            "contact uncertain"
        ),
    }
    return {"id": "roughness-flag", "raised": verdict.raised,
            "headline": headlines.get(verdict.name, verdict.name),
            "detail": verdict.text}  # fmt: skip


def _regimes(frame: Any) -> np.ndarray:
    """Each run's roughness regime (three states); older frames: from σ > h_m."""
    if "roughness_regime" in frame:
        return frame["roughness_regime"].to_numpy(dtype=object)
    rough = frame["roughness_exceeds_gap"].fillna(False).astype(bool).to_numpy()
    return np.where(rough, "asperity_contact", "film").astype(object)


def dataset_flag(frame: Any) -> dict[str, Any]:
    """The prominent flag of a set of runs: how many immersed runs are in asperity contact
    or uncertain (Davis's band h_m = x₁/4 … x₁/3)."""
    wet = frame["fluid"].notna().to_numpy()
    regimes = _regimes(frame)[wet]
    rough = int(np.sum(regimes == "asperity_contact"))
    unsure = int(np.sum(regimes == "uncertain"))
    unstated = int(np.sum(regimes == "not_stated"))  # a material's roughness not stated
    raised = bool(rough or unsure or unstated)
    # Only the two columns read below (a copy of every column of a million runs was a
    # report's largest transient memory).
    immersed = frame.loc[wet, ["composite_roughness_m", "film_parameter"]]
    if immersed.empty:
        detail = "All runs are dry."
    else:
        sigma = immersed["composite_roughness_m"].astype(float)
        film = immersed["film_parameter"].to_numpy(float)
        span = (
            f"σ from {engineering(float(sigma.min()), 'm', 3)} to "
            f"{engineering(float(sigma.max()), 'm', 3)}"
            if sigma.notna().any()
            else "σ not known"
        )
        median = f"{float(np.nanmedian(film)):.2g}" if np.isfinite(film).any() else "not computed"
        detail = (
            f"Of {len(immersed)} immersed runs, {rough} are in asperity contact "
            f"(σ > x₁/3, Λ < 1), {unsure} uncertain (x₁/4 < σ ≤ x₁/3, 1 ≤ Λ < 4/3) and "
            f"{len(immersed) - rough - unsure - unstated} in film (σ ≤ x₁/4, Λ ≥ 4/3)"
            + (
                f"; {unstated} not determined (a material's roughness is not stated)"
                if unstated
                else ""
            )
            + f", with {GAP_DEFINITION} and Davis et al.'s band h_m = x₁/4 … x₁/3; median "
            f"Λ = h_m/σ = {median}, {span}. "
            + (
                "Asperities touch through the film in the runs in asperity contact: expect "
                "dry-like friction there; in the uncertain runs they may."
                if rough or unsure
                else "The film separates the surfaces in every immersed run whose roughness "
                "is stated."
            )
        )
    if rough:
        headline = f"Roughness exceeds the EHD gap (σ > x₁/3) in {rough} runs: asperity contact" + (
            f"; uncertain in {unsure}" if unsure else ""
        )
    elif unsure:
        headline = f"Roughness within the uncertainty of the EHD gap in {unsure} runs: uncertain"
    elif unstated:
        headline = f"Roughness not stated in {unstated} immersed runs: regime not determined"
    else:
        headline = "Roughness within the EHD gap: film"
    return {"id": "roughness-flag", "raised": raised, "headline": headline, "detail": detail}


def no_runs_flag(description: str) -> dict[str, Any]:
    return {
        "id": "no-runs",
        "raised": False,
        "headline": "No stored collisions match",
        "detail": f"Query: {description}.",
    }
