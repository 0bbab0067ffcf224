"""The Bayesian option of the Walton and restitution fits: posterior draws by emcee's
affine-invariant ensemble sampler (issue 27; docs/physics.md, "Bayesian fits").

Why this shape. The least-squares fits already decide *which* model the runs follow (the
Walton model by BIC, the restitution form as asked); the Bayesian option keeps that choice
and replaces the bootstrap interval of each parameter by a posterior credible interval, so
the two answers differ only in how the uncertainty is stated and can be compared run for
run. Likelihood: the fit's own model with independent Gaussian scatter, its scale σ fitted
with the parameters (a log-uniform, scale-invariant prior); or, when the runs state their
u, errors in every measured variable (``walton``: effective variance; ``restitution``: the
shared v_N,in integrated out) plus a sampled σ_extra beyond the stated u (half-Cauchy
prior, scale the median stated u). Priors: uniform on each parameter's physical range
(``PRIORS``), stated in every result (docs/intervals.md, "The Bayesian option").
From ``LARGE_N`` runs with stated u the restitution likelihood takes the moments of its
integral over the true speed; from ``STATED_REFUSED_FROM`` runs with stated u the
restitution interval, and from ``WALTON_BETA_REFUSED_FROM`` Walton β's, are refused with
their reason (measured off centre from 400 to 10,000 runs: ``stated_refusal``,
``walton_beta_refusal``).

Walton: the sticking model is Ψ_out = −βΨ_in, the sliding one Ψ_out = Ψ_in − μ_f(1+e)B and
the split one Walton's max(−βΨ_in, Ψ_in − μ_f(1+e)B) (the folded runs of
``granudb.analysis.walton``; the transition follows from β and μ_f, so no split point is
sampled). ē has its own Gaussian scatter (a separate factor of the same posterior).
Restitution: e = e_dry exp(−k/St_n) or e_dry(1 − St_c/St_n)₊, e_dry sampled jointly with the
group's dry runs (``_dry_factor``), never held at their mean.

Sampler: emcee (Foreman-Mackey, Hogg, Lang & Goodman 2013, PASP 125, 306), its ensemble of
walkers moved by differential-evolution proposals (ter Braak 2006, Stat. Comput. 16, 239)
mixed with Goodman & Weare's stretch move (2010, Comm. App. Math. Comp. Sci. 5, 65; see
``MOVES``), walkers started in a small ball around the least-squares fit, every walker
evaluated at once (``vectorize``).
Summaries: the posterior median and the 2.5 and 97.5 percentiles of the draws after burn-in
(an equal-tailed 95 % credible interval). A chain that has not converged gives no number:
the mean acceptance fraction must lie in ``ACCEPTANCE`` and the chain after burn-in must be
at least ``AUTOCORRELATION_MULTIPLE`` integrated autocorrelation times long (the length emcee's
authors advise for a reliable estimate of τ), else every parameter is "not determined:
chain did not converge (…)".
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from granudb.analysis import defaults
from granudb.analysis import walton as core
from granudb.errors import ValidationError
from granudb.lazy import emcee
from granudb.lazy import pandas as pd
from granudb.vocabulary.terms import uncertainty_column

#: The name of the option, as ``--method`` takes it.
METHOD = "bayes"
#: How the Walton and restitution fits state their uncertainty: the bootstrap (the
#: default) or this module's posterior.
METHODS = ("bootstrap", METHOD)


def check_method(method: str) -> None:
    """Refuse a ``method`` that is not one of ``METHODS`` (one line, by name)."""
    if method not in METHODS:
        raise ValidationError(
            "method", str(method), f"must be one of {', '.join(METHODS)}", parameter=True
        )


INTERVAL_METHOD = "posterior median and 95 % equal-tailed credible interval (emcee draws)"
#: A row's ``interval_method`` when its Bayesian interval is refused.
NO_INTERVAL = "no interval given (interval_reason says why)"
LEVEL = defaults.CONFIDENCE_LEVEL
#: Mean acceptance fraction outside this range: the chain did not converge.
ACCEPTANCE = (0.1, 0.9)
#: Draws after burn-in per walker must be at least this many autocorrelation times.
AUTOCORRELATION_MULTIPLE = 50
#: Runs (per-run σ absent) below which no posterior is given: σ and two line parameters.
MIN_RUNS = core.MIN_RUNS_FOR_PARAMETER
#: Shares of the differential-evolution move (ter Braak 2006) and the stretch move
#: (Goodman & Weare 2010): measured on a split Walton set of 60 runs, the mixture's
#: autocorrelation time was 11–13 steps against 30–43 for the stretch move alone, at the
#: same cost per step.
MOVES = (0.8, 0.2)
SAMPLER_NAME = (
    "emcee ensemble sampler: 80 % differential-evolution moves (ter Braak 2006), "
    "20 % affine-invariant stretch moves (Goodman & Weare 2010)"
)
SOURCE = (
    "Foreman-Mackey, Hogg, Lang & Goodman (2013) PASP 125, 306; Goodman & Weare (2010) "
    "Comm. App. Math. Comp. Sci. 5, 65; ter Braak (2006) Stat. Comput. 16, 239"
)
#: Each parameter's prior, as every result states it.
PRIORS = {
    "rotational_restitution": "β uniform on [−1, 1] (Walton's range)",
    "sliding_friction": "μ_f uniform on [0, ∞)",
    "normal_restitution": "ē uniform on (0, 1.05] (the import's limit on measured e), "
    "its scatter σ_e log-uniform",
    "e_dry": "e_dry uniform on (0, 1]",
    "k": "k uniform on [0, 100 max St_n]",
    "fitted_critical_stokes": "St_c uniform on [0, 100 max St_n]",
    "sigma": "σ log-uniform on (0, ∞) (scale-invariant; absent when per-run u is stated)",
    "sigma_extra": "σ_extra (scatter beyond the stated u) half-Cauchy with scale the runs' "
    "median stated u (Gelman 2006)",
    "e_dry_dry_runs": "e_dry uniform on (0, 1], its dry runs' scatter σ_dry log-uniform "
    "(marginalised: the dry runs give e_dry a Student-t factor)",
}
#: Gauss–Hermite nodes over each run's true v_N,in (the restitution fit with stated speeds).
HERMITE_NODES = 12
#: Upper end of the restitution parameter's prior, in multiples of the largest St_n.
PARAMETER_PRIOR_SPAN = 100.0
E_MAX = 1.05
#: From this many immersed runs stating their speeds' u, the restitution likelihood's
#: integral over each run's true v_N,in is replaced by its moments (issue 36,
#: ``_moments_log_posterior``): the quadrature costs 40 ms an evaluation of 16 walkers on
#: 10,000 runs, 5,000 evaluations a chain (about 200 s CPU a posterior), so its coverage
#: there could not be measured over 200 sets; the moments' is (docs/intervals.md).
LARGE_N = 10_000
#: From this many immersed runs stating their speeds' u, the restitution fit's Bayesian
#: interval is refused (``stated_refusal``): its centre lies off the truth by more than its
#: width allows (``benchmarks/fit_coverage.py --behind-refusals``). The likelihood takes
#: each run's stated u as known, though u(v_n,out) follows the measured speeds, and
#: s ~ Normal(1, r) for the true speed's share: terms of order r² (−0.2 to −0.4 % in e_dry,
#: −0.4 to −1.4 % in St_c or k at 4 % speed u) that stay while the width falls as 1/√n.
#: Measured with 4 % speed u (the lowest cell of each size is what the refusal states): at
#: 300 runs St_c with e_dry of 4 dry runs 0.935 (200 sets), the exponential form's e_dry
#: 0.900 and k 0.920 (100 sets); at 400 runs St_c 0.910 (100 sets), e_dry 0.883 and k
#: 0.950 (60 sets); at 500 runs St_c 0.875 (200 sets), e_dry 0.833 and k 0.920 (150
#: sets); at 1,000 runs St_c 0.850 and k 0.867 (60 sets each); at 10,000 runs 0.05–0.15
#: (200 sets a cell). From 1,000 runs until 400 and 500 were measured (27 Nov 2026): the
#: smallest size measured to fail (e_dry at 400, 60 sets; with e_dry falling 0.940, 0.900,
#: 0.883, 0.833 at 100, 300, 400, 500 runs).
STATED_REFUSED_FROM = 400
#: The measured coverage behind the refusal, as the refusal states it.
STATED_REFUSED_COVERAGE = (
    "as few as 0.883 of synthetic sets of 400 runs, 0.833 of 500, 0.850 of 1,000 and 0.05 "
    "of 10,000 (0.900–0.935 at 300)"
)
#: From this many runs stating their speeds' u, Walton β's Bayesian interval is refused
#: (``walton_beta_refusal``): measured at 10,000 runs, 0.875 (200 sets); its offset, about
#: 0.7 posterior sd there, is a third of that at 1,000 runs.
WALTON_BETA_REFUSED_FROM = LARGE_N


#: Walton β's Bayesian interval with the speeds' u stated, measured at 10,000 runs (200
#: sets, 4 mm/s): it held β in this share of them (μ_f's 0.965, ē's as without u).
WALTON_BETA_REFUSED_COVERAGE = 0.875


def walton_beta_refusal(n: int) -> str:
    """Why β of ``n`` Walton runs stating their speeds' u gets no Bayesian interval ('' when
    it gets one): one line, pointing to the default method."""
    return _refused_from(
        n,
        WALTON_BETA_REFUSED_FROM,
        f"interval of β refused from {WALTON_BETA_REFUSED_FROM:,} runs with stated u: its "
        f"Bayesian interval held the truth in {WALTON_BETA_REFUSED_COVERAGE:.3f} of "
        "synthetic sets of 10,000 runs (bound 0.90); the default method (--method "
        "bootstrap: the asymptotic interval, centred for the stated u) covers 0.975 there",
    )


def stated_refusal(n: int) -> str:
    """Why ``n`` immersed runs with stated u get no Bayesian restitution interval ('' when
    they get one): one line, pointing to the default method."""
    return _refused_from(
        n,
        STATED_REFUSED_FROM,
        f"Bayesian interval refused from {STATED_REFUSED_FROM:,} runs with stated u: the "
        "posterior's centre is off by terms of order u² that its width no longer hides "
        f"(its 95 % interval held the truth in {STATED_REFUSED_COVERAGE}); use the default "
        "method (--method bootstrap: its bootstrap-t with the speeds redrawn covers "
        "0.94–1.00 at 300 to 3,000 runs, its asymptotic interval from 10,000 runs, centred "
        "for the stated u, 0.95–0.99); value: least squares",
    )


def _refused_from(n: int, start: int, reason: str) -> str:
    """``reason`` from ``start`` runs on, '' below."""
    return reason if n >= start else ""


@dataclass(frozen=True)
class Settings:
    """The sampler's settings, stated in every result."""

    walkers: int = 32
    steps: int = 1500
    burn_in: int = 500
    seed: int = 0

    def describe(self) -> dict[str, Any]:
        return {
            "sampler": SAMPLER_NAME,
            "sampler_source": SOURCE,
            "sampler_walkers": self.walkers,
            "sampler_steps": self.steps,
            "sampler_burn_in": self.burn_in,
            "sampler_seed": self.seed,
        }


