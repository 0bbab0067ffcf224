"""Restitution against the normal Stokes number, e(St_n), per (dataset, particle, wall)
(Joseph & Hunt 2004 figure 5; docs/physics.md §10).

Why this shape: e_dry is a restitution, so it is bounded by 1; when the group has dry runs
their mean e is the measured dry limit and is used (fixed) instead of being fitted, and
the result says which. The threshold form's St_c is the *fitted* no-rebound threshold of
these runs, named ``fitted_critical_stokes``: it is not the default St_c of the rebound
verdict. Every empty fit says why in ``reason``.

Intervals: a studentized bootstrap over runs (``granudb.analysis.intervals``): each
resample is refitted by Gauss–Newton steps from the fit (vectorised over resamples, a step
halved until the sum of squares falls; the threshold form's runs below St_c drop out of
the Jacobian), and its standard error is √diag((JᵀWJ)⁻¹ S/(n−p)). Above
``walton_bootstrap.RULE_RUNS`` runs one Gauss–Newton step with the fit's Jacobian stands
for the refit (``one_step``: asymptotically the same, a few weighted sums per resample).
The asymptotic ± 1.96 se alone covered the threshold 75 % of the time at n = 5 and 82 % at n = 24.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from granudb.analysis import asymptotic, bayesian, intervals, restitution_small_n, shared_scale
from granudb.analysis import walton_bootstrap as resampling
from granudb.errors import ValidationError
from granudb.lazy import scipy_optimize

RESTITUTION_MODELS = {
    # name: (formula, citation)
    "threshold": (
        "e = e_dry (1 − St_c/St_n) for St_n > St_c, else 0 (St_c: the fitted threshold)",
        "an empirical form for the no-rebound threshold, as used by Joseph et al. (2001) "
        "J. Fluid Mech. 433, 329 and Gondret, Lance & Petit (2002) Phys. Fluids 14, 643",
    ),
    "exponential": (
        "e = e_dry exp(−k/St_n)",
        "Legendre, Zenit, Daniel & Guiraud (2006) Chem. Eng. Sci. 61, 3543",
    ),
}
PARAMETER_NAMES = {"threshold": "fitted_critical_stokes", "exponential": "k"}
#: The form fitted when none is named: Legendre et al.'s, the form of the prediction.
DEFAULT_MODEL = "exponential"
#: The form a report fits instead, and why (``restitution_model``).
REPORT_MODEL = "threshold"
REPORT_REASON = (
    "the report's choice, not fit restitution's default (exponential): its fitted St_c is "
    "the no-rebound threshold of these runs, read beside the St_c of the rebound verdict "
    "(figure 5)"
)
DEFAULT_REASON = "granudb's default: the form of the predicted restitution (Legendre et al.)"


def restitution_model(asked: str | None = None, *, report: bool = False) -> tuple[str, str]:
    """The one decision of which e(St_n) form is fitted, and why, for ``fit restitution``,
    ``granudb.fit_restitution`` and the report alike: the form ``asked`` for, else in a
    report ``REPORT_MODEL``, else ``DEFAULT_MODEL``. Every fit row carries the reason
    (``model_reason``) and every caption says it.

    >>> restitution_model()[0], restitution_model(report=True)[0]
    ('exponential', 'threshold')
    >>> restitution_model("threshold")
    ('threshold', 'as asked')
    """
    if asked is not None:
        if asked not in RESTITUTION_MODELS:
            raise ValidationError(
                "model", asked, f"must be one of {', '.join(RESTITUTION_MODELS)}", parameter=True
            )
        return asked, "as asked"
    return (REPORT_MODEL, REPORT_REASON) if report else (DEFAULT_MODEL, DEFAULT_REASON)


E_DRY_MAX = 1.0
SEED = 0
#: Fewer runs than this get no bootstrap interval: St_c's bootstrap-t covered 0.85 to 0.86
#: at n = 10 (benchmarks/fit_coverage.py; a pivot on ln St_c did no better); they get the
#: profile likelihood of ``restitution_small_n`` instead (issue 36).
MIN_RUNS_FOR_INTERVAL = 20
#: Gauss–Newton iterations of each resample's refit (it starts at the fit).
ITERATIONS = 30
#: ... or until no resample's parameters move by more than this share of the fit's
#: standard errors (the pivot needs the estimates to a small fraction of their spread).
TOLERANCE = 1e-3
_INPUTS = ["dataset", "particle", "wall", "fluid", "normal_stokes_number", "normal_restitution"]


def restitution_curve(model: str, stokes: np.ndarray, e_dry: float, parameter: float) -> np.ndarray:
    """e(St_n) of ``model`` ("threshold": parameter St_c; "exponential": parameter k)."""
    st = np.asarray(stokes, dtype=float)
    if model == "threshold":
        return np.where(st > parameter, e_dry * (1.0 - parameter / st), 0.0)
    if model == "exponential":
        return e_dry * np.exp(-parameter / st)
    raise KeyError(model)


def threshold_least_squares(
    st: np.ndarray, e: np.ndarray, e_dry: float | None
) -> tuple[float, float, float, float]:
    """(e_dry, e_dry_stderr, St_c, St_c_stderr) minimising Σ(e − e_dry(1 − St_c/St_n)₊)² over
    0 ≤ e_dry ≤ 1 (or e_dry fixed, stderr NaN), St_c ≥ 0: the global minimum, exactly.

    Why exact and without scipy: for St_c between two consecutive distinct St_n the runs
    above it are fixed, and with c = e_dry·St_c the model e_dry − c/St_n is linear in
    (e_dry, c), the constraint St_c ∈ [lo, hi] is linear too (e_dry·lo ≤ c ≤ e_dry·hi), and
    the sum of squares is continuous across the breakpoints (the model is 0 at St_n = St_c
    either way). So each interval is a small convex quadratic problem whose optimum is its
    interior stationary point or lies on an edge of its feasible polygon; suffix sums give
    every interval's coefficients at once and the smallest sum wins. The standard errors
    are ``curve_fit``'s: (JᵀJ)⁻¹ · S/(n − p) with J the model's Jacobian at the optimum.
    """
    order = np.argsort(st, kind="stable")
    s, y = np.asarray(st, float)[order], np.asarray(e, float)[order]
    n = len(s)
    u = 1.0 / s
    # suffix sums over the runs k..n-1 (the active ones when St_c lies below s[k])
    count = np.arange(n, 0, -1, dtype=float)
    su, suu = _suffix(u), _suffix(u * u)
    se, seu = _suffix(y), _suffix(y * u)
    total = float(np.sum(y * y))
    first = np.r_[True, s[1:] > s[:-1]]  # k starts an interval only at a new St_n value
    lo = np.r_[0.0, s[:-1]][first]
    hi = s[first]
    n_k, su, suu, se, seu = count[first], su[first], suu[first], se[first], seu[first]

    candidates = []  # (a, c) per interval for each way the optimum can sit
    if e_dry is None:
        with np.errstate(divide="ignore", invalid="ignore"):
            det = n_k * suu - su * su
            a = (se * suu - su * seu) / det
            c = (su * se - n_k * seu) / det
        inside = np.isfinite(a) & (a >= 0) & (a <= 1) & (c >= a * lo) & (c <= a * hi)
        candidates.append((np.where(inside, a, np.nan), np.where(inside, c, np.nan)))
        fixed_a = np.ones_like(lo)  # the edge e_dry = 1
    else:
        fixed_a = np.full_like(lo, e_dry)
    with np.errstate(divide="ignore", invalid="ignore"):
        c = np.clip((fixed_a * su - seu) / suu, fixed_a * lo, fixed_a * hi)
    candidates.append((fixed_a, c))
    for t in (lo, hi):  # the edges St_c = lo and St_c = hi
        if e_dry is None:
            with np.errstate(divide="ignore", invalid="ignore"):
                a = np.clip((se - t * seu) / (n_k - 2 * t * su + t * t * suu), 0.0, 1.0)
        else:
            a = fixed_a
        candidates.append((a, a * t))
    a_best, c_best, least = math.nan, math.nan, math.inf
    for a, c in candidates:  # one set at a time: a few arrays of the runs' length, no more
        a = np.broadcast_to(a, lo.shape)
        value = total - 2 * a * se + 2 * c * seu + a * a * n_k + c * (c * suu - 2 * a * su)
        value[~(np.isfinite(value) & (a > 0))] = np.inf
        best = int(np.argmin(value))
        if value[best] < least:  # ties: the earlier candidate, as one argmin over all
            a_best, c_best, least = float(a[best]), float(c[best]), float(value[best])
    if not math.isfinite(least):
        raise ValueError("no finite least-squares solution")
    critical = c_best / a_best
    residual = y - np.where(s > critical, a_best * (1 - critical * u), 0.0)
    ss = float(residual @ residual)
    # At a run's own St_n (where the optimum often sits) the model has a kink and the
    # Jacobian two one-sided values: the larger standard error of the two is reported.
    errors = [_errors(s > critical, a_best, critical, u, ss, e_dry)]
    if np.any(np.abs(s - critical) <= 1e-12 * critical):
        errors.append(_errors(s >= critical * (1 - 1e-12), a_best, critical, u, ss, e_dry))
    e_dry_se, critical_se = np.max(errors, axis=0)
    return (a_best if e_dry is None else e_dry), float(e_dry_se), critical, float(critical_se)


def _errors(
    active: np.ndarray, a: float, critical: float, u: np.ndarray, ss: float, e_dry: float | None
) -> tuple[float, float]:
    """curve_fit's standard errors: sqrt(diag((JᵀJ)⁻¹) · S/(n − p)); e_dry's NaN if fixed."""
    d_a = np.where(active, 1 - critical * u, 0.0)
    d_c = np.where(active, -a * u, 0.0)
    if e_dry is not None:
        dof, jj = len(u) - 1, float(d_c @ d_c)
        return math.nan, (math.sqrt(ss / dof / jj) if dof > 0 and jj > 0 else math.inf)
    jtj = np.array([[d_a @ d_a, d_a @ d_c], [d_a @ d_c, d_c @ d_c]])
    dof = len(u) - 2
    try:
        cov = np.linalg.inv(jtj) * (ss / dof) if dof > 0 else np.full((2, 2), math.inf)
    except np.linalg.LinAlgError:
        cov = np.full((2, 2), math.inf)
    return math.sqrt(cov[0, 0]), math.sqrt(cov[1, 1])


def _suffix(values: np.ndarray) -> np.ndarray:
    """Σ values[k:] for every k."""
    return np.cumsum(values[::-1])[::-1]


def _fit(model: str, st: np.ndarray, e: np.ndarray, e_dry: float | None) -> tuple:
    """(e_dry, e_dry_stderr, parameter, parameter_stderr) by bounded least squares; e_dry is
    fixed (stderr NaN) when given. The threshold form is solved exactly in numpy
    (``threshold_least_squares``); the exponential form by scipy's ``curve_fit``."""
    if model == "threshold":
        return threshold_least_squares(st, e, e_dry)
    start = max(1.0, float(np.min(st)) * 0.5)
    if e_dry is None:
        values, covariance = scipy_optimize.curve_fit(
            lambda s, a, b: restitution_curve(model, s, a, b),
            st,
            e,
            p0=(min(0.99, float(np.max(e)) * 1.05), start),
            bounds=([0.0, 0.0], [E_DRY_MAX, np.inf]),
            maxfev=20000,
        )
        errors = np.sqrt(np.diag(covariance))
        return float(values[0]), float(errors[0]), float(values[1]), float(errors[1])
    values, covariance = scipy_optimize.curve_fit(
        lambda s, b: restitution_curve(model, s, e_dry, b),
        st,
        e,
        p0=(start,),
        bounds=([0.0], [np.inf]),
        maxfev=20000,
    )
    return e_dry, math.nan, float(values[0]), float(np.sqrt(covariance[0, 0]))


