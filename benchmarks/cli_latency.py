"""How long does each ``granudb`` command take to answer, against Python's own start-up?

Creates a seeded SQLite database in a temporary folder, then times, in one run and
interleaved round by round (so a busy machine slows every command alike), each command
below and three baselines:

- ``python -c pass``: the interpreter alone;
- the floor, ``python -c "import sqlalchemy, sqlalchemy.orm"``: a command that reads the
  database through SQLAlchemy's ORM cannot start faster than this;
- ``sqlite-utils tables FILE`` on the same file (when sqlite-utils is installed), the
  obvious alternative tool for a look at a SQLite file.

granudb's bytecode is written first, as ``pip install .`` leaves it (README's figures are
so measured): an editable install run with ``PYTHONDONTWRITEBYTECODE`` set would otherwise
compile every granudb module again in each timed process, which SQLAlchemy, installed
with its bytecode, does not.

Each figure is the median of ``--runs`` (default 5) after one warm-up round. Prints each
command's median, its ratio to each baseline and pass/fail against issue 17's bounds:
``--help`` ≤ 4× ``python -c pass``; ``materials list --format json`` ≤ 1.3× the floor;
``pair … --format json`` ≤ 1.5× the floor. Exit code 1 if a bound fails.

    python benchmarks/cli_latency.py [--runs 5]
"""

from __future__ import annotations

import argparse
import compileall
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from importlib.util import find_spec
from pathlib import Path

PY = sys.executable
GRANUDB = [PY, "-m", "granudb"]
PAIR = [
    "pair",
    "steel",
    "Zerodur",
    "--diameter",
    "12.7 mm",
    "--velocity",
    "0.3 m/s",
    "--fluid",
    "water",
    "--angle",
    "30 deg",
    "--format",
    "json",
]


def commands(db: Path) -> dict[str, list[str]]:
    """Label → argv; baselines first."""
    found = {
        "python -c pass": [PY, "-c", "pass"],
        "floor: import sqlalchemy, sqlalchemy.orm": [
            PY,
            "-c",
            "import sqlalchemy, sqlalchemy.orm",
        ],
    }
    utils = shutil.which("sqlite-utils") or str(Path(PY).with_name("sqlite-utils"))
    if Path(utils).exists():
        found["sqlite-utils tables FILE"] = [utils, "tables", str(db)]
    on_db = ["--db", str(db)]
    found |= {
        "granudb --help": [*GRANUDB, "--help"],
        "granudb materials --help": [*GRANUDB, "materials", "--help"],
        "granudb materials list --format json": [
            *GRANUDB,
            "materials",
            "list",
            "--format",
            "json",
            *on_db,
        ],
        "granudb materials list": [*GRANUDB, "materials", "list", *on_db],
        "granudb fluids list --format json": [
            *GRANUDB,
            "fluids",
            "list",
            "--format",
            "json",
            *on_db,
        ],
        "granudb sources list --format json": [
            *GRANUDB,
            "sources",
            "list",
            "--format",
            "json",
            *on_db,
        ],
        "granudb db current --format json": [*GRANUDB, "db", "current", "--format", "json", *on_db],
        "granudb pair … --format json": [*GRANUDB, *PAIR, *on_db],
        "granudb pair … (table)": [*GRANUDB, *PAIR[:-2], *on_db],
    }
    return found


def run_once(argv: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(argv, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


BOUNDS = [
    # (command, baseline, largest ratio allowed)
    ("granudb --help", "python -c pass", 4.0),
    ("granudb materials list --format json", "floor: import sqlalchemy, sqlalchemy.orm", 1.3),
    ("granudb pair … --format json", "floor: import sqlalchemy, sqlalchemy.orm", 1.5),
]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    compileall.compile_dir(Path(find_spec("granudb").origin).parent, quiet=1)
    with tempfile.TemporaryDirectory() as folder:
        db = Path(folder) / "granudb.sqlite"
        subprocess.run(
            [*GRANUDB, "materials", "list", "--db", str(db)], check=True, capture_output=True
        )
        argvs = commands(db)
        times: dict[str, list[float]] = {label: [] for label in argvs}
        for round_ in range(args.runs + 1):
            for label, argv in argvs.items():
                elapsed = run_once(argv)
                if round_:  # round 0 warms caches
                    times[label].append(elapsed)
    median = {label: statistics.median(values) for label, values in times.items()}
    base = median["python -c pass"]
    floor = median["floor: import sqlalchemy, sqlalchemy.orm"]
    utils = median.get("sqlite-utils tables FILE")
    print(f"medians of {args.runs} runs after a warm-up round (interleaved)")
    print(f"{'command':42} {'median':>8} {'× pass':>7} {'× floor':>8} {'× sqlite-utils':>15}")
    for label, value in median.items():
        vs_utils = f"{value / utils:15.2f}" if utils else f"{'-':>15}"
        print(f"{label:42} {value:7.3f}s {value / base:7.2f} {value / floor:8.2f} {vs_utils}")
    failed = 0
    for label, baseline, limit in BOUNDS:
        ratio = median[label] / median[baseline]
        ok = ratio <= limit
        failed += not ok
        print(
            f"{'PASS' if ok else 'FAIL'}: {label}: {median[label]:.3f} s = {ratio:.2f}× "
            f"{baseline} ({median[baseline]:.3f} s); bound ≤ {limit}×"
        )
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
