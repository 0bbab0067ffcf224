"""How long does ``granudb report --dataset …`` take on a large dataset, and where does it go?

Imports a synthetic dataset of N runs (default 100,000; the same generator as
``import_speed.py``: steel on Zerodur, dry, water and glycerol, angles 0–80°) into a fresh
SQLite database, then times ``granudb report --dataset benchmark --format html`` as a
separate process (median of ``--runs``, default 3) and reports its peak memory (max RSS of
the child). With ``--profile`` it also runs the report once in this process under cProfile
and prints the functions that take the time. As a same-run baseline it times the floor
of any report process: ``python -c "import sqlalchemy, pandas, jinja2"`` (the libraries a
report needs, nothing of granudb; figures are granudb's own SVG, fits are numpy, so neither
matplotlib nor scipy is imported). granudb's bytecode is compiled first, as an
installed granudb's is (pip compiles it; a checkout under PYTHONDONTWRITEBYTECODE would
recompile every module in every report). Prints pass/fail against issue
17's bounds: 100,000 runs ≤ 2 s, 1,000,000 runs ≤ 15 s (for other sizes the bound is
interpolated linearly between those two points, and reported as such), and peak memory
≤ 600 MB at any size (the runs are read and derived in chunks, keeping only the columns
the report uses).

With ``--baseline-src DIR`` (a source tree of another granudb, say an export of main:
``git archive main | tar -x -C DIR``) it also times that version's report on the same
database, interleaved, and prints the ratio; ``--db PATH`` reuses a database that already
holds the dataset ``benchmark`` (``--rows`` is then its size, for the bound).

    python benchmarks/report_speed.py [--rows 100000] [--runs 3] [--profile]
                                      [--baseline-src DIR] [--db PATH]
"""

from __future__ import annotations

import argparse
import compileall
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from import_speed import write_csv  # noqa: E402

FLOOR = "import sqlalchemy, pandas, jinja2"
#: Peak memory (max RSS) of the report process at any size, MB.
MEMORY_BOUND_MB = 600


def timed(argv: list[str], source: Path | None = None) -> tuple[float, float, float]:
    """(seconds, peak memory in MB, CPU seconds) of one child process (its own rusage, from
    wait4);
    ``source``: run granudb from that source tree (first on the path, and the working
    directory, which ``python -m`` puts first)."""
    env = None if source is None else {**os.environ, "PYTHONPATH": str(source)}
    start = time.perf_counter()
    child = subprocess.Popen(
        argv, env=env, cwd=source, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE
    )
    _, status, usage = os.wait4(child.pid, 0)
    seconds = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"{argv[:4]} failed: {child.stderr.read().decode()[-2000:]}")
    child.stderr.close()
    return seconds, usage.ru_maxrss / 1024, usage.ru_utime + usage.ru_stime


def bound_s(rows: int) -> float:
    """Issue 17: 2 s at 100,000 runs, 15 s at 1,000,000; linear between (and beyond)."""
    return 2.0 + (rows - 100_000) * (15.0 - 2.0) / 900_000


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=100_000)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--profile", action="store_true")
    parser.add_argument("--baseline-src", type=Path, default=None)
    parser.add_argument("--db", type=Path, default=None)
    args = parser.parse_args()
    import granudb
    from granudb.api.database import connect

    # Bytecode as an installed granudb has it (pip compiles it): where
    # PYTHONDONTWRITEBYTECODE is set, a source checkout otherwise recompiles every
    # module of granudb in every report process (about 0.1 s here), which the floor's
    # installed libraries never do.
    compiled = [Path(granudb.__file__).parent]
    if args.baseline_src is not None:
        compiled.append(args.baseline_src / "granudb")
    for folder in compiled:
        compileall.compile_dir(folder, quiet=1)
    from granudb.io.collision_import import import_collisions

    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        db = None if args.db is None else args.db.resolve()
        if db is None:
            data = folder / "collisions.csv"
            write_csv(data, args.rows)
            db = folder / "granudb.sqlite"
            database = connect(str(db))
            import_collisions(database, data, dataset="benchmark")
            database.dispose()
        out = folder / "report.html"
        argv = [sys.executable, "-m", "granudb", "report", "--dataset", "benchmark"]
        argv += ["--format", "html", "--output", str(out), "--force", "--db", str(db)]
        runs, floors, baseline = [], [], []
        source = None if args.baseline_src is None else args.baseline_src.resolve()
        for _ in range(args.runs):
            runs.append(timed(argv))
            floors.append(timed([sys.executable, "-c", FLOOR]))
            if source is not None:
                baseline.append(timed(argv, source))
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
    times = [t for t, _, _ in runs]
    cpu = statistics.median(c for _, _, c in runs)
    peak_mb = max(m for _, m, _ in runs)
    median = statistics.median(times)
    limit = bound_s(args.rows)
    floor = statistics.median(t for t, _, _ in floors)
    floor_cpu = statistics.median(c for _, _, c in floors)
    print(f"load average at the end: {', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print(f"report on {args.rows:,} runs: median {median:.2f} s of {args.runs} ({times})")
    print(f"import floor (same run): median {floor:.2f} s; report = {median / floor:.1f}× floor")
    print(
        f"CPU time: report median {cpu:.2f} s, floor {floor_cpu:.2f} s "
        f"({cpu / floor_cpu:.1f}× floor)"
    )
    if baseline:
        before = statistics.median(t for t, _, _ in baseline)
        before_cpu = statistics.median(c for _, _, c in baseline)
        print(
            f"baseline {args.baseline_src} (same run): median {before:.2f} s (CPU "
            f"{before_cpu:.2f} s), peak {max(m for _, m, _ in baseline):,.0f} MB; this version "
            f"takes {median / before:.2f}× its time ({before / median:.1f}× faster; CPU "
            f"{cpu / before_cpu:.2f}×)"
        )
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
