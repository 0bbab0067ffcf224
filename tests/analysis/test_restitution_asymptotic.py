"""The restitution fit's large-n interval (issue 36, "Fast at large n"): from
``asymptotic_from`` immersed runs in a group it gives θ̂ ± t·se (delta method, e_dry's own
variance carried in, the stated u's shift from perturbed copies) instead of the bootstrap,
says so in the record, draws the report's band from the same law, and holds its coverage.
A small version of benchmarks/fit_coverage.py's "large n" cells: n = 2,000 with the switch
lowered to 1,000 through the fit's parameter."""

from __future__ import annotations

import math

import numpy as np
import pytest
from analysis import coverage

from granudb.analysis import asymptotic, bands, fits, restitution_fit, walton_bootstrap
from granudb.analysis.synthetic import restitution_runs

N, SWITCH, SETS, QUICK_BOUND = 2000, 1000, 40, 0.825  # true 0.95: P(< 33 of 40) ≈ 0.3 %


@pytest.mark.parametrize(
    ("model", "stated", "dry", "keys"),
    [
        ("threshold", False, 4, coverage.PARAMETER),
        ("threshold", True, 50, coverage.PARAMETER),
        ("exponential", True, 0, coverage.PARAMETER),
        ("exponential", False, 0, coverage.E_DRY),
    ],
)
def test_asymptotic_interval_holds_its_coverage_and_says_its_method(
    model, stated, dry, keys
) -> None:
    make = coverage.large_sets(model, stated, dry)
    truth = coverage.LARGE_TRUTH[model] if keys == coverage.PARAMETER else 0.97
    said = asymptotic.restitution_method(SWITCH, stated, dry)
    hits = []
    for seed in range(SETS):
        [row] = fits.restitution(make(N, 900 + seed), model, asymptotic_from=SWITCH)
        assert row["bootstrap_resamples"] == 0
        assert row["bootstrap_rule"] == asymptotic.rule(SWITCH)
        assert row["interval_method"].startswith(said)
        value, low, high = (row[k] for k in keys)
        if stated:  # centred on θ̂ − b̂ (t symmetric, not clipped here), b̂ in the words
            words = row["interval_method"][len(said) :]
            assert words.startswith("; the value is θ̂, the fit of the runs as measured, not")
            shifts = dict(
                part.rsplit(" ", 1) for part in words.split("(b̂ = ")[1].split(")")[0].split(", ")
            )
            name = "e_dry" if keys == coverage.E_DRY else restitution_fit.PARAMETER_NAMES[model]
            assert (low + high) / 2 == pytest.approx(value - float(shifts[name]), rel=1e-4)
        else:
            assert low < value < high and "b̂" not in row["interval_method"]
        hits.append(low <= truth <= high)
    assert np.mean(hits) >= QUICK_BOUND, np.mean(hits)


def test_e_dry_of_few_dry_runs_widens_the_interval_by_its_own_variance() -> None:
    """With 4 dry runs the parameter's uncertainty is mostly e_dry's: the interval is far
    wider than with e_dry fitted from the immersed runs, and t on 3 degrees of freedom."""
    frame = restitution_runs(0.97, "threshold", 10.0, n=N, seed=5, dry=4)
    [row] = fits.restitution(frame, "threshold", asymptotic_from=SWITCH)
    immersed = frame[frame["fluid"].notna()]
    dry = frame.loc[frame["fluid"].isna(), "normal_restitution"].to_numpy()
    st = immersed["normal_stokes_number"].to_numpy()
    e = immersed["normal_restitution"].to_numpy()
    fit = (row["e_dry"], row["e_dry_stderr"], row["parameter"], row["parameter_stderr"])
    _, covariance, dof = restitution_fit.asymptotic_law("threshold", st, e, fit, True, 0, None, dry)
    alone, _, _ = restitution_fit.asymptotic_law("threshold", st, e, fit, True, 0, None, None)
    assert covariance[1, 1] > 4 * row["parameter_stderr"] ** 2  # the dry runs' variance in
    assert 3.0 <= dof[1] < 4.0  # Welch–Satterthwaite: nearly all of it from 4 dry runs
    half = (row["parameter_high"] - row["parameter_low"]) / 2
    assert math.isclose(half, 3.182 * math.sqrt(covariance[1, 1]), rel_tol=0.01)  # t(3)
    assert row["e_dry_source"].endswith("(fixed in the fit, its variance in the interval)")


def test_below_the_switch_and_with_a_count_asked_the_bootstrap_is_unchanged() -> None:
    frame = restitution_runs(0.97, "exponential", 35.0, n=N, seed=3, dry=50)
    default = fits.restitution(frame, "exponential")[0]  # 2,000 < ASYMPTOTIC_FROM
    asked = fits.restitution(
        frame, "exponential", resamples=default["bootstrap_resamples"], asymptotic_from=SWITCH
    )[0]
    assert default["bootstrap_resamples"] == 1000 and "bootstrap" in default["interval_method"]
    assert "bootstrap_rule" not in default
    for key in ("parameter", "parameter_low", "parameter_high", "interval_method"):
        assert asked[key] == default[key]  # a count asked for: the same draws, same interval
    large = fits.restitution(frame, "exponential", asymptotic_from=SWITCH)[0]
    assert large["parameter"] == default["parameter"]
    low, high = default["parameter_low"], default["parameter_high"]
    assert abs(large["parameter_low"] - low) < 0.25 * (high - low)  # the two agree here
    assert abs(large["parameter_high"] - high) < 0.25 * (high - low)


@pytest.mark.parametrize("stated", [False, True])
def test_the_band_is_drawn_from_the_intervals_law(stated) -> None:
    make = coverage.large_sets("exponential", stated, 0)
    frame = make(N, 11)
    [row] = fits.restitution(frame, "exponential", asymptotic_from=SWITCH)
    immersed = frame["normal_stokes_number"].notna().to_numpy()
    st = frame["normal_stokes_number"].to_numpy()[immersed]
    e = frame["normal_restitution"].to_numpy()[immersed]
    fit = (row["e_dry"], row["e_dry_stderr"], row["parameter"], row["parameter_stderr"])
    speeds = walton_bootstrap.stated_speeds(frame) if stated else None
    a, p = restitution_fit.asymptotic_sets(
        "exponential", st, e, fit, False, asymptotic.SETS, 0, speeds
    )
    low, high = np.percentile(p, [2.5, 97.5])  # the sets' spread is the interval's
    width = row["parameter_high"] - row["parameter_low"]
    assert abs(low - row["parameter_low"]) < 0.1 * width
    assert abs(high - row["parameter_high"]) < 0.1 * width
    grid = np.geomspace(15, 3000, 20)
    band = bands.restitution_band(frame, row, grid)
    assert band is not None
    curves = restitution_fit.restitution_curve("exponential", grid[None, :], a[:, None], p[:, None])
    assert np.allclose(band[0], np.percentile(curves, 2.5, axis=0))  # the same sets