DEFAULT = Settings()
#: The default with stated u: σ_extra (its half-Cauchy prior piles up at 0) mixes slower,
#: its autocorrelation time measured at 17–22 steps on 10 restitution runs (more than
#: 1,000 draws / 50), so the chain is twice as long.
STATED_DEFAULT = Settings(steps=2500)


def effective(settings: Settings, stated: bool) -> Settings:
    """The settings a posterior runs with: ``STATED_DEFAULT`` for the default when the runs
    state their u (σ_extra sampled), else ``settings`` as given."""
    return STATED_DEFAULT if stated and settings == DEFAULT else settings


@dataclass(frozen=True)
class Posterior:
    """Draws after burn-in, shape (walkers, draws, parameters), and the diagnostics."""

    names: tuple[str, ...]
    chain: np.ndarray
    acceptance: float
    autocorrelation: np.ndarray  # τ per parameter, in steps
    reason: str  # "" when the chain converged, else "not determined: ..."

    def summary(self, name: str) -> tuple[float, float, float]:
        """(median, low, high) of ``name``; NaN when the chain did not converge."""
        if self.reason:
            return math.nan, math.nan, math.nan
        values = self.chain[..., self.names.index(name)].ravel()
        tail = 50.0 * (1.0 - LEVEL)
        low, median, high = np.percentile(values, [tail, 50.0, 100.0 - tail])
        return float(median), float(low), float(high)

    def spread(self, name: str) -> float:
        """The posterior standard deviation of ``name`` (NaN when not converged)."""
        if self.reason:
            return math.nan
        return float(np.std(self.chain[..., self.names.index(name)]))

    def diagnostics(self) -> dict[str, Any]:
        tau = self.autocorrelation
        return {
            "acceptance_fraction": self.acceptance,
            "autocorrelation_time": float(np.max(tau)) if tau.size else math.nan,
            "autocorrelation_times": ", ".join(
                f"{n} {t:.3g}" for n, t in zip(self.names, tau, strict=True)
            ),
            "converged": not self.reason,
        }

    def draws(self, key: dict[str, Any]) -> Any:
        """The draws as a long frame: ``key`` columns, chain (walker), draw (step after
        burn-in), one column per parameter."""
        walkers, steps, _ = self.chain.shape
        columns = {
            "chain": np.repeat(np.arange(walkers), steps),
            "draw": np.tile(np.arange(steps), walkers),
        }
        for i, name in enumerate(self.names):
            values = self.chain[..., i].ravel()
            if name == "log_sigma":
                values = np.exp(values)
            columns[RESULT_NAMES.get(name, name)] = values
        frame = pd.DataFrame(columns)
        for position, (name, value) in enumerate(key.items()):
            frame.insert(position, name, value)
        return frame