def _curve(model: str, u: np.ndarray, a: np.ndarray, p: np.ndarray) -> tuple:
    """(f, ∂f/∂e_dry, ∂f/∂parameter) at 1/St_n = ``u`` (n,) for columns ``a``, ``p`` (m, 1)."""
    if model == "threshold":
        active = u * p < 1.0
        slope = np.where(active, 1.0 - p * u, 0.0)
        return a * slope, slope, np.where(active, -a * u, 0.0)
    decay = np.exp(-p * u)
    return a * decay, decay, -a * u * decay


def refit(
    model: str, st: np.ndarray, e: np.ndarray, w: np.ndarray, start: tuple, fixed: bool,
    scale: tuple = (math.nan, math.nan),
):  # fmt: skip
    """Weighted least-squares fits, one per row of the weights ``w`` (m, n), by damped
    Gauss–Newton from ``start`` = (e_dry, parameter) within 0 ≤ e_dry ≤ 1, parameter ≥ 0
    (e_dry held when ``fixed``): ((e_dry, se), (parameter, se)), arrays of shape (m,);
    ``scale``: the fit's standard errors, which set when the steps are small enough."""
    a_tol, p_tol = (TOLERANCE * v if math.isfinite(v) and v > 0 else 0.0 for v in scale)
    u = 1.0 / np.asarray(st, dtype=float)
    m = len(w)
    a = np.array(np.broadcast_to(np.asarray(start[0], dtype=float), (m,)))[:, None]
    p = np.full((m, 1), float(start[1]))

    def sse(a, p):
        return np.einsum("ij,ij->i", w, (e - _curve(model, u, a, p)[0]) ** 2)

    current = sse(a, p)
    for _ in range(ITERATIONS):
        f, ja, jp = _curve(model, u, a, p)
        r = e - f
        wjp = w * jp
        gp, pp = np.einsum("ij,ij->i", wjp, r), np.einsum("ij,ij->i", wjp, jp)
        if fixed:
            with np.errstate(invalid="ignore", divide="ignore"):
                da, dp = np.zeros(m), np.where(pp > 0, gp / pp, 0.0)
        else:
            ga = np.einsum("ij,ij->i", w * ja, r)
            aa, ap = np.einsum("ij,ij->i", w * ja, ja), np.einsum("ij,ij->i", w * ja, jp)
            det = aa * pp - ap * ap
            with np.errstate(invalid="ignore", divide="ignore"):
                da = np.where(det > 0, (pp * ga - ap * gp) / det, 0.0)
                dp = np.where(det > 0, (aa * gp - ap * ga) / det, 0.0)
        if np.all((np.abs(dp) <= p_tol) & (np.abs(da) <= a_tol)):
            break  # every resample's next step is a small share of the standard errors
        step = np.ones(m)
        moved = np.zeros(m, dtype=bool)
        for _ in range(8):  # halve until the sum of squares falls
            ta = np.clip(a[:, 0] + step * da, 0.0, E_DRY_MAX)[:, None]
            tp = np.maximum(p[:, 0] + step * dp, 0.0)[:, None]
            trial = sse(ta, tp)
            better = (trial < current) & ~moved
            a[better], p[better], current[better] = ta[better], tp[better], trial[better]
            moved |= better
            step = np.where(moved, step, step / 2)
            if moved.all():
                break
        if not moved.any():
            break
    f, ja, jp = _curve(model, u, a, p)
    count = w.sum(axis=1)
    dof = count - (1 if fixed else 2)
    with np.errstate(invalid="ignore", divide="ignore"):
        variance = np.where(dof > 0, current / dof, np.nan)
        pp = np.einsum("ij,ij->i", w * jp, jp)
        if fixed:
            a_se, p_se = np.full(m, np.nan), np.sqrt(variance / pp)
        else:
            aa, ap = np.einsum("ij,ij->i", w * ja, ja), np.einsum("ij,ij->i", w * ja, jp)
            det = aa * pp - ap * ap
            a_se, p_se = np.sqrt(variance * pp / det), np.sqrt(variance * aa / det)
    return (a[:, 0], a_se), (p[:, 0], p_se)


