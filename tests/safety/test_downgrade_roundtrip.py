"""Every downgrade keeps the data, both ways, on every backend, or says what it would lose
and refuses until confirmed (issue 14: ``db downgrade 0001`` once deleted every collision
through ON DELETE CASCADE, and ``base`` dropped everything without a word)."""

from __future__ import annotations

import pytest
from sqlalchemy import inspect, text
from support import dump_hash, engine_for, execute

from granudb.api.database import connect
from granudb.db import migration
from granudb.errors import ConfirmationNeeded
from granudb.io.seed import read_seed

LAB_DATA = [
    "INSERT INTO materials (name, name_key, density_kg_m3, youngs_modulus_pa, poisson_ratio, "
    "roughness_rms_m, yield_stress_pa) VALUES ('PEEK', 'peek', 1300, 3.6e9, 0.38, 5e-8, 9e7)",
    "INSERT INTO datasets (name, version, doi, authors, keywords, state, released_at) VALUES "
    "('lab', '1', '10.5281/zenodo.1', '[{\"family_names\": \"Hunt\"}]', '[\"wet\"]', "
    "'released', CURRENT_TIMESTAMP)",
    "INSERT INTO datasets (name, version) VALUES ('plain', '1')",
    # a run with spins and angle not measured (NULL) …
    "INSERT INTO collisions (dataset_id, run, particle_id, wall_id, fluid_id, diameter_m, "
    "v_n_in_m_s, v_t_in_m_s, v_n_out_m_s, v_t_out_m_s, notes) SELECT d.id, 'r1', p.id, w.id, "
    "f.id, 0.0127, 0.3, 0.1, 0.2, 0.05, 'no spin' FROM datasets d, materials p, materials w, "
    "fluids f WHERE d.name = 'lab' AND p.name = 'steel' AND w.name = 'glass' "
    "AND f.name = 'water'",
    # … and one against a free target sphere
    "INSERT INTO collisions (dataset_id, run, particle_id, wall_id, diameter_m, "
    "wall_diameter_m, nominal_angle_rad, v_n_in_m_s, v_t_in_m_s, omega_in_rad_s, v_n_out_m_s, "
    "v_t_out_m_s, omega_out_rad_s, wall_v_n_in_m_s, wall_v_t_out_m_s) SELECT d.id, 'r2', p.id, "
    "w.id, 0.0127, 0.0254, 0.4, 0.5, 0.2, 3.0, 0.4, 0.1, -2.0, 0.0, 0.05 FROM datasets d, "
    "materials p, materials w WHERE d.name = 'lab' AND p.name = 'PEEK' AND w.name = 'steel'",
    "INSERT INTO collisions (dataset_id, run, particle_id, wall_id, diameter_m, "
    "nominal_angle_rad, v_n_in_m_s, v_t_in_m_s, omega_in_rad_s, v_n_out_m_s, v_t_out_m_s, "
    "omega_out_rad_s) SELECT d.id, 'p1', p.id, p.id, 0.003, 0.1, 1.0, 0.1, 0.0, 0.9, 0.1, 0.0 "
    "FROM datasets d, materials p WHERE d.name = 'plain' AND p.name = 'glass'",
    "INSERT INTO collision_imports (dataset_id, file_sha256, file_name, rows) SELECT id, "
    "'ab', 'runs.csv', 2 FROM datasets WHERE name = 'lab'",
]

#: Columns kept by every revision, compared value by value after a round trip.
KEPT = (
    "SELECT c.run, c.diameter_m, c.v_n_in_m_s, c.v_t_in_m_s, c.v_n_out_m_s, c.v_t_out_m_s, "
    "c.notes, d.name FROM collisions c JOIN datasets d ON d.id = c.dataset_id ORDER BY c.run"
)


def _with_data(db: str) -> None:
    connect(db).dispose()
    for sql in LAB_DATA:
        execute(db, sql)


