"""Coverage with an error the catalogue shares with every run (issue 36, docs/intervals.md,
"What the catalogue states").

A fit's runs stand on values from the catalogue: St_n on the particle's ρ and d and the
fluid's μ(T); g of (5.8) on E*, R* and the pressure–viscosity coefficient; the gap
temperature on the fluid's μ(T) curve. Where the catalogue is off, it is off by one factor
for every run of the fit, which no resampling of the runs can see. For each study, the
catalogue's error is drawn once per synthetic set (``--sets`` sets a cell, known truth,
``granudb.analysis.synthetic``), and the interval of the runs alone is compared with the
interval widened by the catalogue's share (``granudb.analysis.shared_scale``):

- ``restitution``: St_c (threshold, 10) and k (exponential, 35), 5 % on St_n, at
  n = 5, 10, 30 and 100;
- ``gap``: μ₀ (1.6 mPa·s), 2 % on E* (g moves 2.6–2.9 × that through A(c), μ₀ by 3.5 ×
  g's), at n = 5, 8, 30 and 300;
- ``curve``: the gap temperature, the fluid's μ(T) (falling 2.5 % a kelvin) off by a
  factor of log-sd 5 %, at n = 5, 8, 30 and 300.

Each cell prints the share of sets given an interval and the coverage of those, alone and
widened, with PASS (widened ≥ 0.90) or FAIL; exit status 1 on a FAIL.
``tests/analysis/test_shared_scale.py`` keeps 30- and 40-set versions.

    nice -n 10 python benchmarks/shared_scale_coverage.py [--sets 200] [--only curve]
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable, Iterator

import numpy as np

from granudb.analysis import fits, gap_viscosity_fit
from granudb.analysis.synthetic import restitution_runs, sliding_runs
from granudb.physics.viscosity import TabulatedViscosity

BOUND = 0.90
KEY = ("d", "steel", "Zerodur")
GAP_KEY = ("synthetic", "steel", "Zerodur", "glycerol-37")
FLUID = "glycerol-37"
#: The catalogue's error (log-sd) of St_n, of E*, and of the μ(T) curve.
STOKES_SHARE, MODULUS_SHARE, CURVE_SHARE = 0.05, 0.02, 0.05
VISCOSITY = 1.6e-3  # μ₀, Pa·s


def _draw(seed: int, share: float) -> float:
    """The catalogue's one factor for the set ``seed``."""
    return math.exp(share * np.random.default_rng(20_000 + seed).standard_normal())


def _restitution(model: str, truth: float, n: int, seed: int, widen: bool) -> tuple:
    frame = restitution_runs(0.97, model, truth, n=n, seed=seed)
    frame["normal_stokes_number"] *= _draw(seed, STOKES_SHARE)
    scale = {KEY: (STOKES_SHARE, "the study's catalogue")} if widen else None
    [row] = fits.restitution(frame, model, stokes_scale=scale)
    return row["parameter_low"], row["parameter_high"], truth


def _modulus_share() -> float:
    """u_r of g for MODULUS_SHARE on E*: g's log slope in E* on the study's runs."""
    frame = sliding_runs(VISCOSITY, n=300, seed=0)
    inputs = frame.assign(normal_speed_m_s=frame["v_n_in_m_s"])
    g = gap_viscosity_fit.model_friction(inputs, 1.0)
    moved = inputs.assign(reduced_modulus_pa=inputs["reduced_modulus_pa"] * 1.001)
    slope = float(np.mean(np.log(gap_viscosity_fit.model_friction(moved, 1.0) / g)))
    return abs(slope / math.log(1.001)) * MODULUS_SHARE


def _gap(share: float, n: int, seed: int, widen: bool) -> tuple:
    frame = sliding_runs(VISCOSITY, n=n, seed=seed)
    frame["reduced_modulus_pa"] *= _draw(seed, MODULUS_SHARE)
    scale = {GAP_KEY: (share, "E*")} if widen else None
    [row] = fits.gap_viscosity(frame, {}, gap_scale=scale)
    return row["gap_viscosity_low_pa_s"], row["gap_viscosity_high_pa_s"], VISCOSITY


def curve(shift: float = 1.0) -> TabulatedViscosity:
    """The study's μ(T): 3 mPa·s at 20 °C falling 2.5 % a kelvin, times ``shift``."""
    temperatures = np.arange(0.0, 81.0, 5.0)
    return TabulatedViscosity(temperatures, shift * 3.0e-3 * np.exp(-0.025 * (temperatures - 20)))


def _curve(n: int, seed: int, widen: bool) -> tuple:
    frame = sliding_runs(VISCOSITY, n=n, seed=seed, fluid=FLUID)
    models = {FLUID: curve(_draw(seed, CURVE_SHARE))}  # the catalogue's curve, off
    curves = {FLUID: lambda _t: CURVE_SHARE} if widen else None
    [row] = fits.gap_viscosity(frame, models, curves=curves)
    truth = float(curve().temperature_for_viscosity(VISCOSITY))
    return row["gap_temperature_low_c"], row["gap_temperature_high_c"], truth


def studies() -> Iterator[tuple[str, tuple[int, ...], Callable[[int, int, bool], tuple]]]:
    """(cell name, sizes, fit(n, seed, widen) → (low, high, truth))."""
    yield (
        "restitution: threshold St_c, 5 % on St_n",
        (5, 10, 30, 100),
        (lambda n, seed, widen: _restitution("threshold", 10.0, n, seed, widen)),
    )
    yield (
        "restitution: exponential k, 5 % on St_n",
        (5, 10, 30, 100),
        (lambda n, seed, widen: _restitution("exponential", 35.0, n, seed, widen)),
    )
    share = _modulus_share()
    yield (
        f"gap: μ₀, 2 % on E* (g {share:.2%})",
        (5, 8, 30, 300),
        (lambda n, seed, widen: _gap(share, n, seed, widen)),
    )
    yield "curve: gap temperature, 5 % on μ(T)", (5, 8, 30, 300), _curve


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sets", type=int, default=200)
    parser.add_argument("--only", nargs="*", default=[], help="substrings of the cells' names")
    args = parser.parse_args()
    failed = False
    for name, sizes, fit in studies():
        if args.only and not any(part in name for part in args.only):
            continue
        for n in sizes:
            given = {False: 0, True: 0}
            hits = {False: 0, True: 0}
            for seed in range(args.sets):
                for widen in (False, True):
                    low, high, truth = fit(n, seed, widen)
                    if math.isfinite(low) and math.isfinite(high):
                        given[widen] += 1
                        hits[widen] += low <= truth <= high
            alone, wide = (hits[w] / max(given[w], 1) for w in (False, True))
            verdict = "PASS" if wide >= BOUND else "FAIL"
            failed |= verdict == "FAIL"
            print(
                f"{name}, n = {n}: given {given[True] / args.sets:.0%}; coverage of the runs "
                f"alone {alone:.3f}, widened {wide:.3f}: {verdict}",
                flush=True,
            )
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
