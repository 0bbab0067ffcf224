"""Propagation that knows when first order fails (issue 36; JCGM 101:2008).

``propagate`` gives a quantity's standard uncertainty and 95 % coverage interval from its
inputs' standard uncertainties, and names the method that gave them:

- **first order (GUM)**, u² = Σ (∂f/∂x_i)² u_i² with ±1.96u as the interval, where a cheap
  check says it is adequate; else
- **Monte Carlo (JCGM 101)**: ``draws`` seeded, vectorised normal draws of the inputs, the
  standard deviation of f and the 2.5 % and 97.5 % quantiles as an asymmetric coverage
  interval, and the share of draws where f is not defined (NaN: no rebound, …).

The check (``first_order_adequate``) costs 4k + 1 evaluations of f for k inputs, on the
axes at ±u and ±2u: first order is kept only where (a) every one of them is finite, (b) the
curvature's second-order terms of GUM (JCGM 100 §5.1.2, note) change u by less than
``TOLERANCE`` (u₂² = Σ ½ (∂²f/∂x_i²)² u_i⁴ over u₁²), (c) the mean's shift ½ Σ ∂²f/∂x_i² u_i²
is under ``TOLERANCE`` of u₁, and (d) on each axis the quadratic through ±u predicts f at
±2u to ``TOLERANCE`` of u₁ (a step or a kink, as e(St) at St_c, fails it). Checked against
known distributions in tests/physics/test_monte_carlo.py (its 10⁶-draw comparison on μ_f
of (5.8) and e near St_c is in the git history; benchmarks/propagation.py now studies
derive's own per-row method, ``granudb.physics.propagation_check``, which this scalar
function is not: it serves a caller's own f).

f takes keyword arrays (the inputs by name) and returns an array of the same shape; it is
called with arrays of draws, so it must be vectorised (every ``granudb.physics`` function
is). Pure numpy.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

#: Relative departure from first order above which the Monte Carlo is used.
TOLERANCE = 0.05
#: Monte Carlo draws when first order is not adequate (JCGM 101 §7.2 suggests 10⁶ for a
#: 95 % interval to two significant digits; 2·10⁵ gives its ends to about 1 %).
DRAWS = 200_000
LEVEL = 0.95
FIRST_ORDER = "first order (GUM, JCGM 100:2008 §5.1), interval ±1.96u"
MONTE_CARLO = "Monte Carlo (JCGM 101:2008), {draws:,} normal draws, seed {seed}"


@dataclass(frozen=True)
class Propagated:
    """One quantity's value, standard uncertainty and 95 % coverage interval, the method
    that gave them, and the share of Monte Carlo draws where it is not defined."""

    value: float
    u: float
    low: float
    high: float
    method: str
    undefined: float = 0.0
    why: str = ""  # why first order was not adequate ('' when it was)


def _axis(x: dict[str, float], name: str, shift: float) -> dict[str, np.ndarray]:
    moved = {k: np.asarray(v, dtype=float) for k, v in x.items()}
    moved[name] = moved[name] + shift
    return moved


def first_order_adequate(
    f: Callable[..., np.ndarray],
    x: dict[str, float],
    u: dict[str, float],
    tolerance: float = TOLERANCE,
) -> tuple[float, float, str]:
    """(f(x), first-order u, '' or why first order is not adequate) by the check in the
    module's docstring."""
    value = float(f(**{k: np.asarray(v, dtype=float) for k, v in x.items()}))
    names = [k for k in x if u.get(k) and u[k] > 0]
    if not math.isfinite(value):
        return value, math.nan, "f is not defined at the inputs' values"
    grads, curvatures, worst = [], [], 0.0
    for name in names:
        h = u[name]
        values = [float(f(**_axis(x, name, s * h))) for s in (-2, -1, 1, 2)]
        if not all(math.isfinite(v) for v in values):
            return value, math.nan, f"f is not defined within ±2u of {name}"
        m2, m1, p1, p2 = values
        grad = (p1 - m1) / (2 * h)
        curvature = (p1 - 2 * value + m1) / (h * h)
        grads.append(grad * h)
        curvatures.append(curvature * h * h)
        # the quadratic through ±u at ±2u
        quad_p2 = value + 2 * grad * h + 2 * curvature * h * h
        quad_m2 = value - 2 * grad * h + 2 * curvature * h * h
        worst = max(worst, abs(p2 - quad_p2), abs(m2 - quad_m2))
    u1 = math.sqrt(sum(g * g for g in grads))
    if u1 == 0.0:
        return value, 0.0, ""
    u2 = math.sqrt(sum(0.5 * c * c for c in curvatures))
    shift = abs(0.5 * sum(curvatures))
    if math.sqrt(u1 * u1 + u2 * u2) / u1 - 1.0 > tolerance:
        return value, u1, f"curvature changes u by {math.sqrt(1 + (u2 / u1) ** 2) - 1:.1%}"
    if shift > tolerance * u1:
        return value, u1, f"curvature shifts the mean by {shift / u1:.2f}u"
    if worst > tolerance * u1:
        return value, u1, f"f departs from a quadratic within ±2u by {worst / u1:.2f}u"
    return value, u1, ""


def monte_carlo(
    f: Callable[..., np.ndarray],
    x: dict[str, float],
    u: dict[str, float],
    draws: int = DRAWS,
    seed: int = 0,
    level: float = LEVEL,
) -> tuple[float, float, float, float, float]:
    """(mean, standard deviation, low, high, share undefined) of f over ``draws`` normal
    draws of the inputs (independent, standard deviations ``u``; seeded), the interval
    the probabilistically symmetric one at ``level`` (JCGM 101 §7.7) of the defined draws."""
    rng = np.random.default_rng(seed)
    sample = {
        k: float(v) + (u.get(k) or 0.0) * rng.standard_normal(draws) if u.get(k) else float(v)
        for k, v in x.items()
    }
    y = np.asarray(f(**sample), dtype=float)
    y = np.broadcast_to(y, (draws,))
    defined = np.isfinite(y)
    share = 1.0 - float(np.mean(defined))
    y = y[defined]
    if y.size == 0:
        return math.nan, math.nan, math.nan, math.nan, share
    tail = 0.5 * (1.0 - level)
    low, high = np.quantile(y, [tail, 1.0 - tail])
    return float(np.mean(y)), float(np.std(y, ddof=1)), float(low), float(high), share


def propagate(
    f: Callable[..., np.ndarray],
    x: dict[str, float],
    u: dict[str, float],
    *,
    tolerance: float = TOLERANCE,
    draws: int = DRAWS,
    seed: int = 0,
) -> Propagated:
    """f(x) with its u and 95 % coverage interval: first order where
    ``first_order_adequate`` says so, else a seeded Monte Carlo (``monte_carlo``); the
    value is f(x) either way, the method named.

    >>> got = propagate(lambda a: a * a, {"a": 2.0}, {"a": 0.02})
    >>> round(got.u, 4), got.method.startswith("first order")
    (0.08, True)
    >>> got = propagate(lambda a: np.exp(3 * a), {"a": 1.0}, {"a": 0.3}, draws=10_000)
    >>> got.method.startswith("Monte Carlo"), got.high - got.value > got.value - got.low
    (True, True)
    """
    value, u1, why = first_order_adequate(f, x, u, tolerance)
    if not why:
        half = 1.959963984540054 * u1
        return Propagated(value, u1, value - half, value + half, FIRST_ORDER)
    _, sd, low, high, share = monte_carlo(f, x, u, draws, seed)
    return Propagated(value, sd, low, high, MONTE_CARLO.format(draws=draws, seed=seed), share, why)
