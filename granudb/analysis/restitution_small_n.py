"""Intervals of the restitution fit below its bootstrap's minimum (issue 36): the profile
likelihood with the F calibration.

Why this shape. Both forms are linear in e_dry at a fixed parameter p (St_c or k): e =
e_dry h(St_n; p), h = max(1 − p/St_n, 0) or exp(−p/St_n). So the sum of squares S(a, p) =
Σe² − 2a Σe h + a² Σh² is known in closed form on a grid of p, and each parameter's
profile (the other minimised within its bounds, 0 ≤ e_dry ≤ 1, p ≥ 0) costs one pass over
the grid. The interval is {θ: (S_prof(θ) − S_min) / (S_min/(n − k)) ≤ t²_{n−k}} (k fitted
parameters): exact for a model linear in its parameters under normal scatter (the F test
of one parameter), and for these curved forms the likelihood-ratio set that follows the
curvature the bootstrap-t at few runs could not (it covered 0.75 at n = 5). An interval
whose end runs into the grid's end (the runs do not bound it) is refused with that reason.

e_dry from the dry runs (issue 36: nothing held fixed that was estimated). Where e_dry is the
mean of m ≥ 2 dry runs, the true e_dry given them follows ē_dry + s_dry/√m · T, T Student's
t with m − 1 degrees of freedom (their unknown scatter integrated; the law the bootstrap
redraws, ``restitution_fit.dry_means``). At each e_dry the profile's signed root r(p) =
±√((S(p) − S_min)/(S_min/(n − 1))) gives the parameter's confidence distribution F_t,n−1(r(p))
(the F interval is its 2.5 and 97.5 % points); ``mixed_intervals`` averages it over
DRY_NODES equal-probability quantiles of e_dry's law, and the interval is the average's 2.5
and 97.5 % points. With e_dry exact it is the F interval; where e_dry's error dominates it
is e_dry's t-interval mapped through the fit. Holding e_dry at the mean covered 0.905 (n =
10, 4 dry runs). Measured coverage per form and parameter: docs/intervals.md.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from granudb.analysis import intervals

#: The small-n interval's method words.
METHOD = (
    "profile likelihood, F-calibrated: {{θ: (S_prof(θ) − S_min)/(S_min/(n − k)) ≤ "
    "t²_(n−k)}}, the other parameter minimised within its bounds at each θ (fewer than {runs} "
    "runs)"
)


def gave(row: Mapping[str, Any]) -> bool:
    """True where a restitution row's intervals are this module's (no bootstrap sets)."""
    return str(row.get("interval_method", "")).startswith(METHOD.split(",")[0])


#: What the method adds with e_dry held at one dry run's value (one run states no scatter).
FIXED = "; e_dry held at the one dry run's e (one run cannot state its uncertainty)"
#: What the method adds with e_dry the mean of two or more dry runs (``mixed_intervals``).
MIXED = (
    "; e_dry the dry runs' mean, its uncertainty integrated: the parameter's confidence "
    "distribution F_t(n−1)(±√((S(θ) − S_min)/(S_min/(n − 1)))) at each e_dry averaged over "
    "ē_dry + s_dry/√m · t_(m−1) ({nodes} quantiles), the interval its 2.5 and 97.5 % points"
)
#: Equal-probability quantile nodes of e_dry's Student-t law in ``mixed_intervals``.
DRY_NODES = 256
#: Grid of the parameter: this many points from GRID_LOW min St_n to GRID_HIGH max St_n.
GRID_POINTS = 4000
GRID_LOW, GRID_HIGH = 1e-3, 100.0
#: Grid of e_dry on [0, 1].
E_DRY_POINTS = 4001


def shapes(model: str, st: np.ndarray, p: np.ndarray) -> np.ndarray:
    """h(St_n; p), shape (len(p), len(st)): e = e_dry h."""
    ratio = p[:, None] / st[None, :]
    if model == "threshold":
        return np.maximum(1.0 - ratio, 0.0)
    return np.exp(-ratio)


def profile_intervals(
    model: str,
    st: np.ndarray,
    e: np.ndarray,
    e_dry: float | None,
    *,
    level: float = intervals.LEVEL,
    e_dry_max: float = 1.0,
) -> dict[str, intervals.Interval]:
    """{"parameter": …, "e_dry": … (unless ``e_dry`` is held)}: the F-calibrated profile
    likelihood intervals of the restitution fit on the immersed runs ``st``, ``e``."""
    st, e = np.asarray(st, dtype=float), np.asarray(e, dtype=float)
    n = len(st)
    fitted = 1 if e_dry is not None else 2
    dof = n - fitted
    nan = math.nan
    if dof < 1:
        why = f"interval not determined: {n} runs, at least {fitted + 1} needed"
        found = {"parameter": intervals.Interval(nan, nan, 0.0, why)}
        return found if e_dry is not None else {**found, "e_dry": found["parameter"]}
    p = np.concatenate(
        [[0.0], np.geomspace(GRID_LOW * st.min(), GRID_HIGH * st.max(), GRID_POINTS)]
    )
    h = shapes(model, st, p)
    see, eh, hh = float(e @ e), h @ e, np.einsum("ij,ij->i", h, h)
    if e_dry is not None:
        a_best = np.full(len(p), e_dry)
    else:
        with np.errstate(invalid="ignore", divide="ignore"):
            a_best = np.clip(np.where(hh > 0, eh / hh, 0.0), 0.0, e_dry_max)
    s_p = see - 2 * a_best * eh + a_best**2 * hh
    s_min = float(np.min(s_p))
    if not s_min > intervals.ROUNDING * see:
        why = "interval not determined: the runs lie on the curve (zero scatter)"
        found = {"parameter": intervals.Interval(nan, nan, 1.0, why)}
        return found if e_dry is not None else {**found, "e_dry": found["parameter"]}
    limit = s_min + s_min / dof * intervals.student_t(level, dof) ** 2
    found = {"parameter": _ends(p, s_p <= limit, "the parameter")}
    if e_dry is None:
        a = np.linspace(0.0, e_dry_max, E_DRY_POINTS)
        s_a = np.min(see - 2 * a[:, None] * eh[None, :] + a[:, None] ** 2 * hh[None, :], axis=1)
        found["e_dry"] = _ends(a, s_a <= limit, "e_dry", open_top=False)
    return found


def t_cdf(t: np.ndarray, dof: int) -> np.ndarray:
    """P(T ≤ t) for Student's T with integer ``dof``, elementwise, in the closed form of
    ``intervals.central_t_probability`` (Abramowitz & Stegun 1964, 26.7.3–26.7.4)."""
    t = np.asarray(t, dtype=float)
    theta = np.arctan(np.abs(t) / math.sqrt(dof))
    c2 = np.cos(theta) ** 2
    if dof % 2:  # odd
        total = np.zeros_like(theta)
        if dof > 1:
            term = np.cos(theta)
            total = term.copy()
            for k in range(3, dof - 1, 2):
                term = term * c2 * (k - 1) / k
                total = total + term
        central = 2.0 / math.pi * (theta + np.sin(theta) * total)
    else:
        term = np.ones_like(theta)
        total = term.copy()
        for k in range(2, dof - 1, 2):
            term = term * c2 * (k - 1) / k
            total = total + term
        central = np.sin(theta) * total
    return 0.5 + 0.5 * np.sign(t) * central


def t_quantiles(q: np.ndarray, dof: int) -> np.ndarray:
    """Student's t quantiles at probabilities ``q`` (0 < q < 1), by bisection of ``t_cdf``."""
    q = np.asarray(q, dtype=float)
    low, high = np.full(q.shape, -1.0), np.full(q.shape, 1.0)
    while np.any(t_cdf(low, dof) > q):
        low = np.where(t_cdf(low, dof) > q, 2.0 * low, low)
    while np.any(t_cdf(high, dof) < q):
        high = np.where(t_cdf(high, dof) < q, 2.0 * high, high)
    for _ in range(80):
        mid = 0.5 * (low + high)
        below = t_cdf(mid, dof) < q
        low, high = np.where(below, mid, low), np.where(below, high, mid)
    return 0.5 * (low + high)


