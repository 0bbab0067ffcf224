"""How fast is the vectorized derivation, against the obvious per-row alternative?

Derives every column of ``granudb.physics.derive`` for N random scenarios (default
1,000,000, in chunks to bound memory), then times the obvious alternative on a sample:
a per-row Python loop with scalar math and ``scipy.integrate.quad`` for the friction
integral A(c). Prints rows per second for both, their ratio, peak memory, and the largest
relative disagreement between the two on the sample (should be ≤ 1e-9), and pass/fail
against issue 17's bounds: 1,000,000 scenarios ≤ 0.4 s (scaled linearly for other
``--rows``), peak memory ≤ 250 MB.

Then the same scenarios with every input uncertain (1 % of each of the 16 sources),
timed in the same run in CPU time: ``derive`` with its standard uncertainties, 95 %
intervals, per-row check and verdict probabilities against ``derive`` without, on the
rows where first order holds (the check's own verdict, found with ``monte_carlo=False``),
bound ≤ 3× (issues 27, 36). Its cost where first order does not hold is stated: the
rows the check fails at 1 %, 5 % and 10 % on a ``--mc-sample`` of the scenarios, those
the Monte Carlo served within one call's draw budget and those left at first order, the
draws and the CPU time.

The timed figure is ``derive()`` alone: drawing the random scenarios (numpy's generator,
not granudb) is timed apart and printed on its own line. ``--threads`` is passed to
``derive`` (default: its own, the calling thread only).

    python benchmarks/derive_speed.py [--rows 1000000] [--sample 2000] [--chunk 250000]
                                      [--repeats 5] [--threads N] [--mc-sample 2000]
"""

from __future__ import annotations

import argparse
import math
import resource
import statistics
import time

import numpy as np
from scipy.integrate import quad

from granudb.physics.derive import derive
from granudb.physics.propagation_check import DRAW_BUDGET, FIRST_ORDER


def scenarios(n: int, seed: int) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(seed)
    return {
        "particle_density_kg_m3": rng.uniform(1000, 8000, n),
        "particle_youngs_modulus_pa": rng.uniform(1e9, 2e11, n),
        "particle_poisson_ratio": rng.uniform(0.1, 0.45, n),
        "particle_roughness_rms_m": rng.uniform(1e-9, 1e-6, n),
        "wall_density_kg_m3": rng.uniform(1000, 8000, n),
        "wall_youngs_modulus_pa": rng.uniform(1e9, 2e11, n),
        "wall_poisson_ratio": rng.uniform(0.1, 0.45, n),
        "wall_roughness_rms_m": rng.uniform(1e-9, 1e-6, n),
        "diameter_m": rng.uniform(1e-3, 3e-2, n),
        "v_n_in_m_s": rng.uniform(0.01, 2.0, n),
        "v_t_in_m_s": rng.uniform(0.0, 2.0, n),
        "fluid_density_kg_m3": rng.uniform(990, 1260, n),
        "viscosity_pa_s": rng.uniform(5e-4, 0.5, n),
        "pressure_viscosity_pa_inv": np.full(n, 6e-9),
    }


def per_row(row: dict[str, float]) -> dict[str, float]:
    """The obvious implementation: one scenario at a time, quad for A(c)."""
    e_star = 1 / (
        (1 - row["particle_poisson_ratio"] ** 2) / row["particle_youngs_modulus_pa"]
        + (1 - row["wall_poisson_ratio"] ** 2) / row["wall_youngs_modulus_pa"]
    )
    r = row["diameter_m"] / 2
    vn, vt, mu = row["v_n_in_m_s"], row["v_t_in_m_s"], row["viscosity_pa_s"]
    rho_p = row["particle_density_kg_m3"]
    load = 4 / 3 * r**2 * e_star * (5 * math.pi * rho_p * vn**2 / (4 * e_star)) ** 0.6
    a = (3 * r * load / (4 * e_star)) ** (1 / 3)
    p = 3 * load / (2 * math.pi * a**2)
    eta = row["pressure_viscosity_pa_inv"] / 16
    c = eta * p
    integral, _ = quad(
        lambda z: (1 + c * math.sqrt(1 - z * z)) ** 16 * z, 0, 1, epsabs=0, epsrel=1e-13, limit=200
    )
    h = 4.3384 * r * (mu * vt * eta / r) ** (5 / 7) * (load / (e_star * r**2)) ** (-1 / 21)
    friction = 2 * math.pi * mu * vt * a**2 * integral / (load * h)
    x1 = (4 * mu * vn * r**1.5 / (math.pi * e_star)) ** 0.4
    return {
        "reduced_modulus_pa": e_star,
        "stokes_number": 2 * rho_p * r * math.hypot(vn, vt) / (9 * mu),
        "impact_load_n": load,
        "max_pressure_pa": p,
        "min_gap_m": x1 / 3,
        "friction_integral": integral,
        "lubricated_friction": friction,
    }