def sample(log_posterior, start: np.ndarray, spread: np.ndarray, names, settings: Settings):
    """Run the ensemble from a ball of ``spread`` around ``start`` (each walker's start
    drawn until the posterior is finite there) and judge convergence."""
    rng = np.random.default_rng(settings.seed)
    ndim = len(start)
    walkers = max(settings.walkers, 2 * ndim + 2)
    points = np.empty((walkers, ndim))
    for i in range(walkers):
        for _ in range(100):
            trial = start + spread * rng.standard_normal(ndim)
            if np.isfinite(log_posterior(trial[None, :])[0]):
                break
        else:
            trial = start
        points[i] = trial
    moves = [(emcee.moves.DEMove(), MOVES[0]), (emcee.moves.StretchMove(), MOVES[1])]
    sampler = emcee.EnsembleSampler(walkers, ndim, log_posterior, moves=moves, vectorize=True)
    sampler.random_state = np.random.RandomState(settings.seed).get_state()
    sampler.run_mcmc(points, settings.steps, progress=False)
    chain = sampler.get_chain(discard=settings.burn_in).transpose(1, 0, 2)
    acceptance = float(np.mean(sampler.acceptance_fraction))
    tau = np.asarray(sampler.get_autocorr_time(discard=settings.burn_in, tol=0))
    # tol=0: emcee's own length check (which only logs) is replaced by the one below
    length = settings.steps - settings.burn_in
    problems = []
    if not ACCEPTANCE[0] <= acceptance <= ACCEPTANCE[1]:
        problems.append(
            f"acceptance fraction {acceptance:.2f} outside {ACCEPTANCE[0]}–{ACCEPTANCE[1]}"
        )
    if not (np.all(np.isfinite(tau)) and length >= AUTOCORRELATION_MULTIPLE * np.max(tau)):
        problems.append(
            f"{length} draws per walker < {AUTOCORRELATION_MULTIPLE} × autocorrelation time "
            f"{np.max(tau):.3g}"
        )
    reason = f"not determined: chain did not converge ({'; '.join(problems)})" if problems else ""
    return Posterior(tuple(names), chain, acceptance, tau, reason)


def _gaussian(residual: np.ndarray, log_sigma: np.ndarray | None, sigma: np.ndarray | None):
    """Σ log N(residual | 0, σ) over runs (the last axis), up to a constant."""
    if sigma is not None:
        return -0.5 * np.sum((residual / sigma) ** 2, axis=-1)
    assert log_sigma is not None  # σ is either stated (sigma) or a parameter (log_sigma)
    n = residual.shape[-1]
    return -0.5 * np.sum(residual**2, axis=-1) * np.exp(-2 * log_sigma) - n * log_sigma


def _log_scale(residual: np.ndarray, parameters: int) -> float:
    """ln of the least-squares scatter, the walkers' start for ln σ."""
    dof = max(residual.size - parameters, 1)
    return math.log(max(math.sqrt(float(residual @ residual) / dof), 1e-12))


