"""What a dataset's catalogue values are, and where they differ: from today's catalogue
(a release that pins values the catalogue has since changed) or from another dataset's.

A release's runs point at the revisions it keeps (``granudb.db.catalog_revisions``) and
read only the pair values stored before its release; a draft reads the live rows. So the
catalogue a dataset *reads* is: for each material and fluid its runs use, the row they
point at (with a fluid's points), and for each pair of materials the pair values it
sees. ``pinned_changes`` compares that with today's live rows and ``catalogue_diff``
with another dataset's; every output that says "the release pins …" or "the catalogue
differs …" (``dataset show|list|diff|export``, reports, DEM decks, derived listings)
takes the records from here. Each record: ``kind`` ("material", "fluid", "fluid point",
"pair"), ``name``, ``field`` (a stored column name, whose suffix says the unit),
``temperature_c`` (a fluid point's; else None), ``first`` and ``second`` (the two values,
SI; None: absent), and for a pinned revision its ``revision`` number and ``kept_at``.

Sources are read the same way: a release cites each source as it was when released
(``sources_read``, the one place every output that prints a release's citations takes
them from: reports, ``dataset show``, packages), a draft today's. A source record of
``pinned_changes`` names the revision the release cites (``revision``, numbered as
``sources history`` numbers them) and today's (``now_revision``).
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import func, select
from sqlalchemy.engine import Connection

from granudb.db import catalog_rows
from granudb.vocabulary.catalog import FLUIDS, MATERIALS
from granudb.vocabulary.rules import same_value
from granudb.vocabulary.terms import keyed, stored, stored_values

#: Listing columns that are not values of their own (derived flags, counts).
_NOT_COMPARED = {"shear_modulus_derived", "points"}
#: A fluid point's key (its temperature) and what is compared at each key.
(_POINT_KEY,) = keyed("fluid_points")
_POINT_COLUMNS = (
    *(s.column for s in stored("fluid_points", uncertainties=True) if not s.keyed),
    "source",
)
_PAIR_COLUMNS = (*stored_values("pair_values"), "source")
#: A value shown with a flag saying it was derived (G from E and ν): two derived values
#: are not stored values, so they are not compared.
_COMPANIONS = {**MATERIALS.companions, **FLUIDS.companions}


def used_rows(connection: Connection, dataset_id: int) -> dict[str, dict[int, int]]:
    """The catalogue rows dataset ``dataset_id``'s runs point at, per kind ("material",
    "fluid"): {live row id: the id the runs use (the live row or a kept revision)}."""
    runs = catalog_rows.RUNS
    used: dict[str, dict[int, int]] = {}
    for kind, references in catalog_rows.RUN_REFERENCES.items():
        clause = catalog_rows.ENTRY_TABLES[kind]
        ids: set[int] = set()
        for reference in references:
            column = runs.c[reference]
            query = select(column).where(runs.c.dataset_id == dataset_id).distinct()
            ids |= {i for i in connection.execute(query).scalars() if i is not None}
        rows = connection.execute(
            select(clause.c.id, clause.c.revision_of).where(clause.c.id.in_(sorted(ids)))
        )
        used[kind] = {live or row_id: row_id for row_id, live in rows}
    return used


def _entry(connection: Connection, kind: str, row_id: int, fluids: dict) -> dict[str, Any]:
    """The listing record of one material or fluid row, a fluid's points under
    ``points_by_temperature``."""
    if kind == "fluid":
        row = fluids[row_id]
        record = catalog_rows.fluid_record(row)
        record["points_by_temperature"] = {
            p[_POINT_KEY]: p for p in catalog_rows.point_records(row)
        }
        return record
    return catalog_rows.material_record(catalog_rows.material_row_by_id(connection, row_id))


def _compare(kind: str, first: dict, second: dict) -> list[dict[str, Any]]:
    """Field by field, where two records of the same entry differ (``first``'s name)."""
    name = first["name"]
    found = []
    for field in first:
        if field in _NOT_COMPARED or field == "points_by_temperature":
            continue
        companion = _COMPANIONS.get(field)
        if companion and first.get(companion) and second.get(companion):
            continue  # G = E / (2(1 + ν)) on both: not a stored value; E or ν says it
        if not same_value(first[field], second.get(field)):
            found.append(_record(kind, name, field, first[field], second.get(field)))
    if kind == "fluid":
        one, other = first["points_by_temperature"], second["points_by_temperature"]
        for t in sorted(one.keys() | other.keys()):
            a, b = one.get(t, {}), other.get(t, {})
            for field in _POINT_COLUMNS:
                if not same_value(a.get(field), b.get(field)):
                    found.append(_record("fluid point", name, field, a.get(field), b.get(field), t))
    return found


def _record(kind: str, name: str, field: str, first: Any, second: Any,
            key: float | None = None) -> dict[str, Any]:  # fmt: skip
    return {"kind": kind, "name": name, "field": field, _POINT_KEY: key,
            "first": first, "second": second, "revision": None, "kept_at": None}  # fmt: skip


def run_pairs(connection: Connection, dataset_id: int) -> set[frozenset[str]]:
    """The pairs of materials dataset ``dataset_id``'s runs use, by their live names
    (either way round)."""
    runs = catalog_rows.RUNS
    clause = catalog_rows.ENTRY_TABLES["material"]
    rows = connection.execute(select(clause.c.id, clause.c.revision_of, clause.c.name)).all()
    names = {row_id: name for row_id, live, name in rows if live is None}
    live = {row_id: names[of] for row_id, of, _ in rows if of is not None}
    query = select(runs.c.particle_id, runs.c.wall_id).where(runs.c.dataset_id == dataset_id)
    return {
        frozenset((live.get(p) or names[p], live.get(w) or names[w]))
        for p, w in connection.execute(query.distinct())
    }


def _pairs(connection: Connection, dataset_id: int | None, pairs: set) -> dict[tuple, dict]:
    """The pair values dataset ``dataset_id`` reads (a release: those stored before it;
    None: today's) for ``pairs`` (``run_pairs``), keyed by the two names."""
    before = catalog_rows.released_at(connection, dataset_id)
    found = {}
    for row in catalog_rows.pair_value_rows(connection, before=before):
        if frozenset((row.particle, row.wall)) in pairs:
            found[(row.particle, row.wall)] = catalog_rows.pair_value_record(row)
    return found


def _compare_pairs(first: dict[tuple, dict], second: dict[tuple, dict]) -> list[dict]:
    found = []
    for pair in sorted(first.keys() | second.keys()):
        a, b = first.get(pair, {}), second.get(pair, {})
        for field in _PAIR_COLUMNS:
            if not same_value(a.get(field), b.get(field)):
                found.append(_record("pair", " on ".join(pair), field, a.get(field), b.get(field)))
    return found


def sources_read(connection: Connection, dataset_id: int | None) -> dict[str, Any]:
    """Every source by key as dataset ``dataset_id`` cites it: a release, as it was when
    released (the revision kept after that, else the live row); a draft or no dataset,
    as it is today (``catalog_rows.SourceRow``s)."""
    return catalog_rows.sources_as_of(connection, catalog_rows.released_at(connection, dataset_id))


def _revision_numbers(connection: Connection, when: Any) -> dict[str, tuple[int, int]]:
    """{key: (the revision of the source read at ``when``, today's revision)} for each
    source with kept revisions, numbered as ``sources history`` numbers them: 1 is the
    oldest text, today's is one more than the revisions kept."""
    keys = {row["id"]: row["key"] for row in connection.execute(
        select(catalog_rows.SOURCES.c.id, catalog_rows.SOURCES.c.key)).mappings()}  # fmt: skip
    kept: dict[str, list[Any]] = {}
    for revision in catalog_rows.source_revision_rows(connection):
        kept.setdefault(keys[revision["source_id"]], []).append(revision["kept_at"])
    numbers = {}
    for key, times in kept.items():
        later = [n for n, at in enumerate(times, start=1) if when is not None and at > when]
        numbers[key] = (later[0] if later else len(times) + 1, len(times) + 1)
    return numbers


def dataset_source(connection: Connection, dataset_id: int | None) -> str | None:
    """The key of the source dataset ``dataset_id`` itself cites (None: none, or no
    dataset)."""
    if dataset_id is None:
        return None
    own = catalog_rows.lightweight_table("datasets", ["id", "source_id"])
    sources = catalog_rows.SOURCES
    query = select(sources.c.key).join(own, own.c.source_id == sources.c.id)
    return connection.execute(query.where(own.c.id == dataset_id)).scalar_one_or_none()


def _cited(
    connection: Connection, used: dict[str, dict[int, int]], fluids: dict, dataset_id: int
) -> set:
    """The keys of the sources a dataset cites: its own and those of the rows it reads
    (with a fluid's points')."""
    keys: set[str | None] = {dataset_source(connection, dataset_id)}
    for kind, rows in used.items():
        for row_id in rows.values():
            record = _entry(connection, kind, row_id, fluids)
            keys |= {record.get(c) for c in ("source", "density_source",
                                              "pressure_viscosity_source")}  # fmt: skip
            keys |= {p["source"] for p in record.get("points_by_temperature", {}).values()}
    return keys - {None}


def _compare_sources(
    connection: Connection, first_id: int, second_id: int | None, cited: set[str]
) -> list[dict[str, Any]]:
    """Sources as dataset ``first_id`` reads them (a release: as they were when released)
    against dataset ``second_id``'s (None: today's), field by field; a source's changes
    are revisions (``granudb.db.catalog_revisions.keep_source_revision``)."""
    one, other = sources_read(connection, first_id), sources_read(connection, second_id)
    numbers = _revision_numbers(connection, catalog_rows.released_at(connection, first_id))
    found = []
    for key in sorted(one.keys() & other.keys() & cited):
        a, b = catalog_rows.source_record(one[key]), catalog_rows.source_record(other[key])
        cites, today = numbers.get(key, (None, None))
        found += [
            {**_record("source", key, f, a[f], b[f]), "revision": cites, "now_revision": today}
            for f in a
            if not same_value(a[f], b[f])
        ]
    return found


def pinned_changes(connection: Connection, dataset_id: int) -> list[dict[str, Any]]:
    """Where the catalogue values dataset ``dataset_id`` reads (a release's pinned
    revisions and pair values) differ from today's catalogue: ``first`` is what the
    dataset pins, ``second`` the catalogue now. A draft reads today's values: none."""
    if catalog_rows.released_at(connection, dataset_id) is None:
        return []
    used = used_rows(connection, dataset_id)
    fluids = catalog_rows.fluid_rows_by_id(connection) if used["fluid"] else {}
    changes = []
    for kind, rows in used.items():
        clause = catalog_rows.ENTRY_TABLES[kind]
        for live, pinned in sorted(rows.items()):
            if live == pinned:
                continue
            found = _compare(
                kind,
                _entry(connection, kind, pinned, fluids),
                _entry(connection, kind, live, fluids),
            )
            number = connection.execute(
                select(func.count()).select_from(clause)
                .where(clause.c.revision_of == live, clause.c.id <= pinned)
            ).scalar()  # fmt: skip
            kept = connection.execute(
                select(clause.c.updated_at).where(clause.c.id == pinned)
            ).scalar()
            changes += [{**c, "revision": number, "kept_at": kept} for c in found]
    cited = _cited(connection, used, fluids, dataset_id)
    changes += _compare_sources(connection, dataset_id, None, cited)
    pairs = run_pairs(connection, dataset_id)
    changes += _compare_pairs(
        _pairs(connection, dataset_id, pairs), _pairs(connection, None, pairs)
    )
    return changes


def catalogue_diff(connection: Connection, first_id: int, second_id: int) -> list[dict]:
    """Where the catalogue values two datasets read differ, for the materials, fluids
    (with their points) and pairs both use: ``first`` is dataset ``first_id``'s value,
    ``second`` dataset ``second_id``'s (a release's pinned revision, a draft's live row)."""
    one, other = used_rows(connection, first_id), used_rows(connection, second_id)
    fluids = catalog_rows.fluid_rows_by_id(connection) if one["fluid"] or other["fluid"] else {}
    changes = []
    for kind in one:
        for live in sorted(one[kind].keys() & other[kind].keys()):
            a, b = one[kind][live], other[kind][live]
            if a != b:
                changes += _compare(
                    kind, _entry(connection, kind, a, fluids), _entry(connection, kind, b, fluids)
                )
    cited = _cited(connection, one, fluids, first_id) & _cited(connection, other, fluids, second_id)
    changes += _compare_sources(connection, first_id, second_id, cited)
    pairs = run_pairs(connection, first_id) & run_pairs(connection, second_id)
    return changes + _compare_pairs(
        _pairs(connection, first_id, pairs), _pairs(connection, second_id, pairs)
    )
