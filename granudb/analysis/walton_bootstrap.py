"""The Walton-fit bootstrap in O(n) per resample with a small constant (issue 13, issue 17;
docs/physics.md §14).

Why this shape. Each resample draws n runs with replacement (integer weights on the runs,
which are sorted once by the folded Ψ_in) and re-decides the model and the split exactly as
``walton.decide`` does: the same three models, bounds −1 ≤ β ≤ 1 and μ_f ≥ 0, minimum runs
per line, BIC and the tests of a sticking line with β < 0. ``decide`` evaluates the
split's residual sum of squares at every k from
prefix sums of eight series: about thirty passes over a (resamples × runs) array. Here the
same minimum is found from a few passes:

- Runs are cut into blocks of ``BLOCK_RUNS`` consecutive runs (fewer for a small group:
  the power of two ≥ n, at least 8, so that five runs are not padded to 128). The
  weighted sums of the series over each block come from one batched matrix product
  (BLAS), their cumulative sums over blocks give the exact prefix sums at every block
  boundary.
- The sticking line's minimum residual S_stick(k) (over β ∈ [0, 1]) can only grow when a
  run is added, and the sliding line's S_slide(k) (over μ_f ≥ 0) can only shrink when k
  grows. So within a block [K_J, K_J+1], S(k) ≥ S_stick(K_J) + S_slide(K_J+1): a lower bound
  from boundary sums alone. A block whose bound exceeds the best boundary value cannot hold
  the minimum and is skipped; the others (those around the split) are cut into
  sub-blocks of ``FINE_RUNS`` runs, whose boundary sums lower the best value and bound
  their S(k) the same way, and the sub-blocks that remain are evaluated run by run, on
  the six series the two lines' residuals read (the prefix sums of all eleven are
  formed at each resample's chosen k only: where every run slides, as in lubricated
  runs, about a hundred blocks of a 100,000-run group stay near the minimum; the two
  steps cut their cost to a third).
  The minimum found is the minimum of ``decide`` (up to rounding: the sums are added in a
  different order), smallest k on a tie (a run drawn no time changes no sum, so the
  smallest k of such a tie is found from the drawn runs: ``_first_tied``).

The counts are drawn once for a group's fits of the same seed and size (the Walton and
gap-viscosity fits and the restitution fit of the same runs, the bands of their curves:
``shared_counts``), and the fits run with the BLAS on one thread (``one_thread``).

The cost per resample is then the draw itself (integers, counted by np.add.at) plus one pass of
the matrix product, so the number of resamples is bounded by time only for very large
groups: ``resample_count`` states the rule (1000 resamples up to 10,000 runs, then
resamples × runs ≤ 10⁷ per group, never fewer than 200), and every result carries the
count used, the seed and the rule's text.
"""

from __future__ import annotations

import hashlib
from typing import Any

import numpy as np

from granudb.analysis import defaults
from granudb.analysis import walton as core
from granudb.lazy import threadpoolctl
from granudb.vocabulary.terms import uncertainty_column

#: Resamples of the Walton and gap-viscosity bootstraps for groups up to RULE_RUNS runs.
DEFAULT_RESAMPLES = defaults.DEFAULT_RESAMPLES
#: Above this many runs a group gets CELL_BUDGET // n resamples (but ≥ MIN_RESAMPLES).
RULE_RUNS = 10_000
CELL_BUDGET = 10_000_000
MIN_RESAMPLES = 200
RESAMPLE_RULE = (
    f"{DEFAULT_RESAMPLES} resamples up to {RULE_RUNS:,} runs in a group; above, "
    f"{CELL_BUDGET:.0e} / n (never fewer than {MIN_RESAMPLES})"
).replace("1e+07", "10⁷")
#: Runs per block of the boundary sums (the refined blocks are evaluated run by run).
BLOCK_RUNS = 128
#: Resamples × padded runs per batch (bounds memory at a few tens of MB).
BATCH_CELLS = 1 << 21
#: Runs per sub-block: a candidate block's sub-block sums come first, and only the
#: sub-blocks whose lower bound is within the best S found are evaluated run by run.
FINE_RUNS = 16
#: Candidate (sub-)blocks × their runs per refinement chunk.
REFINE_CELLS = 1 << 17
# series: x², xy, y², c², dc, d², e, e², x, y, 1 (d = x − y)
SERIES = 11
XX, XY, YY, CC, DC, DD, EE, E2, X, Y, ONE = range(SERIES)
#: The first LINES series are all that the residual sums of squares read (``_parts``).
LINES = 6