def walton(
    x: np.ndarray,
    y: np.ndarray,
    c: np.ndarray,
    e: np.ndarray,
    model: str,
    start: tuple[float, float],
    *,
    sigma: np.ndarray | None = None,
    stated: np.ndarray | None = None,
    settings: Settings = DEFAULT,
) -> Posterior:
    """The posterior of Walton's model ``model`` ("sticking", "sliding", "split") on folded
    runs (``x`` = Ψ_in, ``y`` = Ψ_out, ``c`` = (1+e)B, ``e``) and of ē; ``start`` = the
    least-squares (β, μ_f) (NaN where the model has no such line).

    ``stated`` (4, n): each run's stated u as ``walton_bootstrap.stated_walton`` gives it
    (r = u(v_N,in)/v_N,in, then the numerator speeds' shares of u(e), u(Ψ_in), u(Ψ_out)).
    Errors in all variables, marginalised with the effective variance of the residual
    (exact to first order: the lines are linear in Ψ_in, Ψ_out and e): on the sliding
    line u(Ψ_out)² + u(Ψ_in)² + (μ_f B)²(u(e)² + r²), the shared v_N,in's factor moving
    Ψ_in, Ψ_out and e together (its share of the residual is μ_f B r); on the sticking
    line u(Ψ_out)² + β²u(Ψ_in)² (the shared factor cancels); each run on the branch the
    model puts it at; plus σ_extra² (scatter beyond the stated u, sampled). ``sigma``: a
    per-run u of Ψ_out alone (no speeds stated), used as the residual's stated u. Neither:
    σ is fitted. ē: ``with_mean``."""
    beta0 = start[0] if math.isfinite(start[0]) else 0.0
    mu0 = start[1] if math.isfinite(start[1]) else 0.0
    if stated is None and sigma is not None:
        zero = np.zeros_like(x)
        stated = np.stack([zero, zero, zero, np.asarray(sigma, dtype=float)])
    log_posterior, names = walton_log_posterior(x, y, c, e, model, stated)
    scale = _median_u(stated[3]) if stated is not None else math.nan
    line = _walton_line(x, c, model)
    fitted = y - line(np.array([beta0]), np.array([mu0]))[0][0]
    first = {
        "beta": beta0,
        "mu_f": mu0,
        "log_sigma": _log_scale(fitted, len(names) - 1),
        "sigma_extra": 0.5 * scale,
    }
    point = np.array([first[n] for n in names])
    spread = np.array(
        [1e-3 if n.startswith("log") else 0.1 * scale if n == "sigma_extra" else 1e-4
         for n in names]
    )  # fmt: skip
    posterior = sample(log_posterior, point, spread, names, settings)
    return with_mean(posterior, e, settings.seed)


class _Buffers:
    """Arrays reused between evaluations of one log posterior, by name and shape."""

    def __init__(self) -> None:
        self._arrays: dict[str, np.ndarray] = {}

    def get(self, name: str, shape: tuple[int, ...], dtype: Any = float) -> np.ndarray:
        found = self._arrays.get(name)
        if found is None or found.shape != shape:
            found = self._arrays[name] = np.empty(shape, dtype=dtype)
        return found


def _walton_line(x: np.ndarray, c: np.ndarray, model: str):
    """(β, μ_f) per walker → (the model's Ψ_out at each run (walkers, n), sticking mask)."""

    def line(beta, mu):
        stick, slide = -beta[:, None] * x, x - mu[:, None] * c
        if model == "sticking":
            return stick, np.ones(stick.shape, dtype=bool)
        if model == "sliding":
            return slide, np.zeros(slide.shape, dtype=bool)
        return np.maximum(stick, slide), stick >= slide

    return line


def walton_log_posterior(
    x: np.ndarray,
    y: np.ndarray,
    c: np.ndarray,
    e: np.ndarray,
    model: str,
    stated: np.ndarray | None = None,
) -> tuple[Any, list[str]]:
    """The log posterior of ``walton`` (up to a constant) over a batch of walkers (rows of
    p: the parameters ``names``), and ``names``. ``stated``: (4, n) as ``walton`` takes it,
    or None (σ fitted).

    Cost (issue 36): with stated u each evaluation works in buffers kept between calls
    (fresh (walkers, n) temporaries cost more in page faults than in arithmetic: 4.7 ms
    against 0.77 ms an evaluation of 16 walkers on 10,000 runs), computes the walker-free
    parts (u(Ψ_out)², u(Ψ_in)², u(e)² + r²) once, and each branch's variance only where
    the model has that branch. The arithmetic is the same, operation for operation, as the
    direct formula: the values are equal to the last bit (tests/analysis/test_bayes_speed.py
    compares them, and the chains of the same seed)."""
    has_beta, has_mu = model != "sliding", model != "sticking"
    b = c / (1.0 + e)
    line = _walton_line(x, c, model)
    names = [n for n, has in (("beta", has_beta), ("mu_f", has_mu)) if has]
    names += ["sigma_extra"] if stated is not None else ["log_sigma"]
    at = {n: i for i, n in enumerate(names)}
    if stated is None:

        def fitted_sigma(p: np.ndarray) -> np.ndarray:
            m = len(p)
            beta = p[:, at["beta"]] if has_beta else np.zeros(m)
            mu = p[:, at["mu_f"]] if has_mu else np.zeros(m)
            inside = (beta >= -1) & (beta <= 1) & (mu >= 0)
            value = _gaussian(y - line(beta, mu)[0], p[:, at["log_sigma"]], None)
            return np.where(inside & np.isfinite(value), value, -np.inf)

        return fitted_sigma, names

    r, u_e, u_in, u_out = stated
    scale = _median_u(u_out)
    out2 = u_out**2
    slide0 = u_out**2 + u_in**2  # the sliding line's variance: slide0 + (μ_f B)² slide1
    slide1 = u_e**2 + r**2
    work = _Buffers()

    def log_posterior(p: np.ndarray) -> np.ndarray:
        m = len(p)
        shape = (m, len(x))
        beta = p[:, at["beta"]] if has_beta else np.zeros(m)
        mu = p[:, at["mu_f"]] if has_mu else np.zeros(m)
        extra = p[:, at["sigma_extra"]]
        inside = (beta >= -1) & (beta <= 1) & (mu >= 0) & (extra >= 0)
        predicted, other, total = work.get("a", shape), work.get("b", shape), work.get("c", shape)
        if has_beta:  # the sticking line −βΨ_in and its variance u(Ψ_out)² + (βu(Ψ_in))²
            np.multiply(-beta[:, None], x, out=predicted)
        if has_mu:  # the sliding line Ψ_in − μ_f(1+e)B
            np.multiply(mu[:, None], c, out=other)
            np.subtract(x, other, out=other if has_beta else predicted)
        if has_beta and has_mu:  # split: the larger line; each run's variance on its branch
            sticking = work.get("mask", shape, bool)
            np.greater_equal(predicted, other, out=sticking)
            np.maximum(predicted, other, out=predicted)
        if has_mu:
            np.multiply(mu[:, None], b, out=total)
            np.square(total, out=total)
            total *= slide1
            np.add(slide0, total, out=total)
        if has_beta:
            stick = other if has_mu else total
            np.multiply(beta[:, None], u_in, out=stick)
            np.square(stick, out=stick)
            np.add(out2, stick, out=stick)
            if has_mu:
                np.copyto(total, stick, where=sticking)
        total += (extra**2)[:, None]
        value = _normal(np.subtract(y, predicted, out=predicted), total)
        value += _half_cauchy(extra, scale)
        return np.where(inside & np.isfinite(value), value, -np.inf)

    return log_posterior, names


