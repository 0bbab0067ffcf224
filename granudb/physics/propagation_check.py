"""Which rows first order (GUM) serves, and a Monte Carlo (JCGM 101) for the others.

``granudb.physics.uncertainty.propagate`` gives every derived quantity's u to first order.
This module decides, row by row and at almost no cost, whether that is adequate, and
replaces the u of the rows where it is not by an adaptive, seeded, vectorised Monte Carlo
over the same derivation; every row also gets the 95 % coverage interval of each quantity
(``low95_<q>``, ``high95_<q>``) and its method (``propagation_method``, one column for
the row's u, intervals and verdict probabilities).

**First order's interval** (``first_order_intervals``): Q·exp(±1.96 u_r) (first order
on ln Q; u_r = u(Q)/|Q|) for every positive quantity, ±1.96u for the ``LINEAR`` ones; the
predicted restitution through St_am's log-normal interval and St_c's step (e is
monotone in St), its u by Gauss–Legendre quadrature above the step where the step is
inside the interval.

**The check** (``first_order_adequate``), per row, from first order's own results (no
evaluation of the physics):

- *Curvature.* For Q = Π (1 + ε_k)^{s_k} (ε_k the inputs' relative deviations, standard
  deviations r_k), ln Q's second-order term in normalised coordinates is
  −diag(a_k r_k) with a_k = s_k r_k, whose norm is at most u_r r_max (r_max the largest
  r_k: ``_input_scale``). An end of the log interval then moves by at most
  ½ 1.96² u_r r_max, 0.49 r_max of its width 3.92 u_r, and by W/(1 − e^−W) times that
  share of the linear width (W = 3.92 u_r). A(c) adds the change Δs of its log slope
  across c's interval: 0.125 Δs u_r(c)/u_r(Q). ±1.96u (``LINEAR``) takes the old bound
  0.49 (u_r + r_max). First order is kept where the bound is at most ``TOLERANCE``.
- *Steps.* The friction used and Maw's ψ switch where asperities touch (Λ = 1) and bend
  at (5.8)'s cap: where the contact probability, or the probability that μ_lub exceeds
  the cap (log-normal, as the verdict probabilities), is between 2.5 and 97.5 %, they
  and the verdict probabilities go to the Monte Carlo.

Validated against a 10⁶-draw Monte Carlo in benchmarks/propagation.py (every quantity at
1, 5 and 10 % input u, 37 % glycerol and near St_c: docs/propagation.md) and in
tests/physics/test_propagation_study.py.

**Cost where first order holds** (``benchmarks/derive_speed.py``: about 0.8 of the plain
derive's CPU for the check and the 70 interval ends, as much again for first order's u).
Each log-normal quantity checked by u(Q)/Q alone is one pass: u/Q is divided once and,
while it is in cache, compared with the row's limit and turned into the interval ends
(``first_order_adequate``'s ``ends``), which are written straight into the output's rows
(``into``: ``granudb.physics.row_chunks``); a Q ≤ 0 is looked for only where the
smallest Q is not > 0, and a np.where only where some row needs it. Measured against
the code before (27 Nov 2026, same process, alternating, 120,000–240,000 first-order
rows): the check and intervals 0.78× its CPU, derive with uncertainties 0.80–0.86×.

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
it is). Seeded by ``SEED``, the first row's index within its block and the batch: the same
table gives the same numbers.
"""

from __future__ import annotations

import contextlib
import warnings
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np

from granudb.physics import flow, lubrication
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
#: Draws of the derivation one call may spend on its Monte Carlo, over all its rows
#: (``derive(..., monte_carlo_draws=…)``): about 5 s of CPU on this project's machine
#: (measured: 1 µs a draw of one row), 250 rows at the full ``MAX_DRAWS`` or 1,250 at two
#: batches; one scenario (``pair``) never reaches it. Each block of rows gets
#: its share (its rows' share of the call's); a row the share does not reach keeps first
#: order and its method says so (``NOT_RUN``), never silently.
DRAW_BUDGET = 5_000_000
#: Rows × draws evaluated at once (bounds memory).
CHUNK = 200_000
SEED = 20_081  # JCGM 101:2008
Z95 = 1.959963984540054
#: The check's bound per unit of (u_r + r_max) (½ 1.96² / 3.92).
_BOUND = 0.5 * Z95 * Z95 / (2 * Z95)
FIRST_ORDER = "first order (GUM)"
MONTE_CARLO = "Monte Carlo (JCGM 101), {draws:,} draws"
NOT_REACHED = " (tolerance not reached)"
NOT_RUN = (
    "{first}; the check failed for {failed}; Monte Carlo not run: the call's budget of "
    "{budget:,} draws was spent on earlier rows (monte_carlo_draws raises it)"
)

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


