"""The large-n interval: θ̂ ± z σ̂ with the sandwich standard error, in place of the
bootstrap where a group is large enough for it to hold (issue 36; docs/intervals.md,
"Which method at which size").

Why. The Walton and gap-viscosity fits' parameters are least-squares slopes of lines
through the origin (β on the sticking line, μ_f on the sliding line, q = μ₀^{2/7} on
μ_f = q g) and a mean (ē): for a fixed split each is a weighted mean of per-run values, so
the central limit theorem makes θ̂ normal around its limit, and the heteroscedasticity-
consistent (sandwich, HC1; White 1980, MacKinnon & White 1985) standard error is consistent
whatever the scatter's shape. At large n the split point is fixed to within a few runs
(a change point is estimated at rate 1/n, faster than the slopes' 1/√n), so holding it adds
nothing to first order. The bootstrap's draws cost O(resamples × n); this costs O(n).
Measured coverage (benchmarks/fit_coverage.py, --asymptotic): docs/intervals.md.

Where it is used: a group of at least ``ASYMPTOTIC_FROM`` runs (the fit's
``asymptotic_from`` argument lowers or raises it) whose resample count was not asked for,
and, for the Walton fit, every line of the chosen model with at least
``ASYMPTOTIC_FROM // 10`` runs. A count asked for always gets the bootstrap.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from statistics import NormalDist
from typing import Any

import numpy as np

from granudb.analysis import intervals
from granudb.analysis import walton as core
from granudb.analysis import walton_bootstrap as resampling

#: Runs in a group from which the asymptotic interval replaces the bootstrap.
ASYMPTOTIC_FROM = 10_000
#: A Walton line needs this share of ``asymptotic_from`` runs (else the bootstrap).
LINE_SHARE = 10
METHOD = (
    "asymptotic normal interval θ̂ ± z·se{of}, se the larger of least squares' and the "
    "sandwich's (HC1), the split held at its estimate (at least {switch:,} runs in the "
    "group: no bootstrap)"
)
#: What the method adds when the runs state a u (the scatter carries it).
STATED = "; the runs' stated u is not redrawn: it is in the per-run values' scatter"
#: Parameter sets drawn from the asymptotic normal law, for a band (``normal_sets``).
SETS = 1000
#: What a band made from ``normal_sets`` is drawn over (the report's captions say it).
BAND_SETS_WORDS = (
    f"{SETS:,} parameter sets drawn from the normal law of its asymptotic interval "
    "(estimate, standard error)"
)


def method(switch: int, stated: bool, of: str = "") -> str:
    """The interval method's words for a switch size ``switch`` (``of``: what θ is, when
    the parameter is a transform of it)."""
    return METHOD.format(switch=switch, of=of) + (STATED if stated else "")


def rule(switch: int) -> str:
    """A fit record's ``bootstrap_rule`` where no bootstrap ran."""
    return f"no resamples: the asymptotic interval from {switch:,} runs in a group"


def uses(n: int, asked: int | None, switch: int) -> bool:
    """Whether a group of ``n`` runs gets the asymptotic interval (no count asked for)."""
    return asked is None and n >= switch


def line_se(a: np.ndarray, residual: np.ndarray) -> float:
    """The standard error of a line through the origin's slope, regressor ``a`` and
    residuals ``residual``: the larger of least squares' √(S/(m−1)/Σa²) and the sandwich
    (HC1) √(m/(m−1) Σ(a r)²)/Σa² (the scatter grows with Ψ where speeds carry a relative u).
    NaN with fewer than two runs."""
    m = len(a)
    if m < 2:
        return math.nan
    saa = float(a @ a)
    if not saa > 0:
        return math.nan
    ls = math.sqrt(float(residual @ residual) / (m - 1) / saa)
    hc1 = math.sqrt(m / (m - 1) * float(np.sum((a * residual) ** 2))) / saa
    return max(ls, hc1)


