"""Does the gap-viscosity interval without stated u hold at any speed noise (issue 36)?

Without the runs' stated u the errors-in-variables bias of μ₀ (g of (5.8) is computed
from the same measured speeds as μ_f) grows against its standard error as √n and as the
noise σ: the fit refuses the interval where the bias that the runs' own scatter implies
exceeds a share of q's standard error (``gap_viscosity_fit.scatter_noise``,
``noise_bias``, ``BOOTSTRAP_BIAS_SHARE``, ``BIAS_SHARE``). For each cell (speed noise on
every speed, sliding runs) this prints, over ``--sets`` synthetic sets of known truth
(``granudb.analysis.synthetic.sliding_runs``, μ₀ = 1.6 mPa·s):

- σ̂, the noise the fit reads off the scatter (mean over the sets), against the truth;
- the share of sets given an interval, and the coverage of the given intervals, with the
  bound 0.90 (PASS/FAIL; a cell where none is given is "refused");
- behind the refusal (``--behind``): the coverage of every set's interval with the
  refusal lifted, to show what the refusal rests on.

    nice -n 10 python benchmarks/gap_noise.py [--sets 300] [--cells 0.02:300 0.05:150 …]
        [--behind]
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from granudb.analysis import fits
from granudb.analysis import gap_viscosity_fit as gap
from granudb.analysis.synthetic import sliding_runs

TRUTH = 1.6e-3
BOUND = 0.90
CELLS = ("0.02:300", "0.02:800", "0.02:1000", "0.05:100", "0.05:150", "0.05:200",
         "0.05:300", "0.10:30", "0.10:40", "0.10:60", "0.10:100")  # fmt: skip


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sets", type=int, default=300)
    parser.add_argument("--cells", nargs="+", default=list(CELLS))
    parser.add_argument("--behind", action="store_true", help="lift the refusal")
    args = parser.parse_args()
    if args.behind:
        gap.BOOTSTRAP_BIAS_SHARE = gap.BIAS_SHARE = math.inf
    print(f"gap viscosity μ₀ without stated u, {args.sets} sets a cell; bound ≥ {BOUND}"
          + (" (refusal lifted)" if args.behind else ""))  # fmt: skip
    failed = False
    for cell in args.cells:
        noise, n = float(cell.split(":")[0]), int(cell.split(":")[1])
        start = time.process_time()
        hits, sigmas = [], []
        for seed in range(args.sets):
            frame = sliding_runs(TRUTH, n=n, seed=seed, noise=noise)
            [row] = fits.gap_viscosity(frame, {})
            low, high = row["gap_viscosity_low_pa_s"], row["gap_viscosity_high_pa_s"]
            if math.isfinite(low) and math.isfinite(high):
                hits.append(low <= TRUTH <= high)
            sigmas.append(gap.implied_noise(frame))
        given = len(hits)
        coverage = float(np.mean(hits)) if hits else math.nan
        verdict = "refused" if not hits else ("PASS" if coverage >= BOUND else "FAIL")
        failed |= verdict == "FAIL"
        print(
            f"noise {noise:4.0%} n={n:5d}: σ̂ {np.nanmean(sigmas):.2%}  "
            f"given {given:3d}/{args.sets}  coverage {coverage:.3f}  {verdict}  "
            f"({time.process_time() - start:.0f} s CPU)",
            flush=True,
        )
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