def uncertainties(
    chunk: dict[str, np.ndarray], relative: float = 0.01
) -> dict[str, np.ndarray | float]:
    """``relative`` × every input (all 16 sources) as its standard uncertainty."""
    return {f"u_{name}": relative * np.abs(values) for name, values in chunk.items()}


def _first_order_rows(args: argparse.Namespace) -> list[np.ndarray]:
    """Per chunk, the rows whose check keeps first order at 1 % (no Monte Carlo run)."""
    kept, done = [], 0
    while done < args.rows:
        n = min(args.chunk, args.rows - done)
        chunk = scenarios(n, seed=done)
        got = derive(**chunk, uncertainties=uncertainties(chunk), monte_carlo=False)
        kept.append(np.asarray(got["propagation_method"]) == FIRST_ORDER)
        done += n
    return kept


def _cpu_pass(args: argparse.Namespace, kept: list[np.ndarray], uncertain: bool) -> float:
    """CPU seconds in derive() over the first-order rows of every chunk."""
    spent, done = 0.0, 0
    for rows in kept:
        n = rows.size
        chunk = {k: v[rows] for k, v in scenarios(n, seed=done).items()}
        extra = {"uncertainties": uncertainties(chunk)} if uncertain else {}
        start = time.process_time()
        derive(**chunk, threads=args.threads, **extra)
        spent += time.process_time() - start
        done += n
    return spent


def _monte_carlo_cost(args: argparse.Namespace, relative: float) -> str:
    """One line: on ``--mc-sample`` rows, the rows the check fails, those the Monte Carlo
    served within the call's draw budget (``DRAW_BUDGET``) and those it left at first
    order, the draws and the CPU time; the budget bounds the cost at any size."""
    sample = scenarios(args.mc_sample, seed=99)
    start = time.process_time()
    got = derive(**sample, uncertainties=uncertainties(sample, relative))
    spent = time.process_time() - start
    start = time.process_time()
    derive(**sample)
    plain = time.process_time() - start
    methods = [str(m) for m in np.asarray(got["propagation_method"]) if m != FIRST_ORDER]
    served = [m for m in methods if m.startswith("Monte Carlo")]
    draws = sum(int(m.split(" draws")[0].split(", ")[-1].replace(",", "")) for m in served)
    return (
        f"  {relative:>4.0%}: the check fails on {len(methods):,} of {args.mc_sample:,} rows "
        f"({len(methods) / args.mc_sample:.1%}); the Monte Carlo served {len(served):,} "
        f"({draws:,} draws), {len(methods) - len(served):,} kept first order (the call's "
        f"budget of {DRAW_BUDGET:,} draws); {spent:.2f} s CPU ({spent / max(plain, 1e-9):,.0f}x "
        f"plain); a call on any number of rows spends at most the budget on draws"
    )