def interval(
    point: float,
    se: float,
    *,
    bounds: tuple[float, float] = (-math.inf, math.inf),
    level: float = intervals.LEVEL,
) -> intervals.Interval:
    """θ̂ ± z se clipped to ``bounds`` (``determined`` 1); refused as ``t_interval`` is.

    >>> got = interval(0.11, 0.001)
    >>> round(got.low, 5), round(got.high, 5)
    (0.10804, 0.11196)
    """
    nan = math.nan
    if not math.isfinite(point):
        return intervals.Interval(nan, nan, 0.0, "not determined by these runs")
    if not (math.isfinite(se) and se > intervals.ROUNDING * abs(point)):
        return intervals.Interval(nan, nan, 1.0, "interval not determined: zero standard error")
    half = NormalDist().inv_cdf(0.5 + level / 2) * se
    return intervals.Interval(
        float(max(point - half, bounds[0])), float(min(point + half, bounds[1])), 1.0
    )


def walton_errors(x, y, c, e, k: int) -> tuple[float, float, float]:
    """(se β, se μ_f, se ē) of a Walton fit split at ``k`` (runs [0, k) stick): the
    sandwich-or-least-squares standard error of each line (``line_se``) and s/√n."""
    fit = core.at_split(x, y, c, e, k)
    beta, friction = float(fit.beta[0]), float(fit.friction[0])
    beta_se = line_se(x[:k], y[:k] + beta * x[:k]) if math.isfinite(beta) else math.nan
    d = x[k:] - y[k:]
    mu_se = line_se(c[k:], d - friction * c[k:]) if math.isfinite(friction) else math.nan
    return beta_se, mu_se, float(fit.restitution_se[0])


def normal_sets(row: Mapping[str, Any], seed: int, count: int = SETS) -> core.Decision:
    """``count`` parameter sets (β, μ_f, ē) drawn independently from the asymptotic normal
    law of a Walton row (its values and ``_stderr``), seeded: the band of its lines when the
    interval is asymptotic (granudb.analysis.bands)."""
    rng = np.random.default_rng(seed)

    def drawn(name: str, value: str) -> np.ndarray:
        point, se = float(row.get(value, math.nan)), float(row.get(f"{name}_stderr", math.nan))
        if not (math.isfinite(point) and math.isfinite(se)):
            return np.full(count, math.nan)
        return point + se * rng.standard_normal(count)

    beta = np.clip(drawn("rotational_restitution", "rotational_restitution"), *core.BETA_BOUNDS)
    friction = np.maximum(drawn("sliding_friction", "sliding_friction"), 0.0)
    mean = drawn("normal_restitution", "normal_restitution_mean")
    model = core.MODELS.index(row["model"]) if row.get("model") in core.MODELS else -1
    full = np.full(count, math.nan)
    return core.Decision(
        np.full(count, model),
        np.full(count, int(row.get("n_sticking") or 0)),
        beta,
        friction,
        mean,
        np.full((count, len(core.MODELS)), math.nan),
        full,
        full.copy(),
        full.copy(),
    )


#: Perturbed copies of all the runs that estimate the stated u's bias (``stated_shift``).
SHIFT_DRAWS = 16
#: What the method adds when the runs' stated u corrects the interval's centre.
STATED_SHIFT = (
    "; centred on θ̂ − b̂, b̂ the mean shift of θ over {draws} copies of all the runs with "
    "every measured speed perturbed by its stated u (normal), the runs re-sorted and the "
    "model and split re-decided in each; se² plus the copies' variance v (as the perturbed "
    "bootstrap adds it) and b̂'s own variance v/{draws}"
)


#: What the method adds about the value itself where the interval's centre is corrected:
#: the value stays the fit of the runs as measured (as on the bootstrap path, whose pivot
#: corrects the interval and not the value, so a value does not jump at the switch), and
#: b̂ is given so that the corrected estimate θ̂ − b̂ can be read off.
UNCORRECTED_VALUE = (
    "; the value is {value}, the fit of the runs as measured, not corrected (b̂ = {shift}), "
    "so it may lie outside its interval"
)


