"""How long does ``granudb report --dataset …`` take on a large dataset, and where does it go?

Imports a synthetic dataset of N runs (default 100,000; the same generator as
``import_speed.py``: steel on Zerodur, dry, water and glycerol, angles 0–80°) into a fresh
SQLite database, then times ``granudb report --dataset benchmark --format html`` as a
separate process (median of ``--runs``, default 3) and reports its peak memory (max RSS of
the child). With ``--profile`` it also runs the report once in this process under cProfile
and prints the functions that take the time. As a same-run baseline it times the floor
of any report process: ``python -c "import sqlalchemy.orm, pandas, matplotlib.figure,
matplotlib.backends.backend_svg, jinja2"`` (the libraries a report needs, nothing of
granudb; the report imports neither pyplot nor scipy). Prints pass/fail against issue
17's bounds: 100,000 runs ≤ 2 s, 1,000,000 runs ≤ 15 s (for other sizes the bound is
interpolated linearly between those two points, and reported as such), and peak memory
≤ 600 MB at any size (the runs are read and derived in chunks, keeping only the columns
the report uses).

    python benchmarks/report_speed.py [--rows 100000] [--runs 3] [--profile]
"""

from __future__ import annotations

import argparse
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from import_speed import write_csv  # noqa: E402

FLOOR = "import sqlalchemy.orm, pandas, matplotlib.figure, matplotlib.backends.backend_svg, jinja2"
#: Peak memory (max RSS) of the report process at any size, MB.
MEMORY_BOUND_MB = 600


def bound_s(rows: int) -> float:
    """Issue 17: 2 s at 100,000 runs, 15 s at 1,000,000; linear between (and beyond)."""
    return 2.0 + (rows - 100_000) * (15.0 - 2.0) / 900_000


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=100_000)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--profile", action="store_true")
    args = parser.parse_args()
    from granudb.api.database import connect
    from granudb.io.collisions_csv import import_collisions

    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        data = folder / "collisions.csv"
        write_csv(data, args.rows)
        db = folder / "granudb.sqlite"
        database = connect(str(db))
        import_collisions(database, data, dataset="benchmark")
        database.dispose()
        out = folder / "report.html"
        argv = [sys.executable, "-m", "granudb", "report", "--dataset", "benchmark"]
        argv += ["--format", "html", "--output", str(out), "--force", "--db", str(db)]
        times, floors = [], []
        floor_argv = [sys.executable, "-c", FLOOR]
        for _ in range(args.runs):
            start = time.perf_counter()
            subprocess.run(argv, check=True, capture_output=True)
            times.append(time.perf_counter() - start)
            start = time.perf_counter()
            subprocess.run(floor_argv, check=True, capture_output=True)
            floors.append(time.perf_counter() - start)
        size_mb = out.stat().st_size / 1e6
        if args.profile:
            import cProfile
            import pstats

            from granudb.cli.main import app

            profiler = cProfile.Profile()
            profiler.enable()
            try:
                app([*argv[3:]], standalone_mode=False)
            finally:
                profiler.disable()
            pstats.Stats(profiler).sort_stats("cumulative").print_stats(30)
    peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    median = statistics.median(times)
    limit = bound_s(args.rows)
    floor = statistics.median(floors)
    print(f"report on {args.rows:,} runs: median {median:.2f} s of {args.runs} ({times})")
    print(f"import floor (same run): median {floor:.2f} s; report = {median / floor:.1f}× floor")
    print(f"HTML {size_mb:.1f} MB; peak memory of the report process {peak_mb:,.0f} MB")
    print(
        f"{'PASS' if peak_mb <= MEMORY_BOUND_MB else 'FAIL'}: peak memory {peak_mb:,.0f} MB; "
        f"bound <= {MEMORY_BOUND_MB} MB"
    )
    print(
        f"{'PASS' if median <= limit else 'FAIL'}: {median:.2f} s; bound <= {limit:.1f} s "
        f"({args.rows / median:,.0f} runs/s)"
    )


if __name__ == "__main__":
    main()
