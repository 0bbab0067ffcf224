"""``survey_collisions`` finds the measured columns that hold a value; reading only those
gives the same runs as reading every column (the others are NaN either way)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from granudb.api.database import opened
from granudb.db.collision_queries import iter_collisions, survey_collisions
from granudb.vocabulary import COLLISION_MEASURED, COLLISION_TARGET

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"


def _read(connection, **options) -> dict[str, np.ndarray]:
    chunks = list(iter_collisions(connection, dataset="ex", chunk_rows=5, **options))
    return {k: np.concatenate([c[k] for c in chunks]) for k in chunks[0]}


def test_reading_only_the_surveyed_columns_reads_the_same_runs(cli, db: str) -> None:
    result = cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", db=db)
    assert result.exit_code == 0, result.stderr
    with opened(db) as database, database.reading() as connection:
        count, present = survey_collisions(connection, dataset="ex")
        everything = _read(connection)
        surveyed = _read(connection, measured=present)
        assert survey_collisions(connection, dataset="ex", fluid="dry")[0] < count
    assert count == len(everything["v_n_in_m_s"]) == 12
    assert {"v_n_in_m_s", "v_t_in_m_s", "diameter_m"} <= present
    assert not present & set(COLLISION_TARGET)  # the example has no target sphere
    for name in COLLISION_MEASURED:
        has = ~np.isnan(everything[name])
        assert has.any() == (name in present), name
    assert everything.keys() == surveyed.keys()
    for name, values in everything.items():
        np.testing.assert_array_equal(values, surveyed[name], err_msg=name)
