"""Assembling a report: what was asked, the properties with their sources, the derived
quantities and verdicts, fits next to the published values, figures and methods.

The result is a plain dict (``report``) that the HTML and Markdown templates render; every
string in it that came from the database is escaped by the templates, never here. The
pieces live beside this module: ``sections`` (text and property tables), ``tables`` (fits),
``figures`` (SVG figures), ``groups`` (one label and colour per group) and
``references`` (methods and the works cited).
"""

from __future__ import annotations

from collections.abc import Mapping
from datetime import UTC, datetime
from pathlib import PurePath
from typing import Any

import numpy as np
from sqlalchemy.engine import Connection, make_url

from granudb.analysis import fits
from granudb.analysis import walton_bootstrap as resampling
from granudb.db import catalog_rows as catalog
from granudb.db import lookup_rows
from granudb.db.catalog_differences import dataset_source, sources_read
from granudb.lazy import pandas as pd
from granudb.reporting import figures, references, sections, tables
from granudb.reporting.groups import colours, fluid_names, labels_of
from granudb.reporting.pinned import pinned_notes
from granudb.reporting.values import method_text
from granudb.reporting.verdicts import verdicts
from granudb.scenario import plug_ins
from granudb.scenario.collision_query import CollisionQuery
from granudb.scenario.collisions import select_collisions
from granudb.scenario.dry_values import dry_values, provenance_keys
from granudb.scenario.pair import derive_pair
from granudb.version import __version__

#: The columns of the runs a report reads (tables, fits, figures and the flag): the runs are
#: read with only these, so a report on a million runs holds 30 columns, not 75.
REPORT_COLUMNS = [
    *("dataset", "version", "run", "particle", "wall", "fluid"),
    *("diameter_m", "v_n_in_m_s", "viscosity_pa_s", "particle_density_kg_m3"),
    *("effective_incidence", "effective_rebound", "normal_restitution", "tangential_speed_m_s"),
    *("walton_factor", "rotational_restitution", "sliding_friction", "normal_stokes_number"),
    *("added_mass_stokes_number", "shear_strain", "effective_radius_m", "reduced_modulus_pa"),
    *("eta_hat_pa_inv", "effective_mass_kg", "roughness_exceeds_gap", "roughness_regime"),
    *("composite_roughness_m", "film_parameter", "derivation_note", "restitution_ceiling"),
    # the error bars, where runs state uncertainties (absent otherwise)
    *("u_effective_incidence", "u_effective_rebound", "u_normal_restitution"),
    "u_normal_stokes_number",
]
# and what the catalogue's share of St_n is read from (the restitution fit's plug-in)
REPORT_COLUMNS += [c for c in plug_ins.COLUMNS if c not in REPORT_COLUMNS]

#: Scenario inputs granudb assumes when ``report --pair`` is not given them.
DEFAULT_DIAMETER_M = 12.7e-3
DEFAULT_SPEED_M_S = 0.3


def database_name(url: Any) -> str:
    """The database as a report's header names it: an SQLite file by its name only (never
    the folder it sits in on the author's machine), a server database by its name.

    >>> database_name("sqlite:////home/ada/lab/granudb.sqlite")
    'granudb.sqlite'
    >>> database_name("postgresql+psycopg://ada:secret@db.example/lab")
    'lab (postgresql)'
    """
    url = make_url(str(url))
    if url.get_backend_name() == "sqlite":
        return PurePath(url.database).name if url.database else "in-memory SQLite"
    return f"{url.database} ({url.get_backend_name()})"


def _header(header: Mapping[str, Any], title: str) -> dict[str, Any]:
    """The report's skeleton; ``header``: the ``title`` asked for (or None: ``title``),
    the ``query`` as the command that makes it and the ``database`` as ``database_name``."""
    return {
        "title": header.get("title") or title,
        "query": header["query"],
        "database": header["database"],
        "version": __version__,
        "generated_at": datetime.now(UTC).replace(microsecond=0).isoformat(),
        "dataset": None,
        "flags": [],
        "assumed": [],
        "assumptions": [],
        "pinned": [],
        "verdicts": [],
        "properties": [],
        "derived": [],
        "tables": [],
        "figures": [],
        "runs": None,
        "methods": references.methods(),
        "references": [],
    }


