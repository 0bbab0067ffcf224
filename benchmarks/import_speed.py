"""How fast does ``granudb collisions import`` load a large CSV, against the sqlite3 shell?

Writes an N-row collision CSV (default 1,000,000) with units in the headers, imports it
into a fresh SQLite database with ``granudb.io.collisions_csv.import_collisions`` (parse,
convert units, validate every rule, resolve names, bulk insert, all in one transaction),
and in the same run loads the same file with the ``sqlite3`` shell's ``.import --csv`` into
a plain table (no conversion, no validation: the floor for getting bytes into SQLite).
Prints rows per second for both, the ratio, and the peak memory of this process.

    python benchmarks/import_speed.py [--rows 1000000]
"""

from __future__ import annotations

import argparse
import csv
import resource
import shutil
import sqlite3
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np


def write_csv(path: Path, rows: int) -> None:
    rng = np.random.default_rng(0)
    angle = rng.uniform(0, 80, rows)
    vn = rng.uniform(50, 400, rows)
    vt = vn * np.tan(np.radians(angle))
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(
            [
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
        )
        fluids = np.array(["", "glycerol-37", "water"])[rng.integers(0, 3, rows)]
        for i in range(rows):
            writer.writerow(
                [
                    f"run-{i}",
                    "steel",
                    "Zerodur",
                    fluids[i],
                    "12.7",
                    f"{angle[i]:.4f}",
                    f"{vn[i]:.3f}",
                    f"{vt[i]:.3f}",
                    "0",
                    f"{0.8 * vn[i]:.3f}",
                    f"{0.3 * vt[i]:.3f}",
                    "-2.5",
                    "20",
                    "",
                ]
            )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=1_000_000)
    args = parser.parse_args()
    from granudb.api.database import connect as open_database
    from granudb.io.collisions_csv import import_collisions

    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        data = folder / "collisions.csv"
        write_csv(data, args.rows)
        size_mb = data.stat().st_size / 1e6

        database = open_database(str(folder / "granudb.sqlite"))
        start = time.perf_counter()
        result = import_collisions(database, data, dataset="benchmark")
        granudb_s = time.perf_counter() - start
        with database.engine.connect() as connection:
            from sqlalchemy import text

            stored = connection.execute(text("SELECT count(*) FROM collisions")).scalar()
        database.dispose()
        assert stored == result.rows == args.rows

        plain = folder / "plain.sqlite"
        shell = shutil.which("sqlite3")
        start = time.perf_counter()
        if shell:
            subprocess.run(
                [shell, str(plain), ".mode csv", f".import {data} collisions"], check=True
            )
            how = "sqlite3 shell .import"
        else:
            with sqlite3.connect(plain) as connection, data.open() as handle:
                reader = csv.reader(handle)
                header = next(reader)
                connection.execute(
                    f"CREATE TABLE collisions ({', '.join(f'c{i}' for i in range(len(header)))})"
                )
                connection.executemany(
                    f"INSERT INTO collisions VALUES ({', '.join('?' * len(header))})", reader
                )
            how = "Python sqlite3 executemany (no sqlite3 shell on this machine)"
        shell_s = time.perf_counter() - start

    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"file: {args.rows:,} rows, {size_mb:,.0f} MB")
    print(
        f"granudb import (convert, validate, bulk insert): {granudb_s:.1f} s = "
        f"{args.rows / granudb_s:,.0f} rows/s"
    )
    print(f"{how} (no conversion or checks): {shell_s:.1f} s = {args.rows / shell_s:,.0f} rows/s")
    print(f"ratio: granudb takes {granudb_s / shell_s:.1f}x the time of the raw load")
    print(f"peak memory of this process (max RSS): {peak_mb:,.0f} MB")


if __name__ == "__main__":
    main()