def dry_nodes(dry: np.ndarray, e_dry_max: float = 1.0, nodes: int = DRY_NODES) -> np.ndarray:
    """``nodes`` equal-probability quantiles of the true e_dry's law given the dry runs,
    ē_dry + s_dry/√m · t_(m−1) (m ≥ 2), within [0, ``e_dry_max``]."""
    values = np.asarray(dry, dtype=float)
    m = len(values)
    spread = float(np.std(values, ddof=1)) / math.sqrt(m)
    q = (np.arange(nodes) + 0.5) / nodes
    return np.clip(float(np.mean(values)) + spread * t_quantiles(q, m - 1), 0.0, e_dry_max)


def mixed_intervals(
    model: str,
    st: np.ndarray,
    e: np.ndarray,
    dry: np.ndarray,
    *,
    level: float = intervals.LEVEL,
    e_dry_max: float = 1.0,
) -> dict[str, intervals.Interval]:
    """{"parameter": …}: with e_dry the mean of the ``dry`` runs (≥ 2), the parameter's
    interval from its F-calibrated confidence distribution at each node of e_dry's law
    (``dry_nodes``), averaged: the points where the average reaches (1 ∓ level)/2."""
    st, e = np.asarray(st, dtype=float), np.asarray(e, dtype=float)
    n, nan = len(st), math.nan
    dof = n - 1
    if dof < 1:
        why = f"interval not determined: {n} runs, at least 2 needed"
        return {"parameter": intervals.Interval(nan, nan, 0.0, why)}
    p = np.concatenate(
        [[0.0], np.geomspace(GRID_LOW * st.min(), GRID_HIGH * st.max(), GRID_POINTS)]
    )
    h = shapes(model, st, p)
    see, eh, hh = float(e @ e), h @ e, np.einsum("ij,ij->i", h, h)
    a = dry_nodes(dry, e_dry_max)[:, None]
    s_p = see - 2 * a * eh[None, :] + a**2 * hh[None, :]  # (nodes, grid)
    best = np.argmin(s_p, axis=1)
    s_min = s_p[np.arange(len(a)), best][:, None]
    if not np.all(s_min > intervals.ROUNDING * see):
        why = "interval not determined: the runs lie on the curve (zero scatter)"
        return {"parameter": intervals.Interval(nan, nan, 1.0, why)}
    d = (s_p - s_min) / (s_min / dof)
    # the profile's hull on each side of its minimum: r(p) monotone, so the confidence
    # distribution is (as the F interval takes the hull of its set)
    index = np.arange(len(p))[None, :]
    above = index >= best[:, None]
    right = np.maximum.accumulate(np.where(above, d, 0.0), axis=1)
    left = np.maximum.accumulate(np.where(index <= best[:, None], d, 0.0)[:, ::-1], axis=1)
    r = np.where(above, np.sqrt(right), -np.sqrt(left[:, ::-1]))
    confidence = t_cdf(r, dof).mean(axis=0)  # nondecreasing in p
    tail = 0.5 * (1.0 - level)
    if not confidence[-1] >= 1.0 - tail:
        why = "interval not determined: these runs do not bound the parameter from above"
        return {"parameter": intervals.Interval(nan, nan, 1.0, why)}
    low = float(p[np.flatnonzero(confidence >= tail)[0]])
    high = float(p[np.flatnonzero(confidence <= 1.0 - tail)[-1]])
    if not high > low:
        why = "interval not determined: degenerate profile"
        return {"parameter": intervals.Interval(nan, nan, 1.0, why)}
    return {"parameter": intervals.Interval(low, high, 1.0)}