def pair_report(
    reader: Any,
    header: Mapping[str, Any],
    *,
    particle: str,
    wall: str,
    fluid: str | None,
    diameter_m: float | None,
    speed_m_s: float | None,
    angle_rad: float,
    temperature_c: float | None,
    viscosity_pa_s: float | None,
    critical_stokes: float,
    wall_diameter_m: float | None = None,
    target: str | None = None,
    assumed: set[str] | None = None,
) -> dict[str, Any]:
    """A report for one scenario, plus the stored runs of the same pair if there are any.

    A missing diameter or speed is assumed (12.7 mm, 0.3 m/s, the paper's sphere and a
    typical speed) and the report says so at the top and in the scenario table;
    ``assumed`` names further inputs the caller defaulted (``incidence_angle_rad``).
    """
    assumed = set(assumed or ())
    if diameter_m is None:
        diameter_m = DEFAULT_DIAMETER_M
        assumed.add("diameter_m")
    if speed_m_s is None:
        speed_m_s = DEFAULT_SPEED_M_S
        assumed.add("impact_speed_m_s")
    if target is None and wall_diameter_m is not None:
        assumed.add("target")  # a second sphere is free and at rest unless said fixed
    result = derive_pair(
        reader,
        particle,
        wall,
        fluid=fluid,
        diameter_m=diameter_m,
        speed_m_s=speed_m_s,
        angle_rad=angle_rad,
        temperature_c=temperature_c,
        viscosity_pa_s=viscosity_pa_s,
        wall_diameter_m=wall_diameter_m,
        target=target,
        critical_stokes=critical_stokes,
    )
    name = f"{result.particle['name']} on {result.wall['name']}" + (
        f" in {result.fluid['name']}" if result.fluid else " (dry)"
    )
    report = _header(header, f"granudb report: {name}")
    _pair_sections(report, result, assumed, diameter_m, critical_stokes)

    add_collisions(
        reader, report, CollisionQuery(particle=particle, wall=wall, fluid=fluid), pair=True
    )
    report["references"] = references.references(report, dict(result.cited_sources))
    return report


def _pair_sections(
    report: dict[str, Any],
    result: Any,
    assumed: set[str],
    diameter_m: float,
    critical_stokes: float,
) -> None:
    """The scenario's flag, verdicts, properties, derived quantities and regime map."""
    immersed = result.fluid_state is not None
    report["flags"].append(
        sections.pair_flag(result.derived, immersed, (result.particle, result.wall))
    )
    report["verdicts"] = [
        {"name": v.name, "text": v.text, "raised": v.raised}
        for v in verdicts(
            result.derived,
            critical_stokes,
            immersed,
            materials=(result.particle, result.wall),
            fluid_name=result.fluid["name"] if result.fluid else None,
            dry=result.dry.record(),
        )
    ]
    used = result.dry.record()
    report["methods"] = references.methods(references.e_dry_words(used))
    report["properties"] = [
        sections.material_section("Particle", result.particle, used),
        sections.material_section("Wall", result.wall, used),
        sections.dry_used_section(f"{result.particle['name']} on {result.wall['name']}", used),
    ]
    if immersed:
        report["properties"].append(sections.fluid_section(result.fluid, result.fluid_state))
    scenario = sections.scenario_rows(result.inputs, assumed)
    report["assumed"] = [f"{r['label']} = {r['value']}" for r in scenario if r["name"] in assumed]
    report["derived"] = [
        {"heading": "Scenario", "rows": scenario},
        {
            "heading": "Derived",
            "rows": sections.derived_rows(result.derived),
            "note": method_text(result.derived),  # how the u and intervals were obtained
        },
    ]
    report["figures"].append(
        figures.regime_map_figure(
            result.particle,
            result.wall,
            diameter_m,
            result.fluid_state.density_kg_m3 if immersed else float("nan"),
            critical_stokes,
            point=(
                (result.inputs["v_n_in_m_s"], result.fluid_state.viscosity_pa_s)
                if immersed
                else None
            ),
        )
    )


def dataset_report(reader: Any, header: Mapping[str, Any], *, query: Any) -> dict[str, Any]:
    """A report on stored collisions (a dataset or any query). ``reader``: a Core
    connection (``Database.reading()``: no ORM on the report's path) or a session;
    ``header`` as in ``_header``."""
    report = _header(header, f"granudb report: {query.describe()}")
    if query.dataset is not None:
        dataset = lookup_rows.dataset_row(_connection(reader), query.dataset, query.version)
        report["dataset"] = {
            "name": dataset.name,
            "version": dataset.version,
            "content_hash": dataset.content_hash,
        }
    citations = add_collisions(reader, report, query, pair=False)
    report["references"] = references.references(report, citations)
    return report


def _assumptions(frame: Any) -> list[str]:
    """What the derivation assumed for the runs, each said once with its run count."""
    notes = frame.get("derivation_note")
    if notes is None:
        return []
    codes, distinct = pd.factorize(np.asarray(notes, dtype=object), use_na_sentinel=True)
    tally = np.bincount(codes[codes >= 0], minlength=len(distinct))  # once per distinct note
    counts = {
        note: int(n)
        for note, n in zip(distinct, tally.tolist(), strict=True)
        if isinstance(note, str) and note.startswith("assumed:") and n
    }
    return [f"{n} run{'s' if n != 1 else ''}: {note}" for note, n in sorted(counts.items())]


