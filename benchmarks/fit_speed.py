"""What do the fits cost on 100,000 runs, bootstrap included (issue 13)?

Times, on N synthetic runs of known truth (default 100,000, one group; the generators of
``tests/analysis``):

- the Walton fit (model selection, split, bootstrap) with the documented resample rule
  (``walton_bootstrap.RESAMPLE_RULE``: 200 resamples for one group of 100,000 runs) and
  with 1000 resamples asked for, against two obvious alternatives timed on a few
  resamples in the same run: the straightforward loop (draw a resample, sort it, fit it)
  and the previous vectorised bootstrap (``walton.decide``'s prefix sums on every split of
  every resample). Both alternatives compute the same statistic; the benchmark checks
  that the first resamples agree exactly.
- the gap-viscosity fit (least squares of (5.8) and its bootstrap) and the restitution
  fit (threshold form) on N runs: from 10,000 runs in a group both give the asymptotic
  interval (issue 36; ``granudb.analysis.asymptotic``); each is timed with the bootstrap
  too (``asymptotic_from`` raised), as the code before the switch.
- the Walton and gap-viscosity fits on the same runs measured through noisy speeds, with
  and without the noise stated per run (issue 27): the perturbed bootstrap re-sorts every
  resample and re-decides it by ``walton.decide``, so it is slower; the same-run ratio
  is printed; from 10,000 runs both give the asymptotic interval, whose bias shift comes
  from 16 perturbed copies of the runs. The restitution fit (exponential form) on runs
  with its speeds' u stated likewise, and once with its perturbed bootstrap (before).
  PASS/FAIL against issue 36's bound with stated u: ≤ 3 × 0.6 s for the three fits.

Prints runs × resamples per second, the same-run ratios, and PASS/FAIL for the bound
that keeps a report on 100,000 runs under issue 17's 2 s: all three fits, with the rule,
≤ 0.6 s together (after a warm-up: imports are the report's cost, timed by
``report_speed.py``). The three fits are timed in a row, ``--repeats`` times, and each
time and the total are the median over the repeats (the machine is shared). Each repeat
starts with no kept draws: the first fit draws the resamples' counts and the fits after
it of the same size and seed reuse them (``walton_bootstrap.shared_counts``), as the
fits of one group in a report do; the cost of that one draw is printed too. A last line
times a report's Walton and gap-viscosity fits of one group (the same runs): the second
reuses the first's decided resamples (``walton_bootstrap.batches``).

    python benchmarks/fit_speed.py [--runs 100000] [--naive 10] [--repeats 3]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from granudb.analysis import fits  # noqa: E402
from granudb.analysis import walton as core  # noqa: E402
from granudb.analysis import walton_bootstrap as fast  # noqa: E402
from granudb.analysis.synthetic import (  # noqa: E402
    measured,
    restitution_runs,
    sliding_measured,
    sliding_runs,
    walton_frame,
    walton_measured,
)
from granudb.physics.viscosity import GlycerolWater  # noqa: E402

BOUND_S = 0.6
STATED_BOUND_S = 3 * BOUND_S  # issue 36: with stated u ≤ 3× the bound
#: ``asymptotic_from`` that keeps the bootstrap at every size (the code before issue 36).
BOOTSTRAP_ALWAYS = 10**12


def timed(run, *args, **kwargs):
    start = time.perf_counter()
    out = run(*args, **kwargs)
    return out, time.perf_counter() - start


def straightforward(x, y, c, e, resamples: int, seed: int) -> np.ndarray:
    """One resample at a time: draw, sort, fit (β of each)."""
    rng = np.random.default_rng(seed)
    n, betas = len(x), []
    for pick in rng.integers(0, n, size=(resamples, n)):
        order = np.sort(pick)  # x is sorted: sorted indices sort the resample
        one = core.decide(np.ones((1, n)), x[order], y[order], c[order], e[order])
        betas.append(one.beta[0])
    return np.array(betas)


def dense(x, y, c, e, resamples: int, seed: int) -> np.ndarray:
    """The previous bootstrap: prefix sums at every split of every resample."""
    n = len(x)
    weights = fast.draw_counts(np.random.default_rng(seed), resamples, n, n)
    return core.decide(weights, x, y, c, e).beta


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=100_000)
    parser.add_argument("--naive", type=int, default=10)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    n = args.runs
    frame = walton_frame(n, spin=30.0, seed=1)
    # warm-up: imports (scipy for the restitution fit) and first allocations; a report pays
    # the imports once, and report_speed.py times the whole command
    fits.walton(walton_frame(2000, seed=2))
    fits.restitution(restitution_runs(0.97, "threshold", 20.0, n=50), "threshold")
    fits.gap_viscosity(sliding_runs(1.6e-3, n=50), {"glycerol-37": GlycerolWater(0.37)})
    wet = sliding_runs(1.6e-3, n=n, seed=3)
    wet_e = restitution_runs(0.97, "threshold", 20.0, n=n, seed=4)
    glycerol = {"glycerol-37": GlycerolWater(0.37)}
    runs, before = [], []
    for _ in range(args.repeats):  # the three fits of a report, in a row
        fast.forget_counts()
        cpu = time.process_time()
        [fit], walton_s = timed(fits.walton, frame)
        [gap], gap_s = timed(fits.gap_viscosity, wet, glycerol)
        [rest], rest_s = timed(fits.restitution, wet_e, "threshold")
        cpu = time.process_time() - cpu
        runs.append((walton_s, gap_s, rest_s, walton_s + gap_s + rest_s, cpu))
        # the same fits with the bootstrap at every size (the code before issue 36's switch)
        fast.forget_counts()
        cpu = time.process_time()
        _, w_s = timed(fits.walton, frame, asymptotic_from=BOOTSTRAP_ALWAYS)
        _, g_s = timed(fits.gap_viscosity, wet, glycerol, asymptotic_from=BOOTSTRAP_ALWAYS)
        _, r_s = timed(fits.restitution, wet_e, "threshold", asymptotic_from=BOOTSTRAP_ALWAYS)
        before.append((w_s, g_s, r_s, w_s + g_s + r_s, time.process_time() - cpu))
    walton_s, gap_s, rest_s, total, cpu = np.median(runs, axis=0)
    b_walton, b_gap, b_rest, b_total, b_cpu = np.median(before, axis=0)
    fast.forget_counts()
    _, draw_s = timed(fast.shared_counts, 0, fast.resample_count(n), n)
    [full], full_s = timed(fits.walton, frame, resamples=1000)
    x, y, c, e, *_ = fits.walton_arrays(frame)
    loop, loop_s = timed(straightforward, x, y, c, e, args.naive, 5)
    old, old_s = timed(dense, x, y, c, e, args.naive, 5)
    new = fast.bootstrap(x, y, c, e, args.naive, 5).beta
    same = np.allclose(new, loop, rtol=1e-9, equal_nan=True)
    rate = n * 1000 / full_s
    loop_rate, old_rate = n * args.naive / loop_s, n * args.naive / old_s
    resamples = fast.resample_count(n)
    print(f"Walton fit, {n:,} runs in one group (β = 0.34, μ_f = 0.11, spin ±30 rad/s)")
    print(f"  default ({fit['bootstrap_rule']}): {walton_s:.2f} s (median of {args.repeats})")
    print(
        f"  bootstrap ({fast.RESAMPLE_RULE}): {resamples} resamples, {b_walton:.2f} s (median "
        f"of {args.repeats}; drawing their counts, shared with the fits below: {draw_s:.2f} s)"
    )
    print(f"  1000 resamples: {full_s:.2f} s, {rate:,.0f} run-resamples/s")
    print(
        f"  straightforward loop ({args.naive} resamples): {loop_rate:,.0f} run-resamples/s; "
        f"ratio {rate / loop_rate:.1f}×"
    )
    print(
        f"  previous dense prefix sums ({args.naive} resamples): {old_rate:,.0f} "
        f"run-resamples/s; ratio {rate / old_rate:.1f}×"
    )
    print(f"  same resamples, same β as the loop: {same} (previous: {np.allclose(old, loop)})")
    print(
        f"  β = {fit['rotational_restitution']:.4f} [{fit['rotational_restitution_low']:.4f}, "
        f"{fit['rotational_restitution_high']:.4f}], μ_f = {fit['sliding_friction']:.4f} "
        f"[{fit['sliding_friction_low']:.4f}, {fit['sliding_friction_high']:.4f}]"
    )
    print(
        f"gap viscosity, {n:,} sliding runs: {gap_s:.2f} s ({gap['bootstrap_rule']}; "
        f"bootstrap {b_gap:.2f} s), μ₀ = {gap['gap_viscosity_pa_s'] * 1e3:.3f} mPa·s "
        "(truth 1.600)"
    )
    print(
        f"restitution (threshold), {n:,} runs: {rest_s:.2f} s ({rest['interval_method'][:26]}; "
        f"bootstrap {b_rest:.2f} s), St_c = {rest['fitted_critical_stokes']:.2f} "
        f"[{rest['parameter_low']:.2f}, {rest['parameter_high']:.2f}] (truth 20)"
    )
    fast.forget_counts()
    _, pair_walton_s = timed(fits.walton, wet, asymptotic_from=BOOTSTRAP_ALWAYS)
    _, pair_gap_s = timed(fits.gap_viscosity, wet, glycerol, asymptotic_from=BOOTSTRAP_ALWAYS)
    print(
        f"Walton then gap viscosity on the same {n:,} sliding runs, as a report fits a group: "
        f"{pair_walton_s:.2f} + {pair_gap_s:.2f} s (the gap fit reuses the Walton fit's "
        f"resamples and their decisions; {b_gap:.2f} s alone), both with the bootstrap"
    )
    print(
        f"the three fits with the bootstrap at every size (before): {b_total:.2f} s, CPU time "
        f"{b_cpu:.2f} s (median of {args.repeats}); after / before: {total / b_total:.2f} "
        f"(CPU {cpu / b_cpu:.2f})"
    )
    verdict = "PASS" if total <= BOUND_S and cpu <= BOUND_S else "FAIL"
    print(
        f"{verdict}: all fits with the rule {total:.2f} s (median of {args.repeats}; CPU time "
        f"{cpu:.2f} s, load average {os.getloadavg()[0]:.1f}); bound <= {BOUND_S} s"
    )
    stated_cost(n, args.repeats)


def stated_cost(n: int, repeats: int) -> None:
    """The same runs with and without their speeds' u stated (issue 27), with the default
    (asymptotic from 10,000 runs) and once with the bootstrap (the code before issue 36)."""
    frames = {
        "Walton": (walton_measured(n, stated=False, seed=1), walton_measured(n, seed=1)),
        "gap viscosity": (sliding_measured(3, n=n, stated=False), sliding_measured(3, n=n)),
    }
    fitter = {
        "Walton": lambda f, **k: fits.walton(f, **k),
        "gap viscosity": lambda f, **k: fits.gap_viscosity(f, {}, **k),
    }
    total, cpu_total = 0.0, 0.0
    for name, (plain_frame, given_frame) in frames.items():
        times = []
        for _ in range(repeats):
            fast.forget_counts()
            _, plain_s = timed(fitter[name], plain_frame)
            cpu = time.process_time()
            [given], given_s = timed(fitter[name], given_frame)
            times.append((plain_s, given_s, time.process_time() - cpu))
        plain_s, given_s, cpu = np.median(times, axis=0)
        fast.forget_counts()
        _, boot_s = timed(fitter[name], given_frame, asymptotic_from=BOOTSTRAP_ALWAYS)
        total, cpu_total = total + given_s, cpu_total + cpu
        print(
            f"{name}, {n:,} runs, speeds' u stated: {given_s:.2f} s (CPU {cpu:.2f} s; median of "
            f"{repeats}) against {plain_s:.2f} s without, ratio {given_s / plain_s:.1f}×; with "
            f"the bootstrap (before, once): {boot_s:.2f} s (now: {given['bootstrap_rule']})"
        )
    rest_frame, rest = measured(4, n=n), []
    for _ in range(repeats):
        cpu = time.process_time()
        [given], rest_given_s = timed(fits.restitution, rest_frame, "exponential")
        rest.append((rest_given_s, time.process_time() - cpu))
    rest_s, rest_cpu = np.median(rest, axis=0)
    [boot], rest_boot_s = timed(
        fits.restitution, rest_frame, "exponential", asymptotic_from=BOOTSTRAP_ALWAYS
    )
    print(
        f"restitution (exponential), {n:,} runs, speeds' u stated: {rest_s:.2f} s (CPU "
        f"{rest_cpu:.2f} s; median of {repeats}); with the perturbed bootstrap (before, once): "
        f"{rest_boot_s:.2f} s; k = {given['parameter']:.2f} [{given['parameter_low']:.2f}, "
        f"{given['parameter_high']:.2f}] (bootstrap [{boot['parameter_low']:.2f}, "
        f"{boot['parameter_high']:.2f}]; truth 35)"
    )
    verdict = "PASS" if total <= STATED_BOUND_S and cpu_total <= STATED_BOUND_S else "FAIL"
    print(
        f"{verdict}: the Walton and gap-viscosity fits with the speeds' u stated {total:.2f} s, "
        f"CPU time {cpu_total:.2f} s; bound <= {STATED_BOUND_S:.1f} s"
    )
    total, cpu_total = total + rest_s, cpu_total + rest_cpu
    verdict = "PASS" if total <= STATED_BOUND_S and cpu_total <= STATED_BOUND_S else "FAIL"
    print(
        f"{verdict}: the three fits with the speeds' u stated {total:.2f} s, CPU time "
        f"{cpu_total:.2f} s (restitution, exponential: {rest_s:.2f} s, CPU {rest_cpu:.2f} s); "
        f"bound <= {STATED_BOUND_S:.1f} s"
    )


if __name__ == "__main__":
    main()