def shift_words(shift: float | dict[str, float], value: str = "θ̂", of: str = "") -> str:
    """``UNCORRECTED_VALUE`` with b̂ (one number, or one per parameter name; ``of``: what
    it is a shift of, when the value is a transform) and what the ``value`` is.

    >>> shift_words({"k": -0.2198}).split(", so")[0]
    '; the value is θ̂, the fit of the runs as measured, not corrected (b̂ = k -0.2198)'
    >>> shift_words(0.01, value="q̂^(7/2)", of=" in q").split(", the fit")[0]
    '; the value is q̂^(7/2)'
    """
    if isinstance(shift, dict):
        said = ", ".join(f"{name} {value:.4g}" for name, value in shift.items())
    else:
        said = f"{shift:.4g}{of}"
    return UNCORRECTED_VALUE.format(value=value, shift=said)


def stated_method(switch: int, of: str = "") -> str:
    """The method's words when the runs state a u (``stated_shift`` corrects the centre)."""
    return METHOD.format(switch=switch, of=of) + STATED_SHIFT.format(draws=SHIFT_DRAWS)


def stated_se(se: float, spread: float, draws: int = SHIFT_DRAWS) -> float:
    """The standard error with the runs' stated u: √(se² + v + v/draws) (``STATED_SHIFT``)."""
    return math.sqrt(se**2 + spread + spread / draws)


