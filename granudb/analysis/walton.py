"""The fitting core of Walton's three-parameter model with model selection and a bootstrap
(Joseph & Hunt 2004 §2, (2.6)–(2.10); docs/physics.md §5, §9, §14).

Why this shape. Runs are folded by the sign of v_T,in first (the model is mirror-symmetric:
a run with v_T,in < 0 has Ψ_in and Ψ_out negated), then sorted by the folded Ψ_in = x. Three
models compete:

- ``sticking``: every run on Ψ_out = −βΨ_in (one line through the origin);
- ``sliding``: every run on Ψ_out = Ψ_in − μ_f c_i with c_i = (1+e_i) B_i (slope one);
- ``split``: runs [0, k) stick and [k, n) slide, k chosen by least squares.

The lines are fitted by least squares within Walton's bounds −1 ≤ β ≤ 1 (Maw, Barber &
Fawcett 1976; Walton 1993: β = −1 is a smooth sphere, β = 1 a perfectly rough one) and
μ_f ≥ 0. A sticking line of *negative* β (the contact point keeps part of its speed) is a
line through the origin of slope −β > 0, and sliding runs whose μ_f varies with speed
(lubricated runs) lie near such a line too: they are a line of slope < 1 that misses the
origin, or a cloud whose best line through the origin has a positive slope. So a sticking
line with β < 0 is refused (that model's BIC set to infinity) unless it is a line through
the origin that describes its runs: refused when a free line y = a + bx fits them better
by a likelihood ratio n ln(S₀/S₁) above ``ORIGIN_TEST`` (χ²₁ at 0.999), or when it leaves
more than ``UNEXPLAINED_MAX`` of ΣΨ_out² unexplained (lubricated sliding runs leave 0.19 to
0.37; sticking runs with β = −0.15 and scatter 0.01 leave 0.01 to 0.03, with scatter 0.03
0.07 to 0.25: a stated prior that negative β needs clean data). A line of β ≥ 0 cannot
mimic the sliding line (its Ψ_out ≤ 0) and is never tested. Each model's residual sum of squares S
gives, with a common Gaussian scatter, the Bayesian information criterion
BIC = n ln(S/n) + p ln n with p = 2 (sticking: β, σ), 2 (sliding: μ_f, σ) and 4
(split: β, μ_f, the split point k, σ). BIC rather than AIC because its
penalty grows with n, so a split carved out of one line by chance loses at every n (AIC's
constant penalty lets the best of n−4 chance splits win too often). The smallest BIC wins;
a tie goes to the simpler model.

Every sum is a prefix (sticking line) or suffix (sliding line) cumulative sum over the sorted
runs, so all splits cost O(n). ``decide`` takes integer weights on the sorted runs (ones for
the fit itself); the bootstrap (``granudb.analysis.walton_bootstrap``) draws runs with
replacement as such weights and finds the same minimum from block sums, so each resample
re-decides the model and the split at a fraction of ``decide``'s cost.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: A line with fewer runs than this gives no parameter (its slope or intercept would be
#: fitted to one or two points: no honest interval).
MIN_RUNS_FOR_PARAMETER = 3
#: Each line of a split holds at least this many distinct runs (two may decide which runs
#: slide, but give no parameter: see MIN_RUNS_FOR_PARAMETER).
MIN_RUNS_PER_LINE = 2
MODELS = ("sticking", "sliding", "split")
PARAMETER_COUNT = {"sticking": 2, "sliding": 2, "split": 4}
#: Relative floor on a residual sum of squares (exact synthetic data would give ln 0). It
#: sits above the rounding of sums over n runs (~1e-16 √n of Σy²), so that residuals at the
#: level of rounding compare as equal, whatever order the sums were added in.
SSE_FLOOR = 1e-12
#: Walton's range of the tangential restitution β.
BETA_BOUNDS = (-1.0, 1.0)
#: A sticking line of β < 0 is refused when n ln(S_origin/S_free) exceeds this: the 0.999
#: point of χ² with one degree of freedom (the free line's intercept).
ORIGIN_TEST = 10.83
#: A sticking line of β < 0 is refused when S/ΣΨ_out² of its runs exceeds this.
UNEXPLAINED_MAX = 0.1


def fold(psi_in: np.ndarray, psi_out: np.ndarray, v_t_in: np.ndarray) -> tuple:
    """Ψ_in and Ψ_out negated where v_T,in < 0, so every run has Ψ_in ≥ 0 (mirror symmetry)."""
    sign = np.where(np.asarray(v_t_in, dtype=float) < 0, -1.0, 1.0)
    return sign * np.asarray(psi_in, dtype=float), sign * np.asarray(psi_out, dtype=float)


@dataclass(frozen=True)
class Decision:
    """One fit (or one block of resamples): arrays over resamples, shape (m,)."""

    model: np.ndarray  # index into MODELS
    split: np.ndarray  # k: runs [0, k) stick
    beta: np.ndarray  # NaN where the chosen model has no sticking line of ≥ 3 runs
    friction: np.ndarray  # NaN where the chosen model has no sliding line of ≥ 3 runs
    restitution: np.ndarray  # weighted mean e
    bic: np.ndarray  # shape (m, 3): BIC of sticking, sliding, split
    beta_se: np.ndarray  # least-squares standard error of β on its line (NaN as β)
    friction_se: np.ndarray  # of μ_f on its line
    restitution_se: np.ndarray  # of ē: s/√n


def lines(sxx, sxy, syy, tcc, tdc, tdd) -> tuple:
    """(S_stick, S_slide, β, μ_f) of each line's bounded least squares from its sums: the
    sticking line Ψ_out = −βΨ_in (sums of x², xy, y²) and the sliding line
    d = Ψ_in − Ψ_out = μ_f c (sums of c², dc, d²)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        beta = np.clip(np.where(sxx > 0, -sxy / sxx, 0.0), *BETA_BOUNDS)
        friction = np.maximum(np.where(tcc > 0, tdc / tcc, 0.0), 0.0)
    # S(β) = Σy² + 2βΣxy + β²Σx² at the bounded β; S(μ) = Σd² − 2μΣdc + μ²Σc²
    stick = syy + 2 * beta * sxy + beta**2 * sxx
    slide = tdd - 2 * friction * tdc + friction**2 * tcc
    return stick, slide, beta, friction


