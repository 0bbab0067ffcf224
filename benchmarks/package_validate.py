r"""How much memory and time does ``granudb dataset validate`` need for a large package?

Exports the example dataset as a Data Package folder, replaces its collisions with N rows
(default 2,000,000; run labels made unique, descriptor bytes and sha256 updated), then in
separate processes (so each peak RSS is its own):

- ``granudb.validate_dataset`` on the folder (every check of an import but the storing),
- the floor: reading the same CSV once in the same blocks with pandas (``dtype=str``),
  doing nothing with the cells,
- with ``--frictionless``, ``frictionless validate`` of the same package (the obvious
  alternative tool; slow: it checks row by row in Python).

Prints seconds and peak MB of each, the ratios, and pass/fail against issue 25's bound:
a 2,000,000-row package validates under 400 MB peak.

    python benchmarks/package_validate.py [--rows 2000000] [--frictionless]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "collisions_example.csv"
BOUND_MB = 400

VALIDATE = """
import granudb, sys
result = granudb.validate_dataset(sys.argv[1])
assert result.valid, result.shown
print(result.counts["collisions"])
"""
FLOOR = """
import sys, pandas
rows = 0
with pandas.read_csv(sys.argv[1] + "/data/collisions.csv", dtype=str, keep_default_na=False,
                     chunksize=50_000) as reader:
    for block in reader:
        rows += len(block)
print(rows)
"""


def build(folder: Path, rows: int) -> None:
    import granudb

    db = granudb.connect(folder.parent / "bench.sqlite")
    granudb.import_collisions(EXAMPLE, dataset="bench", db=db)
    granudb.export_dataset("bench", folder, db=db)
    db.dispose()
    data = folder / "data" / "collisions.csv"
    header, *lines = data.read_text(encoding="utf-8").splitlines()
    body = [line.split(",", 1)[1] for line in lines]
    with data.open("w", encoding="utf-8", newline="") as handle:
        handle.write(header + "\n")
        for i in range(rows):
            handle.write(f"r{i},{body[i % len(body)]}\n")
    digest = hashlib.sha256(data.read_bytes()).hexdigest()
    descriptor = json.loads((folder / "datapackage.json").read_text(encoding="utf-8"))
    for resource in descriptor["resources"]:
        if resource["name"] == "collisions":
            resource["bytes"] = data.stat().st_size
            resource["hash"] = f"sha256:{digest}"
    descriptor.pop("granudb:content_hash", None)  # validation does not check it
    (folder / "datapackage.json").write_text(json.dumps(descriptor), encoding="utf-8")


def measure(argv: list[str]) -> tuple[float, float, str]:
    """(seconds, peak MB, stdout) of a child process, peak RSS from GNU time's report."""
    started = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", _PEAK, *argv], capture_output=True, text=True)
    seconds = time.perf_counter() - started
    if done.returncode:
        raise SystemExit(f"{argv[:2]} failed: {done.stderr[-2000:]}")
    out, peak = done.stdout.rsplit("\n", 2)[-3:-1]
    return seconds, float(peak) / 1024, out


#: Runs a command as a child and prints its output, then its peak RSS in kB.
_PEAK = """
import resource, subprocess, sys
done = subprocess.run(sys.argv[1:], capture_output=True, text=True)
sys.stdout.write(done.stdout)
sys.stderr.write(done.stderr)
print()
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
sys.exit(done.returncode)
"""


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--rows", type=int, default=2_000_000)
    parser.add_argument("--frictionless", action="store_true")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "package"
        build(folder, args.rows)
        size = (folder / "data" / "collisions.csv").stat().st_size / 1e6
        print(f"package: {args.rows:,} collisions, {size:.0f} MB of CSV")
        seconds, peak, out = measure([sys.executable, "-c", VALIDATE, str(folder)])
        assert int(out.strip()) == args.rows, out
        floor_s, floor_mb, _ = measure([sys.executable, "-c", FLOOR, str(folder)])
        print(f"granudb validate_dataset: {seconds:.1f} s, {peak:.0f} MB peak")
        print(f"pandas read in blocks (floor): {floor_s:.1f} s, {floor_mb:.0f} MB peak")
        print(f"ratio: {seconds / floor_s:.2f}× the time, {peak / floor_mb:.2f}× the memory")
        if args.frictionless:
            f_s, f_mb, _ = measure(
                [sys.executable, "-m", "frictionless", "validate", str(folder / "datapackage.json")]
            )
            print(f"frictionless validate: {f_s:.1f} s, {f_mb:.0f} MB peak "
                  f"(granudb: {seconds / f_s:.2f}× its time)")  # fmt: skip
        verdict = "pass" if peak < BOUND_MB else "FAIL"
        print(f"bound: peak < {BOUND_MB} MB at {args.rows:,} rows: {verdict}")
        print(f"load average: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