#: What ``interval_method`` adds when the runs' stated speed uncertainties are used.
STATED_METHOD = ", each run's measured normal speeds perturbed by their stated u (normal)"


def stated_speeds(frame: Any) -> tuple[np.ndarray, np.ndarray] | None:
    """Each run's relative standard uncertainty of v_n,in and of v_n,out (0 where none is
    stated), from a collisions frame's ``u_v_n_in_m_s`` and ``u_v_n_out_m_s``; None when
    the frame has neither column."""
    if "u_v_n_in_m_s" not in frame and "u_v_n_out_m_s" not in frame:
        return None
    out = []
    for name in ("v_n_in_m_s", "v_n_out_m_s"):
        u = "u_" + name
        if u not in frame or name not in frame:
            out.append(np.zeros(len(frame)))
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            r = frame[u].to_numpy(dtype=float) / np.abs(frame[name].to_numpy(dtype=float))
        out.append(np.where(np.isfinite(r), r, 0.0))
    return out[0], out[1]


def perturbed(
    rng: np.random.Generator,
    m: int,
    st: np.ndarray,
    e: np.ndarray,
    stated: tuple[np.ndarray, np.ndarray],
) -> tuple[np.ndarray, np.ndarray]:
    """(St_n, e) of ``m`` resamples, shape (m, n), with every run's measured normal speeds
    drawn again from their stated relative uncertainties (``stated_speeds``), normal and
    independent: v_n,in → v_n,in (1 + r_in z₁), v_n,out → v_n,out (1 + r_out z₂), so
    St_n ∝ v_n,in and e = v_n,out / v_n,in move with them. A factor is kept above 1 %
    (a speed never turns round)."""
    r_in, r_out = stated
    z = rng.standard_normal((2, m, len(st)))
    f_in = np.maximum(1.0 + r_in * z[0], 0.01)
    f_out = np.maximum(1.0 + r_out * z[1], 0.01)
    return st * f_in, e * f_out / f_in


#: The per-run quantities of a Walton fit that are ratios of measured speeds over v_N,in
#: (Joseph & Hunt 2004 (2.5), (2.8)): e, Ψ_in, Ψ_out.
RATIOS = ("normal_restitution", "effective_incidence", "effective_rebound")
#: The columns ``stated_walton`` reads: v_N,in (the relative normal speed where the frame
#: has it, else v_n,in), its stated u, and the runs' listed u(e), u(Ψ_in), u(Ψ_out).
STATED_COLUMNS = ["normal_speed_m_s", "v_n_in_m_s", "u_v_n_in_m_s",
                  *(uncertainty_column(q) for q in RATIOS)]  # fmt: skip
#: What the Walton and gap-viscosity fits' interval method adds when runs state u.
STATED_WALTON_METHOD = (
    ", each run's measured speeds (v_N,in, v_n,out, v_T,in, v_T,out) perturbed by their "
    "stated u (normal) and e, Ψ_in, Ψ_out recomputed, runs re-sorted per resample"
)


def stated_walton(group: Any, order: np.ndarray) -> np.ndarray | None:
    """(4, n) for the group's runs at ``order`` (as ``walton_arrays`` sorts them): r =
    u(v_N,in)/v_N,in, then for e, Ψ_in and Ψ_out the standard uncertainty their numerator
    speed gives them over v_N,in, √(u(q)² − (q r)²): the listed u(q) (``ratio_uncertainty``
    of the speeds', spin and diameter included in v_T's) with v_N,in's share taken out, as
    v_N,in is one speed shared by all three. 0 where nothing is stated; None when no run
    states any."""
    if not any(name in group for name in STATED_COLUMNS[2:]):
        return None

    def column(name: str) -> np.ndarray:
        if name not in group:
            return np.full(len(order), np.nan)
        return group[name].to_numpy(dtype=float)[order]

    speed = column("normal_speed_m_s" if "normal_speed_m_s" in group else "v_n_in_m_s")
    with np.errstate(divide="ignore", invalid="ignore"):
        r = column("u_v_n_in_m_s") / np.abs(speed)
        parts = [r] + [
            np.sqrt(np.maximum(column(uncertainty_column(q)) ** 2 - (column(q) * r) ** 2, 0.0))
            for q in RATIOS
        ]
    stated = np.stack([np.where(np.isfinite(p), p, 0.0) for p in parts])
    return stated if stated.any() else None