def _one_pass(args: argparse.Namespace, uncertain: bool = False) -> tuple[float, float]:
    """(seconds in derive(), seconds drawing the scenarios) for ``--rows`` scenarios;
    ``uncertain``: with every input's uncertainty (``uncertainties``)."""
    vectorized_s = drawing_s = 0.0
    done = 0
    while done < args.rows:
        n = min(args.chunk, args.rows - done)
        start = time.perf_counter()
        chunk = scenarios(n, seed=done)
        extra = {"uncertainties": uncertainties(chunk)} if uncertain else {}
        drawing_s += time.perf_counter() - start
        start = time.perf_counter()
        derive(**chunk, threads=args.threads, **extra)
        vectorized_s += time.perf_counter() - start
        del chunk
        done += n
    return vectorized_s, drawing_s


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=1_000_000)
    parser.add_argument("--sample", type=int, default=2_000)
    parser.add_argument("--chunk", type=int, default=250_000)
    parser.add_argument("--threads", type=int, default=None)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--mc-sample", type=int, default=2_000)
    args = parser.parse_args()

    # One warm-up pass, then the median of ``--repeats`` passes (a shared machine's
    # neighbours move a single pass by ±30 %).
    passes = [_one_pass(args) for _ in range(args.repeats + 1)][1:]
    vectorized_s = statistics.median(p[0] for p in passes)
    drawing_s = statistics.median(p[1] for p in passes)
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # before the next
    # with uncertainties, on the rows where first order holds: alternating with passes
    # without, so both see the same machine (CPU time)
    kept = _first_order_rows(args)
    first_rows = int(sum(k.sum() for k in kept))
    pairs = [(_cpu_pass(args, kept, True), _cpu_pass(args, kept, False))
             for _ in range(args.repeats)]  # fmt: skip
    uncertain_s = statistics.median(p[0] for p in pairs)
    plain_s = statistics.median(p[1] for p in pairs)
    costs = [_monte_carlo_cost(args, relative) for relative in (0.01, 0.05, 0.10)]

    sample = scenarios(args.sample, seed=12345)
    start = time.perf_counter()
    slow = [per_row({k: float(v[i]) for k, v in sample.items()}) for i in range(args.sample)]
    per_row_s = time.perf_counter() - start
    fast = derive(**sample)
    worst = 0.0
    for name in slow[0]:
        reference = np.array([row[name] for row in slow])
        worst = max(worst, float(np.max(np.abs(fast[name] / reference - 1))))

    fast_rate = args.rows / vectorized_s
    slow_rate = args.sample / per_row_s
    print(
        f"vectorized derive(): {args.rows:,} rows in {vectorized_s:.2f} s = "
        f"{fast_rate:,.0f} rows/s (median of {args.repeats} after a warm-up; chunks of "
        f"{args.chunk:,}, threads {args.threads or 'default'})"
    )
    print(f"drawing the random scenarios (not timed above): {drawing_s:.2f} s")
    print(
        f"per-row Python + quad: {args.sample:,} rows in {per_row_s:.2f} s = "
        f"{slow_rate:,.0f} rows/s"
    )
    print(f"ratio: {fast_rate / slow_rate:,.0f}x")
    print(f"peak memory (max RSS): {peak_mb:,.0f} MB")
    print(f"largest relative disagreement on the sample: {worst:.2e} (must be <= 1e-9)")
    limit_s = 0.4 * args.rows / 1_000_000
    ok_time, ok_memory = vectorized_s <= limit_s, peak_mb <= 250
    print(
        f"{'PASS' if ok_time else 'FAIL'}: derive {vectorized_s:.2f} s; bound <= {limit_s:.2f} s "
        f"({vectorized_s / limit_s:.2f}x the bound)"
    )
    print(f"{'PASS' if ok_memory else 'FAIL'}: peak memory {peak_mb:,.0f} MB; bound <= 250 MB")
    ratio = uncertain_s / plain_s
    print(
        f"derive with uncertainties (1 % on all 16 sources; 35 u columns, 70 interval ends, "
        f"3 probabilities, the per-row check): first order holds on {first_rows:,} of "
        f"{args.rows:,} rows; on them {uncertain_s:.2f} s CPU, without u, same run: "
        f"{plain_s:.2f} s CPU"
    )
    print(f"{'PASS' if ratio <= 3 else 'FAIL'}: with/without = {ratio:.2f}x; bound <= 3x")
    print("cost where first order does not hold (per-row Monte Carlo, same scenarios' law):")
    for line in costs:
        print(line)
    after_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak memory with uncertainties too (max RSS): {after_mb:,.0f} MB")
    if worst > 1e-9:
        raise SystemExit("the two implementations disagree")


if __name__ == "__main__":
    main()
