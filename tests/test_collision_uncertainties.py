"""Collision datasets carry their measurement uncertainty (issue 27): per run from a
file's ``u(v_n_in) [mm/s]`` columns, or from the dataset's stated default (absolute or
relative), parsed by the one quantity parser, checked like values, stored, listed, hashed,
migrated, and round-tripped through a Data Package byte for byte."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import numpy as np
import pytest
from sqlalchemy import text
from support import dump_hash

import granudb
from granudb.db import migration
from granudb.db.content_hash import content_hash
from granudb.db.models import Dataset
from granudb.vocabulary import COLLISION_UNCERTAINTIES

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "collisions_example.csv"


def with_u(tmp_path: Path, cells: dict[str, list[str]]) -> Path:
    """The example file with extra columns (header → one cell per run, cycled)."""
    rows = list(csv.reader(EXAMPLE.open(encoding="utf-8")))
    path = tmp_path / "runs_with_u.csv"
    with path.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow([*rows[0], *cells])
        for k, row in enumerate(rows[1:]):
            writer.writerow([*row, *(values[k % len(values)] for values in cells.values())])
    return path


def test_file_columns_and_a_relative_default_are_stored_per_run(opened, tmp_path: Path) -> None:
    path = with_u(tmp_path, {"u(v_n_in) [mm/s]": ["5", ""], "u_temperature [K]": ["0.5"]})
    granudb.import_collisions(path, dataset="u", uncertainty="v_n_in=± 2 %, v_n_out=± 3 %",
                              db=opened)  # fmt: skip
    runs = granudb.collisions(dataset="u", wide=True, db=opened)
    assert set(COLLISION_UNCERTAINTIES) <= set(runs.columns)
    v_in, u_in = runs["v_n_in_m_s"].to_numpy(), runs["u_v_n_in_m_s"].to_numpy()
    own = dict(zip(_labels(path), _file_order(path), strict=True))
    assert {bool(cell) for cell in own.values()} == {True, False}  # both kinds of run
    for i, run in enumerate(runs["run"]):
        expected = 0.005 if own[run] else 0.02 * v_in[i]  # the file's own cell wins
        assert u_in[i] == pytest.approx(expected, rel=1e-12)
    assert runs["u_v_n_out_m_s"].to_numpy() == pytest.approx(0.03 * runs["v_n_out_m_s"])
    # a temperature u is a difference: [K] is not shifted by 273.15 (0.5 K = 0.5 °C)
    wet = runs["temperature_c"].notna()
    assert (runs.loc[wet, "u_temperature_c"] == 0.5).all()
    assert runs["u_v_t_in_m_s"].isna().all()  # not stated: empty, never zero
    assert runs.attrs["units"]["u_v_n_in_m_s"] == "m/s"


def _labels(path: Path) -> list[str]:
    return [row["run"] for row in csv.DictReader(path.open(encoding="utf-8"))]


def _file_order(path: Path) -> list[str]:
    return [row["u(v_n_in) [mm/s]"] for row in csv.DictReader(path.open(encoding="utf-8"))]


@pytest.mark.parametrize(
    ("cells", "options", "message"),
    [
        ({"u(v_n_in) [mm/s]": ["-1"]}, (), "u(v_n_in) [mm/s]"),
        ({"u(v_n_in) [mm/s]": ["inf"]}, (), "finite"),
        ({"u(v_n_in) [kg]": ["1"]}, (), "kg"),
        ({}, ("--uncertainty", "v_n_in=± -3 %"), "non-negative"),
        ({}, ("--uncertainty", "run=± 3 %"), "not a column with an uncertainty"),
        ({}, ("--uncertainty", "v_n_in=± 3 kg"), "uncertainty"),
    ],
)
def test_a_bad_uncertainty_is_one_line_and_changes_nothing(
    cli, db: str, tmp_path: Path, cells: dict, options: tuple, message: str
) -> None:
    path = with_u(tmp_path, cells)
    before = dump_hash(db)
    result = cli("collisions", "import", str(path), "--dataset", "d", *options, db=db)
    assert result.exit_code == 1, result.stdout
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and message in lines[0], result.stderr
    assert "Traceback" not in result.stderr
    assert dump_hash(db) == before


def test_the_import_hash_equals_the_stored_rows_hash_and_u_changes_it(
    opened, tmp_path: Path
) -> None:
    plain = granudb.import_collisions(EXAMPLE, dataset="plain", db=opened)
    stated = with_u(tmp_path, {"u(v_n_out) [mm/s]": ["4", ""]})
    granudb.import_collisions(stated, dataset="stated", db=opened)
    assert plain.rows == 12
    hashes = granudb.datasets(db=opened).set_index("name")["content_hash"]
    with opened.session() as session:
        for name in ("plain", "stated"):
            dataset = session.query(Dataset).filter_by(name=name).one()
            assert content_hash(session, dataset) == hashes[name]  # columnar = re-read
    assert hashes["plain"] != hashes["stated"]


def test_u_columns_round_trip_through_a_package_byte_for_byte(
    cli, db: str, new_db: str, tmp_path: Path
) -> None:
    path = with_u(tmp_path, {"u(v_n_in) [mm/s]": ["5", ""], "u(diameter) [mm]": ["0.01"]})
    imported = cli("collisions", "import", str(path), "--dataset", "ex",
                   "--uncertainty", "v_n_out=± 3 %", db=db)  # fmt: skip
    assert imported.exit_code == 0, imported.stderr
    first, second = tmp_path / "one", tmp_path / "two"
    assert cli("dataset", "export", "ex", "--output", str(first), db=db).exit_code == 0
    table = (first / "data" / "collisions.csv").read_text("utf-8")
    header = next(csv.reader(io.StringIO(table)))
    assert set(COLLISION_UNCERTAINTIES) <= set(header)
    schema = json.loads((first / "datapackage.json").read_text("utf-8"))
    fields = next(r for r in schema["resources"] if r["name"] == "collisions")["schema"]
    u_field = next(f for f in fields["fields"] if f["name"] == "u_v_n_in_m_s")
    assert u_field["unit"] == "m/s" and u_field["constraints"]["minimum"] == 0
    assert cli("dataset", "import", str(first), db=new_db).exit_code == 0
    assert cli("dataset", "export", "ex", "--output", str(second), db=new_db).exit_code == 0
    assert (first / "data" / "collisions.csv").read_bytes() == (
        second / "data" / "collisions.csv"
    ).read_bytes()


def test_migration_0008_keeps_every_run_and_its_downgrade_names_the_loss(
    opened, tmp_path: Path
) -> None:
    granudb.import_collisions(with_u(tmp_path, {"u(v_n_in) [mm/s]": ["5"]}), dataset="m",
                              db=opened)  # fmt: skip
    before = granudb.collisions(dataset="m", wide=True, db=opened)
    losses = migration.plan_downgrade(opened, "0007")
    # the later steps' own losses come first (0010: the seeded roughness not stated)
    assert losses[-1] == ("collisions.u_v_n_in_m_s: 12 values dropped (the stated standard "
                          "uncertainty)")  # fmt: skip
    assert all(line.startswith("materials.roughness_rms_m") for line in losses[:-1])
    migration.downgrade(opened, "0007", accepted=losses)
    with opened.engine.connect() as connection:
        assert connection.execute(text("SELECT count(*) FROM collisions")).scalar() == 12
    migration.upgrade(opened, "head")
    after = granudb.collisions(dataset="m", wide=True, db=opened)
    assert after["u_v_n_in_m_s"].isna().all()  # dropped, as the downgrade said
    assert "u_normal_restitution" in before and "u_normal_restitution" not in after
    same = [c for c in after.columns if c not in COLLISION_UNCERTAINTIES]
    assert set(same) < set(before.columns)
    assert after[same].equals(before[same])  # every run and every measured value kept


def test_each_runs_e_psi_and_st_carry_u_that_a_monte_carlo_agrees_with(
    cli, db: str, tmp_path: Path
) -> None:
    """u(e), u(Ψ_in) and u(St_n) of a stored run, from its stated speeds, agree with the
    spread of 200,000 draws of those speeds (JCGM 101:2008) within 3 %; the JSON and CSV
    listings carry the same u columns."""
    path = with_u(tmp_path, {"u(v_n_in) [mm/s]": ["6"], "u(v_n_out) [mm/s]": ["9"],
                             "u(v_t_in) [mm/s]": ["4"]})  # fmt: skip
    assert cli("collisions", "import", str(path), "--dataset", "mc", db=db).exit_code == 0
    shown = cli("collisions", "list", "--dataset", "mc", "--wide", "--format", "json", db=db)
    runs = json.loads(shown.stdout)
    wet = next(r for r in runs if r["fluid"] and r["omega_in_rad_s"] == 0)
    rng = np.random.default_rng(1)
    draws = 200_000
    v_in = wet["v_n_in_m_s"] + 0.006 * rng.standard_normal(draws)
    v_out = wet["v_n_out_m_s"] + 0.009 * rng.standard_normal(draws)
    v_t = wet["v_t_in_m_s"] + 0.004 * rng.standard_normal(draws)
    monte_carlo = {
        "normal_restitution": v_out / v_in,
        "effective_incidence": v_t / v_in,
        "normal_stokes_number": wet["normal_stokes_number"] * v_in / wet["v_n_in_m_s"],
    }
    for name, sample in monte_carlo.items():
        assert wet[f"u_{name}"] == pytest.approx(np.std(sample), rel=0.03), name
    table = cli("collisions", "list", "--dataset", "mc", "--wide", "--format", "csv", db=db)
    row = next(r for r in csv.DictReader(io.StringIO(table.stdout)) if r["run"] == wet["run"])
    assert float(row["u_normal_restitution"]) == pytest.approx(wet["u_normal_restitution"])
    dry = next(r for r in runs if r["fluid"] is None)
    assert dry["u_normal_restitution"] > 0 and dry["u_normal_stokes_number"] is None