#: The verdict probabilities whose verdict switches a quantity discontinuously.
PROBABILITIES = ("probability_asperity_contact", "probability_rebound", "probability_yield")
#: Quantities the asperity-contact verdict switches (μ_dry ↔ the film's μ): a row whose
#: contact probability is between 2.5 and 97.5 % sends them to the Monte Carlo.
CONTACT_STEPPED = ("friction_coefficient_used", "maw_psi_in")
#: Quantities linear in normal inputs (±1.96u is their exact interval) or absolute.
LINEAR = ("normal_speed_m_s", "tangential_speed_m_s", "incidence_angle_rad")
#: Quantities that move with U (their relative scale includes u(U)/|U|).
TANGENTIAL = (
    "tangential_speed_m_s",
    "incidence_angle_rad",
    "traction_film_m",
    "lubricated_friction",
    "shear_strain",
    "friction_coefficient_used",
    "maw_psi_in",
)
#: Quantities built on A(c) (5.9), a polynomial of degree 16 whose log slope changes.
WITH_A = ("friction_integral", "lubricated_friction", "friction_coefficient_used", "maw_psi_in")
RESTITUTION = "predicted_restitution"
#: Gauss–Legendre nodes and weights on [−1, 1] for u of e across St_c's step: e is 0
#: below the step's z* and smooth above it, so the moments are integrated over [z*, 8]
#: alone (``_restitution``); 24 nodes agree with adaptive quadrature to 1e-12 relative on
#: 300 random rows across the step (the 241-point rule over [−6, 6] that stepped over z*
#: was 2 % off at worst, and cost ten times as much).
_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(24)
#: Upper end of that integral in z (Φ(−8) ≈ 6e-16).
_Z_TOP = 8.0


def _input_scale(x: Arrays, u: Arrays, columns: Arrays, scaled: Arrays | None = None) -> np.ndarray:
    """Per row, the largest relative scale r of any stated input: u/|x| (v_n's relative to
    the approach speed v_N, v_t's to the impact speed); a Poisson ratio's u(ν)·(1 + ν²)/
    (ν(1 − ν²)), the ratio of ln(1 − ν²)'s second derivative to its first times u(ν).
    ``scaled``: the sources' scaled u as first order took them
    (``granudb.physics.uncertainty.propagate``), whose relative ones are these u/|x|."""
    shape = np.shape(columns["normal_speed_m_s"])
    r_max = np.zeros(shape)
    scale = {"vn": columns["normal_speed_m_s"], "vt": columns["impact_speed_m_s"]}
    with np.errstate(divide="ignore", invalid="ignore"):
        for source, given in u.items():
            if scaled is not None and source not in scaled:
                continue  # not stated in any row
            if source in ("nu1", "nu2"):
                nu = x[source]
                ratio = np.asarray(given, dtype=float) * (1 + nu * nu) / np.abs(nu * (1 - nu * nu))
            elif scaled is not None and (SOURCES[source] or source == "vn"):
                ratio = scaled[source]  # u/|x| (v_n's: u/v_N), 0 where not stated
            else:
                ratio = np.asarray(given, dtype=float) / np.abs(scale.get(source, x[source]))
            np.fmax(r_max, ratio, out=r_max)  # NaN (not stated) is skipped
    r_max[np.isinf(r_max)] = 0.0  # an input of 0 (v_t) is scaled by what it enters
    return r_max


def _finite(values: Any, fill: float = 0.0) -> Any:
    """``values`` with ``fill`` where not finite (``values`` itself where all are)."""
    finite = np.isfinite(values)
    return values if finite.all() else np.where(finite, values, fill)


