"""One row a read cannot derive (written by another tool, or by an older granudb) never
breaks the read for the whole database: the row is listed with a reason, the others
derive as usual, and fits and reports still run."""

from __future__ import annotations

import json
from pathlib import Path

from support import execute

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"


def _poison(db: str) -> None:
    execute(
        db,
        "INSERT INTO collisions (dataset_id, run, particle_id, wall_id, fluid_id, diameter_m, "
        "v_n_in_m_s, v_t_in_m_s, v_n_out_m_s, v_t_out_m_s, temperature_c) "
        "SELECT d.id, 'hot', p.id, w.id, f.id, 0.0127, 0.3, 0.1, 0.2, 0.05, 80 "
        "FROM datasets d, materials p, materials w, fluids f "
        "WHERE d.name = 'ex' AND p.name = 'steel' AND w.name = 'Zerodur' AND f.name = 'water'",
    )


def test_a_run_outside_its_fluids_data_is_listed_with_a_reason(cli, db: str, tmp_path) -> None:
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", db=db).exit_code == 0
    _poison(db)
    listed = cli("collisions", "list", "--wide", "--format", "json", db=db)
    assert listed.exit_code == 0, listed.stderr
    rows = {r["run"]: r for r in json.loads(listed.stdout)}
    assert len(rows) == 13
    assert "outside fluid water's data" in rows["hot"]["derivation_note"]
    assert rows["hot"]["normal_stokes_number"] is None  # no number rather than a wrong one
    assert rows["steel-g37-1"]["normal_stokes_number"] > 1000
    assert cli("fit", "walton", db=db).exit_code == 0
    out = tmp_path / "r.html"
    assert cli("report", "--dataset", "ex", "--output", str(out), db=db).exit_code == 0

    import granudb

    frame = granudb.collisions(db=db, wide=True)
    assert frame["derivation_note"].notna().sum() == 1
