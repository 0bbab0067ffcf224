"""The Alembic revisions and the SQLAlchemy models describe the same schema, and the
migrations run both ways on a database that holds data."""

from __future__ import annotations

import json

import pytest
from sqlalchemy import func, select, text
from sqlalchemy.exc import IntegrityError
from support import engine_for

from granudb.api.database import connect as open_database
from granudb.db import migration
from granudb.db.models import Base, Material
from granudb.errors import ConfirmationNeeded
from granudb.io.seed import read_seed

#: The materials the shipped seed adds to a new database.
SEEDED = len(read_seed().materials)


def test_autogenerate_finds_no_difference_between_models_and_migrations(db: str) -> None:
    from alembic.autogenerate import compare_metadata
    from alembic.runtime.migration import MigrationContext

    database = open_database(db)
    with database.engine.connect() as connection:
        context = MigrationContext.configure(connection, opts={"compare_type": True})
        differences = compare_metadata(context, Base.metadata)
    database.dispose()
    assert differences == []


def test_check_constraints_are_in_the_migrated_schema(db: str) -> None:
    from sqlalchemy import inspect

    engine = engine_for(db)
    checks = {c["name"] for c in inspect(engine).get_check_constraints("materials")}
    engine.dispose()
    assert {"ck_materials_poisson_ratio_range", "ck_materials_density_positive"} <= checks


PEEK = [
    "materials",
    "add",
    "PEEK",
    "--density",
    "1.3 g/cm^3",
    "--youngs-modulus",
    "3.6 GPa",
    "--poisson-ratio",
    "0.38",
    "--roughness",
    "50 nm",
]


def test_upgrade_downgrade_upgrade_with_data(cli, db: str) -> None:
    from sqlalchemy import inspect

    path = db
    assert cli(*PEEK, db=path).exit_code == 0
    database = open_database(path)
    with database.session() as session:
        assert session.scalar(select(func.count()).select_from(Material)) == SEEDED + 1
    losses = migration.plan_downgrade(database, "base")
    assert f"table materials: all {SEEDED + 1} rows" in losses
    before, after = migration.downgrade(database, "base", accepted=losses)
    assert (before, after) == (migration.head_revision(), None)
    with database.engine.connect() as connection:
        assert migration.current_revision(connection) is None
        # Only Alembic's bookkeeping table may remain.
        assert set(inspect(connection).get_table_names()) <= {"alembic_version"}
    database.dispose()

    result = cli("db", "upgrade", db=path)
    assert result.exit_code == 0, result.stderr
    assert f"→ {migration.head_revision()}" in result.stdout
    database = open_database(path)
    with database.session() as session:
        names = set(session.scalars(select(Material.name)))
    database.dispose()
    assert names == {m["name"] for m in read_seed().materials}  # re-created and re-seeded
    assert cli(*PEEK, db=path).exit_code == 0


def test_db_upgrade_on_current_database_says_so(cli, db: str) -> None:
    result = cli("db", "upgrade", db=db)
    assert result.exit_code == 0
    assert "already at" in result.stdout


def test_cli_downgrade_and_upgrade(cli, db: str) -> None:
    refused = cli("db", "downgrade", "base", db=db)
    assert refused.exit_code == 1 and "--yes" in refused.stderr
    assert "glass" in cli("materials", "list", db=db).stdout
    result = cli("db", "downgrade", "base", "--yes", db=db)
    assert result.exit_code == 0, result.stderr
    assert "→ empty" in result.stdout
    current = cli("db", "current", "--format", "json", db=db)
    assert '"revision": null' in current.stdout
    assert cli("db", "upgrade", db=db).exit_code == 0
    assert "glass" in cli("materials", "list", db=db).stdout


@pytest.mark.sqlite_only
def test_sqlite_runs_in_wal_mode_with_foreign_keys_and_busy_timeout(db: str) -> None:
    from sqlalchemy import text

    database = open_database(db)
    with database.engine.connect() as connection:
        assert connection.execute(text("PRAGMA journal_mode")).scalar() == "wal"
        assert connection.execute(text("PRAGMA foreign_keys")).scalar() == 1
        assert connection.execute(text("PRAGMA busy_timeout")).scalar() >= 5000
    database.dispose()