def one_step(
    model: str, st: np.ndarray, e: np.ndarray, w: np.ndarray, start: tuple, fixed: bool,
    series: np.ndarray | None = None, shift: np.ndarray | None = None,
):  # fmt: skip
    """``refit`` by one Gauss–Newton step from ``start`` with the Jacobian of the fit (the
    one-step bootstrap of large groups: the fit's residuals and Jacobian are shared by all
    resamples, so each costs a few weighted sums). ``series``: ``one_step_series`` of the
    same arguments, computed once for every batch of resamples. ``shift``: with ``fixed``,
    each resample's e_dry − start's (the Gauss–Newton step in the parameter given it)."""
    if series is None:
        series = one_step_series(model, st, e, start)
    a0, p0 = (float(v) for v in start)
    sums = w @ series
    ga, gp, aa, ap, pp, rr, count = sums.T
    with np.errstate(invalid="ignore", divide="ignore"):
        if fixed:  # e_dry held, or moved by ``shift`` (a resample's redrawn dry mean)
            da = np.zeros(len(w)) if shift is None else np.asarray(shift, dtype=float)
            dp, det = (gp - ap * da) / pp, pp
        else:
            det = aa * pp - ap * ap
            da, dp = (pp * ga - ap * gp) / det, (aa * gp - ap * ga) / det
        a = np.clip(a0 + da, 0.0, E_DRY_MAX)
        p = np.maximum(p0 + dp, 0.0)
        dof = count - (1 if fixed else 2)
        scale = np.where(dof > 0, np.maximum(rr - da * ga - dp * gp, 0.0) / dof, np.nan)
        a_se = np.full(len(w), np.nan) if fixed else np.sqrt(scale * pp / det)
        p_se = np.sqrt(scale / pp) if fixed else np.sqrt(scale * aa / det)
    return (a, a_se), (p, p_se)


