"""The catalogue's one read path (``granudb.db.catalog_rows``, SQLAlchemy Core) reads
what was written.

The reads name their tables with lightweight clauses rather than the models, to skip
building the ORM at start-up; these tests hold every named column to the models and check
the records against what a user added (a material, fluid points, sources).
"""

from __future__ import annotations

import pytest

import granudb
from granudb.api.database import opened
from granudb.db import catalog_rows, collision_queries, datasets, lookup_rows, sources
from granudb.db.models import Base
from granudb.errors import NotFoundError


def test_every_column_read_is_a_column_of_the_models() -> None:
    for clause in (*catalog_rows.TABLES, *lookup_rows.TABLES, *collision_queries.TABLES):
        model_table = Base.metadata.tables[clause.name]
        assert set(clause.c.keys()) <= set(model_table.c.keys()), clause.name


def _add_user_rows(cli, db: str, tmp_path) -> None:
    result = cli(
        "materials", "add", "PTFE ball", "--density", "2.2 g/cm^3", "--youngs-modulus",
        "0.5 GPa", "--poisson-ratio", "0.46", "--roughness", "0.4 um", db=db,
    )  # fmt: skip
    assert result.exit_code == 0, result.stderr
    points = tmp_path / "points.csv"
    points.write_text("temperature [degC],viscosity [mPa*s]\n12.5,1.22\n37.5,0.69\n")
    result = cli(
        "fluids", "points", "import", "water", str(points), "--source", "cheng-2008", db=db
    )
    assert result.exit_code == 0, result.stderr


def test_records_hold_what_was_added(cli, db: str, tmp_path) -> None:
    _add_user_rows(cli, db, tmp_path)
    with opened(db) as database, database.reading() as connection:
        materials = {
            m["name"]: m
            for m in map(catalog_rows.material_record, catalog_rows.material_rows(connection))
        }
        water = catalog_rows.get_fluid_row(connection, "WATER")
        keys = [s.key for s in catalog_rows.source_rows(connection)]
    ptfe = materials["PTFE ball"]
    assert ptfe["density_kg_m3"] == pytest.approx(2200.0)
    assert ptfe["youngs_modulus_pa"] == pytest.approx(0.5e9)
    assert ptfe["roughness_rms_m"] == pytest.approx(0.4e-6)
    assert ptfe["shear_modulus_derived"] is True
    assert ptfe["shear_modulus_pa"] == pytest.approx(0.5e9 / (2 * 1.46))
    added = {p.temperature_c: p for p in water.points}
    assert added[12.5].viscosity_pa_s == pytest.approx(1.22e-3)
    assert added[37.5].source.key == "cheng-2008"
    assert [p.temperature_c for p in water.points] == sorted(added)
    assert keys == sorted(keys) and "joseph-hunt-2004" in keys
    assert [r["name"] for r in granudb.materials(db=db, as_frame=False)] == list(materials)


def test_a_missing_name_lists_the_known_ones(db: str) -> None:
    with opened(db) as database, database.reading() as connection:
        with pytest.raises(NotFoundError, match=r"material: 'unobtainium' .*steel"):
            catalog_rows.get_material_row(connection, "unobtainium")
        with pytest.raises(NotFoundError, match=r"fluid: 'mercury' .*glycerol-37"):
            catalog_rows.get_fluid_row(connection, "mercury")
        found = catalog_rows.get_material_row(connection, "  ZERODUR ")
    assert found.name == "Zerodur"


def _refusals(*calls) -> list[str]:
    """The NotFoundError message of each call (each must refuse)."""
    messages = []
    for call in calls:
        with pytest.raises(NotFoundError) as caught:
            call()
        messages.append(str(caught.value))
    return messages


def test_core_lookups_agree_with_the_orm(cli, db: str, tmp_path) -> None:
    """The lookups a read of runs makes (``lookup_rows``) find what the ORM finds, and
    refuse with the same words."""
    from pathlib import Path

    example = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
    for version in ("1.0.0", "1.1.0"):
        result = cli("collisions", "import", str(example), "--dataset", "ex", "--version",
                     version, db=db)  # fmt: skip
        assert result.exit_code == 0, result.stderr
    with opened(db) as database:
        with database.session() as session:
            orm = {
                "latest": datasets.get_dataset(session, "ex"),
                "first": datasets.get_dataset(session, "ex", "1.0.0"),
            }
            errors = _refusals(
                lambda: datasets.get_dataset(session, "nope"),
                lambda: datasets.get_dataset(session, "ex", "9"),
            )
        with database.reading() as connection:
            latest = lookup_rows.dataset_row(connection, "ex")
            first = lookup_rows.dataset_row(connection, "ex", "1.0.0")
            assert (latest.id, latest.version, latest.content_hash) == (
                orm["latest"].id, orm["latest"].version, orm["latest"].content_hash
            )  # fmt: skip
            assert (first.id, first.version) == (orm["first"].id, "1.0.0")
            assert catalog_rows.entry_id(connection, "material", "STEEL") == (
                catalog_rows.entry_id(connection, "material", "steel")
            )
            published = sources.published_records(connection, "joseph-hunt-2004")
            everything = lookup_rows.published_rows(connection)
            theirs = [r for r in everything if r["source"] == "joseph-hunt-2004"]
            assert published == theirs and len(published) > 5
            core_errors = _refusals(
                lambda: lookup_rows.dataset_row(connection, "nope"),
                lambda: lookup_rows.dataset_row(connection, "ex", "9"),
            )
    assert core_errors == errors