def test_concurrent_first_use_creates_and_seeds_once(new_db: str) -> None:
    import json
    import subprocess
    import sys

    path = new_db
    procs = [
        subprocess.Popen(
            [
                sys.executable,
                "-m",
                "granudb",
                "materials",
                "list",
                "--format",
                "json",
                "--db",
                str(path),
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for _ in range(4)
    ]
    outputs = [p.communicate(timeout=120) for p in procs]
    assert [p.returncode for p in procs] == [0, 0, 0, 0], [o[1] for o in outputs]
    for out, _ in outputs:
        assert len(json.loads(out)) == SEEDED
    assert sum("created" in err for _, err in outputs) == 1
    engine = engine_for(path)
    with engine.connect() as connection:
        assert connection.execute(text("SELECT count(*) FROM materials")).scalar() == SEEDED
        assert connection.execute(text("SELECT count(*) FROM sources")).scalar() >= 3
    engine.dispose()


def test_a_database_at_the_first_revision_is_migrated_forward_with_its_data(
    cli, new_db: str
) -> None:
    """A file made by the first release (revision 0001) keeps every row through
    ``granudb db upgrade``, and the new column appears."""
    from granudb.db.engine import open_database as open_raw

    database = open_raw(new_db, migrate=False)
    migration.upgrade(database, "0001")
    with database.engine.begin() as connection:
        connection.execute(text("INSERT INTO datasets (name, version) VALUES ('old', '1')"))
        for name in ("glass", "Zerodur"):
            connection.execute(
                text(
                    "INSERT INTO materials (name, name_key, density_kg_m3, youngs_modulus_pa, "
                    "poisson_ratio, roughness_rms_m) VALUES (:n, :k, 2540, 6e10, 0.23, 1e-7)"
                ),
                {"n": name, "k": name.lower()},
            )
        connection.execute(
            text(
                "INSERT INTO fluids (name, name_key, density_kg_m3, viscosity_pa_s, "
                "reference_temperature_c) VALUES ('oil', 'oil', 960, 0.0096, 25)"
            )
        )
        connection.execute(
            text(
                "INSERT INTO collisions (dataset_id, run, particle_id, wall_id, fluid_id, "
                "diameter_m, incidence_angle_rad, v_n_in_m_s, v_t_in_m_s, omega_in_rad_s, "
                "v_n_out_m_s, v_t_out_m_s, omega_out_rad_s) SELECT d.id, 'r1', p.id, w.id, "
                "f.id, 0.0127, 0.5, 0.3, 0.16, 0, 0.25, 0.05, -2 FROM datasets d, materials p, "
                "materials w, fluids f WHERE p.name = 'glass' AND w.name = 'Zerodur'"
            )
        )
    database.dispose()
    before = cli("materials", "list", "--format", "json", db=new_db)
    # opening with any command migrates it forward
    assert before.exit_code == 0, before.stderr
    current = cli("db", "current", "--format", "json", db=new_db).stdout
    assert f'"revision": "{migration.head_revision()}"' in current
    datasets = cli("dataset", "list", "--format", "json", db=new_db).stdout
    assert '"name": "old"' in datasets
    assert "glass" in before.stdout
    fluid = json.loads(cli("fluids", "show", "oil", "--format", "json", db=new_db).stdout)
    assert fluid["reference_viscosity_pa_s"] == 0.0096  # renamed by 0003, value kept
    runs = json.loads(
        cli(
            "collisions", "list", "--dataset", "old", "--wide", "--format", "json", db=new_db
        ).stdout
    )
    assert runs[0]["nominal_angle_rad"] == 0.5  # the stored angle keeps its value
    assert runs[0]["omega_out_rad_s"] == -2


def test_0010_makes_the_roughness_optional_and_its_downgrade_names_the_loss(db: str) -> None:
    """0010 keeps every material (and its roughness); a roughness not stated (the seeded
    Kharaz materials, issue 23) survives until a downgrade, which names what it does
    with it and is refused without consent; the way back up keeps every row."""
    database = open_database(db)

    def roughness() -> dict[str, float | None]:
        with database.engine.connect() as connection:
            rows = connection.execute(text("SELECT name, roughness_rms_m FROM materials"))
            return dict(rows.fetchall())

    seeded = roughness()
    unstated = sorted(name for name, sigma in seeded.items() if sigma is None)
    assert unstated == ["alumina", "soda-lime glass (Kharaz anvil)"]
    assert seeded["glass"] == pytest.approx(0.1305e-6)
    losses = migration.plan_downgrade(database, "0009")
    assert losses == [
        "materials.roughness_rms_m: 2 values not stated, become 0.0 (the older schema "
        "needs a number; an upgrade keeps the 0)"
    ]
    with pytest.raises(ConfirmationNeeded):
        migration.downgrade(database, "0009")
    assert roughness() == seeded  # refused: nothing changed
    assert migration.downgrade(database, "0009", accepted=losses)[1] == "0009"
    down = roughness()
    assert set(down) == set(seeded) and all(down[n] == 0.0 for n in unstated)
    assert {n: s for n, s in down.items() if n not in unstated} == {
        n: s for n, s in seeded.items() if n not in unstated
    }
    with pytest.raises(IntegrityError), database.engine.begin() as connection:
        # the older schema holds no "not stated"
        connection.execute(text("UPDATE materials SET roughness_rms_m = NULL"))
    migration.upgrade(database)
    assert roughness() == down  # every row kept on the way up
    with database.engine.begin() as connection:  # and the column takes "not stated" again
        connection.execute(
            text("UPDATE materials SET roughness_rms_m = NULL WHERE name = 'alumina'")
        )
    assert roughness()["alumina"] is None
    database.dispose()


def test_0011_adds_the_conditions_and_its_downgrade_names_the_loss(db: str) -> None:
    """0011 gives materials and fluids an empty ``conditions`` (every row kept); a
    downgrade names the conditions it drops, table by table, and is refused without
    consent; the way back up keeps every row, the conditions then empty."""
    import granudb

    database = open_database(db)
    granudb.update_material("glass", conditions="σ from SEM images", db=database)
    granudb.update_fluid("water", conditions="at 20 °C", db=database)

    def rows(table: str) -> dict[str, tuple]:
        with database.engine.connect() as connection:
            found = connection.execute(text(f"SELECT * FROM {table}")).mappings().all()
            return {
                r["name"]: tuple(v for k, v in r.items() if k not in ("conditions", "updated_at"))
                for r in found
            }

    before = {table: rows(table) for table in ("materials", "fluids")}
    losses = migration.plan_downgrade(database, "0010")
    assert losses == [
        "materials.conditions: 1 values dropped (the values' conditions)",
        "fluids.conditions: 1 values dropped (the values' conditions)",
    ]
    with pytest.raises(ConfirmationNeeded):
        migration.downgrade(database, "0010")
    assert granudb.material("glass", db=database)["conditions"] == "σ from SEM images"
    assert migration.downgrade(database, "0010", accepted=losses)[1] == "0010"
    assert {table: rows(table) for table in before} == before  # only the column went
    migration.upgrade(database)
    assert {table: rows(table) for table in before} == before
    assert granudb.material("glass", db=database)["conditions"] is None
    assert granudb.fluid("water", db=database)["conditions"] is None
    database.dispose()