def misses_origin(sums: tuple, beta: np.ndarray, stick: np.ndarray, scale: np.ndarray):
    """True where a sticking line of β < 0 is refused (see ``ORIGIN_TEST``): ``sums`` are
    (count, Σx, Σy, Σx², Σxy, Σy²) of its runs, ``stick`` its residual sum of squares."""
    count, sx, sy, sxx, sxy, syy = sums
    with np.errstate(invalid="ignore", divide="ignore"):
        cxx, cxy = sxx - sx * sx / count, sxy - sx * sy / count
        free = syy - sy * sy / count - np.where(cxx > 0, cxy * cxy / cxx, 0.0)
        ratio = count * np.log(np.maximum(stick, scale) / np.maximum(free, scale))
    unexplained = stick > UNEXPLAINED_MAX * syy
    return (beta < 0) & (count >= MIN_RUNS_FOR_PARAMETER) & ((ratio > ORIGIN_TEST) | unexplained)


def standard_error(
    sse: np.ndarray | float, count: np.ndarray | int, sum_squares: np.ndarray | float
) -> np.ndarray:
    """√(S/(n−1)/Σu²): the least-squares standard error of a one-parameter line through the
    origin (NaN with fewer than two runs or no spread)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        value = np.sqrt(np.maximum(sse, 0.0) / (count - 1) / sum_squares)
    return np.where((count > 1) & (sum_squares > 0), value, np.nan)


def _prefix(weights: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Σ_{j<k} w_j v_j for k = 0..n, shape (m, n+1)."""
    out = np.zeros((weights.shape[0], weights.shape[1] + 1))
    np.cumsum(weights * values, axis=1, out=out[:, 1:])
    return out