def one_step_series(model: str, st: np.ndarray, e: np.ndarray, start: tuple) -> np.ndarray:
    """Per run (n, 7): J_a r, J_p r, J_a², J_a J_p, J_p², r², 1 at ``start`` (the fit): a
    resample's sums for ``one_step`` are its counts times these."""
    u = 1.0 / np.asarray(st, dtype=float)
    a0, p0 = (np.asarray(float(v)) for v in start)
    f, ja, jp = _curve(model, u, a0, p0)
    r = e - f
    return np.stack([ja * r, jp * r, ja * ja, ja * jp, jp * jp, r * r, np.ones_like(r)], axis=1)


def dry_means(dry: np.ndarray | None, resamples: int, seed: int) -> np.ndarray | None:
    """Each resample's e_dry: ē_dry + s_dry/√m · T, T of Student's t with m − 1 degrees of
    freedom (m dry runs, s_dry their sample sd): the law of the true mean given the dry
    runs, their unknown scatter integrated (from a generator of its own so the immersed
    runs' draws are unchanged), at most E_DRY_MAX; None with fewer than two dry runs
    (nothing to redraw). Resampling the dry runs instead gave St_c's interval 0.795 at
    10,000 runs with 4 dry runs (200 sets): the bootstrap of 4 values is too narrow
    ((m−1)/m of the variance, normal tails) where e_dry's error dominates (issue 36)."""
    if dry is None or len(dry) < 2:
        return None
    rng = np.random.default_rng([seed, DRY_STREAM])
    values = np.asarray(dry, dtype=float)
    m = len(values)
    spread = float(np.std(values, ddof=1)) / math.sqrt(m)
    drawn = float(np.mean(values)) + spread * rng.standard_t(m - 1, size=resamples)
    return np.minimum(drawn, E_DRY_MAX)


#: The generator stream of the dry runs' redraws (``dry_means``).
DRY_STREAM = 1
#: What ``interval_method`` adds when the dry runs' mean is redrawn in every resample.
DRY_METHOD = (
    ", the dry runs' mean e_dry redrawn in every resample from its Student-t law "
    "(ē_dry + s_dry/√m · t_(m−1))"
)


