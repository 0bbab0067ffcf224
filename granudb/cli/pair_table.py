"""How ``granudb pair`` looks in a terminal: the collision, the materials with their
sources, every derived quantity with its symbol and relation, the verdicts in words."""

from __future__ import annotations

from typing import Any


def print_pair(document: dict[str, Any], critical_stokes: float) -> None:
    from rich.table import Table
    from rich.text import Text

    from granudb.cli.output import console
    from granudb.report.format import display
    from granudb.report.values import qualified_value
    from granudb.report.verdicts import verdicts
    from granudb.vocabulary import DERIVED_TERMS, term

    out = console()
    out.print(_collision_table(document))
    particle, wall = document["particle"], document["wall"]
    props = Table(title="Materials", title_justify="left")
    props.add_column("property")
    props.add_column(Text(particle["name"]))
    props.add_column(Text(wall["name"]))
    for column in ("density_kg_m3", "youngs_modulus_pa", "poisson_ratio", "roughness_rms_m"):
        props.add_row(
            term(column).title, display(particle[column], column), display(wall[column], column)
        )
    props.add_row("source", Text(_cite(particle)), Text(_cite(wall)))
    out.print(props)

    derived = Table(title="Derived quantities", title_justify="left")
    derived.add_column("quantity")
    derived.add_column("value", justify="right")
    derived.add_column("relation", overflow="fold")
    for name, described in DERIVED_TERMS.items():
        if name not in document or name == "incidence_angle_rad":
            continue
        label = f"{described.symbol} ({described.title.lower()})"
        derived.add_row(
            Text(label), Text(qualified_value(document, name)), Text(described.description)
        )
    out.print(derived)

    out.print("[bold]Verdicts[/bold]")
    fluid = document["fluid"]
    for verdict in verdicts(
        document,
        critical_stokes,
        immersed=fluid is not None,
        materials=(particle, wall),
        fluid_name=fluid["name"] if fluid else None,
    ):
        style = "bold red" if verdict.raised else "green"
        line = Text(f"{'⚠' if verdict.raised else '•'} {verdict.name}: ", style=style)
        line.append(verdict.text, style="default")
        out.print(line)
    if document["sources"]:
        out.print("[bold]Sources[/bold]")
        for key, citation in document["sources"].items():
            out.print(Text(f"[{key}] {citation}"))


def _collision_table(document: dict[str, Any]) -> Any:
    from rich.table import Table
    from rich.text import Text

    from granudb.report.format import display

    inputs, fluid = document["inputs"], document["fluid"]
    table = Table(title="Collision", title_justify="left", show_header=False)
    table.add_column("quantity", style="bold")
    table.add_column("value")
    rows = [
        ("particle", document["particle"]["name"]),
        ("wall", document["wall"]["name"]),
        ("fluid", fluid["name"] if fluid else "none (dry)"),
        ("diameter", display(inputs["diameter_m"], "diameter_m")),
        ("impact speed V", display(inputs["impact_speed_m_s"], "impact_speed_m_s")),
        ("incidence angle", display(inputs["incidence_angle_rad"], "incidence_angle_rad")),
        (
            "v_n,in / v_t,in",
            f"{display(inputs['v_n_in_m_s'], 'v_n_in_m_s')} / "
            f"{display(inputs['v_t_in_m_s'], 'v_t_in_m_s')}",
        ),
    ]
    if fluid:
        rows += [
            (
                "viscosity μ",
                f"{display(fluid['viscosity_pa_s'], 'viscosity_pa_s')} — "
                f"{fluid['viscosity_basis']}",
            ),
            ("fluid density", display(fluid["density_kg_m3"], "density_kg_m3")),
            ("temperature", display(fluid["temperature_c"], "temperature_c")),
        ]
    for name, value in rows:
        table.add_row(name, Text(str(value)))
    return table


def _cite(record: dict[str, Any]) -> str:
    if not record.get("source"):
        return "—"
    locator = record.get("source_locator")
    return f"{record['source']}" + (f", {locator}" if locator else "")
