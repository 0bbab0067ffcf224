"""The Bayesian option of the Walton and restitution fits (issue 27): on synthetic known
truth generated here, its posterior summaries agree with the bootstrap and cover the truth;
a chain too short to trust gives no number; the draws are the summaries' own."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from analysis.synthetic import walton_frame
from paper_runs import paper_rows, write_csv

import granudb
from granudb.analysis import bayesian, fits
from granudb.analysis.groups import walton_arrays
from granudb.analysis.synthetic import restitution_runs
from granudb.errors import ValidationError

WALTON = {
    # parameter: (value key, interval prefix, truth of walton_frame's defaults)
    "β": ("rotational_restitution", "rotational_restitution", 0.34),
    "μ_f": ("sliding_friction", "sliding_friction", 0.11),
    "ē": ("normal_restitution_mean", "normal_restitution", None),  # e clipped: truth ≈ 0.97
}


def _agree(bootstrap: dict, bayes: dict, key: str, prefix: str, truth: float | None) -> None:
    boot_low, boot_high = bootstrap[f"{prefix}_low"], bootstrap[f"{prefix}_high"]
    low, high = bayes[f"{prefix}_low"], bayes[f"{prefix}_high"]
    half = (boot_high - boot_low) / 2
    assert abs(bayes[key] - bootstrap[key]) <= half / 2, (key, bootstrap[key], bayes[key], half)
    ratio = (high - low) / (boot_high - boot_low)
    assert 1 / 1.5 <= ratio <= 1.5, (key, ratio)
    if truth is not None:
        assert low <= truth <= high, (key, low, truth, high)


@pytest.mark.parametrize("seed", [3, 11])
def test_walton_posterior_agrees_with_the_bootstrap_and_covers_the_truth(seed: int) -> None:
    frame = walton_frame(60, seed=seed)
    [bootstrap] = fits.walton(frame)
    [bayes] = fits.walton(frame, method="bayes")
    assert bootstrap["model"] == bayes["model"] == "split"
    assert bayes["converged"] and bayes["reason"] == "", bayes["reason"]
    for key, prefix, truth in WALTON.values():
        _agree(bootstrap, bayes, key, prefix, truth)
    assert bayes["sigma"] == pytest.approx(0.01, rel=0.3)  # walton_frame's scatter
    assert "β uniform on [−1, 1]" in bayes["prior"] and "μ_f uniform" in bayes["prior"]
    assert bayes["sampler_walkers"] == bayesian.DEFAULT.walkers
    assert bayes["autocorrelation_time"] * bayesian.AUTOCORRELATION_MULTIPLE <= (
        bayes["sampler_steps"] - bayes["sampler_burn_in"]
    )


@pytest.mark.parametrize(
    ("model", "parameter"), [("exponential", 35.0), ("threshold", 10.0)]
)  # fmt: skip
def test_restitution_posterior_agrees_with_the_bootstrap_and_covers_the_truth(
    model: str, parameter: float
) -> None:
    frame = restitution_runs(0.97, model, parameter, n=40, seed=2)
    [bootstrap] = fits.restitution(frame, model)
    [bayes] = fits.restitution(frame, model, method="bayes")
    assert bayes["converged"] and bayes["interval_reason"] == ""
    _agree(bootstrap, bayes, "parameter", "parameter", parameter)
    _agree(bootstrap, bayes, "e_dry", "e_dry", 0.97)
    stated = "St_c uniform" if model == "threshold" else "k uniform"
    assert stated in bayes["prior"] and "e_dry uniform on (0, 1]" in bayes["prior"]
    if model == "threshold":
        assert bayes["fitted_critical_stokes"] == bayes["parameter"]


def test_stated_per_run_u_of_e_replaces_the_fitted_scatter() -> None:
    frame = restitution_runs(0.97, "exponential", 35.0, n=30, seed=4)  # scatter 0.02
    [fitted] = fits.restitution(frame, "exponential", method="bayes")
    frame["u_normal_restitution"] = 0.06
    [stated] = fits.restitution(frame, "exponential", method="bayes")
    assert "σ_extra (scatter beyond the stated u) half-Cauchy" in stated["prior"]
    assert "u_e² + σ_extra²" in stated["likelihood"]
    assert math.isnan(stated["sigma"]) and fitted["sigma"] == pytest.approx(0.02, rel=0.35)
    assert stated["sigma_extra"] < 0.06  # the stated u already exceeds the scatter
    width = [r["parameter_high"] - r["parameter_low"] for r in (fitted, stated)]
    assert width[1] > 2 * width[0], width
    frame.loc[0, "u_normal_restitution"] = np.nan  # one run without: σ is fitted again
    [partial] = fits.restitution(frame, "exponential", method="bayes")
    assert partial["sigma"] == fitted["sigma"]


def test_a_chain_too_short_to_trust_gives_no_number() -> None:
    frame = restitution_runs(0.97, "exponential", 35.0, n=30, seed=1)
    short = bayesian.Settings(walkers=16, steps=120, burn_in=60)
    [row] = fits.restitution(frame, "exponential", method="bayes", settings=short)
    assert not row["converged"]
    assert row["interval_reason"].startswith("not determined: chain did not converge (")
    assert math.isnan(row["parameter"]) and math.isnan(row["parameter_low"])
    assert math.isnan(row["e_dry"])


def test_the_draws_are_the_summaries_own_and_stated_per_run_u_widens() -> None:
    frame = walton_frame(40, seed=7)
    found: list = []
    [row] = fits.walton(frame, method="bayes", draws=found)
    [draws] = found
    assert list(draws.columns[:6]) == ["dataset", "particle", "wall", "fluid", "chain", "draw"]
    settings = bayesian.DEFAULT
    assert len(draws) == settings.walkers * (settings.steps - settings.burn_in)
    for column in ("rotational_restitution", "sliding_friction", "normal_restitution_mean"):
        assert np.median(draws[column]) == pytest.approx(row[column], rel=1e-12)
    assert np.median(draws["sigma"]) == pytest.approx(row["sigma"], rel=1e-12)
    # The same runs with a stated u three times their scatter: wider intervals, σ not fitted
    x, y, c, e = walton_arrays(frame.reset_index(drop=True))[:4]
    start = (row["rotational_restitution"], row["sliding_friction"])
    fitted = bayesian.walton(x, y, c, e, row["model"], start)
    stated = bayesian.walton(x, y, c, e, row["model"], start, sigma=np.full(len(x), 0.03))
    assert "log_sigma" not in stated.names
    for name in ("beta", "mu_f"):
        width = [np.subtract(*p.summary(name)[2:0:-1]) for p in (fitted, stated)]
        assert width[1] > 2 * width[0], (name, width)


def test_fit_commands_take_the_method_and_write_the_draws(cli, db: str, tmp_path) -> None:
    rows = [r for r in paper_rows(runs_per_group=12) if r[1] == "steel" and r[3] == ""]
    granudb.import_collisions(write_csv(tmp_path / "runs.csv", rows), dataset="d", db=db)
    target = tmp_path / "draws.csv"
    done = cli(
        "fit", "walton", "--method", "bayes", "--draws", str(target), "--format", "json", db=db
    )
    assert done.exit_code == 0, done.stderr
    [row] = json.loads(done.stdout)
    assert row["fit_method"] == "bayes" and row["converged"]
    with target.open(newline="") as handle:
        header = next(csv.reader(handle))
    assert header[:6] == ["dataset", "particle", "wall", "fluid", "chain", "draw"]
    python = granudb.fit_walton(db=db, method="bayes")
    assert python.loc[0, "sliding_friction"] == row["sliding_friction"]  # one door, one answer
    assert len(python.attrs["draws"]) == sum(1 for _ in target.open()) - 1
    again = cli("fit", "walton", "--method", "bayes", "--draws", str(target), db=db)
    assert again.exit_code != 0 and "exists already" in again.stderr  # never overwritten
    wrong = cli("fit", "restitution", "--method", "mcmc", db=db)
    assert wrong.exit_code != 0 and "must be one of bootstrap, bayes" in wrong.stderr
    with pytest.raises(ValidationError, match="need method bayes"):
        granudb.fit_walton(db=db, draws=tmp_path / "other.csv")
    assert not (tmp_path / "other.csv").exists()


def test_an_unknown_method_is_refused_by_name_before_any_fit() -> None:
    with pytest.raises(ValidationError, match="method: mcmc must be one of bootstrap, bayes"):
        fits.walton(walton_frame(12), method="mcmc")
    with pytest.raises(ValidationError, match="must be one of bootstrap, bayes"):
        fits.restitution(restitution_runs(0.97, "threshold", 10.0, n=12), method="mcmc")


def _sliding_measured(n: int, u: float, seed: int):
    """Sliding runs (μ_f = 0.11, B = 3.5) measured through four speeds, each with noise u
    [m/s]: folded (Ψ_in, Ψ_out, e) and ``walton_bootstrap.stated_walton``'s (r, u_e,
    u_in, u_out) for them (each u over the measured v_N,in)."""
    rng = np.random.default_rng(seed)
    vn = rng.uniform(0.1, 0.38, n)
    x, e = rng.uniform(0.8, 2.5, n), rng.uniform(0.85, 0.95, n)
    y = x - 0.11 * (1 + e) * 3.5
    vn_m, out, t_in, t_out = (v + u * rng.standard_normal(n) for v in (vn, e * vn, x * vn, y * vn))
    u_ratio = u / vn_m
    order = np.argsort(t_in / vn_m)
    arrays = (t_in / vn_m, t_out / vn_m, out / vn_m)
    x_m, y_m, e_m = (a[order] for a in arrays)
    return x_m, y_m, e_m, np.stack([u_ratio[order]] * 4)


def _grid_interval(x, y, e, stated, scale, *, extra_scatter: bool = True):
    """μ_f's 95 % equal-tailed interval from a grid posterior computed independently of
    the sampler's effective variance: each run's likelihood integrated numerically over
    f = v_N,in(measured)/v_N,in(true) ~ N(1, r) (201 points, exact in f), the numerators'
    noise Gaussian, σ_extra half-Cauchy(scale) on a grid (or 0), μ_f flat."""
    r, u_e, u_in, u_out = stated
    b = 3.5
    mu = np.linspace(0.06, 0.16, 301)
    extra = np.linspace(0.0, 8 * scale, 161 if extra_scatter else 1)
    t = np.linspace(-6, 6, 201)
    f = 1 + r[:, None] * t[None, :]  # (n, F)
    weight = np.exp(-0.5 * t**2)
    log_post = np.empty((mu.size, extra.size))
    for j, s in enumerate(extra):
        variance = u_out**2 + u_in**2 + (mu[:, None] * b * u_e[None, :]) ** 2 + s**2  # (M, n)
        residual = (y - x + mu[:, None] * b * e)[..., None] + (mu[:, None] * b)[..., None] / f
        density = np.exp(-0.5 * residual**2 / variance[..., None]) / np.sqrt(variance[..., None])
        per_run = np.sum(density * weight, axis=-1)
        log_post[:, j] = np.sum(np.log(per_run), axis=-1) - np.log1p((s / scale) ** 2)
    marginal = np.exp(log_post - log_post.max()).sum(axis=1)
    cdf = np.cumsum(marginal) / marginal.sum()
    return np.interp([0.025, 0.975], cdf, mu)


def test_stated_u_posterior_matches_an_independent_grid_posterior() -> None:
    """Errors in Ψ_in, Ψ_out and e and the shared v_N,in (1 cm/s on 0.1–0.38 m/s): the
    sampler's μ_f interval agrees with a grid posterior that integrates the shared speed
    numerically; the old likelihood (u(Ψ_out) the whole scatter) is under 0.8× as wide
    and would fail."""
    x, y, e, stated = _sliding_measured(15, 0.01, seed=5)
    c = (1 + e) * 3.5
    posterior = bayesian.walton(x, y, c, e, "sliding", (math.nan, 0.11), stated=stated)
    assert not posterior.reason and "sigma_extra" in posterior.names
    _, low, high = posterior.summary("mu_f")
    grid = _grid_interval(x, y, e, stated, float(np.median(stated[3])))
    width = grid[1] - grid[0]
    assert abs(low - grid[0]) < 0.1 * width and abs(high - grid[1]) < 0.1 * width, (
        (low, high),
        grid,
    )
    only_out = stated.copy()
    only_out[:3] = 0.0  # the old likelihood: u(Ψ_out) the whole scatter
    narrow = _grid_interval(x, y, e, only_out, 1.0, extra_scatter=False)
    assert narrow[1] - narrow[0] < 0.8 * width  # the tolerance tells the two apart


def test_e_dry_is_fitted_jointly_with_its_dry_runs() -> None:
    """e_dry is no longer held at the dry runs' mean: its posterior has a width no more
    than the dry runs' own t-interval (the immersed runs add to it) and holds the truth."""
    frame = restitution_runs(0.97, "threshold", 10.0, n=30, seed=3, dry=4)
    [row] = fits.restitution(frame, "threshold", method="bayes")
    assert row["converged"], row["interval_reason"]
    assert "dry runs e ~ Normal(e_dry, σ_dry), jointly" in row["likelihood"]
    assert (
        row["e_dry_source"].startswith("posterior jointly") and "4 dry runs" in row["e_dry_source"]
    )
    dry = frame["normal_restitution"][frame["fluid"].isna()].to_numpy()
    t_width = 2 * 3.182 * np.std(dry, ddof=1) / 2  # t₀.₉₇₅,₃ s/√4, both sides
    assert 0 < row["e_dry_high"] - row["e_dry_low"] <= 1.1 * t_width
    assert row["e_dry_low"] <= 0.97 <= row["e_dry_high"]
    assert row["parameter_low"] <= 10.0 <= row["parameter_high"]