def stated_inputs(group: Any, arrays: tuple) -> tuple[np.ndarray, np.ndarray] | None:
    """``bootstrap``'s ``stated`` for a group's runs, given their ``walton_arrays``: (the
    runs' Walton factor B, ``stated_walton``), or None when no run states a u."""
    order, factor = arrays[5], arrays[6]
    stated = stated_walton(group, order)
    return None if stated is None else (factor[order], stated)


def perturbed_runs(
    rng: np.random.Generator, m: int, x: np.ndarray, y: np.ndarray, e: np.ndarray, stated
) -> tuple[np.ndarray, ...]:
    """(Ψ_in, Ψ_out, e, f) of ``m`` resamples, shape (m, n), with every run's measured
    speeds drawn again from their stated u (``stated_walton``), normal and independent:
    v_N,in → v_N,in f with f = 1 + r z₀ (kept above 0.01: a speed never turns round), and
    each numerator speed moved by its own u, so q → (q + u_q z)/f for q = e, Ψ_in, Ψ_out:
    the three share the one v_N,in, as they do in the measurement. ``x``, ``y`` are folded
    (Ψ_in ≥ 0); a run whose perturbed Ψ_in turns negative is folded again (v_T,in changed
    sign). e stays ≥ 1 % of its value."""
    r, u_e, u_in, u_out = stated
    z = rng.standard_normal((4, m, len(x)))
    f = np.maximum(1.0 + r * z[0], 0.01)
    x_b, y_b = (x + u_in * z[1]) / f, (y + u_out * z[2]) / f
    e_b = np.maximum(e + u_e * z[3], 0.01 * e) / f
    sign = np.where(x_b < 0, -1.0, 1.0)
    return sign * x_b, sign * y_b, e_b, f


class Perturbed:
    """One batch of perturbed resamples, each row sorted by its own Ψ_in: ``w`` the draw
    counts, ``x``, ``y``, ``c``, ``e``, ``f`` (v_N,in's factor) and ``order`` (the
    original run of each column), all (m, n)."""

    def __init__(self, counts, runs: tuple, factor: np.ndarray, b: np.ndarray) -> None:
        self.order = np.argsort(runs[0], axis=1, kind="stable")
        take = lambda a: np.take_along_axis(a, self.order, axis=1)  # noqa: E731
        self.w, self.x, self.y, self.e, self.f = (take(a) for a in (counts, *runs, factor))
        self.c = (1.0 + self.e) * b[self.order]