def _counts(db: str) -> dict[str, int]:
    engine = engine_for(db)
    with engine.connect() as connection:
        tables = set(inspect(connection).get_table_names()) - {"alembic_version"}
        counts = {
            t: connection.execute(text(f'SELECT count(*) FROM "{t}"')).scalar() for t in tables
        }
    engine.dispose()
    return counts


def _rows(db: str, sql: str) -> list[tuple]:
    engine = engine_for(db)
    with engine.connect() as connection:
        rows = [tuple(r) for r in connection.execute(text(sql))]
    engine.dispose()
    return rows


SEED = read_seed()
#: 0011 drops the conditions a seeded material or fluid states (none today).
CONDITION_LOSSES = [
    f"{table}.conditions: {n} values dropped (the values' conditions)"
    for table, entries in (("materials", SEED.materials), ("fluids", SEED.fluids))
    if (n := sum(e.get("conditions") is not None for e in entries))
]
#: 0010 gives a roughness not stated (the seeded Kharaz materials) the older schema's 0.0.
UNSTATED = sum(m.get("roughness_rms_m") is None for m in SEED.materials)
ROUGHNESS_LOSSES = [
    f"materials.roughness_rms_m: {UNSTATED} values not stated, become 0.0 (the older schema "
    "needs a number; an upgrade keeps the 0)"
][: 1 if UNSTATED else 0]
#: 0006 drops the seeded materials' dry values and brittleness and the pair values table.
DRY_LOSSES = [
    f"materials.{c}: {n} values dropped"
    for c in ("dry_restitution", "dry_friction", "dry_provenance", "brittleness")
    if (n := sum(m.get(c) is not None for m in SEED.materials))
] + [f"pair_values.dry_restitution: {len(SEED.pairs)} values dropped (the pair values table goes)"]
EXPECTED_LOSSES = {
    "0003": [
        "datasets.authors: 1 values dropped",
        "datasets.keywords: 1 values dropped",
        "datasets.state: 1 values dropped (released versions become drafts)",
        "datasets.released_at: 1 values dropped",
    ],
    "0002": [
        "materials.yield_stress_pa: 1 values dropped",
        "collisions.wall_v_n_in_m_s: 1 values dropped",
        "collisions.wall_v_t_out_m_s: 1 values dropped",
        "collisions.omega_in_rad_s: 1 values not measured, become 0.0",
        "collisions.omega_out_rad_s: 1 values not measured, become 0.0",
        "collisions.nominal_angle_rad: 1 values not recorded, become the centre's path angle",
    ],
    "0001": ["datasets.doi: 1 values dropped"],
}


def _said(losses: list[str]) -> list[str]:
    """The losses without the released versions each reaches (tested in
    test_released_downgrade.py)."""
    return [line.split(" — changes released versions")[0] for line in losses]


@pytest.mark.parametrize("target", ["0003", "0002", "0001", "base"])
def test_downgrade_to_every_revision_and_back_keeps_every_row_or_asks(db: str, target: str) -> None:
    _with_data(db)
    counts, kept = _counts(db), _rows(db, KEPT)
    database = connect(db)
    losses = migration.plan_downgrade(database, target)
    if target == "base":
        assert _said(losses) == [
            f"table {t}: all {n} rows"
            for t, n in sorted(counts.items())
            if n and t != "seed_records"
        ]
    else:
        order = ["0003", "0002", "0001"]
        expected = (
            CONDITION_LOSSES
            + ROUGHNESS_LOSSES
            + DRY_LOSSES
            + [line for r in order[: order.index(target) + 1] for line in EXPECTED_LOSSES[r]]
        )
        assert _said(losses) == expected

    before = dump_hash(db)
    with pytest.raises(ConfirmationNeeded):
        migration.downgrade(database, target)  # not confirmed: refused, nothing changed
    with pytest.raises(ConfirmationNeeded, match="would change released versions lab@1"):
        migration.downgrade(database, target, accepted=losses)  # the release not named
    assert dump_hash(db) == before

    migration.downgrade(database, target, accepted=losses, releases=["lab@1"])
    migration.upgrade(database, "head")
    database.dispose()
    after = _counts(db)
    if target == "base":
        assert all(n == 0 for n in after.values())
        return
    # seed_records is bookkeeping the downgrade of 0004 drops (and says so in its docstring)
    counts.pop("seed_records"), after.pop("seed_records")
    # the pair values table goes with 0006 (listed among the losses the person accepted)
    assert after.pop("pair_values") == 0 and counts.pop("pair_values") == len(SEED.pairs)
    assert after == counts
    assert _rows(db, KEPT) == kept


