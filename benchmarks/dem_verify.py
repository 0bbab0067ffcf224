"""Time ``granudb.dem.verify`` per code: seconds per collision and per whole verify.

Runs the paper model (glass and steel spheres, a Zerodur wall) dry and in 78 % glycerol in
every installed code, with ``verify``'s own matrix: normal wall impacts at 0.1, 0.3 and
0.5 m/s, oblique ones at 30° and 60°, and head-on impacts at 0.1, 0.3 and 0.5 m/s per
sphere pair (19 runs a model). LIGGGHTS and LAMMPS run one process per collision (4 at a
time); Yade runs all collisions in one process, because its start-up dominates. Each line
ends with the verification's verdicts, so a slower code that fails is not mistaken for one
that passes.

    python benchmarks/dem_verify.py
"""

from __future__ import annotations

import time

from dem_models import dry_model, wet_model

from granudb.dem import verify as dem_verify


def main() -> None:
    models = {"dry": dry_model(), "glycerol-78": wet_model("glycerol78")}
    print(
        f"{'code':9} {'model':12} {'runs':>5} {'total s':>8} {'s/collision':>12} "
        f"{'max |e err|':>12}  verdicts"
    )
    for code, binary in dem_verify.installed_codes().items():
        if binary is None:
            print(f"{code:9} not installed: not checked")
            continue
        for label, model in models.items():
            todo = dem_verify.cases(model)
            start = time.perf_counter()
            records = dem_verify.verify(model, todo, codes=[code])
            total = time.perf_counter() - start
            worst = max(abs(r.e_rel_error or 0.0) for r in records)
            print(
                f"{code:9} {label:12} {len(records):5d} {total:8.2f} "
                f"{total / len(records):12.3f} {worst:12.2e}  {dem_verify.summary(records)}"
            )


if __name__ == "__main__":
    main()
