"""How fast is the Walton fit with its bootstrap, against a naive per-resample loop?

Fits N synthetic runs (default 100,000; β = 0.34, μ_f = 0.11, spin in ±30 rad/s) with
``granudb.analysis.fits.walton`` (model selection, split and bootstrap of R resamples,
default 1000, in blocks of resamples × runs ≤ 10⁶ cells), and times the obvious
alternative on a few resamples: a Python loop that draws each resample, sorts it and
re-runs the single-fit model choice. Prints runs × resamples per second for both and their
ratio, and checks that both give the same model and similar β.

    python benchmarks/fit_speed.py [--runs 100000] [--resamples 1000] [--naive 20]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from analysis.synthetic import walton_frame  # noqa: E402

from granudb.analysis import fits  # noqa: E402
from granudb.analysis import walton as core  # noqa: E402


def naive(frame, resamples: int, seed: int) -> np.ndarray:
    """One resample at a time: draw, sort, decide (what a straightforward loop does)."""
    x, y, c, e, *_ = fits.walton_arrays(frame)
    rng = np.random.default_rng(seed)
    betas = []
    for _ in range(resamples):
        pick = rng.integers(0, len(x), len(x))
        order = np.argsort(x[pick], kind="stable")
        xs, ys, cs, es = (a[pick][order] for a in (x, y, c, e))
        betas.append(core.decide(np.ones((1, len(xs))), xs, ys, cs, es).beta[0])
    return np.array(betas)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=100_000)
    parser.add_argument("--resamples", type=int, default=1000)
    parser.add_argument("--naive", type=int, default=20)
    args = parser.parse_args()
    frame = walton_frame(args.runs, spin=30.0, seed=1)
    start = time.perf_counter()
    [fit] = fits.walton(frame, resamples=args.resamples, seed=0)
    fast = time.perf_counter() - start
    start = time.perf_counter()
    betas = naive(frame, args.naive, 0)
    slow = time.perf_counter() - start
    fast_rate = args.runs * args.resamples / fast
    slow_rate = args.runs * args.naive / slow
    print(f"runs {args.runs:,}, resamples {args.resamples}")
    print(
        f"granudb walton (fit + bootstrap): {fast:.2f} s, {args.runs / fast:,.0f} runs/s, "
        f"{fast_rate:,.0f} run-resamples/s"
    )
    print(
        f"naive per-resample loop ({args.naive} resamples): {slow:.2f} s, "
        f"{slow_rate:,.0f} run-resamples/s"
    )
    print(f"ratio (per run-resample): {fast_rate / slow_rate:.1f}×")
    print(
        f"model {fit['model']}, β = {fit['rotational_restitution']:.4f} "
        f"[{fit['rotational_restitution_low']:.4f}, {fit['rotational_restitution_high']:.4f}], "
        f"μ_f = {fit['sliding_friction']:.4f} "
        f"[{fit['sliding_friction_low']:.4f}, {fit['sliding_friction_high']:.4f}]; "
        f"naive β mean {np.nanmean(betas):.4f}"
    )


if __name__ == "__main__":
    main()
