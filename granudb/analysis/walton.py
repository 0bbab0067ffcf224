"""The fitting core of Walton's three-parameter model with model selection and a bootstrap
(Joseph & Hunt 2004 §2, (2.6)–(2.10); docs/physics.md §5, §9, §14).

Why this shape. Runs are folded by the sign of v_T,in first (the model is mirror-symmetric:
a run with v_T,in < 0 has Ψ_in and Ψ_out negated), then sorted by the folded Ψ_in = x. Three
models compete:

- ``sticking``: every run on Ψ_out = −βΨ_in (one line through the origin);
- ``sliding``: every run on Ψ_out = Ψ_in − μ_f c_i with c_i = (1+e_i) B_i (slope one);
- ``split``: runs [0, k) stick and [k, n) slide, k chosen by least squares.

The lines are fitted by least squares within the physical bounds 0 ≤ β ≤ 1 (a run that
sticks has its contact point stopped or reversed: β < 0 means it slipped, Joseph & Hunt
(2.8)) and μ_f ≥ 0; without them a "sticking" line of negative β fits sliding runs whose μ_f
varies with speed (lubricated runs) and wins. Each model's residual sum of squares S
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


def _prefix(weights: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Σ_{j<k} w_j v_j for k = 0..n, shape (m, n+1)."""
    out = np.zeros((weights.shape[0], weights.shape[1] + 1))
    np.cumsum(weights * values, axis=1, out=out[:, 1:])
    return out


def decide(weights: np.ndarray, x: np.ndarray, y: np.ndarray, c: np.ndarray, e: np.ndarray):
    """Choose the model, the split and the parameters for each row of ``weights``.

    ``x`` (sorted ascending), ``y``, ``c`` = (1+e)B and ``e`` are per run; ``weights`` (m, n)
    counts how often each run is drawn (ones for the fit itself).
    """
    w = np.asarray(weights, dtype=float)
    m, n = w.shape
    d = x - y
    sxx, sxy, syy = _prefix(w, x * x), _prefix(w, x * y), _prefix(w, y * y)
    scc, sdc, sdd = _prefix(w, c * c), _prefix(w, d * c), _prefix(w, d * d)
    count = _prefix(w, np.ones(n))
    distinct = _prefix((w > 0).astype(float), np.ones(n))
    tcc, tdc, tdd = scc[:, -1:] - scc, sdc[:, -1:] - sdc, sdd[:, -1:] - sdd
    with np.errstate(invalid="ignore", divide="ignore"):
        beta_all = np.clip(np.where(sxx > 0, -sxy / sxx, 0.0), 0.0, 1.0)
        friction_all = np.maximum(np.where(tcc > 0, tdc / tcc, 0.0), 0.0)
    # S(β) = Σy² + 2βΣxy + β²Σx² at the bounded β; S(μ) = Σd² − 2μΣdc + μ²Σc²
    stick = syy + 2 * beta_all * sxy + beta_all**2 * sxx
    slide = tdd - 2 * friction_all * tdc + friction_all**2 * tcc
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
    model = np.argmin(bic, axis=1)  # argmin keeps the first (simpler) model on a tie
    k_chosen = np.select([model == 0, model == 1], [n, 0], split)
    n_stick = distinct[rows, k_chosen]
    n_slide = distinct[:, -1] - n_stick
    beta = beta_all[rows, k_chosen]
    friction = friction_all[rows, k_chosen]
    restitution = (w @ e) / runs
    beta = np.where(n_stick >= MIN_RUNS_FOR_PARAMETER, beta, np.nan)
    friction = np.where(n_slide >= MIN_RUNS_FOR_PARAMETER, friction, np.nan)
    return Decision(model, k_chosen, beta, friction, restitution, bic)


def percentile_interval(values: np.ndarray, level: float) -> tuple[float, float, float]:
    """(low, high, fraction determined) of the finite ``values`` at confidence ``level``."""
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return np.nan, np.nan, 0.0
    tail = 50.0 * (1.0 - level)
    low, high = np.percentile(finite, [tail, 100.0 - tail])
    return float(low), float(high), finite.size / values.size
