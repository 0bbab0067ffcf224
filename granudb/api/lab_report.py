"""``granudb.reporting``: an HTML or Markdown lab report for a pair or for stored runs.

With ``pair=(particle, wall)`` a scenario report (plus the stored runs of that pair),
taking the scenario options of ``granudb.pair`` (a diameter or speed not given is
assumed, and the report says so at the top); otherwise a report on the stored runs the
collision filters select (a dataset, or any query).
"""

from __future__ import annotations

import base64
import shlex
from pathlib import Path
from typing import Any

from granudb.api import inputs
from granudb.api.collision_listing import collision_query
from granudb.api.database import opened
from granudb.errors import ValidationError
from granudb.reporting.build import database_name, dataset_report, pair_report
from granudb.reporting.render import render
from granudb.reporting.write import check_output, write_report
from granudb.scenario.pair import TARGETS

#: The report's formats: one self-contained HTML file, or Markdown with SVG figures.
REPORT_FORMATS = ("html", "md")


def report(
    pair: Any = None,
    *,
    format: str = "html",
    output: str | Path | None = None,
    force: bool = False,
    title: str | None = None,
    # the scenario of a pair report, as ``granudb.pair`` takes it
    diameter: Any = None, velocity: Any = None, angle: Any = None, temperature: Any = None,
    viscosity: Any = None, wall_diameter: Any = None, target: str | None = None,
    db: Any = None,
    **filters: Any,
) -> Any:  # fmt: skip
    """Write a lab report: properties with sources, derived quantities, verdicts with the
    roughness flag, fits next to published values, figures and methods.

    ``pair`` is (particle, wall) for a scenario report, with the scenario options of
    ``granudb.pair`` (``wall_diameter`` and ``target`` for a second sphere); ``filters``
    are the collision filters of ``granudb.collisions`` (``fluid`` is also the pair's
    fluid). ``format`` is "html" or "md". With ``output`` (a file, or a folder to name it
    in) the report is written there — an existing file only with ``force`` — and its
    path returned (the Markdown's figures go to a folder beside it); without, its text is
    returned (the Markdown's figures embedded as data URIs).

    Examples
    --------
    >>> import granudb
    >>> text = granudb.report(("steel", "Zerodur"), fluid="glycerol-37", db=db)
    >>> text.startswith("<!DOCTYPE html>")
    True
    """
    fmt = inputs.choice(format, REPORT_FORMATS, "format")
    if title is not None:
        title = inputs.name(title, "title", max_length=300)  # the shared name rules
    destination = None if output is None else Path(inputs.path(output, "output"))
    check_output(destination, force=force)
    query = collision_query(**filters)
    scenario = {
        "diameter": diameter,
        "velocity": velocity,
        "angle": angle,
        "temperature": temperature,
        "viscosity": viscosity,
        "wall_diameter": wall_diameter,
        "target": target,
    }
    asked = _asked(pair, fmt, title, {**filters, **scenario})
    with opened(db) as database, database.reading() as connection:
        header = {"title": title, "query": asked, "database": database_name(database.url)}
        if pair is None:
            content = dataset_report(connection, header, query=query)
        else:
            particle, wall = _pair(pair)
            content = pair_report(
                connection,
                header,
                particle=particle,
                wall=wall,
                critical_stokes=query.critical_stokes,
                **_scenario(query.fluid, diameter, velocity, angle, temperature, viscosity),
                wall_diameter_m=inputs.quantity(wall_diameter, "wall_diameter_m", "wall_diameter"),
                target=None if target is None else inputs.choice(target, TARGETS, "target"),
            )
    if destination is not None:
        return write_report(content, fmt, destination, force=force)
    if fmt == "md":
        for figure in content["figures"]:
            data = base64.b64encode(figure["svg"].encode("utf-8")).decode("ascii")
            figure["file"] = f"data:image/svg+xml;base64,{data}"
    return render(content, fmt)


def _pair(pair: Any) -> tuple[str, str]:
    names = inputs.sequence(list(pair) if isinstance(pair, tuple) else pair, "pair")
    if len(names) != 2:
        raise ValidationError("pair", repr(pair)[:60], "must be (particle, wall)", parameter=True)
    return inputs.text(names[0], "pair"), inputs.text(names[1], "pair")


def _scenario(
    fluid: str | None,
    diameter: Any,
    velocity: Any,
    angle: Any,
    temperature: Any,
    viscosity: Any,
) -> dict[str, Any]:
    """The pair scenario's inputs in SI, as ``granudb.pair`` reads them; an angle not
    given is 0° and said to be assumed."""
    return {
        "fluid": None if fluid in (None, "dry") else fluid,
        "diameter_m": inputs.quantity(diameter, "diameter_m", "diameter"),
        "speed_m_s": inputs.quantity(velocity, "impact_speed_m_s", "velocity"),
        "angle_rad": inputs.angle(0.0 if angle is None else angle),
        "temperature_c": inputs.quantity(temperature, "temperature_c", "temperature"),
        "viscosity_pa_s": inputs.quantity(viscosity, "viscosity_pa_s", "viscosity"),
        "assumed": set() if angle is not None else {"incidence_angle_rad"},
    }


def _asked(pair: Any, fmt: str, title: str | None, options: dict[str, Any]) -> str:
    """The request as the command that makes it (the report's header shows it)."""
    parts = ["granudb", "report"]
    if pair is not None:
        parts += ["--pair", *map(str, pair)]
    for name, value in options.items():
        if value is None:
            continue
        option = "--" + name.replace("_", "-")
        if isinstance(value, bool):
            parts.append(option if value else option.replace("--", "--no-", 1))
        elif isinstance(value, tuple | list):
            parts += [option, "..".join(map(str, value))]
        else:
            parts += [option, str(value)]
    if fmt != "html":
        parts += ["--format", fmt]
    if title is not None:
        parts += ["--title", title]
    return " ".join(shlex.quote(p) for p in parts)