def _median_u(u: np.ndarray) -> float:
    """The half-Cauchy prior's scale: the runs' median stated u (positive)."""
    positive = u[u > 0]
    return float(np.median(positive)) if positive.size else 1e-3


def _normal(residual: np.ndarray, variance: np.ndarray) -> np.ndarray:
    """Σ log N(residual | 0, variance) over runs (the last axis), up to a constant.
    Overwrites both arrays (the callers' temporaries: no copy of (walkers, n) arrays)."""
    np.square(residual, out=residual)
    np.divide(residual, variance, out=residual)
    np.log(variance, out=variance)
    residual += variance
    return -0.5 * np.sum(residual, axis=-1)


def _half_cauchy(value: np.ndarray, scale: float) -> np.ndarray:
    """log of the half-Cauchy(0, ``scale``) density, up to a constant."""
    return -np.log1p((value / scale) ** 2)


def stated_usable(stated: np.ndarray | None, row: int) -> np.ndarray | None:
    """``stated`` when every run states a positive u in ``row`` (the residual's own
    variable: Ψ_out for Walton, e for restitution), else None (σ is fitted)."""
    if stated is None:
        return None
    u = stated[row]
    return stated if u.size and bool(np.all(np.isfinite(u) & (u > 0))) else None


def with_mean(posterior: Posterior, e: np.ndarray, seed: int) -> Posterior:
    """``posterior`` with ē's draws appended: its exact marginal posterior under a flat
    prior on ē and a log-uniform one on its scatter (Student t with n − 1 degrees of
    freedom about the mean e, scale s/√n), truncated to (0, E_MAX], drawn independently
    (τ = 1) in the chain's shape."""
    walkers, steps, _ = posterior.chain.shape
    n = len(e)
    rng = np.random.default_rng(seed)
    scale = float(np.std(e, ddof=1)) / math.sqrt(n) if n > 1 else math.nan
    draws = np.full(walkers * steps, math.nan)
    missing = np.arange(draws.size)
    for _ in range(100):  # truncation by rejection (rarely needed: ē is far inside)
        trial = float(np.mean(e)) + scale * rng.standard_t(max(n - 1, 1), missing.size)
        keep = (trial > 0) & (trial <= E_MAX)
        draws[missing[keep]] = trial[keep]
        missing = missing[~keep]
        if not missing.size:
            break
    chain = np.concatenate([posterior.chain, draws.reshape(walkers, steps, 1)], axis=2)
    return Posterior(
        (*posterior.names, "e_mean"),
        chain,
        posterior.acceptance,
        np.append(posterior.autocorrelation, 1.0),
        posterior.reason,
    )


@dataclass(frozen=True)
class Form:
    """A restitution form: ``curve(st, e_dry, parameter)`` (broadcasting), the parameter's
    name, and the upper end of e_dry's prior."""

    curve: Any
    parameter: str
    e_dry_max: float


def restitution(
    form: Form,
    st: np.ndarray,
    e: np.ndarray,
    start: tuple[float, float],
    dry: np.ndarray | None = None,
    *,
    stated: tuple[np.ndarray, np.ndarray] | None = None,
    settings: Settings = DEFAULT,
) -> Posterior:
    """The posterior of the restitution ``form`` over immersed runs (St_n, e); ``start`` =
    the least-squares (e_dry, parameter). ``dry``: the group's dry runs' e, whose own
    likelihood enters the posterior jointly (their scatter σ_dry marginalised under a
    log-uniform prior: a Student-t factor in e_dry, ``_dry_factor``); none: e_dry only from
    the immersed runs.

    ``stated`` (r, u_e): each run's relative u of v_N,in and the u of e that v_n,out gives
    it (u(v_n,out)/v_N,in). St_n and e share the measured v_N,in: with s = v_N,in(true) /
    v_N,in(measured) the true St_n is s St_n and the measured e is e(s St_n) s + noise of
    u_e; the likelihood of each run integrates over s ~ N(1, r) by Gauss–Hermite
    quadrature (``HERMITE_NODES``, flat prior on the true speed), the noise variance
    u_e² + σ_extra² with σ_extra sampled. None: σ is fitted."""
    parameter = form.parameter
    log_posterior, names = restitution_log_posterior(form, st, e, dry, stated=stated)
    scale = _median_u(stated[1]) if stated is not None else math.nan
    fitted = e - form.curve(st, start[0], start[1])
    first = {
        "e_dry": start[0],
        parameter: start[1],
        "log_sigma": _log_scale(fitted, 2),
        "sigma_extra": 0.5 * scale if stated is not None else math.nan,
    }
    point = np.array([first[n] for n in names])
    spreads = {"e_dry": 1e-4, parameter: 1e-3 * max(start[1], float(np.min(st)) * 1e-2)}
    if stated is not None:
        spreads["sigma_extra"] = 0.1 * scale
    spread = np.array([spreads.get(n, 1e-3) for n in names])
    return sample(log_posterior, point, spread, names, settings)


