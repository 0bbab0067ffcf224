"""Restitution fits e(St_n) on synthetic runs (issue 13 item 8; PHYSICS.md §10)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from granudb.analysis import fits


def runs(e_dry: float, model: str, parameter: float, *, n: int = 40, seed: int = 0, dry: int = 0):
    rng = np.random.default_rng(seed)
    st = np.geomspace(15, 3000, n)
    e = fits.restitution_curve(model, st, e_dry, parameter) + rng.normal(0, 0.02, n)
    immersed = pd.DataFrame(
        {
            "dataset": "d",
            "particle": "steel",
            "wall": "Zerodur",
            "fluid": "glycerol-37",
            "normal_stokes_number": st,
            "normal_restitution": e,
        }
    )
    dry_runs = pd.DataFrame(
        {
            "dataset": "d",
            "particle": "steel",
            "wall": "Zerodur",
            "fluid": None,
            "normal_stokes_number": np.nan,
            "normal_restitution": e_dry + rng.normal(0, 0.01, dry),
        }
    )
    return pd.concat([immersed, dry_runs], ignore_index=True) if dry else immersed


@pytest.mark.parametrize("model", ["threshold", "exponential"])
def test_e_dry_never_exceeds_one(model: str) -> None:
    # the old bound was 1.2: a fit returned 1.013
    parameter = 10.0 if model == "threshold" else 35.0
    for seed in range(20):
        [fit] = fits.restitution(runs(1.0, model, parameter, seed=seed), model)
        assert fit["e_dry"] <= 1.0
        assert fit["e_dry_source"] == "fitted, bounded 0 ≤ e_dry ≤ 1"


def test_e_dry_is_fixed_from_the_dry_runs_when_there_are_any() -> None:
    frame = runs(0.97, "exponential", 35.0, dry=8, seed=1)
    [fit] = fits.restitution(frame, "exponential")
    dry_mean = float(frame.loc[frame["fluid"].isna(), "normal_restitution"].mean())
    assert fit["e_dry"] == pytest.approx(dry_mean)
    assert fit["e_dry_source"] == "mean e of the group's 8 dry runs (fixed)"
    assert math.isnan(fit["e_dry_stderr"]) and fit["n_dry_runs"] == 8
    assert fit["parameter"] == pytest.approx(35.0, rel=0.1)


def test_threshold_is_named_as_fitted_and_attributed_honestly() -> None:
    [fit] = fits.restitution(runs(0.97, "threshold", 10.0, seed=2), "threshold")
    assert fit["parameter_name"] == "fitted_critical_stokes"
    assert fit["fitted_critical_stokes"] == pytest.approx(10.0, rel=0.15)
    assert "Davis" not in fit["citation"] and "Gondret" in fit["citation"]
    [fit] = fits.restitution(runs(0.97, "exponential", 35.0, seed=2), "exponential")
    assert "Legendre" in fit["citation"]


def test_an_empty_fit_says_why() -> None:
    frame = runs(0.97, "threshold", 10.0, n=2)
    [fit] = fits.restitution(frame, "threshold")
    assert math.isnan(fit["e_dry"]) and math.isnan(fit["parameter"])
    assert fit["reason"].startswith("St_n must take ≥ 3 distinct values")
