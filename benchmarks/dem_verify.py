"""Time ``granudb.dem.verify`` per code: seconds per collision and per whole verify.

Runs the dry paper model (glass and steel spheres, a Zerodur wall: 3 normal and 2
oblique wall impacts per sphere type and 3 head-on impacts per sphere pair, 19 runs)
in every installed code. LIGGGHTS and LAMMPS run one process per collision (4 at a time);
Yade runs all collisions in one process, because its start-up dominates.

    python benchmarks/dem_verify.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from dem.dem_cases import dry_model  # noqa: E402

from granudb.dem import verify as dem_verify  # noqa: E402


def main() -> None:
    model = dry_model()
    todo = dem_verify.cases(model)
    print(f"{'code':9} {'runs':>5} {'total s':>8} {'s/collision':>12} {'max |e err|':>12}")
    for code, binary in dem_verify.installed_codes().items():
        if binary is None:
            print(f"{code:9} not installed: not checked")
            continue
        start = time.perf_counter()
        records = dem_verify.verify(model, todo, codes=[code])
        total = time.perf_counter() - start
        worst = max(abs(r.e_rel_error or 0.0) for r in records)
        print(f"{code:9} {len(records):5d} {total:8.2f} {total / len(records):12.3f} {worst:12.2e}")


if __name__ == "__main__":
    main()