def _log_factor(u_r: np.ndarray) -> np.ndarray:
    """Linear-space share of a shift of the log interval's end: W/(1 − e^−W), W its width."""
    w = 2 * Z95 * _finite(u_r)
    with np.errstate(divide="ignore", invalid="ignore"):
        factor = w / -np.expm1(-w)
    small = ~(w > 1e-12)
    return np.where(small, 1.0, factor) if small.any() else factor


def _u_r_limit(r_q: np.ndarray, tolerance: float) -> np.ndarray:
    """The largest u_r(Q) at which a lognormal interval passes ``_BOUND`` r_q F(W) ≤
    ``tolerance`` (F = W/(1 − e^−W) ≤ 1 + W/2 + W²/12, W = 3.92 u_r): one limit per row,
    so each quantity's check is one product and one comparison (negative: none passes)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        k = tolerance / (_BOUND * r_q)
        w = -3.0 + 6.0 * np.sqrt(0.25 + (k - 1.0) / 3.0)
    passes = k >= 1.0
    return w / (2 * Z95) if passes.all() else np.where(passes, w / (2 * Z95), -1.0)


def _a_change(columns: Arrays, out: Arrays) -> tuple[np.ndarray, np.ndarray]:
    """(|Δs|, u_r(c)): the change of A's log slope s = d ln A/d ln c across c's own
    95 % interval, and c's relative u (c = η̂ p_max)."""
    c = columns["eta_hat_pa_inv"] * columns["max_pressure_pa"]
    with np.errstate(divide="ignore", invalid="ignore"):
        parts = [out[f"u_{k}"] / columns[k] for k in ("eta_hat_pa_inv", "max_pressure_pa")]
        eta, p_max = (v if np.isfinite(v).all() else np.nan_to_num(v) for v in parts)
        u_c = np.sqrt(eta * eta + p_max * p_max)  # √(a² + b²): np.hypot is 3-6x slower
        # s(c) from first order itself (u_r(A) = s u_r(c)); s at the interval's top once
        s_c = out["u_friction_integral"] / columns["friction_integral"] / u_c
        top = lubrication.friction_integral_log_slope(c * np.exp(Z95 * u_c))
        change = 2.0 * np.abs(top - s_c)
    return _finite(change), u_c


def first_order_adequate(
    x: Arrays,
    u: Arrays,
    columns: Arrays,
    out: Arrays,
    names: tuple[str, ...],
    friction_cap: Any = np.inf,
    tolerance: float = TOLERANCE,
    scaled: Arrays | None = None,
    ends: Arrays | None = None,
    into: Arrays | None = None,
) -> dict[str, np.ndarray]:
    """By quantity (and ``"verdicts"``), true by row where first order's u and its 95 %
    interval (``first_order_intervals``) are adequate by the module's check, from the
    inputs ``x`` and their u (``u``, step names), derive's ``columns`` and first order's
    ``out`` (``u_<q>`` and the verdict probabilities); ``friction_cap`` is the film's
    μ_f cap min(μ_dry, γ_max). ``scaled``: the sources' scaled u if first order kept
    them (``_input_scale``). ``ends``, if given, receives the interval ends of the
    log-normal quantities checked by u(Q)/Q alone, from the same u(Q)/Q while it is at
    hand (``first_order_intervals`` then takes them), written into ``into`` where given."""
    into = into or {}
    r_max = _input_scale(x, u, columns, scaled)
    with np.errstate(divide="ignore", invalid="ignore"):
        r_u = out["u_tangential_speed_m_s"] / np.abs(columns["tangential_speed_m_s"])
    r_t = np.fmax(r_max, _finite(r_u))  # for what moves with U
    p = out["probability_asperity_contact"]
    contact = ~((p > 0.025) & (p < 0.975))
    # the film's μ is capped (μ_used = min(μ_lub, cap)): a cap inside μ_lub's interval
    # is a kink of μ_used and ψ
    # P(μ_lub > cap) between 2.5 and 97.5 % (log-normal): |ln(μ_lub/cap)| < 1.96 u_r
    with np.errstate(divide="ignore", invalid="ignore"):
        lub, u_lub = columns["lubricated_friction"], out["u_lubricated_friction"]
        contact &= ~(np.abs(np.log(lub / friction_cap)) < Z95 * u_lub / lub)
    ok: dict[str, np.ndarray] = {"verdicts": contact}
    change, u_c = _a_change(columns, out) if set(WITH_A) & set(names) else (0.0, 0.0)
    a_term = 0.125 * change * u_c  # A's share of the bound, times u_r(Q)
    bounds = (_BOUND * r_max, _BOUND * r_t)  # the inputs' share (what moves with U: r_t)
    limit = _u_r_limit(r_max, tolerance)
    limit_t = _u_r_limit(r_t, tolerance)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for name in names:
            if name in ("normal_speed_m_s", "tangential_speed_m_s"):  # linear: exact
                continue
            if name == RESTITUTION and "added_mass_stokes_number" in ok:
                ok[name] = ok["added_mass_stokes_number"]  # through St_am's interval
                continue
            r_q = r_t if name in TANGENTIAL else r_max
            source = "added_mass_stokes_number" if name == RESTITUTION else name
            q, u_q = columns[source], out[f"u_{source}"]
            if name in LINEAR:  # ±1.96u: curvature of the exponential and of the inputs
                ok[name] = ~(_BOUND * (u_q / np.abs(q) + r_q) > tolerance)
            elif name in WITH_A:  # lognormal, with A's change of slope
                u_r = u_q / np.abs(q)
                bound = (bounds[name in TANGENTIAL] + a_term / u_r) * _log_factor(u_r)
                ok[name] = ~(bound > tolerance)  # NaN (no u) passes
            else:  # lognormal: only the inputs' own curvature moves its ends
                u_r = np.divide(u_q, q)  # Q > 0 (a Q ≤ 0 passes: ±1.96u)
                ok[name] = ~(u_r > (limit_t if name in TANGENTIAL else limit))
                if ends is not None and source == name:
                    low95, high95 = interval_columns(name)
                    ends[low95], ends[high95] = _log_normal_ends(
                        q, u_q, u_r, into.get(low95), into.get(high95)
                    )
            if name in CONTACT_STEPPED:
                ok[name] &= contact
    return ok


