"""Reading and deriving runs chunk by chunk gives the same table as one piece (issue 17:
a report on a million runs in bounded memory), on both backends."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest
from paper_runs import paper_rows, write_csv  # noqa: E402
from support import execute  # noqa: E402

from granudb.api.database import connect
from granudb.io.collision_import import import_collisions
from granudb.scenario.collision_query import CollisionQuery
from granudb.scenario.collisions import collision_table, select_collisions


@pytest.fixture
def runs_db(db: str, tmp_path: Path) -> str:
    database = connect(db)
    import_collisions(database, write_csv(tmp_path / "paper.csv", paper_rows()), dataset="p")
    database.dispose()
    execute(  # a run its fluid's data cannot derive (another tool wrote it): blank columns
        db,
        "INSERT INTO collisions (dataset_id, run, particle_id, wall_id, fluid_id, diameter_m, "
        "v_n_in_m_s, v_t_in_m_s, v_n_out_m_s, v_t_out_m_s, temperature_c) "
        "SELECT d.id, 'hot', p.id, w.id, f.id, 0.0127, 0.3, 0.1, 0.2, 0.05, 80 "
        "FROM datasets d, materials p, materials w, fluids f "
        "WHERE d.name = 'p' AND p.name = 'steel' AND w.name = 'Zerodur' AND f.name = 'water'",
    )
    return db


@pytest.mark.parametrize("chunk_rows", [1, 7, 40])
def test_chunks_give_the_table_of_one_piece(runs_db: str, chunk_rows: int) -> None:
    database = connect(runs_db)
    with database.session() as session:
        whole = collision_table(session)
        chunked = collision_table(session, chunk_rows=chunk_rows)
    database.dispose()
    assert len(whole) == 41 and whole["derivation_note"].notna().sum() == 1
    pd.testing.assert_frame_equal(chunked, whole)
    assert chunked.attrs["units"] == whole.attrs["units"]


def test_columns_and_conditions_act_per_chunk_as_on_the_whole(runs_db: str) -> None:
    query = CollisionQuery(min_normal_stokes=50, regime="gross_slip")
    columns = ["run", "fluid", "normal_stokes_number", "sliding_friction", "tangential_regime"]
    database = connect(runs_db)
    with database.session() as session:
        every = collision_table(session)
        lean = select_collisions(session, query, columns=columns)
        numbers = select_collisions(session, query, columns=columns[1:])  # no text read
        full = select_collisions(session, query)
    database.dispose()
    expected = every[
        (every["normal_stokes_number"] >= 50) & (every["tangential_regime"] == "gross_slip")
    ].reset_index(drop=True)
    assert 0 < len(expected) < len(every)
    # (a text column none of the chosen rows fills is an object column of None: as when
    # the whole table has no such text)
    pd.testing.assert_frame_equal(full, expected, check_dtype=False)
    assert list(lean.columns) == columns
    pd.testing.assert_frame_equal(lean, expected[columns])
    pd.testing.assert_frame_equal(numbers, expected[columns[1:]])
