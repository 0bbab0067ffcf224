"""Which rows first order (GUM) serves, and a Monte Carlo (JCGM 101) for the others.

``granudb.physics.uncertainty.propagate`` gives every derived quantity's u to first order.
This module decides, row by row and at almost no cost, whether that is adequate, and
replaces the u of the rows where it is not by an adaptive, seeded, vectorised Monte Carlo
over the same derivation; every row also gets the 95 % coverage interval of each quantity
(``low95_<q>``, ``high95_<q>``) and its method (``propagation_method``, one column for
the row's u, intervals and verdict probabilities).

**The check** (``first_order_adequate``), per row, from first order's own results:

- *Smoothness.* Every propagated quantity is a product of powers of the inputs or a
  smooth function of such products. For Q = Π (1 + ε_k)^{s_k} (ε_k the inputs' relative
  deviations, standard deviations r_k), Q's second-order term in normalised coordinates
  is H = a aᵀ − diag(a_k r_k) with a_k = s_k r_k, whose norm is at most u_r² + u_r r_max
  (u_r = u(Q)/|Q|, r_max the largest relative input u). An end of the 95 % interval
  then moves by at most ½ 1.96² ‖H‖ |Q| (the curvature along the worst direction at
  1.96 standard deviations), 0.49 (u_r + r_max) of the interval's width 3.92 u(Q).
  First order is kept where that bound is at most ``TOLERANCE`` for every quantity:
  max u_r + r_max ≤ TOLERANCE / 0.49.
- *Steps.* A verdict switches a quantity discontinuously (e = 0 below St_c, the friction
  used where the asperities touch, the elastic state at yield). Where the first-order
  95 % interval of the verdict's ratio (St_n/St_c, Λ, p_max/1.6Y; lognormal, as the
  verdict probabilities take it) reaches 1, the row goes to the Monte Carlo.

The check is validated against a 10⁶-draw Monte Carlo in benchmarks/propagation_study.py
(every quantity at 1, 5 and 10 % input u and near St_c) and in
tests/physics/test_propagation_check.py.

**The Monte Carlo** (``monte_carlo_rows``): each source of a flagged row is drawn normal
with its u (the particle's and the wall's one draw where they are one material; v_t with
v_n's relative draw where they are one speed); draws outside an input's domain (E ≤ 0,
ν ∉ (−1, ½), …) leave that draw undefined (NaN, like a draw with no value). Batches of
``BATCH`` draws per row, each batch's mean, standard deviation and 2.5 %/97.5 %
quantiles, are averaged (JCGM 101 §7.9.4) until twice the standard deviation of the
batches' averages is within ``NUMERICAL_TOLERANCE`` of the interval's width for every
quantity of the row, or ``MAX_DRAWS`` (then the method says the tolerance was not
reached). Each verdict's probability is the share of the draws where it holds. The
value stays f(x) (the derivation's), the interval is the Monte Carlo's (asymmetric where
it is). Seeded by ``SEED`` and the row's index: the same table gives the same numbers.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from granudb.physics.uncertainty import SOURCES

Arrays = dict[str, np.ndarray]

#: Largest share of the first-order interval's width an end may move (the check's bound).
TOLERANCE = 0.05
#: Stop when 2 × the standard deviation of the batches' averages ≤ this × the width.
NUMERICAL_TOLERANCE = 0.02
#: Draws per row in one batch, and at most in all (JCGM 101 §7.9: h batches of M).
BATCH = 2_000
MAX_DRAWS = 20_000
MIN_BATCHES = 2
#: Rows × draws evaluated at once (bounds memory).
CHUNK = 200_000
SEED = 20_081  # JCGM 101:2008
Z95 = 1.959963984540054
#: The check's bound per unit of (u_r + r_max) (½ 1.96² / 3.92).
_BOUND = 0.5 * Z95 * Z95 / (2 * Z95)
FIRST_ORDER = "first order (GUM)"
MONTE_CARLO = "Monte Carlo (JCGM 101), {draws:,} draws"
NOT_REACHED = "; tolerance not reached"

#: The column naming each row's method, and the ends of a quantity's 95 % interval: the
#: names ``granudb.vocabulary.terms`` gives them (physics imports nothing of granudb;
#: tests/physics/test_uncertainty.py checks derive's columns against the vocabulary).
PROPAGATION_METHOD = "propagation_method"


def interval_columns(name: str) -> tuple[str, str]:
    """``low95_<name>``, ``high95_<name>`` (``granudb.vocabulary.terms.interval_columns``)."""
    return f"low95_{name}", f"high95_{name}"


#: The verdicts: the probability's column, the derive column that holds the verdict, and
#: whether the verdict holds where that column is true.
VERDICTS = {
    "probability_asperity_contact": "roughness_exceeds_gap",
    "probability_rebound": "rebound_expected",
}
#: Particle's source → the wall's (one draw where they are one material).
_PARTNERS = {"rho1": "rho2", "e1": "e2", "nu1": "nu2", "s1": "s2", "y1": "y2"}


def _relative(columns: Arrays, out: Arrays, names: tuple[str, ...]) -> np.ndarray:
    """max over ``names`` of u(Q)/|Q| by row (NaN-free: quantities of 0 or without u skip)."""
    worst = np.zeros(np.shape(columns[names[0]]))
    with np.errstate(divide="ignore", invalid="ignore"):
        for name in names:
            ratio = out[f"u_{name}"] / np.abs(columns[name])
            np.fmax(worst, np.where(np.isfinite(ratio), ratio, 0.0), out=worst)
    return worst


#: The verdict probabilities whose verdict switches a quantity discontinuously.
PROBABILITIES = ("probability_asperity_contact", "probability_rebound", "probability_yield")


#: The quantities a verdict switches discontinuously (checked with the verdicts).
STEPPED = ("predicted_restitution", "friction_coefficient_used", "maw_psi_in")


def first_order_adequate(
    x: Arrays,
    u: Arrays,
    columns: Arrays,
    out: Arrays,
    names: tuple[str, ...],
    tolerance: float = TOLERANCE,
) -> dict[str, np.ndarray]:
    """By quantity (and ``"verdicts"``), true by row where first order's u and ±1.96u
    interval are adequate (the module's check), from the inputs ``x`` and their u
    (``u``, step names), derive's ``columns`` and first order's ``out`` (``u_<q>`` and
    the verdict probabilities: a verdict's first-order 95 % interval reaches its
    threshold exactly where its probability is between 2.5 % and 97.5 %)."""
    r_max = np.zeros(np.shape(columns[names[0]]))
    with np.errstate(divide="ignore", invalid="ignore"):
        for source, given in u.items():
            if SOURCES.get(source) or source == "vn":
                ratio = np.asarray(given, dtype=float) / np.abs(x[source])
                np.fmax(r_max, np.where(np.isfinite(ratio), ratio, 0.0), out=r_max)
    limit = tolerance / _BOUND - r_max
    verdicts = np.ones(r_max.shape, dtype=bool)
    for probability in PROBABILITIES:
        p = out[probability]
        verdicts &= ~((p > 0.025) & (p < 0.975))
    ok: dict[str, np.ndarray] = {"verdicts": verdicts}
    with np.errstate(divide="ignore", invalid="ignore"):
        for name in names:
            ratio = out[f"u_{name}"] / np.abs(columns[name])
            ok[name] = ~(ratio > limit)  # NaN (no u, or Q = 0) passes
            if name in STEPPED:
                ok[name] &= verdicts
    return ok


def _draw(
    x: Arrays,
    u: Arrays,
    rows: np.ndarray,
    draws: int,
    rng: np.random.Generator,
    correlated: np.ndarray,
    one_speed: np.ndarray,
) -> tuple[Arrays, np.ndarray]:
    """The inputs of ``rows``, each repeated ``draws`` times (row-major), with every
    stated source drawn normal; and the draws inside every input's domain."""
    n = rows.size * draws
    drawn = {
        k: np.repeat(v[rows], draws) if np.ndim(v) else np.full(n, float(v)) for k, v in x.items()
    }
    z: Arrays = {}
    for source in u:
        z[source] = rng.standard_normal(n)
    shared = np.repeat(correlated[rows], draws)
    for first, second in _PARTNERS.items():
        if first in z and second in z:
            z[second] = np.where(shared, z[first], z[second])
    if "vn" in z and "vt" in z:
        # one speed at a set angle: v_t moves with v_n's relative draw
        same = np.repeat(one_speed[rows], draws)
        with np.errstate(divide="ignore", invalid="ignore"):
            rel_vn = np.repeat(u["vn"][rows] / np.abs(x["vn"][rows]), draws)
            z_vt = z["vn"] * rel_vn * np.abs(drawn["vt"]) / np.repeat(u["vt"][rows], draws)
        z["vt"] = np.where(same & np.isfinite(z_vt), z_vt, z["vt"])
    for source, noise in z.items():
        sd = np.nan_to_num(np.repeat(u[source][rows], draws))
        drawn[source] = drawn[source] + sd * noise
    ok = np.ones(n, dtype=bool)
    for source, relative in SOURCES.items():
        if source in z and relative:
            ok &= ~(drawn[source] <= 0)  # NaN (not given) stays allowed
    for nu in ("nu1", "nu2"):
        if nu in z:
            ok &= (drawn[nu] > -1) & (drawn[nu] < 0.5)
    if "vn" in z:
        approach = drawn["vn"] - np.where(np.isnan(drawn["w_vn"]), 0.0, drawn["w_vn"])
        ok &= approach > 0
    if not ok.all():  # a draw outside the domain is evaluated at the row's value, then NaN
        for source in z:
            drawn[source] = np.where(ok, drawn[source], np.repeat(x[source][rows], draws))
    return drawn, ok


def monte_carlo_rows(
    evaluate: Callable[[Arrays], Arrays],
    x: Arrays,
    u: Arrays,
    rows: np.ndarray,
    names: tuple[str, ...],
    correlated: np.ndarray,
    one_speed: np.ndarray,
    *,
    batch: int = BATCH,
    max_draws: int = MAX_DRAWS,
    numerical_tolerance: float = NUMERICAL_TOLERANCE,
    seed: int = SEED,
) -> tuple[Arrays, np.ndarray, np.ndarray]:
    """({u_<q>, low95_<q>, high95_<q>, probabilities} of ``rows``, draws used by row,
    whether the tolerance was reached by row): the module's adaptive Monte Carlo;
    ``evaluate`` maps inputs (step names) to derive's columns."""
    stats = ("sd", "low", "high")
    per_chunk = max(1, CHUNK // batch)
    result: Arrays = {}
    used = np.zeros(rows.size, dtype=int)
    reached = np.zeros(rows.size, dtype=bool)
    for start in range(0, rows.size, per_chunk):
        part = rows[start : start + per_chunk]
        m = part.size
        batches: list[dict[str, np.ndarray]] = []
        while True:
            h = len(batches)
            rng = np.random.default_rng([seed, int(part[0]), h])
            drawn, ok = _draw(x, u, part, batch, rng, correlated, one_speed)
            with np.errstate(all="ignore"):
                y = evaluate(drawn)
            one: dict[str, np.ndarray] = {}
            for name in names:
                values = np.where(ok, np.asarray(y[name], dtype=float), np.nan)
                values = values.reshape(m, batch)
                values = np.where(np.isfinite(values), values, np.nan)
                with np.errstate(all="ignore"), _quiet():
                    low, high = np.nanquantile(values, [0.025, 0.975], axis=1)
                    one[f"{name}:sd"] = np.nanstd(values, axis=1, ddof=1)
                one[f"{name}:low"], one[f"{name}:high"] = low, high
            for probability, verdict in VERDICTS.items():
                holds = np.asarray(y[verdict], dtype=float).reshape(m, batch)
                one[probability] = np.mean(np.where(ok.reshape(m, batch), holds, np.nan), 1)
            with np.errstate(all="ignore"):
                ratio = np.asarray(y["max_pressure_pa"], dtype=float) / (
                    1.6 * np.fmin(drawn["y1"], drawn["y2"])
                )
            yields = np.where(ok & np.isfinite(ratio), ratio > 1, np.nan).reshape(m, batch)
            with _quiet():
                one["probability_yield"] = np.nanmean(yields, axis=1)
            batches.append(one)
            h += 1
            if h < MIN_BATCHES:
                continue
            done = np.ones(m, dtype=bool)
            for name in names:
                width = _mean(batches, f"{name}:high") - _mean(batches, f"{name}:low")
                for stat in stats:
                    spread = _spread(batches, f"{name}:{stat}")
                    done &= ~(2 * spread > numerical_tolerance * width)
            if done.all() or h * batch >= max_draws:
                break
        sl = slice(start, start + m)
        used[sl] = len(batches) * batch
        reached[sl] = done
        for key in batches[0]:
            name, _, stat = key.partition(":")
            column = {"": name, "sd": f"u_{name}", "low": interval_columns(name)[0],
                      "high": interval_columns(name)[1]}[stat]  # fmt: skip
            result.setdefault(column, np.empty(rows.size))[sl] = _mean(batches, key)
    return result, used, reached


class _quiet:
    """Silence numpy's 'all-NaN slice' warnings (an undefined quantity stays NaN)."""

    def __enter__(self) -> None:
        import warnings

        self._catch = warnings.catch_warnings()
        self._catch.__enter__()
        warnings.simplefilter("ignore", RuntimeWarning)

    def __exit__(self, *exc: object) -> None:
        self._catch.__exit__(*exc)


def _mean(batches: list[dict[str, np.ndarray]], key: str) -> np.ndarray:
    with _quiet():
        return np.nanmean(np.stack([b[key] for b in batches]), axis=0)


def _spread(batches: list[dict[str, np.ndarray]], key: str) -> np.ndarray:
    """The standard deviation of the batches' average of ``key`` (s/√h)."""
    stack = np.stack([b[key] for b in batches])
    with _quiet():
        return np.nanstd(stack, axis=0, ddof=1) / np.sqrt(len(batches))


def check_and_resample(
    evaluate: Callable[[Arrays], Arrays],
    x: Arrays,
    u: Arrays,
    columns: Arrays,
    out: Arrays,
    names: tuple[str, ...],
    correlated: np.ndarray,
    one_speed: np.ndarray,
) -> Arrays:
    """``out`` (first order's ``u_<q>`` and probabilities) with, for every row: the 95 %
    intervals ``low95_<q>``/``high95_<q>`` and ``propagation_method``; rows where
    ``first_order_adequate`` fails get the Monte Carlo's u, intervals and probabilities.
    A row none of whose inputs states a u has no method (None) and no interval (NaN)."""
    shape = np.shape(columns[names[0]])
    stated = np.zeros(shape, dtype=bool)
    for given in u.values():
        stated |= np.isfinite(np.asarray(given, dtype=float))
    ok = first_order_adequate(x, u, columns, out, names)
    row_ok = np.logical_and.reduce([ok[k] for k in ok])
    result = dict(out)
    for name in names:
        low, high = interval_columns(name)
        half = Z95 * out[f"u_{name}"]
        result[low], result[high] = columns[name] - half, columns[name] + half
    method = np.full(shape, None, dtype=object)
    method[stated] = FIRST_ORDER
    rows = np.flatnonzero(stated & ~row_ok)
    if rows.size:

        def flat(v: Any) -> np.ndarray:
            return np.broadcast_to(np.asarray(v, dtype=float), shape).reshape(-1)

        flat_x = {k: flat(v) for k, v in x.items()}
        given = {k: flat(v) for k, v in u.items()}
        drawn, used, reached = monte_carlo_rows(
            evaluate, flat_x, given, rows, names, flat(correlated) != 0, flat(one_speed) != 0
        )
        for column, values in drawn.items():
            target = np.array(np.broadcast_to(result[column], shape), dtype=float).reshape(-1)
            # a quantity first order leaves without u (none of its inputs stated) keeps none
            if column.startswith(("u_", "low95_", "high95_")):
                keep = flat(out_u(out, column))[rows]
                if column.endswith("predicted_restitution"):  # e = 0 below St_c has a u here
                    keep = flat(columns["normal_stokes_number"])[rows]
            else:  # a probability without a number (dry, no Y) stays without
                keep = flat(out[column])[rows]
            quantity = column.removeprefix("u_").removeprefix("low95_").removeprefix("high95_")
            failed = ~flat(ok.get(quantity, ok["verdicts"]))[rows].astype(bool)
            target[rows] = np.where(failed, np.where(np.isnan(keep), np.nan, values), target[rows])
            result[column] = target.reshape(shape)
        flat_method = method.reshape(-1)
        failing = {k: flat(v)[rows] == 0 for k, v in ok.items()}
        for index, row in enumerate(rows):
            which = [k if k != "verdicts" else "verdict probabilities" for k in failing
                     if failing[k][index]]  # fmt: skip
            text = MONTE_CARLO.format(draws=int(used[index]))
            text += NOT_REACHED if not reached[index] else ""
            flat_method[row] = f"{text} for {', '.join(which)}; {FIRST_ORDER} for the rest"
        method = flat_method.reshape(shape)
    result[PROPAGATION_METHOD] = method
    return result


def out_u(out: Arrays, column: str) -> np.ndarray:
    """First order's u of the quantity a ``u_``/``low95_``/``high95_`` column is of."""
    for prefix in ("u_", "low95_", "high95_"):
        if column.startswith(prefix):
            return np.asarray(out[f"u_{column.removeprefix(prefix)}"], dtype=float)
    raise KeyError(column)