def _dot(w: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Σ_j w_ij v_j, or Σ_j w_ij v_ij when ``values`` has a row per resample."""
    return w @ values if values.ndim == 1 else np.einsum("ij,ij->i", w, values)


def decide(weights: np.ndarray, x: np.ndarray, y: np.ndarray, c: np.ndarray, e: np.ndarray):
    """Choose the model, the split and the parameters for each row of ``weights``.

    ``x`` (sorted ascending), ``y``, ``c`` = (1+e)B and ``e`` are per run, shape (n,), or
    per resample and run, shape (m, n), each row sorted by its own x (the bootstrap with
    the runs' stated uncertainties, ``walton_bootstrap.perturbed_batches``); ``weights``
    (m, n) counts how often each run is drawn (ones for the fit itself).
    """
    w = np.asarray(weights, dtype=float)
    m, n = w.shape
    d = x - y
    sxx, sxy, syy = _prefix(w, x * x), _prefix(w, x * y), _prefix(w, y * y)
    scc, sdc, sdd = _prefix(w, c * c), _prefix(w, d * c), _prefix(w, d * d)
    count = _prefix(w, np.ones(n))
    distinct = _prefix((w > 0).astype(float), np.ones(n))
    tcc, tdc, tdd = scc[:, -1:] - scc, sdc[:, -1:] - sdc, sdd[:, -1:] - sdd
    stick, slide, beta_all, friction_all = lines(sxx, sxy, syy, tcc, tdc, tdd)
    total = np.maximum(stick + slide, 0.0)
    runs = count[:, -1]
    scale = np.maximum(syy[:, -1] + sdd[:, -1], 1e-300) * SSE_FLOOR
    k = np.arange(n + 1)
    inner = (k > 0) & (k < n)
    allowed = (
        inner
        & (distinct >= MIN_RUNS_PER_LINE)
        & ((distinct[:, -1:] - distinct) >= MIN_RUNS_PER_LINE)
    )
    split = np.argmin(np.where(allowed, total, np.inf), axis=1)
    rows = np.arange(m)
    has_split = allowed[rows, split]
    sse = np.stack([total[:, n], total[:, 0], total[rows, split]], axis=1)
    penalty = np.array([PARAMETER_COUNT[name] for name in MODELS]) * np.log(runs)[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        bic = runs[:, None] * np.log(np.maximum(sse, scale[:, None]) / runs[:, None]) + penalty
    bic[:, 2] = np.where(has_split, bic[:, 2], np.inf)
    sx, sy = _prefix(w, x), _prefix(w, y)
    for column, at in ((0, np.full(m, n)), (2, split)):
        sums = tuple(s[rows, at] for s in (count, sx, sy, sxx, sxy, syy))
        refused = misses_origin(sums, beta_all[rows, at], stick[rows, at], scale)
        bic[refused, column] = np.inf
    model = np.argmin(bic, axis=1)  # argmin keeps the first (simpler) model on a tie
    k_chosen = np.select([model == 0, model == 1], [n, 0], split)
    n_stick = distinct[rows, k_chosen]
    n_slide = distinct[:, -1] - n_stick
    beta = beta_all[rows, k_chosen]
    friction = friction_all[rows, k_chosen]
    restitution = _dot(w, e) / runs
    beta_se = standard_error(stick[rows, k_chosen], count[rows, k_chosen], sxx[rows, k_chosen])
    slid = runs - count[rows, k_chosen]
    friction_se = standard_error(slide[rows, k_chosen], slid, tcc[rows, k_chosen])
    spread = np.maximum(_dot(w, e * e) - runs * restitution**2, 0.0)
    restitution_se = standard_error(spread, runs, runs)
    lines_ = (beta, beta_se, friction, friction_se)
    return decision(model, k_chosen, bic, lines_, (n_stick, n_slide), (restitution, restitution_se))


def decision(model, split, bic, line: tuple, distinct: tuple, mean: tuple) -> Decision:
    """The Decision, β (and its standard error) NaN where the sticking line has fewer than
    MIN_RUNS_FOR_PARAMETER distinct runs, μ_f where the sliding line has: ``line`` is
    (β, se, μ_f, se), ``distinct`` (sticking, sliding) distinct runs, ``mean`` (ē, se)."""
    beta, beta_se, friction, friction_se = line
    ok_beta = distinct[0] >= MIN_RUNS_FOR_PARAMETER
    ok_friction = distinct[1] >= MIN_RUNS_FOR_PARAMETER
    return Decision(
        model,
        split,
        np.where(ok_beta, beta, np.nan),
        np.where(ok_friction, friction, np.nan),
        mean[0],
        bic,
        np.where(ok_beta, beta_se, np.nan),
        np.where(ok_friction, friction_se, np.nan),
        mean[1],
    )


def percentile_interval(values: np.ndarray, level: float) -> tuple[float, float, float]:
    """(low, high, fraction determined) of the finite ``values`` at confidence ``level``."""
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return np.nan, np.nan, 0.0
    tail = 50.0 * (1.0 - level)
    low, high = np.percentile(finite, [tail, 100.0 - tail])
    return float(low), float(high), finite.size / values.size


#: A run counted as sliding is moved to the sticking side when sliding on the line of the
#: sliding runs after it would need β above Walton's bound by more than this many standard
#: deviations of that line's prediction (``kinematic_sticking``).
KINEMATIC_MARGIN = 2.0


def kinematic_sticking(x: np.ndarray, y: np.ndarray, c: np.ndarray, k: int) -> tuple[int, str]:
    """(runs of [k, n) that stick by their own kinematics, the reason in words).

    A run on the sliding line has Ψ_out = Ψ_in − μ_f c; sliding is possible only while the
    rebound does not reverse the contact point faster than it came, Ψ_out ≥ −Ψ_in, i.e. β =
    μ_f c/Ψ_in − 1 ≤ 1 (Walton's bound), so a run with Ψ_in < μ_f c/2 cannot slide on a line
    of that μ_f. The runs counted as sliding (sorted by Ψ_in, from ``k``) are taken in order:
    the first is moved to the sticking side when the line fitted to the sliding runs after
    it predicts for it a Ψ_out below −Ψ_in (β > 1) by more than ``KINEMATIC_MARGIN``
    standard deviations of that prediction (from the scatter of those runs, when there are
    two or more), and its own β = −Ψ_out/Ψ_in lies in Walton's
    [−1, 1] (Ψ_out consistent with a sticking line). Its single-run μ_f, (1+β)Ψ_in/c, is
    then a lower bound, never a value (docs/physics.md §14). Stops at the first run that
    may slide (a sticking run has a smaller Ψ_in than every sliding run)."""
    n = len(x)
    moved, said = 0, []
    while n - (k + moved) >= 2:
        i = k + moved
        rest = slice(i + 1, n)
        cc = float(np.sum(c[rest] ** 2))
        mu = max(float(np.sum((x[rest] - y[rest]) * c[rest])) / cc, 0.0)
        m = n - i - 1
        residual = (x[rest] - y[rest]) - mu * c[rest]
        spread = math.sqrt(float(np.sum(residual**2)) / (m - 1)) if m >= 2 else 0.0
        predicted = spread * math.sqrt(1.0 + c[i] ** 2 / cc)
        # on the line of the others, the run would leave with Ψ_out = Ψ_in − μ c < −Ψ_in
        beyond = (mu * c[i] - 2.0 * x[i]) - KINEMATIC_MARGIN * predicted
        beta_i = -y[i] / x[i] if x[i] > 0 else math.nan
        if not (beyond > 0 and BETA_BOUNDS[0] <= beta_i <= BETA_BOUNDS[1]):
            break
        said.append(
            f"the run at Ψ_in {x[i]:.3g} sticks by its own kinematics (β {beta_i:+.2f}, "
            f"single-run μ_f {(1 + beta_i) * x[i] / c[i]:.3g}, a lower bound): on the sliding "
            f"line of the {m} runs after it (μ_f {mu:.3g}) it would need β > 1"
        )
        moved += 1
    return moved, "; ".join(said)


def at_split(x: np.ndarray, y: np.ndarray, c: np.ndarray, e: np.ndarray, k: int) -> Decision:
    """The Decision of a split held at ``k`` (runs [0, k) stick, [k, n) slide), as
    ``decide`` makes it for its chosen k: the model ``split`` (``sticking`` when k = n,
    ``sliding`` when k = 0), β and μ_f from lines of at least MIN_RUNS_FOR_PARAMETER runs,
    BIC as NaN (no choice was made here)."""
    n = len(x)
    d = x - y
    sxx, sxy, syy = (float(np.sum(v[:k])) for v in (x * x, x * y, y * y))
    tcc, tdc, tdd = (float(np.sum(v[k:])) for v in (c * c, d * c, d * d))
    stick, slide, beta, friction = lines(*(np.array([v]) for v in (sxx, sxy, syy, tcc, tdc, tdd)))
    beta_se = standard_error(stick, np.array([k]), np.array([sxx]))
    friction_se = standard_error(slide, np.array([n - k]), np.array([tcc]))
    model = np.array([0 if k == n else 1 if k == 0 else 2])
    mean = np.array([float(np.mean(e))])
    spread = np.array([float(np.sum((e - mean) ** 2))])
    mean_se = standard_error(spread, np.array([n]), np.array([n]))
    line = (beta, beta_se, friction, friction_se)
    bic = np.full((1, len(MODELS)), np.nan)
    return decision(
        model, np.array([k]), bic, line, (np.array([k]), np.array([n - k])), (mean, mean_se)
    )


def kinematic_sliding(x: np.ndarray, y: np.ndarray, c: np.ndarray, beta: float) -> tuple[int, str]:
    """(runs that slide by their kinematics although the fit took every run as sticking on a
    line of ``beta`` < 0, the reason in words): 0 and '' where none do.

    On a sticking line of β < 0 every run keeps the direction of its contact point (Ψ_out =
    −βΨ_in > 0), and in Walton's model no run lies below the sticking line (Ψ_out =
    max(−βΨ_in, Ψ_in − μ_f c)). A first run (smallest Ψ_in) that reverses (Ψ_out < 0, its
    own β = −Ψ_out/Ψ_in in (0, 1]) cannot be on that line; the runs after it are then on the
    other branch, the sliding line of slope one (they keep their direction, and sticking
    runs have a smaller Ψ_in than every sliding run). Sliding runs of a μ_f that varies, or
    few runs, can mimic a line through the origin of slope −β > 0 (the ``misses_origin``
    test has little power at few runs); so where the split with that one run sticking and
    the rest sliding has the smaller BIC (p = 4 against 2), the runs after the first are
    taken as sliding. The sticking line then has one run: no β, and too few runs to choose
    a model (the caller says "not determined")."""
    n = len(x)
    if not (beta < 0 and n >= 1 + MIN_RUNS_PER_LINE and x[0] > 0 and y[0] < 0):
        return 0, ""
    beta_0 = -y[0] / x[0]
    if not beta_0 <= BETA_BOUNDS[1]:
        return 0, ""
    d, cc = x[1:] - y[1:], c[1:]
    friction = max(float(d @ cc) / float(cc @ cc), 0.0)
    slide = float(np.sum((d - friction * cc) ** 2))
    stick = float(np.sum((y + beta * x) ** 2))
    scale = max(float(y @ y + (x - y) @ (x - y)), 1e-300) * SSE_FLOOR
    bic_stick = n * math.log(max(stick, scale) / n) + PARAMETER_COUNT["sticking"] * math.log(n)
    bic_split = n * math.log(max(slide, scale) / n) + PARAMETER_COUNT["split"] * math.log(n)
    if not bic_split < bic_stick:
        return 0, ""
    return n - 1, (
        f"the run at Ψ_in {x[0]:.3g} reverses (β {beta_0:+.2f}) and cannot be on the sticking "
        f"line of β {beta:+.2f} (whose runs keep their direction); the {n - 1} runs after it "
        f"lie on a sliding line (μ_f {friction:.3g}, BIC {bic_split:.4g} against the "
        f"sticking line's {bic_stick:.4g})"
    )