def perturbed_batches(x, y, b, e, stated: np.ndarray, resamples: int, seed: int):
    """Yield (Perturbed, decision) per batch: the Walton bootstrap with the runs' stated
    uncertainties (``b`` the runs' Walton factor B). Each resample draws its runs, perturbs
    their speeds (``perturbed_runs``), re-sorts them and re-decides model and split
    (``walton.decide`` on the rows' own order: the block search needs one order for all)."""
    n = len(x)
    rng = np.random.default_rng(seed)
    batch = max(1, BATCH_CELLS // (16 * n))  # decide holds about 16 (m, n) arrays
    for start in range(0, resamples, batch):
        m = min(batch, resamples - start)
        counts = draw_counts(rng, m, n, n)
        x_b, y_b, e_b, f = perturbed_runs(rng, m, x, y, e, stated)
        runs = Perturbed(counts, (x_b, y_b, e_b), f, b)
        yield runs, core.decide(runs.w, runs.x, runs.y, runs.c, runs.e)


def resample_count(n: int) -> int:
    """Resamples for a group of ``n`` runs under ``RESAMPLE_RULE``."""
    if n <= RULE_RUNS:
        return DEFAULT_RESAMPLES
    return max(MIN_RESAMPLES, min(DEFAULT_RESAMPLES, CELL_BUDGET // n))


def _parts(p: np.ndarray, full: np.ndarray) -> tuple[np.ndarray, ...]:
    """(S_stick, S_slide, β, μ_f) at prefix sums ``p`` (..., SERIES) given the totals."""
    rest = full[..., CC] - p[..., CC], full[..., DC] - p[..., DC], full[..., DD] - p[..., DD]
    return core.lines(p[..., XX], p[..., XY], p[..., YY], *rest)


def padding(n: int) -> tuple[int, int, int]:
    """(runs per block, blocks, padded runs) of a group of ``n`` runs: blocks of
    ``BLOCK_RUNS`` runs, fewer for a small group (the power of two ≥ n, at least 8)."""
    block = min(BLOCK_RUNS, max(8, 1 << max(0, n - 1).bit_length()))
    blocks = max(1, -(-n // block))
    return block, blocks, blocks * block


class Sorted:
    """One group's runs (sorted by folded Ψ_in), padded to whole blocks, as series."""

    def __init__(self, x: np.ndarray, y: np.ndarray, c: np.ndarray, e: np.ndarray) -> None:
        self.n = len(x)
        self.block, self.blocks, self.size = padding(self.n)
        size = self.size
        d = x - y
        # (blocks, block, SERIES): each block's runs × series, for the batched
        # product, filled in place (no second copy of a third of a million runs × SERIES)
        series = np.zeros((size, SERIES))
        columns = (x * x, x * y, y * y, c * c, d * c, d * d, e, e * e, x, y, 1.0)
        for i, values in enumerate(columns):
            series[: self.n, i] = values
        self.series = series.reshape(self.blocks, self.block, SERIES)
        #: the series the split search reads, contiguous (a run's six in one cache line)
        self.lines = np.ascontiguousarray(self.series[:, :, :LINES])


def draw_counts(
    rng: np.random.Generator, m: int, n: int, size: int, out: np.ndarray | None = None
) -> np.ndarray:
    """(m, size) float counts of n draws with replacement among n runs (zero padding);
    ``out``: an array (of any type that holds the counts) of at least m rows of ``size``
    whose padding is zero, filled and returned (its first m rows) instead of a new one.

    Row by row, the draws are those of one ``rng.integers(0, n, size=(m, n))`` (the
    generator's values come in order); each row's draws and counts stay in cache (a
    bincount over the whole batch is about twice as slow), and with ``out`` a batch's
    arrays are reused rather than allocated (and their pages touched) again: a sixth less
    time for the bootstrap's largest step, and no (m, n) array of draws."""
    weights = np.zeros((m, size)) if out is None else out[:m]
    counts = np.empty(n, dtype=np.intp)
    for row in weights:
        # np.add.at on an intp array is numpy's fast path: 0.47 ms a row of 100,000
        # draws here against 1.19 ms for np.bincount (which first scans for the range)
        counts.fill(0)
        np.add.at(counts, rng.integers(0, n, size=n), 1)
        row[:n] = counts
    return weights


#: Draw counts kept for reuse, at most this many resamples × runs in all (one byte each):
#: a report fits the same group with the same seed and resample rule several times (the
#: Walton fit, the gap viscosity, the restitution fit on a group of the same runs, the
#: bands of their curves), and drawing 200 × 100,000 runs costs as much as the rest of a
#: fit. A request larger than this is drawn batch by batch and not kept.
SHARED_CELLS = 40_000_000
_shared: dict[tuple[int, int], tuple[np.ndarray, np.random.Generator]] = {}


def shared_counts(seed: int, resamples: int, n: int) -> np.ndarray | None:
    """(resamples, n) counts (uint8, or uint16 if a run is ever drawn 256 times) of the
    draws ``draw_counts(np.random.default_rng(seed), resamples, n, n)`` makes: drawn once per
    (seed, n) and kept (rows drawn for more resamples extend the kept ones, since the draws
    come in order, so a smaller request is a prefix), the least recently used dropped
    beyond ``SHARED_CELLS``. None when ``resamples`` × n alone exceeds it."""
    if resamples * n > SHARED_CELLS:
        return None
    key = (int(seed), int(n))
    kept, rng = _shared.pop(key, (np.zeros((0, n), dtype=np.uint8), None))
    if rng is None:
        rng = np.random.default_rng(seed)
    if len(kept) < resamples:
        more = np.empty((resamples - len(kept), n), dtype=np.uint16)
        draw_counts(rng, len(more), n, n, more)
        small = kept.dtype == np.uint8 and (more.size == 0 or more.max() < 256)
        kept = np.concatenate([kept, more.astype(np.uint8) if small else more])
    _shared[key] = (kept, rng)  # most recently used last
    while sum(a.size for a, _ in _shared.values()) > SHARED_CELLS and len(_shared) > 1:
        del _shared[next(iter(_shared))]
    return kept[:resamples]


def one_thread() -> Any:
    """A context in which the BLAS runs on one thread (a fit's bootstrap runs in it):
    its products are small (20 resamples × 100,000 runs × 4 series: 5 ms on one thread,
    10 ms on two here), and a BLAS that spreads a product over the cores leaves threads
    spinning after it, which on a shared 2-core machine slowed the numpy steps between
    the products (the three fits of ``benchmarks/fit_speed.py`` on 100,000 runs by about
    a third)."""
    return threadpoolctl.threadpool_limits(1, user_api="blas")


def forget_counts() -> None:
    """Drop the counts ``shared_counts`` keeps and the decisions ``batches`` keeps: the
    next fit draws and decides its resamples again."""
    _shared.clear()
    _decided.clear()


def count_batches(seed: int, resamples: int, n: int, size: int, batch: int):
    """Yield float (m, size) counts (zero padding beyond n), ``batch`` resamples at a
    time, of the draws of ``draw_counts(np.random.default_rng(seed), resamples, n, size)``
    (from ``shared_counts`` when they fit in it). The array is reused by the next batch:
    use it before asking for the next."""
    kept = shared_counts(seed, resamples, n)
    rng = np.random.default_rng(seed)
    weights = np.zeros((min(batch, resamples), size))
    for start in range(0, resamples, batch):
        m = min(batch, resamples - start)
        if kept is None:
            yield draw_counts(rng, m, n, size, weights)
        else:
            weights[:m, :n] = kept[start : start + m]
            yield weights[:m]


def _nth_drawn(counts: np.ndarray, need: int) -> np.ndarray:
    """Index of the ``need``-th drawn run (count > 0) of each row (0 for a row with fewer).

    A resample draws about 63 % of the runs, so the ``need``-th drawn run is nearly always
    among the first few: each row is looked at over a short window first, and only the
    (rare) rows without ``need`` drawn runs there over their whole length."""
    window = min(counts.shape[1], 64)
    seen = np.cumsum(counts[:, :window] > 0, axis=1)
    found = np.argmax(seen >= need, axis=1)
    short = np.flatnonzero(seen[:, -1] < need) if window else np.arange(len(counts))
    if short.size:
        found[short] = np.argmax(np.cumsum(counts[short] > 0, axis=1) >= need, axis=1)
    return found


def _allowed(w: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(lo, hi, distinct): splits k ∈ [lo, hi] leave ≥ MIN_RUNS_PER_LINE distinct runs on
    each line; ``distinct`` counts the distinct runs drawn."""
    need = core.MIN_RUNS_PER_LINE
    lo = _nth_drawn(w[:, :n], need) + 1  # the need-th drawn run stays on the sticking line
    hi = n - 1 - _nth_drawn(w[:, n - 1 :: -1], need)  # the need-th last starts the sliding one
    distinct = np.count_nonzero(w[:, :n], axis=1)
    empty = distinct < 2 * need
    lo[empty], hi[empty] = n, 0
    return lo, hi, distinct


def _refine(
    runs: Sorted, w: np.ndarray, start: np.ndarray, full: np.ndarray, pairs: tuple, size: int
) -> tuple[np.ndarray, np.ndarray]:
    """S(k) and k at the best k of each candidate (row, block) pair, blocks of ``size``
    runs with the prefix sums ``start`` (P, LINES) at their first run, from the six
    series of the two lines only (the prefix sums at the chosen k follow in
    ``_at_split``)."""
    rows, blocks, lo, hi = pairs
    local = w.reshape(len(w), -1, size)[rows, blocks]  # (P, size)
    sums = np.empty((len(rows), size + 1, LINES))
    sums[:, 0] = start
    np.multiply(local[:, :, None], runs.lines.reshape(-1, size, LINES)[blocks], out=sums[:, 1:])
    np.cumsum(sums[:, 1:], axis=1, out=sums[:, 1:])
    sums[:, 1:] += sums[:, :1]
    stick, slide, _, _ = _parts(sums, full[rows][:, None, :])
    k = blocks[:, None] * size + np.arange(size + 1)
    inside = (k >= lo[:, None]) & (k <= hi[:, None])
    total = np.where(inside, np.maximum(stick + slide, 0.0), np.inf)
    best = np.argmin(total, axis=1)
    at = np.arange(len(rows))
    return total[at, best], k[at, best]


def _sub_blocks(runs: Sorted, w: np.ndarray, prefix: np.ndarray, full: np.ndarray, pairs: tuple):
    """(prefix sums (P, s + 1, LINES), S (P, s + 1), S's lower bound (P, s)) at the
    boundaries of the s sub-blocks of ``FINE_RUNS`` runs of each candidate (row, block)
    pair: the block's boundary sums plus the sub-blocks' weighted sums."""
    rows, blocks = pairs
    b, fine = runs.block, min(FINE_RUNS, runs.block)
    local = w.reshape(len(w), runs.blocks, b // fine, 1, fine)[rows, blocks]  # (P, s, 1, f)
    parts = np.matmul(local, runs.lines[blocks].reshape(len(rows), b // fine, fine, LINES))
    sums = np.empty((len(rows), b // fine + 1, LINES))
    sums[:, 0] = prefix[rows, blocks, :LINES]
    np.cumsum(parts[:, :, 0], axis=1, out=sums[:, 1:])
    sums[:, 1:] += sums[:, :1]
    stick, slide, _, _ = _parts(sums, full[rows][:, None, :])
    return sums, np.maximum(stick + slide, 0.0), stick[:, :-1] + slide[:, 1:]


def _at_split(runs: Sorted, w: np.ndarray, prefix: np.ndarray, split: np.ndarray) -> np.ndarray:
    """Prefix sums of all series at each row's split k: the block's boundary sums plus
    the weighted series of the block's runs before k."""
    b = runs.block
    block = np.minimum(split // b, runs.blocks - 1)
    rows = np.arange(len(w))
    local = w.reshape(len(w), runs.blocks, b)[rows, block]  # (m, b)
    local = local * (block[:, None] * b + np.arange(b) < split[:, None])
    return prefix[rows, block] + np.einsum("rb,rbs->rs", local, runs.series[block])


def _split(runs: Sorted, w: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> tuple:
    """Exact best split per row: (S at the split, k, prefix sums at k, boundary prefix)."""
    m, b = len(w), runs.block
    blocksums = np.matmul(w.reshape(m, runs.blocks, b).transpose(1, 0, 2), runs.series)
    # summed over blocks in the product's (blocks, m, series) order, contiguous; read
    # as (m, blocks + 1, series)
    prefix = np.zeros((runs.blocks + 1, m, SERIES))
    np.cumsum(blocksums, axis=0, out=prefix[1:])
    prefix = prefix.transpose(1, 0, 2)
    full = prefix[:, -1]
    stick, slide, _, _ = _parts(prefix, full[:, None, :])
    bounds = np.arange(runs.blocks + 1) * b
    inside = (bounds >= lo[:, None]) & (bounds <= hi[:, None])
    best = np.min(np.where(inside, np.maximum(stick + slide, 0.0), np.inf), axis=1)
    lower = stick[:, :-1] + slide[:, 1:]  # S(k) ≥ this within block J
    slack = 1e-9 * np.abs(best) + 1e-300
    keep = (lower <= (best + slack)[:, None]) | ~np.isfinite(best)[:, None]
    keep &= (bounds[1:] >= lo[:, None]) & (bounds[:-1] <= hi[:, None])
    rows, blocks = np.nonzero(keep)
    # the candidate blocks' sub-blocks: their boundaries may lower the best S found, and
    # only the sub-blocks whose bound is within it are evaluated run by run
    fine = min(FINE_RUNS, b)
    per = b // fine
    found = []
    step = max(1, REFINE_CELLS // b)
    for start in range(0, len(rows), step):
        r, j = rows[start : start + step], blocks[start : start + step]
        sums, total, lower = _sub_blocks(runs, w, prefix, full, (r, j))
        k = j[:, None] * b + np.arange(per + 1) * fine
        inside = (k >= lo[r][:, None]) & (k <= hi[r][:, None])
        np.minimum.at(best, r, np.min(np.where(inside, total, np.inf), axis=1))
        found.append((sums, lower))
    sums = np.concatenate([f[0] for f in found]) if found else np.zeros((0, per + 1, LINES))
    lower = np.concatenate([f[1] for f in found]) if found else np.zeros((0, per))
    slack = 1e-9 * np.abs(best) + 1e-300
    k = (blocks * b)[:, None] + np.arange(per + 1) * fine
    keep = (lower <= (best + slack)[rows][:, None]) | ~np.isfinite(best)[rows][:, None]
    keep &= (k[:, 1:] >= lo[rows][:, None]) & (k[:, :-1] <= hi[rows][:, None])
    pair, sub = np.nonzero(keep)
    rows, blocks, sums = rows[pair], blocks[pair] * per + sub, sums[pair, sub]
    value = np.full(m, np.inf)
    split = np.zeros(m, dtype=int)
    step = max(1, REFINE_CELLS // fine)
    for start in range(0, len(rows), step):
        r, j = rows[start : start + step], blocks[start : start + step]
        pairs = (r, j, lo[r], hi[r])
        total, k = _refine(runs, w, sums[start : start + step], full, pairs, fine)
        order = np.lexsort((k, total, r))  # per row: smallest S, then smallest k
        first = order[np.r_[True, r[order][1:] != r[order][:-1]]]
        better = (total[first] < value[r[first]]) | (
            (total[first] == value[r[first]]) & (k[first] < split[r[first]])
        )
        chosen = first[better]
        value[r[chosen]], split[r[chosen]] = total[chosen], k[chosen]
    split = _first_tied(w, split)
    at = np.where(np.isfinite(value)[:, None], _at_split(runs, w, prefix, split), 0.0)
    return value, split, at, full


def _first_tied(w: np.ndarray, split: np.ndarray) -> np.ndarray:
    """The smallest k with the S of each row's ``split``: a run drawn no time adds
    nothing to any sum, so S is the same from just after the last drawn run before k
    (``walton.decide`` keeps the smallest k of such a tie; the block search may find a
    later one, its sums added in another order). Rows with no split are kept."""
    rows = np.arange(len(w))[:, None]
    back = split[:, None] - 1 - np.arange(64)  # k − 1, k − 2, …: the last drawn is near
    drawn = (back >= 0) & (w[rows, np.maximum(back, 0)] > 0)
    out = np.where(drawn.any(axis=1), split - np.argmax(drawn, axis=1), split)
    for row in np.flatnonzero(~drawn.any(axis=1) & (split > 64)):  # 64 runs never drawn
        before = np.flatnonzero(w[row, : split[row]])
        out[row] = before[-1] + 1 if before.size else split[row]
    return out


def decide_blocks(runs: Sorted, w: np.ndarray) -> core.Decision:
    """``walton.decide`` for weights ``w`` (m, padded runs) by the block search."""
    m, n = len(w), runs.n
    lo, hi, distinct = _allowed(w, n)
    value, split, at, full = _split(runs, w, lo, hi)
    zero = np.zeros_like(full)
    stick_all, _, beta_all, _ = _parts(full, full)
    _, slide_all, _, friction_none = _parts(zero, full)
    has_split = np.isfinite(value)
    counted = full[:, ONE]  # the draws: integer sums, exact
    scale = np.maximum(full[:, YY] + full[:, DD], 1e-300) * core.SSE_FLOOR
    sse = np.stack([np.maximum(stick_all, 0.0), np.maximum(slide_all, 0.0), value], axis=1)
    penalty = (
        np.array([core.PARAMETER_COUNT[name] for name in core.MODELS]) * np.log(counted)[:, None]
    )
    with np.errstate(divide="ignore", invalid="ignore"):
        bic = (
            counted[:, None] * np.log(np.maximum(sse, scale[:, None]) / counted[:, None]) + penalty
        )
    bic[:, 2] = np.where(has_split, bic[:, 2], np.inf)
    stick_split, slide_split, beta_split, friction_split = _parts(at, full)
    for column, sums, beta, stick in (
        (0, full, beta_all, stick_all),
        (2, at, beta_split, stick_split),
    ):
        origin = tuple(sums[:, i] for i in (ONE, X, Y, XX, XY, YY))
        bic[core.misses_origin(origin, beta, stick, scale), column] = np.inf
    model = np.argmin(bic, axis=1)
    k = np.select([model == 0, model == 2], [n, split], 0)
    beta = np.select([model == 0, model == 2], [beta_all, beta_split], np.nan)
    friction = np.select([model == 1, model == 2], [friction_none, friction_split], np.nan)
    n_stick = np.array([np.count_nonzero(w[i, : k[i]]) for i in range(m)])
    stuck = np.select([model == 0, model == 2], [full[:, ONE], at[:, ONE]], 0.0)
    beta_se = core.standard_error(
        np.select([model == 0], [stick_all], stick_split),
        stuck,
        np.select([model == 0], [full[:, XX]], at[:, XX]),
    )
    friction_se = core.standard_error(
        np.select([model == 1], [slide_all], slide_split),
        counted - stuck,
        full[:, CC] - np.select([model == 2], [at[:, CC]], 0.0),
    )
    mean = full[:, EE] / counted
    spread = np.maximum(full[:, E2] - counted * mean**2, 0.0)
    line = (beta, beta_se, friction, friction_se)
    mean_se = core.standard_error(spread, counted, counted)
    return core.decision(model, k, bic, line, (n_stick, distinct - n_stick), (mean, mean_se))


#: Resamples of the bootstrap decisions kept (``batches``), all groups together (a few
#: hundred bytes each): a report's Walton fit of a group, its gap-viscosity fit and the
#: bands of its lines re-decide the same resamples of the same runs.
KEPT_DECISIONS = 100_000
_decided: dict[tuple, core.Decision] = {}


def _runs_key(arrays: tuple, resamples: int, seed: int) -> tuple:
    """The key of a bootstrap: a digest of the runs' values, their count, resamples, seed."""
    digest = hashlib.blake2b(digest_size=16)
    for a in arrays:
        digest.update(np.ascontiguousarray(a, dtype=float).tobytes())
    return digest.hexdigest(), len(arrays[0]), int(resamples), int(seed)


def _rows(decision: core.Decision, start: int, stop: int) -> core.Decision:
    fields = core.Decision.__dataclass_fields__
    return core.Decision(*(getattr(decision, f)[start:stop] for f in fields))


def batches(x: np.ndarray, y: np.ndarray, c: np.ndarray, e: np.ndarray, resamples: int, seed: int):
    """Yield (counts, decision) per batch of resamples: the (m, padded runs) draw counts
    (reused by the next batch: use them before asking for it) and their fits. The
    decisions of the same runs, resamples and seed are made once and kept (the least
    recently used dropped beyond ``KEPT_DECISIONS`` resamples in all)."""
    key = _runs_key((x, y, c, e), resamples, seed)
    kept = _decided.pop(key, None)
    n = len(x)
    runs = Sorted(x, y, c, e) if kept is None else None
    size = padding(n)[2]
    batch = max(1, BATCH_CELLS // size)
    parts, start = [], 0
    for counts in count_batches(seed, resamples, n, size, batch):
        if runs is not None:  # nothing kept: decide
            parts.append(decide_blocks(runs, counts))
        yield counts, parts[-1] if kept is None else _rows(kept, start, start + len(counts))
        start += len(counts)
    _decided[key] = concatenate(parts) if kept is None else kept  # most recently used last
    while sum(len(d.model) for d in _decided.values()) > KEPT_DECISIONS and len(_decided) > 1:
        del _decided[next(iter(_decided))]


def concatenate(parts: list[core.Decision]) -> core.Decision:
    """One Decision of the resamples of ``parts``, in order."""
    fields = core.Decision.__dataclass_fields__
    return core.Decision(*(np.concatenate([getattr(p, f) for p in parts]) for f in fields))


def bootstrap(
    x: np.ndarray,
    y: np.ndarray,
    c: np.ndarray,
    e: np.ndarray,
    resamples: int,
    seed: int,
    stated: tuple[np.ndarray, np.ndarray] | None = None,
) -> core.Decision:
    """``resamples`` bootstrap fits over runs (each re-decides model and split), in batches.
    ``stated``: (the runs' Walton factor B, ``stated_walton``), and each resample also
    perturbs every run's measured speeds by their stated u (``perturbed_batches``).

    Deterministic for a given (data, resamples, seed).
    """
    if stated is None:
        key = _runs_key((x, y, c, e), resamples, seed)
        if key not in _decided:
            for _ in batches(x, y, c, e, resamples, seed):  # decides and keeps them
                pass
        return _decided[key]
    found = perturbed_batches(x, y, stated[0], e, stated[1], resamples, seed)
    return concatenate([decision for _, decision in found])
