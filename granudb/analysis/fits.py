"""Fits of measured collisions: Walton's β and μ_f, restitution against Stokes number, and
the gap viscosity of smooth sliding collisions (Joseph & Hunt §3–§5; docs/physics.md §14).

All fits take the DataFrame of ``granudb.analysis.query.select_collisions`` (or any frame
with the columns they read) and work per group (dataset × particle × wall × fluid). The
fitting cores live in ``walton``, ``gap_viscosity_fit`` and ``restitution_fit``; this module
groups the runs and names the results.

Walton fit: runs folded by the sign of v_T,in, three models (all sticking, all sliding,
split) chosen by BIC (see ``granudb.analysis.walton``), β only from a sticking line and μ_f
only from a sliding line of at least three runs, and bootstrap percentile intervals over
runs (model and split re-decided in every resample) made studentized
(``granudb.analysis.intervals``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from granudb.analysis import asymptotic, bayesian, defaults, intervals
from granudb.analysis import walton as core
from granudb.analysis import walton_bootstrap as resampling
from granudb.analysis.gap_viscosity_fit import gap_viscosity
from granudb.analysis.groups import GROUP, WALTON_INPUTS, group_frames, walton_arrays
from granudb.analysis.restitution_fit import (
    RESTITUTION_MODELS,
    restitution,
    restitution_curve,
)
from granudb.lazy import pandas as pd
from granudb.scenario.row_groups import group_rows

__all__ = [
    "FIT_METHODS",
    "GROUP",
    "RESTITUTION_MODELS",
    "WALTON_COLUMNS",
    "WALTON_KEYS",
    "gap_viscosity",
    "restitution",
    "restitution_curve",
    "walton",
    "walton_arrays",
]

#: How a fit states its uncertainty: the bootstrap (the default) or the posterior of the
#: Bayesian option (``granudb.analysis.bayesian``).
FIT_METHODS = bayesian.METHODS
DEFAULT_METHOD = "bootstrap"
DEFAULT_RESAMPLES = resampling.DEFAULT_RESAMPLES
DEFAULT_SEED = 0
CONFIDENCE_LEVEL = defaults.CONFIDENCE_LEVEL

#: Every key of a ``walton`` result and what it means.
WALTON_KEYS = {
    "dataset, particle, wall, fluid": "the group ('dry' when no fluid)",
    "n_runs": "runs with finite Ψ_in, Ψ_out and e",
    "n_folded": "runs with v_T,in < 0, whose Ψ_in and Ψ_out were negated before fitting",
    "model": "'sticking', 'sliding' or 'split' (smallest BIC; a split where runs counted as "
    "sliding stick by their own kinematics: walton.kinematic_sticking), or None (not "
    "determined) with fewer than 3 runs or too few runs on a line to choose",
    "model_reason": "the BIC values behind the choice, or why none was chosen, in words",
    "bic_sticking, bic_sliding, bic_split": "BIC = n ln(S/n) + p ln n, p = 2, 2, 4",
    "model_support_sticking, _sliding, _split": "share of bootstrap resamples choosing it "
    "(NaN with the asymptotic interval: no resamples)",
    "n_sticking, n_sliding": "runs on each line of the chosen model",
    "split_effective_incidence": "folded Ψ_in of the first sliding run of a split, else NaN",
    "rotational_restitution": "β from the sticking line (NaN unless it has ≥ 3 runs)",
    "rotational_restitution_low, _high": "95 % interval of β: studentized bootstrap from "
    "MIN_RUNS_FOR_INTERVAL runs on the line, the t-interval below (NaN, with the reason, where "
    "neither is measured to hold: fits._beta_refusal, or a degenerate bootstrap)",
    "rotational_restitution_interval_method, sliding_friction_interval_method, "
    "normal_restitution_interval_method": "how that parameter's interval was made ('' when "
    "none): the bootstrap's method, SMALL_N_METHOD or MEAN_METHOD",
    "rotational_restitution_stderr": "least-squares standard error of β on its line",
    "rotational_restitution_determined": "share of resamples in which β was determined",
    "sliding_friction": "μ_f from the sliding line (NaN unless it has ≥ 3 runs)",
    "sliding_friction_low, _high, _stderr, _determined": "as for β",
    "sliding_friction_lower_bound": "all sticking: μ_f ≥ (1+β)Ψ_in/((1+e)B) at the largest "
    "Ψ_in (2.10): a bound, not a value",
    "normal_restitution_mean": "ē over all runs of the group",
    "normal_restitution_low, _high, _stderr, _determined": "interval of ē (bootstrap-t from "
    "MIN_RUNS_FOR_INTERVAL runs, the t-interval of the mean from 2), s/√n, share determined",
    "normal_restitution_std": "standard deviation of e over the runs",
    "walton_factor": "mean B used (7/2 unless the frame has walton_factor)",
    "confidence_level, bootstrap_resamples, bootstrap_seed": "how the intervals were made "
    "(bootstrap_resamples 0: the asymptotic interval, from asymptotic_from runs in the group)",
    "bootstrap_rule": "how the resample count was chosen (resampling.RESAMPLE_RULE, or "
    "'as asked' when the caller gave one)",
    "reason": "why β or μ_f is absent ('' when both are given)",
    "fit_method": "'bootstrap' or 'bayes' (FIT_METHODS)",
    "interval_method": "how the intervals were made: the one method of every given interval, "
    "else each parameter's ('β: …; μ_f: …; ē: …'); the bootstrap's says whether the runs' "
    "stated speed uncertainties were used (resampling.STATED_WALTON_METHOD)",
    "bayes only: prior, likelihood, sigma": "how the posterior was made "
    "(values are posterior medians, _low/_high its 95 % equal-tailed credible interval, "
    "_stderr its standard deviation; sigma the scatter of Ψ_out)",
    "bayes only: sampler, sampler_source, sampler_walkers, _steps, _burn_in, _seed": "the "
    "sampler's settings",
    "bayes only: acceptance_fraction, autocorrelation_time(s), converged": "the chain's "
    "diagnostics (no value unless it converged: bayesian.ACCEPTANCE, "
    "bayesian.AUTOCORRELATION_MULTIPLE)",
}

WALTON_COLUMNS = [
    "dataset",
    "particle",
    "wall",
    "fluid",
    "model",
    "rotational_restitution",
    "rotational_restitution_low",
    "rotational_restitution_high",
    "sliding_friction",
    "sliding_friction_low",
    "sliding_friction_high",
    "sliding_friction_lower_bound",
    "normal_restitution_mean",
    "normal_restitution_low",
    "normal_restitution_high",
    "n_sticking",
    "n_sliding",
    "reason",
]
# (the CLI prints these; JSON consumers of ``walton`` get every key of WALTON_KEYS)


_NUMBERS = [
    f"{name}{suffix}"
    for name in ("rotational_restitution", "sliding_friction")
    for suffix in ("", "_low", "_high", "_stderr", "_determined")
] + [
    "bic_sticking",
    "bic_sliding",
    "bic_split",
    "model_support_sticking",
    "model_support_sliding",
    "model_support_split",
    "split_effective_incidence",
    "sliding_friction_lower_bound",
    "normal_restitution_mean",
    "normal_restitution_low",
    "normal_restitution_high",
    "normal_restitution_std",
]


def _groups(frame: Any) -> Any:
    runs = [name for name in WALTON_INPUTS if name not in GROUP]  # the key says the group
    runs.append(bayesian.STATED_U_WALTON)  # when the runs state it (the Bayesian option)
    runs += [name for name in resampling.STATED_COLUMNS if name not in runs]  # the bootstrap's
    return group_frames(frame, GROUP, runs, fill={"fluid": "dry"})


#: Physical range of each Walton parameter (the interval is clipped to it).
BOUNDS = {
    "rotational_restitution": core.BETA_BOUNDS,
    "sliding_friction": (0.0, math.inf),
    "normal_restitution": (0.0, math.inf),
}
#: Runs on a line (β, μ_f) or in the group (ē) below which no interval is given: with a
#: few runs the line's standard error has few degrees of freedom and the bootstrap-t pivot
#: is erratic (measured in benchmarks/fit_coverage.py over 100 sets: β on 4 to 9 sticking
#: runs was behind every miss at n = 30, coverage 0.875; all-sticking β covered 0.85 at
#: n = 5 and 0.88 at n = 10).
MIN_RUNS_FOR_INTERVAL = 10


#: What each parameter's ``_interval_method`` says when the small-n interval gave it.
SMALL_N_METHOD = (
    f"{intervals.T_METHOD}, on the least-squares line through the origin of the runs on "
    f"the line (fewer than {MIN_RUNS_FOR_INTERVAL} runs, or runs moved by their kinematics)"
)
MEAN_METHOD = (
    f"{intervals.T_METHOD}: the mean of the runs' e (fewer than {MIN_RUNS_FOR_INTERVAL} runs)"
)


#: What the small-n interval's method adds when the runs state a u: it is not redrawn.
STATED_SMALL_N = "; the runs' stated u is not redrawn: it is in the per-run values' scatter"


def _interval(
    row: dict, name: str, values: tuple, point: tuple[float, float], runs: int, how=None
) -> str:
    """Put the interval of ``name`` into ``row``, its method under ``name + '_interval_method'``;
    the reason when there is none. ``how``: {"boot": the bootstrap's method, "small": the
    small-n interval at any n, "refuse": why the small-n interval is refused, "stated": the
    runs state a u, "asymptotic": the large-n interval's method words}. With "asymptotic",
    θ̂ ± z se (``asymptotic.interval``; ``point`` its centre and se); else below
    MIN_RUNS_FOR_INTERVAL runs the t-interval of the per-run values
    (``intervals.t_interval``), else the bootstrap-t."""
    how = how or {}
    small = how.get("small", False) or runs < MIN_RUNS_FOR_INTERVAL
    if small and how.get("refuse"):
        found, method = intervals.Interval(math.nan, math.nan, 0.0, how["refuse"]), ""
    elif how.get("asymptotic"):
        found = asymptotic.interval(*point, bounds=BOUNDS[name], level=CONFIDENCE_LEVEL)
        method = how["asymptotic"]
    elif small:
        found = intervals.t_interval(*point, runs, bounds=BOUNDS[name], level=CONFIDENCE_LEVEL)
        method = MEAN_METHOD if name == "normal_restitution" else SMALL_N_METHOD
        method += STATED_SMALL_N if how.get("stated") else ""
    else:
        found = intervals.studentized(*point, *values, bounds=BOUNDS[name], level=CONFIDENCE_LEVEL)
        method = how.get("boot", intervals.METHOD)
    reason = found.reason
    row[f"{name}_low"] = math.nan if reason else found.low
    row[f"{name}_high"] = math.nan if reason else found.high
    row[f"{name}_stderr"] = point[1] if math.isfinite(point[0]) else math.nan
    row[f"{name}_determined"] = found.determined
    row[f"{name}_interval_method"] = "" if reason else method
    return reason if math.isfinite(point[0]) else ""


def _reason(model: str, n_stick: int, n_slide: int) -> str:
    parts = []
    if model == "sliding":
        parts.append("all runs slide: β is not determined by sliding runs")
    elif n_stick < core.MIN_RUNS_FOR_PARAMETER:
        parts.append(f"{n_stick} sticking runs (< {core.MIN_RUNS_FOR_PARAMETER}): no β")
    if model == "sticking":
        parts.append(
            "all runs stick: μ_f is not determined (sliding_friction_lower_bound is a bound)"
        )
    elif n_slide < core.MIN_RUNS_FOR_PARAMETER:
        parts.append(f"{n_slide} sliding runs (< {core.MIN_RUNS_FOR_PARAMETER}): no μ_f")
    return "; ".join(parts)


def bootstrap_plan(n: int, resamples: int | None) -> tuple[int, str]:
    """(resamples, rule): ``resamples`` as asked, else the count of the documented rule."""
    if resamples is not None:
        return resamples, "as asked"
    return resampling.resample_count(n), resampling.RESAMPLE_RULE


def _beta_refusal(model: str, n: int) -> str:
    """Why β gets no small-n interval ('' where its t-interval is measured to hold): on the
    sticking line of a split (a sliding run near the crossing taken as sticking biases β:
    the t-interval covered 0.81 to 0.94 at n = 5 to 9, 0.83 with stated u), or all
    sticking with fewer runs than a split needs to be tested (n = 3: 0.18 on split data)."""
    if model == "split":
        return (
            f"interval not determined: fewer than {MIN_RUNS_FOR_INTERVAL} runs on the sticking "
            "line of a split (no interval measured here holds its coverage there: the "
            "t-interval covered 0.81–0.94 at 5–9 runs)"
        )
    if n < 2 * core.MIN_RUNS_PER_LINE:
        return (
            f"interval not determined: {n} runs cannot test a split (it needs "
            f"{2 * core.MIN_RUNS_PER_LINE}); on split data β's t-interval covered 0.18 there"
        )
    return ""


def _bayes_beta_refusal(row: dict) -> str:
    """The Bayesian option's refusal of β's interval ('' where given): as the
    least-squares fit's, with too few runs to test a split (``bayesian.walton_row``)."""
    n = int(row["n_runs"])
    if n >= 2 * core.MIN_RUNS_PER_LINE or not math.isfinite(row["rotational_restitution"]):
        return ""
    return "interval of β " + _beta_refusal("sticking", n).removeprefix("interval ")


#: The row's ``interval_method`` when none of its parameters has an interval.
NO_INTERVAL = "no interval given (reason says why)"


def _joined_method(row: dict) -> str:
    """The row's ``interval_method``: the one method every given interval used, or each
    parameter's ("β: …; μ_f: …; ē: …") when they differ."""
    found = {
        symbol: row.get(f"{name}_interval_method", "")
        for symbol, name in (
            ("β", "rotational_restitution"),
            ("μ_f", "sliding_friction"),
            ("ē", "normal_restitution"),
        )
    }
    given = {symbol: method for symbol, method in found.items() if method}
    if not given:
        return NO_INTERVAL
    if len(set(given.values())) == 1:
        return next(iter(given.values()))
    return "; ".join(f"{symbol}: {method}" for symbol, method in given.items())


def _walton_group(
    key: tuple,
    group: Any,
    asked: int | None,
    seed: int,
    sets: dict | None = None,
    switch: int = asymptotic.ASYMPTOTIC_FROM,
) -> dict[str, Any]:
    arrays = walton_arrays(group)
    x, y, c, e, folded, _, factor = arrays
    n = len(x)
    stated = resampling.stated_inputs(group, arrays)
    resamples, rule = bootstrap_plan(n, asked)
    row: dict[str, Any] = {**dict(zip(GROUP, key, strict=True)), "n_runs": n, "n_folded": folded}
    row.update(confidence_level=CONFIDENCE_LEVEL, bootstrap_resamples=resamples)
    row["bootstrap_rule"] = rule
    boot_method = intervals.METHOD + (resampling.STATED_WALTON_METHOD if stated is not None else "")
    row["interval_method"] = boot_method
    row.update(bootstrap_seed=seed, walton_factor=float(np.mean(factor)) if n else math.nan)
    row.update(dict.fromkeys(_NUMBERS, math.nan), model=None, model_reason="")
    row.update(n_sticking=0, n_sliding=0)
    row.update({f"{name}_interval_method": "" for name in BOUNDS})
    if n < core.MIN_RUNS_FOR_PARAMETER:
        row["normal_restitution_mean"] = float(np.mean(e)) if n else math.nan
        if n >= 2:
            se = float(np.std(e, ddof=1) / math.sqrt(n))
            stated_u = {"stated": stated is not None}
            _interval(
                row, "normal_restitution", (), (row["normal_restitution_mean"], se), n, stated_u
            )
            row["normal_restitution_std"] = float(np.std(e, ddof=1))
        row["interval_method"] = _joined_method(row)
        row["reason"] = f"{n} runs: a Walton fit needs at least {core.MIN_RUNS_FOR_PARAMETER}"
        return row
    fit = core.decide(np.ones((1, n)), x, y, c, e)
    model = core.MODELS[int(fit.model[0])]
    k = int(fit.split[0])
    # large n: the asymptotic interval where every line of the model is large too
    large = asymptotic.uses(n, asked, switch) and all(
        m == 0 or m >= switch // asymptotic.LINE_SHARE for m in (k, n - k)
    )
    boot = None if large else resampling.bootstrap(x, y, c, e, resamples, seed, stated)
    if sets is not None and boot is not None:  # the report's bands reuse them (bands.py)
        sets[tuple(key)] = boot
    if large:
        row.update(bootstrap_resamples=0, bootstrap_rule=asymptotic.rule(switch))
    bic = dict(zip(core.MODELS, fit.bic[0].tolist(), strict=True))
    row.update({f"bic_{name}": value for name, value in bic.items()})
    if boot is not None:
        support = {m: float(np.mean(boot.model == i)) for i, m in enumerate(core.MODELS)}
        row.update({f"model_support_{m}": share for m, share in support.items()})
    ranked = sorted(bic, key=lambda m: bic[m])
    row["model_reason"] = (
        f"{model}: smallest BIC {bic[model]:.4g} (next {ranked[1]} {bic[ranked[1]]:.4g}; "
        "BIC = n ln(S/n) + p ln n, p = 2 sticking, 2 sliding, 4 split)"
    )
    # a run counted as sliding whose own kinematics says it sticks never enters μ_f
    if model == "sticking":  # ... and one taken as sticking that slides never enters β
        moved, moved_why = core.kinematic_sliding(x, y, c, float(fit.beta[0]))
        moved = -moved
    else:
        moved, moved_why = core.kinematic_sticking(x, y, c, k)
    if moved:
        k += moved
        fit = core.at_split(x, y, c, e, k)
        if min(k, n - k) < core.MIN_RUNS_PER_LINE:
            row.update(n_sticking=k, n_sliding=n - k)
            row["normal_restitution_mean"] = float(np.mean(e))
            row["normal_restitution_std"] = float(np.std(e, ddof=1))
            mean = (float(fit.restitution[0]), float(fit.restitution_se[0]))
            _interval(
                row,
                "normal_restitution",
                (),
                mean,
                n,
                {"small": True, "stated": stated is not None},
            )
            row["interval_method"] = _joined_method(row)
            row["model_reason"] = (
                f"not determined: {moved_why}; {k} sticking and {n - k} sliding runs, too "
                f"few to choose a model (a split needs {core.MIN_RUNS_PER_LINE} runs on each "
                f"line; BIC chose {model})"
            )
            row["reason"] = (
                f"model not determined ({k} sticking, {n - k} sliding runs): no β, no μ_f"
            )
            return row
        row["model_reason"] = (
            f"split: {moved_why}; BIC chose {model} (smallest BIC {bic[model]:.4g})"
        )
        model = "split"
    how = {"boot": boot_method, "small": bool(moved), "stated": stated is not None}
    errors: tuple[float, ...] = (math.nan,) * 3
    centre: tuple[float, ...] = errors
    if large:
        how["asymptotic"] = asymptotic.method(switch, False)
        errors = asymptotic.walton_errors(x, y, c, e, k)
        centre = (float(fit.beta[0]), float(fit.friction[0]), float(fit.restitution[0]))
        if stated is not None:  # the measurement error's bias, as the bootstrap's pivot
            shift, spread = asymptotic.stated_shift(x, y, e, stated, centre, seed)
            # one method for the three parameters, each one's b̂ in it
            how["asymptotic"] = asymptotic.stated_method(switch) + asymptotic.shift_words(
                {name: float(b) for name, b in zip(("β", "μ_f", "ē"), shift, strict=True)}
            )
            centre = tuple(float(v) for v in np.asarray(centre) - shift)
            errors = tuple(asymptotic.stated_se(*pair) for pair in zip(errors, spread, strict=True))
        boot = core.Decision(*([np.array([])] * 9))  # no resamples: the values are unused
    assert boot is not None  # drawn above unless the interval is asymptotic
    row["model"] = model
    row.update(n_sticking=k, n_sliding=n - k)
    row["split_effective_incidence"] = float(x[k]) if model == "split" else math.nan
    row["rotational_restitution"] = float(fit.beta[0])
    beta = (centre[0], errors[0]) if large else (float(fit.beta[0]), float(fit.beta_se[0]))
    why_beta = _interval(
        row,
        "rotational_restitution",
        (boot.beta, boot.beta_se),
        beta,
        k,
        {**how, "refuse": _beta_refusal(model, n)},
    )
    row["sliding_friction"] = float(fit.friction[0])
    friction = (
        (centre[1], errors[1]) if large else (float(fit.friction[0]), float(fit.friction_se[0]))
    )
    why_mu = _interval(
        row, "sliding_friction", (boot.friction, boot.friction_se), friction, n - k, how
    )
    bound = math.nan
    if model == "sticking" and not math.isnan(row["rotational_restitution"]):
        bound = float((1 + row["rotational_restitution"]) * x[-1] / c[-1])
    row["sliding_friction_lower_bound"] = bound
    row["normal_restitution_mean"] = float(np.mean(e))
    mean = (centre[2], errors[2]) if large else (float(fit.restitution[0]), fit.restitution_se[0])
    why_e = _interval(
        row, "normal_restitution", (boot.restitution, boot.restitution_se), mean, n, how
    )
    row["normal_restitution_std"] = float(np.std(e, ddof=1))
    row["interval_method"] = _joined_method(row)
    if large and sets is not None:  # the band of each line from the same normal law
        sets[tuple(key)] = asymptotic.normal_sets(row, seed)
    said = [
        f"interval of {symbol} {why.removeprefix('interval ')}"
        for symbol, why in (("β", why_beta), ("μ_f", why_mu), ("ē", why_e))
        if why
    ]
    row["reason"] = "; ".join([p for p in [_reason(model, k, n - k), *said] if p])
    return row


def walton(
    frame: Any,
    *,
    resamples: int | None = None,
    seed: int = DEFAULT_SEED,
    method: str = DEFAULT_METHOD,
    settings: bayesian.Settings = bayesian.DEFAULT,
    draws: list | None = None,
    sets: dict | None = None,
    asymptotic_from: int = asymptotic.ASYMPTOTIC_FROM,
) -> list[dict[str, Any]]:
    """β, μ_f and ē per group with model selection and bootstrap intervals (Joseph & Hunt
    figures 4, 6, 9). Keys: ``WALTON_KEYS``. ``resamples`` None follows
    ``walton_bootstrap.RESAMPLE_RULE`` (1000 for groups up to 10,000 runs). ``method``
    "bayes": posterior medians and credible intervals for the model chosen
    (``bayesian.walton_row``, sampler ``settings``), each group's draws appended to
    ``draws`` when a list is given. ``sets``: a dict that receives each fitted group's
    bootstrap parameter sets (a ``walton.Decision``) under its (dataset, particle, wall,
    fluid), for the bands of its lines (``bands.walton_sets`` makes the same anew).
    ``asymptotic_from``: the group size from which, with no count asked for, the intervals
    are asymptotic (``granudb.analysis.asymptotic``) instead of bootstrapped."""
    bayesian.check_method(method)
    rows = []
    with resampling.one_thread():
        for key, group in _groups(frame):
            row = _walton_group(key, group, resamples, seed, sets, asymptotic_from)
            row["fit_method"] = method
            if method == bayesian.METHOD:
                arrays = walton_arrays(group)
                sigma = bayesian.stated_u(group, "effective_rebound", arrays[5])
                stated = resampling.stated_walton(group, arrays[5])
                stated = bayesian.stated_usable(stated, 3)  # every run's u(Ψ_out) > 0
                found, why = bayesian.walton_row(row, arrays, settings, sigma, stated)
                if row["model"] is not None:
                    reason = _reason(row["model"], row["n_sticking"], row["n_sliding"])
                    beta = _bayes_beta_refusal(row)
                    row["reason"] = "; ".join(p for p in (reason, beta, why) if p)
                if draws is not None and found is not None:
                    draws.append(found)
            rows.append(row)
    return rows


#: What a run is on Walton's plot, as its group's fit decided (the one classification the
#: regime map, the Walton table and every export share).
BRANCHES = ("sticking", "sliding", "no rebound", "not determined")


def _group_key(value: Any) -> Any:
    """A group's key part: no fluid is None whether written None, NaN or "dry"."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return None
    return None if isinstance(value, str) and value.casefold() == "dry" else value


def walton_branches(frame: Any, fits: list[dict[str, Any]]) -> np.ndarray:
    """Each run's branch, exactly as its group's Walton fit counted it: runs folded by
    the sign of v_T,in and sorted by Ψ_in as the fit sorts them, the first ``n_sticking``
    of a group sticking and the rest sliding (model "sticking": all stick; "sliding":
    all slide); a run without a rebound (e ≤ 0 or not measured) is "no rebound"; the runs
    of a group the fit chose no model for are "not determined". An object array of
    ``BRANCHES`` names, in the frame's row order."""
    # one string object per branch (not one per run): the figures hash these cells
    names = np.array(BRANCHES, dtype=object)
    rebound = frame["normal_restitution"].to_numpy(dtype=float) > 0
    branches = names[np.where(rebound, 3, 2)]
    chosen = {tuple(_group_key(f.get(g)) for g in GROUP): f for f in fits if f.get("model")}
    inputs = [c for c in WALTON_INPUTS if c not in GROUP and c in frame]
    for key, rows in group_rows(frame, GROUP).items():
        fit = chosen.get(tuple(_group_key(k) for k in key))
        if fit is None:
            continue
        runs = pd.DataFrame({c: frame[c].take(rows) for c in inputs}, copy=False)
        order = walton_arrays(runs)[5]  # the columns it reads, not a copy of every column
        sticking = int(fit.get("n_sticking") or 0)
        branches[rows[order]] = names[(np.arange(len(order)) >= sticking).astype(np.intp)]
    return branches
