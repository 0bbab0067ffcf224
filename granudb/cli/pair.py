"""``granudb pair``: what happens when this particle hits that wall in this fluid.

A table for people shows the collision, the materials with their sources, every derived
quantity with its symbol and relation, and the verdicts in words; JSON is the document
``granudb.pair`` returns, CSV that document flattened to one row.
"""

from __future__ import annotations

import sys
from typing import Annotated, Any

import typer

from granudb import api
from granudb.cli.options import (
    CriticalStokes,
    DbOption,
    Format,
    FormatOption,
    text_options,
    wraps,
)
from granudb.cli.output import console, emit, to_json
from granudb.lazy import rich_table, rich_text

Particle = Annotated[str, typer.Argument(help="Particle material, e.g. steel.")]
Wall = Annotated[str, typer.Argument(help="Wall (or second particle) material, e.g. Zerodur.")]
#: ``granudb.api.scenario.SCENARIO_OPTIONS`` as options, each with its help.
scenario_options = text_options(
    "scenario",
    {
        "diameter": 'Particle diameter, "12.7 mm" (required).',
        "velocity": 'Impact speed V of the centre, "0.3 m/s" (required).',
        "fluid": "Fluid; omit (or 'dry') for a dry collision.",
        "angle": 'Incidence angle from the normal, "30 deg" (default 0°).',
        "temperature": 'Fluid temperature, "20 degC" (default: the fluid\'s reference).',
        "viscosity": 'Override the fluid viscosity, "0.8 cP" (what-if).',
        "wall_diameter": "Diameter of a second sphere, free and at rest unless --target fixed "
        "(default: a flat wall).",
        "target": "wall, fixed or free (a second sphere's default).",
        "critical_stokes": CriticalStokes,
    },
)


@scenario_options
@wraps("pair")
def pair(
    particle: Particle,
    wall: Wall,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
    scenario: dict | None = None,
) -> None:
    """Properties, every derived quantity and the regime verdicts for one collision."""
    document = api.pair(particle, wall, db=db, **scenario or {})
    if fmt is Format.json:
        sys.stdout.write(to_json(document) + "\n")
    elif fmt is Format.csv:
        row = flatten(document)
        emit([row], list(row), fmt)
    else:
        print_pair(document)


def flatten(document: dict[str, Any]) -> dict[str, Any]:
    """One CSV row of a pair document: nested records as ``particle_<column>``,
    ``fluid_<column>``, ``inputs`` under their own names, derived values as they are,
    verdicts as ``verdict_<key>`` sentences."""
    row: dict[str, Any] = {}
    for key, value in document.items():
        if key == "inputs":
            row.update(value)
        elif key == "sources":
            row["sources"] = "; ".join(value)
        elif key == "verdicts":
            row.update({f"verdict_{v['key']}": v["text"] for v in value})
        elif isinstance(value, dict):
            row.update({f"{key}_{k}": v for k, v in value.items()})
        elif value is None and key == "fluid":
            row["fluid_name"] = "dry"
        else:
            row[key] = value
    return row


def print_pair(document: dict[str, Any]) -> None:
    """The collision, the materials, the derived quantities and the verdicts as tables."""
    Table, Text = rich_table.Table, rich_text.Text
    out = console()
    out.print(_collision_table(document))
    particle, wall = document["particle"], document["wall"]
    props = Table(title="Materials", title_justify="left")
    props.add_column("property")
    props.add_column(Text(particle["name"]))
    props.add_column(Text(wall["name"]))
    for column in ("density_kg_m3", "youngs_modulus_pa", "poisson_ratio", "roughness_rms_m"):
        props.add_row(
            api.term(column).title,
            api.display_uncertain(particle[column], particle.get(f"u_{column}"), column),
            api.display_uncertain(wall[column], wall.get(f"u_{column}"), column),
        )
    props.add_row("source", Text(_cite(particle)), Text(_cite(wall)))
    if particle.get("conditions") or wall.get("conditions"):  # as the source gives them
        props.add_row(
            "conditions",
            Text(particle.get("conditions") or "—"),
            Text(wall.get("conditions") or "—"),
        )
    out.print(props)
    dry = document["dry_values"]
    values = Table(title="Dry values of the pair", title_justify="left")
    for heading in ("value", "", "basis", "source"):
        values.add_column(heading, overflow="fold")
    for name, symbol in (("dry_restitution", "e_dry"), ("dry_friction", "μ_dry"),
                         ("immersed_friction", "μ immersed")):  # fmt: skip
        values.add_row(
            symbol, f"{dry[name]:.4g}", dry[f"{name}_basis"], Text(dry[f"{name}_source"])
        )
    out.print(values)

    derived = Table(title="Derived quantities", title_justify="left")
    derived.add_column("quantity")
    derived.add_column("value", justify="right")
    derived.add_column("relation", overflow="fold")
    for name, described in api.derived_terms().items():
        if name not in document or name == "incidence_angle_rad":
            continue
        label = f"{described.symbol} ({described.title.lower()})"
        value = api.qualified_value(document, name)
        interval = api.interval_text(document, name)
        value += f"\n{interval}" if interval else ""
        derived.add_row(Text(label), Text(value), Text(described.description))
    out.print(derived)
    method = api.method_text(document)
    if method:
        out.print(Text(method))

    out.print("[bold]Verdicts[/bold]")
    for verdict in document["verdicts"]:
        style = "bold red" if verdict["raised"] else "green"
        line = Text(f"{'⚠' if verdict['raised'] else '•'} {verdict['title']}: ", style=style)
        line.append(verdict["text"], style="default")
        out.print(line)
    if document["sources"]:
        out.print("[bold]Sources[/bold]")
        for key, citation in document["sources"].items():
            out.print(Text(f"[{key}] {citation}"))


def _collision_table(document: dict[str, Any]) -> Any:
    inputs, fluid = document["inputs"], document["fluid"]
    table = rich_table.Table(title="Collision", title_justify="left", show_header=False)
    table.add_column("quantity", style="bold")
    table.add_column("value")

    def show(value: Any, column: str, uncertainty: str | None = None) -> str:
        return api.display_uncertain(value, inputs.get(uncertainty or f"u_{column}"), column)

    rows = [
        ("particle", document["particle"]["name"]),
        ("wall", document["wall"]["name"]),
        ("target", api.target_words(inputs)),
        ("fluid", fluid["name"] if fluid else "none (dry)"),
        ("diameter", show(inputs["diameter_m"], "diameter_m")),
        ("impact speed V", show(inputs["impact_speed_m_s"], "impact_speed_m_s")),
        ("incidence angle", show(inputs["incidence_angle_rad"], "incidence_angle_rad")),
        (
            "v_n,in / v_t,in",
            f"{show(inputs['v_n_in_m_s'], 'v_n_in_m_s')} / "
            f"{show(inputs['v_t_in_m_s'], 'v_t_in_m_s')}",
        ),
    ]
    if fluid:
        rows += [
            (
                "viscosity μ",
                f"{show(fluid['viscosity_pa_s'], 'viscosity_pa_s')} — {fluid['viscosity_basis']}",
            ),
            (
                "fluid density",
                show(fluid["density_kg_m3"], "density_kg_m3", "u_fluid_density_kg_m3"),
            ),
            ("temperature", show(fluid["temperature_c"], "temperature_c")),
        ]
    for name, value in rows:
        table.add_row(name, rich_text.Text(str(value)))
    return table


def _cite(record: dict[str, Any]) -> str:
    if not record.get("source"):
        return "—"
    locator = record.get("source_locator")
    return f"{record['source']}" + (f", {locator}" if locator else "")