def restitution_log_posterior(
    form: Form,
    st: np.ndarray,
    e: np.ndarray,
    dry: np.ndarray | None = None,
    *,
    stated: tuple[np.ndarray, np.ndarray] | None = None,
    moments: bool | None = None,
) -> tuple[Any, list[str]]:
    """``restitution``'s log posterior over a batch of walkers, and its parameters' names.
    With ``stated``: the quadrature over each run's true v_N,in, or from ``LARGE_N`` runs
    (``moments`` None) or when ``moments`` is True, its moments (``_moments_log_posterior``)."""
    parameter = form.parameter
    names = ["e_dry", parameter] + (["sigma_extra"] if stated is not None else ["log_sigma"])
    at = {n: i for i, n in enumerate(names)}
    top = PARAMETER_PRIOR_SPAN * float(np.max(st))
    dry_term = _dry_factor(dry)
    if moments is None:
        moments = stated is not None and large_n(len(st))
    if stated is not None and moments:
        return _moments_log_posterior(form, st, e, stated, top, dry_term), names
    if stated is not None:
        r, u_e = stated
        nodes, weights = np.polynomial.hermite.hermgauss(HERMITE_NODES)
        factor = 1.0 + math.sqrt(2.0) * r[:, None] * nodes[None, :]  # (n, K): s per node
        log_w = np.log(weights / math.sqrt(math.pi))
        scale = _median_u(u_e)

    def quadrature(p: np.ndarray) -> np.ndarray:
        a, q = p[:, at["e_dry"]], p[:, at[parameter]]
        inside = (a > 0) & (a <= form.e_dry_max) & (q >= 0) & (q <= top)
        if stated is None:  # walkers outside the prior (q < 0) may overflow: discarded below
            with np.errstate(over="ignore", invalid="ignore"):
                curve = form.curve(st[None, :], a[:, None], q[:, None])
                value = _gaussian(e - curve, p[:, at["log_sigma"]], None)
        else:
            extra = p[:, at["sigma_extra"]]
            inside &= extra >= 0
            with np.errstate(divide="ignore", invalid="ignore"):
                curve = (
                    form.curve(st[None, :, None] * factor[None], a[:, None, None], q[:, None, None])
                    * factor[None]
                )
            total = (u_e**2)[None, :] + extra[:, None] ** 2  # (walkers, n)
            z2 = (e[None, :, None] - curve) ** 2 / total[..., None]
            per_run = _logsumexp(log_w[None, None, :] - 0.5 * z2, axis=-1)
            value = np.sum(per_run - 0.5 * np.log(total), axis=-1) + _half_cauchy(extra, scale)
        value = value + dry_term(a)
        return np.where(inside & np.isfinite(value), value, -np.inf)

    return quadrature, names


def large_n(n: int) -> bool:
    """Whether ``n`` immersed runs with stated u get the moments' likelihood (``LARGE_N``)."""
    return n >= LARGE_N


def _moments_log_posterior(form: Form, st, e, stated, top: float, dry_term):
    """The restitution log posterior with stated u from ``LARGE_N`` runs: each run's
    e ~ Normal(h(1) + ½r²h''(1), √(u_e² + σ_extra² + r²h'(1)²)) with h(s) = s e(s St_n) the
    measured e at a true speed s times the measured one: the mean to second order in r,
    the variance to first (the effective variance, as the Walton option's), in place of
    the quadrature over s. Threshold form above St_c: h(s) = e_dry(s − St_c/St_n) is
    linear in s, so these moments are the quadrature's integral exactly (to its own
    12-node accuracy); exponential: h' = e(1 + k/St_n), h'' = e (k/St_n)². Parameters
    (e_dry, parameter, σ_extra), as ``restitution``'s."""
    r, u_e = stated
    inverse = 1.0 / st
    r2, half_r2, ue2 = r**2, 0.5 * r**2, u_e**2
    scale = _median_u(u_e)
    threshold = form.parameter == "fitted_critical_stokes"
    work = _Buffers()

    def log_posterior(p: np.ndarray) -> np.ndarray:
        a, q, extra = p[:, 0], p[:, 1], p[:, 2]
        inside = (a > 0) & (a <= form.e_dry_max) & (q >= 0) & (q <= top) & (extra >= 0)
        shape = (len(p), len(st))
        kappa, curve, other = work.get("k", shape), work.get("c", shape), work.get("o", shape)
        np.multiply(q[:, None], inverse, out=kappa)  # St_c/St_n or k/St_n
        if threshold:  # e_dry(1 − κ)₊, slope e_dry above St_c, 0 below
            above = work.get("above", shape, bool)
            np.less(kappa, 1.0, out=above)
            np.subtract(1.0, kappa, out=curve)
            curve *= a[:, None]
            curve *= above
            np.multiply(above, (a**2)[:, None], out=other)  # h'(1)²
            other *= r2
        else:  # e_dry exp(−κ); h' = e(1 + κ), h'' = e κ²
            np.negative(kappa, out=curve)
            np.exp(curve, out=curve)
            curve *= a[:, None]
            np.add(kappa, 1.0, out=other)
            other *= curve
            np.square(other, out=other)
            other *= r2  # r²h'(1)²
            np.square(kappa, out=kappa)
            kappa *= curve
            kappa *= half_r2
            curve += kappa  # the mean, h(1) + ½r²h''(1)
        other += ue2
        other += (extra**2)[:, None]
        np.subtract(e, curve, out=curve)
        value = _normal(curve, other) + _half_cauchy(extra, scale) + dry_term(a)
        return np.where(inside & np.isfinite(value), value, -np.inf)

    return log_posterior


