"""Do the fits' nominal 95 % intervals hold the truth at least 90 % of the time (issue 23)?

For every fit parameter (Walton β, μ_f and ē; the restitution fits' e_dry and St_c or k; the
gap viscosity μ₀) and every n in 3, 5, 10, 30, 100: ``--sets`` synthetic sets of known truth
(``granudb.analysis.synthetic``, noise included; with and without stated u; e_dry from 4 and
from 50 dry runs: the threshold fit with and without stated u, the exponential without, the
Bayesian threshold fit both ways) are fitted with the fit's own defaults (resample rule,
seed), and the share of sets whose interval holds the truth is printed with the bound 0.90,
the share of sets given a value and an interval, and the reason when the interval was
refused. An n at which the fit refuses every interval (below its stated minimum) is
"refused", not a failure. Each row names the method(s) that gave its intervals (bootstrap-t,
small-n t, Bayes, asymptotic). n = 10,000 is not in the default sizes (``--sizes 10000``
runs it): there the Walton and gap-viscosity fits give the asymptotic interval
(``granudb.analysis.asymptotic``, from 10,000 runs; seconds a cell), the restitution fits
too (from issue 36; before it the bootstrap, minutes a cell); the cells named "large n: …"
(both forms, with and without stated u, e_dry fitted or from 4 or 50 dry runs) run at n =
10,000 only. Between 100 and 10,000 runs the fits with stated u give their bootstrap-t;
``--sizes 300 1000 3000 --only "stated u" --skip Bayes "large n"`` measures it there
(0.05–0.94 s CPU a set; docs/intervals.md). The Bayesian restitution cells with stated u
were measured at 300 to 1,000 runs (``--sizes 400 500`` with ``--only "Bayes: restitution
exp."`` or the threshold cell's full name; 5–7 s CPU a set), which placed
``bayesian.STATED_REFUSED_FROM`` (from it add ``--behind-refusals``). Exit status 1 when any
coverage is below the bound, or an interval has zero width. The Bayesian option's rows
("Bayes: …", posterior credible intervals by emcee) run at most ``coverage.BAYES_SETS``
(200) sets per cell: a posterior costs 1–6 s CPU a set (minutes a cell). ``--only`` and
``--skip`` take several substrings (any matches; a case's full name picks that cell alone);
cases on the same synthetic sets share their fits. ``--behind-refusals``: the Bayesian
restitution interval with stated u, refused from ``bayesian.STATED_REFUSED_FROM`` runs, and
Walton β's, refused from ``bayesian.WALTON_BETA_REFUSED_FROM``, are given and measured (what
the refusals rest on). Each row ends with its wall time, the CPU time a set (data, fit and
posterior) and the sets.

    nice -n 10 python benchmarks/fit_coverage.py [--sets 200] [--sizes 3 5 10 30 100]
        [--only "Bayes: Walton μ_f" "Bayes: Walton β"] [--skip Bayes]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from coverage_cases import BOUND, CASES, SIZES, tally  # noqa: E402  (benchmarks/, no test module)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sets", type=int, default=200)
    parser.add_argument("--sizes", type=int, nargs="+", default=list(SIZES))
    parser.add_argument(
        "--only", nargs="+", default=[""], help="cases whose name contains any of these"
    )
    parser.add_argument(
        "--skip", nargs="+", default=["\0"], help="leave out cases whose name contains any"
    )
    parser.add_argument(
        "--behind-refusals",
        action="store_true",
        help="measure the Bayesian restitution interval with stated u where the fit refuses "
        "it (from bayesian.STATED_REFUSED_FROM runs; Walton β's from "
        "bayesian.WALTON_BETA_REFUSED_FROM), to state what the refusals rest on",
    )
    args = parser.parse_args()
    if args.behind_refusals:
        from granudb.analysis import bayesian

        bayesian.STATED_REFUSED_FROM = bayesian.WALTON_BETA_REFUSED_FROM = sys.maxsize
        print("behind the refusals: the Bayesian restitution interval with stated u is given")
    failed = False
    print(f"coverage of nominal 95 % intervals over {args.sets} synthetic sets; bound ≥ {BOUND}")
    print(
        f"{'fit':50} {'n':>4} {'coverage':>9} {'value':>6} {'interval':>9} {'method':>12}  verdict"
    )
    print("(rows marked 'Bayes:' are the Bayesian option, at most their case's most_sets sets)")
    for case in CASES:
        if not any(o in case.name for o in args.only) or any(s in case.name for s in args.skip):
            continue
        for n in [m for m in args.sizes if case.sizes is None or m in case.sizes]:
            start, cpu = time.perf_counter(), time.process_time()
            t = tally(case, n, min(args.sets, case.most_sets or args.sets))
            took, cpu = time.perf_counter() - start, time.process_time() - cpu
            shared = cpu < 0.01 * t.sets  # every fit made for an earlier cell on the same sets
            cost = "fits shared with a cell above" if shared else f"{cpu / t.sets:.2f} s CPU a set"
            if t.given == 0:
                verdict = f"refused ({t.reason or 'no value'})"
            elif t.zero_width:
                verdict, failed = f"FAIL: {t.zero_width} zero-width intervals", True
            elif t.coverage >= BOUND:
                verdict = "PASS"
            else:
                verdict, failed = "FAIL", True
            print(
                f"{case.name:50} {n:>4} {t.coverage:>9.3f} {t.fitted / t.sets:>6.0%} "
                f"{t.given / t.sets:>9.0%} {t.method:>12}  {verdict} "
                f"[{took:.0f} s; {cost}, {t.sets} sets]",
                flush=True,
            )
    print("FAIL" if failed else "PASS")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
