"""Fits that use the runs' stated speed uncertainties (issue 27): every bootstrap resample
also redraws each run's measured v_n,in and v_n,out from their stated u, so a dataset with
per-run velocity uncertainties gives wider intervals than the same runs without, and the
intervals still cover the truth on synthetic runs measured with that noise."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from granudb.analysis import fits

TRUTH = {"e_dry": 0.95, "parameter": 35.0}
#: The relative standard uncertainty of each measured speed (a high-speed camera's few %).
U_REL = 0.04


def measured(seed: int, *, n: int = 20, stated: bool = True) -> pd.DataFrame:
    """Runs whose true St_n and e follow the exponential law, measured through speeds with
    U_REL relative noise: St_n ∝ v_n,in and e = v_n,out / v_n,in carry it."""
    rng = np.random.default_rng(seed)
    st_true = np.geomspace(15, 3000, n)
    v_in_true = st_true * 1e-3  # m/s; St_n ∝ v_n,in at a fixed sphere and fluid
    e_true = fits.restitution_curve("exponential", st_true, *TRUTH.values())
    v_in = v_in_true * (1 + U_REL * rng.standard_normal(n))
    v_out = e_true * v_in_true * (1 + U_REL * rng.standard_normal(n))
    frame = pd.DataFrame(
        {
            "dataset": "d",
            "particle": "steel",
            "wall": "Zerodur",
            "fluid": "glycerol-37",
            "v_n_in_m_s": v_in,
            "v_n_out_m_s": v_out,
            "normal_stokes_number": st_true * v_in / v_in_true,
            "normal_restitution": v_out / v_in,
        }
    )
    if stated:
        frame["u_v_n_in_m_s"] = U_REL * v_in
        frame["u_v_n_out_m_s"] = U_REL * v_out
    return frame


def test_stated_velocity_uncertainties_widen_the_intervals() -> None:
    for seed in range(3):
        [with_u] = fits.restitution(measured(seed), "exponential")
        [without] = fits.restitution(measured(seed, stated=False), "exponential")
        assert with_u["parameter"] == without["parameter"]  # the fit itself is the same
        for name in ("parameter", "e_dry"):
            wide = with_u[f"{name}_high"] - with_u[f"{name}_low"]
            narrow = without[f"{name}_high"] - without[f"{name}_low"]
            assert wide > 1.05 * narrow, (seed, name, wide, narrow)
        assert "perturbed by their stated u" in with_u["interval_method"]
        assert "perturbed" not in without["interval_method"]


def test_runs_without_a_stated_u_are_resampled_as_before() -> None:
    frame = measured(0)
    frame["u_v_n_in_m_s"] = np.nan
    frame["u_v_n_out_m_s"] = np.nan
    [empty] = fits.restitution(frame, "exponential")
    [without] = fits.restitution(measured(0, stated=False), "exponential")
    assert empty["parameter_low"] == without["parameter_low"]
    assert empty["parameter_high"] == without["parameter_high"]


@pytest.mark.parametrize("name", ["parameter", "e_dry"])
def test_intervals_with_stated_u_cover_the_truth(name: str) -> None:
    trials = 60
    covered = 0
    for seed in range(trials):
        [fit] = fits.restitution(measured(100 + seed), "exponential")
        covered += fit[f"{name}_low"] <= TRUTH[name] <= fit[f"{name}_high"]
    # 95 % intervals: at least 0.90 (benchmarks/fit_coverage.py measures more trials)
    assert covered / trials >= 0.90, covered
