"""Propagation that knows when first order fails (issue 36): the check keeps first order
where it holds and switches to a seeded Monte Carlo where it does not, checked against
known distributions (derive's per-row method is studied in benchmarks/propagation.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from granudb.physics import flow
from granudb.physics.monte_carlo import FIRST_ORDER, first_order_adequate, propagate


def test_a_linear_quantity_keeps_first_order_exactly() -> None:
    got = propagate(lambda a, b: 2 * a - 3 * b, {"a": 1.0, "b": 2.0}, {"a": 0.1, "b": 0.2})
    assert got.method == FIRST_ORDER and got.why == ""
    assert got.u == pytest.approx(math.hypot(0.2, 0.6), rel=1e-9)
    assert got.high - got.value == pytest.approx(got.value - got.low)


def test_a_lognormal_gets_its_asymmetric_interval_from_the_monte_carlo() -> None:
    # y = exp(a), a ~ N(0, 0.4²): the 95 % interval is exp(±1.96·0.4), far from ±1.96u
    got = propagate(lambda a: np.exp(a), {"a": 0.0}, {"a": 0.4}, seed=3)
    assert got.method.startswith("Monte Carlo") and "curvature" in got.why
    low, high = math.exp(-1.959964 * 0.4), math.exp(1.959964 * 0.4)
    assert got.low == pytest.approx(low, rel=0.01) and got.high == pytest.approx(high, rel=0.01)
    sd = math.sqrt((math.exp(0.16) - 1) * math.exp(0.16))
    assert got.u == pytest.approx(sd, rel=0.01)


def test_no_rebound_below_st_c_is_a_step_that_first_order_cannot_see() -> None:
    # e = 0.97 exp(−35/St) above St_c = 10, 0 below: at St = 10.5 ± 5 % a sixth of the
    # draws give no rebound and the first-order u (its slope above St_c) is not the spread
    def e(st):
        return flow.predicted_restitution(st, 0.97)

    _, _, why = first_order_adequate(e, {"st": 10.5}, {"st": 0.525})
    assert why
    got = propagate(e, {"st": 10.5}, {"st": 0.525}, seed=1)
    assert got.low == 0.0 and got.method.startswith("Monte Carlo")
    share_zero = stats.norm.cdf((10.0 - 10.5) / 0.525)
    draws = np.random.default_rng(9).normal(10.5, 0.525, 400_000)
    assert np.mean(e(draws) == 0) == pytest.approx(share_zero, abs=0.005)
    assert got.u == pytest.approx(np.std(e(draws)), rel=0.02)


def test_the_monte_carlo_is_seeded_and_an_undefined_share_is_said() -> None:
    def f(a):
        return np.where(a > 0, np.sqrt(np.abs(a)), np.nan)

    one = propagate(f, {"a": 0.5}, {"a": 0.5}, seed=4, draws=50_000)
    two = propagate(f, {"a": 0.5}, {"a": 0.5}, seed=4, draws=50_000)
    assert one == two
    assert one.undefined == pytest.approx(stats.norm.cdf(-1.0), abs=0.01)
    assert "not defined" in one.why