def bootstrap_sets(model: str, st: np.ndarray, e: np.ndarray, fit: tuple, fixed: bool,
                   resamples: int, seed: int, stated: tuple | None = None,
                   dry: np.ndarray | None = None) -> tuple:  # fmt: skip
    """The bootstrap's parameter sets ((e_dry, se), (parameter, se)), arrays over resamples,
    refitted from ``fit`` = (e_dry, e_dry_se, parameter, parameter_se): the sets behind
    ``bootstrap_intervals`` and the report's band of the fitted curve. ``stated``: the
    runs' relative standard uncertainties of v_n,in and v_n,out
    (``resampling.stated_speeds``); each resample then also perturbs every run's measured
    speeds by them (``perturbed``). ``dry``: the dry runs' e when e_dry is their mean
    (``fixed``): each resample then holds its own redrawn mean (``dry_means``), so e_dry's
    uncertainty enters the parameter's interval (issue 36)."""
    n = len(st)
    a_all = dry_means(dry, resamples, seed) if fixed else None
    rng = np.random.default_rng(seed)
    large = n > resampling.RULE_RUNS
    batch = max(1, resampling.BATCH_CELLS // (n if large else 8 * n))
    parts = []
    series = one_step_series(model, st, e, (fit[0], fit[2])) if large else None
    # without stated u the draws are the generator's only use: the shared counts
    # (``resampling.count_batches``); with it, each batch's draws, then its perturbations
    plain = None if stated is not None else resampling.count_batches(seed, resamples, n, n, batch)
    weights = np.zeros((min(batch, resamples), n)) if plain is None else None
    for start in range(0, resamples, batch):
        if plain is None:
            w = resampling.draw_counts(rng, min(batch, resamples - start), n, n, weights)
        else:
            w = next(plain)
        a0 = fit[0] if a_all is None else a_all[start : start + len(w)]
        if stated is not None:
            st_b, e_b = resampling.perturbed(rng, len(w), st, e, stated)
            parts.append(refit(model, st_b, e_b, w, (a0, fit[2]), fixed, (fit[1], fit[3])))
        elif large:
            shift = None if a_all is None else a0 - fit[0]
            parts.append(one_step(model, st, e, w, (fit[0], fit[2]), fixed, series, shift))
        else:
            parts.append(refit(model, st, e, w, (a0, fit[2]), fixed, (fit[1], fit[3])))
    return tuple(
        tuple(np.concatenate([part[i][j] for part in parts]) for j in range(2)) for i in range(2)
    )


def bootstrap_intervals(model: str, st: np.ndarray, e: np.ndarray, fit: tuple, fixed: bool,
                        resamples: int, seed: int, stated: tuple | None = None,
                        dry: np.ndarray | None = None) -> dict:  # fmt: skip
    """{name: intervals.Interval}: studentized bootstrap intervals of e_dry (unless ``fixed``)
    and the parameter, from
    ``fit`` = (e_dry, e_dry_se, parameter, parameter_se), and the runs' ``stated``
    uncertainties (``bootstrap_sets``)."""
    (a, a_se), (p, p_se) = bootstrap_sets(model, st, e, fit, fixed, resamples, seed, stated, dry)
    found = {"parameter": intervals.studentized(fit[2], fit[3], p, p_se, bounds=(0.0, math.inf))}
    if not fixed:
        found["e_dry"] = intervals.studentized(fit[0], fit[1], a, a_se, bounds=(0.0, E_DRY_MAX))
    return found


def asymptotic_law(model: str, st: np.ndarray, e: np.ndarray, fit: tuple, fixed: bool,
                   seed: int, stated: tuple | None = None,
                   dry: np.ndarray | None = None) -> tuple:  # fmt: skip
    """The asymptotic normal law of (e_dry, parameter) at large n (issue 36): (centre (2,),
    covariance (2, 2), degrees of freedom (2,)) from ``fit`` = (e_dry, e_dry_se, parameter,
    parameter_se). The least squares' covariance by the delta method
    (``asymptotic.nls_covariance``: sandwich or least squares, the Jacobian at the fit);
    with ``fixed`` e_dry the mean of ``dry`` runs (≥ 2), its variance s²/n_dry carried into
    the parameter by ∂θ/∂e_dry = −ΣJ_θJ_e/ΣJ_θ² (the Gauss–Newton step ``one_step`` takes
    for a moved e_dry), on n_dry − 1 degrees of freedom; with ``stated`` u, the centre moved
    by the mean shift of ``asymptotic.SHIFT_DRAWS`` copies of all the runs perturbed by
    their stated u (``resampling.perturbed``, each refitted by ``refit``) and their
    covariance added (× (1 + 1/copies), on copies − 1 degrees of freedom), as
    ``asymptotic.stated_shift`` does for the Walton fit. The degrees of freedom are
    Welch–Satterthwaite's (``asymptotic.welch_dof``); the intervals and the report's band
    both come from this law (``asymptotic_intervals``, ``asymptotic_sets``)."""
    st, e = np.asarray(st, dtype=float), np.asarray(e, dtype=float)
    centre = np.array([fit[0], fit[2]], dtype=float)
    f, ja, jp = _curve(model, 1.0 / st, centre[:1], centre[1:])
    r = e - f
    parts: list[list[tuple[float, float]]] = [[], []]
    covariance = np.zeros((2, 2))
    if fixed:
        covariance[1, 1] = asymptotic.nls_covariance(jp[:, None], r)[0, 0]
        if dry is not None and len(dry) >= 2:
            dry_var = float(np.var(dry, ddof=1)) / len(dry)
            slope = -float(ja @ jp) / float(jp @ jp)
            covariance += dry_var * np.array([[1.0, slope], [slope, slope * slope]])
            parts[0].append((dry_var, len(dry) - 1))
            parts[1].append((slope * slope * dry_var, len(dry) - 1))
    else:
        covariance += asymptotic.nls_covariance(np.stack([ja, jp], axis=1), r)
    if stated is not None:
        draws = asymptotic.SHIFT_DRAWS
        rng = np.random.default_rng(seed)
        st_b, e_b = resampling.perturbed(rng, draws, st, e, stated)
        (a, _), (p, _) = refit(model, st_b, e_b, np.ones((draws, len(st))), (fit[0], fit[2]),
                               fixed, (fit[1], fit[3]))  # fmt: skip
        shifts = np.stack([a, p], axis=1) - centre
        shifts = shifts[np.all(np.isfinite(shifts), axis=1)]
        if len(shifts) < max(2, draws // 2):
            return centre, np.full((2, 2), math.nan), np.full(2, math.nan)
        spread = np.cov(shifts.T) * (1 + 1 / draws)
        centre, covariance = centre - shifts.mean(axis=0), covariance + spread
        for i in range(2):
            parts[i].append((float(spread[i, i]), draws - 1))
    dof = [
        asymptotic.welch_dof([(float(covariance[i, i]) - sum(v for v, _ in parts[i]),
                              math.inf), *parts[i]])
        for i in range(2)
    ]  # fmt: skip
    return centre, covariance, np.array(dof)


def asymptotic_intervals(model: str, st: np.ndarray, e: np.ndarray, fit: tuple, fixed: bool,
                         seed: int, stated: tuple | None = None,
                         dry: np.ndarray | None = None) -> tuple[dict, dict]:  # fmt: skip
    """({name: intervals.Interval}, {name: b̂}): the asymptotic intervals θ̂ ± t se of the
    parameter and (unless ``fixed``) e_dry from ``asymptotic_law``, in place of
    ``bootstrap_intervals``, and each one's shift b̂ = θ̂ − its centre (0 without stated u)."""
    centre, covariance, dof = asymptotic_law(model, st, e, fit, fixed, seed, stated, dry)
    shift = {"e_dry": float(fit[0] - centre[0]), "parameter": float(fit[2] - centre[1])}
    se = np.sqrt(np.diag(covariance))
    level = intervals.LEVEL
    found = {"parameter": asymptotic.t_interval(
        centre[1], se[1], dof[1], bounds=(0.0, math.inf), level=level)}  # fmt: skip
    if not fixed:
        found["e_dry"] = asymptotic.t_interval(
            centre[0], se[0], dof[0], bounds=(0.0, E_DRY_MAX), level=level
        )
    return found, {name: shift[name] for name in found}


def asymptotic_sets(model: str, st: np.ndarray, e: np.ndarray, fit: tuple, fixed: bool,
                    count: int, seed: int, stated: tuple | None = None,
                    dry: np.ndarray | None = None) -> tuple:  # fmt: skip
    """``count`` (e_dry, parameter) sets drawn (seeded) from ``asymptotic_law``'s normal law,
    within 0 ≤ e_dry ≤ 1 and parameter ≥ 0: the report's band where the interval is
    asymptotic (``granudb.analysis.bands``)."""
    centre, covariance, _ = asymptotic_law(model, st, e, fit, fixed, seed, stated, dry)
    if not np.all(np.isfinite(covariance)):
        return np.full(count, math.nan), np.full(count, math.nan)
    values, vectors = np.linalg.eigh(covariance)
    root = vectors * np.sqrt(np.maximum(values, 0.0))
    drawn = centre + np.random.default_rng(seed).standard_normal((count, 2)) @ root.T
    return np.clip(drawn[:, 0], 0.0, E_DRY_MAX), np.maximum(drawn[:, 1], 0.0)


def _group_row(
    model: str,
    key: tuple,
    st: np.ndarray,
    e: np.ndarray,
    dry_e: np.ndarray,
    resamples: int | None = None,
    stated: tuple | None = None,
    switch: int = asymptotic.ASYMPTOTIC_FROM,
) -> dict[str, Any]:
    fixed = float(min(np.mean(dry_e), E_DRY_MAX)) if dry_e.size else None
    large = asymptotic.uses(len(st), resamples, switch)  # the asymptotic interval (issue 36)
    row: dict[str, Any] = {
        "dataset": key[0],
        "particle": key[1],
        "wall": key[2],
        "model": model,
        "formula": RESTITUTION_MODELS[model][0],
        "citation": RESTITUTION_MODELS[model][1],
        "n_runs": len(st),
        "n_dry_runs": int(dry_e.size),
        "e_dry": math.nan,
        "e_dry_stderr": math.nan,
        "e_dry_source": (
            f"mean e of the group's {dry_e.size} dry run{'s' if dry_e.size != 1 else ''} "
            + (
                (
                    "(fixed in the fit, its variance in the interval)"
                    if large
                    else "(fixed in the fit, redrawn in the bootstrap)"
                )
                if dry_e.size >= 2
                else "(fixed)"
            )
            if fixed is not None
            else "fitted, bounded 0 ≤ e_dry ≤ 1"
        ),
        "parameter_name": PARAMETER_NAMES[model],
        "parameter": math.nan,
        "parameter_stderr": math.nan,
        "parameter_low": math.nan,
        "parameter_high": math.nan,
        "e_dry_low": math.nan,
        "e_dry_high": math.nan,
        "interval_method": intervals.METHOD + (resampling.STATED_METHOD if stated else ""),
        "bootstrap_resamples": resampling.resample_count(len(st))
        if resamples is None
        else resamples,
        "bootstrap_seed": SEED,
        "interval_reason": "",
        "stokes_number": "St_n = m* v_N,in/(6πμR*²) of the relative normal approach (as derived)",
        "reason": "",
    }
    if large:  # no resamples: the record says the method and the switch
        row["interval_method"] = asymptotic.restitution_method(
            switch, stated is not None, int(dry_e.size)
        )
        row.update(bootstrap_resamples=0, bootstrap_rule=asymptotic.rule(switch))
    needed = 2 if fixed is not None else 3
    if len(np.unique(st)) < needed or float(np.max(st)) < 2.0 * float(np.min(st)):
        distinct = len(np.unique(st))
        row["reason"] = (
            f"St_n must take ≥ {needed} distinct values spanning a factor of 2 "
            + (f"(1 value, {st[0]:.3g})" if distinct == 1 else
               f"({distinct} values from {np.min(st):.3g} to {np.max(st):.3g})")
        )  # fmt: skip
    else:
        try:
            e_dry, e_dry_se, parameter, parameter_se = _fit(model, st, e, fixed)
            row.update(e_dry=e_dry, e_dry_stderr=e_dry_se, parameter=parameter)
            row["parameter_stderr"] = parameter_se
        except (RuntimeError, ValueError) as exc:
            row["reason"] = f"least squares did not converge ({type(exc).__name__})"
        else:
            _intervals(row, model, st, e, fixed is not None, stated, dry_e, large)
    if model == "threshold":
        row["fitted_critical_stokes"] = row["parameter"]
    return row


def _intervals(
    row: dict,
    model: str,
    st: np.ndarray,
    e: np.ndarray,
    fixed: bool,
    stated: tuple | None = None,
    dry: np.ndarray | None = None,
    large: bool = False,
) -> None:
    """The bootstrap-t intervals into ``row`` (``large``: the asymptotic ones), or why there
    are none (``interval_reason``)."""
    refused = intervals.too_few(len(st), MIN_RUNS_FOR_INTERVAL)
    if refused:  # few runs: the profile likelihood where it is measured to hold (issue 36)
        restitution_small_n.into_row(row, model, st, e, fixed, stated, dry, MIN_RUNS_FOR_INTERVAL)
        return
    fit = (row["e_dry"], row["e_dry_stderr"], row["parameter"], row["parameter_stderr"])
    if large:
        found, shift = asymptotic_intervals(model, st, e, fit, fixed, SEED, stated, dry)
        if stated is not None and all(map(math.isfinite, shift.values())):
            names = {"parameter": PARAMETER_NAMES[model], "e_dry": "e_dry"}
            row["interval_method"] += asymptotic.shift_words(
                {names[name]: value for name, value in sorted(shift.items())}
            )
    else:
        found = bootstrap_intervals(
            model, st, e, fit, fixed, row["bootstrap_resamples"], SEED, stated, dry
        )
    if fixed and dry is not None and len(dry) >= 2 and not large:
        row["interval_method"] += DRY_METHOD
    reasons = []
    for name, got in found.items():
        row[f"{name}_low"], row[f"{name}_high"] = got.low, got.high
        if got.reason:
            reasons.append(
                f"{PARAMETER_NAMES[model] if name == 'parameter' else name}: {got.reason}"
            )
    row["interval_reason"] = "; ".join(reasons)


def _widen_by_scale(row: dict, share: float, sources: str) -> None:
    """The parameter's interval widened by the catalogue's share of St_n, a relative error
    shared by every run (St_c and k scale with it, e_dry does not:
    ``granudb.analysis.shared_scale``); the method says so."""
    if not (share > 0) or math.isnan(row.get("parameter_low", math.nan)):
        return
    row["parameter_low"], row["parameter_high"] = shared_scale.widened(
        row["parameter_low"], row["parameter_high"], row["parameter"], share, intervals.LEVEL
    )
    row["interval_method"] += shared_scale.words(share, sources)


def _bayes_stated(frame: Any, runs: np.ndarray, e: np.ndarray, speeds: tuple | None):
    """The Bayesian option's per-run (r, u_e): r = u(v_N,in)/v_N,in and u_e =
    u(v_n,out)/v_N,in = r_out e from the stated speeds; without them, the runs' listed
    u(e) with r = 0; None unless every run has u_e > 0 (then σ is fitted)."""
    found: np.ndarray | None
    if speeds is not None:
        r_in, r_out = speeds
        found = np.stack([r_in, r_out * np.abs(e)])
    else:
        u = bayesian.stated_u(frame, "normal_restitution", runs)
        found = None if u is None else np.stack([np.zeros_like(u), u])
    usable = bayesian.stated_usable(found, 1)
    return None if usable is None else (usable[0], usable[1])


def restitution(
    frame: Any,
    model: str | None = None,
    *,
    method: str = "bootstrap",
    settings: bayesian.Settings = bayesian.DEFAULT,
    draws: list | None = None,
    report: bool = False,
    resamples: int | None = None,
    asymptotic_from: int = asymptotic.ASYMPTOTIC_FROM,
    stokes_scale: dict[tuple, tuple[float, str]] | None = None,
) -> list[dict[str, Any]]:
    """Fit e(St_n) of the immersed runs per (dataset, particle, wall), all fluids together
    (figure 5).

    Keys: the group; ``model``, ``formula``, ``citation``; ``n_runs`` (immersed) and
    ``n_dry_runs``; ``e_dry`` (≤ 1) with ``e_dry_stderr`` (asymptotic, NaN when fixed) and
    ``e_dry_source`` (fitted, or the dry runs' mean); ``parameter_name``
    ('fitted_critical_stokes' or 'k'), ``parameter``, ``parameter_stderr`` (asymptotic);
    ``parameter_low``/``_high`` and ``e_dry_low``/``_high``: studentized bootstrap intervals
    (``interval_method``, ``bootstrap_resamples``, ``bootstrap_seed``); below
    MIN_RUNS_FOR_INTERVAL runs the profile likelihood's (``restitution_small_n``,
    ``bootstrap_resamples`` 0); NaN with ``interval_reason`` where refused or degenerate;
    ``fitted_critical_stokes`` (threshold form only); ``stokes_number`` (which St);
    ``reason`` (why the fit is empty, else ''); ``fit_method``; ``model_reason`` (why
    this form: ``restitution_model``; ``model`` None: the default, or with ``report`` the
    report's form); ``resamples``: the bootstrap's count (None: the rule's); from
    ``asymptotic_from`` immersed runs in a group, with no count asked for, the interval is
    asymptotic instead (``asymptotic_intervals``; ``bootstrap_resamples`` 0 and
    ``bootstrap_rule`` say so). Where runs carry stated
    uncertainties of their normal speeds (``u_v_n_in_m_s``, ``u_v_n_out_m_s``), every
    resample perturbs them too (``interval_method`` says so; docs/physics.md, "Fit
    intervals"). ``method`` "bayes": values are posterior medians with 95 % credible
    intervals (``bayesian.restitution_row``, which adds the prior, likelihood, sampler
    settings and diagnostics), each group's draws appended to ``draws`` when a list is given.
    ``stokes_scale``: {(dataset, particle, wall): (u_r, sources)}, the catalogue's share of
    each group's St_n where it states one (``granudb.scenario.plug_ins.stokes_scale``):
    an error shared by every run, which widens the parameter's interval whatever the
    method (``granudb.analysis.shared_scale``; ``interval_method`` says so).
    """
    model, why = restitution_model(model, report=report)
    bayesian.check_method(method)
    st = frame["normal_stokes_number"].to_numpy(dtype=float)
    e = frame["normal_restitution"].to_numpy(dtype=float)
    finite_e = np.isfinite(e)
    immersed = np.isfinite(st) & finite_e
    dry = finite_e & (frame["fluid"].isna().to_numpy() if "fluid" in frame else False)
    # Each group's row positions (frame order) from the key columns alone: no copy of the
    # frame, of its immersed or dry rows, or of the frame sorted by group.
    groups = frame.groupby([frame[k] for k in _INPUTS[:3]], sort=True).indices
    speeds = resampling.stated_speeds(frame)
    scales = stokes_scale or {}
    results = []
    with resampling.one_thread():  # as the other fits (walton_bootstrap.one_thread)
        for key in sorted(groups):
            rows = groups[key]
            runs = rows[immersed[rows]]
            if runs.size:
                stated = None if speeds is None else tuple(r[runs] for r in speeds)
                stated = stated if stated is not None and any(r.any() for r in stated) else None
                row = _group_row(model, key, st[runs], e[runs], e[rows[dry[rows]]],
                                 resamples, stated, asymptotic_from)  # fmt: skip
                row["fit_method"] = method
                row["model_reason"] = why
                if method == bayesian.METHOD:
                    form = bayesian.Form(
                        lambda s, a, q: restitution_curve(model, s, a, q),
                        PARAMETER_NAMES[model],
                        E_DRY_MAX,
                    )
                    found = bayesian.restitution_row(
                        row, form, st[runs], e[runs], settings,
                        _bayes_stated(frame, runs, e[runs], stated), e[rows[dry[rows]]],
                    )  # fmt: skip
                    if draws is not None and found is not None:
                        draws.append(found)
                if key in scales:  # the catalogue's share of St_n, whatever the method
                    _widen_by_scale(row, *scales[key])
                results.append(row)
    return results
