"""The fast Walton bootstrap gives the straightforward bootstrap's statistic, and its
large-group rule is stated and still recovers the truth (issue 13; docs/physics.md §14)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from analysis.synthetic import walton_frame

from granudb.analysis import asymptotic, fits, groups
from granudb.analysis import walton as core
from granudb.analysis import walton_bootstrap as fast
from granudb.analysis.synthetic import sliding_runs

BETA, MU = 0.34, 0.11
CASES = [
    (4, {}),
    (9, {}),
    (20, {}),
    (150, {}),
    (700, {}),
    (3000, {}),
    (40, {"psi_range": (0.75, 2.5)}),  # all sliding
    (40, {"psi_range": (0.02, 0.45)}),  # all sticking
    (500, {"noise": 0.3}),  # a flat residual curve: few blocks can be skipped
    (300, {"spin": 0.0, "noise": 0.0}),  # exact data: residuals at the floor
]


@pytest.mark.parametrize(("n", "options"), CASES)
def test_block_search_decides_as_the_dense_prefix_sums(n: int, options: dict) -> None:
    for seed in range(3):
        x, y, c, e, *_ = groups.walton_arrays(walton_frame(n, seed=seed, **options))
        runs = fast.Sorted(x, y, c, e)
        size = runs.size
        weights = fast.draw_counts(np.random.default_rng(seed), 30, n, size)
        got = fast.decide_blocks(runs, weights)
        want = core.decide(weights[:, :n], x, y, c, e)
        assert np.array_equal(got.model, want.model)
        assert np.array_equal(got.split, want.split)
        for name in ("beta", "friction", "restitution", "bic"):
            assert np.allclose(getattr(got, name), getattr(want, name), rtol=1e-9, equal_nan=True)


def straightforward(x, y, c, e, resamples: int, seed: int) -> core.Decision:
    """Draw each resample's runs, sort them, fit them as a data set of their own."""
    rng = np.random.default_rng(seed)
    n = len(x)
    size = -(-n // fast.BLOCK_RUNS) * fast.BLOCK_RUNS
    batch = max(1, fast.BATCH_CELLS // size)
    rows = []
    for start in range(0, resamples, batch):  # the same draws, batch by batch
        for pick in rng.integers(0, n, size=(min(batch, resamples - start), n)):
            order = np.sort(pick)  # x is sorted, so sorted indices sort the resample
            one = core.decide(np.ones((1, n)), x[order], y[order], c[order], e[order])
            rows.append((one.model[0], one.beta[0], one.friction[0], one.restitution[0]))
    return np.array(rows).T


def test_bootstrap_equals_the_straightforward_loop() -> None:
    x, y, c, e, *_ = groups.walton_arrays(walton_frame(400, spin=30.0, seed=4))
    boot = fast.bootstrap(x, y, c, e, 300, 9)
    model, beta, friction, restitution = straightforward(x, y, c, e, 300, 9)
    assert np.array_equal(boot.model, model)
    assert np.allclose(boot.beta, beta, rtol=1e-9, equal_nan=True)
    assert np.allclose(boot.friction, friction, rtol=1e-9, equal_nan=True)
    assert np.allclose(boot.restitution, restitution, rtol=1e-12)
    for fast_values, loop_values in ((boot.beta, beta), (boot.friction, friction)):
        assert core.percentile_interval(fast_values, 0.95) == pytest.approx(
            core.percentile_interval(loop_values, 0.95), rel=1e-9
        )


def test_resample_rule() -> None:
    assert fast.resample_count(50) == fast.DEFAULT_RESAMPLES == 1000
    assert fast.resample_count(fast.RULE_RUNS) == 1000
    assert fast.resample_count(33_000) == 303
    assert fast.resample_count(100_000) == fast.resample_count(10**7) == fast.MIN_RESAMPLES
    assert "10⁷ / n" in fast.RESAMPLE_RULE and "200" in fast.RESAMPLE_RULE


def test_a_large_group_states_the_rule_and_recovers_the_truth() -> None:
    n = 25_000
    frame = walton_frame(n, spin=30.0, seed=2)
    fit = fits.walton(frame, asymptotic_from=n + 1)[0]  # the bootstrap, not the large-n rule
    assert fit["bootstrap_resamples"] == 400 and fit["bootstrap_seed"] == 0
    assert fit["bootstrap_rule"] == fast.RESAMPLE_RULE
    assert fit["model"] == "split"
    assert fit["rotational_restitution_low"] <= BETA <= fit["rotational_restitution_high"]
    assert fit["sliding_friction_low"] <= MU <= fit["sliding_friction_high"]
    width = fit["rotational_restitution_high"] - fit["rotational_restitution_low"]
    assert 0 < width < 0.01  # 25,000 runs pin β down; the interval is not a formality
    # from asymptotic.ASYMPTOTIC_FROM runs (the default) no resamples: the asymptotic
    # interval, its rule and method said, as close to the bootstrap's as its 400 draws allow
    large = fits.walton(frame)[0]
    assert large["bootstrap_resamples"] == 0 and large["bootstrap_rule"] == asymptotic.rule(
        asymptotic.ASYMPTOTIC_FROM
    )
    assert large["interval_method"] == asymptotic.method(asymptotic.ASYMPTOTIC_FROM, False)
    for name in ("rotational_restitution", "sliding_friction", "normal_restitution"):
        low, high = fit[f"{name}_low"], fit[f"{name}_high"]
        assert abs(large[f"{name}_low"] - low) < 0.15 * (high - low)
        assert abs(large[f"{name}_high"] - high) < 0.15 * (high - low)
    asked = fits.walton(walton_frame(200, seed=2), resamples=50)[0]
    assert asked["bootstrap_resamples"] == 50 and asked["bootstrap_rule"] == "as asked"
    small = fits.walton(walton_frame(200, seed=2))[0]
    assert small["bootstrap_resamples"] == 1000 and small["bootstrap_rule"] == fast.RESAMPLE_RULE


def test_too_few_distinct_runs_in_a_resample_give_no_split() -> None:
    x, y, c, e, *_ = groups.walton_arrays(walton_frame(5, seed=1))
    runs = fast.Sorted(x, y, c, e)
    weights = np.zeros((1, runs.size))
    weights[0, [0, 4]] = [3, 2]  # two distinct runs: no line of two on each side
    got = fast.decide_blocks(runs, weights)
    assert got.bic[0, 2] == math.inf and got.model[0] != 2


def test_shared_counts_are_the_draws_of_one_generator(monkeypatch) -> None:
    n, seed = 300, 7
    want = fast.draw_counts(np.random.default_rng(seed), 40, n, n)
    fast.forget_counts()
    first = fast.shared_counts(seed, 25, n)  # drawn, then extended: a prefix of the same
    assert np.array_equal(first, want[:25])
    assert np.array_equal(fast.shared_counts(seed, 40, n), want)
    assert np.array_equal(fast.shared_counts(seed, 10, n), want[:10])
    size = 384
    kept = np.concatenate([c.copy() for c in fast.count_batches(seed, 40, n, size, 16)])
    monkeypatch.setattr(fast, "SHARED_CELLS", 100)  # too many cells to keep: drawn anew
    assert fast.shared_counts(seed, 40, n) is None
    drawn = np.concatenate([c.copy() for c in fast.count_batches(seed, 40, n, size, 16)])
    assert np.array_equal(kept, drawn) and np.array_equal(drawn[:, :n], want)
    assert not drawn[:, n:].any()


def test_a_groups_resamples_are_decided_once() -> None:
    x, y, c, e, *_ = groups.walton_arrays(walton_frame(300, spin=30.0, seed=5))
    fast.forget_counts()
    first = fast.bootstrap(x, y, c, e, 50, 3)
    assert fast.bootstrap(x, y, c, e, 50, 3) is first  # kept, not decided again
    by_batch = fast.concatenate([d for _, d in fast.batches(x, y, c, e, 50, 3)])
    other = fast.bootstrap(x, y * 1.01, c, e, 50, 3)  # other runs: decided anew
    assert other is not first and not np.array_equal(other.beta, first.beta)
    fast.forget_counts()
    fresh = fast.bootstrap(x, y, c, e, 50, 3)
    for field in core.Decision.__dataclass_fields__:
        for got in (by_batch, fresh):
            assert np.array_equal(getattr(got, field), getattr(first, field), equal_nan=True)


def test_gap_viscosity_after_the_walton_fit_of_its_runs_is_unchanged() -> None:
    wet = sliding_runs(1.6e-3, n=300, seed=3)
    fast.forget_counts()
    [alone] = fits.gap_viscosity(wet, {})
    fast.forget_counts()
    fits.walton(wet)  # decides the group's resamples; the gap fit then reuses them
    [after] = fits.gap_viscosity(wet, {})
    assert after.keys() == alone.keys()
    for name, value in alone.items():
        assert after[name] == value or (value != value and after[name] != after[name]), name