def _ends(grid: np.ndarray, inside: np.ndarray, what: str, open_top: bool = True):
    """The interval of the grid points ``inside`` (their hull), or refused where it reaches
    the grid's open end (not bounded by the runs) or is empty."""
    nan = math.nan
    where = np.flatnonzero(inside)
    if where.size == 0:
        return intervals.Interval(nan, nan, 0.0, "interval not determined: empty profile set")
    low, high = int(where[0]), int(where[-1])
    if open_top and high == len(grid) - 1:
        return intervals.Interval(
            nan, nan, 1.0, f"interval not determined: these runs do not bound {what} from above"
        )
    if not grid[high] > grid[low]:
        return intervals.Interval(nan, nan, 1.0, "interval not determined: degenerate profile")
    return intervals.Interval(float(grid[low]), float(grid[high]), 1.0)


#: With the runs' speeds' u stated, e_dry's profile interval is refused from this many runs:
#: it covered 0.93 at 5 runs but 0.895 at 10 and 0.915 at 19 (200 sets, 4 % speed u): the
#: errors in St_n (∝ v_N,in) are not in the profile (the Bayesian option models them).
STATED_E_DRY_FROM = 10


def into_row(
    row: dict,
    model: str,
    st: np.ndarray,
    e: np.ndarray,
    fixed: bool,
    stated: tuple | None,
    dry: np.ndarray | None,
    minimum: int,
) -> None:
    """The restitution fit's small-n intervals into ``row`` (its ``parameter_low``/``_high``,
    ``e_dry_low``/``_high``, ``interval_method``; ``interval_reason`` for what is refused,
    the bootstrap's ``minimum`` of runs and the measured reason)."""
    too_few = intervals.too_few(len(st), minimum)
    mixed = fixed and dry is not None and len(dry) >= 2
    if mixed:  # e_dry's own uncertainty integrated (issue 36)
        found = mixed_intervals(model, st, e, np.asarray(dry, dtype=float))
    else:
        found = profile_intervals(model, st, e, row["e_dry"] if fixed else None)
    if stated is not None and not fixed and len(st) >= STATED_E_DRY_FROM:
        found["e_dry"] = intervals.Interval(
            math.nan,
            math.nan,
            0.0,
            f"interval not determined: with the speeds' stated u its profile likelihood "
            f"covered 0.895 at 10 runs (200 sets; errors in St_n are not in it; the Bayesian "
            f"option models them) and the bootstrap needs more ({too_few})",
        )
    reasons = []
    for name, got in found.items():
        row[f"{name}_low"], row[f"{name}_high"] = got.low, got.high
        if got.reason:
            what = row.get("parameter_name", name) if name == "parameter" else name
            reasons.append(f"{what}: {got.reason}")
    if any(not got.reason for got in found.values()):
        said = MIXED.format(nodes=DRY_NODES) if mixed else FIXED if fixed else ""
        row["interval_method"] = METHOD.format(runs=minimum) + said
        row["bootstrap_resamples"] = 0  # no resamples drawn: the record says so
        row["bootstrap_rule"] = f"no resamples: the profile likelihood below {minimum} runs"
        if mixed:
            row["e_dry_source"] = row.get("e_dry_source", "").replace(
                "redrawn in the bootstrap", "its t-law integrated in the profile likelihood"
            )
    else:
        reasons.append(too_few)
    row["interval_reason"] = "; ".join(reasons)