def _logsumexp(a: np.ndarray, axis: int) -> np.ndarray:
    top = np.max(a, axis=axis, keepdims=True)
    top = np.where(np.isfinite(top), top, 0.0)
    with np.errstate(divide="ignore"):
        return np.log(np.sum(np.exp(a - top), axis=axis)) + np.squeeze(top, axis=axis)


def _dry_factor(dry: np.ndarray | None):
    """The dry runs' factor of e_dry's posterior: with e_j ~ N(e_dry, σ_dry) and
    p(σ_dry) ∝ 1/σ_dry, σ_dry integrated out leaves (S + m(e_dry − ē)²)^(−m/2) (S the
    dry runs' sum of squares about their mean ē, m ≥ 2 runs; a Student t with m − 1
    degrees of freedom). Fewer than 2 dry runs: no factor (one run cannot state its own
    scatter)."""
    if dry is None or len(dry) < 2:
        return lambda a: np.zeros_like(a)
    m, mean = len(dry), float(np.mean(dry))
    ss = float(np.sum((dry - mean) ** 2))
    ss = max(ss, 1e-12 * max(mean**2, 1.0))
    return lambda a: -0.5 * m * np.log(ss + m * (a - mean) ** 2)


#: The column of the runs' stated u of Ψ_out that the Walton option reads when present.
STATED_U_WALTON = uncertainty_column("effective_rebound")
#: The result key of each sampled parameter (σ is reported as σ, sampled as ln σ).
RESULT_NAMES = {
    "beta": "rotational_restitution",
    "mu_f": "sliding_friction",
    "e_mean": "normal_restitution_mean",
    "log_sigma": "sigma",
    "sigma_extra": "sigma_extra",
}
#: The Walton row's keys of each parameter's median, interval and spread.
_WALTON_KEYS = {
    "beta": ("rotational_restitution", "rotational_restitution"),
    "mu_f": ("sliding_friction", "sliding_friction"),
    "e_mean": ("normal_restitution_mean", "normal_restitution"),
}
LIKELIHOOD = {
    "walton": "Ψ_out ~ Normal(the chosen model's line at Ψ_in, σ) per run, independent; "
    "e ~ Normal(ē, σ_e)",
    "walton stated": "errors in Ψ_in, Ψ_out and e from each run's stated u, marginalised "
    "by the residual's effective variance (first order; the shared v_N,in's factor moves "
    "all three together): Ψ_out − line(Ψ_in, e) ~ Normal(0, √(v_run + σ_extra²)), "
    "v_run = u(Ψ_out)² + u(Ψ_in)² + (μ_f B)²(u(e)² + r²) on the sliding line, "
    "u(Ψ_out)² + β²u(Ψ_in)² on the sticking line (r = u(v_N,in)/v_N,in); "
    "e ~ Normal(ē, σ_e)",
    "restitution": "e ~ Normal(e(St_n) of the chosen form, σ) per run, independent",
    "restitution stated": "St_n and e share the measured v_N,in: each run's true speed "
    "v_N,in s, s ~ Normal(1, r), integrated out (Gauss–Hermite, 12 nodes); "
    "e ~ Normal(s e(s St_n), √(u_e² + σ_extra²)), u_e = u(v_n,out)/v_N,in",
    "restitution stated large": f"from {LARGE_N:,} runs (the large-n approximation): St_n "
    "and e share the measured v_N,in, each run's true speed v_N,in s, s ~ Normal(1, r), "
    "entering by its moments, not integrated: e ~ Normal(h(1) + ½r²h''(1), "
    "√(u_e² + σ_extra² + r²h'(1)²)), h(s) = s e(s St_n) (mean to second order in r, "
    "variance to first; exact for the threshold form above St_c), u_e = u(v_n,out)/v_N,in",
    "dry": "; dry runs e ~ Normal(e_dry, σ_dry), jointly (σ_dry integrated out)",
}


def stated_u(frame: Any, column: str, rows: np.ndarray) -> np.ndarray | None:
    """The runs' stated standard uncertainty of ``column`` (its ``u_`` column, the
    vocabulary's naming) at positions ``rows``, when every one of them states one (> 0);
    else None, and σ is fitted."""
    name = uncertainty_column(column)
    if name not in frame:
        return None
    u = frame[name].to_numpy(dtype=float)[rows]
    return u if u.size and bool(np.all(np.isfinite(u) & (u > 0))) else None


def _stated(row: dict, kind: str, names: tuple, per_run: bool, settings: Settings,
            dry: bool = False, large: bool = False) -> None:  # fmt: skip
    said = []
    for n in names:
        if n == "log_sigma":
            continue
        if n == "e_mean":
            said.append(PRIORS["normal_restitution"])
        elif n == "e_dry" and dry:
            said.append(PRIORS["e_dry_dry_runs"])
        else:
            said.append(PRIORS[RESULT_NAMES.get(n, n)])
    if not per_run:
        said.append(PRIORS["sigma"])
    likelihood = LIKELIHOOD[f"{kind} stated" + (" large" if large else "") if per_run else kind]
    likelihood += LIKELIHOOD["dry"] if dry else ""
    row.update(fit_method=METHOD, interval_method=INTERVAL_METHOD, prior="; ".join(said))
    row.update(likelihood=likelihood, **settings.describe())