def stated_shift(x, y, e, stated: tuple, point, seed: int, draws: int = SHIFT_DRAWS):
    """(b̂, v) of (β, μ_f, ē), arrays of 3: the bias that the runs' measurement error
    puts into a Walton fit, estimated as the perturbed bootstrap estimates it (its pivot
    centres the interval on θ̂ − b̂): ``draws`` copies of all the runs, every speed drawn
    again from its stated u (``walton_bootstrap.perturbed_runs``), re-sorted and re-decided
    (``walton_bootstrap.decide_blocks``, the block search equal to ``walton.decide``);
    ``point`` the fit's (β̂, μ̂_f, ē) on the runs ``x``, ``y``, ``e``
    (sorted by Ψ_in, ``stated`` as ``walton_bootstrap.stated_inputs`` gives it); b̂ the
    mean of θ_copy − θ̂, v their variance (b̂'s own is v / draws). NaN where fewer than half the
    copies determine θ."""
    b, u = stated
    n = len(x)
    point = np.asarray(point, dtype=float)
    rng = np.random.default_rng(seed)
    found = []
    for _ in range(draws):  # one copy at a time: the block search needs one order
        x_b, y_b, e_b, _f = (a[0] for a in resampling.perturbed_runs(rng, 1, x, y, e, u))
        order = np.argsort(x_b, kind="stable")
        x_b, y_b, e_b = x_b[order], y_b[order], e_b[order]
        runs = resampling.Sorted(x_b, y_b, (1.0 + e_b) * b[order], e_b)
        weights = np.zeros((1, runs.size))
        weights[0, :n] = 1.0
        got = resampling.decide_blocks(runs, weights)
        found.append([got.beta[0], got.friction[0], got.restitution[0]])
    shifts = np.array(found) - point
    shift, spread = np.full(3, math.nan), np.full(3, math.nan)
    for i in range(3):
        ok = np.isfinite(shifts[:, i])
        if ok.sum() >= max(2, draws // 2):
            shift[i] = float(np.mean(shifts[ok, i]))
            spread[i] = float(np.var(shifts[ok, i], ddof=1))
    return shift, spread


# The restitution fit's large-n interval (issue 36): a non-linear least squares e(St_n)
# with e_dry fitted, or held at the dry runs' mean, whose own uncertainty then enters.

#: What a restitution row's ``interval_method`` says when its interval is asymptotic.
RESTITUTION_METHOD = (
    "asymptotic normal interval θ̂ ± t·se of the non-linear least squares (delta method: "
    "se the larger of least squares' (JᵀJ)⁻¹S/(n−p) and the sandwich's (HC1) per parameter, "
    "J the model's Jacobian at the fit; at least {switch:,} runs in the group: no bootstrap)"
)
#: ... when e_dry is the dry runs' mean (its variance carried through the fit).
RESTITUTION_DRY = (
    "; e_dry the mean of {dry} dry runs, its variance s²/{dry} carried into the parameter by "
    "∂θ/∂e_dry = −ΣJ_θJ_e/ΣJ_θ², t on the Welch–Satterthwaite degrees of freedom"
)

#: ... when the runs state a u of their speeds.
RESTITUTION_STATED = (
    "; centred on θ̂ − b̂, b̂ the mean shift of θ over {draws} copies of all the runs with "
    "every measured normal speed perturbed by its stated u (normal), each refitted; se² plus "
    "the copies' covariance × (1 + 1/{draws})"
)


def restitution_method(switch: int, stated: bool, dry: int) -> str:
    """The restitution fit's asymptotic interval's words: ``stated`` u (the perturbed
    copies' shift, ``STATED_SHIFT``), ``dry`` dry runs behind a fixed e_dry (≥ 2)."""
    words = RESTITUTION_METHOD.format(switch=switch)
    if dry >= 2:
        words += RESTITUTION_DRY.format(dry=dry)
    return words + (RESTITUTION_STATED.format(draws=SHIFT_DRAWS) if stated else "")


def nls_covariance(jacobian: np.ndarray, residual: np.ndarray) -> np.ndarray:
    """The covariance of a least-squares fit's parameters, Jacobian ``jacobian`` (n, p) and
    residuals ``residual`` at the fit: the sandwich (HC1) n/(n−p) A⁻¹(Σr²JJᵀ)A⁻¹, A = JᵀJ,
    its diagonal raised to least squares' A⁻¹S/(n−p) where that is larger (the correlation
    the sandwich's). NaN where A is singular or n ≤ p."""
    n, p = jacobian.shape
    columns = [np.ascontiguousarray(jacobian[:, i]) for i in range(p)]
    weighted = [c * residual for c in columns]
    # column by column: p² dot products of length n (a matrix product of an (n, p) array
    # waits on BLAS's threads, tens of ms on a busy machine)
    a = np.array([[float(c @ d) for d in columns] for c in columns])
    meat = np.array([[float(c @ d) for d in weighted] for c in weighted])
    if n <= p or not np.all(np.isfinite(a)) or np.linalg.matrix_rank(a) < p:
        return np.full((p, p), math.nan)
    inverse = np.linalg.inv(a)
    sandwich = inverse @ meat @ inverse * (n / (n - p))
    ls = np.diag(inverse) * float(residual @ residual) / (n - p)
    scale = np.sqrt(np.maximum(ls, np.diag(sandwich)) / np.diag(sandwich))
    scale = np.where(np.isfinite(scale), scale, 1.0)
    return sandwich * np.outer(scale, scale)


def welch_dof(parts: list[tuple[float, float]]) -> float:
    """The Welch–Satterthwaite degrees of freedom of a sum of variances (variance, dof)
    pairs (dof ``math.inf``: known): (Σv)² / Σ v²/ν.

    >>> welch_dof([(1.0, 3), (0.0, math.inf)])
    3.0
    """
    total = sum(v for v, _ in parts)
    denominator = sum(v * v / dof for v, dof in parts if math.isfinite(dof) and v > 0)
    return total * total / denominator if denominator > 0 else math.inf


#: Above these degrees of freedom the normal quantile stands for Student's.
NORMAL_DOF = 1000


def t_interval(
    point: float, se: float, dof: float, *, bounds: tuple[float, float], level: float
) -> intervals.Interval:
    """θ̂ ± t se with t Student's at ``dof`` (rounded down; the normal's above NORMAL_DOF),
    clipped to ``bounds``; refused as ``interval`` refuses."""
    got = interval(point, se, bounds=(-math.inf, math.inf), level=level)
    if got.reason or not dof < NORMAL_DOF:
        return interval(point, se, bounds=bounds, level=level)
    half = intervals.student_t(level, max(1, int(dof))) * se
    return intervals.Interval(
        float(max(point - half, bounds[0])), float(min(point + half, bounds[1])), 1.0
    )