def first_order_intervals(
    columns: Arrays,
    out: Arrays,
    names: tuple[str, ...],
    critical_stokes: float,
    ends: Arrays | None = None,
    into: Arrays | None = None,
) -> Arrays:
    """The 95 % interval of each quantity by first order: Q·exp(±1.96 u_r) for a positive
    quantity (first order on ln Q: every one is a product of powers or A(c) of one), ±1.96u
    for ``LINEAR`` ones and any Q ≤ 0; the predicted restitution through St_am's
    lognormal interval and St_c's step (e is monotone in St), with its u by quadrature
    where the step is inside the interval. Also returns ``u_predicted_restitution``.
    ``ends``: interval ends already computed (``first_order_adequate``); ``into``: arrays
    to write the interval ends into, where given."""
    result: Arrays = {}
    ends = ends or {}
    into = into or {}
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for name in names:
            low95, high95 = interval_columns(name)
            if low95 in ends:
                result[low95], result[high95] = ends[low95], ends[high95]
                continue
            if name == RESTITUTION:  # below, in this place of the result
                result[low95] = result[high95] = None  # type: ignore[assignment]
                continue
            q, u_q = columns[name], out[f"u_{name}"]
            if name in LINEAR:
                width = Z95 * u_q
                low = np.subtract(q, width, out=into.get(low95))
                high = np.add(q, width, out=into.get(high95))
            else:
                low, high = _log_normal_ends(
                    q, u_q, np.divide(u_q, q), into.get(low95), into.get(high95)
                )
            result[low95], result[high95] = low, high
    if RESTITUTION in names:
        for column, values in _restitution(columns, out, critical_stokes).items():
            target = into.get(column)  # copied there while still in cache
            if target is not None:
                target[...] = values
            result[column] = values if target is None else target
    return result