def _connection(reader: Any) -> Any:
    return reader if isinstance(reader, Connection) else reader.connection()


def _properties(
    connection: Any, frame: Any, fluids: Any, pinned: int | None
) -> tuple[list[dict[str, Any]], dict[str, str]]:
    """Property blocks of every material and fluid the runs use, and their citations.
    ``fluids``: each run's ``fluid_names``; ``pinned``: the one dataset version the runs
    come from (``lookup_rows.single_dataset_id``), whose catalogue a release keeps."""
    blocks_out, keys = [], set()
    particles = sorted(set(frame["particle"].unique().tolist()))
    walls = sorted(set(frame["wall"].unique().tolist()) - set(particles))
    known = sources_read(connection, pinned)  # a release cites its sources as released
    for role, names in (("Particle", particles), ("Wall", walls)):
        for name in names:
            record = catalog.material_record(catalog.get_material_row(connection, name, pinned))
            blocks_out.append(sections.material_section(role, record))
            keys.add(record.get("source"))
            keys.update(provenance_keys(record.get("dry_provenance"), known))
    pairs = frame[["particle", "wall"]].drop_duplicates().itertuples(index=False)
    for particle, wall in sorted((str(p), str(w)) for p, w in pairs):
        used = dry_values(connection, particle, wall, pinned)
        blocks_out.append(sections.dry_used_section(f"{particle} on {wall}", used.record()))
        keys.update(used.keys())
    for name in sorted(set(fluids.tolist()) - {"dry"}):
        record = catalog.fluid_record(catalog.get_fluid_row(connection, name, pinned))
        blocks_out.append(sections.fluid_section(record))
        keys |= {record.get("source"), record.get("density_source"),
                 record.get("pressure_viscosity_source")}  # fmt: skip
    keys.add(dataset_source(connection, pinned))  # the runs' own source
    citations = {key: known[key] for key in sorted(k for k in keys if k)}
    return blocks_out, citations


def add_collisions(reader: Any, report: dict[str, Any], query: Any, *, pair: bool) -> dict:
    """The stored runs matching ``query``: flag, properties, fit tables and figures.
    Returns the citations of the materials and fluids involved. The BLAS runs on one
    thread throughout (``walton_bootstrap.one_thread``, as in the fits): the report's
    products are small, and threads left spinning after one cost about 0.1 s of CPU on
    100,000 runs on a 2-core machine (benchmarks/report_speed.py)."""
    with resampling.one_thread():
        return _add_collisions(reader, report, query, pair=pair)


def _add_collisions(reader: Any, report: dict[str, Any], query: Any, *, pair: bool) -> dict:
    connection = _connection(reader)
    frame = select_collisions(connection, query, columns=REPORT_COLUMNS, shared_text=True)
    if frame.empty:
        if not pair:
            report["flags"].append(sections.no_runs_flag(query.describe()))
        return {}
    citations: dict[str, str] = {}
    fluids = fluid_names(frame["fluid"])  # each run's fluid as people read it, once
    pinned = None
    if not pair:
        report["flags"].append(sections.dataset_flag(frame))
        pinned = lookup_rows.single_dataset_id(connection, frame)  # a release's own values
        report["properties"], citations = _properties(connection, frame, fluids, pinned)
        report["pinned"] = pinned_notes(connection, pinned)
    report["assumptions"] = _assumptions(frame)
    labels = labels_of(frame, fluids)
    palette = colours(labels)
    walton_sets: dict = {}  # the fits' bootstrap sets, for the bands of their lines
    walton = fits.walton(frame, sets=walton_sets)
    branches = fits.walton_branches(frame, walton)  # the one classification of each run
    if not pair:
        report["runs"] = tables.run_table(tables.run_frame(frame, branches, fluids))
    report["tables"].append(
        tables.walton_table(walton, lookup_rows.published_rows(connection), palette)
    )
    # the catalogue's shares of St_n and of g, as fit_restitution and fit_gap_viscosity
    # take them (each group's typical run derived once for both)
    stokes, gap_shares = plug_ins.catalogue_shares(connection, frame)
    restitution = fits.restitution(frame, report=True, stokes_scale=stokes)  # form and why
    if restitution:
        report["tables"].append(tables.restitution_table(restitution))
    models, curves = plug_ins.fluid_curves(connection)
    gap = fits.gap_viscosity(frame, models, gap_scale=gap_shares, curves=curves)
    if gap:
        report["tables"].append(tables.gap_table(gap, palette))
    fitted = {"walton": walton, "branches": branches, "restitution": restitution,
              "critical_stokes": query.critical_stokes, "walton_sets": walton_sets}  # fmt: skip
    report["figures"] += figures.dataset_figures(frame, labels, palette, fitted)
    if not pair:
        report["figures"] += figures.pair_maps(
            connection, frame, branches, labels, palette, query.critical_stokes, fluids, pinned
        )
    return citations