def _no_chain(row: dict) -> None:
    row.update(acceptance_fraction=math.nan, autocorrelation_time=math.nan)
    row.update(autocorrelation_times="", converged=False)


def _extra(row: dict, posterior: Posterior) -> None:
    """σ (fitted) or σ_extra (beyond the stated u): the posterior median; the other NaN."""
    log_sigma = posterior.summary("log_sigma")[0] if "log_sigma" in posterior.names else math.nan
    row["sigma"] = math.exp(log_sigma) if math.isfinite(log_sigma) else math.nan
    extra = posterior.summary("sigma_extra") if "sigma_extra" in posterior.names else None
    row["sigma_extra"] = extra[0] if extra else math.nan


def walton_row(
    row: dict,
    arrays: tuple,
    settings: Settings = DEFAULT,
    sigma: np.ndarray | None = None,
    stated: np.ndarray | None = None,
) -> tuple[Any, str]:
    """Replace a Walton row's values and intervals by the posterior's (median, 95 %
    credible interval, posterior standard deviation as ``_stderr``) for the model the row
    chose; parameters the least-squares fit did not determine stay NaN. ``arrays``: the
    group's ``walton_arrays``; ``stated``: the runs' stated u (``walton``), else ``sigma``:
    per-run u of Ψ_out, in the same (sorted) order.
    Returns (draws frame or None, reason: '' or why there is no posterior)."""
    x, y, c, e = arrays[:4]
    model = row.get("model")
    per_run = stated is not None or sigma is not None
    settings = effective(settings, per_run)
    if model is None:
        _stated(row, "walton", (), per_run, settings)
        _no_chain(row)
        return None, ""
    start = (row["rotational_restitution"], row["sliding_friction"])
    posterior = walton(x, y, c, e, model, start, sigma=sigma, stated=stated, settings=settings)
    refused = walton_beta_refusal(len(x)) if stated is not None and not posterior.reason else ""
    _stated(row, "walton", posterior.names, per_run, settings)
    row.update(posterior.diagnostics())
    for name, (value_key, prefix) in _WALTON_KEYS.items():
        if name not in posterior.names or not math.isfinite(row[value_key]):
            continue  # a line of < 3 runs: no value whatever the method
        median, low, high = posterior.summary(name)
        if name == "beta" and len(x) < 2 * core.MIN_RUNS_PER_LINE:
            # too few runs to test a split: the median, no interval (issue 36: on split
            # data the all-sticking posterior at 3 runs covered 0.44)
            row[value_key] = median
            continue
        if name == "beta" and refused:  # the median; no interval, and why
            row.update({value_key: median, f"{prefix}_low": math.nan, f"{prefix}_high": math.nan})
            row[f"{prefix}_interval_method"] = ""
            row[f"{prefix}_stderr"] = math.nan
            continue
        row.update({value_key: median, f"{prefix}_low": low, f"{prefix}_high": high})
        row[f"{prefix}_interval_method"] = INTERVAL_METHOD
        if f"{prefix}_stderr" in row:
            row[f"{prefix}_stderr"] = posterior.spread(name)
    _extra(row, posterior)
    key = {k: row[k] for k in ("dataset", "particle", "wall", "fluid")}
    if refused and "beta" in posterior.names and math.isfinite(row["rotational_restitution"]):
        return posterior.draws(key), refused
    return posterior.draws(key), posterior.reason


def restitution_row(
    row: dict,
    form: Form,
    st: np.ndarray,
    e: np.ndarray,
    settings: Settings = DEFAULT,
    stated: tuple[np.ndarray, np.ndarray] | None = None,
    dry: np.ndarray | None = None,
) -> Any:
    """Replace a restitution row's e_dry and parameter (and intervals, standard errors) by
    the posterior's; ``stated``: per-run (r, u_e) (``restitution``); ``dry``: the dry runs'
    e, fitted jointly. Returns the draws frame (None when the least-squares fit gave
    nothing to start from); a chain that did not converge leaves NaN and says why in
    ``interval_reason``."""
    parameter = form.parameter
    joint = dry is not None and len(dry) >= 2
    names = ("e_dry", parameter, "sigma_extra" if stated is not None else "log_sigma")
    settings = effective(settings, stated is not None)
    large = stated is not None and large_n(len(st))
    _stated(row, "restitution", names, stated is not None, settings, dry=joint, large=large)
    if row["reason"]:
        _no_chain(row)
        return None
    refused = stated_refusal(len(st)) if stated is not None else ""
    if refused:  # the least-squares values stay; no interval, and why
        _no_chain(row)
        for key in ("e_dry", "parameter"):
            row.update({f"{key}_low": math.nan, f"{key}_high": math.nan})
            row[f"{key}_stderr"] = math.nan
        row.update(interval_method=NO_INTERVAL, interval_reason=refused)
        return None
    posterior = restitution(
        form, st, e, (row["e_dry"], row["parameter"]), dry if joint else None,
        stated=stated, settings=settings,
    )  # fmt: skip
    row.update(posterior.diagnostics())
    for name, key in (("e_dry", "e_dry"), (parameter, "parameter")):
        median, low, high = posterior.summary(name)
        row.update({key: median, f"{key}_low": low, f"{key}_high": high})
        row[f"{key}_stderr"] = posterior.spread(name)
    if joint and dry is not None:
        row["e_dry_source"] = (
            f"posterior jointly with the immersed runs and the group's {len(dry)} dry runs"
        )
    if "fitted_critical_stokes" in row:
        row["fitted_critical_stokes"] = row["parameter"]
    _extra(row, posterior)
    row["interval_reason"] = posterior.reason
    group = {k: row[k] for k in ("dataset", "particle", "wall", "model")}
    return posterior.draws(group)
