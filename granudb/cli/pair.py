"""``granudb pair``: what happens when this particle hits that wall in this fluid."""

from __future__ import annotations

from typing import Annotated

import typer

from granudb.cli.common import DbOption, Format, quantity

PairFormat = Annotated[
    Format, typer.Option("--format", "-f", help="table for people; json (SI) for scripts.")
]


def pair(
    particle: Annotated[str, typer.Argument(help="Particle material, e.g. steel.")],
    wall: Annotated[str, typer.Argument(help="Wall (or second particle) material, e.g. Zerodur.")],
    diameter: Annotated[str, typer.Option("--diameter", help='Particle diameter, "12.7 mm".')],
    velocity: Annotated[str, typer.Option("--velocity", help='Impact speed, "0.3 m/s".')],
    fluid: Annotated[
        str | None, typer.Option("--fluid", help="Fluid; omit for a dry collision.")
    ] = None,
    angle: Annotated[
        str, typer.Option("--angle", help='Incidence angle from the normal, "30 deg" (0 to < 90°).')
    ] = "0 deg",
    temperature: Annotated[
        str | None,
        typer.Option(
            "--temperature", help='Fluid temperature, "20 degC" (default: the fluid\'s reference).'
        ),
    ] = None,
    viscosity: Annotated[
        str | None,
        typer.Option("--viscosity", help='Override the fluid viscosity, "0.8 cP" (what-if).'),
    ] = None,
    wall_diameter: Annotated[
        str | None,
        typer.Option("--wall-diameter", help="Diameter of a second sphere (default: a flat wall)."),
    ] = None,
    critical_stokes: Annotated[
        float, typer.Option("--critical-stokes", help="No rebound below this normal Stokes number.")
    ] = 10.0,
    db: DbOption = None,
    fmt: PairFormat = Format.table,
) -> None:
    """Properties, every derived quantity and the regime verdicts for one collision."""
    from granudb.analysis.derivation import derive_pair
    from granudb.cli.common import open_db

    if fmt is Format.csv:
        from granudb.errors import ValidationError

        raise ValidationError("--format", "csv", "is not offered for pair (use table or json)")
    if fluid is None:
        from granudb.errors import ValidationError

        for option, text in (("--viscosity", viscosity), ("--temperature", temperature)):
            if text is not None:
                raise ValidationError(
                    option, text, "needs --fluid (a dry collision has no fluid to set)"
                )
    values = {
        "diameter_m": quantity(diameter, "diameter_m", "--diameter"),
        "speed_m_s": quantity(velocity, "v_n_in_m_s", "--velocity"),
        "angle_rad": _angle(angle),
        "temperature_c": quantity(temperature, "temperature_c", "--temperature"),
        "viscosity_pa_s": quantity(viscosity, "viscosity_pa_s", "--viscosity"),
        "wall_diameter_m": quantity(wall_diameter, "wall_diameter_m", "--wall-diameter"),
    }
    if not critical_stokes > 0:
        from granudb.errors import ValidationError

        raise ValidationError("--critical-stokes", f"{critical_stokes:g}", "must be > 0")
    database = open_db(db)
    with database.session() as session:
        result = derive_pair(
            session, particle, wall, fluid=fluid, critical_stokes=critical_stokes, **values
        )
    if fmt is Format.json:
        import sys

        from granudb.analysis.derivation import pair_json
        from granudb.cli.output import to_json

        sys.stdout.write(to_json(pair_json(result)) + "\n")
        return
    _print(result, critical_stokes)


def _angle(text: str) -> float:
    from granudb.errors import ValidationError
    from granudb.io.units import parse_quantity

    value = parse_quantity(text, "rad", "--angle")
    if not 0.0 <= value < 1.5707963267948966:
        raise ValidationError("--angle", text, "must be ≥ 0° and < 90°")
    return value


def _print(result, critical_stokes: float) -> None:
    from rich.table import Table
    from rich.text import Text

    from granudb.cli.output import console, label
    from granudb.report.format import display
    from granudb.report.verdicts import verdicts
    from granudb.vocabulary import DERIVED_TERMS

    out = console()
    inputs = Table(title="Collision", title_justify="left", show_header=False)
    inputs.add_column("quantity", style="bold")
    inputs.add_column("value")
    state = result.fluid_state
    rows = [
        ("particle", result.particle["name"]),
        ("wall", result.wall["name"]),
        ("fluid", state.name if state else "none (dry)"),
        ("diameter", display(result.inputs["diameter_m"], "diameter_m")),
        ("impact speed", display(result.inputs["impact_speed_m_s"], "impact_speed_m_s")),
        ("incidence angle", display(result.inputs["incidence_angle_rad"], "incidence_angle_rad")),
        (
            "v_n,in / v_t,in",
            f"{display(result.inputs['v_n_in_m_s'], 'v_n_in_m_s')} / "
            f"{display(result.inputs['v_t_in_m_s'], 'v_t_in_m_s')}",
        ),
    ]
    if state:
        rows += [
            ("viscosity", f"{display(state.viscosity_pa_s, 'viscosity_pa_s')} — {state.basis}"),
            ("fluid density", display(state.density_kg_m3, "density_kg_m3")),
            ("temperature", display(state.temperature_c, "temperature_c")),
        ]
    for name, value in rows:
        inputs.add_row(name, Text(str(value)))
    out.print(inputs)

    props = Table(title="Materials", title_justify="left")
    props.add_column("property")
    props.add_column(Text(result.particle["name"]))
    props.add_column(Text(result.wall["name"]))
    for column in (
        "density_kg_m3",
        "youngs_modulus_pa",
        "poisson_ratio",
        "roughness_rms_m",
        "shear_modulus_pa",
    ):
        props.add_row(
            label(column),
            display(result.particle[column], column),
            display(result.wall[column], column),
        )
    props.add_row("source", Text(_cite(result.particle)), Text(_cite(result.wall)))
    out.print(props)

    derived = Table(title="Derived quantities", title_justify="left")
    derived.add_column("quantity")
    derived.add_column("value", justify="right")
    derived.add_column("relation", overflow="fold")
    for name, described in DERIVED_TERMS.items():
        description = described.description
        if name not in result.derived or name == "incidence_angle_rad":
            continue
        derived.add_row(name, Text(display(result.derived[name], name)), Text(description))
    out.print(derived)

    out.print("[bold]Verdicts[/bold]")
    for verdict in verdicts(result.derived, critical_stokes, immersed=state is not None):
        style = "bold red" if verdict.raised else "green"
        line = Text(f"{'⚠' if verdict.raised else '•'} {verdict.name}: ", style=style)
        line.append(verdict.text, style="default")
        out.print(line)
    if result.citations:
        out.print("[bold]Sources[/bold]")
        for key, citation in result.citations.items():
            out.print(Text(f"[{key}] {citation}"))


def _cite(record: dict) -> str:
    if not record.get("source"):
        return "—"
    return f"{record['source']}" + (
        f", {record['source_locator']}" if record.get("source_locator") else ""
    )
