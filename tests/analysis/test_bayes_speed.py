"""The Bayesian option's cheaper evaluations leave its results unchanged (issue 36): the
Walton log posterior with stated u, now evaluated in reused buffers, equals a direct
transcription of its formula to the last bit, and the same seed gives the same chain;
the restitution posterior from ``bayesian.LARGE_N`` runs with stated u takes its
moments (not the quadrature), and says so."""

from __future__ import annotations

import numpy as np
import pytest

from granudb.analysis import bayesian, fits
from granudb.analysis.groups import walton_arrays
from granudb.analysis.restitution_fit import restitution_curve
from granudb.analysis.synthetic import measured, walton_measured
from granudb.analysis.walton_bootstrap import stated_walton


def _direct(x, y, c, e, model, stated):
    """The Walton log posterior with stated u as its formula reads (the code before issue
    36's speed-up, transcribed): fresh arrays, both lines and both variances everywhere."""
    b = c / (1.0 + e)
    r, u_e, u_in, u_out = stated
    has_beta, has_mu = model != "sliding", model != "sticking"
    scale = float(np.median(u_out[u_out > 0]))

    def log_posterior(p):
        m = len(p)
        beta = p[:, 0] if has_beta else np.zeros(m)
        mu = p[:, int(has_beta)] if has_mu else np.zeros(m)
        extra = p[:, -1]
        stick, slide = -beta[:, None] * x, x - mu[:, None] * c
        if model == "sticking":
            predicted, sticking = stick, np.ones(stick.shape, dtype=bool)
        elif model == "sliding":
            predicted, sticking = slide, np.zeros(slide.shape, dtype=bool)
        else:
            predicted, sticking = np.maximum(stick, slide), stick >= slide
        slide_v = u_out**2 + u_in**2 + (mu[:, None] * b) ** 2 * (u_e**2 + r**2)
        stick_v = u_out**2 + (beta[:, None] * u_in) ** 2
        total = np.where(sticking, stick_v, slide_v) + extra[:, None] ** 2
        residual = y - predicted
        value = -0.5 * np.sum(residual**2 / total + np.log(total), axis=-1)
        value = value - np.log1p((extra / scale) ** 2)
        inside = (beta >= -1) & (beta <= 1) & (mu >= 0) & (extra >= 0)
        return np.where(inside & np.isfinite(value), value, -np.inf)

    return log_posterior


def _walton_inputs(n: int = 40, seed: int = 2):
    frame = walton_measured(n, seed=seed)
    arrays = walton_arrays(frame)
    stated = stated_walton(frame, arrays[5])
    assert stated is not None
    return (*arrays[:4], stated)


@pytest.mark.parametrize("model", ["split", "sliding", "sticking"])
def test_walton_stated_log_posterior_equals_its_direct_formula_bitwise(model: str) -> None:
    x, y, c, e, stated = _walton_inputs()
    fast, names = bayesian.walton_log_posterior(x, y, c, e, model, stated)
    direct = _direct(x, y, c, e, model, stated)
    rng = np.random.default_rng(1)
    centre = {"beta": 0.34, "mu_f": 0.11, "sigma_extra": 0.002}
    for walkers in (1, 16, 16, 7):  # the buffers are reused, and resized
        p = np.array([centre[n] for n in names]) + 0.05 * rng.standard_normal((walkers, len(names)))
        got, want = fast(p), direct(p)
        assert np.isfinite(want).sum() >= 1
        assert np.array_equal(got, want), (model, got - want)


def test_walton_stated_chain_of_the_same_seed_is_the_direct_formulas() -> None:
    """The sampler on the fast and on the direct log posterior: the same draws, exactly."""
    x, y, c, e, stated = _walton_inputs()
    fast, names = bayesian.walton_log_posterior(x, y, c, e, "split", stated)
    settings = bayesian.Settings(walkers=16, steps=200, burn_in=100, seed=4)
    start, spread = np.array([0.34, 0.11, 0.002]), np.array([1e-4, 1e-4, 1e-4])
    one = bayesian.sample(fast, start, spread, names, settings)
    two = bayesian.sample(_direct(x, y, c, e, "split", stated), start, spread, names, settings)
    assert np.array_equal(one.chain, two.chain)


def _integral(form, st, e, r, u_e, p):
    """The stated-u likelihood's integral over s ~ N(1, r), by a dense grid (±8r, 4001
    points) per run and walker: log ∫ N(e; s e(s St_n), √(u_e² + σ_extra²)) N(s; 1, r) ds
    summed over runs (the half-Cauchy prior added, as the posteriors do)."""
    out = []
    for a, q, extra in p:
        grid = 1.0 + r[:, None] * np.linspace(-8, 8, 4001)[None, :]
        h = form.curve(st[:, None] * grid, a, q) * grid
        total = u_e[:, None] ** 2 + extra**2
        density = np.exp(-0.5 * (e[:, None] - h) ** 2 / total) / np.sqrt(total)
        weight = np.exp(-0.5 * ((grid - 1.0) / r[:, None]) ** 2)
        per_run = np.trapezoid(density * weight, grid, axis=1) / np.trapezoid(weight, grid, axis=1)
        scale = float(np.median(u_e))
        out.append(np.sum(np.log(per_run)) - np.log1p((extra / scale) ** 2))
    return np.array(out)


