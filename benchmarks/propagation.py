"""Does every propagated u and 95 % interval of ``derive`` agree with a 10⁶-draw Monte Carlo?

The propagation study of issue 36. For every derived quantity ``granudb.physics.derive``
propagates (``u_<q>``, ``low95_<q>``, ``high95_<q>``, ``propagation_method``), at 1, 5 and
10 % relative input u on every stated input (all 16 sources), in two scenarios:

- **glycerol 37 %, steel on Zerodur** (Joseph & Hunt's pair, v_n = 0.3 m/s, v_t =
  0.17 m/s, C = 6·10⁻⁹ Pa⁻¹): μ_f of (5.8) is strongly non-linear (A(c) of degree 16);
- **near St_c**: glass on Zerodur in a viscous liquid at St_n ≈ 11 (just above St_c = 10),
  where the predicted restitution jumps to 0.

granudb's answer (derive with ``uncertainties``: first order where its per-row check
allows, else its adaptive Monte Carlo) is compared with an independent Monte Carlo: 10⁶
normal draws of the same inputs (another seed, another code path: derive without u on
the draws; a draw outside an input's domain is dropped). PASS when both ends of granudb's
interval are within 5 % of the reference interval's width of the reference's ends, for
every quantity with a spread. Prints the method per quantity and the worst quantity.

    nice -n 10 python benchmarks/propagation.py [--draws 1000000] [--quantities a,b]

Runs without the test extras (no test module is imported).
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from granudb.physics.derive import UNCERTAIN_INPUTS, derive
from granudb.physics.propagation_check import FIRST_ORDER, interval_columns

REFERENCE_SEED = 12345
LEVELS = (0.01, 0.05, 0.10)
#: Ends within this share of the reference interval's width (the criterion).
CRITERION = 0.05

GLYCEROL_37 = {
    "particle_density_kg_m3": 7780.0,
    "particle_youngs_modulus_pa": 190e9,
    "particle_poisson_ratio": 0.27,
    "particle_roughness_rms_m": 23.6e-9,
    "wall_density_kg_m3": 2540.0,
    "wall_youngs_modulus_pa": 91e9,
    "wall_poisson_ratio": 0.24,
    "wall_roughness_rms_m": 15.5e-9,
    "diameter_m": 0.0127,
    "v_n_in_m_s": 0.3,
    "v_t_in_m_s": 0.17,
    "fluid_density_kg_m3": 1090.0,
    "viscosity_pa_s": 3.2e-3,
    "pressure_viscosity_pa_inv": 6e-9,
}
NEAR_CRITICAL = {
    **GLYCEROL_37,
    "particle_density_kg_m3": 2540.0,
    "particle_youngs_modulus_pa": 70e9,
    "particle_poisson_ratio": 0.22,
    "fluid_density_kg_m3": 1200.0,
    "viscosity_pa_s": 0.045,
    "v_t_in_m_s": 0.05,
    "v_n_in_m_s": 1.0,  # scaled below to St_n = 11
}


def near_critical() -> dict[str, float]:
    """``NEAR_CRITICAL`` with v_n set so that St_n = 11 (St_n ∝ v_n)."""
    scenario = dict(NEAR_CRITICAL)
    st_n = float(derive(**scenario)["normal_stokes_number"])
    scenario["v_n_in_m_s"] *= 11.0 / st_n
    return scenario


SCENARIOS = {"glycerol 37 % steel/Zerodur": GLYCEROL_37, "near St_c (St_n = 11)": None}


def stated(scenario: dict[str, float], relative: float) -> dict[str, float]:
    """``relative`` × every input as its standard uncertainty."""
    return {f"u_{k}": relative * abs(v) for k, v in scenario.items() if k in UNCERTAIN_INPUTS}


def reference(
    scenario: dict[str, float], relative: float, draws: int, names: list[str], seed: int
) -> dict[str, tuple[float, float, float]]:
    """name → (sd, 2.5 %, 97.5 % quantiles) of ``draws`` normal draws through derive."""
    rng = np.random.default_rng(seed)
    values: dict[str, list[np.ndarray]] = {name: [] for name in names}
    chunk = 200_000
    for start in range(0, draws, chunk):
        n = min(chunk, draws - start)
        x = {
            k: v + (relative * abs(v) * rng.standard_normal(n) if k in UNCERTAIN_INPUTS else 0)
            for k, v in scenario.items()
        }
        x = {k: np.broadcast_to(np.asarray(v, dtype=float), (n,)) for k, v in x.items()}
        ok = (x["particle_poisson_ratio"] < 0.5) & (x["wall_poisson_ratio"] < 0.5)
        for k in scenario:
            if k not in ("particle_poisson_ratio", "wall_poisson_ratio"):
                ok &= x[k] > 0
        got = derive(**{k: v[ok] for k, v in x.items()})
        for name in names:
            values[name].append(np.asarray(got[name], dtype=float))
    out = {}
    for name in names:
        v = np.concatenate(values[name])
        v = v[np.isfinite(v)]
        if v.size < 2:
            out[name] = (np.nan, np.nan, np.nan)
            continue
        low, high = np.quantile(v, [0.025, 0.975])
        out[name] = (float(np.std(v, ddof=1)), float(low), float(high))
    return out


def compare(
    label: str, scenario: dict[str, float], relative: float, draws: int, only: list[str] | None
) -> tuple[int, int, list[str]]:
    """Print one block of the study; (quantities compared, failures, lines)."""
    start = time.process_time()
    got = derive(**scenario, uncertainties=stated(scenario, relative))
    granudb_s = time.process_time() - start
    method = str(np.asarray(got["propagation_method"]).item())
    names = [k[2:] for k in got if k.startswith("u_") and (not only or k[2:] in only)]
    ref = reference(scenario, relative, draws, names, REFERENCE_SEED)
    print(f"\n{label}, {relative:.0%} on every input (granudb {granudb_s:.2f} s CPU): {method}")
    print(
        f"  {'quantity':27} {'value':>10} {'u':>9} {'MC sd':>9} {'low':>10} {'MC low':>10} "
        f"{'high':>10} {'MC high':>10} {'off':>5}  method"
    )
    compared = fails = 0
    for name in names:
        value = float(np.asarray(got[name], dtype=float))
        u = float(np.asarray(got[f"u_{name}"], dtype=float))
        low95, high95 = interval_columns(name)
        low, high = float(np.asarray(got[low95])), float(np.asarray(got[high95]))
        sd, ref_low, ref_high = ref[name]
        width = ref_high - ref_low
        if not np.isfinite(u) or not width > 0:
            continue  # no u stated for it, or no spread (a constant: walton_factor, …)
        compared += 1
        off = max(abs(low - ref_low), abs(high - ref_high)) / width
        ok = off <= CRITERION
        fails += not ok
        how = "Monte Carlo" if _by_monte_carlo(method, name) else "first order"
        print(
            f"  {name:27} {value:>10.4g} {u:>9.3g} {sd:>9.3g} {low:>10.4g} {ref_low:>10.4g} "
            f"{high:>10.4g} {ref_high:>10.4g} {off:>5.1%}  {how}{'' if ok else '  FAIL'}"
        )
    return compared, fails, []


def _by_monte_carlo(method: str, name: str) -> bool:
    """Whether a row's ``propagation_method`` says the Monte Carlo gave ``name``'s u."""
    if method.startswith(FIRST_ORDER):
        return False
    return name in method.split(" for ", 1)[1].split(";")[0].split(", ")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=1_000_000)
    parser.add_argument("--quantities", default="", help="comma-separated (default: all)")
    args = parser.parse_args(argv)
    only = [q for q in args.quantities.split(",") if q] or None
    total = failed = 0
    for label, scenario in SCENARIOS.items():
        for relative in LEVELS:
            n, f, _ = compare(label, scenario or near_critical(), relative, args.draws, only)
            total, failed = total + n, failed + f
    verdict = "PASS" if not failed else f"FAIL ({failed} of {total})"
    print(f"\n{verdict}: {total} quantity intervals against a {args.draws:,}-draw Monte Carlo")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
