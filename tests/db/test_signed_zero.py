"""A measured "-0" is stored as 0.0 on every backend, so a file has one content hash
wherever it is imported (SQLite gives -0.0 back as 0.0; PostgreSQL kept the sign)."""

from __future__ import annotations

import math

from sqlalchemy import text

from granudb.api.database import opened
from granudb.db import datasets
from granudb.db.content_hash import content_hash

HEADER = (
    "run,particle,wall,fluid,diameter [mm],incidence_angle [deg],v_n_in [mm/s],"
    "v_t_in [mm/s],omega_in [rad/s],v_n_out [mm/s],v_t_out [mm/s],omega_out [rad/s]"
)


def _import(cli, db: str, path, zero: str, dataset: str) -> None:
    path.write_text(
        HEADER + "\n"
        f"r1,steel,Zerodur,,12.7,0,300,{zero},{zero},290,{zero},{zero}\n"
        "r2,steel,Zerodur,,12.7,30,300,173.2,0,290,150,-10\n",
        "utf-8",
    )
    result = cli("collisions", "import", str(path), "--dataset", dataset, db=db)
    assert result.exit_code == 0, result.stderr


def test_negative_zero_is_stored_as_zero_and_hashes_as_zero(cli, db: str, tmp_path) -> None:
    _import(cli, db, tmp_path / "signed.csv", "-0", "signed")
    _import(cli, db, tmp_path / "plain.csv", "0", "plain")
    with opened(db) as database, database.session() as session:
        stored = session.execute(
            text(
                "SELECT c.v_t_in_m_s, c.omega_in_rad_s, c.v_t_out_m_s, c.omega_out_rad_s "
                "FROM collisions c JOIN datasets d ON d.id = c.dataset_id "
                "WHERE d.name = 'signed' AND c.run = 'r1'"
            )  # fmt: skip
        ).one()
        signed = datasets.get_dataset(session, "signed")
        plain = datasets.get_dataset(session, "plain")
        assert signed.content_hash == content_hash(session, signed)
        assert signed.content_hash == plain.content_hash  # the same measurements
    assert all(float(v) == 0.0 and math.copysign(1.0, float(v)) == 1.0 for v in stored)
