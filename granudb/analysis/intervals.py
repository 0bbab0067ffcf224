"""Bootstrap intervals that hold their coverage where runs are few (issue 23; docs/physics.md,
"Fit intervals").

Why studentized. The percentile interval of a bootstrap is too narrow for small samples
(its width shrinks like √((n−1)/n) and it ignores that the spread itself is estimated):
measured, Walton's μ_f at n = 5 covered the truth 84 % of the time, the asymptotic
± 1.96 se of the restitution threshold 75 %. The studentized (bootstrap-t) interval
(Efron & Tibshirani 1993, *An Introduction to the Bootstrap*, §12.5; Davison & Hinkley
1997, *Bootstrap Methods and their Application*, §5.2.1, eq. 5.7) pivots on
t* = (θ* − θ̂)/se*: every fit here has a closed-form standard error for each resample (a
line through the origin: √(S/(n−1)/Σu²); a mean: s/√n; a nonlinear least-squares fit:
√diag((JᵀJ)⁻¹ S/(n−p))), so the pivot costs a few sums more than the percentile interval.
The interval is [θ̂ − t*₉₇.₅ se, θ̂ − t*₂.₅ se], widened to hold the percentile interval
too (where resamples switch model their se* grow and the pivot alone is too narrow:
measured 0.895 coverage in two cells of benchmarks/fit_coverage.py, ≥ 0.916 with the hull),
clipped to the parameter's physical range.

Never a zero-width interval: a standard error of zero (every run on the line, or one run
drawn over and over) or bootstrap pivots without spread give "not determined" with the
reason, as does a parameter determined in fewer than ``MIN_DETERMINED`` of the resamples.
Below a fit's stated minimum number of runs the interval is refused with
"not determined: N runs, at least M needed" (``too_few``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from granudb.analysis import defaults

LEVEL = defaults.CONFIDENCE_LEVEL
#: A parameter determined in fewer resamples than this share gets no interval.
MIN_DETERMINED = 0.5
METHOD = "studentized bootstrap (bootstrap-t) over runs"
#: A standard error below this share of the estimate is rounding (exact data: the sums of
#: squares cancel to ~1e-8 of the estimate): zero.
ROUNDING = 1e-6


@dataclass(frozen=True)
class Interval:
    """An interval and the share of resamples that determined the parameter; ``reason``
    is "" when the interval is given, else why not (and low, high are NaN)."""

    low: float
    high: float
    determined: float
    reason: str = ""


def too_few(n: int, minimum: int) -> str:
    """The refusal of a fit below its minimum number of runs ('' when there are enough)."""
    return f"not determined: {n} runs, at least {minimum} needed" if n < minimum else ""


def studentized(
    point: float,
    se: float,
    boot: np.ndarray,
    boot_se: np.ndarray,
    *,
    bounds: tuple[float, float] = (-math.inf, math.inf),
    level: float = LEVEL,
) -> Interval:
    """The bootstrap-t interval of ``point`` (standard error ``se``) from the resamples'
    estimates ``boot`` and their standard errors ``boot_se`` (NaN where a resample did not
    determine the parameter), clipped to ``bounds``.

    >>> rng = np.random.default_rng(0)
    >>> boot = 1.0 + 0.1 * rng.standard_normal(1000)
    >>> got = studentized(1.0, 0.1, boot, np.full(1000, 0.1))
    >>> round(got.low, 1), round(got.high, 1), got.reason
    (0.8, 1.2, '')
    """
    boot, boot_se = np.asarray(boot, dtype=float), np.asarray(boot_se, dtype=float)
    nan = math.nan
    valid = np.isfinite(boot)
    share = float(np.mean(valid)) if boot.size else 0.0
    if not math.isfinite(point):
        return Interval(nan, nan, share, "not determined by these runs")
    if not (math.isfinite(se) and se > ROUNDING * abs(point)):
        return Interval(nan, nan, share, "interval not determined: zero standard error")
    if share < MIN_DETERMINED:
        return Interval(
            nan, nan, share, f"interval not determined: determined in {share:.0%} of resamples"
        )
    with np.errstate(divide="ignore", invalid="ignore"):
        pivot = (boot[valid] - point) / boot_se[valid]
    pivot = pivot[~np.isnan(pivot)]  # 0/0: a resample equal to the fit, without spread
    if pivot.size == 0 or np.ptp(np.where(np.isfinite(pivot), pivot, 0.0)) == 0:
        return Interval(nan, nan, share, "interval not determined: the bootstrap is degenerate")
    tail = 50.0 * (1.0 - level)
    # order statistics, no interpolation (a pivot may be ±inf: se* = 0 off the estimate)
    lower_t = np.percentile(pivot, tail, method="lower")
    upper_t = np.percentile(pivot, 100.0 - tail, method="higher")
    # the hull with the percentile interval: where resamples switch model their se* grow,
    # the pivots shrink toward 0 and the bootstrap-t interval alone comes out too narrow
    finite = boot[valid]
    low = max(min(point - upper_t * se, np.percentile(finite, tail, method="lower")), bounds[0])
    high = min(
        max(point - lower_t * se, np.percentile(finite, 100 - tail, method="higher")), bounds[1]
    )
    if not (math.isfinite(low) and math.isfinite(high)):
        return Interval(nan, nan, share, "interval not determined: the bootstrap is unbounded")
    if not high > low:
        return Interval(nan, nan, share, "interval not determined: the bootstrap is degenerate")
    return Interval(float(low), float(high), share)


#: The small-n interval of a parameter that is a (weighted) mean of per-run values.
T_METHOD = "t-interval of the per-run values (Student t, n−1 degrees of freedom)"


def t_interval(
    point: float,
    se: float,
    runs: int,
    *,
    bounds: tuple[float, float] = (-math.inf, math.inf),
    level: float = LEVEL,
) -> Interval:
    """θ̂ ± t_{runs−1} se, clipped to ``bounds``: exact coverage for a mean of ``runs``
    independent normal per-run values (the least-squares slope of a line through the origin
    is the weighted mean of the per-run slopes, weights u², and √(S/(n−1)/Σu²) its standard
    error; Student 1908). ``determined`` is 1. Refused (NaN, the reason) with fewer than two
    runs or a standard error at the level of rounding.

    >>> got = t_interval(0.11, 0.01, 5)
    >>> round(got.low, 4), round(got.high, 4)
    (0.0822, 0.1378)
    """
    nan = math.nan
    if not math.isfinite(point):
        return Interval(nan, nan, 0.0, "not determined by these runs")
    if runs < 2:
        return Interval(nan, nan, 0.0, f"not determined: {runs} runs, at least 2 needed")
    if not (math.isfinite(se) and se > ROUNDING * abs(point)):
        return Interval(nan, nan, 1.0, "interval not determined: zero standard error")
    half = student_t(level, runs - 1) * se
    low, high = max(point - half, bounds[0]), min(point + half, bounds[1])
    return Interval(float(low), float(high), 1.0)


def central_t_probability(t: float, dof: int) -> float:
    """P(|T| < t) for Student's T with integer ``dof`` degrees of freedom, in closed form
    (Abramowitz & Stegun 1964, 26.7.3–26.7.4): no scipy in a report's path."""
    theta = math.atan(t / math.sqrt(dof))
    c2 = math.cos(theta) ** 2
    if dof % 2:  # odd
        if dof == 1:
            return 2.0 * theta / math.pi
        term = total = math.cos(theta)
        for k in range(3, dof - 1, 2):
            term *= c2 * (k - 1) / k
            total += term
        return 2.0 / math.pi * (theta + math.sin(theta) * total)
    term = total = 1.0
    for k in range(2, dof - 1, 2):
        term *= c2 * (k - 1) / k
        total += term
    return math.sin(theta) * total


def student_t(level: float, dof: int) -> float:
    """The two-sided ``level`` quantile t of Student's T (P(|T| < t) = level), by bisection
    of ``central_t_probability`` to 1e-12 of t.

    >>> round(student_t(0.95, 4), 4), round(student_t(0.95, 1), 3)
    (2.7764, 12.706)
    """
    low, high = 0.0, 1.0
    while central_t_probability(high, dof) < level:
        high *= 2.0
    while high - low > 1e-12 * high:
        mid = 0.5 * (low + high)
        low, high = (mid, high) if central_t_probability(mid, dof) < level else (low, mid)
    return 0.5 * (low + high)
