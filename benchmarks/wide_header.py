r"""How much does refusing a package with a very wide header cost (issue 35)?

Exports the example dataset as a Data Package folder twice; in one copy the collisions
header gets N more columns (default 1,000,000: about 8 MB of header; size and sha256
fixed so the header is what is judged). Then, each in its own process (peak RSS from
``VmHWM``, which exec resets):

- the floor: ``granudb dataset validate`` of the unchanged package,
- ``granudb dataset validate`` of the wide one (refused: the header is bounded at
  16 KiB / 200 columns before pandas reads it).

Prints seconds and peak MB of each, their ratio, and pass/fail against issue 35's bound:
refused in under 2 s and 200 MB (before: 3 minutes and 2.9 GB).

    python benchmarks/wide_header.py [--columns 1000000]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "collisions_example.csv"
BOUND_S, BOUND_MB = 2.0, 200

VALIDATE = """
import re, sys
from pathlib import Path
from granudb.cli.main import main
sys.argv = ["granudb", "dataset", "validate", sys.argv[1]]
try:
    main()
except SystemExit:
    pass
status = Path("/proc/self/status").read_text()
print(int(re.search(r"VmHWM:\\s*(\\d+) kB", status).group(1)) / 1024, file=sys.stderr)
"""


def build(folder: Path, columns: int) -> None:
    import granudb

    db = granudb.connect(folder / "bench.sqlite")
    granudb.import_collisions(EXAMPLE, dataset="bench", db=db)
    granudb.export_dataset("bench", folder / "plain", db=db)
    granudb.export_dataset("bench", folder / "wide", db=db)
    db.dispose()
    wide = folder / "wide"
    data = wide / "data" / "collisions.csv"
    header, rest = data.read_bytes().split(b"\n", 1)
    extra = b",".join(b"c%d" % i for i in range(columns))
    data.write_bytes(header + b"," + extra + b"\n" + rest)
    descriptor = json.loads((wide / "datapackage.json").read_text(encoding="utf-8"))
    for entry in descriptor["resources"]:
        if entry["name"] == "collisions":
            entry["bytes"] = data.stat().st_size
            entry["hash"] = "sha256:" + hashlib.sha256(data.read_bytes()).hexdigest()
    descriptor.pop("granudb:content_hash", None)
    (wide / "datapackage.json").write_text(json.dumps(descriptor), encoding="utf-8")


def _cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def measure(package: Path) -> tuple[float, float, str, float]:
    """(wall seconds, peak MB, what validate printed, CPU seconds) of a child process.
    CPU time is shown beside wall time: on a shared machine the wall time is mostly
    waiting for a core."""
    started, cpu = time.perf_counter(), _cpu()
    done = subprocess.run(
        [sys.executable, "-c", VALIDATE, str(package)], capture_output=True, text=True
    )
    seconds = time.perf_counter() - started
    *said, peak = done.stderr.strip().splitlines()
    shown = (done.stdout + "\n".join(said)).strip().splitlines()[-1]
    return seconds, float(peak), shown, _cpu() - cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--columns", type=int, default=1_000_000)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        build(folder, args.columns)
        plain = measure(folder / "plain")
        wide = measure(folder / "wide")
    for label, (wall, peak, shown, cpu) in (("unchanged package", plain),
                                            (f"+{args.columns:,} columns", wide)):  # fmt: skip
        print(f"{label}: {wall:.2f} s wall, {cpu:.2f} s CPU, {peak:.0f} MB  ({shown[:90]})")
    print(f"ratio: {wide[3] / plain[3]:.2f}x CPU time, {wide[1] / plain[1]:.2f}x memory")
    print(f"load average: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    for what, ok in (("wall", wide[0] < BOUND_S), ("CPU", wide[3] < BOUND_S)):
        verdict = "pass" if ok and wide[1] < BOUND_MB else "FAIL"
        print(f"bound {BOUND_S:g} s ({what}) and {BOUND_MB} MB: {verdict}")


if __name__ == "__main__":
    main()
