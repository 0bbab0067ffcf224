"""Helpers tests import (``pythonpath = tests`` in pyproject)."""

from __future__ import annotations

import hashlib
from typing import Any


def engine_for(db: str) -> Any:
    """A plain SQLAlchemy engine on a test database (no granudb settings, no migration)."""
    from sqlalchemy import create_engine

    from granudb.config import resolve_database_url

    return create_engine(resolve_database_url(db))


def dump_hash(db: str) -> str:
    """A hash of the database's logical content: every table, every row.

    Logical, not bytes: a read can checkpoint SQLite's WAL and change the file without
    changing any data, and it is the data that must stay the same. Rows are sorted, so the
    hash does not depend on the order a backend returns them in.
    """
    from sqlalchemy import inspect, text

    engine = engine_for(db)
    digest = hashlib.sha256()
    try:
        with engine.connect() as connection:
            for table in sorted(inspect(connection).get_table_names()):
                rows = connection.execute(text(f'SELECT * FROM "{table}"'))
                digest.update(f"{table}:{list(rows.keys())}".encode())
                for line in sorted(repr(tuple(row)) for row in rows):
                    digest.update(line.encode())
    finally:
        engine.dispose()
    return digest.hexdigest()


def execute(db: str, sql: str, params: dict[str, Any] | None = None) -> None:
    """Run one statement in its own transaction, bypassing granudb (as another tool would)."""
    from sqlalchemy import event, text

    engine = engine_for(db)
    if engine.dialect.name == "sqlite":
        event.listen(engine, "connect", lambda dbapi, _: dbapi.execute("PRAGMA foreign_keys=ON"))
    try:
        with engine.begin() as connection:
            connection.execute(text(sql), params or {})
    finally:
        engine.dispose()


#: Steel on Zerodur as ``derive()`` takes them (SI; Joseph & Hunt 2004, table 1): the
#: materials of the physics tests' scenarios.
STEEL_ON_ZERODUR = dict(
    particle_density_kg_m3=7780.0,
    particle_youngs_modulus_pa=190e9,
    particle_poisson_ratio=0.27,
    particle_roughness_rms_m=0.0236e-6,
    wall_density_kg_m3=2540.0,
    wall_youngs_modulus_pa=91e9,
    wall_poisson_ratio=0.24,
    wall_roughness_rms_m=0.0155e-6,
    diameter_m=12.7e-3,
)

#: A collision CSV's header with units, and one good row, for tests that build files.
COLLISION_HEADER = [
    "run",
    "particle",
    "wall",
    "fluid",
    "diameter [mm]",
    "incidence_angle [deg]",
    "v_n_in [mm/s]",
    "v_t_in [mm/s]",
    "omega_in [rad/s]",
    "v_n_out [mm/s]",
    "v_t_out [mm/s]",
    "omega_out [rad/s]",
    "temperature [degC]",
    "notes",
]
GOOD_ROW = [
    "r1",
    "steel",
    "Zerodur",
    "",
    "12.7",
    "20",
    "300",
    "109.2",
    "0",
    "291",
    "60",
    "-5",
    "",
    "",
]


def write_csv(
    path: Any, rows: list[list[str]], header: list[str] = COLLISION_HEADER, **options: Any
) -> Any:
    """Write ``rows`` under ``header`` as a CSV file (``options`` go to ``csv.writer``)."""
    import csv

    with path.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n", **options)
        writer.writerow(header)
        writer.writerows(rows)
    return path


def require_binary(binary: str) -> None:
    """Skip a test that runs ``binary`` when it is missing, except where the environment
    requires it (CI sets ``GRANUDB_REQUIRE_DEM=1``): there a missing code fails."""
    import os
    import shutil

    import pytest

    if shutil.which(binary) is not None:
        return
    if os.environ.get("GRANUDB_REQUIRE_DEM") == "1":
        pytest.fail(f"{binary} is required (GRANUDB_REQUIRE_DEM=1) but not installed")
    pytest.skip(f"{binary} not installed")


class CostBound:
    """Bounded cost, not speed: the block must finish within ``cpu_seconds`` of this
    process's CPU time (a hang, or an exponent evaluated by brute force, overruns it by
    orders of magnitude; other processes on the machine do not count). Speed itself is
    measured in benchmarks/, never here."""

    def __init__(self, cpu_seconds: float = 10.0) -> None:
        self.cpu_seconds = cpu_seconds

    def __enter__(self) -> CostBound:
        import time

        self.started = time.process_time()
        return self

    def __exit__(self, *exc: object) -> None:
        import time

        used = time.process_time() - self.started
        assert used < self.cpu_seconds, f"{used:.1f} s of CPU (bound {self.cpu_seconds} s)"


def release_ptfe_runs(database: Any, tmp_path: Any, example: Any) -> None:
    """Add a PTFE material, import ``example``'s runs with PTFE for steel as dataset
    "ptfe" and release it (a release using a material nothing else uses)."""
    import granudb

    granudb.add_material("PTFE", density="2.2 g/cm^3", youngs_modulus="0.5 GPa",
                         poisson_ratio=0.46, roughness="0.2 um", db=database)  # fmt: skip
    rows = example.read_text("utf-8").replace(",steel,", ",PTFE,")
    (source := tmp_path / "ptfe.csv").write_text(rows, encoding="utf-8")
    granudb.import_collisions(source, dataset="ptfe", db=database)
    granudb.release_dataset("ptfe", db=database)