def _log_normal_ends(
    q: Any, u_q: Any, u_r: Any, low: np.ndarray | None, high: np.ndarray | None
) -> tuple[np.ndarray, np.ndarray]:
    """Q·exp(∓1.96 u_r) and Q·exp(±1.96 u_r), u_r = u(Q)/Q (overwritten), written into
    ``low``/``high`` where given; ±1.96u where Q ≤ 0 (Q = 0: U = 0, no film)."""
    t = u_r
    if not isinstance(t, np.ndarray) or not t.ndim:  # one scenario
        t = np.array(t, dtype=float, ndmin=1)
    t *= Z95
    np.exp(t, out=t)
    high = np.multiply(q, t, out=high)
    low = np.divide(q, t, out=t if low is None else low)
    if np.ndim(q) == 0:
        low, high = low.reshape(()), high.reshape(())
    if not (q.size and q.min() > 0):  # some Q ≤ 0 (or NaN): look row by row
        negative = q <= 0
        if negative.any():
            low[...] = np.where(negative, q - Z95 * u_q, low)
            high[...] = np.where(negative, q + Z95 * u_q, high)
    return low, high


def _restitution(columns: Arrays, out: Arrays, critical_stokes: float) -> Arrays:
    """e's interval: e(St) = ceiling·exp(−β/St) at St_am·exp(±1.96 u_r(St_am)), 0 where
    St_n·exp(±1.96 u_r(St_n)) ≤ St_c (comonotone); its u by quadrature across the step."""
    st_am, st_n = columns["added_mass_stokes_number"], columns["normal_stokes_number"]
    ceiling = columns["restitution_ceiling"]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        s_am = out["u_added_mass_stokes_number"] / st_am
        s_n = out["u_normal_stokes_number"] / st_n
        inv = -flow.LEGENDRE_BETA / st_am  # ln(e/ceiling) = −β/St
        g = np.exp(Z95 * s_am)
        high = np.asarray(ceiling * np.exp(inv / g))  # an array also for one scenario
        low = np.asarray(ceiling * np.exp(inv * g))
        margin = np.log(critical_stokes / st_n)  # rebound where z s_n > margin
        z_n = Z95 * s_n
        np.putmask(high, ~(z_n > margin), 0.0)
        np.putmask(low, ~(-z_n > margin), 0.0)
    u_e = out[f"u_{RESTITUTION}"]
    p = out["probability_rebound"]
    across = (p > 0.025) & (p < 0.975) & np.isfinite(s_am)
    if across.any():
        u_e = np.array(u_e, dtype=float, copy=True)
        rows = np.flatnonzero(across.reshape(-1))
        flat = {k: np.reshape(v if np.shape(v) == across.shape else
                              np.broadcast_to(v, across.shape), -1)[rows]
                for k, v in (("am", st_am), ("n", st_n), ("c", ceiling), ("sa", s_am),
                             ("sn", s_n))}  # fmt: skip
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            # rebound (e > 0) where z > z* = ln(St_c/St_n)/s_n; e = ceiling·exp(−β/St_am)
            # is smooth above: Gauss–Legendre over [z*, _Z_TOP] (St > 0 here: St_am and
            # its u are finite)
            low_z = np.clip(np.log(critical_stokes / flat["n"]) / flat["sn"], -_Z_TOP, _Z_TOP)
            half = 0.5 * (_Z_TOP - low_z)[:, None]
            z = low_z[:, None] + half * (_GL_NODES[None, :] + 1.0)
            weights = half * _GL_WEIGHTS[None, :] * np.exp(-0.5 * z * z) / np.sqrt(2 * np.pi)
            st = flat["am"][:, None] * np.exp(z * flat["sa"][:, None])
            e = flat["c"][:, None] * np.exp(-flow.LEGENDRE_BETA / st)
        mean = np.einsum("ij,ij->i", e, weights)
        e *= e
        sd = np.sqrt(np.maximum(np.einsum("ij,ij->i", e, weights) - mean * mean, 0.0))
        u_e.reshape(-1)[rows] = sd
    # no St (dry), no u of St, or no rebound likely with no u: no interval
    missing = np.isnan(st_am + s_am) | (np.isnan(u_e) & (p <= 0.025))
    if np.ndim(missing):
        np.putmask(low, missing, np.nan)
        np.putmask(high, missing, np.nan)
    elif missing:
        low, high = np.full((), np.nan), np.full((), np.nan)
    low95, high95 = interval_columns(RESTITUTION)
    return {low95: low, high95: high, f"u_{RESTITUTION}": u_e}


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
    budget: float = np.inf,
) -> tuple[Arrays, np.ndarray, np.ndarray]:
    """({u_<q>, low95_<q>, high95_<q>, probabilities} of ``rows``, draws used by row,
    whether the tolerance was reached by row): the module's adaptive Monte Carlo;
    ``evaluate`` maps inputs (step names) to derive's columns. At most ``budget`` draws in
    all: rows are served in order, each with at least ``MIN_BATCHES`` batches; a row the
    budget does not reach has 0 draws (and NaN results)."""
    stats = ("sd", "low", "high")
    per_chunk = max(1, CHUNK // batch)
    result: Arrays = {}
    used = np.zeros(rows.size, dtype=int)
    reached = np.zeros(rows.size, dtype=bool)
    remaining = budget
    for start in range(0, rows.size, per_chunk):
        affordable = int(min(per_chunk, remaining // (MIN_BATCHES * batch)))
        if affordable < 1:
            break
        part = rows[start : start + affordable]
        m = part.size
        # this chunk's rows may go on while the budget lasts (never below MIN_BATCHES)
        limit = max(MIN_BATCHES * batch, min(max_draws, int(remaining // m) // batch * batch))
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
            if done.all() or h * batch >= limit:
                break
        remaining -= m * len(batches) * batch
        sl = slice(start, start + m)
        used[sl] = len(batches) * batch
        reached[sl] = done
        for key in batches[0]:
            name, _, stat = key.partition(":")
            column = {"": name, "sd": f"u_{name}", "low": interval_columns(name)[0],
                      "high": interval_columns(name)[1]}[stat]  # fmt: skip
            result.setdefault(column, np.full(rows.size, np.nan))[sl] = _mean(batches, key)
        if m < per_chunk and start + m < rows.size:
            break  # the budget is spent
    return result, used, reached


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    """Silence numpy's 'all-NaN slice' warnings (an undefined quantity stays NaN)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        yield


def _mean(batches: list[dict[str, np.ndarray]], key: str) -> np.ndarray:
    with _quiet():
        return np.asarray(np.nanmean(np.stack([b[key] for b in batches]), axis=0))


def _spread(batches: list[dict[str, np.ndarray]], key: str) -> np.ndarray:
    """The standard deviation of the batches' average of ``key`` (s/√h)."""
    stack = np.stack([b[key] for b in batches])
    with _quiet():
        return np.asarray(np.nanstd(stack, axis=0, ddof=1) / np.sqrt(len(batches)))


def check_and_resample(
    evaluate: Callable[[Arrays], Arrays],
    x: Arrays,
    u: Arrays,
    columns: Arrays,
    out: Arrays,
    names: tuple[str, ...],
    correlated: np.ndarray,
    one_speed: np.ndarray,
    critical_stokes: float,
    friction_cap: Any = np.inf,
    *,
    monte_carlo: bool = True,
    budget: float = DRAW_BUDGET,
    into: Arrays | None = None,
    scaled: Arrays | None = None,
) -> Arrays:
    """``out`` (first order's ``u_<q>`` and probabilities) with, for every row: the 95 %
    intervals ``low95_<q>``/``high95_<q>`` and ``propagation_method``; rows where
    ``first_order_adequate`` fails get the Monte Carlo's u, intervals and probabilities
    for the quantities that failed (and the probabilities), as far as ``budget`` draws
    reach (rows in order; the others keep first order, and their method says why). A row
    none of whose inputs states a u has no method (None) and no interval (NaN). ``into``:
    arrays to write first order's interval ends into, where given; ``scaled``: the
    sources' scaled u as first order took them, if kept."""
    shape = np.shape(columns[names[0]])
    stated = np.zeros(shape, dtype=bool)
    for given in u.values():
        stated |= np.isfinite(np.asarray(given, dtype=float))
        if stated.all():
            break
    result = dict(out)
    ends: Arrays = {}
    ok = first_order_adequate(
        x, u, columns, out, names, friction_cap, scaled=scaled, ends=ends, into=into
    )
    result.update(first_order_intervals(columns, out, names, critical_stokes, ends, into))
    all_ok = np.ones(shape, dtype=bool)
    for v in ok.values():
        all_ok &= v
    any_bad = np.logical_not(all_ok, out=all_ok)
    any_bad &= stated
    method = (into or {}).get(PROPAGATION_METHOD)
    if method is None:
        method = np.empty(shape, dtype=object)
    if stated.all():
        method[...] = FIRST_ORDER
    else:
        method[...] = None
        method[stated] = FIRST_ORDER
    if not any_bad.any():
        result[PROPAGATION_METHOD] = method
        return result
    rows = np.flatnonzero(any_bad.reshape(-1))
    failing = {k: ~np.broadcast_to(v, shape) & stated for k, v in ok.items()}

    def flat(v: Any) -> np.ndarray:
        return np.broadcast_to(np.asarray(v, dtype=float), shape).reshape(-1)

    flat_x = {k: flat(v) for k, v in x.items()}
    u_flat = {k: flat(v) for k, v in u.items()}
    fail_at = {k: v.reshape(-1)[rows] for k, v in failing.items()}
    if not monte_carlo:  # first order kept everywhere; the method says where it failed
        labels = [k for k in names if k in fail_at] + ["verdicts"]
        flat_method = method.reshape(-1)
        for index in range(rows.size):
            failed = ", ".join(k for k in labels if fail_at[k][index])
            flat_method[rows[index]] = f"{FIRST_ORDER}; the check failed for {failed}"
        result[PROPAGATION_METHOD] = method  # written through its flat view
        return result
    # the draws' statistics (and the tolerance) only for the quantities some row sends
    drawn_names = tuple(k for k in names if k in fail_at and fail_at[k].any())
    drawn, used, reached = monte_carlo_rows(
        evaluate,
        flat_x,
        u_flat,
        rows,
        drawn_names,
        flat(correlated) != 0,
        flat(one_speed) != 0,
        budget=budget,
    )
    served = used > 0
    any_verdict = fail_at["verdicts"] | fail_at.get(RESTITUTION, False)
    for column, values in drawn.items():
        if column not in result:
            continue
        target = np.array(np.broadcast_to(result[column], shape), dtype=float).reshape(-1)
        quantity = column.removeprefix("u_").removeprefix("low95_").removeprefix("high95_")
        if column.startswith(("u_", "low95_", "high95_")):
            # a quantity first order leaves without u (none of its inputs stated) keeps none
            keep = flat(out[f"u_{quantity}"])[rows]
            if quantity == RESTITUTION:  # e = 0 below St_c has a spread here
                keep = flat(columns["normal_stokes_number"])[rows]
            elif quantity in CONTACT_STEPPED:  # so has μ at its cap (no first-order u)
                keep = flat(out["u_lubricated_friction"])[rows]
            replace = fail_at[quantity] & ~np.isnan(keep) & served
        else:  # a probability without a number (dry, no Y) stays without
            replace = any_verdict & ~np.isnan(flat(out[column])[rows]) & served
        target[rows] = np.where(replace, values, target[rows])
        result[column] = target.reshape(shape)
    # one text per distinct pattern of failing quantities and draws (no per-row Python)
    labels = [k for k in names if k in fail_at] + ["verdicts"]
    bits = np.zeros(rows.size, dtype=np.int64)
    for index, k in enumerate(labels):
        bits |= fail_at[k].astype(np.int64) << index
    key = np.stack([bits, used, reached.astype(np.int64)], axis=1)
    patterns, inverse = np.unique(key, axis=0, return_inverse=True)
    texts = []
    for pattern_bits, draws, done in patterns:
        which = ", ".join(
            k if k != "verdicts" else "verdict probabilities"
            for index, k in enumerate(labels)
            if pattern_bits >> index & 1
        )
        if not draws:
            texts.append(NOT_RUN.format(first=FIRST_ORDER, failed=which, budget=int(budget)))
            continue
        text = MONTE_CARLO.format(draws=int(draws)) + ("" if done else NOT_REACHED)
        texts.append(f"{text} for {which}; {FIRST_ORDER} for the rest")
    flat_method = method.reshape(-1)
    flat_method[rows] = np.array(texts, dtype=object)[inverse.reshape(-1)]
    result[PROPAGATION_METHOD] = method  # written through its flat view
    return result


def out_u(out: Arrays, column: str) -> np.ndarray:
    """First order's u of the quantity a ``u_``/``low95_``/``high95_`` column is of."""
    for prefix in ("u_", "low95_", "high95_"):
        if column.startswith(prefix):
            return np.asarray(out[f"u_{column.removeprefix(prefix)}"], dtype=float)
    raise KeyError(column)