def test_the_restitution_fit_with_stated_u_takes_the_moments_from_large_n() -> None:
    """Below ``LARGE_N`` runs the quadrature, from it the moments; the likelihood's words
    say which. Against the integral itself (a dense grid over s): the threshold form's
    h(s) is linear in s above St_c, so its moments are exact (the log posteriors differ by
    one constant across walkers); the exponential's agree to O(r²) terms."""
    frame = measured(1, n=40)
    assert not bayesian.large_n(40) and bayesian.large_n(bayesian.LARGE_N)
    [row] = fits.restitution(frame, "exponential", method="bayes")
    assert row["likelihood"].startswith("St_n and e share the measured v_N,in")
    words = bayesian.LIKELIHOOD["restitution stated large"]
    assert words.startswith(f"from {bayesian.LARGE_N:,} runs (the large-n approximation)")
    rng = np.random.default_rng(0)
    st = np.geomspace(15, 3000, 40)
    r = np.full(len(st), 0.04)
    for model, truth in (("threshold", 10.0), ("exponential", 35.0)):
        e = restitution_curve(model, st, 0.95, truth) * (1 + 0.04 * rng.standard_normal(40))
        u_e = 0.04 * np.abs(e)
        name = "fitted_critical_stokes" if model == "threshold" else "k"
        form = bayesian.Form(lambda s, a, q, m=model: restitution_curve(m, s, a, q), name, 1.0)
        p = np.column_stack([
            0.95 + 0.01 * rng.standard_normal(8), truth * (1 + 0.02 * rng.standard_normal(8)),
            0.001 + 0.02 * rng.random(8),
        ])  # fmt: skip
        moments, _ = bayesian.restitution_log_posterior(form, st, e, stated=(r, u_e), moments=True)
        exact = _integral(form, st, e, r, u_e, p)
        gap = moments(p) - exact
        assert np.all(np.isfinite(gap))
        # exponential: 2.5 % of the exact log posterior's spread over these walkers measured
        tolerance = 1e-6 if model == "threshold" else 0.05 * float(np.ptp(exact))
        assert float(np.ptp(gap)) < tolerance, (model, gap, np.ptp(exact))


def test_the_restitution_interval_with_stated_u_is_refused_from_its_size_with_why() -> None:
    """From ``STATED_REFUSED_FROM`` runs with stated u: the least-squares values, no
    interval, the one reason (``stated_refusal``) naming the default method, which gives
    an interval on the same runs; without stated u the posterior is given."""
    n = bayesian.STATED_REFUSED_FROM
    frame = measured(0, n=n)
    [row] = fits.restitution(frame, "exponential", method="bayes")
    [default] = fits.restitution(frame, "exponential")
    assert row["interval_reason"] == bayesian.stated_refusal(n) != ""
    assert "--method bootstrap" in row["interval_reason"]
    assert row["interval_method"] == bayesian.NO_INTERVAL and not row["converged"]
    for key in ("e_dry", "parameter"):
        assert np.isnan(row[f"{key}_low"]) and np.isnan(row[f"{key}_high"])
        assert row[key] == default[key]  # least squares, as the default's value
        assert default[f"{key}_low"] < default[key] < default[f"{key}_high"]
    assert bayesian.stated_refusal(n - 1) == ""


def test_walton_beta_interval_with_stated_u_is_refused_from_its_size_with_why() -> None:
    """From ``WALTON_BETA_REFUSED_FROM`` runs stating their speeds' u: β's posterior
    median, no interval, the one reason naming the default method; μ_f and ē keep theirs."""
    n = bayesian.WALTON_BETA_REFUSED_FROM
    [row] = fits.walton(walton_measured(n, seed=0), method="bayes")
    assert row["model"] == "split" and row["converged"]
    assert (
        bayesian.walton_beta_refusal(n) in row["reason"] and "--method bootstrap" in row["reason"]
    )
    assert np.isfinite(row["rotational_restitution"])
    assert np.isnan(row["rotational_restitution_low"]) and np.isnan(
        row["rotational_restitution_high"]
    )
    assert row["sliding_friction_low"] < row["sliding_friction"] < row["sliding_friction_high"]
    assert row["interval_method"] == bayesian.INTERVAL_METHOD
    assert bayesian.walton_beta_refusal(n - 1) == ""