def test_downgrade_that_loses_nothing_runs_without_asking(db: str) -> None:
    execute(db, "DELETE FROM pair_values")
    execute(db, "DELETE FROM materials WHERE roughness_rms_m IS NULL")  # 0010's loss
    execute(db, "UPDATE materials SET conditions = NULL")  # 0011's
    execute(db, "UPDATE fluids SET conditions = NULL")
    execute(
        db,
        "UPDATE materials SET dry_restitution = NULL, dry_friction = NULL, "
        "dry_provenance = NULL, brittleness = NULL",
    )
    database = connect(db)
    assert migration.plan_downgrade(database, "0003") == []
    assert migration.downgrade(database, "0003") == (migration.head_revision(), "0003")
    database.dispose()


def test_downgrade_refuses_data_written_after_consent(db: str) -> None:
    _with_data(db)
    database = connect(db)
    losses = migration.plan_downgrade(database, "0001")
    execute(db, "UPDATE datasets SET doi = '10.1/x' WHERE name = 'plain'")
    before = dump_hash(db)
    with pytest.raises(ConfirmationNeeded, match="2 values dropped"):
        migration.downgrade(database, "0001", accepted=losses, releases=["lab@1"])
    database.dispose()
    assert dump_hash(db) == before


def test_cli_downgrade_says_what_it_loses_and_needs_yes(cli, db: str) -> None:
    _with_data(db)
    before = dump_hash(db)
    released = cli("db", "downgrade", "0002", "--yes", db=db)
    assert released.exit_code == 1
    assert released.stderr.startswith(
        "Error: db downgrade 0002: would change released versions lab@1"
    )
    assert "--yes is not enough: add --drop-released-values" in released.stderr
    refused = cli("db", "downgrade", "0002", "--drop-released-values", db=db)
    assert refused.exit_code == 1
    lines = refused.stderr.strip().splitlines()
    assert len(lines) == 1 and "materials.yield_stress_pa: 1 values dropped" in lines[0]
    assert "materials.dry_restitution" in lines[0]
    assert "--yes" in lines[0] and "internal error" not in lines[0]
    assert dump_hash(db) == before
    done = cli("db", "downgrade", "0002", "--yes", "--drop-released-values", db=db)
    assert done.exit_code == 0, done.stderr
    assert "lost collisions.wall_v_n_in_m_s: 1 values dropped" in done.stdout
    assert f"schema: {migration.head_revision()} → 0002" in done.stdout


def test_cli_downgrade_asks_on_a_terminal(cli, db: str, monkeypatch) -> None:
    from typer.testing import CliRunner

    from granudb.cli import confirm
    from granudb.cli.main import app

    _with_data(db)
    monkeypatch.setattr(confirm, "interactive", lambda: True)
    before = dump_hash(db)
    runner = CliRunner()
    base = ["db", "downgrade", "base", "--drop-released-values", "--db", db]
    no = runner.invoke(app, base, input="n\n")
    assert no.exit_code == 1 and "not confirmed" in no.stderr
    assert "table collisions: all 3 rows" in no.stderr
    assert dump_hash(db) == before
    yes = runner.invoke(app, base, input="y\n")
    assert yes.exit_code == 0, yes.stderr
    assert f"schema: {migration.head_revision()} → empty" in yes.stdout
